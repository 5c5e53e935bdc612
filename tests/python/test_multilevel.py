"""tcMultilevelMesh from Python (trichart.multilevel_mesh): the levels of the bundled bunny,
their parents and clusters, the ClusterId<k> arrays of the finest level, the options, and a clear
error for a bad branching factor or a non-triangle input."""
import pytest
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet

import trichart
from trichart import tcArrayNames
from trichart.pipeline import TriChartError


@pytest.fixture(scope="module")
def bunny(testing_data):
    return trichart.read_mesh(testing_data / "meshes" / "bunny_npm.off")


def point_values(mesh, name):
    array = mesh.GetPointData().GetArray(name)
    assert array is not None, f"no point array {name}"
    assert array.GetNumberOfTuples() == mesh.GetNumberOfPoints()
    return [int(array.GetTuple1(i)) for i in range(array.GetNumberOfTuples())]


def test_levels_shrink_by_the_branching_factor(bunny):
    levels = trichart.multilevel_mesh(bunny)
    n = levels.GetNumberOfBlocks()
    assert n >= 3
    sizes = [levels.GetBlock(k).GetNumberOfPoints() for k in range(n)]
    assert sizes[0] == bunny.GetNumberOfPoints()
    for finer, coarser in zip(sizes, sizes[1:]):
        assert coarser == pytest.approx(finer / 8, rel=0.05)
    for k in range(n):
        name = levels.GetMetaData(k).Get(vtkCompositeDataSet.NAME())
        assert name == tcArrayNames.LevelBlockPrefix() + str(k)
        assert levels.GetBlock(k).GetNumberOfPolys() > 0


def test_parents_and_cluster_sizes_agree(bunny):
    levels = trichart.multilevel_mesh(bunny)
    n = levels.GetNumberOfBlocks()
    for k in range(n):
        level = levels.GetBlock(k)
        parents = point_values(level, tcArrayNames.ParentId())
        sizes = point_values(level, tcArrayNames.ClusterSize())
        assert sum(sizes) == bunny.GetNumberOfPoints()
        if k + 1 == n:
            assert set(parents) == {-1}
            continue
        above = levels.GetBlock(k + 1)
        assert set(parents) == set(range(above.GetNumberOfPoints()))  # every parent has a child
        summed = [0] * above.GetNumberOfPoints()
        for v, p in enumerate(parents):
            summed[p] += sizes[v]
        assert summed == point_values(above, tcArrayNames.ClusterSize())


def test_finest_level_maps_every_vertex_to_its_cluster(bunny):
    levels = trichart.multilevel_mesh(bunny)
    finest = levels.GetBlock(0)
    assert finest.GetNumberOfPolys() == bunny.GetNumberOfPolys()
    cluster = list(range(finest.GetNumberOfPoints()))
    for k in range(1, levels.GetNumberOfBlocks()):
        parents = point_values(levels.GetBlock(k - 1), tcArrayNames.ParentId())
        cluster = [parents[c] for c in cluster]
        assert point_values(finest, tcArrayNames.LevelClusterIdPrefix() + str(k)) == cluster
    assert finest.GetPointData().GetArray(
        tcArrayNames.LevelClusterIdPrefix() + str(levels.GetNumberOfBlocks())) is None


def test_options_reach_the_core(bunny):
    levels = trichart.multilevel_mesh(bunny, branching_factor=4, max_levels=2,
                                      link_condition=False)
    assert levels.GetNumberOfBlocks() == 3
    sizes = [levels.GetBlock(k).GetNumberOfPoints() for k in range(3)]
    assert sizes[1] == round(sizes[0] / 4) and sizes[2] == round(sizes[1] / 4)
    few = trichart.multilevel_mesh(bunny, coarsest_vertices=200)
    assert few.GetNumberOfBlocks() == 2  # 230 vertices, then 29 < 200 is not built


def test_progress_is_reported(bunny):
    seen = []
    trichart.multilevel_mesh(bunny, progress=lambda label, f: seen.append((label, f)))
    assert seen and seen[-1] == ("multilevel", 1.0)


def test_a_non_triangle_input_is_refused(tmp_path):
    (tmp_path / "quad.off").write_text("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")
    with pytest.raises(TriChartError, match="multilevel.*triangles"):
        trichart.multilevel_mesh(trichart.read_mesh(tmp_path / "quad.off"))


def test_a_non_manifold_input_needs_the_link_condition_off(tmp_path):
    # Two tetrahedra sharing vertex 0.
    (tmp_path / "pinched.off").write_text(
        "OFF\n7 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n-1 0 0\n0 -1 0\n0 0 -1\n"
        "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 5 4\n3 0 4 6\n3 0 6 5\n3 4 5 6\n")
    mesh = trichart.read_mesh(tmp_path / "pinched.off")
    with pytest.raises(TriChartError, match="link condition"):
        trichart.multilevel_mesh(mesh, coarsest_vertices=1)
    levels = trichart.multilevel_mesh(mesh, coarsest_vertices=1, link_condition=False)
    assert levels.GetNumberOfBlocks() >= 2
