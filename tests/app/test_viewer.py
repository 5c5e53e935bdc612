"""trichart-viewer --screenshot: one picture per stage, compared with its baseline; a missing
or corrupt file is reported on stderr and the viewer still produces its window (no crash)."""
import os
import pathlib
import subprocess

import pytest

from imagecompare import compare_with_baseline

VIEWER = os.environ["TRICHART_VIEWER"]
DATA = pathlib.Path(os.environ["TRICHART_TESTING_DATA"])


def viewer(*args):
    return subprocess.run([VIEWER, *map(str, args)], capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("stage", ["input", "preparation", "curvature", "clusters", "features",
                                   "base"])
def test_stage_screenshot_matches_baseline(stage, tmp_path):
    shot = tmp_path / f"TestViewer_{stage}.png"
    r = viewer(DATA / "meshes" / "bunny_npm.off", "--stage", stage, "--screenshot", shot)
    assert r.returncode == 0, r.stderr
    ok, detail = compare_with_baseline(shot, DATA / "baselines" / f"TestViewer_{stage}.png")
    assert ok, detail


@pytest.mark.parametrize("name,content", [("missing.off", None),
                                          ("corrupt.off", "OFF\n3 1 0\n0 0 0\nnot numbers\n")])
def test_bad_file_is_reported_not_fatal(name, content, tmp_path):
    mesh = tmp_path / name
    if content is not None:
        mesh.write_text(content)
    shot = tmp_path / "shot.png"
    r = viewer(mesh, "--screenshot", shot)
    assert r.returncode == 1
    assert "trichart-viewer: error:" in r.stderr and name in r.stderr
    assert shot.stat().st_size > 0  # the window was still drawn


def test_unknown_stage_is_refused():
    r = viewer(DATA / "meshes" / "cube.off", "--stage", "nonsense", "--screenshot", "x.png")
    assert r.returncode == 2 and "unknown stage" in r.stderr
