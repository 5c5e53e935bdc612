"""tcBaseComplex from Python: the base complex over the bundled meshes after the feature
stages, its target control, and a clear error for an open mesh."""
import pytest

import trichart
from trichart import tcArrayNames
from trichart.pipeline import TriChartError


def features_of(path, clusters=12):
    clean, _ = trichart.prepare(trichart.read_mesh(path))
    surface, _ = trichart.curvature(clean)
    clustered, _ = trichart.cluster(surface, number_of_clusters=clusters)
    features, _, _ = trichart.refine_features(clustered)
    return features


def test_every_vertex_is_parameterized(testing_data):
    features = features_of(testing_data / "meshes" / "fandisk.off")
    base, parameterized = trichart.base_complex(features, target_faces=200)
    faces = parameterized.GetPointData().GetArray(tcArrayNames.BaseFaceId())
    bary = parameterized.GetPointData().GetArray(tcArrayNames.BaseBarycentric())
    assert faces.GetNumberOfTuples() == features.GetNumberOfPoints()
    assert bary.GetNumberOfComponents() == 3
    n = base.GetNumberOfPolys()
    for v in range(faces.GetNumberOfTuples()):
        assert 0 <= faces.GetTuple1(v) < n
        assert sum(bary.GetTuple3(v)) == pytest.approx(1.0, abs=1e-9)
    ids = base.GetPointData().GetArray(tcArrayNames.InputPointId())
    assert ids.GetNumberOfTuples() == base.GetNumberOfPoints()


def test_a_lower_target_gives_a_coarser_base(testing_data):
    features = features_of(testing_data / "meshes" / "bunny_npm.off")
    fine, _ = trichart.base_complex(features, target_faces=1000)
    coarse, _ = trichart.base_complex(features, target_faces=100)
    assert coarse.GetNumberOfPolys() < fine.GetNumberOfPolys() <= 1000


def test_cube_corners_stay(testing_data):
    features = features_of(testing_data / "meshes" / "cube.off", clusters=6)
    base, _ = trichart.base_complex(features, target_faces=4)
    assert base.GetNumberOfPoints() == 8 and base.GetNumberOfPolys() == 12


def test_an_open_mesh_is_refused_with_a_reason(tmp_path):
    (tmp_path / "open.off").write_text(
        "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")
    mesh, _ = trichart.prepare(trichart.read_mesh(tmp_path / "open.off"))
    with pytest.raises(TriChartError, match="base complex"):
        trichart.base_complex(mesh)


def test_max_error_stops_the_simplification_before_the_target(testing_data):
    # Down to 20 faces fandisk's features stop at 68 (MaxError 0: the count alone decides).
    # The default bound (1e-4 of the squared diagonal) stops at 198, a looser one in between;
    # never above one face per 32 input points (6475 / 32 = 202).
    features = features_of(testing_data / "meshes" / "fandisk.off")
    counts = {}
    for bound in (0.0, 1e-3, None):
        options = {} if bound is None else {"max_error": bound}
        base, _ = trichart.base_complex(features, target_faces=20, **options)
        counts[bound] = base.GetNumberOfPolys()
    print(counts)
    assert counts[0.0] < counts[1e-3] < counts[None] <= features.GetNumberOfPoints() // 32
    f = trichart.pipeline.TriChartBaseComplex.tcBaseComplex()
    assert f.GetMaxError() == 1e-4
    f.SetMaxError(-1.0)
    assert f.GetMaxError() == 0.0
