/**
 * @file CameraFile.h
 * @brief The cameras of `scenevis --cameras FILE.json`, and the checks that the command line's
 * camera options share with them.
 *
 * The file is one JSON array of camera objects:
 *
 *     [ {"eye": [0, 0, 5], "focal": [0, 0, 0]},
 *       {"eye": [5, 0, 0], "focal": [0, 0, 0], "up": [0, 0, 1], "view_angle": 60,
 *        "clipping_range": [0.5, 50]},
 *       {"eye": [0, 5, 0], "focal": [0, 0, 0], "parallel_scale": 2} ]
 *
 * "eye" and "focal" are required; "up", "view_angle" (degrees, (0, 180): perspective),
 * "parallel_scale" (> 0: parallel projection; not with "view_angle") and "clipping_range"
 * ([near, far], 0 < near < far) are optional. Anything else is an error, so that a misspelt
 * member is not silently ignored. The reader is strict RFC 8259 JSON (no NaN, no trailing commas,
 * no comments) and needs no JSON library; every error is one line naming the file, and the line
 * and column or the camera at fault.
 */
#ifndef scenevis_tool_CameraFile_h
#define scenevis_tool_CameraFile_h

#include <string>
#include <vector>

namespace scenevis
{
namespace tool
{

/// One camera as the user gave it (command line or camera file). What is not given is left to
/// the tool: the default view fitted to the scene, VTK's 30-degree view angle, a parallel scale
/// fitted to the scene and a clipping range reset to the visible props.
struct CameraSpec
{
  bool hasEye = false;
  double eye[3] = { 0, 0, 0 };
  bool hasFocal = false; ///< without it (command line only): the scene's centre
  double focal[3] = { 0, 0, 0 };
  bool hasUp = false;
  double up[3] = { 0, 1, 0 };
  bool parallel = false;
  double viewAngle = 0.0;             ///< degrees in (0, 180); 0: not given
  double parallelScale = 0.0;         ///< > 0: given (and parallel is true); 0: fitted
  double clippingRange[2] = { 0, 0 }; ///< near < far: fixed; else reset to the props

  bool FixedClippingRange() const { return this->clippingRange[0] < this->clippingRange[1]; }
};

/// Each check returns "" when the value is fine, else what is wrong (to follow a flag or a
/// camera's member name, e.g. "expects degrees in (0, 180), got 180").
std::string CheckViewAngle(double degrees);
std::string CheckParallelScale(double scale);
std::string CheckClippingRange(double nearDistance, double farDistance);

/**
 * Reads the cameras of @p path. Each camera starts as @p defaults (the command line's --up,
 * --parallel, --parallel-scale, --view-angle and --clipping-range) and takes what the file gives:
 * a "view_angle" makes it perspective, a "parallel_scale" parallel.
 * @throws std::runtime_error with one line when the file cannot be read, is not JSON, or is not
 * a non-empty array of valid cameras.
 */
std::vector<CameraSpec> ReadCameraFile(const std::string& path, const CameraSpec& defaults);

} // namespace tool
} // namespace scenevis

#endif
