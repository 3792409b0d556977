// scenevis: the SceneVis command-line tool. Renders a model or an embedded demo scene offscreen
// with a chosen translucency method, writes PNG frames and a JSON report of what was done and how
// long it took; writes sorted polydata for a camera. `scenevis --help` documents it.
#include "vtkBSPSortFilter.h"
#include "vtkDemoSceneSource.h"
#include "vtkOrderedTranslucentPass.h"

#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/Models.h"
#include "scenevis/testing/RenderWindow.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDepthSortPolyData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataAlgorithm.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
constexpr int kExitUsage = 2;
constexpr int kExitFailure = 1;

const char* const kHelp = R"(scenevis - exact translucency ordering for VTK scenes, headless

Usage:
  scenevis render [options]   render offscreen to PNG, print (and optionally write) a report
  scenevis sort [options]     write the polydata sorted for a camera (VTK XML .vtp) with
                              OriginalCellId and SortRank cell arrays
  scenevis --help | --version

Scene (both commands):
  --scene NAME|FILE     embedded demo: spheres (default: 64 overlapping translucent spheres),
                        cyclic-quads, triangles, cad, building; or a model file
                        (.vtp .vtk .ply .stl .obj .glb .gltf)
  --triangles N         approximate triangle count of the spheres/cad demos (default 20000)
  --parts N             parts of the cad demo (default 1000)
  --opacity A           opacity given to a model file's surface (default 0.4)
  --camera EX,EY,EZ[,FX,FY,FZ]   eye (and focal point; default: the scene's centre);
                        default camera: a three-quarter view that fits the scene
  --parallel            parallel projection

render:
  --sort METHOD         auto (default), none (unsorted alpha), oit (VTK's default weighted
                        OIT), depth-sort (vtkDepthSortPolyData), bsp (vtkBSPSortFilter),
                        peel:N (dual depth peeling with at most N peels)
  --size WxH            image size in pixels (default 800x600)
  --frames N            orbit frames (default 1); frame i is written as OUT-000i.png
  --orbit DEG           camera azimuth step per frame (default 5)
  --out FILE.png        output image (default scenevis.png)
  --report FILE.json    also write the report as JSON
  --backend osmesa|x11  rendering back-end (default osmesa, or $SCENEVIS_BACKEND)

sort:
  --out FILE.vtp        output polydata (required)
  --front-to-back       front-to-back instead of back-to-front

Exit codes: 0 success, 1 failure (unreadable file, rendering failed), 2 bad usage.
)";

struct UsageError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

struct Options
{
  std::string command;
  std::string scene = "spheres";
  vtkIdType triangles = 20000;
  vtkIdType parts = 1000;
  double opacity = 0.4;
  bool hasCamera = false;
  bool hasFocal = false;
  double eye[3] = { 0, 0, 0 };
  double focal[3] = { 0, 0, 0 };
  bool parallel = false;
  std::string sort = "auto";
  int width = 800;
  int height = 600;
  int frames = 1;
  double orbit = 5.0;
  std::string out;
  std::string report;
  std::string backend;
  bool frontToBack = false;
};

double ParseNumber(const std::string& flag, const std::string& text)
{
  try
  {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used != text.size() || !std::isfinite(value))
    {
      throw std::invalid_argument(text);
    }
    return value;
  }
  catch (const std::exception&)
  {
    throw UsageError(flag + " expects a finite number, got '" + text + "'");
  }
}

long ParseCount(const std::string& flag, const std::string& text, long lo, long hi)
{
  const double value = ParseNumber(flag, text);
  if (value != std::floor(value) || value < lo || value > hi)
  {
    throw UsageError(flag + " expects a whole number from " + std::to_string(lo) + " to " +
      std::to_string(hi) + ", got '" + text + "'");
  }
  return static_cast<long>(value);
}

std::vector<double> ParseList(const std::string& flag, const std::string& text)
{
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ','))
  {
    values.push_back(ParseNumber(flag, item));
  }
  return values;
}

