// scenevis: the SceneVis command-line tool. Renders a model or an embedded demo scene offscreen
// with a chosen translucency method, writes PNG frames and a JSON report of what was done and how
// long it took; writes sorted polydata for a camera; measures accuracy against time of every
// translucency method (`bench`). `scenevis --help` documents it.
#include "vtkBSPSortFilter.h"
#include "vtkBSPSortedPolyDataMapper.h"
#include "vtkBSPTranslucentPass.h"
#include "vtkDemoSceneSource.h"
#include "vtkOrderedTranslucentPass.h"
#include "vtkPainterSortFilter.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/Models.h"
#include "scenevis/testing/RenderWindow.h"

#include <vtkActor.h>
#include <vtkAutoInit.h>
#include <vtkAxis.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkChartLegend.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkCommand.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDataArray.h>
#include <vtkDepthSortPolyData.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataAlgorithm.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

// The chart (bench plot) needs the 2D context device and text rendering; the harness initialises
// the OpenGL2 rendering overrides itself.
VTK_MODULE_INIT(vtkRenderingContextOpenGL2);
VTK_MODULE_INIT(vtkRenderingFreeType);
VTK_MODULE_INIT(vtkInteractionStyle); // vtkContextView makes an interactor style

namespace
{
constexpr int kExitUsage = 2;
constexpr int kExitFailure = 1;

const char* const kHelp = R"(scenevis - exact translucency ordering for VTK scenes, headless

Usage:
  scenevis render [options]   render offscreen to PNG, print (and optionally write) a report
  scenevis sort [options]     write the polydata sorted for a camera (VTK XML .vtp) with
                              OriginalCellId and SortRank cell arrays
  scenevis bench [options]    accuracy versus time of every translucency method: a CSV table
                              and a plot (PNG) of frame time against image error
  scenevis --help | --version

Scene (all commands):
  --scene NAME|KEY|FILE embedded demo: spheres (default: 64 overlapping translucent spheres),
                        cyclic-quads, triangles, cad, building; or a key of the data cache
                        (scripts/fetch-data.sh), e.g. bunny-stl; or a model file
                        (.vtp .vtk .ply .stl .obj .glb .gltf). bench: repeatable
  --triangles N         approximate triangle count of the spheres/cad demos (default 20000)
  --parts N             parts of the cad demo (default 1000)
  --opacity A           opacity given to a model file's surface (default 0.4)
  --camera EX,EY,EZ[,FX,FY,FZ]   eye (and focal point; default: the scene's centre);
                        default camera: a three-quarter view that fits the scene
  --parallel            parallel projection

render:
  --sort METHOD         auto (default), none (unsorted alpha), oit (VTK's default weighted
                        OIT), depth-sort (vtkDepthSortPolyData), painter (vtkPainterSortFilter:
                        Newell's painter's algorithm with splits, redone every frame),
                        bsp (vtkBSPSortFilter), bsp-mapper (vtkBSPSortedPolyDataMapper: the BSP
                        order rewritten into the index buffer only), multi-actor (one actor per
                        part of the scene's PartId array, ordered across actors by
                        vtkBSPTranslucentPass), peel:N (dual depth peeling, at most N peels)
  --size WxH            image size in pixels (default 800x600)
  --frames N            orbit frames (default 1); frame i is written as OUT-000i.png
  --orbit DEG           camera azimuth step per frame (default 5)
  --out FILE.png        output image (default scenevis.png)
  --report FILE.json    also write the report as JSON
  --backend osmesa|x11  rendering back-end (default osmesa, or $SCENEVIS_BACKEND)

sort:
  --out FILE.vtp        output polydata (required)
  --front-to-back       front-to-back instead of back-to-front

bench:
  Runs every method (none, oit, depth-sort, painter (skipped above 20000 triangles), bsp,
  bsp-mapper, multi-actor (scenes with parts), peel:4, peel:100 = the reference) on each scene
  in one process: a warm-up frame, then N frames on an orbit. Per method: the median frame time
  (sort + render), the median sort time, the image error against peel:100 at the same camera
  (mean absolute error in 0..255 levels, % of covered pixels off by more than 16 levels) and,
  where the method has a drawing order, the misordered pixels of the ID-buffer oracle (painter's
  ID image of the drawn fragments versus their z-buffer ID image; outside the edge mask, the
  pixels compared, and over all pixels), means over the frames.
  --scene ...           default: spheres (--triangles, default here 19000: 19456 triangles),
                        cyclic-quads, and bunny-stl if fetched
  --frames N            timed frames per method (default 10)
  --orbit DEG           azimuth step per frame (default 2)
  --size WxH            image size (default 640x480)
  --out-dir DIR         where accuracy-vs-time.csv and accuracy-vs-time.png go (default .)

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
  std::vector<std::string> scenes; ///< bench: every --scene, in order
  std::string outDir = ".";
  bool framesSet = false;
  bool sizeSet = false;
  bool orbitSet = false;
  bool trianglesSet = false;
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
    throw UsageError("missing command (render, sort or bench); see scenevis --help");
  }
  options.command = argv[1];
  if (options.command != "render" && options.command != "sort" && options.command != "bench")
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
    {
      options.scene = value();
      options.scenes.push_back(options.scene);
    }
    else if (flag == "--triangles")
    {
      options.triangles = ParseCount(flag, value(), 64, 200000000);
      options.trianglesSet = true;
    }
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
      options.sizeSet = true;
    }
    else if (flag == "--frames")
    {
      options.frames = static_cast<int>(ParseCount(flag, value(), 1, 100000));
      options.framesSet = true;
    }
    else if (flag == "--orbit")
    {
      options.orbit = ParseNumber(flag, value());
      options.orbitSet = true;
    }
    else if (flag == "--out-dir")
      options.outDir = value();
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
  if (s != "auto" && s != "none" && s != "oit" && s != "depth-sort" && s != "painter" &&
    s != "bsp" && s != "bsp-mapper" && s != "multi-actor" && s.rfind("peel:", 0) != 0)
  {
    throw UsageError("--sort expects auto, none, oit, depth-sort, painter, bsp, bsp-mapper, "
                     "multi-actor or peel:N");
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
  if (options.command == "bench")
  {
    if (!options.framesSet)
      options.frames = 10;
    if (!options.orbitSet)
      options.orbit = 2.0;
    if (!options.trianglesSet)
      options.triangles = 19000; // 19,456 spheres triangles: small enough for the painter
    if (!options.sizeSet)
    {
      options.width = 640;
      options.height = 480;
    }
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
  std::string name = options.scene;
  std::string description = "file '" + name + "'";
  if (name.find('.') == std::string::npos)
  {
    const std::string cached = scenevis::testing::DataFile(name);
    if (cached.empty())
    {
      throw UsageError("--scene '" + name +
        "' is neither a demo scene (spheres, cyclic-quads, triangles, cad, building), nor a "
        "fetched data key (scripts/fetch-data.sh), nor a model file (.vtp .vtk .ply .stl .obj "
        ".glb .gltf)");
    }
    description = "data '" + name + "' (" + cached + ")";
    name = cached;
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
  loaded.description = description;
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

/// The scene's polygons split into one polydata per value of its PartId cell array (points
/// compacted, point and cell data copied). Only polygons are kept (the demo scenes and models have
/// nothing else). One entry (the input itself) when there is no PartId array or a single part.
std::vector<vtkSmartPointer<vtkPolyData>> SplitByPart(vtkPolyData* pd)
{
  vtkDataArray* partIds = pd->GetCellData()->GetArray("PartId");
  const vtkIdType cells = pd->GetNumberOfCells();
  if (!partIds || cells == 0 || cells != pd->GetNumberOfPolys())
  {
    return { pd };
  }
  struct Part
  {
    vtkSmartPointer<vtkPolyData> polydata;
    vtkSmartPointer<vtkPoints> points;
    vtkSmartPointer<vtkCellArray> polys;
    std::unordered_map<vtkIdType, vtkIdType> pointMap; // input point id -> part point id
  };
  std::map<long long, Part> parts;
  std::vector<vtkIdType> ids;
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  vtkCellArray* polys = pd->GetPolys();
  vtkIdType c = 0;
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts); ++c)
  {
    Part& part = parts[static_cast<long long>(partIds->GetTuple1(c))];
    if (!part.polydata)
    {
      part.polydata = vtkSmartPointer<vtkPolyData>::New();
      part.points = vtkSmartPointer<vtkPoints>::New();
      part.points->SetDataType(pd->GetPoints()->GetDataType());
      part.polys = vtkSmartPointer<vtkCellArray>::New();
      part.polydata->GetPointData()->CopyAllocate(pd->GetPointData());
      part.polydata->GetCellData()->CopyAllocate(pd->GetCellData());
    }
    ids.resize(static_cast<std::size_t>(npts));
    for (vtkIdType k = 0; k < npts; ++k)
    {
      auto found = part.pointMap.find(pts[k]);
      if (found == part.pointMap.end())
      {
        const vtkIdType mapped = part.points->InsertNextPoint(pd->GetPoint(pts[k]));
        part.polydata->GetPointData()->CopyData(pd->GetPointData(), pts[k], mapped);
        found = part.pointMap.emplace(pts[k], mapped).first;
      }
      ids[static_cast<std::size_t>(k)] = found->second;
    }
    const vtkIdType out = part.polys->InsertNextCell(npts, ids.data());
    part.polydata->GetCellData()->CopyData(pd->GetCellData(), c, out);
  }
  if (parts.size() < 2)
  {
    return { pd };
  }
  std::vector<vtkSmartPointer<vtkPolyData>> result;
  for (auto& entry : parts)
  {
    Part& part = entry.second;
    part.polydata->SetPoints(part.points);
    part.polydata->SetPolys(part.polys);
    part.polydata->Squeeze();
    result.push_back(part.polydata);
  }
  return result;
}

/// One translucency method set up on a renderer: what `render` and `bench` share. The caller
/// owns the renderer (background, camera); the pipeline adds its actors and pass.
class MethodPipeline
{
public:
  MethodPipeline(const std::string& method, vtkPolyData* pd, vtkRenderer* renderer,
    bool showProgress)
    : Method(method)
    , Input(pd)
    , Renderer(renderer)
  {
    vtkCamera* camera = renderer->GetActiveCamera();
    auto makeActor = [&](vtkPolyDataMapper* mapper) {
      mapper->SetScalarModeToUseCellData();
      mapper->SetColorModeToDirectScalars();
      auto actor = vtkSmartPointer<vtkActor>::New();
      actor->SetMapper(mapper);
      renderer->AddActor(actor);
      this->Actors.push_back(actor);
      return actor.Get();
    };
    if (method == "bsp-mapper")
    {
      this->BspMapper->SetInputData(pd);
      makeActor(this->BspMapper);
    }
    else if (method == "multi-actor")
    {
      for (const auto& part : SplitByPart(pd))
      {
        auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
        mapper->SetInputData(part);
        makeActor(mapper);
      }
      this->OrderedPass->SetTranslucentPass(this->BspPass);
    }
    else
    {
      vtkActor* actor = makeActor(this->Mapper);
      if (method == "bsp")
      {
        this->Bsp->SetInputData(pd);
        this->Bsp->SetCamera(camera);
        this->Bsp->SetProp3D(actor);
        if (showProgress)
        {
          this->Progress->Label = "building BSP tree";
          this->Bsp->AddObserver(vtkCommand::ProgressEvent, this->Progress);
        }
        this->Sorter = this->Bsp;
      }
      else if (method == "painter")
      {
        this->Painter->SetInputData(pd);
        this->Painter->SetCamera(camera);
        this->Painter->SetProp3D(actor);
        this->Sorter = this->Painter;
      }
      else if (method == "depth-sort")
      {
        this->DepthSort->SetInputData(pd);
        this->DepthSort->SetCamera(camera);
        this->DepthSort->SetProp3D(actor);
        this->DepthSort->SetDirectionToBackToFront();
        this->DepthSort->SetDepthSortModeToParametricCenter();
        this->Sorter = this->DepthSort;
      }
      if (this->Sorter)
      {
        this->Mapper->SetInputConnection(this->Sorter->GetOutputPort());
      }
      else
      {
        this->Mapper->SetInputData(pd);
      }
    }
    if (method.rfind("peel:", 0) == 0)
    {
      renderer->SetUseDepthPeeling(1);
      renderer->SetMaximumNumberOfPeels(std::stoi(method.substr(5)));
      renderer->SetOcclusionRatio(0.0);
    }
    else if (method != "oit")
    {
      // Every method with a drawing order (and "none": the input's order) needs ordered blending.
      renderer->SetPass(this->OrderedPass);
    }
  }

  /// Brings a filter's order up to date for the camera (before rendering); milliseconds.
  double Update()
  {
    this->OrderCountBefore = this->OrderCount();
    const auto start = std::chrono::steady_clock::now();
    if (this->Sorter)
    {
      this->Sorter->Update();
    }
    this->LastUpdateMs = Milliseconds(start);
    return this->LastUpdateMs;
  }

  /// Whether the per-frame sort happens inside the render (the mapper and the pass).
  bool SortsInRender() const { return this->Method == "bsp-mapper" || this->Method == "multi-actor"; }

  /// Sort time of the last frame in ms (call after rendering it); 0 for methods without a sort
  /// and for frames whose order did not need updating.
  double LastSortMs() const
  {
    if (this->OrderCount() == this->OrderCountBefore)
      return 0.0;
    if (this->Method == "bsp")
      return this->Bsp->GetLastOrderTime() * 1e3;
    if (this->Method == "painter")
      return this->Painter->GetLastOrderTime() * 1e3;
    if (this->Method == "depth-sort")
      return this->LastUpdateMs;
    if (this->Method == "bsp-mapper")
      return this->BspMapper->GetLastOrderTime() * 1e3;
    if (this->Method == "multi-actor")
      return this->BspPass->GetLastOrderTime() * 1e3;
    return 0.0;
  }

  /// One-off preparation in ms: the BSP build (filter, mapper, pass) or the painter's
  /// normalisation; 0 otherwise.
  double BuildMs() const
  {
    if (this->Method == "bsp")
      return this->Bsp->GetLastBuildTime() * 1e3;
    if (this->Method == "painter")
      return this->Painter->GetLastBuildTime() * 1e3;
    if (this->Method == "bsp-mapper")
      return this->BspMapper->GetLastBuildTime() * 1e3;
    if (this->Method == "multi-actor")
      return this->BspPass->GetLastBuildTime() * 1e3;
    return 0.0;
  }

  /// Polygons drawn in the last frame.
  vtkIdType Fragments() const
  {
    if (this->Method == "bsp")
      return this->Bsp->GetNumberOfFragments();
    if (this->Method == "painter")
      return this->Painter->GetNumberOfFragments();
    if (this->Method == "bsp-mapper")
      return this->BspMapper->GetNumberOfFragments();
    if (this->Method == "multi-actor")
      return this->BspPass->GetNumberOfFragments();
    return this->Input->GetNumberOfPolys();
  }

  int Parts() const { return static_cast<int>(this->Actors.size()); }

  /**
   * The polygons in the order they were drawn in the last frame, for the ID-buffer oracle, or
   * nullptr when the method has no drawing order (oit, peel) or does not expose its fragments
   * (bsp-mapper: its split fragments live in its vertex buffers only).
   */
  vtkSmartPointer<vtkPolyData> DrawnOrder() const
  {
    if (this->Sorter)
    {
      return this->Sorter->GetOutput();
    }
    if (this->Method == "none")
    {
      return this->Input;
    }
    if (this->Method == "multi-actor")
    {
      auto fragments = vtkSmartPointer<vtkPolyData>::New();
      this->BspPass->GetOrderedFragments(fragments);
      return fragments;
    }
    return nullptr;
  }

  /// Method-specific JSON members (with a leading comma) and one line of text.
  void Describe(std::ostream& json, std::ostream& text) const
  {
    if (this->Method == "bsp")
    {
      json << ",\n  \"bsp\": {\"fragments\": " << this->Bsp->GetNumberOfFragments()
           << ", \"splits\": " << this->Bsp->GetNumberOfSplits()
           << ", \"depth\": " << this->Bsp->GetTreeDepth()
           << ", \"removed_polygons\": " << this->Bsp->GetNumberOfRemovedPolygons() << "}";
      text << ", BSP build " << this->BuildMs() << " ms (" << this->Bsp->GetNumberOfFragments()
           << " fragments, " << this->Bsp->GetNumberOfSplits() << " splits, depth "
           << this->Bsp->GetTreeDepth() << ")";
    }
    else if (this->Method == "painter")
    {
      json << ",\n  \"painter\": {\"fragments\": " << this->Painter->GetNumberOfFragments()
           << ", \"splits\": " << this->Painter->GetNumberOfSplits()
           << ", \"forced_emissions\": " << this->Painter->GetNumberOfForcedEmissions()
           << ", \"removed_polygons\": " << this->Painter->GetNumberOfRemovedPolygons() << "}";
      text << ", painter's normalisation " << this->BuildMs() << " ms (last frame: "
           << this->Painter->GetNumberOfFragments() << " fragments, "
           << this->Painter->GetNumberOfSplits() << " splits)";
    }
    else if (this->Method == "bsp-mapper")
    {
      json << ",\n  \"bsp_mapper\": {\"fragments\": " << this->BspMapper->GetNumberOfFragments()
           << ", \"triangles\": " << this->BspMapper->GetNumberOfFragmentTriangles()
           << ", \"tree_builds\": " << this->BspMapper->GetNumberOfTreeBuilds()
           << ", \"index_uploads\": " << this->BspMapper->GetNumberOfIndexUploads() << "}";
      text << ", BSP build (in the mapper) " << this->BuildMs() << " ms ("
           << this->BspMapper->GetNumberOfFragments() << " fragments)";
    }
    else if (this->Method == "multi-actor")
    {
      json << ",\n  \"multi_actor\": {\"actors\": " << this->Parts()
           << ", \"sorted_actors\": " << this->BspPass->GetNumberOfSortedActors()
           << ", \"fragments\": " << this->BspPass->GetNumberOfFragments()
           << ", \"splits\": " << this->BspPass->GetNumberOfSplits()
           << ", \"draw_calls\": " << this->BspPass->GetNumberOfDrawCalls() << "}";
      text << ", " << this->Parts() << " actors, BSP build (in the pass) " << this->BuildMs()
           << " ms (" << this->BspPass->GetNumberOfFragments() << " fragments, "
           << this->BspPass->GetNumberOfDrawCalls() << " draw calls)";
    }
  }

private:
  /// Changes whenever the order is (re)computed: the sorter's output time, the mapper's and the
  /// pass's order updates.
  vtkMTimeType OrderCount() const
  {
    if (this->Sorter)
      return this->Sorter->GetOutput()->GetMTime();
    if (this->Method == "bsp-mapper")
      return static_cast<vtkMTimeType>(this->BspMapper->GetNumberOfOrderUpdates());
    if (this->Method == "multi-actor")
      return static_cast<vtkMTimeType>(this->BspPass->GetNumberOfOrderUpdates());
    return 0;
  }

  std::string Method;
  vtkSmartPointer<vtkPolyData> Input;
  vtkRenderer* Renderer;
  std::vector<vtkSmartPointer<vtkActor>> Actors;
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkBSPSortedPolyDataMapper> BspMapper;
  vtkNew<vtkBSPSortFilter> Bsp;
  vtkNew<vtkPainterSortFilter> Painter;
  vtkNew<vtkDepthSortPolyData> DepthSort;
  vtkNew<vtkOrderedTranslucentPass> OrderedPass;
  vtkNew<vtkBSPTranslucentPass> BspPass;
  vtkNew<ProgressBar> Progress;
  vtkPolyDataAlgorithm* Sorter = nullptr;
  double LastUpdateMs = 0.0;
  vtkMTimeType OrderCountBefore = 0;
};

/// The scene as loaded, with smooth normals when it has none.
LoadedScene LoadSceneWithNormals(const Options& options)
{
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
  return scene;
}

constexpr double kBackground[3] = { 26 / 255.0, 26 / 255.0, 31 / 255.0 }; // exact in 8 bits
const scenevis::testing::Rgb kBackgroundRgb = { 26, 26, 31 };

int Render(const Options& options)
{
  if (!options.backend.empty())
  {
    setenv("SCENEVIS_BACKEND", options.backend.c_str(), 1);
  }
  LoadedScene scene = LoadSceneWithNormals(options);
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
  renderer->SetBackground(kBackground[0], kBackground[1], kBackground[2]);
  window->AddRenderer(renderer);
  MethodPipeline pipeline(method, pd, renderer, isatty(STDERR_FILENO) != 0);
  if (method == "multi-actor")
  {
    reason += "; " + std::to_string(pipeline.Parts()) +
      (pipeline.Parts() == 1 ? " actor (the scene has no PartId parts)" : " actors, one per PartId");
  }
  SetUpCamera(options, renderer, pd);

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
    pipeline.Update();
    const auto renderStart = std::chrono::steady_clock::now();
    vtkSmartPointer<vtkImageData> image = scenevis::testing::CaptureImage(window);
    frame.renderMs = Milliseconds(renderStart);
    frame.sortMs = pipeline.LastSortMs();
    if (f == 0)
    {
      buildMs = pipeline.BuildMs();
    }
    if (!scenevis::testing::WritePng(image, frame.file))
    {
      throw std::runtime_error("cannot write '" + frame.file + "'");
    }
    if (scenevis::testing::CoveredFraction(image, kBackgroundRgb) <= 0.0)
    {
      throw std::runtime_error("the rendered image is empty (nothing in view?)");
    }
    frames.push_back(frame);
  }

  // Report.
  const vtkIdType cells = pd->GetNumberOfCells();
  const vtkIdType drawn = pipeline.Fragments();
  std::ostringstream json;
  std::ostringstream details;
  json << std::fixed << std::setprecision(3);
  details << std::fixed << std::setprecision(1);
  json << "{\n  \"command\": \"render\",\n  \"scene\": " << JsonString(scene.description)
       << ",\n  \"polygons\": " << cells << ",\n  \"translucent\": " << (translucent ? "true" : "false")
       << ",\n  \"translucency\": {\"method\": " << JsonString(method)
       << ", \"reason\": " << JsonString(reason) << "},\n  \"culling\": {\"method\": \"none\", "
       << "\"reason\": \"culling is not part of this build yet\"},\n  \"backend\": "
       << JsonString(scenevis::testing::BackendName(backend)) << ",\n  \"size\": ["
       << options.width << ", " << options.height << "],\n  \"load_ms\": " << scene.loadMs
       << ",\n  \"window_ms\": " << windowMs << ",\n  \"build_ms\": " << buildMs
       << ",\n  \"sort_in_render\": " << (pipeline.SortsInRender() ? "true" : "false");
  pipeline.Describe(json, details);
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
  std::cout << "  load " << scene.loadMs << " ms, window " << windowMs << " ms" << details.str()
            << "\n";
  for (const Frame& frame : frames)
  {
    std::cout << "  " << frame.file << ": sort " << std::setprecision(2) << frame.sortMs
              << " ms" << (pipeline.SortsInRender() ? " (inside the render)" : "") << ", render "
              << frame.renderMs << " ms\n";
  }
  if (!options.report.empty())
  {
    std::cout << "  report: " << options.report << "\n";
  }
  return EXIT_SUCCESS;
}

