// Reading model files the tool cannot trust.
#include "UntrustedFiles.h"

#include "Memory.h"

#include <vtkIsolatedRead.h>
#include <vtkSceneVisModelReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace scenevis
{
namespace tool
{
namespace
{
/// Peak resident memory of `render` per byte of the loaded polydata (GetActualMemorySize), the
/// largest of its paths as measured on the 48.6M-triangle engine grid with a margin (BENCHMARKS.md,
/// "Memory and page faults": 2.22 for one mesh chunked, 1.74 drawn whole, 1.44 as parts).
constexpr double kPeakPerPolyDataByte = 2.5;
/// Bytes of a loaded polydata per point (float coordinates, normals) and per polygon (a triangle's
/// offsets and connectivity, RGBA colour, one id array) when only a file's header is known.
constexpr double kBytesPerPoint = 24.0;
constexpr double kBytesPerPolygon = 44.0;
/// A model file in a format without a header to read counts as this many times its size.
constexpr double kBytesPerFileByte = 3.0;
} // namespace

vtkSmartPointer<vtkPolyData> LoadModelKeepingNonFinite(const std::string& path, std::string* error)
{
  return vtkSceneVisModelReader::LoadFile(path, error, false);
}

vtkSmartPointer<vtkPolyData> LoadModelIsolated(
  const std::string& path, std::string& error, ModelLoader load)
{
  // VTK's XML reader checks what it reads (a truncated or garbled .vtp is an error, Tool.Truncated*
  // tests): read in this process, which saves writing and reading the model a second time
  // (a third of the time to the first frame of a 48M-triangle .vtp).
  if (load == LoadModelKeepingNonFinite && path.size() > 4 &&
    path.compare(path.size() - 4, 4, ".vtp") == 0)
    return load(path, &error);
  return vtkIsolatedRead::Run(
    path, [&](std::string* message) { return load(path, message); }, &error);
}

void CheckPointIds(vtkPolyData* pd, const std::string& path)
{
  const std::string bad = vtkSceneVisModelReader::DescribeBadPointId(pd);
  if (!bad.empty())
    throw std::runtime_error("cannot use '" + path + "': " + bad);
}

void CheckFitsInMemory(const std::string& path)
{
  const std::uint64_t available = AvailableMemory();
  if (available == 0)
    return; // the system does not say: nothing to compare with
  std::string basis;
  double polydata = 0.0;
  const VtpHeader header = ReadVtpHeader(path);
  if (header.valid)
  {
    polydata = kBytesPerPoint * static_cast<double>(header.points) +
      kBytesPerPolygon * static_cast<double>(header.polys);
    basis = std::to_string(header.points) + " points and " + std::to_string(header.polys) +
      " polygons in its header";
  }
  else
  {
    struct stat info;
    if (::stat(path.c_str(), &info) != 0)
      return; // the reader says what is wrong with the path
    polydata = kBytesPerFileByte * static_cast<double>(info.st_size);
    basis = FormatBytes(static_cast<std::uint64_t>(info.st_size)) + " on disk";
  }
  const double needed = kPeakPerPolyDataByte * polydata;
  if (needed > static_cast<double>(available))
  {
    throw std::runtime_error("'" + path + "' is too big for this machine: about " +
      FormatBytes(static_cast<std::uint64_t>(needed)) + " needed (" + basis + ") and " +
      FormatBytes(available) +
      " available; refusing to load it (SCENEVIS_MEMORY_LIMIT sets the limit)");
  }
}

} // namespace tool
} // namespace scenevis
