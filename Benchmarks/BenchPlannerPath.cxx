// Auto against fixed along a camera path (issue 18's target: the planner's frames <= 1.1x the
// best fixed exact choice over a path that goes from an overview into the scene).
//
// Per scene, one window per method, each with its own actors (one actor per part, as an
// application that splits its model would have them: plain mappers, cell colours), the same
// camera path for all. The frames are interleaved (frame i of every method, then frame i + 1), so
// a load change on this shared machine hits every method alike. A method's time is the sum of its
// frames' wall times, Render() and glFinish (WaitForCompletion: llvmpipe's rasterizer thread may
// still draw when Render() returns), the planner's Plan() (the renderer's StartEvent) included.
//
// The fixed choices are what an application can install on the same actors: culling none (VTK's
// vtkFrustumCoverageCuller), octree or occlusion (vtkOcclusionCuller with and without occlusion);
// translucency, in scenes with translucent cells, the exact multi-actor order
// (vtkOrderedTranslucentPass + vtkBSPTranslucentPass), and for a one-actor scene the BSP mapper
// (vtkBSPSortedPolyDataMapper + vtkOrderedTranslucentPass). All are exact; "best fixed" is the
// fastest of them on this path. The building (scenes::building, one actor per room and one for
// the outside, each with its room as "RoomId" field data) is also drawn with its portals: the
// planner gets them with SetPortals(), and "opaque + portals" is a vtkPortalCuller with them.
//
// The path: frame 0 is the overview (the scene's bounds fitted in a three-quarter view), the last
// frame is "inside": the first camera of the scene's camera file (real levels), or an eye at 15 %
// of the diagonal from the scene's centre (demos, models); eye and focal point move linearly, the
// clipping range is reset to the props every frame.
//
// Run: build/bin/scenevis_planner_path_bench [--frames N] [--size WxH] [--scene NAME]...
//   NAME: cad, cad-opaque, spheres, cyclic-quads, triangles, building (demos; the building 3 floors
//   of 10 x 10 rooms, inside: the middle of a ground-floor room), building-generated (2 floors of
//   5 x 5 rooms; the planner generates rooms and portals, "opaque + portals" has the hand-made
//   ones; the generation in the untimed warm-up frame is printed), engine (engine-glb), bunny
//   (bunny-stl, opacity 0.4), level-MAP (the data cache).
//   --smoke: one small scene, 4 frames (CI).
//   --csv FILE: also one row per scene in FILE (docs/planner-path.csv is written this way): what
//   the planner chose, its total, the best fixed choice and each fixed choice's total.
//   --rooms-background on|off: the planner generates rooms on a worker thread (its default) or in
//   the render that needs them; for building-generated the warm-up frame's time is printed, and,
//   in the background, the timed frame at which the rooms were adopted ("portals").
#include "vtkSceneVisPlanner.h"

