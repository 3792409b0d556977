# scenevis_enable_warnings(target [VTK]): warnings for our own targets only (VTK headers come in
# as system includes), errors with SCENEVIS_WARNINGS_AS_ERRORS. VTK-style classes pass VTK: VTK's
# macros are written to be followed by ';', which -Wpedantic rejects. Shared by the main build and
# the ParaView plugin's (ParaView/).
function(scenevis_enable_warnings target)
  set(pedantic -Wpedantic)
  if("VTK" IN_LIST ARGN)
    set(pedantic)
  endif()
  target_compile_options(${target} PRIVATE
    $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra ${pedantic} -Wshadow -Wnon-virtual-dtor
      -Wold-style-cast -Wcast-align -Woverloaded-virtual -Wnull-dereference>
    $<$<AND:$<BOOL:${SCENEVIS_WARNINGS_AS_ERRORS}>,$<CXX_COMPILER_ID:GNU,Clang>>:-Werror>)
endfunction()
