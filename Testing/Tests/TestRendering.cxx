// Tests of the headless render windows, the self-check, ordered alpha blending and black-render
// detection.
#include "scenevis/testing/GTestSupport.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

using namespace scenevis::testing;

namespace
{
std::array<int, 3> PixelAt(vtkImageData* image, int x, int y)
{
  auto* p = static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0));
  return { p[0], p[1], p[2] };
}

/// Two translucent (opacity 0.5), unlit quads in ONE polydata: red at z=0 (far), green at z=1
/// (near), overlapping in the centre; @p farFirst selects the cell order.
vtkSmartPointer<vtkRenderer> MakeTwoTranslucentQuads(bool farFirst, Translucency mode)
{
  auto red = MakeQuad(-1, -1, 0.5, 0.5, 0.0);
  auto green = MakeQuad(-0.5, -0.5, 1, 1, 1.0);
  auto both = farFirst ? AppendPolygons(red, green) : AppendPolygons(green, red);
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  const unsigned char r[3] = { 255, 0, 0 };
  const unsigned char g[3] = { 0, 255, 0 };
  colours->InsertNextTypedTuple(farFirst ? r : g);
  colours->InsertNextTypedTuple(farFirst ? g : r);
  both->GetCellData()->SetScalars(colours);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(both);
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetOpacity(0.5);
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->AddActor(actor);
  renderer->SetBackground(0, 0, 0);
  if (mode == Translucency::OrderedAlpha)
  {
    EnableOrderedAlphaBlending(renderer);
  }
  renderer->GetActiveCamera()->SetPosition(0, 0, 10);
  renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  renderer->ResetCameraClippingRange();
  return renderer;
}

vtkSmartPointer<vtkImageData> Render(vtkRenderer* renderer, int size = 64)
{
  auto window = MakeRenderWindow(Backend::OSMesa, size, size);
  window->AddRenderer(renderer);
  auto image = CaptureImage(window);
  window->RemoveRenderer(renderer);
  return image;
}
} // namespace

class RenderWindow : public StrictVtkTest
{
};

TEST_F(RenderWindow, OSMesaWindowsSequentiallyInOneProcess)
{
  for (int i = 0; i < 4; ++i)
  {
    const int w = 32 + 16 * i;
    const int h = 24 + 8 * i;
    vtkSmartPointer<vtkRenderWindow> window = MakeRenderWindow(Backend::OSMesa, w, h);
    ASSERT_TRUE(window);
    EXPECT_EQ(window->GetMultiSamples(), 0);
    EXPECT_NE(DescribeContext(window).find("llvmpipe"), std::string::npos)
      << DescribeContext(window);
    auto image = CaptureImage(window);
    int dims[3];
    image->GetDimensions(dims);
    EXPECT_EQ(dims[0], w);
    EXPECT_EQ(dims[1], h);
  }
}

TEST_F(RenderWindow, SelfCheckStillPassesAfterResize)
{
  vtkSmartPointer<vtkRenderWindow> window = MakeRenderWindow(Backend::OSMesa, 40, 30);
  window->SetSize(72, 50);
  EXPECT_EQ(CheckRenderingWorks(window), "");
  auto image = CaptureImage(window);
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 72);
  EXPECT_EQ(dims[1], 50);
}

TEST_F(RenderWindow, SelfCheckLeavesTheWindowsRenderersInPlace)
{
  vtkSmartPointer<vtkRenderWindow> window = MakeRenderWindow(Backend::OSMesa, 32, 32);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 1);
  window->AddRenderer(renderer);
  EXPECT_EQ(CheckRenderingWorks(window), "");
  EXPECT_EQ(window->GetRenderers()->GetNumberOfItems(), 1);
  auto image = CaptureImage(window);
  const auto p = PixelAt(image, 16, 16);
  EXPECT_EQ(p[0], 0);
  EXPECT_EQ(p[2], 255);
}

TEST_F(RenderWindow, BackendFromEnvironment)
{
  unsetenv("SCENEVIS_BACKEND");
  EXPECT_EQ(DefaultBackend(), Backend::OSMesa);
  setenv("SCENEVIS_BACKEND", "X11", 1);
  EXPECT_EQ(DefaultBackend(), Backend::X11);
  setenv("SCENEVIS_BACKEND", "osmesa", 1);
  EXPECT_EQ(DefaultBackend(), Backend::OSMesa);
  setenv("SCENEVIS_BACKEND", "opengl-please", 1);
  EXPECT_THROW(DefaultBackend(), std::runtime_error);
  unsetenv("SCENEVIS_BACKEND");
}

