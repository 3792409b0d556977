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


@pytest.fixture
def render_window():
    """An offscreen 300 x 300 window without multisampling; skips without an X display."""
    if not os.environ.get("DISPLAY"):
        pytest.skip("no X display (the suite runs under xvfb-run)")
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(300, 300)
    yield window
    window.Finalize()
