# cmake -DEXE=<scenevis_harness_fatal_signals> -DMODE=heap|segv|overflow -DSIGNAL=SIGABRT|SIGSEGV
#   -P FatalSignals.cmake
# Passes when the crashing process ends within 30 s (not hung in a signal handler) and its
# stderr names the signal as scenevis::testing's handler does.
execute_process(COMMAND "${EXE}" "${MODE}" TIMEOUT 30 RESULT_VARIABLE result
  OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${MODE}: result '${result}'\n${err}")
if(result MATCHES "timeout")
  message(FATAL_ERROR "the crash (${MODE}) hung in a signal handler for 30 s")
endif()
if(result STREQUAL "0" OR result STREQUAL "1")
  message(FATAL_ERROR "the process did not crash (${MODE}): exit code ${result}")
endif()
if(NOT err MATCHES "scenevis::testing: ${SIGNAL} \\(fatal\\)")
  message(FATAL_ERROR "the handler did not report ${SIGNAL} (${MODE})")
endif()
