"""trichart-viewer in batch mode: one picture per stage compared with its baseline, the
reconstruction's error figures, the LOD stage's statistics (one bunny and a crowd), an atlas file
written by the viewer opened on its reconstruction and its LOD view, a skinned atlas posed at a
chosen time (a crowd at its own phases), and bad files and options (a missing or corrupt mesh or
atlas, an atlas saved where it cannot go, an animation the atlas lacks) reported on stderr while
the window stays usable (no crash)."""
import os
import pathlib
import re
import subprocess
import sys

import pytest

from imagecompare import compare_with_baseline, differing_pixels

VIEWER = os.environ["TRICHART_VIEWER"]
DATA = pathlib.Path(os.environ["TRICHART_TESTING_DATA"])
BUNNY = DATA / "meshes" / "bunny_npm.off"
STAGES = ["input", "preparation", "curvature", "clusters", "features", "base", "patches", "atlas",
          "reconstruction", "lod"]
CROWD = 16
SHARED = pathlib.Path(os.environ.get("TRICHART_SHARED_DATA", ""))
SNAKE = SHARED / "skinned" / "snake_fbx" / "snake_fbx.glb"
SNAKE_ANIMATION = "Armature|ArmatureAction"  # its only animation, 0.83 s long
WUSON = SHARED / "skinned" / "wuson" / "wuson.glb"


def viewer(*args):
    return subprocess.run([VIEWER, *map(str, args)], capture_output=True, text=True, timeout=300)


def summary(stdout, title):
    """The info text the viewer printed for the stage titled `title` (batch mode prints it)."""
    lines = [line for line in stdout.splitlines() if line.startswith(f"trichart-viewer: {title}")]
    assert lines, f"no '{title}' summary in {stdout!r}"
    return lines[-1]


def figures(text):
    """The numbers of a reconstruction's summary."""
    found = {"points": re.search(r"(\d+) points", text),
             "cells": re.search(r"(\d+) cells", text),
             "hausdorff": re.search(r"Hausdorff (\S+) \((\S+)% of the diagonal\)", text),
             "rms": re.search(r"RMS (\S+) \((\S+)%\)", text),
             "levels": re.search(r"Levels? (\d+)(?: to (\d+))?", text)}
    return {key: match.groups() for key, match in found.items() if match}


def lod_figures(stdout):
    """The numbers of the LOD stage's summary and the timings printed beside it."""
    text = summary(stdout, "Level of detail")
    found = {"charts": int(re.search(r"(\d+) charts x", text).group(1)),
             "instances": int(re.search(r"x (\d+) instances?", text).group(1)),
             "fps": re.search(r"fps (\S+)", text).group(1),
             "triangles": int(re.search(r"(\d+) triangles drawn", text).group(1)),
             "drawn": int(re.search(r"(\d+) charts drawn", text).group(1)),
             "levels": {int(level): int(count)
                        for level, count in re.findall(r"L(\d+) (\d+)", text)},
             "selection": re.search(r"LOD selection (\S+) ms", text).group(1)}
    timing = re.search(r"lod timing: LOD selection (\S+) ms", stdout)
    found["selection_ms"] = float(timing.group(1)) if timing else None
    return found


@pytest.fixture(scope="module")
def bunny(tmp_path_factory):
    """One viewer run over the bunny: every stage's picture (each framed as if shown alone) and
    its atlas saved as File > Save atlas does."""
    folder = tmp_path_factory.mktemp("bunny")
    atlas = folder / "bunny.exr"
    r = viewer(BUNNY, "--stage", ",".join(STAGES), "--screenshot", folder / "{stage}.png",
               "--save-atlas", atlas)
    return {"run": r, "folder": folder, "atlas": atlas}


@pytest.fixture(scope="module")
def crowd(tmp_path_factory):
    """The LOD stage of the bunny as a crowd of CROWD instances."""
    shot = tmp_path_factory.mktemp("crowd") / "crowd.png"
    return {"run": viewer(BUNNY, "--stage", "lod", "--instances", CROWD, "--screenshot", shot),
            "shot": shot}


@pytest.mark.parametrize("stage", STAGES)
def test_stage_screenshot_matches_baseline(stage, bunny):
    assert bunny["run"].returncode == 0, bunny["run"].stderr
    ok, detail = compare_with_baseline(bunny["folder"] / f"{stage}.png",
                                       DATA / "baselines" / f"TestViewer_{stage}.png")
    assert ok, detail


