// The window factory and its self-check; see vtkSceneVisHeadlessWindows.h.
#include "vtkSceneVisHeadlessWindows.h"

#include "vtkSceneVisOSMesaRenderWindow.h"
#include "vtkSceneVisRecordingOutputWindow.h"

#include <vtkActor.h>
#include <vtkAutoInit.h>
#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <vector>

// The factory creates render windows and mappers through VTK's object factories; register the
// OpenGL2 overrides here so consumers need no vtk_module_autoinit() of their own.
VTK_MODULE_INIT(vtkRenderingOpenGL2);

namespace scenevis
{
namespace headless
{

const char* BackendName(Backend backend)
{
  return backend == Backend::X11 ? "x11" : "osmesa";
}

Backend DefaultBackend()
{
  const char* value = std::getenv("SCENEVIS_BACKEND");
  if (!value || !*value)
  {
    return Backend::OSMesa;
  }
  std::string name(value);
  std::transform(name.begin(), name.end(), name.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (name == "osmesa")
  {
    return Backend::OSMesa;
  }
  if (name == "x11")
  {
    return Backend::X11;
  }
  throw std::runtime_error(
    "SCENEVIS_BACKEND='" + std::string(value) + "' is not one of osmesa, x11");
}

bool BackendAvailable(Backend backend, std::string* why)
{
  if (backend == Backend::X11)
  {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display)
    {
      if (why)
      {
        *why = "the X11 back-end needs $DISPLAY (run under xvfb-run -a -s \"-screen 0 "
               "1280x1024x24\")";
      }
      return false;
    }
  }
  return true;
}

vtkSmartPointer<vtkRenderWindow> MakeUncheckedRenderWindow(Backend backend, int width, int height)
{
  std::string why;
  if (!BackendAvailable(backend, &why))
  {
    throw std::runtime_error(why);
  }
  if (width <= 0 || height <= 0)
  {
    throw std::runtime_error("MakeRenderWindow: the window size must be positive");
  }
  vtkSmartPointer<vtkRenderWindow> window;
  if (backend == Backend::OSMesa)
  {
    auto osmesa = vtkSmartPointer<vtkSceneVisOSMesaRenderWindow>::New();
    osmesa->SetSize(width, height);
    if (!osmesa->CreateContext(&why))
    {
      throw std::runtime_error(why);
    }
    window = osmesa;
  }
  else
  {
    window = vtkSmartPointer<vtkRenderWindow>::New();
    if (!vtkOpenGLRenderWindow::SafeDownCast(window))
    {
      throw std::runtime_error(std::string("vtkRenderWindow::New() made a ") +
        window->GetClassName() + ", not an OpenGL window (RenderingOpenGL2 not initialised?)");
    }
    window->SetOffScreenRendering(1);
    window->SetSize(width, height);
  }
  // With depth peeling on llvmpipe, MSAA silently drops all translucent geometry; and MSAA would
  // blend ID colours of neighbouring cells.
  window->SetMultiSamples(0);
  window->SetAlphaBitPlanes(1);
  window->SetLineSmoothing(0);
  window->SetPolygonSmoothing(0);
  window->SetPointSmoothing(0);
  return window;
}

vtkSmartPointer<vtkRenderWindow> MakeRenderWindow(Backend backend, int width, int height)
{
  vtkSmartPointer<vtkRenderWindow> window = MakeUncheckedRenderWindow(backend, width, height);
  const std::string problem = CheckRenderingWorks(window);
  if (!problem.empty())
  {
    throw std::runtime_error(std::string("SceneVis rendering self-check failed (") +
      BackendName(backend) + "): " + problem);
  }
  return window;
}

vtkSmartPointer<vtkRenderWindow> MakeRenderWindow(int width, int height)
{
  return MakeRenderWindow(DefaultBackend(), width, height);
}

namespace
{
/// Read the colour buffer of a window that has just rendered.
vtkSmartPointer<vtkUnsignedCharArray> ReadPixels(vtkRenderWindow* window, bool withAlpha)
{
  const int* size = window->GetSize();
  auto pixels = vtkSmartPointer<vtkUnsignedCharArray>::New();
  // Offscreen VTK 9.1 windows keep the finished frame in the back buffer of their render
  // framebuffer; the front buffer is only valid after a swap to a mapped window.
  const int front = 0;
  if (withAlpha)
  {
    window->GetRGBACharPixelData(0, 0, size[0] - 1, size[1] - 1, front, pixels);
  }
  else
  {
    window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, front, pixels);
  }
  return pixels;
}
} // namespace

std::string CheckRenderingWorks(vtkRenderWindow* window)
{
  if (!window)
  {
    return "no render window";
  }
  std::ostringstream problem;
  auto* osmesa = vtkSceneVisOSMesaRenderWindow::SafeDownCast(window);

  // Render a red, unlit quad that overfills the view into a temporary renderer; the window's own
  // renderers are detached meanwhile so that they cannot cover it.
  std::vector<vtkSmartPointer<vtkRenderer>> saved;
  vtkRendererCollection* renderers = window->GetRenderers();
  renderers->InitTraversal();
  while (vtkRenderer* renderer = renderers->GetNextItem())
  {
    saved.emplace_back(renderer);
  }
  for (auto& renderer : saved)
  {
    window->RemoveRenderer(renderer);
  }

  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-10, -10, 0);
  plane->SetPoint1(10, -10, 0);
  plane->SetPoint2(-10, 10, 0);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(1, 0, 0);
  actor->GetProperty()->LightingOff();
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  renderer->AddActor(actor);
  renderer->GetActiveCamera()->SetPosition(0, 0, 5);
  renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  renderer->GetActiveCamera()->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange();

