// `scenevis cull`: what a culling mode keeps for a camera, as JSON; with --exact, against the
// exact visible set of an ID-buffer render.
#include "AutoPlan.h"
#include "Commands.h"
#include "CullSetup.h"
#include "MethodPipeline.h"
#include "Progress.h"
#include "Report.h"
#include "SceneLoading.h"
#include "ViewSetup.h"
#include "vtkChunkedPolyDataMapper.h"
#include "vtkInstancedActor.h"

#include <vtkSceneVisHeadlessWindows.h>
#include <vtkSceneVisIdBuffer.h>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkMapper.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace scenevis
{
namespace tool
{
namespace
{
/// The key of a cell: its values of the arrays the scene is split into actors by.
std::vector<long long> CellKey(const std::vector<vtkDataArray*>& arrays, vtkIdType cell)
{
  std::vector<long long> key;
  for (vtkDataArray* array : arrays)
    key.push_back(static_cast<long long>(array->GetTuple1(cell)));
  return key;
}

/// The arrays of @p names (the room and the part array) that @p pd has.
std::vector<vtkDataArray*> KeyArrays(vtkPolyData* pd, const std::vector<std::string>& names)
{
  std::vector<vtkDataArray*> arrays;
  for (const std::string& name : names)
  {
    if (vtkDataArray* array = pd->GetCellData()->GetArray(name.c_str()))
      arrays.push_back(array);
  }
  return arrays;
}

/// --instances: the placement index of each actor (the pipeline makes one actor per placement,
/// in order), which is also the PartId of the placement's cells in the flattened scene.
std::unordered_map<vtkProp*, long long> PlacementOfActor(const MethodPipeline& pipeline)
{
  std::unordered_map<vtkProp*, long long> placement;
  const auto& actors = pipeline.GetActors();
  for (std::size_t i = 0; i < actors.size(); ++i)
    placement.emplace(actors[i], static_cast<long long>(i));
  return placement;
}

/// The props drawn in the last render: those the culler kept, or every actor (no culler).
std::vector<vtkProp*> DrawnProps(const MethodPipeline& pipeline, const CullSetup& culling)
{
  if (const std::vector<vtkProp*>* kept = culling.Visible())
    return *kept;
  return std::vector<vtkProp*>(pipeline.GetActors().begin(), pipeline.GetActors().end());
}

/// --instances: the placements drawn in the last render (their indices, the flattened file's
/// PartIds): of each kept actor placed alone (@p placementOf), of each kept vtkInstancedActor
/// the placements it was told to draw.
std::set<long long> DrawnPlacements(const MethodPipeline& pipeline, const CullSetup& culling,
  const std::unordered_map<vtkProp*, long long>& placementOf)
{
  std::set<long long> drawn;
  for (vtkProp* prop : DrawnProps(pipeline, culling))
  {
    if (auto* instanced = vtkInstancedActor::SafeDownCast(prop))
    {
      for (vtkIdType k = 0; k < instanced->GetNumberOfVisiblePlacements(); ++k)
        drawn.insert(instanced->GetPlacementId(instanced->GetVisiblePlacement(k)));
      continue;
    }
    const auto found = placementOf.find(prop);
    if (found != placementOf.end())
      drawn.insert(found->second);
  }
  return drawn;
}

/// cull --exact: the exact visible set (cells with a pixel in a depth-tested ID render of the
/// whole scene) against what the mode drew. False negatives break the promise of a conservative
/// mode; over-draw is what it costs. Translucent surfaces are opaque in the ID render, so what
/// is seen only through glass counts as over-draw, never as a false negative.
/// With @p placementOf (--instances), @p pd is the flattened scene, its parts (key PartId) the
/// placements: an instance is drawn when its actor was kept, whichever mesh it shares.
void DescribeExact(std::ostream& json, vtkRenderWindow* window, vtkCamera* camera,
  bool fixedClippingRange, vtkPolyData* pd, const std::vector<std::string>& keys,
  const MethodPipeline& pipeline, const CullSetup& culling,
  const std::unordered_map<vtkProp*, long long>* placementOf)
{
  namespace idbuffer = scenevis::idbuffer;
  const auto start = std::chrono::steady_clock::now();
  idbuffer::IdRenderOptions idOptions;
  // A fixed clipping range clips what the mode draws too: the exact set must be clipped alike.
  idOptions.cameraClippingRange = fixedClippingRange;
  const idbuffer::IdImage visibleIds = idbuffer::RenderIdBuffer(window, pd, camera, idOptions);
  const std::vector<std::uint32_t> visibleCells = idbuffer::VisibleSet(visibleIds);
  const double exactMs = Milliseconds(start);

  // Which cells of the scene were drawn: the chunked mapper's cells, the cells of the actors
  // kept (matched by their room and part key), or all cells of the one actor if it was kept.
  const std::vector<vtkDataArray*> arrays = KeyArrays(pd, keys);
  const vtkIdType cells = pd->GetNumberOfCells();
  std::vector<char> drawn(static_cast<std::size_t>(cells), 0);
  std::set<std::vector<long long>> drawnKeys;
  const bool split = pipeline.Placements() > 1;
  if (vtkChunkedPolyDataMapper* chunked = pipeline.GetChunkedMapper())
  {
    std::vector<vtkIdType> ids;
    chunked->GetDrawnCellIds(ids);
    for (const vtkIdType id : ids)
      drawn[static_cast<std::size_t>(id)] = 1;
  }
  else if (placementOf)
  {
    for (const long long placement : DrawnPlacements(pipeline, culling, *placementOf))
      drawnKeys.insert({ placement });
    for (vtkIdType c = 0; c < cells; ++c)
      drawn[static_cast<std::size_t>(c)] = drawnKeys.count(CellKey(arrays, c)) ? 1 : 0;
  }
  else if (split)
  {
    const std::vector<vtkProp*>* kept = culling.Visible();
    for (vtkProp* prop : kept ? *kept : std::vector<vtkProp*>())
    {
      auto* actor = vtkActor::SafeDownCast(prop);
      auto* input =
        actor ? vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0)) : nullptr;
      if (input && input->GetNumberOfCells() > 0)
        drawnKeys.insert(CellKey(KeyArrays(input, keys), 0));
    }
    for (vtkIdType c = 0; c < cells; ++c)
      drawn[static_cast<std::size_t>(c)] = drawnKeys.count(CellKey(arrays, c)) ? 1 : 0;
  }
  else if (culling.PropsDrawn() > 0)
  {
    std::fill(drawn.begin(), drawn.end(), 1);
  }
  vtkIdType falseNegativeCells = 0;
  std::set<std::vector<long long>> visibleKeys;
  std::set<std::vector<long long>> missedKeys;
  for (const std::uint32_t id : visibleCells)
  {
    const auto cell = static_cast<vtkIdType>(id);
    const std::vector<long long> key = CellKey(arrays, cell);
    visibleKeys.insert(key);
    if (!drawn[static_cast<std::size_t>(cell)])
    {
      ++falseNegativeCells;
      missedKeys.insert(key);
    }
  }
  // What an approximate mode costs on screen: the pixels whose visible cell it did not draw.
  // The first lost pixels themselves (x, y from the bottom left, cell): where to look.
  std::size_t visiblePixels = 0;
  std::size_t lostPixels = 0;
  std::ostringstream lostList;
  for (std::size_t i = 0; i < visibleIds.ids.size(); ++i)
  {
    const std::uint32_t id = visibleIds.ids[i];
    if (id == idbuffer::kNoId || id >= drawn.size())
      continue;
    ++visiblePixels;
    if (drawn[id])
      continue;
    if (lostPixels < 64)
    {
      const auto width = static_cast<std::size_t>(visibleIds.width);
      lostList << (lostPixels ? ", " : "") << "[" << i % width << ", " << i / width << ", " << id
               << "]";
    }
    ++lostPixels;
  }
  const auto drawnCells = std::count(drawn.begin(), drawn.end(), 1);
  json << ",\n  \"exact\": {\"visible_pixels\": " << visiblePixels
       << ", \"lost_pixels\": " << lostPixels << ", \"visible_cells\": " << visibleCells.size()
       << ", \"drawn_cells\": " << drawnCells
       << ", \"false_negative_cells\": " << falseNegativeCells << ", \"overdraw_cells\": "
       << drawnCells - static_cast<vtkIdType>(visibleCells.size()) + falseNegativeCells;
  if (split)
  {
    vtkIdType overdrawProps = 0;
    for (const auto& key : drawnKeys)
      overdrawProps += visibleKeys.count(key) ? 0 : 1;
    json << ", \"visible_props\": " << visibleKeys.size()
         << ", \"drawn_props\": " << drawnKeys.size()
         << ", \"false_negative_props\": " << missedKeys.size()
         << ", \"overdraw_props\": " << overdrawProps;
  }
  if (lostPixels > 0)
    json << ", \"lost\": [" << lostList.str() << "]";
  json << ", \"id_render_ms\": " << exactMs << "}";
}
} // namespace

