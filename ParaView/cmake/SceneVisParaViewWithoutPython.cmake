# Debian's paraview-dev without python3-paraview (which conflicts with python3-vtk9 and removes
# libvtk9-dev, so the main build and this one cannot have both): the target files of ParaView's
# Python modules, of its VTK's Python modules and of its tools (pvpython) import files that are
# not installed, and CMake stops at the first missing one. Before find_package(ParaView), this
# declares the targets of each such file itself (executables where the file has them, at the
# same locations; the Python modules as empty targets, which the plugin never uses): the file
# then finds its targets defined and returns before checking files. With python3-paraview
# installed nothing is missing and nothing is declared.
function(scenevis_paraview_without_python paraview_cmake_dir)
  get_filename_component(prefix "${paraview_cmake_dir}/../../../.." ABSOLUTE)
  foreach(name IN ITEMS vtk/VTKPython ParaViewPython ParaViewTools)
    set(targets_file "${paraview_cmake_dir}/${name}-targets.cmake")
    file(GLOB config_files "${paraview_cmake_dir}/${name}-targets-*.cmake")
    if(NOT EXISTS "${targets_file}" OR NOT config_files)
      continue()
    endif()
    # Each target's imported file, as the file's own check lists it.
    set(missing 0)
    foreach(config_file IN LISTS config_files)
      file(STRINGS "${config_file}" checks REGEX "^list\\(APPEND _cmake_import_check_files_for_")
      foreach(check IN LISTS checks)
        if(check MATCHES "_cmake_import_check_files_for_([^ ]+) \"\\\${_IMPORT_PREFIX}([^\"]+)\"")
          set(location "${prefix}${CMAKE_MATCH_2}")
          set("location_${CMAKE_MATCH_1}" "${location}")
          if(NOT EXISTS "${location}")
            math(EXPR missing "${missing} + 1")
          endif()
        endif()
      endforeach()
    endforeach()
    if(missing EQUAL 0)
      continue()
    endif()
    file(STRINGS "${targets_file}" expected REGEX "^foreach\\(_cmake_expected_target IN ITEMS ")
    string(REGEX REPLACE "^foreach\\(_cmake_expected_target IN ITEMS (.*)\\)$" "\\1" expected
      "${expected}")
    separate_arguments(expected UNIX_COMMAND "${expected}")
    file(STRINGS "${targets_file}" executables REGEX "^add_executable\\(")
    foreach(target IN LISTS expected)
      if(TARGET "${target}")
        continue()
      endif()
      if("add_executable(${target} IMPORTED)" IN_LIST executables)
        add_executable("${target}" IMPORTED)
        set_target_properties("${target}" PROPERTIES IMPORTED_LOCATION "${location_${target}}")
      else()
        add_library("${target}" INTERFACE IMPORTED)
      endif()
    endforeach()
    list(LENGTH expected count)
    message(STATUS "SceneVis: ${missing} files of ParaView's ${name} targets are not installed "
      "(python3-paraview); its ${count} targets declared here")
  endforeach()
endfunction()