#include "../Tools/CameraFile.h"
#include "../Tools/SplitParts.h"
#include "scenevis/Scenes.h"
#include "scenevis/testing/Models.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"
#include "vtkBSPSortedPolyDataMapper.h"
#include "vtkBSPTranslucentPass.h"
#include "vtkDemoSceneSource.h"
#include "vtkOcclusionCuller.h"
#include "vtkOrderedTranslucentPass.h"
#include "vtkPortalCuller.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkCullerCollection.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace
{
struct Options
{
  int frames = 40;
  int width = 640;
  int height = 480;
  std::vector<std::string> scenes;
  bool smoke = false;
  std::string csv; ///< --csv FILE: one row per scene
  /// --rooms-background on|off: the planner generates rooms in the background or in the render
  /// (-1: the planner's default).
  int roomsInBackground = -1;
};

/// @p text as one CSV field: quoted (quotes doubled) when it holds a comma or a quote.
std::string CsvField(const std::string& text)
{
  if (text.find_first_of(",\"") == std::string::npos)
    return text;
  std::string quoted = "\"";
  for (const char c : text)
    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

struct PathScene
{
  std::string name;
  std::vector<vtkSmartPointer<vtkPolyData>> parts;
  bool translucent = false;
  double opacity = 1.0; ///< given to every actor (models without colours of their own)
  bool hasInside = false;
  scenevis::tool::CameraSpec inside;
  vtkSmartPointer<vtkPolyData> portals; ///< rooms and portals (the building), else null
  bool plannerGetsPortals = true;       ///< false: the planner generates its own
};

/// The building as an application with rooms has it: one actor per room and one for the outside,
/// the room as "RoomId" field data, the portals in vtkPortalCuller's format. "building": 3 floors
/// of 10 x 10 rooms, the planner given the portals; "building-generated": 2 floors of 5 x 5 rooms
/// (under the 10,000 polygons the planner generates rooms for), the planner not given them.
PathScene BuildingScene(bool generated)
{
  namespace st = scenevis::testing;
  PathScene scene;
  scene.name = generated ? "building-generated" : "building";
  scene.plannerGetsPortals = !generated;
  const int floors = generated ? 2 : 3, side = generated ? 5 : 10;
  const scenevis::scenes::BuildingScene b = scenevis::scenes::building(floors, side, side, 1);
  const int rooms = static_cast<int>(b.rooms.size());
  for (int r = -1; r < rooms; ++r)
  {
    vtkSmartPointer<vtkPolyData> pd = st::MakeRoomPolyData(b, r, rooms);
    vtkNew<vtkIntArray> id;
    id->SetName("RoomId");
    id->InsertNextValue(r);
    pd->GetFieldData()->AddArray(id);
    scene.parts.push_back(pd);
  }
  scene.portals = st::MakePortalPolyData(b);
  // Inside: the middle of a ground-floor room near the centre, looking along x.
  const auto& box = b.rooms[static_cast<std::size_t>((side / 2) * side + side / 2 - 1)].bounds;
  scene.inside.eye[0] = (box.lo.x + box.hi.x) / 2;
  scene.inside.eye[1] = (box.lo.y + box.hi.y) / 2;
  scene.inside.eye[2] = box.lo.z + 0.6 * (box.hi.z - box.lo.z);
  scene.inside.focal[0] = scene.inside.eye[0] + 1.0;
  scene.inside.focal[1] = scene.inside.eye[1] + 0.3;
  scene.inside.focal[2] = scene.inside.eye[2] - 0.1;
  scene.inside.viewAngle = 60.0;
  scene.hasInside = true;
  return scene;
}

bool HasTranslucentCells(vtkPolyData* pd)
{
  auto* colors = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetArray("Colors"));
  if (!colors || colors->GetNumberOfComponents() != 4)
    return false;
  for (vtkIdType t = 0; t < colors->GetNumberOfTuples(); ++t)
    if (colors->GetTypedComponent(t, 3) < 255)
      return true;
  return false;
}

void MakeOpaque(vtkPolyData* pd)
{
  if (auto* colors = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetArray("Colors")))
    if (colors->GetNumberOfComponents() == 4)
      for (vtkIdType t = 0; t < colors->GetNumberOfTuples(); ++t)
        colors->SetTypedComponent(t, 3, 255);
}

/// The scene @p name, split into parts by its PartId array; empty parts when it cannot be had.
PathScene LoadScene(const std::string& name, std::string& error)
{
  if (name == "building" || name == "building-generated")
    return BuildingScene(name == "building-generated");
  PathScene scene;
  scene.name = name;
  vtkSmartPointer<vtkPolyData> pd;
  if (name == "cad" || name == "cad-opaque" || name == "spheres" || name == "cyclic-quads" ||
    name == "triangles")
  {
    vtkNew<vtkDemoSceneSource> source;
    source->SetSceneByName(name == "cad-opaque" ? "cad" : name.c_str());
    source->Update();
    pd = source->GetOutput();
    if (name == "cad-opaque")
      MakeOpaque(pd);
  }
  else
  {
    const std::string key = name == "engine" ? "engine-glb" : name == "bunny" ? "bunny-stl" : name;
    const std::string path = scenevis::testing::DataFile(key);
    if (path.empty())
    {
      error = "not in the data cache (bash scripts/fetch-data.sh" +
        std::string(name.rfind("level-", 0) == 0 ? " --levels" : "") + "): " + key;
      return scene;
    }
    pd = scenevis::testing::LoadModel(path, &error);
    if (!pd)
      return scene;
    const std::string cameras = scenevis::testing::DataFile(key + "-cameras");
    if (!cameras.empty())
    {
      scenevis::tool::CameraSpec defaults;
      defaults.up[0] = 0;
      defaults.up[1] = 0;
      defaults.up[2] = 1;
      scene.inside = scenevis::tool::ReadCameraFile(cameras, defaults).front();
      scene.hasInside = true;
    }
  }
  if (name == "bunny")
    scene.opacity = 0.4; // as the command line's models at --opacity 0.4
  scene.translucent = scene.opacity < 1.0 || HasTranslucentCells(pd);
  scene.parts = scenevis::tool::SplitByKeys(pd, { "PartId" });
  return scene;
}

