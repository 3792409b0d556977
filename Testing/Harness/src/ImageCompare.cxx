#include "scenevis/testing/ImageCompare.h"

#include "scenevis/testing/RenderWindow.h"

#include <vtkImageData.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#ifndef SCENEVIS_DEFAULT_BASELINE_DIR
#define SCENEVIS_DEFAULT_BASELINE_DIR "Testing/Data/Baseline"
#endif
#ifndef SCENEVIS_DEFAULT_TEMPORARY_DIR
#define SCENEVIS_DEFAULT_TEMPORARY_DIR "Testing/Temporary"
#endif

namespace scenevis
{
namespace testing
{
namespace
{
std::string Env(const char* name, const char* fallback)
{
  const char* value = std::getenv(name);
  return value && *value ? std::string(value) : std::string(fallback);
}

std::string Stem(const std::string& name)
{
  return std::filesystem::path(name).stem().string();
}
} // namespace

std::string BaselineDirectory()
{
  return Env("SCENEVIS_BASELINE_DIR", SCENEVIS_DEFAULT_BASELINE_DIR);
}

std::string TemporaryDirectory()
{
  return Env("SCENEVIS_TEMPORARY_DIR", SCENEVIS_DEFAULT_TEMPORARY_DIR);
}

std::string WriteTemporaryFile(const std::string& name, const std::string& bytes)
{
  const std::filesystem::path directory(TemporaryDirectory());
  std::error_code ignored;
  std::filesystem::create_directories(directory, ignored);
  const std::filesystem::path path = directory / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path.string();
}

std::string CompareWithBaseline(vtkImageData* image,
  const std::string& baselineName,
  const ImageThresholds& thresholds,
  Rgb background)
{
  const std::filesystem::path baselinePath =
    std::filesystem::path(BaselineDirectory()) / baselineName;
  const std::filesystem::path temporary(TemporaryDirectory());
  std::ostringstream message;
  vtkSmartPointer<vtkImageData> expected = ReadPng(baselinePath.string());
  if (!expected)
  {
    const std::filesystem::path candidate = temporary / baselineName;
    const bool written = WritePng(image, candidate.string());
    message << "Baseline " << baselinePath.string() << " is missing. ";
    if (written)
    {
      message << "The candidate image was written to " << candidate.string()
              << ": LOOK at it, and if it is right copy it into Testing/Data/Baseline/ ("
              << BaselineDirectory() << ").";
    }
    else
    {
      message << "Writing the candidate to " << candidate.string() << " failed too.";
    }
    return message.str();
  }

  const double covered = CoveredFraction(image, background);
  const ImageDifference difference =
    CompareImages(image, expected, background, thresholds.badPixelLevel);
  std::string why;
  bool ok = WithinThresholds(difference, thresholds, &why);
  if (covered < thresholds.minCoveredFraction)
  {
    ok = false;
    why += "the actual image is (almost) all background: covered fraction " +
      std::to_string(covered) + " (black render?); ";
  }
  if (ok)
  {
    return std::string();
  }
  const std::string stem = Stem(baselineName);
  const std::filesystem::path actualPath = temporary / (stem + ".actual.png");
  const std::filesystem::path diffPath = temporary / (stem + ".diff.png");
  WritePng(image, actualPath.string());
  vtkSmartPointer<vtkImageData> diff =
    MakeDifferenceImage(image, expected, thresholds.badPixelLevel);
  if (diff)
  {
    WritePng(diff, diffPath.string());
  }
  message << "Image differs from baseline " << baselinePath.string() << ": " << why << "("
          << difference.Summary() << "). Actual: " << actualPath.string();
  if (diff)
  {
    message << ", difference: " << diffPath.string();
  }
  return message.str();
}

std::string CompareWithBaseline(vtkRenderWindow* window,
  const std::string& baselineName,
  const ImageThresholds& thresholds,
  Rgb background)
{
  vtkSmartPointer<vtkImageData> image = CaptureImage(window);
  return CompareWithBaseline(image, baselineName, thresholds, background);
}

} // namespace testing
} // namespace scenevis
