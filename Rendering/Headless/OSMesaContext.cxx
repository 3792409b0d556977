// OSMesa context handling and the GLX shim that lets VTK 9.1's GLEW initialise on an OSMesa
// context. See OSMesaContext.h.
//
// Why a GLX shim: Debian's VTK is built for X11/GLX, so VTK calls glewInit(), whose Linux build
// fetches every OpenGL entry point with glXGetProcAddressARB and then probes GLX (a current
// Display, the GLX version, the client extension string). Under OSMesa there is no GLX. The
// definitions below live in the executable (SceneVis::RenderingHeadless is a static library
// linked into executables, and CMake exports these symbols with --export-dynamic-symbol), so they
// interpose on libGLX's: while an OSMesa context is current they answer from OSMesa (entry points
// via OSMesaGetProcAddress, a dummy Display, GLX 1.4, no extensions); otherwise they forward to
// the next definition (libGLX) so that the X11 back-end in the same executable is unaffected.

#include "OSMesaContext.h"

#include <GL/osmesa.h>

#include <GL/glx.h>

#include <dlfcn.h>

#include <cstring>

namespace
{
/// Look up the next definition of @p name after the executable (i.e. libGLX's).
template<typename Function>
Function NextSymbol(const char* name)
{
  void* symbol = dlsym(RTLD_NEXT, name);
  Function function = nullptr;
  static_assert(sizeof(function) == sizeof(symbol), "function and data pointers differ in size");
  std::memcpy(&function, &symbol, sizeof(symbol));
  return function;
}

bool OSMesaIsCurrent()
{
  return OSMesaGetCurrentContext() != nullptr;
}

/// GLEW only checks the Display pointer for null; it never dereferences it.
struct alignas(16) FakeDisplayStorage
{
  char Bytes[64];
};
FakeDisplayStorage FakeDisplay;
} // namespace

extern "C"
{
  Display* glXGetCurrentDisplay(void)
  {
    if (OSMesaIsCurrent())
    {
      return reinterpret_cast<Display*>(&FakeDisplay);
    }
    static const auto next = NextSymbol<Display* (*)(void)>("glXGetCurrentDisplay");
    return next ? next() : nullptr;
  }

  Bool glXQueryVersion(Display* dpy, int* major, int* minor)
  {
    if (OSMesaIsCurrent())
    {
      if (major)
      {
        *major = 1;
      }
      if (minor)
      {
        *minor = 4;
      }
      return True;
    }
    static const auto next = NextSymbol<Bool (*)(Display*, int*, int*)>("glXQueryVersion");
    return next ? next(dpy, major, minor) : False;
  }

  const char* glXGetClientString(Display* dpy, int name)
  {
    if (OSMesaIsCurrent())
    {
      switch (name)
      {
        case GLX_VENDOR:
          return "SceneVis OSMesa GLX shim";
        case GLX_VERSION:
          return "1.4";
        default:
          return "";
      }
    }
    static const auto next = NextSymbol<const char* (*)(Display*, int)>("glXGetClientString");
    return next ? next(dpy, name) : nullptr;
  }

  const char* glXQueryExtensionsString(Display* dpy, int screen)
  {
    if (OSMesaIsCurrent())
    {
      return "";
    }
    static const auto next = NextSymbol<const char* (*)(Display*, int)>("glXQueryExtensionsString");
    return next ? next(dpy, screen) : nullptr;
  }

  __GLXextFuncPtr glXGetProcAddressARB(const GLubyte* procName);

  __GLXextFuncPtr glXGetProcAddress(const GLubyte* procName)
  {
    return glXGetProcAddressARB(procName);
  }

  __GLXextFuncPtr glXGetProcAddressARB(const GLubyte* procName)
  {
    if (!OSMesaIsCurrent())
    {
      static const auto next =
        NextSymbol<__GLXextFuncPtr (*)(const GLubyte*)>("glXGetProcAddressARB");
      return next ? next(procName) : nullptr;
    }
    const char* name = reinterpret_cast<const char*>(procName);
    if (std::strncmp(name, "glX", 3) == 0)
    {
      // GLEW asks for GLX entry points this way too; hand out the shim's own.
      struct Entry
      {
        const char* Name;
        __GLXextFuncPtr Function;
      };
      static const Entry entries[] = {
        { "glXGetCurrentDisplay", reinterpret_cast<__GLXextFuncPtr>(&glXGetCurrentDisplay) },
        { "glXQueryVersion", reinterpret_cast<__GLXextFuncPtr>(&glXQueryVersion) },
        { "glXGetClientString", reinterpret_cast<__GLXextFuncPtr>(&glXGetClientString) },
        { "glXQueryExtensionsString",
          reinterpret_cast<__GLXextFuncPtr>(&glXQueryExtensionsString) },
        { "glXGetProcAddress", reinterpret_cast<__GLXextFuncPtr>(&glXGetProcAddress) },
        { "glXGetProcAddressARB", reinterpret_cast<__GLXextFuncPtr>(&glXGetProcAddressARB) },
      };
      for (const Entry& entry : entries)
      {
        if (std::strcmp(entry.Name, name) == 0)
        {
          return entry.Function;
        }
      }
      return nullptr;
    }
    return reinterpret_cast<__GLXextFuncPtr>(OSMesaGetProcAddress(name));
  }
} // extern "C"

