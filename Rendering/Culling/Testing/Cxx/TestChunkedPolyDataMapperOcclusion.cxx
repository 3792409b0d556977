// vtkChunkedPolyDataMapper with OcclusionCulling on: one opaque CAD mesh (the demo assembly,
// 2,000 parts as ONE polydata) from random cameras inside, between and outside the parts, and
// a grazing row view, against
//  - the exact visible set of the ID buffer (same camera and clipping range): every visible cell
//    is among the cells drawn (0 false negatives);
//  - the same mapper with only frustum culling: the images are identical pixel for pixel;
// and occlusion culls chunks frustum culling keeps (a mapper that culls nothing would pass the
// first two). Translucent actors never cull by occlusion.
#include "vtkChunkedPolyDataMapper.h"

#include "vtkDemoSceneSource.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cstdlib>
#include <cstring>
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

bool SameImage(vtkImageData* a, vtkImageData* b)
{
  return a->GetNumberOfPoints() == b->GetNumberOfPoints() &&
    std::memcmp(a->GetScalarPointer(), b->GetScalarPointer(),
      static_cast<std::size_t>(a->GetNumberOfPoints()) *
        static_cast<std::size_t>(a->GetNumberOfScalarComponents())) == 0;
}
} // namespace

int TestChunkedPolyDataMapperOcclusion(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  vtkNew<vtkDemoSceneSource> source;
  source->SetScene(vtkDemoSceneSource::SCENE_CAD_ASSEMBLY);
  source->SetPartCount(2000);
  source->SetTriangleCount(2000 * 60);
  source->Update();
  vtkNew<vtkPolyData> cad;
  cad->ShallowCopy(source->GetOutput());
  cad->GetCellData()->SetScalars(nullptr); // one opaque colour: occlusion needs an opaque surface
  const vtkIdType numCells = cad->GetNumberOfCells();
  vtkNew<vtkPolyData> idMesh;
  idMesh->SetPoints(cad->GetPoints());
  idMesh->SetPolys(cad->GetPolys());
  {
    vtkNew<vtkIdTypeArray> ids;
    ids->SetName("CellIndex");
    ids->SetNumberOfTuples(numCells);
    for (vtkIdType i = 0; i < numCells; ++i)
    {
      ids->SetValue(i, i);
    }
    idMesh->GetCellData()->AddArray(ids);
  }
  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(320, 240);
  vtkSmartPointer<vtkRenderWindow> idWindow = st::MakeRenderWindow(320, 240);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkChunkedPolyDataMapper> mapper;
  mapper->SetInputData(cad);
  mapper->SetChunkSize(256);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  vtkCamera* camera = renderer->GetActiveCamera();
  double b[6];
  cad->GetBounds(b);
  const double size[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };

  std::mt19937_64 gen(31);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t missing = 0, mismatches = 0, culledByOcclusion = 0, drawnOcclusion = 0,
              drawnFrustum = 0;
  const int cameras = 24;
  for (int c = 0; c < cameras; ++c)
  {
    const double focal[3] = { b[0] + u(gen) * size[0], b[2] + u(gen) * size[1],
      b[4] + 0.2 * u(gen) * size[2] };
    double eye[3];
    if (c % 3 == 0)
    {
      // Low over the board looking across it: rows of parts hide rows.
      eye[0] = b[0] + u(gen) * size[0];
      eye[1] = b[2] - 0.1 * size[1];
      eye[2] = b[4] + (0.05 + 0.2 * u(gen)) * size[2];
    }
    else
    {
      const double d = 0.05 + 0.8 * u(gen);
      eye[0] = focal[0] + (u(gen) - 0.5) * size[0] * d;
      eye[1] = focal[1] + (u(gen) - 0.5) * size[1] * d;
      eye[2] = focal[2] + (0.05 + u(gen)) * size[2];
    }
    camera->SetFocalPoint(focal);
    camera->SetPosition(eye);
    camera->SetViewUp(0, 0, 1);
    camera->OrthogonalizeViewUp();
    camera->SetViewAngle(30.0 + 40.0 * u(gen));
    camera->SetParallelProjection(c % 8 == 7);
    camera->SetParallelScale(0.3 * size[0]);
    renderer->ResetCameraClippingRange();

    mapper->OcclusionCullingOff();
    vtkSmartPointer<vtkImageData> reference = st::CaptureImage(window);
    drawnFrustum += static_cast<std::size_t>(mapper->GetNumberOfTrianglesDrawn());
    mapper->OcclusionCullingOn();
    vtkSmartPointer<vtkImageData> image = st::CaptureImage(window);
    drawnOcclusion += static_cast<std::size_t>(mapper->GetNumberOfTrianglesDrawn());
    culledByOcclusion += static_cast<std::size_t>(mapper->GetNumberOfChunksCulledByOcclusion());
    if (!SameImage(reference, image))
    {
      ++mismatches;
      std::cout << "camera " << c << ": the image with occlusion culling differs\n";
    }
    std::vector<vtkIdType> drawnCells;
    mapper->GetDrawnCellIds(drawnCells);
    st::IdRenderOptions options;
    options.originalIdArray = "CellIndex";
    options.cameraClippingRange = true;
    const st::IdImage evs = st::RenderIdBuffer(idWindow, idMesh, camera, options);
    const st::CullingCheck check = st::CullingIsConservative(
      evs, std::vector<std::uint32_t>(drawnCells.begin(), drawnCells.end()));
    missing += check.missing.size();
    if (!check.conservative)
    {
      std::cout << "camera " << c << ": " << check.Summary() << "\n";
    }
  }
  std::cout << cameras << " cameras: triangles drawn with frustum culling " << drawnFrustum
            << ", with occlusion " << drawnOcclusion << "; chunks culled by occlusion "
            << culledByOcclusion << "\n";
  ok &= Check(missing == 0, "0 false negatives (visible cells not drawn: " + std::to_string(missing) + ")");
  ok &= Check(mismatches == 0, "images with and without occlusion culling are identical");
  ok &= Check(culledByOcclusion > 0 && drawnOcclusion < drawnFrustum, "occlusion culls chunks");

  // A translucent actor: no occlusion between its chunks.
  actor->GetProperty()->SetOpacity(0.5);
  st::CaptureImage(window);
  ok &= Check(mapper->GetNumberOfChunksCulledByOcclusion() == 0,
    "a translucent actor culls nothing by occlusion");
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}
