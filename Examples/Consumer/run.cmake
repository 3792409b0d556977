# Installs the SceneVis build tree into a scratch prefix, then configures, builds and runs the
# consumer project against it. Arguments: -DBUILD_DIR= -DSOURCE_DIR= -DWORK_DIR=
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix"
  RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "install failed: ${rc}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}/build"
  -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "configuring the consumer against the installed package failed: ${rc}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK_DIR}/build" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building the consumer failed: ${rc}")
endif()
execute_process(COMMAND "${WORK_DIR}/build/consumer" WORKING_DIRECTORY "${WORK_DIR}"
  RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "the consumer failed: ${rc}")
endif()

# The installed Python package (when SceneVis was built with SCENEVIS_WRAP_PYTHON): importable
# from <prefix>/<PYTHON_DESTINATION> next to vtk, and loading the installed libraries.
if(PYTHON)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env
      "PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_DESTINATION}"
      "${PYTHON}" -c "import vtk, scenevis
sphere = vtk.vtkSphereSource()
s = scenevis.vtkBSPSortFilter()
s.SetInputConnection(sphere.GetOutputPort())
s.SetCamera(vtk.vtkCamera())
s.Update()
libs = {l.split()[-1] for l in open('/proc/self/maps') if 'libSceneVis' in l}
assert libs and all(l.startswith('${WORK_DIR}/prefix/') for l in libs), libs
assert scenevis.__file__.startswith('${WORK_DIR}/prefix/'), scenevis.__file__
print('installed scenevis:', s.GetOutput().GetNumberOfCells(), 'cells sorted')"
    RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "import vtk, scenevis from the installed package failed: ${rc}")
  endif()
endif()