namespace scenevis
{
namespace headless
{

void* CreateOSMesaContext(std::string* error)
{
  // VTK 9.1 needs OpenGL 3.2 core; llvmpipe gives 4.5 core for this request.
  const int attributes[] = { OSMESA_FORMAT,
    OSMESA_RGBA,
    OSMESA_DEPTH_BITS,
    24,
    OSMESA_STENCIL_BITS,
    8,
    OSMESA_ACCUM_BITS,
    0,
    OSMESA_PROFILE,
    OSMESA_CORE_PROFILE,
    OSMESA_CONTEXT_MAJOR_VERSION,
    3,
    OSMESA_CONTEXT_MINOR_VERSION,
    2,
    0 };
  OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!context && error)
  {
    *error = "OSMesaCreateContextAttribs failed to create an OpenGL 3.2 core context (is "
             "libosmesa6 installed and Mesa's llvmpipe available?)";
  }
  return context;
}

bool MakeOSMesaCurrent(void* context, unsigned char* buffer, int width, int height)
{
  return OSMesaMakeCurrent(
           static_cast<OSMesaContext>(context), buffer, GL_UNSIGNED_BYTE, width, height) == GL_TRUE;
}

bool IsOSMesaCurrent(void* context)
{
  return context && OSMesaGetCurrentContext() == static_cast<OSMesaContext>(context);
}

void ReleaseOSMesaCurrent()
{
  if (OSMesaGetCurrentContext())
  {
    OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
  }
}

void DestroyOSMesaContext(void* context)
{
  if (!context)
  {
    return;
  }
  if (IsOSMesaCurrent(context))
  {
    ReleaseOSMesaCurrent();
  }
  OSMesaDestroyContext(static_cast<OSMesaContext>(context));
}

std::string CheckOSMesaSymbolOrder()
{
  void* global = dlsym(RTLD_DEFAULT, "glClear");
  Dl_info info{};
  if (!global || !dladdr(global, &info) || !info.dli_fname)
  {
    return "glClear is not resolvable in this process (no OpenGL library loaded?)";
  }
  if (std::strstr(info.dli_fname, "OSMesa"))
  {
    return std::string();
  }
  return std::string("glClear resolves to ") + info.dli_fname +
    " instead of libOSMesa: libGL/libOpenGL precede libOSMesa in the executable's link order, so "
    "VTK's direct OpenGL 1.1 calls go to glvnd, which has no current context under OSMesa, and "
    "renders are silently black. Link the CMake target SceneVis::RenderingHeadless into the "
    "executable (it puts libOSMesa first) or put libOSMesa before libGL/libOpenGL on the link line";
}

} // namespace headless
} // namespace scenevis
