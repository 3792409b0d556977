# Runs a test command, and runs it once more when it failed because the X server refused a
# connection (ParaView on Debian renders through X; Xvfb refuses a share of connections made at
# the same moment, with ECONNRESET or EAGAIN: two processes opening and closing displays in a
# loop lose 1-15 % of their XOpenDisplay calls here, and the two ranks of an MPI test open theirs
# together). Any other failure, and a second X failure, fails the test as the command did.
#
#   cmake -DSCENEVIS_COMMAND="prog;arg;..." -P RunRetryingX.cmake
cmake_minimum_required(VERSION 3.16)
if(NOT SCENEVIS_COMMAND)
  message(FATAL_ERROR "RunRetryingX.cmake: SCENEVIS_COMMAND (the test command) is not set")
endif()
# What VTK's X render window and Xlib print when no display connection could be made.
set(x_refused "bad X server connection|cannot open display|Can't open display|Bad display")
foreach(attempt 1 2)
  execute_process(COMMAND ${SCENEVIS_COMMAND}
    RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  message("${output}")
  if(result EQUAL 0)
    return()
  endif()
  if(attempt EQUAL 1 AND output MATCHES "${x_refused}")
    message("RunRetryingX: the X server refused a connection (above); running the test once more")
    continue()
  endif()
  message(FATAL_ERROR "RunRetryingX: the test failed (exit ${result})")
endforeach()
message(FATAL_ERROR "RunRetryingX: no run decided the test")