  // Record VTK's errors during the check (e.g. "GLEW could not be initialized") for the message;
  // they are still passed on to the previous output window (and so to a StrictVtkOutput guard).
  std::vector<std::string> vtkMessages;
  {
    ScopedVtkOutputRecorder recorder;
    window->AddRenderer(renderer);
    window->Render();
    vtkMessages = recorder.ErrorsAndWarnings();
  }
  vtkSmartPointer<vtkUnsignedCharArray> pixels = ReadPixels(window, false);
  window->RemoveRenderer(renderer);
  renderer->ReleaseGraphicsResources(window);
  for (auto& r : saved)
  {
    window->AddRenderer(r);
  }

  const int* size = window->GetSize();
  const vtkIdType count = static_cast<vtkIdType>(size[0]) * size[1];
  vtkIdType red = 0;
  vtkIdType black = 0;
  if (pixels->GetNumberOfTuples() == count && pixels->GetNumberOfComponents() == 3)
  {
    const unsigned char* p = pixels->GetPointer(0);
    for (vtkIdType i = 0; i < count; ++i, p += 3)
    {
      if (p[0] >= 250 && p[1] <= 5 && p[2] <= 5)
      {
        ++red;
      }
      else if (p[0] == 0 && p[1] == 0 && p[2] == 0)
      {
        ++black;
      }
    }
  }
  if (red == count)
  {
    return std::string();
  }

  if (pixels->GetNumberOfTuples() != count)
  {
    problem << "could not read back the pixels (got " << pixels->GetNumberOfTuples() << " of "
            << count << "). ";
  }
  else if (black == count)
  {
    problem << "a red quad filling the view rendered completely BLACK. ";
  }
  else
  {
    problem << "a red quad filling the view rendered only " << red << " of " << count
            << " pixels red (" << black << " black). ";
  }
  problem << "Likely causes: ";
  if (osmesa)
  {
    const std::string order = vtkSceneVisOSMesaRenderWindow::CheckLinkOrder();
    if (!order.empty())
    {
      problem << "[link order] " << order << ". ";
    }
    if (!osmesa->IsCurrent())
    {
      problem << "[no context] the OSMesa context is not current. ";
    }
  }
  if (window->GetMultiSamples() > 0)
  {
    problem << "[MSAA] MultiSamples=" << window->GetMultiSamples()
            << " (turn it off with SetMultiSamples(0)). ";
  }
  problem << "Generic: libOSMesa must precede libGL/libOpenGL on the link line; MSAA must be off; "
             "an OpenGL 3.2 context must be current.";
  for (const std::string& message : vtkMessages)
  {
    problem << "\n  VTK said: " << message;
  }
  return problem.str();
}

vtkSmartPointer<vtkImageData> CaptureImage(vtkRenderWindow* window, bool withAlpha)
{
  window->Render();
  vtkSmartPointer<vtkUnsignedCharArray> pixels = ReadPixels(window, withAlpha);
  const int* size = window->GetSize();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(size[0], size[1], 1);
  pixels->SetName("RGB");
  image->GetPointData()->SetScalars(pixels);
  return image;
}

std::string DescribeContext(vtkRenderWindow* window)
{
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!gl)
  {
    return "not an OpenGL window";
  }
  const char* caps = gl->ReportCapabilities();
  std::string text = caps ? caps : "";
  // Keep the vendor/renderer/version lines, drop the long extension list.
  std::istringstream lines(text);
  std::string line;
  std::string result;
  while (std::getline(lines, line))
  {
    if (line.rfind("OpenGL vendor", 0) == 0 || line.rfind("OpenGL renderer", 0) == 0 ||
      line.rfind("OpenGL version", 0) == 0)
    {
      result += (result.empty() ? "" : "; ") + line;
    }
  }
  return result.empty() ? text.substr(0, 200) : result;
}

} // namespace headless
} // namespace scenevis