Options ParseOptions(int argc, char* argv[])
{
  Options options;
  if (argc < 2)
  {
    throw UsageError("missing command (render or sort); see scenevis --help");
  }
  options.command = argv[1];
  if (options.command != "render" && options.command != "sort")
  {
    throw UsageError("unknown command '" + options.command + "'; see scenevis --help");
  }
  for (int i = 2; i < argc; ++i)
  {
    const std::string flag = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc)
      {
        throw UsageError(flag + " needs a value");
      }
      return argv[++i];
    };
    if (flag == "--scene")
      options.scene = value();
    else if (flag == "--triangles")
      options.triangles = ParseCount(flag, value(), 64, 200000000);
    else if (flag == "--parts")
      options.parts = ParseCount(flag, value(), 1, 10000000);
    else if (flag == "--opacity")
    {
      options.opacity = ParseNumber(flag, value());
      if (options.opacity <= 0.0 || options.opacity > 1.0)
        throw UsageError("--opacity expects a value in (0, 1]");
    }
    else if (flag == "--camera")
    {
      const std::vector<double> v = ParseList(flag, value());
      if (v.size() != 3 && v.size() != 6)
        throw UsageError("--camera expects EX,EY,EZ or EX,EY,EZ,FX,FY,FZ");
      std::copy_n(v.begin(), 3, options.eye);
      options.hasCamera = true;
      if (v.size() == 6)
      {
        std::copy_n(v.begin() + 3, 3, options.focal);
        options.hasFocal = true;
      }
    }
    else if (flag == "--parallel")
      options.parallel = true;
    else if (flag == "--sort")
      options.sort = value();
    else if (flag == "--size")
    {
      const std::string size = value();
      const auto x = size.find('x');
      if (x == std::string::npos)
        throw UsageError("--size expects WxH, e.g. 800x600");
      options.width = static_cast<int>(ParseCount(flag, size.substr(0, x), 16, 8192));
      options.height = static_cast<int>(ParseCount(flag, size.substr(x + 1), 16, 8192));
    }
    else if (flag == "--frames")
      options.frames = static_cast<int>(ParseCount(flag, value(), 1, 100000));
    else if (flag == "--orbit")
      options.orbit = ParseNumber(flag, value());
    else if (flag == "--out")
      options.out = value();
    else if (flag == "--report")
      options.report = value();
    else if (flag == "--backend")
      options.backend = value();
    else if (flag == "--front-to-back")
      options.frontToBack = true;
    else
      throw UsageError("unknown option '" + flag + "'; see scenevis --help");
  }
  const std::string& s = options.sort;
  if (s != "auto" && s != "none" && s != "oit" && s != "depth-sort" && s != "bsp" &&
    s.rfind("peel:", 0) != 0)
  {
    throw UsageError("--sort expects auto, none, oit, depth-sort, bsp or peel:N");
  }
  if (s.rfind("peel:", 0) == 0)
  {
    ParseCount("--sort peel:N", s.substr(5), 1, 10000);
  }
  if (options.command == "sort" && options.out.empty())
  {
    throw UsageError("sort needs --out FILE.vtp");
  }
  if (options.out.empty())
  {
    options.out = "scenevis.png";
  }
  return options;
}

double Milliseconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

/// Prints a progress bar on stderr while a filter runs, only when stderr is a terminal.
class ProgressBar : public vtkCommand
{
public:
  static ProgressBar* New() { return new ProgressBar; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    const double fraction = *static_cast<double*>(data);
    const int percent = static_cast<int>(fraction * 100.0);
    if (percent != LastPercent)
    {
      LastPercent = percent;
      std::fprintf(stderr, "\r%s [%-40s] %3d%%", Label.c_str(),
        std::string(static_cast<std::size_t>(percent * 40 / 100), '#').c_str(), percent);
      if (percent >= 100)
      {
        std::fprintf(stderr, "\n");
      }
    }
  }
  std::string Label;
  int LastPercent = -1;
};

struct LoadedScene
{
  vtkSmartPointer<vtkPolyData> polydata;
  std::string description;
  double loadMs = 0.0;
};

