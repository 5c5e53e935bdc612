import os
import pathlib

import pytest


@pytest.fixture(scope="session")
def testing_data():
    return pathlib.Path(os.environ.get("TRICHART_TESTING_DATA",
                                       pathlib.Path(__file__).parents[2] / "testing-data"))


@pytest.fixture
def shared_data():
    path = pathlib.Path(os.environ.get("TRICHART_SHARED_DATA",
                                       pathlib.Path(__file__).parents[3] / "shared" / "data"))
    if not path.is_dir():
        pytest.skip(f"{path} is absent (../shared/data not beside the checkout)")
    return path


@pytest.fixture(scope="module")
def bunny_stages():
    """The static pipeline on the bundled bunny, every stage's output by name (the atlas
    resamples MeanCurvature)."""
    import trichart
    from trichart import tcArrayNames

    data = pathlib.Path(os.environ.get("TRICHART_TESTING_DATA",
                                       pathlib.Path(__file__).parents[2] / "testing-data"))
    clean, _ = trichart.prepare(trichart.read_mesh(data / "meshes" / "bunny_npm.off"))
    surface, _ = trichart.curvature(clean)
    clusters, _ = trichart.cluster(surface)
    features, _, _ = trichart.refine_features(clusters)
    base, parameterized = trichart.base_complex(features)
    patches, paths = trichart.trace_paths(parameterized)
    atlas = trichart.geometry_images(patches, resampled_arrays=[tcArrayNames.MeanCurvature()])
    return {"clean": clean, "base": base, "patches": patches, "paths": paths, "atlas": atlas}
