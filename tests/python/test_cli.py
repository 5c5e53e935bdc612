"""The `trichart` command line (python3 -m trichart)."""
import math
import os
import subprocess
import sys

import pytest


def run(*args, **kwargs):
    return subprocess.run([sys.executable, "-m", "trichart", *map(str, args)],
                          capture_output=True, text=True, timeout=300, **kwargs)


def test_info_prints_versions_and_plugin():
    r = run("info")
    assert r.returncode == 0, r.stderr
    assert "TriChart" in r.stdout and "VTK 9." in r.stdout
    assert "build)" in r.stdout and "ParaView plugin" in r.stdout


def test_build_writes_the_atlas_stages_and_pictures(testing_data, tmp_path):
    atlas = tmp_path / "bunny.exr"
    r = run("build", testing_data / "meshes" / "bunny_npm.off", "-o", atlas,
            "--stages", tmp_path / "stages")
    assert r.returncode == 0, r.stderr
    for name in ("prepared.vtp", "curvature.vtp", "crest_lines.vtp", "clusters.vtp",
                 "features.vtp", "feature_lines.vtp", "corners.vtp", "base_complex.vtp",
                 "parameterized.vtp", "patches.vtp", "paths.vtp", "rebuilt.vtp",
                 "curvature.png", "features.png", "base_complex.png"):
        assert (tmp_path / "stages" / name).stat().st_size > 0, name
    assert "3674 triangles" in r.stdout and "charts up to level" in r.stdout
    assert "bytes per input triangle" in r.stdout
    with open(atlas, "rb") as f:
        assert f.read(4) == b"\x76\x2f\x31\x01"  # the OpenEXR magic number
    with open(tmp_path / "stages" / "curvature.png", "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"


def test_mesh_and_eval_read_the_atlas(testing_data, tmp_path):
    atlas = tmp_path / "cube.exr"
    r = run("build", testing_data / "meshes" / "cube.off", "-o", atlas, "--clusters", "6", "-q")
    assert r.returncode == 0, r.stderr
    r = run("mesh", atlas, "--level", "1", "-o", tmp_path / "level1.vtp")
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "level1.vtp").stat().st_size > 0
    r = run("eval", testing_data / "meshes" / "cube.off", atlas)
    assert r.returncode == 0, r.stderr
    rows = [line.split() for line in r.stdout.splitlines()
            if line.split() and line.split()[0].isdigit()]
    assert len(rows) >= 2, r.stdout
    # A cube is flat between its feature edges: every level rebuilds it almost exactly.
    for row in rows:
        assert float(row[5].rstrip("%")) < 0.1, r.stdout


