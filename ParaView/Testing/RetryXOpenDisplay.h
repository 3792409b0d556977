// The test drivers' XOpenDisplay, which tries again when Xvfb hangs up on a new connection
// (RetryXOpenDisplay.cxx says why).
#ifndef SceneVisRetryXOpenDisplay_h
#define SceneVisRetryXOpenDisplay_h

namespace scenevis_pvtest
{
/// Whether the process's calls to XOpenDisplay resolve to the retrying one (the executable
/// must export its symbols: ENABLE_EXPORTS).
bool XOpenDisplayRetries();
}

#endif
