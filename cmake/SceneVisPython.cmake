# Finds the Python interpreter whose `vtkmodules` is the VTK SceneVis builds against (Debian:
# python3-vtk9, /usr/bin/python3), so that the wrapped `scenevis` package loads next to
# `import vtk`. Another python3 first on PATH (pyenv, a venv without system site-packages) has no
# vtkmodules and is passed over. Sets SCENEVIS_PYTHON_EXECUTABLE (empty when none fits).
function(scenevis_find_vtk_python)
  set(candidates)
  if(Python3_EXECUTABLE)
    list(APPEND candidates "${Python3_EXECUTABLE}")
  endif()
  find_program(_scenevis_path_python3 NAMES python3 NO_CACHE)
  if(_scenevis_path_python3)
    list(APPEND candidates "${_scenevis_path_python3}")
  endif()
  list(APPEND candidates /usr/bin/python3)
  list(REMOVE_DUPLICATES candidates)
  string(REGEX MATCH "^[0-9]+\\.[0-9]+\\." vtk_major_minor "${VTK_VERSION}")
  string(REPLACE "." "\\." vtk_major_minor "${vtk_major_minor}")
  set(found "")
  foreach(python IN LISTS candidates)
    if(NOT EXISTS "${python}")
      continue()
    endif()
    execute_process(
      COMMAND "${python}" -c
        "import vtkmodules.vtkCommonCore as c; print(c.vtkVersion.GetVTKVersion())"
      OUTPUT_VARIABLE version OUTPUT_STRIP_TRAILING_WHITESPACE
      RESULT_VARIABLE result ERROR_QUIET)
    if(result EQUAL 0 AND version MATCHES "^${vtk_major_minor}")
      set(found "${python}")
      break()
    endif()
  endforeach()
  set(SCENEVIS_PYTHON_EXECUTABLE "${found}" PARENT_SCOPE)
endfunction()