def test_single_stage_run_draws_the_same_picture(tmp_path):
    # The baselines come from one run over all stages; the reconstruction follows the atlas's
    # split view there, and must look as when it is shown alone.
    shot = tmp_path / "reconstruction.png"
    r = viewer(BUNNY, "--stage", "reconstruction", "--screenshot", shot)
    assert r.returncode == 0, r.stderr
    ok, detail = compare_with_baseline(shot, DATA / "baselines" / "TestViewer_reconstruction.png")
    assert ok, detail


def test_reconstruction_reports_its_distance_to_the_prepared_mesh(bunny):
    found = figures(summary(bunny["run"].stdout, "Reconstruction"))
    print("bunny reconstruction:", found)
    hausdorff, hausdorff_percent = map(float, found["hausdorff"])
    rms, rms_percent = map(float, found["rms"])
    assert 0 < rms < hausdorff
    # Every chart at its finest level stays within a fraction of a percent of the surface.
    assert rms_percent < 0.5 and hausdorff_percent < 5
    assert int(found["points"][0]) > 1000


def test_atlas_file_opens_on_its_reconstruction(bunny, tmp_path):
    assert bunny["atlas"].stat().st_size > 0
    shot = tmp_path / "reconstruction.png"
    r = viewer(bunny["atlas"], "--stage", "reconstruction", "--screenshot", shot)
    assert r.returncode == 0, r.stderr
    # The same mesh as the pipeline's reconstruction, without distance (no input mesh).
    read = figures(summary(r.stdout, "Reconstruction"))
    built = figures(summary(bunny["run"].stdout, "Reconstruction"))
    assert read["points"] == built["points"] and read["levels"] == built["levels"]
    assert "hausdorff" not in read and "no input mesh" in r.stdout
    ok, detail = compare_with_baseline(
        shot, DATA / "baselines" / "TestViewer_reconstruction_atlasfile.png")
    assert ok, detail


def test_atlas_file_has_no_stages_before_the_atlas(bunny, tmp_path):
    # Asked for a mesh stage, an atlas file still opens on its reconstruction ...
    r = viewer(bunny["atlas"], "--stage", "curvature", "--screenshot", tmp_path / "shot.png")
    assert r.returncode == 0, r.stderr
    assert "Reconstruction" in r.stdout and "Curvature" not in r.stdout
    # ... and refuses to go back to one.
    r = viewer(bunny["atlas"], "--stage", "reconstruction,curvature", "--screenshot",
               tmp_path / "{stage}.png")
    assert r.returncode == 1 and "needs an input mesh" in r.stderr, r.stderr


def test_level_zero_of_an_atlas_is_its_base_complex(bunny, tmp_path):
    atlas = viewer(bunny["atlas"], "--stage", "atlas", "--screenshot", tmp_path / "atlas.png")
    assert atlas.returncode == 0, atlas.stderr
    charts = int(re.search(r"(\d+) charts", atlas.stdout).group(1))
    r = viewer(bunny["atlas"], "--stage", "reconstruction", "--level", "0", "--screenshot",
               tmp_path / "level0.png")
    assert r.returncode == 0, r.stderr
    # At level 0 every chart is one triangle between its three base vertices: a closed mesh
    # of genus 0 (the bunny), so V - E + F = 2 with E = 3F / 2.
    found = figures(summary(r.stdout, "Reconstruction"))
    assert int(found["cells"][0]) == charts and found["levels"] == ("0", None)
    assert int(found["points"][0]) - 3 * charts // 2 + charts == 2


