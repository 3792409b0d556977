// vtkOctreeCuller on the embedded CAD assembly (one actor per part, and one actor per 24-polygon
// patch for normal cones) over random cameras, against the exact visible set of the ID buffer:
//  (a) frustum mode: every visible actor is drawn (0 false negatives) and the image rendered with
//      the culler equals the image without any culler, pixel for pixel;
//  (b) normal-cone mode (patches drawn with back-face culling): 0 false negatives against the
//      visible set of the front-facing triangles, and cones do cull;
//  (c) small-feature mode (approximate): the visible pixels lost are printed; sanity bound only.
#include "vtkOctreeCuller.h"

#include "scenevis/Scenes.h"

#include <glm/geometric.hpp>
#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCullerCollection.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <random>
#include <set>
#include <vector>

namespace
{
namespace st = scenevis::testing;
using scenevis::PolygonMesh;

/// Polydata of polygons [first, first + count) of @p mesh (own points), optionally filtered.
template <typename Keep>
vtkSmartPointer<vtkPolyData> PolysOf(const PolygonMesh& mesh,
  const std::vector<std::pair<std::size_t, std::size_t>>& ranges,
  const std::vector<vtkIdType>& rangeIds,
  Keep keep)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("OriginalId");
  std::vector<vtkIdType> cell;
  for (std::size_t r = 0; r < ranges.size(); ++r)
  {
    for (std::size_t i = ranges[r].first; i < ranges[r].first + ranges[r].second; ++i)
    {
      if (!keep(i))
      {
        continue;
      }
      cell.clear();
      for (std::uint32_t k = 0; k < mesh.polygonSize(i); ++k)
      {
        const glm::dvec3& p = mesh.points[mesh.polygon(i)[k]];
        cell.push_back(points->InsertNextPoint(p.x, p.y, p.z));
      }
      polys->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
      ids->InsertNextValue(rangeIds[r]);
    }
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(points);
  pd->SetPolys(polys);
  pd->GetCellData()->AddArray(ids);
  return pd;
}

auto All = [](std::size_t) { return true; };

struct Actors
{
  vtkNew<vtkRenderer> renderer;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  std::vector<std::pair<std::size_t, std::size_t>> ranges; // polygon range of each actor
};

void MakeActors(Actors& out,
  const scenevis::scenes::Scene& scene,
  std::size_t patch,
  bool backfaceCulling)
{
  for (const auto& part : scene.parts)
  {
    for (std::size_t first = part.firstPolygon; first < part.firstPolygon + part.polygonCount;
         first += patch)
    {
      const std::size_t count = std::min(patch, part.firstPolygon + part.polygonCount - first);
      out.ranges.emplace_back(first, count);
    }
  }
  for (std::size_t a = 0; a < out.ranges.size(); ++a)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(PolysOf(scene.mesh, { out.ranges[a] }, { 0 }, All));
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetBackfaceCulling(backfaceCulling);
    out.renderer->AddActor(actor);
    out.actors.push_back(actor);
  }
}

void RandomCamera(vtkCamera* camera, std::mt19937_64& gen, const scenevis::Box& bounds, int i)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const glm::dvec3 size = bounds.hi - bounds.lo;
  const glm::dvec3 focal =
    bounds.lo + glm::dvec3(u(gen), u(gen), u(gen)) * size;
  glm::dvec3 dir(u(gen) - 0.5, u(gen) - 0.5, u(gen) * 0.8 + 0.1);
  dir = glm::normalize(dir);
  const double distance = glm::length(size) * (0.05 + 0.8 * u(gen));
  const glm::dvec3 eye = focal + dir * distance;
  camera->SetFocalPoint(focal.x, focal.y, focal.z);
  camera->SetPosition(eye.x, eye.y, eye.z);
  camera->SetViewUp(0, 0, 1);
  camera->OrthogonalizeViewUp();
  camera->SetViewAngle(20.0 + 40.0 * u(gen));
  camera->SetParallelProjection(i % 6 == 5);
  camera->SetParallelScale(distance * 0.4);
}

std::vector<std::uint32_t> DirectCull(vtkOctreeCuller* culler, Actors& a)
{
  std::vector<vtkProp*> props(a.actors.begin(), a.actors.end());
  int length = static_cast<int>(props.size());
  int initialized = 0;
  culler->Cull(a.renderer, props.data(), length, initialized);
  std::vector<std::uint32_t> drawn;
  std::vector<vtkProp*> sortedActors(a.actors.begin(), a.actors.end());
  for (int i = 0; i < length; ++i)
  {
    const auto it = std::find(a.actors.begin(), a.actors.end(), props[i]);
    drawn.push_back(static_cast<std::uint32_t>(it - a.actors.begin()));
  }
  return drawn;
}