int RunCull(const Options& options)
{
  ApplyBackendOption(options);
  LoadedScene scene = LoadSceneWithNormals(options);
  vtkPolyData* pd = scene.polydata; // --instances: the mesh library
  // --instances: the placed meshes in world space, where every polygon is needed (the ID render
  // of --exact, --export-scene); placement i is part i.
  vtkSmartPointer<vtkPolyData> flattened;
  if (scene.instanced && (options.exact || !options.exportScene.empty()))
    flattened = FlattenInstances(*scene.instanced);
  std::vector<std::string> exported;
  if (!options.exportScene.empty())
  {
    exported.push_back(options.exportScene + ".vtp");
    WritePolyData(flattened ? flattened.Get() : pd, exported.back());
    if (scene.portals)
    {
      exported.push_back(options.exportScene + "-portals.vtp");
      WritePolyData(scene.portals, exported.back());
    }
  }
  const bool perCamera = !options.cameras.empty();
  const std::vector<CameraSpec> cameras = CamerasToRun(options);
  vtkSmartPointer<vtkRenderWindow> window =
    scenevis::headless::MakeRenderWindow(options.width, options.height);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  double bounds[6];
  SceneBounds(scene, bounds);
  SetUpCamera(cameras[0], renderer, bounds, scene.zUp);
  // Visibility does not depend on the drawing order: nothing is sorted.
  const ScenePlan plan = PlanScene(options, scene, "none", renderer);
  MethodPipeline pipeline("none", pd, renderer, false, &plan.groups, plan.cull.chunked,
    plan.instanced, plan.instancedProps);
  if (pipeline.InstancedProps() && !flattened)
  {
    // The placements live in the instanced actors now (6 MB for 46,000 of them).
    std::vector<Instance>().swap(scene.instanced->instances);
  }
  SetUpCamera(cameras[0], renderer, bounds, scene.zUp); // again: the clipping range from the actors
  const CullSetup culling(
    plan.cull, pipeline, renderer, pd, plan.portals, ProgressBar::OnTerminal());
  const std::unordered_map<vtkProp*, long long> placementOf =
    plan.instanced ? PlacementOfActor(pipeline) : std::unordered_map<vtkProp*, long long>();
  const std::vector<std::string> keys = plan.instanced
    ? std::vector<std::string>{ "PartId" }
    : std::vector<std::string>{ options.roomArray, options.partArray };
  const char* const partArray = options.partArray.c_str();
  const char* const roomArray = options.roomArray.c_str();

  std::vector<std::string> results;
  for (std::size_t c = 0; c < cameras.size(); ++c)
  {
    const CameraSpec& spec = cameras[c];
    if (c > 0)
      SetUpCamera(spec, renderer, bounds, scene.zUp);
    window->Render();

    // What was drawn: the visible actors' polygons, or the chunked mapper's drawn cells.
    std::set<long long> parts;
    std::set<long long> rooms;
    vtkIdType propsVisible = culling.PropsDrawn();
    if (vtkChunkedPolyDataMapper* chunked = pipeline.GetChunkedMapper())
    {
      std::vector<vtkIdType> cells;
      chunked->GetDrawnCellIds(cells);
      parts = DistinctValues(pd, partArray, &cells);
      rooms = DistinctValues(pd, roomArray, &cells);
      propsVisible = cells.empty() ? 0 : 1;
    }
    else if (plan.instanced)
    {
      // A placement is a part: its index (the flattened file's PartId).
      parts = DrawnPlacements(pipeline, culling, placementOf);
    }
    else
    {
      std::set<vtkProp*> visible;
      if (const std::vector<vtkProp*>* kept = culling.Visible())
        visible.insert(kept->begin(), kept->end());
      for (const auto& actor : pipeline.GetActors())
      {
        if (culling.Visible() && !visible.count(actor))
          continue;
        auto* input = vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0));
        if (!input)
          continue;
        const std::set<long long> p = DistinctValues(input, partArray);
        const std::set<long long> r = DistinctValues(input, roomArray);
        parts.insert(p.begin(), p.end());
        rooms.insert(r.begin(), r.end());
      }
    }
    vtkCamera* camera = renderer->GetActiveCamera();
    std::ostringstream json;
    json << std::fixed << std::setprecision(3);
    json << "{\n  \"command\": \"cull\",\n  \"scene\": " << JsonString(scene.description)
         << ",\n  \"camera\": " << JsonCamera(camera, spec.FixedClippingRange())
         << ",\n  \"size\": [" << options.width << ", " << options.height
         << "],\n  \"culling\": {\"method\": " << JsonString(plan.cull.method)
         << ", \"reason\": " << JsonString(plan.cull.reason);
    culling.Describe(json);
    json << "},\n  \"cull_ms\": " << culling.CullMs()
         << ",\n  \"props\": {\"total\": " << pipeline.Placements()
         << ", \"visible\": " << propsVisible
         << "},\n  \"triangles\": {\"total\": " << plan.facts.triangles
         << ", \"visible\": " << culling.TrianglesDrawn()
         << "},\n  \"parts\": {\"total\": " << plan.facts.parts << ", \"visible\": " << parts.size()
         << ", \"ids\": " << JsonIds(parts) << "}";
    if (plan.facts.rooms > 0)
    {
      // -1 is the outside (facade, roof): listed when its props are drawn, not counted as a room.
      const auto insideRooms =
        std::count_if(rooms.begin(), rooms.end(), [](long long room) { return room >= 0; });
      json << ",\n  \"rooms\": {\"total\": " << plan.facts.rooms << ", \"visible\": " << insideRooms
           << ", \"ids\": " << JsonIds(rooms) << "}";
    }
    if (vtkChunkedPolyDataMapper* chunked = pipeline.GetChunkedMapper())
    {
      json << ",\n  \"chunks\": {\"total\": " << chunked->GetNumberOfChunks()
           << ", \"visible\": " << chunked->GetNumberOfChunksDrawn() << "}";
    }
    if (options.exact)
    {
      DescribeExact(json, window, camera, spec.FixedClippingRange(),
        flattened ? flattened.Get() : pd, keys, pipeline, culling,
        plan.instanced ? &placementOf : nullptr);
    }
    if (!exported.empty())
    {
      json << ",\n  \"exported\": [";
      for (std::size_t i = 0; i < exported.size(); ++i)
        json << (i ? ", " : "") << JsonString(exported[i]);
      json << "]";
    }
    json << "\n}";
    results.push_back(json.str());
  }
  std::string text;
  if (perCamera)
  {
    // One result per camera, in the file's order.
    text = "[\n";
    for (std::size_t i = 0; i < results.size(); ++i)
      text += results[i] + (i + 1 < results.size() ? ",\n" : "\n");
    text += "]\n";
  }
  else
  {
    text = results.front() + "\n";
  }
  std::cout << text;
  if (!options.report.empty())
    WriteReport(text, options.report);
  ExitNowIfManyActors(pipeline.Parts());
  return EXIT_SUCCESS;
}

} // namespace tool
} // namespace scenevis
