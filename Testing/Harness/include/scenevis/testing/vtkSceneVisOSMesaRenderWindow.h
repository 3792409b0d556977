/**
 * @file vtkSceneVisOSMesaRenderWindow.h
 * @brief Forwarding header: the OSMesa window is the module SceneVis::RenderingHeadless.
 */
#ifndef scenevis_testing_vtkSceneVisOSMesaRenderWindow_h
#define scenevis_testing_vtkSceneVisOSMesaRenderWindow_h

#include <vtkSceneVisOSMesaRenderWindow.h>

#endif
