// vtkOctreeCuller on a REAL assembly: a small KiCad board (50 parts read from the KiCad VRML
// library, scenevis::testing::MakeKiCadBoard), one actor per placed part (the actors of a part
// share its mapper and differ by their user matrix), over random cameras, against the exact
// visible set of the ID buffer (the merged board, "PartId" = actor index):
//  (a) frustum mode: every visible actor is drawn (0 false negatives), and the image rendered
//      with the culler equals the one without any culler, pixel for pixel;
//  (b) normal-cone mode with back-face culling: 0 false negatives against the visible set of the
//      triangles that face the eye (the parts are not all closed, which the test does not need);
//  (c) small-feature mode (APPROXIMATE): the visible pixels lost are printed;
//  (d) the same board as ONE merged mesh drawn by vtkChunkedPolyDataMapper: every visible
//      triangle is drawn (frustum; and with back-face culling, normal cones, against the front-
//      facing visible set), culling is never skipped (real parts carry degenerate triangles,
//      which must not break the chunk partition), culled images equal unculled ones.
// Skipped (exit code 77) when the KiCad parts are not in the data cache.
#include "vtkChunkedPolyDataMapper.h"
#include "vtkOctreeCuller.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/KiCadBoard.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCullerCollection.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace
{
namespace st = scenevis::testing;

bool Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  return ok;
}

/// Random eye above or beside the board, looking at a random point of it, perspective or
/// parallel, close-ups to overviews.
void RandomCamera(vtkCamera* camera, std::mt19937_64& gen, const double* b, int i)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double size[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
  const double diagonal = std::sqrt(size[0] * size[0] + size[1] * size[1] + size[2] * size[2]);
  double focal[3], dir[3] = { u(gen) - 0.5, u(gen) - 0.5, u(gen) * 0.8 + 0.1 };
  const double norm = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  const double distance = diagonal * (0.03 + 0.8 * u(gen));
  double eye[3];
  for (int k = 0; k < 3; ++k)
  {
    focal[k] = b[2 * k] + u(gen) * size[k];
    eye[k] = focal[k] + dir[k] / norm * distance;
  }
  camera->SetFocalPoint(focal);
  camera->SetPosition(eye);
  camera->SetViewUp(0, 0, 1);
  camera->OrthogonalizeViewUp();
  camera->SetViewAngle(20.0 + 40.0 * u(gen));
  camera->SetParallelProjection(i % 6 == 5);
  camera->SetParallelScale(distance * 0.4);
}

/// Indices (into @p actors) of the props a direct Cull() keeps.
std::vector<std::uint32_t> DirectCull(vtkOctreeCuller* culler, vtkRenderer* renderer,
  const std::vector<vtkSmartPointer<vtkActor>>& actors)
{
  std::vector<vtkProp*> props(actors.begin(), actors.end());
  std::map<vtkProp*, std::uint32_t> index;
  for (std::size_t i = 0; i < props.size(); ++i)
  {
    index[props[i]] = static_cast<std::uint32_t>(i);
  }
  int length = static_cast<int>(props.size());
  int initialized = 0;
  culler->Cull(renderer, props.data(), length, initialized);
  std::vector<std::uint32_t> drawn;
  for (int i = 0; i < length; ++i)
  {
    drawn.push_back(index[props[i]]);
  }
  return drawn;
}

