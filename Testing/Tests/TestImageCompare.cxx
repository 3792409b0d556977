// Tests of the image comparison (synthetic images, no rendering).
#include "scenevis/testing/GTestSupport.h"
#include "scenevis/testing/ImageCompare.h"

#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

using namespace scenevis::testing;

namespace
{
vtkSmartPointer<vtkImageData> MakeImage(int w,
  int h,
  unsigned char r,
  unsigned char g,
  unsigned char b)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* p = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int i = 0; i < w * h; ++i)
  {
    p[3 * i] = r;
    p[3 * i + 1] = g;
    p[3 * i + 2] = b;
  }
  return image;
}

void SetPixel(vtkImageData* image, int x, int y, unsigned char r, unsigned char g, unsigned char b)
{
  auto* p = static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0));
  p[0] = r;
  p[1] = g;
  p[2] = b;
}

/// Point the harness's directories at a fresh folder for this test.
std::filesystem::path UseScratchDirectories(const std::string& name)
{
  const std::filesystem::path root =
    std::filesystem::path(TemporaryDirectory()) / ("harness-" + name);
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root / "baseline");
  setenv("SCENEVIS_BASELINE_DIR", (root / "baseline").c_str(), 1);
  setenv("SCENEVIS_TEMPORARY_DIR", (root / "temporary").c_str(), 1);
  return root;
}

void RestoreDirectories()
{
  unsetenv("SCENEVIS_BASELINE_DIR");
  unsetenv("SCENEVIS_TEMPORARY_DIR");
}
} // namespace

class ImageCompare : public StrictVtkTest
{
protected:
  void TearDown() override
  {
    RestoreDirectories();
    StrictVtkTest::TearDown();
  }
};

TEST_F(ImageCompare, IdenticalImagesHaveNoError)
{
  auto a = MakeImage(10, 10, 10, 20, 30);
  auto b = MakeImage(10, 10, 10, 20, 30);
  const ImageDifference d = CompareImages(a, b);
  ASSERT_TRUE(d.comparable) << d.problem;
  EXPECT_EQ(d.meanAbsError, 0.0);
  EXPECT_EQ(d.maxError, 0);
  EXPECT_EQ(d.coveredPixels, 100u);
  EXPECT_EQ(d.badCoveredPixels, 0u);
  EXPECT_TRUE(ImagesIdentical(a, b));
}

TEST_F(ImageCompare, MetricsAreComputedAsDocumented)
{
  // 10x10 black background; actual has 4 covered pixels, expected 2 of them (one slightly off).
  auto actual = MakeImage(10, 10, 0, 0, 0);
  auto expected = MakeImage(10, 10, 0, 0, 0);
  SetPixel(actual, 1, 1, 100, 100, 100);
  SetPixel(expected, 1, 1, 100, 100, 110); // diff 10: covered, not bad
  SetPixel(actual, 2, 2, 200, 0, 0);
  SetPixel(expected, 2, 2, 200, 0, 0); // identical covered
  SetPixel(actual, 3, 3, 50, 0, 0);    // diff 50 vs background: bad
  SetPixel(actual, 4, 4, 0, 17, 0);    // diff 17: bad
  const ImageDifference d = CompareImages(actual, expected);
  ASSERT_TRUE(d.comparable);
  EXPECT_EQ(d.coveredPixels, 4u);
  EXPECT_EQ(d.badCoveredPixels, 2u);
  EXPECT_DOUBLE_EQ(d.coveredBadFraction, 0.5);
  EXPECT_EQ(d.maxError, 50);
  EXPECT_DOUBLE_EQ(d.meanAbsError, (10.0 + 50.0 + 17.0) / 300.0);
  std::string why;
  EXPECT_FALSE(WithinThresholds(d, ImageThresholds(), &why));
  EXPECT_NE(why.find("bad covered fraction"), std::string::npos) << why;
}

TEST_F(ImageCompare, SizeMismatchIsNotComparable)
{
  const ImageDifference d = CompareImages(MakeImage(4, 4, 1, 1, 1), MakeImage(4, 5, 1, 1, 1));
  EXPECT_FALSE(d.comparable);
  EXPECT_FALSE(WithinThresholds(d, ImageThresholds()));
}

TEST_F(ImageCompare, MissingBaselineWritesCandidateAndFails)
{
  const auto root = UseScratchDirectories("missing");
  auto image = MakeImage(8, 8, 255, 0, 0);
  const std::string message = CompareWithBaseline(image, "Missing.png");
  EXPECT_NE(message.find("is missing"), std::string::npos) << message;
  EXPECT_NE(message.find("Testing/Data/Baseline"), std::string::npos) << message;
  EXPECT_TRUE(std::filesystem::exists(root / "temporary" / "Missing.png"));
}

TEST_F(ImageCompare, FailureWritesActualAndDiff)
{
  const auto root = UseScratchDirectories("failure");
  auto baseline = MakeImage(8, 8, 0, 0, 0);
  SetPixel(baseline, 2, 2, 255, 255, 255);
  ASSERT_TRUE(WritePng(baseline, (root / "baseline" / "Case.png").string()));
  auto actual = MakeImage(8, 8, 0, 0, 0);
  SetPixel(actual, 5, 5, 255, 255, 255);
  const std::string message = CompareWithBaseline(actual, "Case.png");
  EXPECT_NE(message.find("differs from baseline"), std::string::npos) << message;
  EXPECT_TRUE(std::filesystem::exists(root / "temporary" / "Case.actual.png"));
  EXPECT_TRUE(std::filesystem::exists(root / "temporary" / "Case.diff.png"));
  // Same image passes and round-trips through PNG bit-exactly.
  EXPECT_EQ(CompareWithBaseline(baseline, "Case.png"), "");
  auto reread = ReadPng((root / "baseline" / "Case.png").string());
  ASSERT_TRUE(reread);
  EXPECT_TRUE(ImagesIdentical(reread, baseline));
}

TEST_F(ImageCompare, AllBackgroundImageFailsLoudlyEvenAgainstDarkBaseline)
{
  const auto root = UseScratchDirectories("black");
  // A mostly dark baseline: one covered pixel in 400 would pass the mean error threshold.
  auto baseline = MakeImage(20, 20, 0, 0, 0);
  SetPixel(baseline, 3, 3, 40, 40, 40);
  ASSERT_TRUE(WritePng(baseline, (root / "baseline" / "Dark.png").string()));
  auto black = MakeImage(20, 20, 0, 0, 0);
  ImageThresholds lenient;
  lenient.maxMeanAbsError = 1.0;
  lenient.maxCoveredBadFraction = 1.0;
  const std::string message = CompareWithBaseline(black, "Dark.png", lenient);
  EXPECT_NE(message.find("all background"), std::string::npos) << message;
}