LoadedScene LoadScene(const Options& options)
{
  LoadedScene loaded;
  const auto start = std::chrono::steady_clock::now();
  vtkNew<vtkDemoSceneSource> demo;
  if (demo->SetSceneByName(options.scene.c_str()))
  {
    demo->SetTriangleCount(options.triangles);
    demo->SetPartCount(options.parts);
    demo->Update();
    loaded.polydata = demo->GetOutput();
    loaded.description = "embedded demo '" + options.scene + "'";
    loaded.loadMs = Milliseconds(start);
    return loaded;
  }
  const std::string& name = options.scene;
  if (name.find('.') == std::string::npos)
  {
    throw UsageError("--scene '" + name +
      "' is neither a demo scene (spheres, cyclic-quads, triangles, cad, building) nor a model "
      "file (.vtp .vtk .ply .stl .obj .glb .gltf)");
  }
  std::string error;
  loaded.polydata = scenevis::testing::LoadModel(name, &error);
  if (!loaded.polydata)
  {
    throw std::runtime_error(error);
  }
  // A uniform translucent colour, as RGBA cell scalars like the demo scenes.
  const vtkIdType cells = loaded.polydata->GetNumberOfCells();
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(4);
  colors->SetNumberOfTuples(cells);
  const unsigned char rgba[4] = { 200, 170, 120,
    static_cast<unsigned char>(std::lround(options.opacity * 255.0)) };
  for (vtkIdType c = 0; c < cells; ++c)
  {
    colors->SetTypedTuple(c, rgba);
  }
  loaded.polydata->GetCellData()->SetScalars(colors);
  loaded.description = "file '" + name + "'";
  loaded.loadMs = Milliseconds(start);
  return loaded;
}

/// Whether any cell's RGBA scalar has alpha < 255.
bool HasTranslucency(vtkPolyData* pd)
{
  auto* colors = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetScalars());
  if (!colors || colors->GetNumberOfComponents() != 4)
  {
    return false;
  }
  for (vtkIdType c = 0; c < colors->GetNumberOfTuples(); ++c)
  {
    if (colors->GetTypedComponent(c, 3) < 255)
    {
      return true;
    }
  }
  return false;
}

void SetUpCamera(const Options& options, vtkRenderer* renderer, vtkPolyData* pd)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetParallelProjection(options.parallel);
  double bounds[6];
  pd->GetBounds(bounds);
  const double center[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  if (options.hasCamera)
  {
    camera->SetPosition(options.eye);
    camera->SetFocalPoint(options.hasFocal ? options.focal : center);
    renderer->ResetCameraClippingRange();
    return;
  }
  camera->SetFocalPoint(center);
  camera->SetPosition(center[0], center[1], center[2] + 1.0);
  camera->SetViewUp(0, 1, 0);
  camera->Azimuth(30.0);
  camera->Elevation(25.0);
  camera->OrthogonalizeViewUp();
  // From the scene's bounds, not the props': the sorted pipeline has not run yet.
  renderer->ResetCamera(bounds);
  camera->Zoom(1.1);
}

std::string JsonString(const std::string& text)
{
  std::string out = "\"";
  for (char c : text)
  {
    if (c == '"' || c == '\\')
    {
      out += '\\';
    }
    out += c;
  }
  return out + "\"";
}

std::string FrameFileName(const std::string& out, int frame, int frames)
{
  if (frames == 1)
  {
    return out;
  }
  const auto dot = out.find_last_of('.');
  std::ostringstream name;
  name << out.substr(0, dot) << "-" << std::setw(4) << std::setfill('0') << frame
       << (dot == std::string::npos ? ".png" : out.substr(dot));
  return name.str();
}

