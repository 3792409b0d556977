// Tests of the ID-buffer harness: they must be able to fail.
#include "scenevis/testing/GTestSupport.h"
#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/Scenes.h"

#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPlaneSource.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkSphereSource.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <numeric>
#include <stdexcept>

using namespace scenevis::testing;

namespace
{
constexpr int kSize = 64;

/// Camera on +z looking at the origin (quads at larger z are nearer).
vtkSmartPointer<vtkCamera> FrontCamera()
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetPosition(0, 0, 10);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  return camera;
}

/// Cell 0: far quad (z=0), cell 1: near quad (z=1), overlapping in the centre.
vtkSmartPointer<vtkPolyData> FarThenNear()
{
  return AppendPolygons(MakeQuad(-1, -1, 0.5, 0.5, 0.0), MakeQuad(-0.5, -0.5, 1, 1, 1.0));
}

class IdBuffer : public StrictVtkTest
{
protected:
  void SetUp() override { this->Window = MakeRenderWindow(Backend::OSMesa, kSize, kSize); }

  void SaveForInspection(const IdImage& image, const std::string& name)
  {
    WritePng(IdImageToColor(image),
      (std::filesystem::path(TemporaryDirectory()) / ("harness-idbuffer-" + name + ".png"))
        .string());
  }

  vtkSmartPointer<vtkRenderWindow> Window;
};
} // namespace

TEST_F(IdBuffer, ZBufferShowsTheNearQuadInTheOverlap)
{
  auto quads = FarThenNear();
  const IdImage z = RenderVisibleIds(this->Window, quads, FrontCamera());
  ASSERT_EQ(z.width, kSize);
  ASSERT_EQ(z.ids.size(), size_t(kSize * kSize));
  EXPECT_EQ(z.At(kSize / 2, kSize / 2), 1u);           // overlap: near quad
  EXPECT_EQ(z.At(kSize / 2 - 12, kSize / 2 - 12), 0u); // far quad only
  EXPECT_EQ(z.At(1, kSize - 2), kNoId);                // top-left corner: background
  EXPECT_EQ(VisibleSet(z), (std::vector<std::uint32_t>{ 0, 1 }));
}

TEST_F(IdBuffer, FarToNearPainterImageEqualsZBuffer)
{
  auto quads = FarThenNear();
  const IdImage z = RenderVisibleIds(this->Window, quads, FrontCamera());
  const IdImage painter = RenderPainterIds(this->Window, quads, FrontCamera());
  const OrderComparison result = OrderMatchesDepth(painter, z);
  EXPECT_TRUE(result.matches) << result.Summary();
  EXPECT_GT(result.comparedPixels, size_t(kSize * kSize / 2));
}

TEST_F(IdBuffer, NearToFarPainterImageDiffers)
{
  auto quads = FarThenNear();
  const IdImage z = RenderVisibleIds(this->Window, quads, FrontCamera());
  // Draw the near quad first: the far quad then overwrites the overlap.
  auto nearFirst = ReorderCells(quads, { 1, 0 });
  const IdImage painter =
    RenderPainterIds(this->Window, nearFirst, FrontCamera(), "scenevis_original_id");
  EXPECT_EQ(painter.At(kSize / 2, kSize / 2), 0u) << "ids must be the ORIGINAL ids";
  const OrderComparison result = OrderMatchesDepth(painter, z);
  EXPECT_FALSE(result.matches) << result.Summary();
  // The overlap is a quarter of each quad: roughly (0.25 of the 2.5-wide view)^2 of the pixels.
  EXPECT_GT(result.mismatchedPixels, size_t(100)) << result.Summary();
  SaveForInspection(z, "zbuffer");
  SaveForInspection(painter, "near-to-far");
  // Depth-tested, the cell order does not matter.
  const IdImage zReordered =
    RenderVisibleIds(this->Window, nearFirst, FrontCamera(), "scenevis_original_id");
  EXPECT_EQ(zReordered.ids, z.ids);
}

TEST_F(IdBuffer, OccludedQuadIsNotInTheVisibleSet)
{
  // Cell 0: small quad far behind; cell 1: big quad in front covering it completely.
  auto scene = AppendPolygons(MakeQuad(-0.3, -0.3, 0.3, 0.3, -1.0), MakeQuad(-1, -1, 1, 1, 0.0));
  const IdImage evs = RenderVisibleIds(this->Window, scene, FrontCamera());
  EXPECT_EQ(VisibleSet(evs), (std::vector<std::uint32_t>{ 1 }));
  // A culler that drew only the big quad is conservative; one that drew only the hidden one not.
  EXPECT_TRUE(CullingIsConservative(evs, { 1 }).conservative);
  const CullingCheck bad = CullingIsConservative(evs, { 0 });
  EXPECT_FALSE(bad.conservative) << bad.Summary();
  EXPECT_EQ(bad.missing, (std::vector<std::uint32_t>{ 1 }));
  // Without the depth test the hidden quad drawn last shows through.
  auto hiddenLast = ReorderCells(scene, { 1, 0 });
  const IdImage painter =
    RenderPainterIds(this->Window, hiddenLast, FrontCamera(), "scenevis_original_id");
  EXPECT_EQ(painter.At(kSize / 2, kSize / 2), 0u);
  EXPECT_FALSE(OrderMatchesDepth(painter, evs).matches);
}

