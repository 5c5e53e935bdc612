"""Files and figures for other tools: `trichart mesh` and `prepare` write the format the
extension names (and refuse one they do not know), `build` writes only .exr, `trichart export`
writes a glTF 2.0 LOD chain whose every LOD is `trichart mesh` at that level and that VTK's glTF
reader loads; `eval` and `build` print their figures as JSON, `eval` plots them with the QEM
peer and warns when the mesh is not the atlas's, and a closed pipe ends the output quietly."""
import json
import struct
import subprocess
import sys

import numpy
import pytest
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOGeometry import vtkGLTFReader

import trichart


def run(*args):
    return subprocess.run([sys.executable, "-m", "trichart", *map(str, args)],
                          capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def atlas(testing_data, tmp_path_factory):
    path = tmp_path_factory.mktemp("export") / "bunny.exr"
    r = run("build", testing_data / "meshes" / "bunny_npm.off", "-o", path, "-q")
    assert r.returncode == 0, r.stderr
    return path


def points_and_triangles(mesh):
    points = vtk_to_numpy(mesh.GetPoints().GetData())
    return points, mesh.GetNumberOfPolys()


@pytest.mark.parametrize("extension", trichart.MESH_EXTENSIONS)
def test_mesh_writes_the_format_its_extension_names(atlas, tmp_path, extension):
    r = run("mesh", atlas, "--level", "2", "-o", tmp_path / f"level2{extension}")
    assert r.returncode == 0, r.stderr
    written = trichart.read_mesh(tmp_path / f"level2{extension}")
    reference = trichart.rebuild(trichart.read_atlas(atlas), level=2)
    points, triangles = points_and_triangles(written)
    expected, expected_triangles = points_and_triangles(reference)
    # The same triangles and the same distinct points in float (STL repeats a point per
    # triangle; readers may reorder them).
    assert triangles == expected_triangles, extension
    distinct = numpy.unique(points.astype(numpy.float32), axis=0)
    assert numpy.array_equal(distinct, numpy.unique(expected.astype(numpy.float32), axis=0))
    assert [p.name for p in tmp_path.iterdir()] == [f"level2{extension}"]  # no temporary left


@pytest.mark.parametrize("command", ["mesh", "prepare", "build"])
@pytest.mark.parametrize("name", ["out.glb", "out.xyz", "out"])
def test_a_name_the_command_does_not_write_is_refused_before_the_work(atlas, testing_data,
                                                                      tmp_path, command, name):
    source = atlas if command == "mesh" else testing_data / "meshes" / "bunny_npm.off"
    r = run(command, source, "-o", tmp_path / name)
    assert r.returncode == 2
    if command == "build":
        assert "an atlas file is OpenEXR, named .exr" in r.stderr, r.stderr
    else:
        assert "unknown extension" in r.stderr and ".vtp, .vtk, .ply, .obj, .stl, .off" in r.stderr
    assert list(tmp_path.iterdir()) == []


def test_export_refuses_a_name_that_is_not_gltf(atlas, tmp_path):
    r = run("export", atlas, "-o", tmp_path / "chain.obj")
    assert r.returncode == 2 and ".glb (binary) or .gltf (JSON)" in r.stderr, r.stderr
    r = run("export", atlas, "-o", tmp_path / "chain.glb", "--error-ratio", "1")
    assert r.returncode == 2 and "--error-ratio must be" in r.stderr, r.stderr
    assert list(tmp_path.iterdir()) == []


def glb_meshes(path):
    """(positions, indices) of every mesh of a GLB, from its JSON and BIN chunks."""
    data = path.read_bytes()
    magic, version, length = struct.unpack_from("<4sII", data)
    assert (magic, version, length) == (b"glTF", 2, len(data))
    json_length, json_type = struct.unpack_from("<I4s", data, 12)
    assert json_type == b"JSON"
    gltf = json.loads(data[20:20 + json_length])
    bin_start = 20 + json_length + 8
    types = {5126: numpy.float32, 5125: numpy.uint32, 5123: numpy.uint16}

    def read(index, width):
        accessor = gltf["accessors"][index]
        view = gltf["bufferViews"][accessor["bufferView"]]
        start = bin_start + view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
        components = {"SCALAR": 1, "VEC3": 3}[accessor["type"]]
        values = numpy.frombuffer(data, types[accessor["componentType"]],
                                  accessor["count"] * components, start)
        return values.reshape(-1, width)

    meshes = []
    for mesh in gltf["meshes"]:
        primitive = mesh["primitives"][0]
        meshes.append((read(primitive["attributes"]["POSITION"], 3),
                       read(primitive["indices"], 3)))
    return gltf, meshes


def test_every_uniform_lod_is_trichart_mesh_at_its_level(atlas, tmp_path):
    out = tmp_path / "chain.glb"
    r = run("export", atlas, "-o", out, "--chain", "uniform", "-q")
    assert r.returncode == 0, r.stderr
    gltf, meshes = glb_meshes(out)
    levels = trichart.atlas_charts(trichart.read_atlas(atlas)).GetColumnByName(
        trichart.tcArrayNames.MaxLevel())
    finest = max(levels.GetValue(c) for c in range(levels.GetNumberOfTuples()))
    assert len(meshes) == finest + 1
    assert gltf["nodes"][0]["extensions"]["MSFT_lod"]["ids"] == list(range(1, finest + 1))
    for k, (positions, indices) in enumerate(meshes):
        level = finest - k
        r = run("mesh", atlas, "--level", level, "-o", tmp_path / f"l{level}.vtp")
        assert r.returncode == 0, r.stderr
        mesh = trichart.read_mesh(tmp_path / f"l{level}.vtp")
        points = vtk_to_numpy(mesh.GetPoints().GetData())
        triangles = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3)
        assert numpy.array_equal(positions, points.astype(numpy.float32)), f"LOD {k}"
        assert numpy.array_equal(indices, triangles), f"LOD {k}"
        assert gltf["nodes"][k]["extras"]["triangles"] == len(triangles)