TEST_F(RenderWindow, X11WindowUnderXvfb)
{
  std::string why;
  if (!BackendAvailable(Backend::X11, &why))
  {
    GTEST_SKIP() << why;
  }
  vtkSmartPointer<vtkRenderWindow> window = MakeRenderWindow(Backend::X11, 48, 32);
  EXPECT_EQ(window->GetMultiSamples(), 0);
  EXPECT_EQ(CheckRenderingWorks(window), "");
}

TEST_F(RenderWindow, OrderedAlphaBlendingFollowsPrimitiveOrder)
{
  auto farToNear = Render(MakeTwoTranslucentQuads(true, Translucency::OrderedAlpha));
  auto nearToFar = Render(MakeTwoTranslucentQuads(false, Translucency::OrderedAlpha));
  // Far-to-near "over" compositing: green(0.5) over red(0.5) over black = (64, 128, 0).
  const auto a = PixelAt(farToNear, 32, 32);
  EXPECT_NEAR(a[0], 64, 2);
  EXPECT_NEAR(a[1], 128, 2);
  EXPECT_EQ(a[2], 0);
  // Near-to-far draws red over green: the order shows.
  const auto b = PixelAt(nearToFar, 32, 32);
  EXPECT_NEAR(b[0], 128, 2);
  EXPECT_NEAR(b[1], 64, 2);
  EXPECT_FALSE(ImagesIdentical(farToNear, nearToFar));
}

TEST_F(RenderWindow, VtkDefaultTranslucencyIgnoresPrimitiveOrder)
{
  // The measured fact that makes EnableOrderedAlphaBlending necessary.
  auto farToNear = Render(MakeTwoTranslucentQuads(true, Translucency::VtkDefault));
  auto nearToFar = Render(MakeTwoTranslucentQuads(false, Translucency::VtkDefault));
  std::string why;
  EXPECT_TRUE(ImagesIdentical(farToNear, nearToFar, &why)) << why;
}

TEST_F(RenderWindow, BlackRenderFailsTheBaselineComparisonLoudly)
{
  const std::filesystem::path root =
    std::filesystem::path(TemporaryDirectory()) / "harness-blackrender";
  std::filesystem::remove_all(root);
  const std::string temporary = TemporaryDirectory();
  setenv("SCENEVIS_BASELINE_DIR", (root / "baseline").c_str(), 1);
  setenv("SCENEVIS_TEMPORARY_DIR", (root / "temporary").c_str(), 1);

  SphereGridOptions options;
  options.count = 2;
  options.opacity = 1.0;
  auto renderer = MakeSphereGridRenderer(options);
  auto window = MakeRenderWindow(Backend::OSMesa, 64, 64);
  window->AddRenderer(renderer);
  auto good = CaptureImage(window);
  ASSERT_TRUE(WritePng(good, (root / "baseline" / "Spheres.png").string()));
  EXPECT_EQ(CompareWithBaseline(window, "Spheres.png"), "");

  // Turn the camera away from the scene: nothing in the view, an all-black image.
  vtkCamera* camera = renderer->GetActiveCamera();
  double focal[3];
  double position[3];
  camera->GetFocalPoint(focal);
  camera->GetPosition(position);
  camera->SetFocalPoint(
    2 * position[0] - focal[0], 2 * position[1] - focal[1], 2 * position[2] - focal[2]);
  ImageThresholds lenient; // even lenient thresholds must not let a black image pass
  lenient.maxMeanAbsError = 255;
  lenient.maxCoveredBadFraction = 1.0;
  const std::string message = CompareWithBaseline(window, "Spheres.png", lenient);
  EXPECT_NE(message.find("all background"), std::string::npos) << message;
  EXPECT_TRUE(std::filesystem::exists(root / "temporary" / "Spheres.actual.png"));
  EXPECT_TRUE(std::filesystem::exists(root / "temporary" / "Spheres.diff.png"));
  unsetenv("SCENEVIS_BASELINE_DIR");
  unsetenv("SCENEVIS_TEMPORARY_DIR");
}