/// One method on one scene in the accuracy-versus-time report.
struct BenchRow
{
  std::string method;
  std::string scene;
  vtkIdType triangles = 0;
  double fragments = 0.0;      ///< mean over the timed frames
  double frameMs = 0.0;        ///< median of (sort + render + glFinish)
  double sortMs = 0.0;         ///< median
  double setupMs = 0.0;        ///< the untimed warm-up frame (builds, shader compilation)
  double meanAbsError = 0.0;   ///< vs peel:100, mean over frames
  double badPercent = 0.0;     ///< % of covered pixels off by > 16 levels, mean over frames
  double misordered = -1.0;    ///< ID oracle, mean over frames; < 0: not applicable
  double compared = 0.0;       ///< pixels the oracle compared (outside the edge mask), mean
  double misorderedAll = 0.0;  ///< the oracle without the edge mask (every pixel), mean
  bool skipped = false;
  std::string note;
};

double Median(std::vector<double> values)
{
  if (values.empty())
  {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double Mean(const std::vector<double>& values)
{
  return values.empty() ? 0.0
                        : std::accumulate(values.begin(), values.end(), 0.0) /
      static_cast<double>(values.size());
}

/// The scene's name in the report: the demo name, the data key, or the file's stem.
std::string SceneLabel(const std::string& scene)
{
  const auto slash = scene.find_last_of('/');
  std::string name = slash == std::string::npos ? scene : scene.substr(slash + 1);
  const auto dot = name.find('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}

/// Triangles of the polygons (a polygon of n points counts n - 2).
vtkIdType CountTriangles(vtkPolyData* pd)
{
  vtkIdType triangles = 0;
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  vtkCellArray* polys = pd->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);)
  {
    triangles += std::max<vtkIdType>(npts - 2, 0);
  }
  vtkCellArray* strips = pd->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(npts, pts);)
  {
    triangles += std::max<vtkIdType>(npts - 2, 0);
  }
  return triangles;
}

constexpr vtkIdType kPainterMaxTriangles = 20000;
const char* const kBenchMethods[] = { "none", "oit", "depth-sort", "painter", "bsp", "bsp-mapper",
  "multi-actor", "peel:4", "peel:100" };
const char* const kReferenceMethod = "peel:100";

/// Runs one method on a loaded scene; `reference` holds peel:100's frames (filled when `method`
/// is the reference itself).
BenchRow BenchMethod(const Options& options, const std::string& method, const std::string& label,
  vtkPolyData* pd, vtkRenderWindow* window,
  std::vector<vtkSmartPointer<vtkImageData>>& reference)
{
  namespace st = scenevis::testing;
  BenchRow row;
  row.method = method;
  row.scene = label;
  row.triangles = CountTriangles(pd);
  const bool isReference = method == kReferenceMethod;

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(kBackground[0], kBackground[1], kBackground[2]);
  window->AddRenderer(renderer);
  {
    MethodPipeline pipeline(method, pd, renderer, false);
    SetUpCamera(options, renderer, pd);
    vtkCamera* camera = renderer->GetActiveCamera();

    // Warm-up frame at the start camera: tree builds, shader compilation, first uploads.
    auto start = std::chrono::steady_clock::now();
    pipeline.Update();
    window->Render();
    window->WaitForCompletion();
    row.setupMs = Milliseconds(start);

    std::vector<double> frameMs, sortMs, fragments, errors, bad, misordered, compared,
      misorderedAll;
    for (int f = 0; f < options.frames; ++f)
    {
      camera->Azimuth(options.orbit);
      renderer->ResetCameraClippingRange();
      start = std::chrono::steady_clock::now();
      pipeline.Update();
      window->Render();
      window->WaitForCompletion();
      frameMs.push_back(Milliseconds(start));
      sortMs.push_back(pipeline.LastSortMs());
      fragments.push_back(static_cast<double>(pipeline.Fragments()));

      // Accuracy, untimed: the camera did not move, so nothing is sorted again.
      vtkSmartPointer<vtkImageData> image = st::CaptureImage(window);
      if (isReference)
      {
        reference.push_back(image);
      }
      else
      {
        const st::ImageDifference difference =
          st::CompareImages(image, reference.at(static_cast<std::size_t>(f)), kBackgroundRgb);
        if (!difference.comparable)
        {
          throw std::runtime_error("cannot compare with the reference: " + difference.problem);
        }
        errors.push_back(difference.meanAbsError);
        bad.push_back(100.0 * difference.coveredBadFraction);
      }
      if (vtkSmartPointer<vtkPolyData> drawn = pipeline.DrawnOrder())
      {
        const st::IdImage painterIds = st::RenderPainterIds(window, drawn, camera);
        const st::IdImage depthIds = st::RenderVisibleIds(window, drawn, camera);
        const st::OrderComparison order = st::OrderMatchesDepth(painterIds, depthIds);
        // Without the edge mask: on fine meshes (triangles of a few pixels) nearly every pixel
        // is next to another id, so the masked comparison sees little; every pixel counts here,
        // at the price of a few legitimate differences along intersection lines.
        const st::OrderComparison unmasked = st::OrderMatchesDepth(painterIds, depthIds,
          std::vector<std::uint8_t>(depthIds.ids.size(), std::uint8_t(0)));
        if (!order.problem.empty() || !unmasked.problem.empty())
        {
          throw std::runtime_error("ID oracle: " + order.problem + unmasked.problem);
        }
        misordered.push_back(static_cast<double>(order.mismatchedPixels));
        compared.push_back(static_cast<double>(order.comparedPixels));
        misorderedAll.push_back(static_cast<double>(unmasked.mismatchedPixels));
      }
    }
    row.frameMs = Median(frameMs);
    row.sortMs = Median(sortMs);
    row.fragments = Mean(fragments);
    row.meanAbsError = Mean(errors);
    row.badPercent = Mean(bad);
    row.misordered = misordered.empty() ? -1.0 : Mean(misordered);
    row.compared = Mean(compared);
    row.misorderedAll = Mean(misorderedAll);
    if (isReference)
      row.note = "reference";
    else if (method == "bsp-mapper")
      row.note = "sort inside the render; fragments not exposed to the ID oracle";
    else if (method == "multi-actor")
      row.note = std::to_string(pipeline.Parts()) + " actors; sort inside the render";
    else if (method == "oit" || method.rfind("peel:", 0) == 0)
      row.note = "order independent: no drawing order to check";
  }
  window->RemoveRenderer(renderer);
  return row;
}

std::string CsvField(const std::string& text)
{
  if (text.find_first_of(",\"\n") == std::string::npos)
  {
    return text;
  }
  std::string out = "\"";
  for (char c : text)
  {
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  }
  return out + "\"";
}

void WriteCsv(const std::vector<BenchRow>& rows, const std::string& path)
{
  std::ofstream csv(path);
  if (!csv)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
  csv << "method,scene,triangles,fragments,median_frame_ms,sort_ms,mean_abs_error,"
         "bad_pixels_percent,misordered_pixels,oracle_pixels,misordered_unmasked,setup_ms,note\n";
  csv << std::fixed;
  for (const BenchRow& row : rows)
  {
    csv << CsvField(row.method) << "," << CsvField(row.scene) << "," << row.triangles << ",";
    if (row.skipped)
    {
      csv << ",,,,,,,,," << CsvField(row.note) << "\n";
      continue;
    }
    csv << std::setprecision(0) << row.fragments << "," << std::setprecision(3) << row.frameMs
        << "," << row.sortMs << "," << row.meanAbsError << "," << row.badPercent << ",";
    if (row.misordered >= 0.0)
    {
      csv << std::setprecision(1) << row.misordered << "," << std::setprecision(0) << row.compared
          << "," << std::setprecision(1) << row.misorderedAll;
    }
    else
    {
      csv << ",,";
    }
    csv << "," << std::setprecision(1) << row.setupMs << "," << CsvField(row.note) << "\n";
  }
  if (!csv)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

/// Frame time (log x) against mean absolute error, one chart per scene, one marker per method.
void WritePlot(const std::vector<BenchRow>& rows, const std::vector<std::string>& scenes,
  const Options& options, const std::string& path)
{
  const int count = static_cast<int>(scenes.size());
  vtkSmartPointer<vtkRenderWindow> window =
    scenevis::testing::MakeRenderWindow(std::max(1, count) * 520, 900);
  vtkNew<vtkContextView> view;
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  window->AddRenderer(view->GetRenderer());
  vtkNew<vtkChartMatrix> matrix;
  matrix->SetSize(vtkVector2i(std::max(1, count), 2));
  matrix->SetGutter(vtkVector2f(70.0f, 70.0f));
  matrix->SetBorders(70, 60, 20, 40);
  view->GetScene()->AddItem(matrix);

  const unsigned char colors[][3] = { { 228, 26, 28 }, { 255, 127, 0 }, { 166, 86, 40 },
    { 152, 78, 163 }, { 55, 126, 184 }, { 77, 175, 74 }, { 0, 170, 170 }, { 247, 129, 191 },
    { 60, 60, 60 } };
  const int markers[] = { vtkPlotPoints::CROSS, vtkPlotPoints::PLUS, vtkPlotPoints::SQUARE,
    vtkPlotPoints::CIRCLE, vtkPlotPoints::DIAMOND };
  // Top row: mean absolute error; bottom row: % of covered pixels off by more than 16 levels.
  for (int cell = 0; cell < 2 * count; ++cell)
  {
    const int i = cell % count;
    const bool top = cell < count;
    auto value = [top](const BenchRow& row) { return top ? row.meanAbsError : row.badPercent; };
    auto* chart = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(i, top ? 1 : 0)));
    if (!chart)
    {
      continue;
    }
    vtkIdType triangles = 0;
    for (const BenchRow& row : rows)
    {
      if (row.scene == scenes[static_cast<std::size_t>(i)])
        triangles = row.triangles;
    }
    chart->SetTitle(scenes[static_cast<std::size_t>(i)] + " (" + std::to_string(triangles) +
      " triangles, " + std::to_string(options.width) + "x" + std::to_string(options.height) + ")" +
      (top ? "" : ": bad pixels"));
    chart->GetTitleProperties()->SetFontSize(16);
    // Log scale by hand (x = log10(ms), ticks labelled in ms): VTK 9.1's log axes misplace
    // plots of single points.
    vtkAxis* x = chart->GetAxis(vtkAxis::BOTTOM);
    x->SetTitle("median frame time (ms, log scale)");
    double minMs = 1e300;
    double maxMs = 0.0;
    for (const BenchRow& row : rows)
    {
      if (row.scene == scenes[static_cast<std::size_t>(i)] && !row.skipped)
      {
        minMs = std::min(minMs, std::max(row.frameMs, 1e-3));
        maxMs = std::max(maxMs, std::max(row.frameMs, 1e-3));
      }
    }
    if (maxMs <= 0.0)
    {
      minMs = maxMs = 1.0;
    }
    const double lo = std::floor(std::log10(minMs) - 0.05);
    const double hi = std::ceil(std::log10(maxMs) + 0.05);
    x->SetBehavior(vtkAxis::FIXED);
    x->SetMinimum(lo);
    x->SetMaximum(hi);
    vtkNew<vtkDoubleArray> tickPositions;
    vtkNew<vtkStringArray> tickLabels;
    for (int decade = static_cast<int>(lo); decade <= static_cast<int>(hi); ++decade)
    {
      for (const double mantissa : { 1.0, 2.0, 5.0 })
      {
        const double position = decade + std::log10(mantissa);
        if (position > hi + 1e-9)
        {
          break;
        }
        std::ostringstream label;
        label << mantissa * std::pow(10.0, decade);
        tickPositions->InsertNextValue(position);
        tickLabels->InsertNextValue(label.str());
      }
    }
    x->SetCustomTickPositions(tickPositions, tickLabels);
    vtkAxis* y = chart->GetAxis(vtkAxis::LEFT);
    y->SetTitle(top ? "mean abs. error vs peel:100 (levels)"
                    : "% covered pixels off by > 16 levels vs peel:100");
    y->SetMinimum(0.0);
    y->SetBehavior(vtkAxis::FIXED);
    double maxError = top ? 0.5 : 1.0;
    for (const BenchRow& row : rows)
    {
      if (row.scene == scenes[static_cast<std::size_t>(i)] && !row.skipped)
        maxError = std::max(maxError, value(row));
    }
    y->SetMaximum(maxError * 1.15);
    // One table per chart: a row per method that ran, the frame time, and one error column per
    // method that is NaN except in its own row (NaN points are not drawn), so that every method
    // is its own plot (own colour, marker and legend entry) on shared x values.
    std::vector<const BenchRow*> shown;
    std::vector<int> shownIndex;
    int m = 0;
    for (const char* method : kBenchMethods)
    {
      for (const BenchRow& row : rows)
      {
        if (row.scene == scenes[static_cast<std::size_t>(i)] && row.method == method &&
          !row.skipped)
        {
          shown.push_back(&row);
          shownIndex.push_back(m);
        }
      }
      ++m;
    }
    vtkNew<vtkTable> table;
    vtkNew<vtkDoubleArray> time;
    time->SetName("time");
    for (const BenchRow* row : shown)
    {
      time->InsertNextValue(std::log10(std::max(row->frameMs, 1e-3)));
    }
    table->AddColumn(time);
    for (std::size_t k = 0; k < shown.size(); ++k)
    {
      vtkNew<vtkDoubleArray> error;
      error->SetName(shown[k]->method.c_str());
      for (std::size_t r = 0; r < shown.size(); ++r)
      {
        error->InsertNextValue(r == k ? value(*shown[k]) : std::nan(""));
      }
      table->AddColumn(error);
    }
    for (std::size_t k = 0; k < shown.size(); ++k)
    {
      const int index = shownIndex[k];
      vtkPlot* plot = chart->AddPlot(vtkChart::POINTS);
      plot->SetInputData(table, 0, static_cast<vtkIdType>(k + 1));
      plot->SetColor(colors[index][0], colors[index][1], colors[index][2], 255);
      plot->SetLabel(shown[k]->method);
      plot->SetWidth(2.0f);
      if (auto* points = vtkPlotPoints::SafeDownCast(plot))
      {
        points->SetMarkerStyle(markers[index % 5]);
        points->SetMarkerSize(14.0f);
      }
    }
    chart->SetShowLegend(top);
    chart->GetLegend()->GetLabelProperties()->SetFontSize(13);
  }
  vtkSmartPointer<vtkImageData> image = scenevis::testing::CaptureImage(window);
  window->RemoveRenderer(view->GetRenderer());
  if (!scenevis::testing::WritePng(image, path))
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

int Bench(const Options& options)
{
  if (!options.backend.empty())
  {
    setenv("SCENEVIS_BACKEND", options.backend.c_str(), 1);
  }
  std::vector<std::string> scenes = options.scenes;
  if (scenes.empty())
  {
    scenes = { "spheres", "cyclic-quads" };
    if (!scenevis::testing::DataFile("bunny-stl").empty())
    {
      scenes.push_back("bunny-stl");
    }
  }
  if (!options.outDir.empty())
  {
    std::string partial;
    std::stringstream dirs(options.outDir);
    std::string piece;
    if (options.outDir[0] == '/')
      partial = "/";
    while (std::getline(dirs, piece, '/'))
    {
      if (piece.empty())
        continue;
      partial += piece + "/";
      mkdir(partial.c_str(), 0755);
    }
  }
  const std::string csvPath = options.outDir + "/accuracy-vs-time.csv";
  const std::string plotPath = options.outDir + "/accuracy-vs-time.png";

  std::vector<BenchRow> rows;
  std::vector<std::string> labels;
  std::cout << std::fixed << std::setprecision(2);
  std::cout << "scenevis bench: " << scenes.size() << " scene(s), " << options.frames
            << " frames of " << options.orbit << " deg, " << options.width << "x"
            << options.height << "\n";
  {
    vtkSmartPointer<vtkRenderWindow> window =
      scenevis::testing::MakeRenderWindow(options.width, options.height);
    for (const std::string& scene : scenes)
    {
      Options sceneOptions = options;
      sceneOptions.scene = scene;
      const LoadedScene loaded = LoadSceneWithNormals(sceneOptions);
      vtkPolyData* pd = loaded.polydata;
      const std::string label = SceneLabel(scene);
      labels.push_back(label);
      const vtkIdType triangles = CountTriangles(pd);
      const std::size_t parts = SplitByPart(pd).size();
      std::cout << "  " << label << ": " << loaded.description << ", " << triangles
                << " triangles, " << parts << " part(s)\n";

      std::vector<vtkSmartPointer<vtkImageData>> reference;
      std::map<std::string, BenchRow> results;
      // The reference first: every other method is compared with its frames.
      std::vector<std::string> runOrder = { kReferenceMethod };
      for (const char* method : kBenchMethods)
      {
        if (method != std::string(kReferenceMethod))
          runOrder.emplace_back(method);
      }
      for (const std::string& method : runOrder)
      {
        BenchRow row;
        if (method == "painter" && triangles > kPainterMaxTriangles)
        {
          row.note = "skipped: more than " + std::to_string(kPainterMaxTriangles) +
            " triangles (the painter's sort is quadratic in the worst case)";
        }
        else if (method == "multi-actor" && parts < 2)
        {
          row.note = "skipped: the scene has no parts (PartId)";
        }
        if (!row.note.empty())
        {
          row.method = method;
          row.scene = label;
          row.triangles = triangles;
          row.skipped = true;
          std::cout << "    " << std::setw(11) << std::left << method << std::right << " "
                    << row.note << "\n";
        }
        else
        {
          row = BenchMethod(sceneOptions, method, label, pd, window, reference);
          std::cout << "    " << std::setw(11) << std::left << method << std::right
                    << " frame " << std::setw(9) << row.frameMs << " ms, sort " << std::setw(9)
                    << row.sortMs << " ms, error " << std::setw(6) << row.meanAbsError
                    << " levels, " << std::setw(6) << row.badPercent << " % bad";
          if (row.misordered >= 0.0)
          {
            std::cout << ", misordered " << row.misordered << " of " << row.compared
                      << " px (unmasked " << row.misorderedAll << ")";
          }
          std::cout << std::endl;
        }
        results[method] = row;
      }
      for (const char* method : kBenchMethods)
      {
        rows.push_back(results[method]);
      }
    }
  }
  WriteCsv(rows, csvPath);
  WritePlot(rows, labels, options, plotPath);
  std::cout << "  wrote " << csvPath << " and " << plotPath << "\n";
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
    if (options.command == "bench")
    {
      return Bench(options);
    }
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
