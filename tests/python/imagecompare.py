"""Compare a PNG with its baseline in testing-data/baselines, the way VTK's regression tests
do (vtkImageDifference). A missing or differing baseline leaves the candidate and the
difference image in the temporary folder, so that a new baseline can be reviewed and copied."""
import os
import shutil

from vtkmodules.vtkImagingCore import vtkImageDifference  # noqa: F401
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter


def compare_with_baseline(candidate, baseline, threshold=0.05):
    """Return (ok, error). `error` is vtkImageDifference's thresholded error per pixel."""
    temp = os.environ.get("TRICHART_TEMP", os.path.dirname(str(candidate)))
    os.makedirs(temp, exist_ok=True)
    keep = os.path.join(temp, os.path.basename(str(baseline)))
    if not os.path.exists(baseline):
        shutil.copyfile(candidate, keep)
        return False, f"no baseline {baseline}; candidate written to {keep}"
    readers = []
    for path in (candidate, baseline):
        r = vtkPNGReader()
        r.SetFileName(str(path))
        r.Update()
        readers.append(r)
    if readers[0].GetOutput().GetDimensions() != readers[1].GetOutput().GetDimensions():
        shutil.copyfile(candidate, keep)
        return False, f"size differs from {baseline}; candidate written to {keep}"
    diff = vtkImageDifference()
    diff.SetInputConnection(readers[0].GetOutputPort())
    diff.SetImageConnection(readers[1].GetOutputPort())
    diff.Update()
    error = diff.GetThresholdedError()
    if error > threshold:
        shutil.copyfile(candidate, keep)
        w = vtkPNGWriter()
        w.SetFileName(keep.replace(".png", ".diff.png"))
        w.SetInputConnection(diff.GetOutputPort())
        w.Write()
        return False, f"differs from {baseline} by {error:.4f} > {threshold}; see {keep}"
    return True, error


def _rgb(path):
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy

    r = vtkPNGReader()
    r.SetFileName(str(path))
    r.Update()
    dims = r.GetOutput().GetDimensions()
    pixels = vtk_to_numpy(r.GetOutput().GetPointData().GetScalars())
    return numpy.asarray(pixels.reshape(dims[1], dims[0], -1)[:, :, :3], dtype=int)


def differing_inner_pixels(candidate, baseline, level, margin=2):
    """differing_pixels over the pixels that both PNGs cover (not black) together with every
    pixel within `margin` of them: a wrong colour inside a surface, not a silhouette that moved
    by a pixel."""
    import numpy

    a, b = _rgb(candidate), _rgb(baseline)
    covered = (a.max(axis=2) > 0) & (b.max(axis=2) > 0)
    inner = covered.copy()
    for dy in range(-margin, margin + 1):
        for dx in range(-margin, margin + 1):
            inner &= numpy.roll(numpy.roll(covered, dy, axis=0), dx, axis=1)
    return int(((numpy.abs(a - b).max(axis=2) > level) & inner).sum())


def differing_pixels(candidate, baseline, level):
    """Pixels whose red, green or blue differs by more than `level` (of 255) between two PNGs
    of the same size: stricter than vtkImageDifference, whose threshold hides shading changes
    of a few tens of levels."""
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy

    images = []
    for path in (candidate, baseline):
        r = vtkPNGReader()
        r.SetFileName(str(path))
        r.Update()
        dims = r.GetOutput().GetDimensions()
        pixels = vtk_to_numpy(r.GetOutput().GetPointData().GetScalars())
        images.append(pixels.reshape(dims[1], dims[0], -1)[:, :, :3].astype(int))
    if images[0].shape != images[1].shape:
        raise ValueError(f"{candidate} and {baseline} differ in size")
    return int((numpy.abs(images[0] - images[1]).max(axis=2) > level).sum())
