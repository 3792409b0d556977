/**
 * @file ImageCompare.h
 * @brief Image comparison with PNG baselines for rendering tests.
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
 * Directories: baselines are read from Testing/Data/Baseline/ of the source tree, outputs are
 * written to Testing/Temporary/ of the build tree; $SCENEVIS_BASELINE_DIR and
 * $SCENEVIS_TEMPORARY_DIR override them.
 */
#ifndef scenevis_testing_ImageCompare_h
#define scenevis_testing_ImageCompare_h

#include <vtkSmartPointer.h>

#include <array>
#include <cstddef>
#include <string>

class vtkImageData;
class vtkRenderWindow;

namespace scenevis
{
namespace testing
{

/// Result of CompareImages().
struct ImageDifference
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
ImageDifference CompareImages(vtkImageData* actual,
  vtkImageData* expected,
  Rgb background = { 0, 0, 0 },
  int badPixelLevel = 16);

/// Whether @p difference is within @p thresholds; if not and @p why is given, explains.
bool WithinThresholds(const ImageDifference& difference,
  const ImageThresholds& thresholds,
  std::string* why = nullptr);

/// Fraction of pixels of @p image that differ from @p background (0 for an all-background image).
double CoveredFraction(vtkImageData* image, Rgb background = { 0, 0, 0 });

/**
 * A visualisation of the difference: per pixel the absolute channel difference scaled by 4 (so
 * small errors show), with pixels over the bad level painted pure red.
 */
vtkSmartPointer<vtkImageData> MakeDifferenceImage(vtkImageData* actual,
  vtkImageData* expected,
  int badPixelLevel = 16);

/// Read a PNG file; nullptr if it is missing or unreadable.
vtkSmartPointer<vtkImageData> ReadPng(const std::string& path);

/// Write an unsigned-char image as PNG, creating the directory. Returns false on failure.
bool WritePng(vtkImageData* image, const std::string& path);

/// Directory of the PNG baselines (source tree Testing/Data/Baseline, or $SCENEVIS_BASELINE_DIR).
std::string BaselineDirectory();

/// Directory for test outputs (build tree Testing/Temporary, or $SCENEVIS_TEMPORARY_DIR).
std::string TemporaryDirectory();

/// Writes @p bytes to the file @p name in TemporaryDirectory() (created if needed) and returns
/// its path. Not /tmp: a fixed name there is shared by every checkout on the machine, and two
/// test runs at once would rewrite the file the other is reading.
std::string WriteTemporaryFile(const std::string& name, const std::string& bytes);

/**
 * Compare @p image with the baseline PNG @p baselineName (a file name in BaselineDirectory()).
 * On failure writes `<stem>.actual.png` and `<stem>.diff.png` into TemporaryDirectory().
 * When the baseline is missing, writes the candidate `<baselineName>` into TemporaryDirectory()
 * and fails with a message asking to look at it and copy it into Testing/Data/Baseline/.
 * @return an empty string on success, else the failure message (with metrics and file paths).
 */
std::string CompareWithBaseline(vtkImageData* image,
  const std::string& baselineName,
  const ImageThresholds& thresholds = ImageThresholds(),
  Rgb background = { 0, 0, 0 });

/// Render @p window, capture RGB and CompareWithBaseline().
std::string CompareWithBaseline(vtkRenderWindow* window,
  const std::string& baselineName,
  const ImageThresholds& thresholds = ImageThresholds(),
  Rgb background = { 0, 0, 0 });

/// Whether two images are bit-identical in dimensions, components and every byte.
bool ImagesIdentical(vtkImageData* a, vtkImageData* b, std::string* why = nullptr);

} // namespace testing
} // namespace scenevis

#endif