def test_vtk_reads_the_export_back(atlas, tmp_path):
    for name, layout, shown in (("lod.glb", "msft-lod", 1), ("named.gltf", "named-nodes", None)):
        out = tmp_path / name
        r = run("export", atlas, "-o", out, "--layout", layout)
        assert r.returncode == 0, r.stderr
        lods = [line.split() for line in r.stdout.splitlines() if line.split()[0].isdigit()]
        assert len(lods) >= 3, r.stdout
        triangles = [int(row[1]) for row in lods]
        assert triangles == sorted(triangles, reverse=True) and len(set(triangles)) == len(lods)
        reader = vtkGLTFReader()
        reader.SetFileName(str(out))
        reader.Update()
        blocks = reader.GetOutput()
        polys = []
        iterator = blocks.NewIterator()
        iterator.InitTraversal()
        while not iterator.IsDoneWithTraversal():
            polys.append(iterator.GetCurrentDataObject().GetNumberOfPolys())
            iterator.GoToNextItem()
        # MSFT_lod: LOD 0 alone is in the scene; named nodes: every LOD.
        assert polys == (triangles[:shown] if shown else triangles), (layout, polys, triangles)


def test_eval_json_holds_every_level_with_its_peer_and_plots_them(atlas, testing_data, tmp_path):
    plot = tmp_path / "errors.png"
    r = run("eval", testing_data / "meshes" / "bunny_npm.off", atlas, "--json", "--plot", plot)
    assert r.returncode == 0, r.stderr
    figures = json.loads(r.stdout)
    levels = figures["levels"]
    assert [row["level"] for row in levels] == list(range(len(levels))) and len(levels) >= 4
    assert figures["warning"] == "" and "warning" not in r.stderr
    for row in levels:
        assert row["hausdorff_fraction"] >= row["rms_fraction"] > 0
        if row["triangles"] < figures["triangles"]:  # the peer where it can simplify
            assert row["qem"]["triangles"] <= row["triangles"]
            assert row["qem"]["hausdorff_fraction"] > 0
    errors = [row["hausdorff_fraction"] for row in levels]
    assert errors == sorted(errors, reverse=True)
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    r = run("eval", testing_data / "meshes" / "bunny_npm.off", atlas, "--plot", tmp_path / "e.svg")
    assert r.returncode == 2 and "name it .png" in r.stderr


