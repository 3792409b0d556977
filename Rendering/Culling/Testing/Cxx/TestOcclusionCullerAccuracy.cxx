// vtkOcclusionCuller against the exact visible set of the ID buffer (depth-tested ID render of
// every cell with the same camera and clipping range as the culled frame):
//  - 0 false negatives: every part seen at some pixel is drawn. Translucent parts never occlude:
//    the reference for opaque parts is the ID render WITHOUT the translucent ones (what is behind
//    glass is visible), translucent parts themselves are checked against the full render;
//  - the image with the culler equals the image without any culler, pixel for pixel;
//  - occlusion does cull (a culler that keeps everything would pass the first check);
// on the CAD demo assembly (cameras inside, between and outside the parts, grazing views, the
// eye next to a part, parallel projections, the assembly at 1e7) and the generated building
// (one actor per room and part: eyes in rooms, on the stairs, outside; 90 degree views), and the
// building with vtkPortalCuller first and vtkOcclusionCuller after it (the renderer's culler
// list): rooms seen through portals, furniture hidden behind their walls; and the CAD assembly
// drawn through composite mappers (multiblock inputs, as ParaView and VTK's multiblock readers
// draw), one of them holding a huge wall hidden by its block visibility, which must not occlude.
// Over-draw (parts kept / parts visible) is printed beside vtkOctreeCuller's.
#include "vtkOcclusionCuller.h"
#include "vtkOctreeCuller.h"
#include "vtkPortalCuller.h"

#include "scenevis/Scenes.h"
#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCompositeDataDisplayAttributes.h>
#include <vtkCompositePolyDataMapper2.h>
#include <vtkCullerCollection.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <vector>

