#!/usr/bin/env python3
"""A headless regression render of sorted translucency from Python: the C++ example
HeadlessRegression.cxx line for line, against the same baseline.

    vtkDemoSceneSource (64 overlapping translucent spheres)
      -> scenevis.vtkBSPSortedPolyDataMapper (exact back-to-front order in the index buffer)
    renderer with scenevis.vtkOrderedTranslucentPass (plain alpha blending in draw order)
    offscreen vtk.vtkRenderWindow -> vtkWindowToImageFilter -> vtkImageDifference with a baseline

Usage: headless_regression.py BASELINE.png [OUTPUT.png] [--exact] [--write-baseline]
  Exit 0 when the render matches BASELINE.png (vtkImageDifference thresholded error <= 10, as the
  C++ example; with --exact: not one pixel differs), 1 when it does not (OUTPUT.png and
  OUTPUT-diff.png are then written to look at), 77 (skipped) without an X display.
  OUTPUT.png is always written. --write-baseline writes BASELINE.png instead.
Debian's VTK renders offscreen through X: run under `xvfb-run -a -s "-screen 0 1280x1024x24"`,
with LP_NUM_THREADS=1 for a pixel-exact llvmpipe image.
"""
import os
import sys

import vtk
import scenevis


def render_spheres():
    """The render of HeadlessRegression.cxx; returns (window, mapper, idle)."""
    spheres = scenevis.vtkDemoSceneSource()
    spheres.SetTriangleCount(20000)

    mapper = scenevis.vtkBSPSortedPolyDataMapper()
    mapper.SetInputConnection(spheres.GetOutputPort())
    mapper.SetScalarModeToUseCellData()
    mapper.SetColorModeToDirectScalars()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetSpecular(0.0)

    renderer = vtk.vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0.1, 0.1, 0.12)
    renderer.SetPass(scenevis.vtkOrderedTranslucentPass())
    camera = renderer.GetActiveCamera()
    camera.SetPosition(5.5, 3.7, 7.3)
    camera.SetFocalPoint(0, 0, 0)
    camera.SetViewAngle(40)
    renderer.ResetCameraClippingRange()

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(400, 400)
    window.AddRenderer(renderer)
    window.Render()

    # Same camera again: the order is reused, nothing is sorted or uploaded.
    updates = mapper.GetNumberOfOrderUpdates()
    uploads = mapper.GetNumberOfIndexUploads()
    window.Render()
    idle = (mapper.GetNumberOfOrderUpdates() == updates
            and mapper.GetNumberOfIndexUploads() == uploads
            and mapper.GetNumberOfTreeBuilds() == 1)
    print(f"{mapper.GetNumberOfFragments()} fragments; tree built "
          f"{mapper.GetNumberOfTreeBuilds()} time(s); unchanged camera "
          f"{'re-sorted nothing' if idle else 'RE-SORTED'}")
    return window, renderer, mapper, idle


def write_png(port, path):
    writer = vtk.vtkPNGWriter()
    writer.SetInputConnection(port)
    writer.SetFileName(path)
    writer.Write()


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    exact = "--exact" in argv
    if not args:
        print(__doc__.split("\n\n")[2], file=sys.stderr)
        return 2
    baseline = args[0]
    output = args[1] if len(args) > 1 else "headless-regression-python.png"
    if not os.environ.get("DISPLAY"):
        print("skipped: no X display (run under xvfb-run)")
        return 77

    window, _renderer, _mapper, idle = render_spheres()
    capture = vtk.vtkWindowToImageFilter()
    capture.SetInput(window)
    capture.SetInputBufferTypeToRGB()
    capture.ReadFrontBufferOff()
    capture.Update()

    if "--write-baseline" in argv:
        write_png(capture.GetOutputPort(), baseline)
        print(f"wrote baseline {baseline} (look at it before committing it)")
        return 0 if idle else 1
    if not os.path.isfile(baseline):
        print(f"no baseline {baseline} (run with --write-baseline)", file=sys.stderr)
        return 1
    write_png(capture.GetOutputPort(), output)

    reader = vtk.vtkPNGReader()
    reader.SetFileName(baseline)
    difference = vtk.vtkImageDifference()
    difference.SetInputConnection(capture.GetOutputPort())
    difference.SetImageConnection(reader.GetOutputPort())
    difference.Update()
    error = difference.GetThresholdedError()

    # Pixel for pixel: the number of pixels whose RGB differs at all.
    rendered = capture.GetOutput().GetPointData().GetScalars()
    expected = reader.GetOutput().GetPointData().GetScalars()
    if (capture.GetOutput().GetDimensions() != reader.GetOutput().GetDimensions()
            or expected.GetNumberOfComponents() < 3):
        differing = -1
    else:
        differing = sum(
            1 for i in range(rendered.GetNumberOfTuples())
            if rendered.GetTuple(i)[:3] != expected.GetTuple(i)[:3])
    print(f"pixels differing from {baseline}: {differing}")
    matches = differing == 0 if exact else error <= 10.0
    print(f"thresholded error against {baseline}: {error:g}"
          f" ({'matches' if matches else 'DIFFERS'})")
    if not matches:
        diff = os.path.splitext(output)[0] + "-diff.png"
        write_png(difference.GetOutputPort(), diff)
        print(f"wrote {output} and {diff}", file=sys.stderr)
    return 0 if matches and idle else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