/// The triangles of @p merged that face the eye of @p camera, with their id array @p idName.
vtkSmartPointer<vtkPolyData> FrontFacing(vtkPolyData* merged, vtkCamera* camera, const char* idName)
{
  double eye[3], dop[3];
  camera->GetPosition(eye);
  camera->GetDirectionOfProjection(dop);
  const bool parallel = camera->GetParallelProjection() != 0;
  vtkPoints* points = merged->GetPoints();
  vtkCellArray* polys = merged->GetPolys();
  auto* partIds = vtkIdTypeArray::SafeDownCast(merged->GetCellData()->GetArray(idName));
  vtkNew<vtkCellArray> front;
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName(idName);
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    vtkIdType n;
    const vtkIdType* pts;
    polys->GetCellAtId(c, n, pts);
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      points->GetPoint(pts[k], p[k]);
    }
    const double e1[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
    const double e2[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
    const double normal[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] };
    double toEye[3];
    for (int k = 0; k < 3; ++k)
    {
      toEye[k] = parallel ? -dop[k] : eye[k] - p[0][k];
    }
    if (normal[0] * toEye[0] + normal[1] * toEye[1] + normal[2] * toEye[2] > 0.0)
    {
      front->InsertNextCell(3, pts);
      ids->InsertNextValue(partIds->GetValue(c));
    }
  }
  vtkNew<vtkPolyData> out;
  out->SetPoints(points);
  out->SetPolys(front);
  out->GetCellData()->AddArray(ids);
  return out;
}

bool SameImage(vtkImageData* a, vtkImageData* b)
{
  return a->GetNumberOfPoints() == b->GetNumberOfPoints() &&
    std::memcmp(a->GetScalarPointer(), b->GetScalarPointer(),
      static_cast<std::size_t>(a->GetNumberOfPoints()) *
        static_cast<std::size_t>(a->GetNumberOfScalarComponents())) == 0;
}
} // namespace