namespace
{
namespace st = scenevis::testing;
namespace sn = scenevis::scenes;

/// One actor's polygons, with the look of its part.
struct Group
{
  std::vector<std::uint32_t> polygons;
  glm::dvec3 colour{ 1.0 };
  double opacity = 1.0;
};

/// Polydata of the groups' polygons; cell data "OriginalId" = group index. @p keep filters groups.
template <typename Keep>
vtkSmartPointer<vtkPolyData> PolysOf(const scenevis::PolygonMesh& mesh,
  const std::vector<Group>& groups, const std::vector<std::size_t>& which, Keep keep,
  const glm::dvec3& shift = glm::dvec3(0.0))
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("OriginalId");
  std::map<std::uint32_t, vtkIdType> pointOf;
  std::vector<vtkIdType> cell;
  for (const std::size_t g : which)
  {
    if (!keep(g))
    {
      continue;
    }
    for (const std::uint32_t i : groups[g].polygons)
    {
      cell.clear();
      for (std::uint32_t k = 0; k < mesh.polygonSize(i); ++k)
      {
        const std::uint32_t p = mesh.polygon(i)[k];
        auto it = pointOf.find(p);
        if (it == pointOf.end())
        {
          const glm::dvec3 x = mesh.points[p] + shift;
          it = pointOf.emplace(p, points->InsertNextPoint(x.x, x.y, x.z)).first;
        }
        cell.push_back(it->second);
      }
      polys->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
      ids->InsertNextValue(static_cast<vtkIdType>(g));
    }
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(points);
  pd->SetPolys(polys);
  pd->GetCellData()->AddArray(ids);
  return pd;
}

auto All = [](std::size_t) { return true; };

struct SceneActors
{
  vtkNew<vtkRenderer> renderer;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  std::vector<Group> groups;
  vtkSmartPointer<vtkPolyData> all, opaque;
};

/// A square of side @p side in the plane z = @p z, centred on (@p x, @p y).
vtkSmartPointer<vtkPolyData> Wall(double x, double y, double z, double side)
{
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 4; ++k)
  {
    points->InsertNextPoint(
      x + ((k == 1 || k == 2) ? 0.5 : -0.5) * side, y + (k >= 2 ? 0.5 : -0.5) * side, z);
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType quad[4] = { 0, 1, 2, 3 };
  polys->InsertNextCell(4, quad);
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(points);
  pd->SetPolys(polys);
  return pd;
}

/**
 * One actor per group. @p hiddenWall: each part is drawn as ParaView's representations and
 * VTK's multiblock readers draw, a vtkCompositePolyDataMapper2 over a multiblock; the first
 * actor's also holds this wall as a second block, hidden by its block visibility (it must not
 * occlude: it is not drawn, and the reference renders leave it out).
 */
void Build(SceneActors& s, const scenevis::PolygonMesh& mesh, const glm::dvec3& shift,
  vtkPolyData* hiddenWall = nullptr)
{
  std::vector<std::size_t> every(s.groups.size());
  for (std::size_t g = 0; g < every.size(); ++g)
  {
    every[g] = g;
    vtkSmartPointer<vtkPolyDataMapper> mapper;
    if (hiddenWall)
    {
      vtkNew<vtkMultiBlockDataSet> blocks;
      blocks->SetBlock(0, PolysOf(mesh, s.groups, { g }, All, shift));
      vtkNew<vtkCompositePolyDataMapper2> composite;
      if (g == 0)
      {
        blocks->SetBlock(1, hiddenWall);
        vtkNew<vtkCompositeDataDisplayAttributes> attributes;
        attributes->SetBlockVisibility(hiddenWall, false);
        composite->SetCompositeDataDisplayAttributes(attributes);
      }
      composite->SetInputDataObject(blocks);
      mapper = composite;
    }
    else
    {
      mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
      mapper->SetInputData(PolysOf(mesh, s.groups, { g }, All, shift));
    }
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    const Group& group = s.groups[g];
    actor->GetProperty()->SetColor(group.colour.x, group.colour.y, group.colour.z);
    actor->GetProperty()->SetOpacity(group.opacity);
    s.renderer->AddActor(actor);
    s.actors.push_back(actor);
  }
  s.all = PolysOf(mesh, s.groups, every, All, shift);
  s.opaque = PolysOf(
    mesh, s.groups, every, [&](std::size_t g) { return s.groups[g].opacity >= 1.0; }, shift);
}

/// The props drawn after @p first (if any) and then @p culler, as the renderer runs its cullers.
std::vector<std::uint32_t> DirectCull(
  vtkOctreeCuller* culler, SceneActors& s, vtkCuller* first = nullptr)
{
  std::vector<vtkProp*> props(s.actors.begin(), s.actors.end());
  int length = static_cast<int>(props.size());
  int initialized = 0;
  if (first)
  {
    first->Cull(s.renderer, props.data(), length, initialized);
  }
  culler->Cull(s.renderer, props.data(), length, initialized);
  std::map<vtkProp*, std::uint32_t> index;
  for (std::size_t i = 0; i < s.actors.size(); ++i)
  {
    index[s.actors[i]] = static_cast<std::uint32_t>(i);
  }
  std::vector<std::uint32_t> drawn;
  for (int i = 0; i < length; ++i)
  {
    drawn.push_back(index[props[i]]);
  }
  return drawn;
}

bool SameImage(vtkImageData* a, vtkImageData* b)
{
  return a->GetNumberOfPoints() == b->GetNumberOfPoints() &&
    std::memcmp(a->GetScalarPointer(), b->GetScalarPointer(),
      static_cast<std::size_t>(a->GetNumberOfPoints()) *
        static_cast<std::size_t>(a->GetNumberOfScalarComponents())) == 0;
}

struct Tally
{
  std::size_t cameras = 0, missing = 0, visible = 0, drawnOcclusion = 0, drawnFrustum = 0;
  std::size_t culledByOcclusion = 0, images = 0, imageMismatches = 0;
};

/// Culls with both cullers at the renderer's camera and checks against the ID buffer.
void CheckView(SceneActors& s, vtkRenderWindow* window, vtkOcclusionCuller* occlusion,
  vtkOctreeCuller* frustum, bool compareImages, const std::string& label, Tally& t,
  vtkCuller* first = nullptr)
{
  window->GetRenderers()->RemoveAllItems();
  window->AddRenderer(s.renderer);
  s.renderer->ResetCameraClippingRange();
  const std::vector<std::uint32_t> drawn = DirectCull(occlusion, s, first);
  const std::vector<std::uint32_t> drawnFrustum = DirectCull(frustum, s, first);
  st::IdRenderOptions options;
  options.originalIdArray = "OriginalId";
  options.cameraClippingRange = true;
  vtkCamera* camera = s.renderer->GetActiveCamera();
  std::set<std::uint32_t> visible;
  for (const std::uint32_t id :
    st::VisibleSet(st::RenderIdBuffer(window, s.opaque, camera, options)))
  {
    visible.insert(id);
  }
  for (const std::uint32_t id : st::VisibleSet(st::RenderIdBuffer(window, s.all, camera, options)))
  {
    if (s.groups[id].opacity < 1.0)
    {
      visible.insert(id);
    }
  }
  const st::CullingCheck check = st::CullingIsConservative(
    std::vector<std::uint32_t>(visible.begin(), visible.end()), drawn);
  if (!check.conservative)
  {
    std::cout << "FAIL " << label << ": " << check.Summary() << "\n";
    double eye[3], focal[3];
    camera->GetPosition(eye);
    camera->GetFocalPoint(focal);
    const double* range = camera->GetClippingRange();
    std::cout << "  eye " << eye[0] << " " << eye[1] << " " << eye[2] << " focal " << focal[0]
              << " " << focal[1] << " " << focal[2] << " range " << range[0] << " " << range[1]
              << "\n";
    const st::IdImage opaque = st::RenderIdBuffer(window, s.opaque, camera, options);
    for (const std::uint32_t id : check.missing)
    {
      std::size_t pixels = 0;
      int x = -1, y = -1;
      for (int j = 0; j < opaque.height; ++j)
      {
        for (int i = 0; i < opaque.width; ++i)
        {
          if (opaque.At(i, j) == id)
          {
            ++pixels;
            x = i;
            y = j;
          }
        }
      }
      std::cout << "  part " << id << " (" << s.groups[id].polygons.size()
                << " polygons) visible at " << pixels << " pixels, e.g. (" << x << ", " << y
                << ")\n";
    }
  }
  ++t.cameras;
  t.missing += check.missing.size();
  t.visible += visible.size();
  t.drawnOcclusion += drawn.size();
  t.drawnFrustum += drawnFrustum.size();
  t.culledByOcclusion += static_cast<std::size_t>(occlusion->GetNumberOfPropsCulledByOcclusion());
  if (compareImages)
  {
    window->GetRenderers()->RemoveAllItems();
    window->AddRenderer(s.renderer);
    s.renderer->GetCullers()->RemoveAllItems();
    vtkSmartPointer<vtkImageData> reference = st::CaptureImage(window);
    if (first)
    {
      s.renderer->AddCuller(first);
    }
    s.renderer->AddCuller(occlusion);
    vtkSmartPointer<vtkImageData> culled = st::CaptureImage(window);
    s.renderer->GetCullers()->RemoveAllItems();
    ++t.images;
    if (!SameImage(reference, culled))
    {
      ++t.imageMismatches;
      std::cout << "FAIL " << label << ": the image with the culler differs\n";
    }
  }
}

bool Report(const std::string& scene, const Tally& t)
{
  std::cout << scene << ": " << t.cameras << " cameras; parts visible " << t.visible
            << ", drawn with occlusion " << t.drawnOcclusion << " (over-draw "
            << double(t.drawnOcclusion) / std::max<std::size_t>(1, t.visible)
            << "), with frustum culling only " << t.drawnFrustum << " (over-draw "
            << double(t.drawnFrustum) / std::max<std::size_t>(1, t.visible)
            << "); culled by occlusion " << t.culledByOcclusion << "; images compared "
            << t.images << "\n";
  bool ok = true;
  auto check = [&](bool c, const std::string& what) {
    std::cout << (c ? "ok   " : "FAIL ") << scene << ": " << what << "\n";
    ok &= c;
  };
  check(t.missing == 0, "0 false negatives (" + std::to_string(t.missing) + ")");
  check(t.imageMismatches == 0, "images with and without the culler are identical");
  check(t.culledByOcclusion > 0 && t.drawnOcclusion < t.drawnFrustum, "occlusion culls");
  return ok;
}

void LookAt(vtkCamera* camera, const glm::dvec3& eye, const glm::dvec3& focal, double angle,
  bool parallel, double scale)
{
  camera->SetPosition(eye.x, eye.y, eye.z);
  camera->SetFocalPoint(focal.x, focal.y, focal.z);
  const glm::dvec3 d = glm::normalize(focal - eye);
  camera->SetViewUp(std::abs(d.z) > 0.95 ? 1.0 : 0.0, 0.0, std::abs(d.z) > 0.95 ? 0.0 : 1.0);
  camera->OrthogonalizeViewUp();
  camera->SetViewAngle(angle);
  camera->SetParallelProjection(parallel);
  camera->SetParallelScale(scale);
}

/// @p composite: the parts drawn through composite mappers, one with a hidden wall (see Build).
bool TestCad(vtkRenderWindow* window, const glm::dvec3& origin, int cameras, const char* name,
  bool composite = false)
{
  const sn::Scene scene = sn::cadAssembly(400, 60, 3, origin);
  SceneActors s;
  for (const sn::Part& part : scene.parts)
  {
    Group g;
    for (std::uint32_t i = 0; i < part.polygonCount; ++i)
    {
      g.polygons.push_back(part.firstPolygon + i);
    }
    g.colour = part.colour;
    g.opacity = part.opacity;
    s.groups.push_back(g);
  }
  const scenevis::Box box = scene.mesh.bounds();
  const glm::dvec3 centre = box.center();
  const auto wall =
    composite ? Wall(centre.x, centre.y, centre.z, 10.0 * glm::length(box.hi - box.lo)) : nullptr;
  Build(s, scene.mesh, glm::dvec3(0.0), wall);
  vtkNew<vtkCamera> camera;
  s.renderer->SetActiveCamera(camera);
  vtkNew<vtkOcclusionCuller> occlusion;
  vtkNew<vtkOctreeCuller> frustum;
  const scenevis::Box bounds = scene.mesh.bounds();
  const glm::dvec3 size = bounds.hi - bounds.lo;
  std::mt19937_64 gen(99);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Tally t;
  for (int c = 0; c < cameras; ++c)
  {
    const glm::dvec3 focal = bounds.lo + glm::dvec3(u(gen), u(gen), u(gen) * 0.3) * size;
    glm::dvec3 eye;
    const int kind = c % 5;
    if (kind == 0 || kind == 1)
    {
      // Low over the board, looking across it (grazing): rows of parts hide rows.
      eye = focal + glm::dvec3(u(gen) - 0.5, u(gen) - 0.5, 0.0) * size * 0.8;
      eye.z = bounds.lo.z + size.z * (0.05 + 0.2 * u(gen));
    }
    else if (kind == 2)
    {
      // Right next to a part: 0.1 % of the model outside one of its box faces, looking along it.
      const sn::Part& part = scene.parts[1 + static_cast<std::size_t>(u(gen) * (scene.parts.size() - 1))];
      eye = glm::dvec3(part.bounds.hi.x + 1e-3 * glm::length(size), part.bounds.center().y,
        part.bounds.center().z);
    }
    else if (kind == 3)
    {
      eye = focal + glm::normalize(glm::dvec3(u(gen) - 0.5, u(gen) - 0.5, u(gen) * 0.8 + 0.1)) *
        glm::length(size) * (0.05 + 0.8 * u(gen));
    }
    else
    {
      eye = focal + glm::normalize(glm::dvec3(u(gen) - 0.5, u(gen) - 0.5, 0.15)) *
        glm::length(size);
    }
    if (glm::length(focal - eye) < 1e-6 * glm::length(size))
    {
      eye.x += 0.1 * size.x;
    }
    LookAt(camera, eye, focal, kind == 2 ? 90.0 : 30.0 + 40.0 * u(gen), kind == 4,
      glm::length(size) * 0.2);
    CheckView(s, window, occlusion, frustum, c % 4 == 0,
      std::string(name) + " camera " + std::to_string(c), t);
  }
  return Report(name, t);
}

/// @p withPortals: vtkPortalCuller (exact frustum narrowing) runs before both cullers compared.
bool TestBuilding(vtkRenderWindow* window, int cameras, bool withPortals)
{
  const sn::BuildingScene b = sn::building(2, 4, 3, 5);
  // One group per (room, part): walls of a room hide the furniture of the next.
  std::map<std::pair<std::int32_t, std::uint32_t>, std::size_t> groupOf;
  SceneActors s;
  for (std::uint32_t i = 0; i < b.mesh.polygonCount(); ++i)
  {
    const auto key = std::make_pair(b.room[i], b.part[i]);
    auto it = groupOf.find(key);
    if (it == groupOf.end())
    {
      it = groupOf.emplace(key, s.groups.size()).first;
      Group g;
      g.colour = b.parts[b.part[i]].colour;
      g.opacity = b.parts[b.part[i]].opacity;
      s.groups.push_back(g);
    }
    s.groups[it->second].polygons.push_back(i);
  }
  Build(s, b.mesh, glm::dvec3(0.0));
  vtkNew<vtkPortalCuller> portals;
  portals->SetPortals(st::MakePortalPolyData(b));
  for (const auto& entry : groupOf)
  {
    portals->SetPropRoom(s.actors[entry.second], entry.first.first);
  }
  vtkNew<vtkCamera> camera;
  s.renderer->SetActiveCamera(camera);
  vtkNew<vtkOcclusionCuller> occlusion;
  vtkNew<vtkOctreeCuller> frustum;
  std::mt19937_64 gen(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Tally t;
  const scenevis::Box bounds = b.mesh.bounds();
  for (int c = 0; c < cameras; ++c)
  {
    glm::dvec3 eye, focal;
    bool parallel = false;
    if (c % 6 == 5)
    {
      // Outside, looking at the facade (windows show rooms), every other one parallel.
      const double a = u(gen) * 6.283;
      focal = bounds.center();
      eye = focal + glm::dvec3(std::cos(a), std::sin(a), 0.3) * glm::length(bounds.hi - bounds.lo);
      parallel = c % 12 == 11;
    }
    else
    {
      const sn::Room& room = b.rooms[static_cast<std::size_t>(u(gen) * b.rooms.size())];
      const glm::dvec3 lo = room.bounds.lo + glm::dvec3(0.3, 0.3, 0.4);
      const glm::dvec3 hi = room.bounds.hi - glm::dvec3(0.3, 0.3, 0.4);
      eye = lo + glm::dvec3(u(gen), u(gen), u(gen)) * (hi - lo);
      const double a = u(gen) * 6.283;
      focal = eye + glm::dvec3(std::cos(a), std::sin(a), 0.2 * (u(gen) - 0.5));
    }
    LookAt(camera, eye, focal, 90.0, parallel, glm::length(bounds.hi - bounds.lo) * 0.3);
    const std::string name = withPortals ? "building with portals" : "building";
    CheckView(s, window, occlusion, frustum, c % 4 == 0, name + " camera " + std::to_string(c), t,
      withPortals ? portals.GetPointer() : nullptr);
  }
  // After the portal culler the cullers see a different subset of the props at each camera
  // (often less than half): their hierarchy, built once over the renderer's props, stays.
  bool ok = Report(withPortals ? "building, portals then occlusion" : "building", t);
  for (vtkOctreeCuller* culler : { static_cast<vtkOctreeCuller*>(occlusion), frustum.Get() })
  {
    if (culler->GetNumberOfRebuilds() != 1)
    {
      std::cout << "FAIL " << (withPortals ? "building with portals" : "building") << ": "
                << culler->GetClassName() << " rebuilt its hierarchy "
                << culler->GetNumberOfRebuilds() << " times for " << cameras
                << " cameras (expected once)\n";
      ok = false;
    }
  }
  return ok;
}
} // namespace

int TestOcclusionCullerAccuracy(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(320, 240);
  bool ok = true;
  ok &= TestCad(window, glm::dvec3(0.0), 40, "cad");
  ok &= TestCad(window, glm::dvec3(1e7, -1e7, 5e6), 10, "cad at 1e7");
  ok &= TestCad(window, glm::dvec3(0.0), 20, "cad, composite mappers", true);
  ok &= TestBuilding(window, 36, false);
  ok &= TestBuilding(window, 36, true);
  {
    vtkNew<vtkOcclusionCuller> culler;
    std::ostringstream print;
    culler->Print(print);
    ok &= print.str().find("NumberOfPropsCulledByOcclusion") != std::string::npos;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
