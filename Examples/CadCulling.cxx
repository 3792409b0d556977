// Culling a large CAD assembly, offscreen:
//  1. many actors (one per part) with vtkOctreeCuller replacing VTK's vtkFrustumCoverageCuller;
//  2. one merged mesh drawn by vtkChunkedPolyDataMapper (spatial chunks, one set of GPU buffers).
// Each part flies the camera over the board, prints per-frame statistics and writes PNGs.
//
// Usage: CadCulling [output-directory]   (default: the current directory)
#include "vtkChunkedPolyDataMapper.h"
#include "vtkDemoSceneSource.h"
#include "vtkOctreeCuller.h"

#include "scenevis/Scenes.h"
#include "scenevis/testing/RenderWindow.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCullerCollection.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace
{
void WritePng(vtkRenderWindow* window, const std::string& path)
{
  vtkSmartPointer<vtkImageData> image = scenevis::testing::CaptureImage(window);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
  std::cout << "  wrote " << path << "\n";
}

/// Fly-over: frame f of n looks down at a point moving diagonally over the board.
void FlyOver(vtkCamera* camera, const double* b, int f, int n)
{
  const double w = b[1] - b[0], h = b[3] - b[2];
  const double t = 0.15 + 0.7 * f / std::max(1, n - 1);
  const double fx = b[0] + t * w, fy = b[2] + t * h;
  camera->SetFocalPoint(fx, fy, b[4]);
  camera->SetPosition(fx - 0.1 * w, fy - 0.15 * h, b[4] + 0.2 * w);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(35);
}

double Milliseconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}
} // namespace

int main(int argc, char* argv[])
{
  const std::string dir = argc > 1 ? argv[1] : ".";
  const int frames = 8;
  vtkSmartPointer<vtkRenderWindow> window = scenevis::testing::MakeRenderWindow(800, 600);

  // ---- 1. Many actors: 5000 parts, one actor each, culled by vtkOctreeCuller. ----------------
  {
    const scenevis::scenes::Scene scene = scenevis::scenes::cadAssembly(5000, 60, 7);
    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(0.12, 0.13, 0.16);
    renderer->GetCullers()->RemoveAllItems();
    vtkNew<vtkOctreeCuller> culler; // UPDATE_ON_EVENTS: moved parts are noticed by themselves
    renderer->AddCuller(culler);
    window->AddRenderer(renderer);
    for (const auto& part : scene.parts)
    {
      vtkNew<vtkPoints> points;
      vtkNew<vtkCellArray> polys;
      std::vector<vtkIdType> cell;
      for (std::uint32_t i = part.firstPolygon; i < part.firstPolygon + part.polygonCount; ++i)
      {
        cell.clear();
        for (std::uint32_t k = 0; k < scene.mesh.polygonSize(i); ++k)
        {
          const auto& p = scene.mesh.points[scene.mesh.polygon(i)[k]];
          cell.push_back(points->InsertNextPoint(p.x, p.y, p.z));
        }
        polys->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
      }
      vtkNew<vtkPolyData> pd;
      pd->SetPoints(points);
      pd->SetPolys(polys);
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(pd);
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->GetProperty()->SetColor(part.colour.x, part.colour.y, part.colour.z);
      actor->GetProperty()->SetOpacity(part.opacity);
      renderer->AddActor(actor);
    }
    double b[6];
    renderer->ComputeVisiblePropBounds(b);
    std::cout << "many actors: " << scene.parts.size() << " actors, "
              << scenevis::scenes::triangleCount(scene.mesh) << " triangles\n";
    for (int f = 0; f < frames; ++f)
    {
      FlyOver(renderer->GetActiveCamera(), b, f, frames);
      renderer->ResetCameraClippingRange();
      const auto start = std::chrono::steady_clock::now();
      window->Render();
      const double ms = Milliseconds(start);
      std::printf("  frame %d: props drawn %lld, culled %lld (frustum %lld), nodes visited %lld, "
                  "triangles %lld, frame %.1f ms\n",
        f, static_cast<long long>(culler->GetNumberOfPropsDrawn()),
        static_cast<long long>(culler->GetNumberOfPropsCulled()),
        static_cast<long long>(culler->GetNumberOfPropsCulledByFrustum()),
        static_cast<long long>(culler->GetNumberOfNodesVisited()),
        static_cast<long long>(culler->GetNumberOfTrianglesDrawn()), ms);
      if (f == 0 || f == frames - 1)
      {
        WritePng(window, dir + "/cad-actors-" + std::to_string(f) + ".png");
      }
    }
    std::cout << "  hierarchy built " << culler->GetNumberOfRebuilds() << " time(s)\n";
    window->RemoveRenderer(renderer);
  }

  // ---- 2. One mesh: 20000 parts merged, ~1M triangles, vtkChunkedPolyDataMapper. ------------
  {
    vtkNew<vtkDemoSceneSource> source;
    source->SetScene(vtkDemoSceneSource::SCENE_CAD_ASSEMBLY);
    source->SetPartCount(20000);
    source->SetTriangleCount(1000000);
    source->SetSeed(7);
    vtkNew<vtkChunkedPolyDataMapper> mapper;
    mapper->SetInputConnection(source->GetOutputPort());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->BackfaceCullingOn(); // closed parts: normal cones may cull chunks
    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(0.12, 0.13, 0.16);
    renderer->AddActor(actor);
    window->AddRenderer(renderer);
    source->Update();
    double b[6];
    source->GetOutput()->GetBounds(b);
    std::cout << "one mesh: " << source->GetOutput()->GetNumberOfPolys() << " triangles\n";
    for (int f = 0; f < frames; ++f)
    {
      FlyOver(renderer->GetActiveCamera(), b, f, frames);
      renderer->ResetCameraClippingRange();
      const auto start = std::chrono::steady_clock::now();
      window->Render();
      const double ms = Milliseconds(start);
      std::printf("  frame %d: triangles drawn %lld of %lld, chunks %lld of %lld (normal cone "
                  "culled %lld) in %lld draw calls, cull %.0f us, frame %.1f ms\n",
        f, static_cast<long long>(mapper->GetNumberOfTrianglesDrawn()),
        static_cast<long long>(mapper->GetNumberOfTriangles()),
        static_cast<long long>(mapper->GetNumberOfChunksDrawn()),
        static_cast<long long>(mapper->GetNumberOfChunks()),
        static_cast<long long>(mapper->GetNumberOfChunksCulledByNormalCone()),
        static_cast<long long>(mapper->GetNumberOfDrawCalls()), 1e6 * mapper->GetLastCullTime(),
        ms);
      if (f == 0 || f == frames - 1)
      {
        WritePng(window, dir + "/cad-mesh-" + std::to_string(f) + ".png");
      }
    }
    std::cout << "  partition built " << mapper->GetNumberOfPartitionBuilds() << " time(s) in "
              << mapper->GetLastPartitionTime() << " s; vertex buffers built "
              << mapper->GetNumberOfVertexBufferBuilds() << " time(s)\n";
    window->RemoveRenderer(renderer);
  }
  return 0;
}
