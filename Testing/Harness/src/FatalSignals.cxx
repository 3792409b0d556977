#include "scenevis/testing/FatalSignals.h"

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SCENEVIS_SANITIZER_HANDLERS 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) ||                         \
  __has_feature(memory_sanitizer)
#define SCENEVIS_SANITIZER_HANDLERS 1
#endif
#endif

#if defined(__linux__) && !defined(SCENEVIS_SANITIZER_HANDLERS)
#include <csignal>
#include <cstring>
#include <execinfo.h>
#include <unistd.h>

namespace
{
constexpr int kSignals[] = { SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT };

void Write(const char* text)
{
  const ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

const char* Name(int signal)
{
  switch (signal)
  {
    case SIGSEGV:
      return "SIGSEGV";
    case SIGBUS:
      return "SIGBUS";
    case SIGILL:
      return "SIGILL";
    case SIGFPE:
      return "SIGFPE";
    case SIGABRT:
      return "SIGABRT";
    default:
      return "a fatal signal";
  }
}

void OnFatalSignal(int signal)
{
  ::alarm(10); // should the unwinder block, SIGALRM's default action ends the process
  Write("\nscenevis::testing: ");
  Write(Name(signal));
  Write(" (fatal); raw stack (addr2line -e <binary> -f -C <offset>):\n");
  void* frames[64];
  const int count = ::backtrace(frames, 64);
  ::backtrace_symbols_fd(frames, count, STDERR_FILENO);
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = SIG_DFL;
  ::sigemptyset(&action.sa_mask);
  ::sigaction(signal, &action, nullptr);
  ::raise(signal); // delivered on return: the default action (core, killed by the signal)
}

/// The handler's own stack (sigaltstack is per thread: the installing one's), so that a stack
/// overflow there still reaches it.
char gAlternateStack[64 * 1024];
} // namespace

namespace scenevis
{
namespace testing
{
bool InstallFatalSignalHandlers()
{
  static const bool prepared = []
  {
    void* frame[1];
    ::backtrace(frame, 1); // loads the unwinder now: it may allocate the first time
    stack_t stack;
    std::memset(&stack, 0, sizeof(stack));
    stack.ss_sp = gAlternateStack;
    stack.ss_size = sizeof(gAlternateStack);
    ::sigaltstack(&stack, nullptr);
    return true;
  }();
  (void)prepared;
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = &OnFatalSignal;
  action.sa_flags = SA_ONSTACK | SA_RESETHAND;
  ::sigemptyset(&action.sa_mask);
  for (const int signal : kSignals)
  {
    ::sigaction(signal, &action, nullptr);
  }
  return true;
}
} // namespace testing
} // namespace scenevis

#else

namespace scenevis
{
namespace testing
{
bool InstallFatalSignalHandlers()
{
  return false;
}
} // namespace testing
} // namespace scenevis

#endif
