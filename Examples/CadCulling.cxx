// Culling a large CAD assembly, offscreen:
//  1. many actors (one per part) with vtkOctreeCuller replacing VTK's vtkFrustumCoverageCuller;
//  2. one merged mesh drawn by vtkChunkedPolyDataMapper (spatial chunks, one set of GPU buffers).
// Each part flies the camera over the board, prints per-frame statistics and writes PNGs.
//
// Usage: CadCulling [output-directory] [--kicad[=TRIANGLES]]
//   output-directory: where the PNGs go (default: the current directory);
//   --kicad: instead of the embedded synthetic assembly, a real one: KiCad parts tiled onto boards
//     (scenevis::testing::MakeKiCadBoard, data cache key kicad-wrl-dir) of TRIANGLES triangles
//     (default 2,000,000); one actor per placed part, the actors of a part sharing its mapper.
//     Without the data it says so and exits 0.
#include "vtkChunkedPolyDataMapper.h"
#include "vtkDemoSceneSource.h"
#include "vtkOctreeCuller.h"

#include "scenevis/Scenes.h"
#include "scenevis/testing/KiCadBoard.h"
#include "scenevis/testing/RenderWindow.h"

#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCullerCollection.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
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
#include <cstdlib>
#include <iostream>
#include <map>
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

/// Shallow copy of @p mesh whose cell scalars are the RGB of its RGBA "Colors".
vtkSmartPointer<vtkPolyData> OpaqueCopy(vtkPolyData* mesh)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(mesh);
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(mesh->GetCellData()->GetScalars());
  if (!rgba || rgba->GetNumberOfComponents() != 4)
  {
    return copy;
  }
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(rgba->GetNumberOfTuples());
  for (vtkIdType i = 0; i < rgba->GetNumberOfTuples(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      rgb->SetValue(3 * i + k, rgba->GetValue(4 * i + k));
    }
  }
  copy->GetCellData()->SetScalars(rgb);
  return copy;
}

/// One actor per part of the embedded synthetic assembly (5000 parts, 300k triangles).
void AddEmbeddedActors(vtkRenderer* renderer)
{
  const scenevis::scenes::Scene scene = scenevis::scenes::cadAssembly(5000, 60, 7);
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
}

/// One actor per placed KiCad part; the instances of a part share one mapper (one set of GPU
/// buffers) and differ by their user matrix. Colours are the parts' own RGBA cell scalars.
void AddKiCadActors(vtkRenderer* renderer, const scenevis::testing::KiCadBoard& board)
{
  std::map<vtkPolyData*, vtkSmartPointer<vtkPolyDataMapper>> mappers;
  for (const scenevis::testing::KiCadInstance& inst : board.instances)
  {
    vtkSmartPointer<vtkPolyDataMapper>& mapper = mappers[inst.polys];
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
  }
}

double Milliseconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}
} // namespace

int main(int argc, char* argv[])
{
  std::string dir = ".";
  bool kicad = false;
  std::size_t kicadTriangles = 2000000;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg.rfind("--kicad", 0) == 0)
    {
      kicad = true;
      if (arg.size() > 8 && arg[7] == '=')
      {
        kicadTriangles = std::strtoull(arg.c_str() + 8, nullptr, 10);
      }
    }
    else
    {
      dir = arg;
    }
  }
  const int frames = 8;
  scenevis::testing::KiCadBoard board;
  if (kicad)
  {
    scenevis::testing::KiCadBoardOptions options;
    options.targetTriangles = kicadTriangles;
    const auto start = std::chrono::steady_clock::now();
    board = scenevis::testing::MakeKiCadBoard(options);
    if (board.Empty())
    {
      std::cout << "KiCad board skipped: " << board.error << "\n";
      return 0;
    }
    std::cout << "KiCad board: " << board.partFiles.size() << " part files read, "
              << board.instances.size() << " instances on " << board.boards << " boards, "
              << board.triangles << " triangles (" << Milliseconds(start) / 1000.0
              << " s to build)\n";
  }
  vtkSmartPointer<vtkRenderWindow> window = scenevis::testing::MakeRenderWindow(800, 600);

  // ---- 1. Many actors: one per part, culled by vtkOctreeCuller. ------------------------------
  {
    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(0.12, 0.13, 0.16);
    renderer->GetCullers()->RemoveAllItems();
    vtkNew<vtkOctreeCuller> culler; // UPDATE_ON_EVENTS: moved parts are noticed by themselves
    renderer->AddCuller(culler);
    window->AddRenderer(renderer);
    if (kicad)
    {
      AddKiCadActors(renderer, board);
    }
    else
    {
      AddEmbeddedActors(renderer);
    }
    double b[6];
    renderer->ComputeVisiblePropBounds(b);
    std::cout << "many actors: " << renderer->GetActors()->GetNumberOfItems() << " actors\n";
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
        WritePng(
          window, dir + (kicad ? "/kicad" : "/cad") + "-actors-" + std::to_string(f) + ".png");
      }
    }
    std::cout << "  hierarchy built " << culler->GetNumberOfRebuilds() << " time(s)\n";
    window->RemoveRenderer(renderer);
  }

  // ---- 2. One mesh: all parts merged (embedded: 20000 parts, ~1M triangles), drawn by
  // vtkChunkedPolyDataMapper. -------------------------------------------------------------------
  {
    vtkNew<vtkDemoSceneSource> source;
    source->SetScene(vtkDemoSceneSource::SCENE_CAD_ASSEMBLY);
    source->SetPartCount(20000);
    source->SetTriangleCount(1000000);
    source->SetSeed(7);
    vtkNew<vtkChunkedPolyDataMapper> mapper;
    if (kicad)
    {
      // One mesh is one actor: a single translucent LED would send all of it to the translucent
      // pass, so the merged form is drawn opaque (RGB of the part colours).
      mapper->SetInputData(OpaqueCopy(board.merged));
      mapper->SetScalarModeToUseCellData();
      mapper->SetColorModeToDirectScalars();
    }
    else
    {
      mapper->SetInputConnection(source->GetOutputPort());
      source->Update();
    }
    vtkPolyData* mesh = vtkPolyData::SafeDownCast(mapper->GetInputDataObject(0, 0));
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    // Closed synthetic parts: normal cones may cull chunks. KiCad parts are not all closed or
    // consistently oriented, so they are drawn two-sided.
    actor->GetProperty()->SetBackfaceCulling(!kicad);
    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(0.12, 0.13, 0.16);
    renderer->AddActor(actor);
    window->AddRenderer(renderer);
    double b[6];
    mesh->GetBounds(b);
    std::cout << "one mesh: " << mesh->GetNumberOfPolys() << " triangles\n";
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
        WritePng(window, dir + (kicad ? "/kicad" : "/cad") + "-mesh-" + std::to_string(f) + ".png");
      }
    }
    std::cout << "  partition built " << mapper->GetNumberOfPartitionBuilds() << " time(s) in "
              << mapper->GetLastPartitionTime() << " s; vertex buffers built "
              << mapper->GetNumberOfVertexBufferBuilds() << " time(s)\n";
    window->RemoveRenderer(renderer);
  }
  return 0;
}
