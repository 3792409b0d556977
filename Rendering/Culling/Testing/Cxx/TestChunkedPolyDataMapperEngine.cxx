// vtkChunkedPolyDataMapper on real CAD data: the 2CylinderEngine glTF (assimp test models) as ONE
// merged mesh, with its degenerate triangles (two points at the same coordinates) left in.
// Skipped (exit code 77) when the data cache lacks engine-glb (scripts/fetch-data.sh).
//  (a) the mapper culls it: no warning (StrictVtkOutput), culling never skipped;
//  (b) 0 false negatives against the ID-buffer visible set over random cameras, culled images
//      identical to unculled ones;
//  (c) a close-up view draws fewer triangles than the mesh.
#include "vtkChunkedPolyDataMapper.h"

#include "ChunkedMapperTesting.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/Models.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkOpenGLIndexBufferObject.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <random>
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

void RandomCamera(vtkCamera* camera, std::mt19937_64& gen, const double* b)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const glm::dvec3 lo(b[0], b[2], b[4]), hi(b[1], b[3], b[5]);
  const glm::dvec3 size = hi - lo;
  const glm::dvec3 focal = lo + glm::dvec3(u(gen), u(gen), u(gen)) * size;
  const glm::dvec3 dir = glm::normalize(glm::dvec3(u(gen) - 0.5, u(gen) - 0.5, u(gen) - 0.5));
  const double distance = glm::length(size) * (0.1 + 0.9 * u(gen));
  const glm::dvec3 eye = focal + dir * distance;
  camera->SetFocalPoint(focal.x, focal.y, focal.z);
  camera->SetPosition(eye.x, eye.y, eye.z);
  camera->SetViewUp(0, 0, 1);
  camera->OrthogonalizeViewUp();
  camera->SetViewAngle(20.0 + 30.0 * u(gen));
}
} // namespace

int TestChunkedPolyDataMapperEngine(int, char*[])
{
  const std::string path = st::DataFile("engine-glb");
  if (path.empty())
  {
    std::cout << "SKIP: the 2CylinderEngine glTF (engine-glb) is not in the data cache "
              << st::DataDirectory() << "; run scripts/fetch-data.sh\n";
    return 77;
  }
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  std::string error;
  vtkSmartPointer<vtkPolyData> mesh = st::LoadModel(path, &error);
  if (!mesh)
  {
    std::cout << "FAIL cannot read " << path << ": " << error << "\n";
    return EXIT_FAILURE;
  }
  std::vector<unsigned int> vtkIndices;
  vtkOpenGLIndexBufferObject::AppendTriangleIndexBuffer(
    vtkIndices, mesh->GetPolys(), mesh->GetPoints(), 0, nullptr, nullptr);
  const auto vtkTriangles = static_cast<vtkIdType>(vtkIndices.size() / 3);
  std::cout << "2CylinderEngine: " << mesh->GetNumberOfPolys() << " polygons, "
            << mesh->GetNumberOfStrips() << " strips; VTK's index buffer keeps " << vtkTriangles
            << " triangles of the polygons\n";
  const char* idName = "InputCellId";
  vtkSmartPointer<vtkPolyData> idMesh = chunked_testing::TrianglesWithInputIds(mesh, idName);

  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(400, 300);
  vtkSmartPointer<vtkRenderWindow> idWindow = st::MakeRenderWindow(400, 300);
  vtkNew<vtkChunkedPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  mapper->SetChunkSize(512);
  mapper->ScalarVisibilityOff(); // part colours may be translucent; culling is the subject
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  window->AddRenderer(renderer);
  double bounds[6];
  mesh->GetBounds(bounds);
  vtkCamera* camera = renderer->GetActiveCamera();
  auto render = [&]()
  {
    renderer->ResetCameraClippingRange(bounds);
    return st::CaptureImage(window);
  };

  std::mt19937_64 gen(2024);
  const int cameras = 24;
  std::size_t skipped = 0, missing = 0, partial = 0, mismatches = 0, visibleSum = 0;
  for (int c = 0; c < cameras; ++c)
  {
    RandomCamera(camera, gen, bounds);
    vtkSmartPointer<vtkImageData> image = render();
    skipped += mapper->GetCullingSkipped() ? 1 : 0;
    partial += mapper->GetNumberOfTrianglesDrawn() < mapper->GetNumberOfTriangles() ? 1 : 0;
    std::vector<vtkIdType> drawnCells;
    mapper->GetDrawnCellIds(drawnCells);
    const std::vector<std::uint32_t> drawn(drawnCells.begin(), drawnCells.end());
    const std::vector<std::uint32_t> visible =
      st::VisibleSet(st::RenderVisibleIds(idWindow, idMesh, camera, idName));
    visibleSum += visible.size();
    const st::CullingCheck check = st::CullingIsConservative(visible, drawn);
    missing += check.missing.size();
    if (!check.conservative)
    {
      std::cout << "camera " << c << ": " << check.Summary() << "\n";
    }
    if (c % 4 == 0)
    {
      mapper->SetFrustumCulling(false);
      vtkSmartPointer<vtkImageData> reference = render();
      mapper->SetFrustumCulling(true);
      mismatches += st::ImagesIdentical(reference, image) ? 0 : 1;
    }
    std::cout << "camera " << c << ": drew " << mapper->GetNumberOfTrianglesDrawn() << " of "
              << mapper->GetNumberOfTriangles() << " triangles, " << visible.size()
              << " cells visible\n";
  }
  // A close-up: the eye a tenth of the diagonal from the centre, looking at it.
  const glm::dvec3 lo(bounds[0], bounds[2], bounds[4]), hi(bounds[1], bounds[3], bounds[5]);
  const glm::dvec3 center = 0.5 * (lo + hi);
  const glm::dvec3 eye = center + 0.1 * glm::length(hi - lo) * glm::dvec3(0.6, -0.64, 0.48);
  camera->SetFocalPoint(center.x, center.y, center.z);
  camera->SetPosition(eye.x, eye.y, eye.z);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(30);
  render();
  const vtkIdType closeDrawn = mapper->GetNumberOfTrianglesDrawn();
  std::cout << "close-up: drew " << closeDrawn << " of " << mapper->GetNumberOfTriangles()
            << " triangles in " << mapper->GetNumberOfDrawCalls() << " draw calls\n";

  if (mesh->GetNumberOfStrips() == 0)
  {
    ok &= Check(mapper->GetNumberOfTriangles() == vtkTriangles,
      "(a) triangle list: as many triangles as VTK's index buffer (" +
        std::to_string(mapper->GetNumberOfTriangles()) + ")");
  }
  ok &= Check(skipped == 0, "(a) culling never skipped (" + std::to_string(skipped) + ")");
  ok &= Check(missing == 0 && visibleSum > 0,
    "(b) 0 false negatives against the ID-buffer EVS (" + std::to_string(missing) + " of " +
      std::to_string(visibleSum) + " visible cells)");
  ok &= Check(mismatches == 0, "(b) culled images identical to unculled ones");
  ok &= Check(partial > 0,
    "(b) random views drew part of the mesh (" + std::to_string(partial) + " of " +
      std::to_string(cameras) + ")");
  ok &= Check(!mapper->GetCullingSkipped() && closeDrawn < mapper->GetNumberOfTriangles(),
    "(c) the close-up draws fewer triangles than the mesh");
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}
