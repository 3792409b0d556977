// Reading model files the tool cannot trust.
#include "UntrustedFiles.h"

#include "Memory.h"

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

vtkSmartPointer<vtkPolyData> LoadModelIsolated(
  const std::string& path, std::string& error, ModelLoader load)
{
  // VTK's XML reader checks what it reads (a truncated or garbled .vtp is an error, Tool.Truncated*
  // tests): read in this process, which saves writing and reading the model a second time
  // (a third of the time to the first frame of a 48M-triangle .vtp).
  if (load == scenevis::testing::LoadModel && path.size() > 4 &&
    path.compare(path.size() - 4, 4, ".vtp") == 0)
    return load(path, &error);
  const char* tmp = std::getenv("TMPDIR");
  std::string file = std::string(tmp && *tmp ? tmp : "/tmp") + "/scenevis-load-XXXXXX.vtp";
  const int fd = ::mkstemps(&file[0], 4);
  int channel[2] = { -1, -1 };
  if (fd < 0 || ::pipe(channel) != 0)
  {
    if (fd >= 0)
    {
      ::close(fd);
      std::remove(file.c_str());
    }
    return load(path, &error);
  }
  ::close(fd);
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t child = ::fork();
  if (child == 0)
  {
    ::close(channel[0]);
    const rlimit noCore{ 0, 0 };
    ::setrlimit(RLIMIT_CORE, &noCore); // a reader crash is reported, not dumped
    // Some readers print straight to stderr (vtkPLY: a line per missing element), and glibc
    // reports heap corruption there: the parent says what happened, in one line.
    const int devNull = ::open("/dev/null", O_WRONLY);
    if (devNull >= 0)
      ::dup2(devNull, STDERR_FILENO);
    std::string message;
    vtkSmartPointer<vtkPolyData> pd = load(path, &message);
    if (pd)
    {
      vtkNew<vtkXMLPolyDataWriter> writer;
      writer->SetFileName(file.c_str());
      writer->SetInputData(pd);
      writer->SetCompressorTypeToNone();
      writer->SetDataModeToAppended();
      writer->EncodeAppendedDataOff();
      if (writer->Write() != 1)
        message = "cannot pass '" + path + "' on: writing " + file + " failed";
    }
    if (!message.empty())
    {
      const ssize_t written = ::write(channel[1], message.data(), message.size());
      ::_exit(written >= 0 ? 1 : 2);
    }
    ::_exit(0);
  }
  ::close(channel[1]);
  if (child < 0)
  {
    ::close(channel[0]);
    std::remove(file.c_str());
    return load(path, &error);
  }
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = ::read(channel[0], buffer, sizeof(buffer))) != 0;)
  {
    if (n > 0)
      message.append(buffer, static_cast<std::size_t>(n));
    else if (errno != EINTR)
      break;
  }
  ::close(channel[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR)
  {
  }
  vtkSmartPointer<vtkPolyData> result;
  if (WIFSIGNALED(status))
  {
    error = "cannot read '" + path + "': VTK's reader crashed on it (signal " +
      std::to_string(WTERMSIG(status)) + ", " + ::strsignal(WTERMSIG(status)) + ")";
  }
  else if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(file.c_str());
    reader->Update();
    result = vtkSmartPointer<vtkPolyData>::New();
    result->ShallowCopy(reader->GetOutput());
  }
  else
  {
    error = message.empty() ? "cannot read '" + path + "'" : message;
  }
  std::remove(file.c_str());
  return result;
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
