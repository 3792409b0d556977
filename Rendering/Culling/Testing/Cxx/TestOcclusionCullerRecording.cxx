// Occlusion recordings from VTK. vtkOcclusionCuller::SetOcclusionRecordFile: each Render() adds
// one cull to the file, whose draws are what the culler rasterized that frame (as many triangles
// as it reports), and replaying a cull into a buffer gives one behind which every prop culled by
// occlusion that frame is hidden. vtkChunkedPolyDataMapper::SetOcclusionRecordFile: one cull per
// render of the mesh, its chunks' triangles. Clearing the name stops recording; a file that
// cannot be written is an error, and culling goes on unrecorded.
#include "vtkChunkedPolyDataMapper.h"
#include "vtkOcclusionCuller.h"

#include "scenevis/OcclusionBuffer.h"
#include "scenevis/OcclusionRecording.h"
#include "scenevis/testing/Expect.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkAppendPolyData.h>
#include <vtkCamera.h>
#include <vtkCubeSource.h>
#include <vtkCullerCollection.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTriangleFilter.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace
{
namespace so = scenevis::occlusion;
namespace st = scenevis::testing;

vtkSmartPointer<vtkActor> Box(double x, double y, double z, double sx, double sy, double sz)
{
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(x, y, z);
  cube->SetXLength(sx);
  cube->SetYLength(sy);
  cube->SetZLength(sz);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(triangles->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

bool ReadRecording(const std::string& path, std::vector<so::RecordedCull>& culls)
{
  std::ifstream in(path, std::ios::binary);
  std::string error;
  if (!so::readOcclusionRecording(in, culls, error))
  {
    std::cerr << path << ": " << error << std::endl;
    return false;
  }
  return true;
}

/// Triangles in all draws of a recorded cull.
std::size_t RecordedTriangles(const so::RecordedCull& cull)
{
  std::size_t n = 0;
  for (const so::RecordedDraw& d : cull.draws)
  {
    n += d.indices.size() / 3;
  }
  return n;
}

/// The same wall and boxes as one mesh under a vtkChunkedPolyDataMapper with occlusion culling.
void TestChunkedMapper(vtkRenderWindow* window, const std::vector<vtkSmartPointer<vtkActor>>& parts)
{
  const std::string path = "TestOcclusionCullerRecording-chunked.rec";
  std::remove(path.c_str());
  vtkNew<vtkAppendPolyData> append;
  for (const auto& part : parts)
  {
    part->GetMapper()->Update();
    append->AddInputData(vtkPolyData::SafeDownCast(part->GetMapper()->GetInputDataObject(0, 0)));
  }
  append->Update();
  vtkNew<vtkChunkedPolyDataMapper> mapper;
  mapper->SetInputConnection(append->GetOutputPort());
  mapper->SetChunkSize(12);
  mapper->OcclusionCullingOn();
  mapper->SetOcclusionRecordFile(path.c_str());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> ren;
  ren->AddActor(actor);
  ren->GetActiveCamera()->SetPosition(0, 0, 10);
  ren->GetActiveCamera()->SetFocalPoint(0, 0, -3);
  ren->ResetCameraClippingRange();
  window->AddRenderer(ren);
  window->Render();
  window->Render();
  SCENEVIS_EXPECT(mapper->GetNumberOfChunksCulledByOcclusion() > 0);
  std::vector<so::RecordedCull> culls;
  SCENEVIS_EXPECT(ReadRecording(path, culls));
  SCENEVIS_EXPECT(culls.size() == 2);
  for (const so::RecordedCull& cull : culls)
  {
    SCENEVIS_EXPECT(RecordedTriangles(cull) > 0);
    so::MaskedDepthBuffer buffer;
    so::prepareReplay(buffer, cull);
    so::replayDraws(buffer, cull);
    SCENEVIS_EXPECT(buffer.stats().trianglesDrawn > 0);
  }
  mapper->SetOcclusionRecordFile("no-such-directory/y.rec");
  window->Render();
  SCENEVIS_EXPECT(std::string(mapper->GetOcclusionRecordFile()).empty());
  SCENEVIS_EXPECT(mapper->GetNumberOfChunksCulledByOcclusion() > 0);
  window->RemoveRenderer(ren);
  std::remove(path.c_str());
}

/// Whether the world-space box of @p actor is hidden behind @p buffer.
bool Hidden(so::MaskedDepthBuffer& buffer, vtkActor* actor)
{
  const double* b = actor->GetBounds();
  return buffer.boxOccluded({ b[0], b[2], b[4] }, { b[1], b[3], b[5] });
}
} // namespace

int TestOcclusionCullerRecording(int, char*[])
{
  // The expected error is judged through the output window; loguru's copy on stderr would match
  // the test's failure pattern.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  st::StrictVtkOutput vtkOutput;
  vtkOutput.ExpectError("cannot write the occlusion recording no-such-directory/x.rec");
  vtkOutput.ExpectError("cannot write the occlusion recording no-such-directory/y.rec");
  const std::string path = "TestOcclusionCullerRecording.rec";
  std::remove(path.c_str());

  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(160, 120);
  vtkNew<vtkRenderer> ren;
  window->AddRenderer(ren);
  ren->GetCullers()->RemoveAllItems();
  vtkNew<vtkOcclusionCuller> culler;
  ren->AddCuller(culler);
  // A wall in front of a row of small boxes, and one box beside the wall (visible; outside the
  // chunked mapper's narrower view).
  std::vector<vtkSmartPointer<vtkActor>> hidden;
  ren->AddActor(Box(0, 0, 0, 6, 4, 0.2));
  for (int i = 0; i < 5; ++i)
  {
    // Far behind the wall: the chunk tree's first split (along depth) puts them in chunks of
    // their own.
    hidden.push_back(Box(-2 + i, 0, -20, 0.5, 0.5, 0.5));
    ren->AddActor(hidden.back());
  }
  vtkSmartPointer<vtkActor> beside = Box(5, 0, -3, 0.5, 0.5, 0.5);
  ren->AddActor(beside);
  vtkCamera* camera = ren->GetActiveCamera();
  camera->SetPosition(0, 0, 10);
  camera->SetFocalPoint(0, 0, -3);
  camera->SetViewAngle(50);

  culler->SetOcclusionRecordFile(path.c_str());
  SCENEVIS_EXPECT(path == culler->GetOcclusionRecordFile());
  std::vector<vtkIdType> triangles, culled;
  for (int frame = 0; frame < 3; ++frame)
  {
    camera->Azimuth(frame == 0 ? 0.0 : 2.0);
    ren->ResetCameraClippingRange();
    window->Render();
    triangles.push_back(culler->GetNumberOfOccluderTriangles());
    culled.push_back(culler->GetNumberOfPropsCulledByOcclusion());
  }
  std::vector<so::RecordedCull> culls;
  SCENEVIS_EXPECT(ReadRecording(path, culls));
  SCENEVIS_EXPECT(culls.size() == 3);
  for (std::size_t c = 0; c < culls.size() && c < triangles.size(); ++c)
  {
    st::ExpectContext() = "cull " + std::to_string(c);
    const int* size = ren->GetSize();
    SCENEVIS_EXPECT(culls[c].width == size[0] && culls[c].height == size[1]);
    const std::size_t recorded = RecordedTriangles(culls[c]);
    SCENEVIS_EXPECT(recorded == static_cast<std::size_t>(triangles[c]));
    SCENEVIS_EXPECT(culled[c] == 5); // the row behind the wall
    so::MaskedDepthBuffer buffer;
    so::prepareReplay(buffer, culls[c]);
    so::replayDraws(buffer, culls[c]);
    SCENEVIS_EXPECT(buffer.stats().trianglesIn == recorded);
    for (const auto& box : hidden)
    {
      SCENEVIS_EXPECT(Hidden(buffer, box));
    }
    SCENEVIS_EXPECT(!Hidden(buffer, beside));
  }
  st::ExpectContext().clear();

  // "" stops: the file keeps the three culls.
  culler->SetOcclusionRecordFile("");
  window->Render();
  SCENEVIS_EXPECT(ReadRecording(path, culls) && culls.size() == 3);
  culler->SetOcclusionRecordFile(nullptr);
  SCENEVIS_EXPECT(std::string(culler->GetOcclusionRecordFile()).empty());

  // A file that cannot be written: an error, and culling goes on.
  culler->SetOcclusionRecordFile("no-such-directory/x.rec");
  window->Render();
  SCENEVIS_EXPECT(std::string(culler->GetOcclusionRecordFile()).empty());
  SCENEVIS_EXPECT(culler->GetNumberOfPropsCulledByOcclusion() == 5);
  std::remove(path.c_str());

  std::vector<vtkSmartPointer<vtkActor>> parts = { Box(0, 0, 0, 6, 4, 0.2), beside };
  parts.insert(parts.end(), hidden.begin(), hidden.end());
  window->RemoveRenderer(ren);
  TestChunkedMapper(window, parts);
  return vtkOutput.ExitCode(st::ExpectFailures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE);
}