int TestOctreeCullerKiCad(int, char*[])
{
  st::KiCadBoardOptions options;
  options.partTypes = 20;
  options.maximumParts = 50;
  options.seed = 5;
  const st::KiCadBoard board = st::MakeKiCadBoard(options);
  if (board.Empty())
  {
    std::cout << "skipped: " << board.error << "\n";
    return 77;
  }
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  const int cameras = 30;
  std::cout << "KiCad board: " << board.partFiles.size() << " part files, "
            << board.instances.size() << " actors (with " << board.boards << " board plates), "
            << board.triangles << " triangles\n";
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(400, 300);
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkCamera> camera;
  renderer->SetActiveCamera(camera);
  std::vector<vtkSmartPointer<vtkActor>> actors;
  std::map<vtkPolyData*, vtkSmartPointer<vtkPolyDataMapper>> mappers;
  for (const st::KiCadInstance& inst : board.instances)
  {
    auto& mapper = mappers[inst.polys];
    if (!mapper)
    {
      mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
      mapper->SetInputData(inst.polys);
      mapper->SetScalarModeToUseCellData();
      mapper->SetColorModeToDirectScalars();
    }
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->SetUserMatrix(inst.matrix);
    renderer->AddActor(actor);
    actors.push_back(actor.GetPointer());
  }
  ok &= Check(board.merged && board.triangles > 10000 && board.instances.size() > 50,
    "a board of real parts: 50 parts plus plates, merged form present");

  // ---- (a) frustum + (c) small features. -----------------------------------------------------
  {
    vtkNew<vtkOctreeCuller> culler;
    vtkNew<vtkOctreeCuller> smallCuller;
    smallCuller->SetMinimumPixelSize(4.0);
    std::mt19937_64 gen(2024);
    std::size_t missing = 0, drawnTotal = 0, visibleTotal = 0, imageMismatches = 0;
    std::size_t smallMissing = 0, smallDrawn = 0, lostPixels = 0, coveredPixels = 0;
    for (int c = 0; c < cameras; ++c)
    {
      RandomCamera(camera, gen, board.bounds, c);
      window->GetRenderers()->RemoveAllItems();
      window->AddRenderer(renderer);
      renderer->ResetCameraClippingRange(board.bounds);
      const std::vector<std::uint32_t> drawn = DirectCull(culler, renderer, actors);
      const std::vector<std::uint32_t> drawnSmall = DirectCull(smallCuller, renderer, actors);
      const st::IdImage evs = st::RenderVisibleIds(window, board.merged, camera, "PartId");
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
      if (c % 5 == 0)
      {
        // Integration: through the renderer, the culler replacing VTK's, the image equals the
        // one rendered without any culler (translucent LED parts included).
        window->GetRenderers()->RemoveAllItems();
        window->AddRenderer(renderer);
        renderer->GetCullers()->RemoveAllItems();
        renderer->ResetCameraClippingRange(board.bounds);
        vtkSmartPointer<vtkImageData> reference = st::CaptureImage(window);
        renderer->AddCuller(culler);
        vtkSmartPointer<vtkImageData> culled = st::CaptureImage(window);
        imageMismatches += SameImage(reference, culled) ? 0 : 1;
        renderer->GetCullers()->RemoveAllItems();
      }
    }
    std::cout << "frustum: " << cameras << " cameras x " << actors.size() << " actors; drawn "
              << drawnTotal << ", visible (ID buffer) " << visibleTotal << ", culled "
              << cameras * actors.size() - drawnTotal << "\n";
    ok &= Check(missing == 0, "frustum mode: 0 false negatives (" + std::to_string(missing) + ")");
    ok &= Check(drawnTotal < cameras * actors.size(), "frustum mode culls something");
    ok &= Check(visibleTotal > 0, "the cameras see parts");
    ok &= Check(imageMismatches == 0, "images with and without the culler are identical");
    ok &= Check(culler->GetNumberOfRebuilds() == 1, "one build for all cameras");
    std::cout << "small-feature (4 px, APPROXIMATE): drew " << smallDrawn << " instead of "
              << drawnTotal << "; visible actors lost " << smallMissing << "; visible pixels lost "
              << lostPixels << " of " << coveredPixels << " ("
              << 100.0 * static_cast<double>(lostPixels) / std::max<double>(1.0, coveredPixels)
              << " %)\n";
    ok &= Check(smallDrawn <= drawnTotal, "small-feature mode draws no more than frustum mode");
  }

  // ---- (b) normal cones, actors drawn with back-face culling. --------------------------------
  {
    for (const auto& actor : actors)
    {
      actor->GetProperty()->BackfaceCullingOn();
    }
    vtkNew<vtkOctreeCuller> culler;
    culler->NormalConeCullingOn();
    std::mt19937_64 gen(77);
    std::size_t missing = 0, coneCulled = 0, drawnTotal = 0;
    for (int c = 0; c < cameras; ++c)
    {
      RandomCamera(camera, gen, board.bounds, c);
      window->GetRenderers()->RemoveAllItems();
      window->AddRenderer(renderer);
      renderer->ResetCameraClippingRange(board.bounds);
      const std::vector<std::uint32_t> drawn = DirectCull(culler, renderer, actors);
      coneCulled += static_cast<std::size_t>(culler->GetNumberOfPropsCulledByNormalCone());
      drawnTotal += drawn.size();
      const std::vector<std::uint32_t> visible = st::VisibleSet(st::RenderVisibleIds(
        window, FrontFacing(board.merged, camera, "PartId"), camera, "PartId"));
      const st::CullingCheck check = st::CullingIsConservative(visible, drawn);
      missing += check.missing.size();
      if (!check.conservative)
      {
        std::cout << "camera " << c << ": " << check.Summary() << "\n";
      }
    }
    std::cout << "normal cones: " << actors.size() << " actors x " << cameras << " cameras; drawn "
              << drawnTotal << ", culled by cone " << coneCulled
              << " (whole real parts rarely face away entirely)\n";
    ok &=
      Check(missing == 0, "normal-cone mode: 0 false negatives (" + std::to_string(missing) + ")");
  }
  // ---- (d) one merged mesh, vtkChunkedPolyDataMapper. ----------------------------------------
  {
    vtkNew<vtkPolyData> mesh;
    mesh->ShallowCopy(board.merged);
    vtkNew<vtkIdTypeArray> cellIndex;
    cellIndex->SetName("CellIndex");
    cellIndex->SetNumberOfValues(mesh->GetNumberOfCells());
    for (vtkIdType i = 0; i < mesh->GetNumberOfCells(); ++i)
    {
      cellIndex->SetValue(i, i);
    }
    mesh->GetCellData()->AddArray(cellIndex);
    vtkNew<vtkChunkedPolyDataMapper> mapper;
    mapper->SetInputData(mesh);
    mapper->SetChunkSize(256); // parts are small: chunks of a few parts, or sides of one
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    vtkNew<vtkRenderer> meshRenderer;
    meshRenderer->AddActor(actor);
    meshRenderer->SetActiveCamera(camera);
    auto render = [&]()
    {
      window->GetRenderers()->RemoveAllItems();
      window->AddRenderer(meshRenderer);
      meshRenderer->ResetCameraClippingRange(board.bounds);
      return st::CaptureImage(window);
    };
    // The ID renders go to a window of their own: detaching this renderer from its window for
    // them would release its graphics resources and rebuild the buffers counted below.
    vtkSmartPointer<vtkRenderWindow> idWindow = st::MakeRenderWindow(400, 300);
    std::mt19937_64 gen(99);
    std::size_t missing = 0, skipped = 0, partial = 0, coneCulled = 0, mismatches = 0;
    const vtkIdType total = mesh->GetNumberOfPolys();
    for (int pass = 0; pass < 2; ++pass)
    {
      actor->GetProperty()->SetBackfaceCulling(pass == 1);
      for (int c = 0; c < cameras; ++c)
      {
        RandomCamera(camera, gen, board.bounds, c);
        vtkSmartPointer<vtkImageData> image = render();
        skipped += mapper->GetCullingSkipped() ? 1 : 0;
        partial += mapper->GetNumberOfTrianglesDrawn() < total ? 1 : 0;
        coneCulled += static_cast<std::size_t>(mapper->GetNumberOfChunksCulledByNormalCone());
        std::vector<vtkIdType> drawnCells;
        mapper->GetDrawnCellIds(drawnCells);
        const std::vector<std::uint32_t> drawn(drawnCells.begin(), drawnCells.end());
        vtkSmartPointer<vtkPolyData> truth =
          pass == 1 ? FrontFacing(mesh, camera, "CellIndex") : vtkSmartPointer<vtkPolyData>(mesh);
        const st::CullingCheck check = st::CullingIsConservative(
          st::VisibleSet(st::RenderVisibleIds(idWindow, truth, camera, "CellIndex")), drawn);
        missing += check.missing.size();
        if (!check.conservative)
        {
          std::cout << "chunked, pass " << pass << ", camera " << c << ": " << check.Summary()
                    << "\n";
        }
        if (c % 5 == 0)
        {
          mapper->SetFrustumCulling(false);
          mapper->SetNormalConeCulling(false);
          vtkSmartPointer<vtkImageData> reference = render();
          mapper->SetFrustumCulling(true);
          mapper->SetNormalConeCulling(true);
          mismatches += SameImage(reference, image) ? 0 : 1;
        }
      }
    }
    std::cout << "chunked mapper: " << total << " triangles in " << mapper->GetNumberOfChunks()
              << " chunks; " << partial << " of " << 2 * cameras
              << " views drew part of the mesh; chunks culled by normal cones " << coneCulled
              << "\n";
    ok &= Check(skipped == 0, "chunked mapper: culling never skipped on the real mesh");
    ok &= Check(missing == 0,
      "chunked mapper: 0 false negatives, frustum and normal cones (" + std::to_string(missing) +
        ")");
    ok &= Check(partial > 0, "chunked mapper culls triangles");
    ok &= Check(mismatches == 0, "chunked mapper: culled images identical to unculled ones");
    ok &= Check(mapper->GetNumberOfVertexBufferBuilds() <= 2,
      "chunked mapper: vertex buffers built once per property state, not per camera (" +
        std::to_string(mapper->GetNumberOfVertexBufferBuilds()) + ")");
  }
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}
