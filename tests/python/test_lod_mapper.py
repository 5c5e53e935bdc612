"""tcLODMapper from Python: an atlas drawn with level of detail, in one or many instances."""
import pytest

import trichart
from trichart import tcArrayNames


@pytest.fixture(scope="module")
def atlas(bunny_stages):
    return bunny_stages["atlas"]


_WINDOW = []


def scene(atlas):
    """A new mapper of `atlas` in a new renderer, in the module's one off-screen window: each
    window is an X connection, and opening one after another can fail under Xvfb."""
    from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow

    mapper = trichart.tcLODMapper()
    mapper.SetInputData(atlas)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    if not _WINDOW:
        _WINDOW.append(vtkRenderWindow())
        _WINDOW[0].SetOffScreenRendering(1)
        _WINDOW[0].SetSize(320, 240)
    window = _WINDOW[0]
    previous = window.GetRenderers().GetFirstRenderer()
    if previous is not None:
        window.RemoveRenderer(previous)
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
    column = charts.GetColumnByName(tcArrayNames.MaxLevel())
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


def test_removing_the_input_frees_the_converted_atlas(atlas):
    mapper = trichart.tcLODMapper()
    mapper.SetInputData(atlas)
    bounds = mapper.GetBounds()  # converts the atlas, without rendering
    assert mapper.GetNumberOfCharts() == trichart.atlas_charts(atlas).GetNumberOfRows() > 0
    assert bounds[1] > bounds[0]
    mapper.SetInputData(None)
    assert mapper.GetNumberOfCharts() == 0
    mapper.SetInputData(atlas)  # and a new input is converted again
    mapper.GetBounds()
    assert mapper.GetNumberOfCharts() == trichart.atlas_charts(atlas).GetNumberOfRows()


def pixels(window):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.Update()
    return vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).astype(int)


def test_color_by_attribute_maps_it_through_the_lookup_table(atlas):
    from vtkmodules.vtkCommonCore import vtkLookupTable

    mapper, window = scene(atlas)
    window.GetRenderers().GetFirstRenderer().SetBackground(0, 0, 0)
    mapper.SetFixedLevel(-1)
    mapper.SetColorMode(trichart.tcLODMapper.ColorByAttribute)
    mapper.SetColorAttribute(tcArrayNames.MeanCurvature())
    table = vtkLookupTable()  # blue below the middle of the range, red above
    table.SetNumberOfTableValues(2)
    table.SetTableValue(0, 0, 0, 1, 1)
    table.SetTableValue(1, 1, 0, 0, 1)
    table.Build()
    mapper.SetLookupTable(table)
    window.Render()
    rgb = pixels(window)
    red = ((rgb[:, 0] > 40) & (rgb[:, 2] < 10)).sum()
    blue = ((rgb[:, 2] > 40) & (rgb[:, 0] < 10)).sum()
    # Mean curvature changes sign over the bunny: both halves of the table show.
    assert red > 200 and blue > 200
    # An attribute the atlas lacks is reported and the actor's grey is used: no pure hues.
    mapper.SetColorAttribute("NoSuchArray")
    window.Render()
    rgb = pixels(window)
    assert ((rgb[:, 0] > 40) & (rgb[:, 2] < 10)).sum() == 0
    assert (rgb.max(axis=1) > 40).sum() > 400


def test_a_skinned_atlas_is_posed_on_the_gpu_per_instance(shared_data, tmp_path):
    """The snake built into an atlas and drawn by tcLODMapper as two instances, each at its own
    time: every vertex the GPU draws (read back by transform feedback) lies on the finest level
    rebuilt and posed on the CPU (trichart.pose) at its instance's time, and the two differ."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.vtkCommonDataModel import vtkPolyData, vtkStaticPointLocator

    glb = shared_data / "skinned" / "snake_fbx" / "snake_fbx.glb"
    trichart.build(glb, tmp_path / "snake.exr")
    atlas = trichart.read_atlas(tmp_path / "snake.exr")
    finest = trichart.rebuild(atlas)
    duration = trichart.time_steps(glb)[-1]
    # The atlas announces the times of the file it was built from.
    assert trichart.time_steps(tmp_path / "snake.exr") == trichart.time_steps(glb)
    times = (0.3 * duration, 0.8 * duration)
    mapper, window = scene(atlas)
    seconds = vtkDoubleArray()
    for t in times:
        seconds.InsertNextValue(t)
    instances = vtkDoubleArray()
    instances.SetNumberOfComponents(16)
    for _ in times:
        instances.InsertNextTuple([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
    mapper.SetInstanceMatrices(instances)
    mapper.SetInstanceTimes(seconds)
    mapper.SetFixedLevel(15)  # every chart at its finest
    mapper.CaptureVerticesOn()
    window.Render()
    assert mapper.GetSkinned()
    captured = vtk_to_numpy(mapper.GetCapturedVertices())
    captured = captured[captured[:, 3] >= 0]
    rest = vtk_to_numpy(finest.GetPoints().GetData())
    diagonal = np.linalg.norm(rest.max(axis=0) - rest.min(axis=0))
    rng = np.random.default_rng(3)
    for instance, t in enumerate(times):
        posed = trichart.pose(finest, t)
        cloud = vtkPolyData()
        cloud.SetPoints(posed.GetPoints())
        locator = vtkStaticPointLocator()
        locator.SetDataSet(cloud)
        locator.BuildLocator()
        mine = captured[captured[:, 7] == instance][:, :3]
        assert len(mine) > 0
        worst = 0.0
        for p in mine[rng.choice(len(mine), size=min(3000, len(mine)), replace=False)]:
            q = posed.GetPoint(locator.FindClosestPoint(p))
            worst = max(worst, float(np.linalg.norm(np.array(q) - p)) / diagonal)
        print(f"instance {instance} at {t:.3f} s: largest distance to CPU posing {worst:.2e}")
        assert worst < 1e-6
    first = captured[captured[:, 7] == 0][:, :3]
    second = captured[captured[:, 7] == 1][:, :3]
    assert np.abs(first - second).max() > 0.01 * diagonal
