/**
 * @file FatalSignals.h
 * @brief A crash in a test ends the process at once, with the signal and a raw stack.
 *
 * VTK's test driver installs loguru's and kwsys' signal handlers, which print a symbolized stack
 * trace. Both allocate and take locks inside the handler, so a crash with the heap's lock held (a
 * corrupted heap, a crash inside malloc or in a driver thread) deadlocks in the handler: in CI a
 * SIGSEGV became a 600 s timeout with nothing but "Loguru caught a signal: SIGSEGV" printed
 * (vtkLogger.h itself warns of "crashes and deadlocks"). The handler here only calls
 * async-signal-safe functions (write, backtrace_symbols_fd after backtrace's library was loaded at
 * install, sigaction, raise), runs on its own stack in the thread that installed it (a stack
 * overflow there reaches it too; in other threads it still ends the process, without a stack),
 * arms a 10 s alarm in case the unwinder still blocks, and re-raises the signal with the default
 * action, so CTest reports the crash ("Exception: SegFault") as soon as it happens.
 *
 * StrictVtkOutput's constructor installs it, so every VTK-level test that guards its output has
 * it. Sanitizer builds keep the sanitizers' own handlers (their reports are better): there it does
 * nothing.
 */
#ifndef scenevis_testing_FatalSignals_h
#define scenevis_testing_FatalSignals_h

namespace scenevis
{
namespace testing
{

/// Install the handler for SIGSEGV, SIGBUS, SIGILL, SIGFPE and SIGABRT (once; later calls
/// re-install it over handlers installed since). Returns false where it is not installed
/// (sanitizer builds, platforms without sigaction).
bool InstallFatalSignalHandlers();

} // namespace testing
} // namespace scenevis

#endif
