"""The `trichart` package from Python: wrapped filters, pipeline helpers, errors, progress."""
import math

import pytest

import trichart
from trichart import tcArrayNames
from trichart.pipeline import TriChartError


def test_filters_are_wrapped():
    for name in ("tcMeshReader", "tcMeshPreparation", "tcCurvature", "tcSpectralClustering",
                 "tcFeatureRefinement", "tcBaseComplex", "tcPathTracing", "tcGeometryImages",
                 "tcGeometryImageMesh", "tcSurfaceDistance", "tcAtlasReader", "tcAtlasWriter"):
        assert hasattr(trichart, name), name
    assert trichart.tcCurvature().GetNumberOfOutputPorts() == 2


def test_read_prepare_curvature_on_the_bunny(testing_data):
    mesh = trichart.read_mesh(testing_data / "meshes" / "bunny_npm.off")
    assert (mesh.GetNumberOfPoints(), mesh.GetNumberOfPolys()) == (1839, 3674)
    clean, report = trichart.prepare(mesh)
    assert clean.GetNumberOfPolys() == 3674
    surface, crest = trichart.curvature(clean)
    k = surface.GetPointData().GetArray(tcArrayNames.PrincipalCurvatures())
    assert k.GetNumberOfComponents() == 2
    assert all(k.GetComponent(i, 0) >= k.GetComponent(i, 1) for i in range(k.GetNumberOfTuples()))
    assert all(math.isfinite(k.GetComponent(i, 0)) for i in range(k.GetNumberOfTuples()))
    assert crest.GetNumberOfLines() > 0


def test_curvature_options_reach_the_filter(testing_data):
    clean, _ = trichart.prepare(trichart.read_mesh(testing_data / "meshes" / "bunny_npm.off"))
    _, no_lines = trichart.curvature(clean, compute_crest_lines=False)
    assert no_lines.GetNumberOfLines() == 0
    with pytest.raises(TypeError):
        trichart.curvature(clean, no_such_option=1)


def test_progress_is_reported_and_can_abort(testing_data):
    clean, _ = trichart.prepare(trichart.read_mesh(testing_data / "meshes" / "fandisk.off"))
    seen = []
    trichart.curvature(clean, progress=lambda label, f: seen.append((label, f)))
    assert seen and seen[-1][1] == pytest.approx(1.0)
    assert all(label == "curvature" for label, _ in seen)
    with pytest.raises(KeyboardInterrupt):
        trichart.curvature(clean, progress=lambda label, f: f < 0.3)


def test_missing_and_unknown_files_raise_clear_errors(tmp_path):
    with pytest.raises(TriChartError, match="does not exist"):
        trichart.read_mesh(tmp_path / "nothing.off")
    (tmp_path / "mesh.xyz").write_text("0 0 0\n")
    with pytest.raises(TriChartError, match="unknown extension"):
        trichart.read_mesh(tmp_path / "mesh.xyz")


def test_non_triangles_are_refused_by_curvature(tmp_path):
    (tmp_path / "quad.off").write_text("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")
    mesh = trichart.read_mesh(tmp_path / "quad.off")
    with pytest.raises(TriChartError, match="tcMeshPreparation"):
        trichart.curvature(mesh)


def test_build_writes_the_atlas_and_every_stage(testing_data, tmp_path):
    result = trichart.build(testing_data / "meshes" / "cube.off", tmp_path / "cube.exr",
                            stages=tmp_path / "out", image=False,
                            cluster_options={"number_of_clusters": 6})
    for name in ("prepared", "curvature", "crest_lines", "clusters", "cluster_boundaries",
                 "features", "feature_lines", "corners", "base_complex", "parameterized",
                 "patches", "paths", "rebuilt"):
        assert (tmp_path / "out" / f"{name}.vtp").stat().st_size > 0, name
    assert (tmp_path / "cube.exr").stat().st_size > 0
    assert result["surface"].GetNumberOfPolys() == 12
    assert set(result["seconds"]) >= {"curvature", "base", "paths", "images", "write"}
    assert not list((tmp_path / "out").glob(".tmp-*"))
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]


def test_plugin_path_points_at_the_plugin():
    from trichart import _config

    if not _config.PARAVIEW_VERSION:
        pytest.skip("built without ParaView: no plugin")
    path = trichart.plugin_path()
    assert path.endswith("TriChart.so")


def _uv_sphere(meridians, parallels):
    """vtkSphereSource's UV sphere of radius 0.5."""
    from vtkmodules.vtkFiltersSources import vtkSphereSource

    source = vtkSphereSource()
    source.SetThetaResolution(meridians)
    source.SetPhiResolution(parallels)
    source.Update()
    return source.GetOutput()


