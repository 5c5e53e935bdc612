"""Spectral clustering and feature refinement from Python: arrays, determinism, options,
errors, and the feature outputs on the bundled fandisk."""
import pytest

import trichart
from trichart import tcArrayNames
from trichart.pipeline import TriChartError


@pytest.fixture(scope="module")
def fandisk_curvature():
    import os
    import pathlib

    data = pathlib.Path(os.environ.get("TRICHART_TESTING_DATA",
                                       pathlib.Path(__file__).parents[2] / "testing-data"))
    clean, _ = trichart.prepare(trichart.read_mesh(data / "meshes" / "fandisk.off"))
    surface, _ = trichart.curvature(clean)
    return surface


def values(array):
    return [array.GetTuple1(i) for i in range(array.GetNumberOfTuples())]


def test_every_face_gets_a_cluster_and_runs_are_identical(fandisk_curvature):
    a, boundaries = trichart.cluster(fandisk_curvature, number_of_clusters=12)
    b, _ = trichart.cluster(fandisk_curvature, number_of_clusters=12)
    ids = values(a.GetCellData().GetArray(tcArrayNames.ClusterId()))
    assert len(ids) == fandisk_curvature.GetNumberOfPolys()
    assert set(ids) == set(range(12))
    assert ids == values(b.GetCellData().GetArray(tcArrayNames.ClusterId()))
    eigenvalues = values(a.GetFieldData().GetArray(tcArrayNames.Eigenvalues()))
    assert eigenvalues == sorted(eigenvalues, reverse=True)
    assert boundaries.GetNumberOfLines() > 0


def test_features_lines_and_corners(fandisk_curvature):
    clustered, _ = trichart.cluster(fandisk_curvature, number_of_clusters=12)
    features, lines, corners = trichart.refine_features(clustered)
    flags = values(features.GetPointData().GetArray(tcArrayNames.FeatureVertex()))
    assert lines.GetNumberOfLines() > 0 and sum(flags) > 0
    # Every point of a feature line is flagged on the mesh, through InputPointId.
    ids = lines.GetPointData().GetArray(tcArrayNames.InputPointId())
    assert all(flags[int(ids.GetTuple1(i))] == 1 for i in range(ids.GetNumberOfTuples()))
    corner_flags = values(features.GetPointData().GetArray(tcArrayNames.CornerVertex()))
    assert corners.GetNumberOfPoints() == sum(corner_flags) > 0
    assert lines.GetCellData().GetArray(tcArrayNames.MeanAbsCurvature()) is not None


def test_a_stricter_threshold_keeps_fewer_lines(fandisk_curvature):
    clustered, _ = trichart.cluster(fandisk_curvature, number_of_clusters=12)
    _, lines, _ = trichart.refine_features(clustered)
    _, strict, _ = trichart.refine_features(clustered, curvature_threshold_scale=3.0)
    assert strict.GetNumberOfLines() < lines.GetNumberOfLines()


def test_clustering_needs_curvature(testing_data):
    clean, _ = trichart.prepare(trichart.read_mesh(testing_data / "meshes" / "cube.off"))
    with pytest.raises(TriChartError, match="tcCurvature"):
        trichart.cluster(clean)


def test_refinement_needs_clusters(fandisk_curvature):
    with pytest.raises(TriChartError, match=tcArrayNames.ClusterId()):
        trichart.refine_features(fandisk_curvature)


def test_normal_sigma_reaches_the_clustering(fandisk_curvature):
    plain, _ = trichart.cluster(fandisk_curvature, number_of_clusters=12)
    creased, _ = trichart.cluster(fandisk_curvature, number_of_clusters=12, normal_sigma=0.05)
    assert (values(plain.GetCellData().GetArray(tcArrayNames.ClusterId()))
            != values(creased.GetCellData().GetArray(tcArrayNames.ClusterId())))