def test_a_corrupt_atlas_is_refused(testing_data, tmp_path):
    atlas = tmp_path / "cube.exr"
    r = run("build", testing_data / "meshes" / "cube.off", "-o", atlas, "--clusters", "6", "-q")
    assert r.returncode == 0, r.stderr
    data = atlas.read_bytes()
    atlas.write_bytes(data[: len(data) // 2])
    r = run("mesh", atlas, "-o", tmp_path / "out.vtp")
    assert r.returncode == 2
    assert "trichart: error:" in r.stderr and "cube.exr" in r.stderr
    assert not (tmp_path / "out.vtp").exists()


def test_build_shows_progress(testing_data, tmp_path):
    r = run("build", testing_data / "meshes" / "cube.off", "-o", tmp_path / "cube.exr",
            "--clusters", "6")
    assert r.returncode == 0, r.stderr
    for stage in ("curvature", "clusters", "features", "base", "paths", "images"):
        assert f"{stage}: 100%" in r.stderr


@pytest.mark.parametrize("content,message", [
    (None, "does not exist"),
    ("", "bad.off"),
    # The file and line where it went wrong.
    ("OFF\n3 1 0\n0 0 0\n1 0 0\n", "bad.off:4: the file ends after 2 of 3 vertices"),
])
def test_bad_files_fail_with_a_message_and_write_nothing(tmp_path, content, message):
    mesh = tmp_path / "bad.off"
    if content is not None:
        mesh.write_text(content)
    out = tmp_path / "out"
    r = run("build", mesh, "-o", tmp_path / "bad.exr", "--stages", out, "--no-image")
    assert r.returncode == 2
    assert "trichart: error:" in r.stderr and message in r.stderr
    assert not (out / "prepared.vtp").exists() and not (tmp_path / "bad.exr").exists()


def test_too_many_clusters_is_a_clear_error(testing_data, tmp_path):
    r = run("build", testing_data / "meshes" / "cube.off", "-o", tmp_path / "cube.exr")
    assert r.returncode == 2
    assert "12" in r.stderr and "16" in r.stderr


def test_build_options_reach_the_stages(testing_data, tmp_path):
    # Floater's map alone and no feature-line straightening give another atlas than the
    # defaults; out-of-range values are refused before anything runs.
    plain = tmp_path / "plain.exr"
    r = run("build", testing_data / "meshes" / "bunny_npm.off", "-o", plain, "-q",
            "--stretch-iterations", "0", "--crease-angle", "0")
    assert r.returncode == 0, r.stderr
    default = tmp_path / "default.exr"
    assert run("build", testing_data / "meshes" / "bunny_npm.off", "-o", default,
               "-q").returncode == 0
    assert plain.read_bytes() != default.read_bytes()
    for option, value in (("--stretch-iterations", "101"), ("--crease-angle", "-1"),
                          ("--max-error", "2"), ("--error-target", "0.7"),
                          ("--crease-lines", "-5")):
        r = run("build", testing_data / "meshes" / "bunny_npm.off", "-o",
                tmp_path / "bad.exr", option, value)
        assert r.returncode == 2 and option in r.stderr, r.stderr
        assert not (tmp_path / "bad.exr").exists()


def test_build_keeps_the_texture_unless_told_not_to(testing_data, tmp_path):
    import trichart

    sphere = testing_data / "meshes" / "textured_sphere.glb"
    charts = {}
    for flags in ((), ("--no-appearance",), ("--no-seam-lines",)):
        atlas = tmp_path / ("atlas" + "".join(flags) + ".exr")
        r = run("build", sphere, "-o", atlas, "-q", *flags)
        assert r.returncode == 0, r.stderr
        read = trichart.read_atlas(atlas)
        images = read.GetBlock(1).GetBlock(0).GetPointData()
        uv = images.GetArray("TextureCoordinates")
        if "--no-appearance" in flags:
            assert read.GetNumberOfBlocks() == 2 and uv is None
        else:
            assert read.GetNumberOfBlocks() == 3 and uv.GetNumberOfComponents() == 2
            assert read.GetBlock(2).GetBlock(0).GetDimensions() == (64, 32, 1)
        charts[flags] = trichart.atlas_charts(read).GetNumberOfRows()
    # The sphere's seam (and its poles' one vertex per segment) cut charts: fewer without.
    assert charts[("--no-seam-lines",)] < charts[()]


def _finest_hausdorff(mesh, atlas):
    """Hausdorff / diagonal (%) of the finest row that `trichart eval` prints."""
    r = run("eval", mesh, atlas)
    assert r.returncode == 0, r.stderr
    rows = [line.split() for line in r.stdout.splitlines() if line.split()[:1] != []
            and line.split()[0].isdigit()]
    return float(rows[-1][5].rstrip("%"))


def test_build_error_target_brings_the_finest_level_closer(testing_data, tmp_path):
    # The default spends the input's point count; a target of 0.2% of the diagonal raises the
    # charts above it, which on this coarse bunny brings the finest Hausdorff down severalfold.
    mesh = testing_data / "meshes" / "bunny_npm.off"
    figures = {}
    for target in ("0", "0.002"):
        atlas = tmp_path / f"t{target}.exr"
        r = run("build", mesh, "-o", atlas, "-q", "--error-target", target)
        assert r.returncode == 0, r.stderr
        figures[target] = _finest_hausdorff(mesh, atlas)
    print("bunny_npm finest Hausdorff / diagonal (%): default", figures["0"], "target 0.2%",
          figures["0.002"])
    assert figures["0.002"] < 0.5 * figures["0"]


def test_prepare_reports_and_splits(tmp_path):
    mesh = tmp_path / "fins.off"
    # Three triangles on the edge (0, 1): a non-manifold edge.
    mesh.write_text("OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n")
    r = run("prepare", mesh, "-o", tmp_path / "fins.vtp", "--split-non-manifold")
    assert r.returncode == 0, r.stderr
    assert "non-manifold" in r.stdout
    assert (tmp_path / "fins.vtp").exists()


def test_build_removes_slivers_and_retries_when_the_paths_cannot_be_traced(shared_data,
                                                                            tmp_path):
    # couplingdown's CAD tessellation has needles (a side 13 times the shortest) that the base
    # complex keeps and the paths cannot be cut through; the build removes them and goes on.
    mesh = shared_data / "cad" / "couplingdown.off"
    r = run("build", mesh, "-o", tmp_path / "c.exr", "-q")
    assert r.returncode == 0, r.stderr
    assert "note: the paths could not be traced (input triangle" in r.stdout, r.stdout
    assert "found 180 slivers" in r.stdout
    assert (tmp_path / "c.exr").stat().st_size > 0
    # Asked for up front, there is nothing to retry.
    r = run("build", mesh, "-o", tmp_path / "d.exr", "-q", "--remove-slivers")
    assert r.returncode == 0, r.stderr
    assert "note:" not in r.stdout and "found 180 slivers" in r.stdout


def test_an_open_mesh_is_refused_after_the_preparation_with_the_flag_to_use(testing_data,
                                                                             tmp_path):
    # The bundled bunny with one triangle taken out: a hole of 3 boundary edges.
    lines = (testing_data / "meshes" / "bunny_npm.off").read_text().split("\n")
    points, faces = map(int, lines[1].split()[:2])
    lines[1] = f"{points} {faces - 1} 0"
    del lines[2 + points]
    mesh = tmp_path / "holed.off"
    mesh.write_text("\n".join(lines))
    r = run("build", mesh, "-o", tmp_path / "holed.exr")
    assert r.returncode == 2
    assert "3 boundary edges (close the holes: FillHoles, trichart build --fill-holes)" in r.stderr
    # It stops before the stages that would run for nothing.
    assert "prepare: 100%" in r.stderr and "curvature:" not in r.stderr, r.stderr
    assert not (tmp_path / "holed.exr").exists()
    r = run("build", mesh, "-o", tmp_path / "holed.exr", "-q", "--fill-holes",
            "--max-hole-edges", "3")
    assert r.returncode == 0, r.stderr
    assert "filled 1 hole with 1 triangle" in r.stdout, r.stdout
    # Too small a limit leaves the hole open and names the option that closes it.
    r = run("prepare", mesh, "-o", tmp_path / "p.vtp", "--fill-holes", "--max-hole-edges", "2")
    assert r.returncode == 2 and "--max-hole-edges must be 3 or more (0: any size)" in r.stderr


def _with_parts(mesh, path, stray_triangle=False, moebius_segments=0):
    """`mesh` (an OFF file) written to `path` with a stray triangle and a Moebius strip of
    2 * moebius_segments triangles appended, far from it: components the pipeline cannot take."""
    lines = [line for line in mesh.read_text().split("\n") if line.strip()]
    num_points, num_faces = map(int, lines[1].split()[:2])
    points = lines[2:2 + num_points]
    faces = lines[2 + num_points:2 + num_points + num_faces]
    if stray_triangle:
        n = len(points)
        points += ["10 0 0", "11 0 0", "10 1 0"]
        faces.append(f"3 {n} {n + 1} {n + 2}")
    if moebius_segments:
        n, segments = len(points), moebius_segments
        for i in range(segments):
            t = 2 * math.pi * i / segments
            h, z = 0.3 * math.cos(t / 2), 0.3 * math.sin(t / 2)
            for sign in (1, -1):
                points.append(f"{-10 + math.cos(t) * (1 + sign * h)} "
                              f"{math.sin(t) * (1 + sign * h)} {sign * z}")
        for i in range(segments):
            top, bottom = n + 2 * i, n + 2 * i + 1
            # The half twist: after the last segment, top and bottom swap.
            next_top = top + 2 if i + 1 < segments else n + 1
            next_bottom = top + 3 if i + 1 < segments else n
            faces += [f"3 {top} {bottom} {next_bottom}", f"3 {top} {next_bottom} {next_top}"]
    path.write_text("OFF\n" + f"{len(points)} {len(faces)} 0\n" + "\n".join(points + faces) +
                    "\n")
    return path


def test_build_drops_the_components_the_flags_name(testing_data, tmp_path):
    # The bundled bunny (3674 triangles, closed) with a stray triangle and a Moebius strip.
    mesh = _with_parts(testing_data / "meshes" / "bunny_npm.off", tmp_path / "parts.off",
                       stray_triangle=True, moebius_segments=12)
    r = run("build", mesh, "-o", tmp_path / "parts.exr", "-q")
    assert r.returncode == 2
    assert ("1 non-orientable (Moebius-like) component (24 of the 3699 triangles), which no "
            "orientation fixes (drop it: DropNonOrientable, trichart build "
            "--drop-non-orientable" in r.stderr), r.stderr
    assert ("or keep only the largest component, which is closed and oriented (3674 of the "
            "3699 triangles): KeepLargestComponent, trichart build --keep-largest-component"
            in r.stderr), r.stderr
    # Dropping the strip leaves the stray triangle open: still refused, for its 3 edges.
    r = run("prepare", mesh, "-o", tmp_path / "p.vtp", "--drop-non-orientable")
    assert r.returncode == 0, r.stderr
    assert "dropped 1 non-orientable component with 24 triangles (DropNonOrientable)" in r.stdout
    assert "3 boundary edges" in r.stdout, r.stdout
    r = run("prepare", mesh, "-o", tmp_path / "p.vtp", "--drop-non-orientable",
            "--min-component-triangles", "2")
    assert r.returncode == 0, r.stderr
    assert ("dropped 1 component of fewer triangles than MinComponentTriangles, with 1 "
            "triangle in all" in r.stdout), r.stdout
    assert "boundary edges" not in r.stdout and "3674 output triangles" in r.stdout, r.stdout
    r = run("build", mesh, "-o", tmp_path / "parts.exr", "-q", "--keep-largest-component")
    assert r.returncode == 0, r.stderr
    assert ("dropped 2 components other than the largest, with 25 triangles in all "
            "(KeepLargestComponent)" in r.stdout), r.stdout
    assert "3674 triangles" in r.stdout and (tmp_path / "parts.exr").stat().st_size > 0
    r = run("prepare", mesh, "-o", tmp_path / "p.vtp", "--min-component-triangles", "-1")
    assert r.returncode == 2 and "--min-component-triangles must be 0" in r.stderr, r.stderr


def test_build_takes_a_skinned_character_in_its_rest_pose(shared_data, tmp_path):
    # The FBX snake of the data README: a closed tube of 1056 quads, 2112 triangles.
    mesh = shared_data / "skinned" / "snake_fbx" / "animation_with_skeleton.fbx"
    r = run("build", mesh, "-o", tmp_path / "snake.exr", "-q")
    assert r.returncode == 0, r.stderr
    assert "2112 triangles" in r.stdout and "triangulated 1056 polygons" in r.stdout, r.stdout
    assert "read: importer: Autodesk FBX Importer" in r.stdout, r.stdout
    assert "read: skinned: 1 mesh, 14 bones" in r.stdout, r.stdout
    assert "read: skeleton: 17 joints" in r.stdout, r.stdout
    assert "read: animation 0 'Armature|ArmatureAction': 0.833333 s, 14 key times" in r.stdout
    assert (tmp_path / "snake.exr").stat().st_size > 0
