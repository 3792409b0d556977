// What the commands write: the JSON pieces of their reports (strings, vectors, cameras, id
// lists), the names of the files of frames and cameras, polydata files and report files.
#ifndef scenevis_tool_Report_h
#define scenevis_tool_Report_h

#include <cstddef>
#include <set>
#include <string>

class vtkCamera;
class vtkPolyData;

namespace scenevis
{
namespace tool
{

/// @p text as a JSON string: quoted, with quotes and backslashes escaped.
std::string JsonString(const std::string& text);

/// The three values at @p v as a JSON array (9 significant digits).
std::string JsonVector(const double* v);

/// The camera a frame or result used, as it was when drawn: eye, focal point, up, projection,
/// view angle (perspective) or parallel scale, and the clipping range and whether it was fixed.
std::string JsonCamera(vtkCamera* camera, bool fixedClippingRange);

/// @p ids as a JSON array of numbers.
std::string JsonIds(const std::set<long long>& ids);

/// The output of camera @p index of --cameras: OUT-INDEX.EXT (out-0.png, out-1.png, ...).
std::string CameraFileName(const std::string& out, std::size_t index, const char* extension);

/// The output of orbit frame @p frame of @p frames: OUT itself when there is one frame, else
/// OUT-0007.EXT (.png when OUT has no extension).
std::string FrameFileName(const std::string& out, int frame, int frames);

/// Writes @p pd as a binary VTK XML file; throws std::runtime_error when it cannot.
void WritePolyData(vtkPolyData* pd, const std::string& path);

/// Writes a report (--report) to @p path; throws std::runtime_error when it cannot.
void WriteReport(const std::string& text, const std::string& path);

} // namespace tool
} // namespace scenevis

#endif