def corrupt_atlases(atlas):
    """A truncated atlas (a write that stopped half-way) and text that only claims to be one."""
    data = atlas.read_bytes()
    return [("truncated.exr", data[: len(data) // 2]), ("text.exr", b"not an atlas\n" * 10)]


@pytest.mark.parametrize("which", [0, 1])
def test_corrupt_atlas_is_reported_and_the_viewer_stays_usable(which, bunny, tmp_path):
    name, content = corrupt_atlases(bunny["atlas"])[which]
    bad = tmp_path / name
    bad.write_bytes(content)
    shot = tmp_path / "reconstruction.png"
    # The bad file first, then the good one in the same window.
    r = viewer(bad, bunny["atlas"], "--stage", "reconstruction", "--screenshot", shot)
    assert r.returncode == 1
    assert "trichart-viewer: error:" in r.stderr and name in r.stderr, r.stderr
    ok, detail = compare_with_baseline(
        shot, DATA / "baselines" / "TestViewer_reconstruction_atlasfile.png")
    assert ok, detail


def test_an_opened_atlas_saved_again_is_the_same_file(bunny, tmp_path):
    again = tmp_path / "again.exr"
    r = viewer(bunny["atlas"], "--save-atlas", again)
    assert r.returncode == 0, r.stderr
    assert again.read_bytes() == bunny["atlas"].read_bytes()


def test_saving_the_atlas_where_it_cannot_go_is_reported(bunny, tmp_path):
    target = tmp_path / "no-such-folder" / "bunny.exr"
    r = viewer(bunny["atlas"], "--save-atlas", target)
    assert r.returncode == 1
    assert "trichart-viewer: error:" in r.stderr and "no-such-folder" in r.stderr, r.stderr
    assert not target.exists()


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


@pytest.mark.parametrize("stage", ["nonsense", "base,nonsense"])
def test_unknown_stage_is_refused(stage):
    r = viewer(DATA / "meshes" / "cube.off", "--stage", stage, "--screenshot", "x{stage}.png")
    assert r.returncode == 2 and "unknown stage 'nonsense'" in r.stderr
    assert "reconstruction" in r.stderr  # the list of names


def test_several_stages_need_a_file_name_pattern():
    r = viewer(DATA / "meshes" / "cube.off", "--stage", "input,base", "--screenshot", "x.png")
    assert r.returncode == 2 and "{stage}" in r.stderr


def test_lod_statistics_describe_the_frame(bunny):
    lod = lod_figures(bunny["run"].stdout)
    print("bunny lod:", lod)
    atlas = summary(bunny["run"].stdout, "Geometry-image atlas")
    assert lod["charts"] == int(re.search(r"(\d+) charts", atlas).group(1))
    # Framed whole, every chart is in view and drawn once.
    assert lod["instances"] == 1 and lod["drawn"] == lod["charts"]
    assert sum(lod["levels"].values()) == lod["drawn"]
    # A chart at level n is a grid of 4^n triangles.
    assert lod["triangles"] == sum(count * 4 ** level for level, count in lod["levels"].items())
    # Timings vary from run to run: the picture shows "-", stdout the figure.
    assert lod["fps"] == "-" and lod["selection"] == "-"
    assert lod["selection_ms"] is not None and lod["selection_ms"] > 0


def test_lod_crowd_screenshot_matches_baseline(crowd):
    assert crowd["run"].returncode == 0, crowd["run"].stderr
    ok, detail = compare_with_baseline(crowd["shot"],
                                       DATA / "baselines" / "TestViewer_lod_crowd.png")
    assert ok, detail


def test_lod_crowd_draws_every_instance_coarser(bunny, crowd):
    one, many = lod_figures(bunny["run"].stdout), lod_figures(crowd["run"].stdout)
    print("bunny lod crowd:", many)
    assert many["instances"] == CROWD and many["charts"] == one["charts"]
    assert many["drawn"] == CROWD * one["charts"]
    assert sum(many["levels"].values()) == many["drawn"]
    assert many["triangles"] == sum(count * 4 ** level for level, count in many["levels"].items())
    # Framed whole, the crowd is farther away: its charts take coarser levels on average than
    # the bunny framed alone, and it draws fewer than CROWD bunnies at that bunny's levels.
    def mean_level(f):
        return sum(level * count for level, count in f["levels"].items()) / f["drawn"]
    assert mean_level(many) < mean_level(one) - 0.5
    assert many["triangles"] < CROWD * one["triangles"]


def test_atlas_file_shows_the_same_lod_view(bunny, crowd, tmp_path):
    for run, instances in ((bunny["run"], 1), (crowd["run"], CROWD)):
        r = viewer(bunny["atlas"], "--stage", "lod", "--instances", instances, "--screenshot",
                   tmp_path / f"lod{instances}.png")
        assert r.returncode == 0, r.stderr
        # The same atlas seen the same way: the same levels, chart for chart.
        read, built = lod_figures(r.stdout), lod_figures(run.stdout)
        for key in ("charts", "instances", "triangles", "drawn", "levels"):
            assert read[key] == built[key], key


def test_lod_stage_leaves_the_other_stages_camera_alone(bunny, tmp_path):
    # The LOD stage flies its own camera: the reconstruction shown after it is framed as alone.
    r = viewer(bunny["atlas"], "--stage", "lod,reconstruction", "--instances", CROWD,
               "--screenshot", tmp_path / "{stage}.png")
    assert r.returncode == 0, r.stderr
    ok, detail = compare_with_baseline(
        tmp_path / "reconstruction.png",
        DATA / "baselines" / "TestViewer_reconstruction_atlasfile.png")
    assert ok, detail


@pytest.mark.parametrize("instances", ["0", "2501", "many"])
def test_bad_instance_count_is_refused(instances):
    r = viewer(DATA / "meshes" / "cube.off", "--stage", "lod", "--instances", instances,
               "--screenshot", "x.png")
    assert r.returncode == 2 and "--instances" in r.stderr


def test_untraceable_paths_are_built_again_without_slivers(tmp_path):
    # couplingdown's CAD needles make its paths untraceable as prepared by default: the viewer,
    # like `trichart build`, turns RemoveSlivers on, runs again and says so in the summary.
    shared = pathlib.Path(os.environ.get("TRICHART_SHARED_DATA", ""))
    mesh = shared / "cad" / "couplingdown.off"
    if not mesh.is_file():
        pytest.skip(f"{mesh} is absent (../shared/data not beside the checkout)")
    r = viewer(mesh, "--stage", "patches,reconstruction", "--screenshot", tmp_path / "{stage}.png")
    assert r.returncode == 0, r.stderr
    for title in ("Triangle patches", "Reconstruction"):
        text = summary(r.stdout, title)
        assert "Note: The paths could not be traced (input triangle" in text, text
        assert "built again with RemoveSlivers on" in text, text
    assert re.search(r"(\d+) patches", summary(r.stdout, "Triangle patches"))
    assert (tmp_path / "reconstruction.png").stat().st_size > 0
    # A mesh that traces as it is gets no note.
    r = viewer(BUNNY, "--stage", "patches", "--screenshot", tmp_path / "bunny.png")
    assert r.returncode == 0 and "Note:" not in r.stdout, r.stdout


def test_preparation_says_what_to_check_for_a_surface_the_base_complex_refuses(tmp_path):
    # The bundled bunny with one triangle taken out: a hole of 3 boundary edges.
    lines = BUNNY.read_text().split("\n")
    points, faces = map(int, lines[1].split()[:2])
    lines[1] = f"{points} {faces - 1} 0"
    del lines[2 + points]
    mesh = tmp_path / "holed.off"
    mesh.write_text("\n".join(lines))
    r = viewer(mesh, "--stage", "preparation", "--screenshot", tmp_path / "p.png")
    assert r.returncode == 0, r.stderr
    text = summary(r.stdout, "Preparation")
    assert "Not a closed, oriented manifold" in text, text
    assert "3 boundary edges (close the holes: FillHoles" in text, text
    # The bunny as it is needs nothing.
    r = viewer(BUNNY, "--stage", "preparation", "--screenshot", tmp_path / "b.png")
    assert "Not a closed" not in summary(r.stdout, "Preparation")


def test_cad_creases_are_drawn_sharp(tmp_path):
    # fandisk's stages carry normals fitted across its creases; the viewer splits them at 45
    # degrees, so flat faces are evenly lit up to their edges (the baseline), with no dark band.
    shot = tmp_path / "fandisk.png"
    r = viewer(DATA / "meshes" / "fandisk.off", "--stage", "patches", "--screenshot", shot)
    assert r.returncode == 0, r.stderr
    baseline = DATA / "baselines" / "TestViewer_patches_fandisk.png"
    ok, detail = compare_with_baseline(shot, baseline)
    assert ok, detail
    # Shading fitted across the creases differs from the baseline by over 20 levels at 8340
    # pixels, which vtkImageDifference's threshold lets through.
    assert differing_pixels(shot, baseline, 20) < 1000


@pytest.mark.parametrize("mesh,stage", [("cad/rotor.off", "features"),
                                        ("static_small/homer.off", "base")])
def test_iso_view_screenshots_of_shared_meshes(tmp_path, mesh, stage):
    # A CAD part seen from the front is edge-on; --view iso looks from the +X+Y+Z corner.
    path = pathlib.Path(os.environ.get("TRICHART_SHARED_DATA", "")) / mesh
    if not path.is_file():
        pytest.skip(f"{path} is absent (../shared/data not beside the checkout)")
    shot = tmp_path / "iso.png"
    r = viewer(path, "--stage", stage, "--view", "iso", "--screenshot", shot)
    assert r.returncode == 0, r.stderr
    name = pathlib.Path(mesh).name.split(".")[0]
    ok, detail = compare_with_baseline(shot, DATA / "baselines" / f"TestViewer_{stage}_{name}_iso.png")
    assert ok, detail
    # The turns and zoom move the picture; the default view is the front one.
    turned = tmp_path / "turned.png"
    r = viewer(path, "--stage", stage, "--view", "iso", "--azimuth", "40", "--elevation", "-20",
               "--zoom", "1.5", "--screenshot", turned)
    assert r.returncode == 0, r.stderr
    assert differing_pixels(shot, turned, 20) > 10000


@pytest.mark.parametrize("option,value", [("--view", "diagonal"), ("--azimuth", "x"),
                                          ("--elevation", "120"), ("--zoom", "0"),
                                          ("--zoom", "nan")])
def test_bad_camera_options_are_refused(option, value):
    r = viewer(BUNNY, option, value, "--screenshot", "x.png")
    assert r.returncode == 2 and option in r.stderr, r.stderr


def test_a_textured_mesh_is_shown_textured(tmp_path):
    # The input stage of a textured mesh opens coloured by its texture, and --array Texture
    # colours the reconstruction and the LOD view by the atlas's copy of it: the checker's
    # saturated hues show (an untextured sphere is grey).
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader

    sphere = DATA / "meshes" / "textured_sphere.glb"
    r = viewer(sphere, "--stage", "input", "--screenshot", tmp_path / "input.png")
    assert r.returncode == 0, r.stderr
    r = viewer(sphere, "--stage", "reconstruction,lod", "--array", "Texture", "--screenshot",
               tmp_path / "{stage}.png")
    assert r.returncode == 0, r.stderr
    for name in ("input", "reconstruction", "lod"):
        reader = vtkPNGReader()
        reader.SetFileName(str(tmp_path / f"{name}.png"))
        reader.Update()
        rgb = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)
        # Saturated pixels by the channels above half their brightest: the front of the sphere
        # shows the checker's cyan, blue and magenta columns.
        brightest = rgb.max(axis=1)
        saturated = brightest - rgb.min(axis=1) > 80
        high = rgb > brightest[:, None] // 2
        for hue in ((0, 1, 1), (0, 0, 1), (1, 0, 1)):
            count = int((saturated & (high == numpy.array(hue, bool)).all(axis=1)).sum())
            assert count > 2000, (name, hue, count)


def test_export_gltf_writes_the_lod_chain_of_the_open_mesh(tmp_path):
    # As File > Export LOD chain as glTF: the textured sphere's chain, its texture embedded;
    # a name that is not glTF is refused and nothing is written.
    out = tmp_path / "sphere.glb"
    r = viewer(DATA / "meshes" / "textured_sphere.glb", "--stage", "atlas", "--export-gltf", out)
    assert r.returncode == 0, r.stderr
    data = out.read_bytes()
    assert data[:4] == b"glTF"
    import json
    import struct
    gltf = json.loads(data[20:20 + struct.unpack_from("<I", data, 12)[0]])
    assert len(gltf["meshes"]) >= 2 and gltf["images"][0]["mimeType"] == "image/png"
    bad = tmp_path / "sphere.obj"
    r = viewer(DATA / "meshes" / "textured_sphere.glb", "--stage", "atlas", "--export-gltf", bad)
    assert r.returncode != 0 and ".glb" in r.stderr, r.stderr
    assert not bad.exists()


def build_skinned(tmp_path_factory, mesh, *options):
    """The atlas of a skinned mesh of ../shared/data, built by `trichart build`."""
    if not mesh.is_file():
        pytest.skip(f"{mesh} is absent (../shared/data not beside the checkout)")
    atlas = tmp_path_factory.mktemp(mesh.stem) / f"{mesh.stem}.exr"
    r = subprocess.run([sys.executable, "-m", "trichart", "build", mesh, "-o", atlas, "-q",
                        *options], capture_output=True, text=True, timeout=300)
    if "No module named trichart" in r.stderr:
        pytest.skip("the trichart package is not built (TRICHART_WRAP_PYTHON off)")
    assert r.returncode == 0, r.stderr
    return atlas


@pytest.fixture(scope="module")
def snake(tmp_path_factory):
    """The skinned snake's atlas (a rig of 17 joints, one animation of 0.83 s)."""
    return build_skinned(tmp_path_factory, SNAKE)


@pytest.fixture(scope="module")
def wuson(tmp_path_factory):
    """The skinned wuson's atlas (three animations: Wuson_Run, Wuson_Walk, Wuson_Bind)."""
    return build_skinned(tmp_path_factory, WUSON, "--fill-holes", "--split-non-manifold")


def posed_lod(atlas, shot, *args):
    """The LOD stage of `atlas` saved as `shot`, with the summary's pose line."""
    r = viewer(atlas, "--stage", "lod", "--screenshot", shot, *args)
    assert r.returncode == 0, r.stderr
    return re.search(r"animation '(.*)' at (\S+) s of (\S+) s(, own phases|, in step)?",
                     summary(r.stdout, "Level of detail"))


def test_skinned_atlas_moves_with_the_time(snake, tmp_path):
    start = posed_lod(snake, tmp_path / "start.png")
    later = posed_lod(snake, tmp_path / "later.png", "--time", "0.4", "--animation", "0")
    # Without --time, the first animation at 0; the index names the same animation.
    assert start.groups()[:3] == (SNAKE_ANIMATION, "0.00", "0.83"), start.group(0)
    assert later.groups()[:3] == (SNAKE_ANIMATION, "0.40", "0.83"), later.group(0)
    # The snake bends: thousands of pixels change between the two poses.
    moved = differing_pixels(tmp_path / "start.png", tmp_path / "later.png", 20)
    print("snake pixels moved between 0 s and 0.4 s:", moved)
    assert moved > 2000


@pytest.mark.parametrize("args,message", [
    (["--animation", "walk"], "there is no animation 'walk'; the animations are "
                              f"'{SNAKE_ANIMATION}' (0)"),
    (["--animation", "1"], "there is no animation '1'"),
    (["--time", "5"], f"the time 5 s is past the end of the animation '{SNAKE_ANIMATION}'")])
def test_a_pose_the_atlas_lacks_is_reported(snake, tmp_path, args, message):
    r = viewer(snake, "--stage", "lod", "--screenshot", tmp_path / "shot.png", *args)
    assert r.returncode == 1, r.stderr
    assert "trichart-viewer: error: Cannot pose snake_fbx.exr as asked: " + message in r.stderr, \
        r.stderr


def test_a_pose_of_an_atlas_without_a_rig_is_reported(bunny, tmp_path):
    r = viewer(bunny["atlas"], "--stage", "lod", "--time", "0.5", "--screenshot",
               tmp_path / "shot.png")
    assert r.returncode == 1 and "the atlas has no animation" in r.stderr, r.stderr


@pytest.mark.parametrize("time", ["-1", "soon", "nan"])
def test_bad_time_is_refused(time):
    r = viewer(BUNNY, "--stage", "lod", "--time", time, "--screenshot", "x.png")
    assert r.returncode == 2 and "--time" in r.stderr, r.stderr


def test_posed_crowd_matches_baseline(wuson, tmp_path):
    # Nine wusons walking, each at 0.5 s plus its own phase: no two in step. By name: the rig has
    # three animations, Wuson_Walk the second.
    shot = tmp_path / "crowd.png"
    pose = posed_lod(wuson, shot, "--instances", "9", "--animation", "Wuson_Walk", "--time", "0.5")
    assert pose.groups() == ("Wuson_Walk", "0.50", "3.60", ", own phases"), pose.group(0)
    ok, detail = compare_with_baseline(shot, DATA / "baselines" / "TestViewer_lod_wuson_crowd.png")
    assert ok, detail