def test_fill_holes_closes_an_open_sphere():
    # A UV sphere without its polar caps (z > 0.4 and z < -0.4): two holes.
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    from vtkmodules.vtkCommonCore import vtkIdList

    sphere = _uv_sphere(48, 32)
    kept = vtkPolyData()
    kept.SetPoints(sphere.GetPoints())
    kept.Allocate()
    ids = vtkIdList()
    for c in range(sphere.GetNumberOfCells()):
        sphere.GetCellPoints(c, ids)
        z = sum(sphere.GetPoint(ids.GetId(k))[2] for k in range(ids.GetNumberOfIds()))
        if abs(z / ids.GetNumberOfIds()) < 0.4:
            kept.InsertNextCell(sphere.GetCellType(c), ids)
    opened, report = trichart.prepare(kept)
    assert "boundary edges" in report and "filled" not in report

    closed, report = trichart.prepare(kept, fill_holes=True)
    print(report)
    assert "filled 2 holes" in report and "boundary edge" not in report
    boundary = closed.GetPointData().GetArray(tcArrayNames.BoundaryVertex())
    assert max(boundary.GetValue(i) for i in range(boundary.GetNumberOfTuples())) == 0
    new_points = closed.GetNumberOfPoints() - opened.GetNumberOfPoints()
    assert new_points > 0
    input_ids = closed.GetPointData().GetArray(tcArrayNames.InputPointId())
    assert sum(1 for i in range(input_ids.GetNumberOfTuples()) if input_ids.GetValue(i) < 0) \
        == new_points
    # Faired patches follow the sphere (radius 0.5) closely.
    for i in range(opened.GetNumberOfPoints(), closed.GetNumberOfPoints()):
        x, y, z = closed.GetPoint(i)
        assert abs(math.sqrt(x * x + y * y + z * z) - 0.5) < 0.05

    # Loops longer than max_hole_edges stay open.
    _, report = trichart.prepare(kept, fill_holes=True, max_hole_edges=10)
    assert "left 2 holes open" in report


def _slivers(mesh, max_angle=170.0, max_ratio=10.0):
    """Triangles of `mesh` with an angle above max_angle degrees or a side max_ratio times
    another."""
    from vtkmodules.vtkCommonCore import vtkIdList

    ids = vtkIdList()
    count = 0
    for c in range(mesh.GetNumberOfCells()):
        mesh.GetCellPoints(c, ids)
        p = [mesh.GetPoint(ids.GetId(k)) for k in range(3)]
        sides = sorted(math.dist(p[k], p[(k + 1) % 3]) for k in range(3))
        cosine = (sides[0] ** 2 + sides[1] ** 2 - sides[2] ** 2) / (2 * sides[0] * sides[1])
        count += sides[2] > max_ratio * sides[0] or cosine < math.cos(math.radians(max_angle))
    return count


def test_remove_slivers_collapses_the_needles_of_a_uv_sphere():
    # 96 meridians and 32 parallels: the triangles next to the poles have sides 15 times
    # their shortest.
    sphere = _uv_sphere(96, 32)
    plain, report = trichart.prepare(sphere)
    needles = _slivers(plain)
    assert needles > 100 and "sliver" not in report

    clean, report = trichart.prepare(sphere, remove_slivers=True)
    print(report)
    left = _slivers(clean)
    assert f"found {needles} slivers" in report
    assert left < needles / 10 and (f"left {left} sliver" in report) == (left > 0)
    assert clean.GetNumberOfPoints() < plain.GetNumberOfPoints()
    # No point moved: every output point is where its input point was.
    input_ids = clean.GetPointData().GetArray(tcArrayNames.InputPointId())
    for i in range(clean.GetNumberOfPoints()):
        assert clean.GetPoint(i) == sphere.GetPoint(input_ids.GetValue(i))
    boundary = clean.GetPointData().GetArray(tcArrayNames.BoundaryVertex())
    assert max(boundary.GetValue(i) for i in range(boundary.GetNumberOfTuples())) == 0
    # A looser needle ratio leaves them.
    _, report = trichart.prepare(sphere, remove_slivers=True, sliver_edge_ratio=20.0)
    assert "sliver" not in report


def _sphere_and_stray_triangle():
    """A closed sphere and, far from it, a lone triangle: two components."""
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    from vtkmodules.vtkFiltersCore import vtkAppendPolyData
    from vtkmodules.vtkFiltersSources import vtkSphereSource
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(16)
    sphere.SetPhiResolution(8)
    points = vtkPoints()
    for p in ((5, 0, 0), (6, 0, 0), (5, 1, 0)):
        points.InsertNextPoint(p)
    cells = vtkCellArray()
    cells.InsertNextCell(3, (0, 1, 2))
    stray = vtkPolyData()
    stray.SetPoints(points)
    stray.SetPolys(cells)
    append = vtkAppendPolyData()
    append.AddInputConnection(sphere.GetOutputPort())
    append.AddInputData(stray)
    append.Update()
    return append.GetOutput()


def test_component_options_drop_the_stray_triangle_and_the_filter_counts_it():
    mesh = _sphere_and_stray_triangle()
    plain, report = trichart.prepare(mesh)
    assert "2 connected components" in report and "3 boundary edges" in report, report
    sphere_triangles = plain.GetNumberOfPolys() - 1
    for options in ({"keep_largest_component": True}, {"min_component_triangles": 2}):
        f = trichart.tcMeshPreparation()
        f.SetInputData(mesh)
        for name, value in options.items():
            getattr(f, "Set" + "".join(w.capitalize() for w in name.split("_")))(value)
        f.Update()
        clean = f.GetOutput()
        assert f.GetDroppedComponents() == 1 and f.GetDroppedComponentTriangles() == 1, options
        assert f.GetClosedManifold() and f.GetBoundaryEdges() == 0, f.GetReport()
        assert clean.GetNumberOfPolys() == sphere_triangles
        # The sphere's triangles keep their input cells, in order; the stray one is gone.
        cells = clean.GetCellData().GetArray(tcArrayNames.InputCellId())
        assert [cells.GetValue(i) for i in range(cells.GetNumberOfTuples())] == list(
            range(sphere_triangles))
        assert "dropped 3 points with the dropped components" in f.GetReport(), f.GetReport()
    _, report = trichart.prepare(mesh, keep_largest_component=True)
    assert ("dropped 1 component other than the largest, with 1 triangle in all "
            "(KeepLargestComponent)") in report, report
