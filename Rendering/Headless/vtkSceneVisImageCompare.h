/**
 * @file    vtkSceneVisImageCompare.h
 * @brief   Comparing rendered images and reading/writing them as PNG: the measures of an offscreen
 *          regression render (pair with vtkSceneVisHeadlessWindows.h's CaptureImage()).
 *
 * Metrics of CompareImages() (over the channels both images have, at most RGB: alpha is ignored
 * because what lands in a window's alpha channel differs between pipelines without being visible):
 *  - meanAbsError: mean absolute difference over all channels of all pixels, in 0..255 levels;
 *  - maxError: the largest channel difference anywhere;
 *  - coveredBadFraction: among COVERED pixels (pixels that differ from the background colour in
 *    at least one of the two images), the fraction whose largest channel difference exceeds
 *    ImageThresholds::badPixelLevel (16). Measuring over covered pixels keeps a small object on a
 *    large empty background from hiding its errors in the average.
 *
 * @code
 * vtkSmartPointer<vtkImageData> expected = scenevis::headless::ReadPng("baseline.png");
 * const scenevis::headless::ImageDifference difference =
 *   scenevis::headless::CompareImages(scenevis::headless::CaptureImage(window), expected);
 * std::string why;
 * if (!scenevis::headless::WithinThresholds(difference, scenevis::headless::ImageThresholds(),
 * &why))
 *   ... // why says which limit was broken
 * @endcode
 *
 * Plain functions and value types in namespace scenevis::headless (not wrapped for Python).
 *
 * @sa vtkSceneVisHeadlessWindows.h
 */
#ifndef vtkSceneVisImageCompare_h
#define vtkSceneVisImageCompare_h

#include "SceneVisRenderingHeadlessModule.h" // For export macro

#include <vtkSmartPointer.h> // For vtkSmartPointer

#include <array>   // For std::array
#include <cstddef> // For std::size_t
#include <string>  // For std::string

class vtkImageData;

namespace scenevis
{
namespace headless
{

/// Result of CompareImages().
struct SCENEVISRENDERINGHEADLESS_EXPORT ImageDifference
{
  bool comparable = false; ///< false when sizes/formats differ (then see `problem`)
  std::string problem;     ///< why the images could not be compared
  int width = 0;
  int height = 0;
  int channels = 0;        ///< channels compared (1..3)
  double meanAbsError = 0; ///< 0..255
  int maxError = 0;        ///< 0..255
  std::size_t coveredPixels = 0;
  std::size_t badCoveredPixels = 0;
  double coveredBadFraction = 0; ///< badCoveredPixels / coveredPixels (0 when nothing covered)

  /// One line for test output.
  std::string Summary() const;
};

/// Pass/fail limits for image comparisons; the defaults demand a (near) exact match.
struct ImageThresholds
{
  double maxMeanAbsError = 0.5; ///< in 0..255 levels
  double maxCoveredBadFraction = 0.001;
  int maxError = 255;     ///< 255: not checked
  int badPixelLevel = 16; ///< channel difference above which a pixel is "bad"
  /// Fail when fewer than this fraction of pixels is covered in the ACTUAL image: a render that is
  /// all background (black) fails loudly instead of comparing "close enough" to a dark baseline.
  double minCoveredFraction = 0.001;
};

/// The thresholds of a mean error and a fraction of bad covered pixels; the rest as defaulted.
inline ImageThresholds Thresholds(double maxMeanAbsError, double maxCoveredBadFraction)
{
  ImageThresholds thresholds;
  thresholds.maxMeanAbsError = maxMeanAbsError;
  thresholds.maxCoveredBadFraction = maxCoveredBadFraction;
  return thresholds;
}

/// An RGB colour in 0..255.
using Rgb = std::array<unsigned char, 3>;

/// Compare two unsigned-char images (1-4 components, same dimensions); a covered pixel is "bad"
/// when its largest channel difference exceeds @p badPixelLevel.
SCENEVISRENDERINGHEADLESS_EXPORT ImageDifference CompareImages(vtkImageData* actual,
  vtkImageData* expected, Rgb background = { 0, 0, 0 }, int badPixelLevel = 16);

/// Whether @p difference is within @p thresholds; if not and @p why is given, explains.
SCENEVISRENDERINGHEADLESS_EXPORT bool WithinThresholds(
  const ImageDifference& difference, const ImageThresholds& thresholds, std::string* why = nullptr);

/// Fraction of pixels of @p image that differ from @p background (0 for an all-background image).
SCENEVISRENDERINGHEADLESS_EXPORT double CoveredFraction(
  vtkImageData* image, Rgb background = { 0, 0, 0 });

/**
 * A visualisation of the difference: per pixel the absolute channel difference scaled by 4 (so
 * small errors show), with pixels over the bad level painted pure red.
 */
SCENEVISRENDERINGHEADLESS_EXPORT vtkSmartPointer<vtkImageData> MakeDifferenceImage(
  vtkImageData* actual, vtkImageData* expected, int badPixelLevel = 16);

/// Read a PNG file; nullptr if it is missing or unreadable.
SCENEVISRENDERINGHEADLESS_EXPORT vtkSmartPointer<vtkImageData> ReadPng(const std::string& path);

/// Write an unsigned-char image as PNG, creating the directory. Returns false on failure.
SCENEVISRENDERINGHEADLESS_EXPORT bool WritePng(vtkImageData* image, const std::string& path);

/// Whether two images are bit-identical in dimensions, components and every byte.
SCENEVISRENDERINGHEADLESS_EXPORT bool ImagesIdentical(
  vtkImageData* a, vtkImageData* b, std::string* why = nullptr);

} // namespace headless
} // namespace scenevis

#endif
