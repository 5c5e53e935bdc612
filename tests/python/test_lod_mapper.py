"""tcLODMapper from Python: an atlas drawn with level of detail, in one or many instances."""
import os
import pathlib

import pytest

import trichart


@pytest.fixture(scope="module")
def atlas():
    data = pathlib.Path(os.environ.get("TRICHART_TESTING_DATA",
                                       pathlib.Path(__file__).parents[2] / "testing-data"))
    clean, _ = trichart.prepare(trichart.read_mesh(data / "meshes" / "bunny_npm.off"))
    surface, _ = trichart.curvature(clean)
    clusters, _ = trichart.cluster(surface)
    features, _, _ = trichart.refine_features(clusters)
    _, parameterized = trichart.base_complex(features)
    patches, _ = trichart.trace_paths(parameterized)
    return trichart.geometry_images(patches)


def scene(atlas):
    from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow

    mapper = trichart.tcLODMapper()
    mapper.SetInputData(atlas)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(320, 240)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    return mapper, window


def test_fixed_level_draws_every_chart(atlas):
    mapper, window = scene(atlas)
    charts = trichart.atlas_charts(atlas)
    mapper.SetFixedLevel(2)
    window.Render()
    count = mapper.GetNumberOfCharts()
    assert count == charts.GetNumberOfRows() > 0
    column = charts.GetColumnByName("MaxLevel")
    finest = [int(column.GetTuple1(c)) for c in range(count)]
    # Every chart at level 2 (or its finest when coarser): 4^level grid triangles each.
    assert mapper.GetTrianglesDrawn() == sum(4 ** min(2, m) for m in finest)
    assert mapper.GetChartsDrawn() == count


def test_instances_multiply_the_work_and_the_bounds(atlas):
    from vtkmodules.vtkCommonCore import vtkDoubleArray

    mapper, window = scene(atlas)
    mapper.SetFixedLevel(1)
    window.Render()
    one = mapper.GetTrianglesDrawn()
    bounds = mapper.GetBounds()
    matrices = vtkDoubleArray()
    matrices.SetNumberOfComponents(16)
    shift = 2.0 * (bounds[1] - bounds[0])
    for i in range(3):
        matrices.InsertNextTuple([1, 0, 0, i * shift, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
    mapper.SetInstanceMatrices(matrices)
    assert mapper.GetNumberOfInstances() == 3
    wide = mapper.GetBounds()
    assert wide[1] == pytest.approx(bounds[1] + 2 * shift)
    window.GetRenderers().GetFirstRenderer().ResetCamera()
    window.Render()
    assert mapper.GetTrianglesDrawn() == 3 * one


def test_bad_instance_matrices_are_refused(atlas):
    from vtkmodules.vtkCommonCore import vtkDoubleArray

    mapper, _ = scene(atlas)
    matrices = vtkDoubleArray()
    matrices.SetNumberOfComponents(9)
    matrices.InsertNextTuple([1] * 9)
    mapper.SetInstanceMatrices(matrices)  # reported, not applied
    assert mapper.GetNumberOfInstances() == 1


def test_not_an_atlas_draws_nothing(atlas):
    from vtkmodules.vtkFiltersSources import vtkSphereSource

    mapper, window = scene(atlas)
    sphere = vtkSphereSource()
    mapper.SetInputConnection(sphere.GetOutputPort())
    window.Render()  # the error is reported; nothing is drawn and nothing crashes
    assert mapper.GetNumberOfCharts() == 0
    assert mapper.GetTrianglesDrawn() == 0