bool Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  return ok;
}
} // namespace

int TestOctreeCullerAccuracy(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  const int cameras = 30;
  const scenevis::scenes::Scene scene = scenevis::scenes::cadAssembly(500, 60, 1);
  const scenevis::Box bounds = scene.mesh.bounds();
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(400, 300);

  // ---- (a) + (c): one actor per part. ---------------------------------------------------------
  {
    Actors a;
    MakeActors(a, scene, 1u << 30, false);
    std::vector<vtkIdType> partIds(a.ranges.size());
    for (std::size_t i = 0; i < partIds.size(); ++i)
    {
      partIds[i] = static_cast<vtkIdType>(i);
    }
    vtkSmartPointer<vtkPolyData> merged = PolysOf(scene.mesh, a.ranges, partIds, All);
    vtkNew<vtkCamera> camera;
    a.renderer->SetActiveCamera(camera);
    vtkNew<vtkOctreeCuller> culler;
    vtkNew<vtkOctreeCuller> smallCuller;
    smallCuller->SetMinimumPixelSize(4.0);
    std::mt19937_64 gen(2024);
    std::size_t missing = 0, drawnTotal = 0, visibleTotal = 0, imageMismatches = 0;
    std::size_t smallMissing = 0, lostPixels = 0, coveredPixels = 0, smallDrawn = 0;
    for (int c = 0; c < cameras; ++c)
    {
      RandomCamera(camera, gen, bounds, c);
      window->GetRenderers()->RemoveAllItems();
      window->AddRenderer(a.renderer);
      a.renderer->ResetCameraClippingRange();
      const std::vector<std::uint32_t> drawn = DirectCull(culler, a);
      const std::vector<std::uint32_t> drawnSmall = DirectCull(smallCuller, a);
      const st::IdImage evs = st::RenderVisibleIds(window, merged, camera, "OriginalId");
      const std::vector<std::uint32_t> visible = st::VisibleSet(evs);
      const st::CullingCheck check = st::CullingIsConservative(visible, drawn);
      missing += check.missing.size();
      if (!check.conservative)
      {
        std::cout << "camera " << c << ": " << check.Summary() << "\n";
      }
      drawnTotal += drawn.size();
      visibleTotal += visible.size();
      const st::CullingCheck smallCheck = st::CullingIsConservative(visible, drawnSmall);
      smallMissing += smallCheck.missing.size();
      smallDrawn += drawnSmall.size();
      const std::set<std::uint32_t> lost(smallCheck.missing.begin(), smallCheck.missing.end());
      for (const std::uint32_t id : evs.ids)
      {
        coveredPixels += id != st::kNoId ? 1 : 0;
        lostPixels += lost.count(id);
      }

      // Integration: rendered through the renderer, with the culler replacing VTK's, the image
      // equals the one rendered without any culler.
      if (c % 5 == 0)
      {
        window->GetRenderers()->RemoveAllItems();
        window->AddRenderer(a.renderer);
        a.renderer->GetCullers()->RemoveAllItems();
        a.renderer->ResetCameraClippingRange();
        vtkSmartPointer<vtkImageData> reference = st::CaptureImage(window);
        a.renderer->AddCuller(culler);
        vtkSmartPointer<vtkImageData> culled = st::CaptureImage(window);
        const bool same = reference->GetNumberOfPoints() == culled->GetNumberOfPoints() &&
          std::memcmp(reference->GetScalarPointer(), culled->GetScalarPointer(),
            static_cast<std::size_t>(reference->GetNumberOfPoints()) *
              static_cast<std::size_t>(reference->GetNumberOfScalarComponents())) == 0;
        imageMismatches += same ? 0 : 1;
        ok &= Check(culler->GetNumberOfPropsDrawn() == static_cast<vtkIdType>(drawn.size()),
          "camera " + std::to_string(c) + ": renderer drew " +
            std::to_string(culler->GetNumberOfPropsDrawn()) + " props, direct Cull() " +
            std::to_string(drawn.size()));
        a.renderer->GetCullers()->RemoveAllItems();
      }
    }
    std::cout << "frustum: " << cameras << " cameras, " << a.actors.size() << " actors; drawn "
              << drawnTotal << ", visible (ID buffer) " << visibleTotal << ", culled "
              << (cameras * a.actors.size() - drawnTotal) << " (rebuilds "
              << culler->GetNumberOfRebuilds() << ")\n";
    ok &= Check(missing == 0, "frustum mode: 0 false negatives (" + std::to_string(missing) + ")");
    ok &= Check(drawnTotal < cameras * a.actors.size(), "frustum mode culls something");
    ok &= Check(imageMismatches == 0, "images with and without the culler are identical");
    ok &= Check(culler->GetNumberOfRebuilds() == 1, "one build, no rebuild per frame");
    std::cout << "small-feature (4 px, APPROXIMATE): drew " << smallDrawn << " instead of "
              << drawnTotal << "; visible actors lost " << smallMissing << "; visible pixels lost "
              << lostPixels << " of " << coveredPixels << " ("
              << 100.0 * static_cast<double>(lostPixels) / std::max<double>(1.0, coveredPixels)
              << " %)\n";
    ok &= Check(smallDrawn <= drawnTotal && lostPixels * 50 < coveredPixels,
      "small-feature mode: fewer props, under 2 % of the pixels lost");
  }

  // ---- (b) normal cones: patches of 24 polygons drawn with back-face culling. ---------------
  {
    Actors a;
    MakeActors(a, scene, 24, true);
    vtkNew<vtkCamera> camera;
    a.renderer->SetActiveCamera(camera);
    vtkNew<vtkOctreeCuller> culler;
    culler->NormalConeCullingOn();
    std::vector<vtkIdType> patchIds(a.ranges.size());
    std::vector<std::uint32_t> patchOf(scene.mesh.polygonCount());
    for (std::size_t i = 0; i < patchIds.size(); ++i)
    {
      patchIds[i] = static_cast<vtkIdType>(i);
      for (std::size_t p = a.ranges[i].first; p < a.ranges[i].first + a.ranges[i].second; ++p)
      {
        patchOf[p] = static_cast<std::uint32_t>(i);
      }
    }
    std::mt19937_64 gen(77);
    std::size_t missing = 0, coneCulled = 0, drawnTotal = 0;
    for (int c = 0; c < cameras; ++c)
    {
      RandomCamera(camera, gen, bounds, c);
      window->GetRenderers()->RemoveAllItems();
      window->AddRenderer(a.renderer);
      a.renderer->ResetCameraClippingRange();
      const std::vector<std::uint32_t> drawn = DirectCull(culler, a);
      coneCulled += static_cast<std::size_t>(culler->GetNumberOfPropsCulledByNormalCone());
      drawnTotal += drawn.size();
      // Ground truth with back-face culling: the visible set of the front-facing triangles.
      double eye[3], dop[3];
      camera->GetPosition(eye);
      camera->GetDirectionOfProjection(dop);
      const bool parallel = camera->GetParallelProjection() != 0;
      const PolygonMesh& mesh = scene.mesh;
      auto front = [&](std::size_t i)
      {
        const std::uint32_t* ids = mesh.polygon(i);
        const glm::dvec3 n = scenevis::newellNormal(mesh.points.data(), ids, mesh.polygonSize(i));
        const glm::dvec3 toEye = parallel ? -glm::dvec3(dop[0], dop[1], dop[2])
                                          : glm::dvec3(eye[0], eye[1], eye[2]) - mesh.points[ids[0]];
        return glm::dot(n, toEye) > 0.0;
      };
      vtkSmartPointer<vtkPolyData> frontFacing = PolysOf(mesh, a.ranges, patchIds, front);
      const std::vector<std::uint32_t> visible =
        st::VisibleSet(st::RenderVisibleIds(window, frontFacing, camera, "OriginalId"));
      const st::CullingCheck check = st::CullingIsConservative(visible, drawn);
      missing += check.missing.size();
      if (!check.conservative)
      {
        std::cout << "camera " << c << ": " << check.Summary() << "\n";
      }
    }
    std::cout << "normal cones: " << a.actors.size() << " patch actors x " << cameras
              << " cameras; drawn " << drawnTotal << ", culled by cone " << coneCulled << "\n";
    ok &= Check(missing == 0, "normal-cone mode: 0 false negatives (" + std::to_string(missing) + ")");
    ok &= Check(coneCulled > 0, "normal cones cull back-facing patches");
  }
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}