int Render(const Options& options)
{
  if (!options.backend.empty())
  {
    setenv("SCENEVIS_BACKEND", options.backend.c_str(), 1);
  }
  LoadedScene scene = LoadScene(options);
  if (!scene.polydata->GetPointData()->GetNormals())
  {
    // Smooth shading; sharp edges (CAD, buildings) stay sharp. The sorters carry normals along.
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(scene.polydata);
    normals->SetFeatureAngle(50.0);
    normals->Update();
    scene.polydata = normals->GetOutput();
  }
  vtkPolyData* pd = scene.polydata;
  const bool translucent = HasTranslucency(pd);

  std::string method = options.sort;
  std::string reason = "requested with --sort";
  if (method == "auto")
  {
    method = translucent ? "bsp" : "none";
    reason = translucent
      ? "the scene has translucent polygons: exact order with the BSP tree"
      : "the scene is opaque: no sorting needed";
  }

  const auto windowStart = std::chrono::steady_clock::now();
  const scenevis::testing::Backend backend = scenevis::testing::DefaultBackend();
  vtkSmartPointer<vtkRenderWindow> window =
    scenevis::testing::MakeRenderWindow(backend, options.width, options.height);
  const double windowMs = Milliseconds(windowStart);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(26 / 255.0, 26 / 255.0, 31 / 255.0); // exact in 8 bits
  window->AddRenderer(renderer);

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  SetUpCamera(options, renderer, pd);

  vtkNew<vtkBSPSortFilter> bsp;
  vtkNew<vtkDepthSortPolyData> depthSort;
  vtkPolyDataAlgorithm* sorter = nullptr;
  vtkNew<ProgressBar> progress;
  progress->Label = "building BSP tree";
  if (method == "bsp")
  {
    bsp->SetInputData(pd);
    bsp->SetCamera(renderer->GetActiveCamera());
    bsp->SetProp3D(actor);
    if (isatty(STDERR_FILENO))
    {
      bsp->AddObserver(vtkCommand::ProgressEvent, progress);
    }
    sorter = bsp;
  }
  else if (method == "depth-sort")
  {
    depthSort->SetInputData(pd);
    depthSort->SetCamera(renderer->GetActiveCamera());
    depthSort->SetProp3D(actor);
    depthSort->SetDirectionToBackToFront();
    depthSort->SetDepthSortModeToParametricCenter();
    sorter = depthSort;
  }
  if (sorter)
  {
    mapper->SetInputConnection(sorter->GetOutputPort());
  }
  else
  {
    mapper->SetInputData(pd);
  }
  vtkNew<vtkOrderedTranslucentPass> orderedPass;
  if (method == "bsp" || method == "depth-sort" || method == "none")
  {
    renderer->SetPass(orderedPass);
  }
  else if (method.rfind("peel:", 0) == 0)
  {
    renderer->SetUseDepthPeeling(1);
    renderer->SetMaximumNumberOfPeels(std::stoi(method.substr(5)));
    renderer->SetOcclusionRatio(0.0);
  }

  struct Frame
  {
    double sortMs;
    double renderMs;
    std::string file;
  };
  std::vector<Frame> frames;
  double buildMs = 0.0;
  for (int f = 0; f < options.frames; ++f)
  {
    if (f > 0)
    {
      renderer->GetActiveCamera()->Azimuth(options.orbit);
      renderer->ResetCameraClippingRange();
    }
    Frame frame{ 0.0, 0.0, FrameFileName(options.out, f, options.frames) };
    const auto sortStart = std::chrono::steady_clock::now();
    if (sorter)
    {
      sorter->Update();
    }
    frame.sortMs = Milliseconds(sortStart);
    if (f == 0 && method == "bsp")
    {
      buildMs = bsp->GetLastBuildTime() * 1e3;
      frame.sortMs = bsp->GetLastOrderTime() * 1e3;
    }
    const auto renderStart = std::chrono::steady_clock::now();
    vtkSmartPointer<vtkImageData> image = scenevis::testing::CaptureImage(window);
    frame.renderMs = Milliseconds(renderStart);
    if (!scenevis::testing::WritePng(image, frame.file))
    {
      throw std::runtime_error("cannot write '" + frame.file + "'");
    }
    if (scenevis::testing::CoveredFraction(image, { 26, 26, 31 }) <= 0.0)
    {
      throw std::runtime_error("the rendered image is empty (nothing in view?)");
    }
    frames.push_back(frame);
  }

  // Report.
  const vtkIdType cells = pd->GetNumberOfCells();
  const vtkIdType drawn = sorter ? sorter->GetOutput()->GetNumberOfCells() : cells;
  std::ostringstream json;
  json << std::fixed << std::setprecision(3);
  json << "{\n  \"command\": \"render\",\n  \"scene\": " << JsonString(scene.description)
       << ",\n  \"polygons\": " << cells << ",\n  \"translucent\": " << (translucent ? "true" : "false")
       << ",\n  \"translucency\": {\"method\": " << JsonString(method)
       << ", \"reason\": " << JsonString(reason) << "},\n  \"culling\": {\"method\": \"none\", "
       << "\"reason\": \"culling is not part of this build yet\"},\n  \"backend\": "
       << JsonString(scenevis::testing::BackendName(backend)) << ",\n  \"size\": ["
       << options.width << ", " << options.height << "],\n  \"load_ms\": " << scene.loadMs
       << ",\n  \"window_ms\": " << windowMs << ",\n  \"build_ms\": " << buildMs;
  if (method == "bsp")
  {
    json << ",\n  \"bsp\": {\"fragments\": " << bsp->GetNumberOfFragments()
         << ", \"splits\": " << bsp->GetNumberOfSplits() << ", \"depth\": " << bsp->GetTreeDepth()
         << ", \"removed_polygons\": " << bsp->GetNumberOfRemovedPolygons() << "}";
  }
  json << ",\n  \"frames\": [";
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    json << (i ? "," : "") << "\n    {\"file\": " << JsonString(frames[i].file)
         << ", \"sort_ms\": " << frames[i].sortMs << ", \"render_ms\": " << frames[i].renderMs
         << ", \"polygons_drawn\": " << drawn << "}";
  }
  json << "\n  ]\n}\n";
  if (!options.report.empty())
  {
    std::ofstream(options.report) << json.str();
  }

  std::cout << std::fixed << std::setprecision(1);
  std::cout << "scenevis render: " << scene.description << ", " << cells << " polygons"
            << (translucent ? " (translucent)" : " (opaque)") << "\n";
  std::cout << "  translucency: " << method << " - " << reason << "\n";
  std::cout << "  back-end: " << scenevis::testing::BackendName(backend) << ", "
            << options.width << "x" << options.height << "\n";
  std::cout << "  load " << scene.loadMs << " ms, window " << windowMs << " ms";
  if (method == "bsp")
  {
    std::cout << ", BSP build " << buildMs << " ms (" << bsp->GetNumberOfFragments()
              << " fragments, " << bsp->GetNumberOfSplits() << " splits, depth "
              << bsp->GetTreeDepth() << ")";
  }
  std::cout << "\n";
  for (const Frame& frame : frames)
  {
    std::cout << "  " << frame.file << ": sort " << std::setprecision(2) << frame.sortMs
              << " ms, render " << frame.renderMs << " ms\n";
  }
  if (!options.report.empty())
  {
    std::cout << "  report: " << options.report << "\n";
  }
  return EXIT_SUCCESS;
}

