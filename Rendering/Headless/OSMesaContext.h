/**
 * @file OSMesaContext.h
 * @brief Internal: the only place that talks to OSMesa and provides the GLX shim for GLEW.
 *
 * Kept in its own translation unit because <GL/osmesa.h> includes <GL/gl.h>, which must not meet
 * VTK's GLEW headers. Not installed; used by vtkSceneVisOSMesaRenderWindow.cxx.
 */
#ifndef scenevis_headless_OSMesaContext_h
#define scenevis_headless_OSMesaContext_h

#include <string>

namespace scenevis
{
namespace headless
{

/// Create an OpenGL 3.2+ core-profile OSMesa context (RGBA8, depth 24, stencil 8).
/// Returns nullptr and fills @p error on failure.
void* CreateOSMesaContext(std::string* error);

/// Bind @p context to the RGBA8 @p buffer of @p width x @p height pixels.
bool MakeOSMesaCurrent(void* context, unsigned char* buffer, int width, int height);

/// Whether @p context is the calling thread's current OSMesa context.
bool IsOSMesaCurrent(void* context);

/// Unbind any OSMesa context from the calling thread.
void ReleaseOSMesaCurrent();

/// Destroy @p context (unbinding it first when current).
void DestroyOSMesaContext(void* context);

/**
 * Diagnose the link order: names the shared object that the process-wide symbol glClear (which
 * VTK calls directly, without GLEW) resolves to. With libOSMesa first it is libOSMesa; with
 * libGL/libOpenGL first it is glvnd's dispatcher, which has no current context under OSMesa, so
 * every OpenGL 1.1 call (glClear, glDrawElements, glReadPixels...) is silently dropped.
 * @return an empty string when glClear resolves to libOSMesa, else an explanation.
 */
std::string CheckOSMesaSymbolOrder();

} // namespace headless
} // namespace scenevis

#endif
