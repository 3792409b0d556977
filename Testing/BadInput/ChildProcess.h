// Child processes for the bad-input tests: run a command (or a function, forked) with a timeout
// and tell how it ended, so that a crash or a hang of the code under test is an observed result
// rather than the end of the test.
#ifndef scenevis_BadInput_ChildProcess_h
#define scenevis_BadInput_ChildProcess_h

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace badinput
{
inline constexpr double kTimeoutSeconds = 30.0;

struct Run
{
  bool timedOut = false;
  int exitCode = -1; ///< when it exited
  int signal = 0;    ///< when a signal ended it
  double seconds = 0.0;
  std::string out, err;
};

inline std::string ReadFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Waits for child @p pid, killing it after the timeout; fills the exit fields of a Run.
inline Run WaitForChild(pid_t pid)
{
  Run run;
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  for (;;)
  {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == pid)
    {
      break;
    }
    if (run.seconds > kTimeoutSeconds)
    {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      run.timedOut = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!run.timedOut)
  {
    if (WIFEXITED(status))
    {
      run.exitCode = WEXITSTATUS(status);
    }
    else if (WIFSIGNALED(status))
    {
      run.signal = WTERMSIG(status);
    }
  }
  return run;
}

/// Runs @p argv in a child process with stdout/stderr to files; kills it after the timeout.
inline Run RunChild(const std::vector<std::string>& argv, const std::string& scratch)
{
  const std::string outPath = scratch + "/stdout.txt";
  const std::string errPath = scratch + "/stderr.txt";
  const pid_t pid = fork();
  if (pid == 0)
  {
    const int out = open(outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, STDOUT_FILENO);
    dup2(err, STDERR_FILENO);
    const rlimit noCore = { 0, 0 }; // expected crashes must not litter the build with core files
    setrlimit(RLIMIT_CORE, &noCore);
    std::vector<char*> args;
    for (const std::string& a : argv)
    {
      args.push_back(const_cast<char*>(a.c_str()));
    }
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  Run run = WaitForChild(pid);
  run.out = ReadFile(outPath);
  run.err = ReadFile(errPath);
  return run;
}

inline std::vector<std::string> Lines(const std::string& text)
{
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
  {
    lines.push_back(line);
  }
  return lines;
}

} // namespace badinput

#endif
