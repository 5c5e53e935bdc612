import os
import pathlib

import pytest


@pytest.fixture
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
