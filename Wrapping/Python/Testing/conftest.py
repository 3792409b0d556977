"""pytest set-up for the `scenevis` Python tests (run by ctest as Python.pytest.*, with PYTHONPATH
pointing at the build tree's package)."""
import os

import pytest
import vtk


class VtkMessages:
    """Everything VTK prints (errors and warnings) while installed, as one string."""

    def __init__(self):
        self.window = vtk.vtkStringOutputWindow()
        self.previous = vtk.vtkOutputWindow.GetInstance()

    def text(self):
        return self.window.GetOutput()


@pytest.fixture
def vtk_messages():
    """Captures VTK's error and warning output instead of printing it."""
    messages = VtkMessages()
    vtk.vtkOutputWindow.SetInstance(messages.window)
    try:
        yield messages
    finally:
        vtk.vtkOutputWindow.SetInstance(messages.previous)


@pytest.fixture(scope="session")
def _shared_window():
    """One offscreen window per test process, as the C++ tests have: VTK 9.1's X window aborts
    the process when GLX cannot give it a context, which became likelier with every further
    window a process created under Xvfb (seen: 1 run in 7 with a window per test)."""
    if not os.environ.get("DISPLAY"):
        pytest.skip("no X display (the suite runs under xvfb-run)")
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    yield window
    window.Finalize()


@pytest.fixture
def render_window(_shared_window):
    """The offscreen window, 300 x 300, without renderers; skips without an X display."""
    _shared_window.SetSize(300, 300)
    yield _shared_window
    renderers = _shared_window.GetRenderers()
    for renderer in [renderers.GetItemAsObject(i) for i in range(renderers.GetNumberOfItems())]:
        _shared_window.RemoveRenderer(renderer)