/// One way of drawing the scene: its window, renderer, actors and what is installed.
struct Method
{
  std::string name;
  vtkSmartPointer<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  vtkSmartPointer<vtkSceneVisPlanner> planner;
  vtkNew<vtkOcclusionCuller> culler;
  vtkNew<vtkPortalCuller> portalCuller;
  vtkNew<vtkOrderedTranslucentPass> ordered;
  vtkNew<vtkBSPTranslucentPass> sorted;
  std::vector<double> frameMs;
  std::map<std::string, int> planFrames; ///< the planner's choices and on how many frames
  /// The planner's generated rooms: the timed frame (0-based) at which they were first in use
  /// (-2: from the warm-up frame on; -1: not yet), and the wall time from the end of the warm-up
  /// frame to the end of that frame.
  int roomsAdoptedAt = -1;
  double roomsAdoptedAfterMs = 0.0;
  double roomsAdoptedPlanMs = 0.0; ///< that frame's Plan()
  std::chrono::steady_clock::time_point warmedUp;

  Method(const std::string& methodName, const PathScene& scene, const Options& options)
    : name(methodName)
    , window(scenevis::testing::MakeRenderWindow(options.width, options.height))
  {
    this->window->AddRenderer(this->renderer);
    vtkNew<vtkProperty> property; // shared: the colours are cell scalars
    property->SetOpacity(scene.opacity);
    for (const auto& part : scene.parts)
    {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(part);
      mapper->SetScalarModeToUseCellData();
      mapper->SetColorModeToDirectScalars();
      auto actor = vtkSmartPointer<vtkActor>::New();
      actor->SetMapper(mapper);
      actor->SetProperty(property);
      this->renderer->GetViewProps()->AddItem(actor); // each actor is new: no O(n^2) scan
      actor->AddConsumer(this->renderer);
      this->actors.push_back(actor);
    }
    if (methodName == "planner")
    {
      this->planner = vtkSceneVisPlanner::Attach(this->renderer);
      if (options.roomsInBackground >= 0)
        this->planner->SetGenerateRoomsInBackground(options.roomsInBackground == 1);
      if (scene.portals && scene.plannerGetsPortals)
        this->planner->SetPortals(scene.portals);
      return;
    }
    const std::string cull = methodName.substr(methodName.find("+ ") + 2);
    if (cull == "octree" || cull == "occlusion")
    {
      this->renderer->GetCullers()->RemoveAllItems();
      this->culler->SetOcclusionCulling(cull == "occlusion");
      this->renderer->AddCuller(this->culler);
    }
    else if (cull == "portals")
    {
      this->renderer->GetCullers()->RemoveAllItems();
      this->portalCuller->SetPortals(scene.portals);
      this->renderer->AddCuller(this->portalCuller);
    }
    if (methodName.rfind("multi-actor", 0) == 0)
    {
      this->ordered->SetTranslucentPass(this->sorted);
      this->renderer->SetPass(this->ordered);
    }
    else if (methodName.rfind("bsp-mapper", 0) == 0)
    {
      // The BSP order rewritten into each actor's index buffer, blended in that order.
      for (const auto& actor : this->actors)
      {
        vtkNew<vtkBSPSortedPolyDataMapper> mapper;
        static_cast<vtkPolyDataMapper*>(mapper)->vtkPolyDataMapper::ShallowCopy(actor->GetMapper());
        actor->SetMapper(mapper);
      }
      this->renderer->SetPass(this->ordered);
    }
  }

  void Render(vtkCamera* path)
  {
    vtkCamera* camera = this->renderer->GetActiveCamera();
    camera->DeepCopy(path);
    this->renderer->ResetCameraClippingRange();
    const auto start = std::chrono::steady_clock::now();
    this->window->Render();
    // Render() returns while llvmpipe may still rasterize; without the wait that work would be
    // timed in the next method's frame.
    this->window->WaitForCompletion();
    this->frameMs.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    if (this->planner)
    {
      ++this->planFrames[std::string(this->planner->GetCullMethod()) + " + " +
        this->planner->GetTranslucencyMethod()];
      if (this->roomsAdoptedAt == -1 && this->planner->GetNumberOfRoomGenerations() > 0 &&
        std::string(this->planner->GetCullMethod()) == "portals")
      {
        this->roomsAdoptedAt = static_cast<int>(this->frameMs.size()) - 1;
        this->roomsAdoptedPlanMs = this->planner->GetLastPlanTime();
        this->roomsAdoptedAfterMs = std::chrono::duration<double, std::milli>(
          std::chrono::steady_clock::now() - this->warmedUp)
                                      .count();
      }
    }
  }

  double Total() const
  {
    double sum = 0.0;
    for (const double ms : this->frameMs)
      sum += ms;
    return sum;
  }