def test_eval_warns_when_the_mesh_is_not_the_atlas_one(atlas, testing_data):
    r = run("eval", testing_data / "meshes" / "fandisk.off", atlas, "--json")
    assert r.returncode == 0, r.stderr
    assert "do not look like one surface" in json.loads(r.stdout)["warning"]
    assert "trichart: warning: the atlas and the mesh do not look like one surface" in r.stderr


def test_a_closed_pipe_stops_the_output_quietly(atlas, testing_data):
    command = (f"{sys.executable} -m trichart eval {testing_data / 'meshes' / 'bunny_npm.off'} "
               f"{atlas} | head -1")
    r = subprocess.run(["bash", "-c", command], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0 and r.stdout.startswith(str(atlas)), r.stdout
    assert "Traceback" not in r.stderr and "BrokenPipe" not in r.stderr, r.stderr


def test_build_json_holds_the_summary(testing_data, tmp_path):
    out = tmp_path / "a.exr"
    r = run("build", testing_data / "meshes" / "bunny_npm.off", "-o", out, "-q", "--json")
    assert r.returncode == 0, r.stderr
    figures = json.loads(r.stdout)
    assert figures["input_triangles"] == 3674 and figures["files"]["atlas"] == str(out)
    assert figures["bytes_per_input_triangle"] == pytest.approx(out.stat().st_size / 3674)
    assert figures["charts"] > 0 and figures["finest_level"] >= 2
    assert figures["memory"]["peak"] <= figures["memory"]["start"] + figures["memory"]["estimate"]


def test_vtk_warnings_reach_the_user_as_plain_lines(tmp_path):
    # Two tetrahedra that share one vertex: the preparation warns of the pinch.
    mesh = tmp_path / "pinch.off"
    mesh.write_text("OFF\n7 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n-1 0 0\n0 -1 0\n0 0 -1\n"
                    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 4 5\n3 0 6 4\n3 0 5 6\n3 4 6 5\n")
    r = run("prepare", mesh, "-o", tmp_path / "out.vtp")
    assert "trichart: warning: tcMeshPreparation: The mesh has" in r.stderr, r.stderr
    assert "\x1b[" not in r.stderr and "0x" not in r.stderr and "WARN|" not in r.stderr, r.stderr


def test_the_mesh_writer_refuses_what_it_does_not_write(testing_data, tmp_path):
    # tcMeshWriter, which the command line and the viewer write meshes through: an unknown
    # extension and polygons for STL or OFF are refused with the reason, and nothing is written;
    # every extension it names is written, in any case.
    from vtkmodules.vtkFiltersSources import vtkPlaneSource

    mesh = trichart.read_mesh(testing_data / "meshes" / "cube.off")
    quads = vtkPlaneSource()
    quads.SetResolution(2, 2)
    quads.Update()
    for data, name, reason in ((mesh, "cube.xyz", ".vtp .vtk .ply .obj .stl .off"),
                               (quads.GetOutput(), "quads.stl", "takes triangles only"),
                               (quads.GetOutput(), "quads.off", "takes triangles only")):
        writer = trichart.TriChartIO.tcMeshWriter()
        writer.SetFileName(str(tmp_path / name))
        writer.SetInputData(data)
        with pytest.raises(trichart.TriChartError, match=reason):
            trichart.pipeline.run(writer, "write")
        assert writer.GetErrorCode() != 0, name
    assert list(tmp_path.iterdir()) == []
    for extension in trichart.MESH_EXTENSIONS:
        trichart.write_mesh(mesh, tmp_path / f"cube{extension.upper()}")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        f"cube{e.upper()}" for e in trichart.MESH_EXTENSIONS)
