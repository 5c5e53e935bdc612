"""Offscreen pictures of TriChart stages (used by the CLI and the tests), in the colour maps of
tcColorMaps, the ones the viewer and the C++ image tests use."""
import os
import tempfile

from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingFreeType  # noqa: F401  (text of the scalar bar)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL back end)

from .TriChartIO import tcArrayNames
from .TriChartRendering import tcColorMaps


def add_lines(renderer, lines, width):
    """Draw `lines` (if any) in black over the surface."""
    if lines is None or lines.GetNumberOfCells() == 0:
        return
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(lines)
    mapper.ScalarVisibilityOff()
    mapper.SetResolveCoincidentTopologyToPolygonOffset()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.05, 0.05, 0.05)
    actor.GetProperty().SetLineWidth(width)
    renderer.AddActor(actor)


def _renderer():
    """A renderer with TriChart's background."""
    renderer = vtkRenderer()
    renderer.SetBackground(0.32, 0.34, 0.43)
    return renderer


def _window(renderer, size):
    """An offscreen window of `size` showing `renderer`, with the camera reset."""
    renderer.ResetCamera()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*size)
    window.AddRenderer(renderer)
    return window


def _label_mapper(data, array, cell):
    """A mapper colouring `data` by the integer `array` (cell or point data)."""
    values = (data.GetCellData() if cell else data.GetPointData()).GetArray(array)
    lut = vtkLookupTable()
    tcColorMaps.LabelColors(lut, values)
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(data)
    if cell:
        mapper.SetScalarModeToUseCellFieldData()
    else:
        mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray(array)
    mapper.SetLookupTable(lut)
    mapper.UseLookupTableScalarRangeOn()
    return mapper


def curvature_scene(surface, crest=None, array=None, size=(800, 600)):
    """A render window with `surface` coloured by `array` (default MeanCurvature), crest lines
    on top, and a legend."""
    array = array or tcArrayNames.MeanCurvature()
    lut = vtkLookupTable()
    tcColorMaps.DivergingColors(lut, surface.GetPointData().GetArray(array), 0)
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(surface)
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray(array)
    mapper.SetLookupTable(lut)
    mapper.UseLookupTableScalarRangeOn()
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = _renderer()
    renderer.AddActor(actor)
    add_lines(renderer, crest, 2.0)
    bar = vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle(array)
    bar.SetNumberOfLabels(5)
    bar.SetWidth(0.1)
    bar.SetHeight(0.6)
    renderer.AddActor2D(bar)
    return _window(renderer, size)


def write_png(window, path):
    """Render `window` and save it as PNG (temporary file, then rename)."""
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.Update()
    path = os.path.abspath(path)
    fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=".png", dir=os.path.dirname(path))
    os.close(fd)
    try:
        writer = vtkPNGWriter()
        writer.SetFileName(tmp)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path


def render_curvature(surface, crest, path, array=None):
    """Save a picture of the curvature stage to `path`."""
    return write_png(curvature_scene(surface, crest, array), path)


def features_scene(features, lines=None, corners=None, size=(800, 600)):
    """`features` coloured by ClusterId, feature lines in black and corners as red spheres."""
    from vtkmodules.vtkFiltersSources import vtkSphereSource
    from vtkmodules.vtkFiltersCore import vtkGlyph3D

    mapper = _label_mapper(features, tcArrayNames.ClusterId(), cell=True)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = _renderer()
    renderer.AddActor(actor)
    add_lines(renderer, lines, 3.0)
    if corners is not None and corners.GetNumberOfPoints() > 0:
        diagonal = features.GetLength()
        sphere = vtkSphereSource()
        sphere.SetRadius(0.008 * diagonal)
        glyphs = vtkGlyph3D()
        glyphs.SetInputData(corners)
        glyphs.SetSourceConnection(sphere.GetOutputPort())
        glyphs.ScalingOff()
        corner_mapper = vtkPolyDataMapper()
        corner_mapper.SetInputConnection(glyphs.GetOutputPort())
        corner_mapper.ScalarVisibilityOff()
        corner_actor = vtkActor()
        corner_actor.SetMapper(corner_mapper)
        corner_actor.GetProperty().SetColor(0.85, 0.1, 0.1)
        renderer.AddActor(corner_actor)
    return _window(renderer, size)


def render_features(features, lines, corners, path):
    """Save a picture of the feature stage (clusters, feature lines, corners) to `path`."""
    return write_png(features_scene(features, lines, corners), path)


def base_complex_scene(base, parameterized, size=(800, 600)):
    """The base complex's edges in black over the input mesh, whose vertices are coloured by
    their base face (BaseFaceId)."""
    from vtkmodules.vtkFiltersCore import vtkExtractEdges

    mapper = _label_mapper(parameterized, tcArrayNames.BaseFaceId(), cell=False)
    mapper.InterpolateScalarsBeforeMappingOff()  # blend the two labels, never invent a third
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetOpacity(0.6)
    renderer = _renderer()
    renderer.AddActor(actor)
    edges = vtkExtractEdges()
    edges.SetInputData(base)
    edges.Update()
    add_lines(renderer, edges.GetOutput(), 2.0)
    return _window(renderer, size)


def render_base_complex(base, parameterized, path):
    """Save a picture of the base-complex stage to `path`."""
    return write_png(base_complex_scene(base, parameterized), path)