  /// The planner's choices and on how many frames each, e.g. "occlusion + none (13 frames);
  /// octree + none (27 frames)"; empty for a fixed method.
  std::string PlanSummary() const
  {
    std::string plan;
    for (const auto& choice : this->planFrames)
      plan += (plan.empty() ? "" : "; ") + choice.first + " (" + std::to_string(choice.second) +
        " frames)";
    return plan;
  }
};

/// The path's camera at @p t in [0, 1] for a scene with @p bounds.
void PathCamera(const PathScene& scene, const double bounds[6], double t, vtkCamera* camera)
{
  const double center[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  const double up[3] = { 0, 0, 1 };
  // Overview: three-quarter view from above, far enough for the bounding sphere at 30 degrees.
  const double distance = diagonal / 2 / std::sin(vtkMath::RadiansFromDegrees(15.0));
  double dir[3] = { -1, -1, 0.8 };
  vtkMath::Normalize(dir);
  const double eye0[3] = { center[0] - dir[0] * distance, center[1] - dir[1] * distance,
    center[2] + dir[2] * distance };
  double eye1[3], focal1[3];
  double angle1 = 30.0;
  if (scene.hasInside)
  {
    std::copy(scene.inside.eye, scene.inside.eye + 3, eye1);
    std::copy(scene.inside.focal, scene.inside.focal + 3, focal1);
    if (scene.inside.viewAngle > 0)
      angle1 = scene.inside.viewAngle;
  }
  else
  {
    const double r = 0.15 * diagonal;
    for (int k = 0; k < 3; ++k)
      eye1[k] = center[k] + (k == 2 ? 0.3 : -0.7) * r;
    std::copy(center, center + 3, focal1);
  }
  double eye[3], focal[3];
  for (int k = 0; k < 3; ++k)
  {
    eye[k] = (1 - t) * eye0[k] + t * eye1[k];
    focal[k] = (1 - t) * center[k] + t * focal1[k];
  }
  camera->SetPosition(eye);
  camera->SetFocalPoint(focal);
  camera->SetViewUp(up);
  camera->SetViewAngle((1 - t) * 30.0 + t * angle1);
  camera->OrthogonalizeViewUp();
}

bool ParseOptions(int argc, char** argv, Options& options)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--frames" && hasValue)
      options.frames = std::max(2, std::atoi(argv[++i]));
    else if (arg == "--size" && hasValue &&
      std::sscanf(argv[++i], "%dx%d", &options.width, &options.height) == 2 && options.width > 0 &&
      options.height > 0)
      continue;
    else if (arg == "--scene" && hasValue)
      options.scenes.emplace_back(argv[++i]);
    else if (arg == "--smoke")
      options.smoke = true;
    else if (arg == "--csv" && hasValue)
      options.csv = argv[++i];
    else if (arg == "--rooms-background" && hasValue &&
      (std::string(argv[i + 1]) == "on" || std::string(argv[i + 1]) == "off"))
      options.roomsInBackground = std::string(argv[++i]) == "on" ? 1 : 0;
    else
    {
      std::cerr << "usage: scenevis_planner_path_bench [--frames N] [--size WxH] [--scene NAME]... "
                   "[--smoke] [--csv FILE] [--rooms-background on|off]\n";
      return false;
    }
  }
  if (options.smoke)
  {
    options.frames = 4;
    options.width = 160;
    options.height = 120;
    if (options.scenes.empty())
      options.scenes = { "cad" };
  }
  if (options.scenes.empty())
    options.scenes = { "cad", "cad-opaque", "spheres", "cyclic-quads", "triangles", "building",
      "building-generated", "engine", "bunny", "level-ctf_inyard" };
  return true;
}
} // namespace

