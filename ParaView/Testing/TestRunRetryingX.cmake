# RunRetryingX.cmake's rule, on three stand-in commands (sh scripts written to WORK_DIR):
# a command that fails with an X refusal twice fails after two runs; one that fails with it once
# passes on its second run; any other failure fails after one run.
#
#   cmake -DRUN_RETRYING_X=.../RunRetryingX.cmake -DWORK_DIR=DIR -P TestRunRetryingX.cmake
cmake_minimum_required(VERSION 3.16)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
file(WRITE "${WORK_DIR}/always.sh"
  "echo run >> runs\necho 'vtkXOpenGLRenderWindow: bad X server connection. DISPLAY=:99'\nexit 1\n")
file(WRITE "${WORK_DIR}/once.sh"
  "echo run >> runs\nif [ -f refused ]; then exit 0; fi\ntouch refused\n"
  "echo 'bad X server connection'\nexit 3\n")
file(WRITE "${WORK_DIR}/other.sh" "echo run >> runs\necho 'image differs'\nexit 1\n")

function(expect script want_ok want_runs)
  file(REMOVE "${WORK_DIR}/runs" "${WORK_DIR}/refused")
  execute_process(COMMAND "${CMAKE_COMMAND}" "-DSCENEVIS_COMMAND=sh;${script}"
    -P "${RUN_RETRYING_X}"
    WORKING_DIRECTORY "${WORK_DIR}" RESULT_VARIABLE result OUTPUT_QUIET ERROR_QUIET)
  file(STRINGS "${WORK_DIR}/runs" runs)
  list(LENGTH runs count)
  if(result EQUAL 0)
    set(ok TRUE)
  else()
    set(ok FALSE)
  endif()
  if(NOT ok STREQUAL want_ok OR NOT count EQUAL want_runs)
    message(FATAL_ERROR
      "${script}: passed ${ok} after ${count} runs; expected passed ${want_ok} after ${want_runs}")
  endif()
  message(STATUS "ok: ${script}: passed ${ok} after ${count} run(s)")
endfunction()

expect(always.sh FALSE 2)
expect(once.sh TRUE 2)
expect(other.sh FALSE 1)
