# Runs COMMAND (a ;-list) and checks its exit code is EXIT and its stderr+stdout matches MATCH.
# ONE_LINE=ON: the whole output (stdout and stderr) must be one line.
# ABSENT=a;b: files the command must not write (removed first): nothing half-written on errors.
# Usage: cmake -DCOMMAND=... -DEXIT=2 -DMATCH=regex [-DONE_LINE=ON] [-DABSENT=...]
#        -P expect_exit.cmake
foreach(file IN LISTS ABSENT)
  file(REMOVE "${file}")
endforeach()
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit ${rc}\n${out}${err}")
if(NOT "${rc}" STREQUAL "${EXIT}")
  message(FATAL_ERROR "expected exit code ${EXIT}, got ${rc}")
endif()
if(DEFINED MATCH AND NOT "${out}${err}" MATCHES "${MATCH}")
  message(FATAL_ERROR "output does not match '${MATCH}'")
endif()
if(ONE_LINE)
  string(REGEX MATCHALL "\n" breaks "${out}${err}")
  list(LENGTH breaks lines)
  if(NOT lines EQUAL 1 OR NOT "${out}${err}" MATCHES "\n$")
    message(FATAL_ERROR "expected exactly one line of output, got ${lines} line break(s)")
  endif()
endif()
foreach(file IN LISTS ABSENT)
  if(EXISTS "${file}")
    message(FATAL_ERROR "the command wrote '${file}' although it failed")
  endif()
endforeach()
