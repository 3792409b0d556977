# Runs COMMAND (a ;-list) and checks its exit code is EXIT and its stderr+stdout matches MATCH.
# ONE_LINE=ON: the whole output (stdout and stderr) must be one line.
# Usage: cmake -DCOMMAND=... -DEXIT=2 -DMATCH=regex [-DONE_LINE=ON] -P expect_exit.cmake
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
