# Checks that libOSMesa is the first OpenGL library among an executable's DT_NEEDED entries (else
# its renders are silently black; see Rendering/Headless/CMakeLists.txt).
# Usage: cmake -DREADELF=/usr/bin/readelf -DEXECUTABLE=path -P ExpectOSMesaFirst.cmake
execute_process(COMMAND "${READELF}" -d "${EXECUTABLE}" RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(rc)
  message(FATAL_ERROR "readelf -d ${EXECUTABLE} failed: ${rc}")
endif()
string(REGEX MATCHALL "\\(NEEDED\\)[^\n]*\\[(libOSMesa|libGL|libOpenGL|libGLX|libEGL)[^]]*\\]"
  gl "${out}")
if(NOT gl)
  message(FATAL_ERROR "${EXECUTABLE} needs no OpenGL library:\n${out}")
endif()
list(GET gl 0 first)
message("OpenGL libraries in DT_NEEDED order:\n${gl}")
if(NOT first MATCHES "libOSMesa")
  message(FATAL_ERROR "the first OpenGL library of ${EXECUTABLE} is not libOSMesa: ${first}")
endif()