TEST_F(IdBuffer, IdsUseAllThreeBytesExactly)
{
  // 32x32 = 1024 cells with original ids up to ~ 1024 * 97 + 70000 > 2^16 (uses the R byte).
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-1, -1, 0);
  plane->SetPoint1(1, -1, 0);
  plane->SetPoint2(-1, 1, 0);
  plane->SetResolution(32, 32);
  plane->Update();
  auto grid = vtkSmartPointer<vtkPolyData>::New();
  grid->DeepCopy(plane->GetOutput());
  vtkNew<vtkIntArray> original;
  original->SetName("original");
  std::vector<std::uint32_t> expected;
  for (vtkIdType cell = 0; cell < grid->GetNumberOfCells(); ++cell)
  {
    const int id = static_cast<int>(cell * 97 + 70000);
    original->InsertNextValue(id);
    expected.push_back(static_cast<std::uint32_t>(id));
  }
  grid->GetCellData()->AddArray(original);
  auto window = MakeRenderWindow(Backend::OSMesa, 256, 256);
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetPosition(0, 0, 1);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetParallelProjection(true);
  camera->SetParallelScale(1.0);
  const IdImage ids = RenderVisibleIds(window, grid, camera, "original");
  EXPECT_EQ(VisibleSet(ids), expected);
  // Pixel (x, y) of a 256x256 view of a 32x32 grid lies in cell (y/8)*32 + x/8.
  for (int y = 4; y < 256; y += 8)
  {
    for (int x = 4; x < 256; x += 8)
    {
      ASSERT_EQ(ids.At(x, y), static_cast<std::uint32_t>(((y / 8) * 32 + x / 8) * 97 + 70000))
        << "at " << x << "," << y;
    }
  }
}

TEST_F(IdBuffer, SpheresAreConsistent)
{
  // Closed convex surfaces: a far-to-near sort of the spheres (by centre) must match the z-buffer
  // except where spheres interpenetrate; here they do not overlap at all.
  vtkNew<vtkSphereSource> a;
  a->SetCenter(-0.6, 0, 0);
  a->SetRadius(0.5);
  vtkNew<vtkSphereSource> b;
  b->SetCenter(0.6, 0, 1);
  b->SetRadius(0.5);
  a->Update();
  b->Update();
  auto both = AppendPolygons(a->GetOutput(), b->GetOutput());
  const IdImage z = RenderVisibleIds(this->Window, both, FrontCamera());
  EXPECT_GT(VisibleSet(z).size(), size_t(20));
  EXPECT_LT(VisibleSet(z).size(), size_t(both->GetNumberOfCells()));
}

TEST_F(IdBuffer, RejectsNonPolygonCells)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->Update();
  auto withLines = vtkSmartPointer<vtkPolyData>::New();
  withLines->DeepCopy(sphere->GetOutput());
  withLines->SetLines(withLines->GetPolys());
  EXPECT_THROW(RenderVisibleIds(this->Window, withLines, nullptr), std::invalid_argument);
  auto polys = vtkSmartPointer<vtkPolyData>::New();
  polys->DeepCopy(sphere->GetOutput());
  EXPECT_THROW(
    RenderVisibleIds(this->Window, polys, nullptr, "no-such-array"), std::invalid_argument);
}

TEST(IdBufferPure, EdgeMaskMarksPixelsNextToAnotherId)
{
  IdImage image;
  image.width = 5;
  image.height = 4;
  image.ids.assign(20, 7);
  image.ids[2 * 5 + 2] = 9; // (2, 2)
  const auto mask = ComputeEdgeMask(image);
  int edges = 0;
  for (auto m : mask)
  {
    edges += m;
  }
  EXPECT_EQ(edges, 9); // the 3x3 block around (2, 2), clipped by nothing
  EXPECT_EQ(mask[0], 0);
  EXPECT_EQ(mask[1 * 5 + 1], 1);
  EXPECT_EQ(mask[3 * 5 + 3], 1);
  EXPECT_EQ(mask[3 * 5 + 4], 0);
}

TEST(IdBufferPure, OrderComparisonIgnoresMaskedPixels)
{
  IdImage z;
  z.width = 2;
  z.height = 1;
  z.ids = { 1, 2 };
  IdImage painter = z;
  painter.ids[1] = 1;
  EXPECT_FALSE(OrderMatchesDepth(painter, z, { 0, 0 }).matches);
  EXPECT_EQ(OrderMatchesDepth(painter, z, { 0, 0 }).mismatchedPixels, 1u);
  EXPECT_TRUE(OrderMatchesDepth(painter, z, { 0, 1 }).matches);
}
