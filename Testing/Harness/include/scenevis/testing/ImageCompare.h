/**
 * @file ImageCompare.h
 * @brief Image comparison with PNG baselines for rendering tests.
 *
 * The measures themselves (CompareImages(), thresholds, coverage, PNG files) are
 * SceneVis::RenderingHeadless's (vtkSceneVisImageCompare.h, what users link); this header brings
 * them into scenevis::testing and adds what only tests need: the baseline and temporary
 * directories and CompareWithBaseline().
 *
 * Directories: baselines are read from Testing/Data/Baseline/ of the source tree, outputs are
 * written to Testing/Temporary/ of the build tree; $SCENEVIS_BASELINE_DIR and
 * $SCENEVIS_TEMPORARY_DIR override them.
 */
#ifndef scenevis_testing_ImageCompare_h
#define scenevis_testing_ImageCompare_h

#include <vtkSceneVisImageCompare.h>
#include <vtkSmartPointer.h>

#include <string>

class vtkImageData;
class vtkRenderWindow;

namespace scenevis
{
namespace testing
{

using headless::CompareImages;
using headless::CoveredFraction;
using headless::ImageDifference;
using headless::ImagesIdentical;
using headless::ImageThresholds;
using headless::MakeDifferenceImage;
using headless::ReadPng;
using headless::Rgb;
using headless::Thresholds;
using headless::WithinThresholds;
using headless::WritePng;

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

} // namespace testing
} // namespace scenevis

#endif