int Sort(const Options& options)
{
  const LoadedScene scene = LoadScene(options);
  vtkNew<vtkCamera> camera;
  camera->SetParallelProjection(options.parallel);
  double bounds[6];
  scene.polydata->GetBounds(bounds);
  const double center[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  if (options.hasCamera)
  {
    camera->SetPosition(options.eye);
    camera->SetFocalPoint(options.hasFocal ? options.focal : center);
  }
  else
  {
    const double size = std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4], 1e-12 });
    camera->SetFocalPoint(center);
    camera->SetPosition(center[0] + size, center[1] + size, center[2] + 2 * size);
  }
  vtkNew<vtkBSPSortFilter> sorter;
  sorter->SetInputData(scene.polydata);
  sorter->SetCamera(camera);
  if (options.frontToBack)
  {
    sorter->SetDirectionToFrontToBack();
  }
  vtkNew<ProgressBar> progress;
  progress->Label = "building BSP tree";
  if (isatty(STDERR_FILENO))
  {
    sorter->AddObserver(vtkCommand::ProgressEvent, progress);
  }
  sorter->Update();
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(sorter->GetOutputPort());
  writer->SetFileName(options.out.c_str());
  writer->SetDataModeToBinary();
  if (writer->Write() != 1)
  {
    throw std::runtime_error("cannot write '" + options.out + "'");
  }
  std::cout << std::fixed << std::setprecision(2) << "scenevis sort: " << scene.description << ", "
            << scene.polydata->GetNumberOfCells() << " polygons -> " << sorter->GetNumberOfFragments()
            << " fragments (" << sorter->GetNumberOfSplits() << " splits), build "
            << sorter->GetLastBuildTime() * 1e3 << " ms, order " << sorter->GetLastOrderTime() * 1e3
            << " ms -> " << options.out << "\n";
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h"))
  {
    std::cout << kHelp;
    return EXIT_SUCCESS;
  }
  if (argc >= 2 && std::string(argv[1]) == "--version")
  {
    std::cout << "scenevis " << SCENEVIS_VERSION << "\n";
    return EXIT_SUCCESS;
  }
  try
  {
    const Options options = ParseOptions(argc, argv);
    return options.command == "render" ? Render(options) : Sort(options);
  }
  catch (const UsageError& e)
  {
    std::cerr << "scenevis: " << e.what() << "\n";
    return kExitUsage;
  }
  catch (const std::exception& e)
  {
    std::cerr << "scenevis: " << e.what() << "\n";
    return kExitFailure;
  }
}
