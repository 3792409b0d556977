#include "vtkIsolatedRead.h"

#include <vtkNew.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

vtkSmartPointer<vtkPolyData> vtkIsolatedRead::Run(
  const std::string& path, const Loader& load, std::string* error)
{
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
    return load(error);
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
    vtkSmartPointer<vtkPolyData> pd = load(&message);
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
    return load(error);
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
    if (error)
      *error = "cannot read '" + path + "': VTK's reader crashed on it (signal " +
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
    if (error)
      *error = message.empty() ? "cannot read '" + path + "'" : message;
  }
  std::remove(file.c_str());
  return result;
}