int main(int argc, char** argv)
{
  Options options;
  if (!ParseOptions(argc, argv, options))
    return 2;
  std::ofstream csv;
  if (!options.csv.empty())
  {
    csv.open(options.csv);
    if (!csv)
    {
      std::cerr << "scenevis_planner_path_bench: cannot write " << options.csv << "\n";
      return 2;
    }
    csv << "scene,parts,translucent,frames,planner_chose,planner_ms,best_fixed,best_fixed_ms,"
           "planner_over_best,fixed\n";
  }
  std::printf("%-18s %-26s %10s %9s  %s\n", "scene", "method", "total ms", "/ best", "plan");
  bool ok = true;
  for (const std::string& name : options.scenes)
  {
    std::string error;
    const PathScene scene = LoadScene(name, error);
    if (scene.parts.empty())
    {
      std::printf("%-18s skipped: %s\n", name.c_str(), error.c_str());
      continue;
    }
    std::vector<std::string> names{ "planner" };
    for (const char* cull : { "none", "octree", "occlusion" })
      names.push_back(std::string(scene.translucent ? "multi-actor" : "opaque") + " + " + cull);
    if (scene.translucent && scene.parts.size() == 1)
      names.emplace_back("bsp-mapper + none");
    if (scene.portals)
      names.push_back(std::string(scene.translucent ? "multi-actor" : "opaque") + " + portals");
    std::vector<std::unique_ptr<Method>> methods;
    for (const auto& methodName : names)
      methods.push_back(std::make_unique<Method>(methodName, scene, options));
    double bounds[6];
    methods.front()->renderer->ComputeVisiblePropBounds(bounds);
    vtkNew<vtkCamera> path;
    // A warm-up frame per method at the overview (buffers uploaded, trees built), not timed.
    PathCamera(scene, bounds, 0.0, path);
    for (auto& method : methods)
    {
      method->Render(path);
      if (method->planner &&
        (method->planner->GetNumberOfRoomGenerations() > 0 ||
          method->planner->IsRoomGenerationPending()))
        std::printf("%-18s planner's first Plan(), not timed in its total: %.1f ms, its frame "
                    "%.1f ms (rooms and portals %s: %s)\n",
          name.c_str(), method->planner->GetLastPlanTime(), method->frameMs.back(),
          method->planner->IsRoomGenerationPending() ? "pending" : "generated",
          method->planner->GetCullReason());
      method->frameMs.clear();
      method->planFrames.clear();
      // -2: in use from the warm-up frame on (generated in it).
      method->roomsAdoptedAt = method->planner &&
          method->planner->GetNumberOfRoomGenerations() > 0 &&
          std::string(method->planner->GetCullMethod()) == "portals"
        ? -2
        : -1;
      method->warmedUp = std::chrono::steady_clock::now();
    }
    for (int f = 0; f < options.frames; ++f)
    {
      PathCamera(scene, bounds, static_cast<double>(f) / (options.frames - 1), path);
      for (auto& method : methods)
        method->Render(path);
    }
    double best = 0.0;
    std::string bestName;
    for (std::size_t m = 1; m < methods.size(); ++m)
      if (bestName.empty() || methods[m]->Total() < best)
      {
        best = methods[m]->Total();
        bestName = methods[m]->name;
      }
    for (const auto& method : methods)
    {
      std::printf("%-18s %-26s %10.1f %9.2f  %s\n", name.c_str(), method->name.c_str(),
        method->Total(), method->Total() / best, method->PlanSummary().c_str());
    }
    const Method& planner = *methods.front();
    if (planner.roomsAdoptedAt >= 0)
      std::printf("%-18s planner's generated rooms in use from timed frame %d (%.0f ms after the "
                  "warm-up frame ended; that frame %.1f ms, its Plan() %.1f ms)\n",
        name.c_str(), planner.roomsAdoptedAt, planner.roomsAdoptedAfterMs,
        planner.frameMs[static_cast<std::size_t>(planner.roomsAdoptedAt)],
        planner.roomsAdoptedPlanMs);
    else if (planner.roomsAdoptedAt == -2)
      std::printf("%-18s planner's generated rooms in use from the warm-up frame (generated in "
                  "it)\n",
        name.c_str());
    else if (planner.planner->IsRoomGenerationPending())
      std::printf(
        "%-18s planner's rooms still generating after %d frames\n", name.c_str(), options.frames);
    std::printf("%-18s planner / best fixed (%s) = %.2f over %d frames, %zu parts%s\n",
      name.c_str(), bestName.c_str(), methods.front()->Total() / best, options.frames,
      scene.parts.size(), scene.translucent ? ", translucent" : ", opaque");
    if (csv.is_open())
    {
      std::string fixed;
      char figure[64];
      for (std::size_t m = 1; m < methods.size(); ++m)
      {
        std::snprintf(figure, sizeof figure, " %.1f ms", methods[m]->Total());
        fixed += (fixed.empty() ? "" : "; ") + methods[m]->name + figure;
      }
      char numbers[160];
      std::snprintf(numbers, sizeof numbers, "%.1f,%s,%.1f,%.2f", methods.front()->Total(),
        CsvField(bestName).c_str(), best, methods.front()->Total() / best);
      csv << CsvField(name) << ',' << scene.parts.size() << ',' << (scene.translucent ? 1 : 0)
          << ',' << options.frames << ',' << CsvField(methods.front()->PlanSummary()) << ','
          << numbers << ',' << CsvField(fixed) << '\n';
    }
    ok = ok && !methods.front()->frameMs.empty();
  }
  return ok ? 0 : 1;
}
