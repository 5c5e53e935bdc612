"""The pipeline on every small mesh of ../shared/data, including the broken ones (non-manifold
horse and dragon scan, the open 32-piece teapot): it never fails on a surface it can repair,
reports what it repaired, and the curvature it computes is finite everywhere."""
import math

import pytest

import trichart
from trichart import tcArrayNames

SMALL = ["bunny_npm.off", "elephant.off", "cow.off", "homer.off", "teapot_npm.off",
         "horse_glmark2.obj", "dragon_vrip_res4.ply.gz"]


def finite(array):
    return all(math.isfinite(array.GetComponent(i, c))
               for i in range(array.GetNumberOfTuples())
               for c in range(array.GetNumberOfComponents()))


@pytest.mark.parametrize("name", SMALL)
@pytest.mark.parametrize("split", [False, True])
def test_prepare_and_curvature_on_shared_meshes(shared_data, name, split):
    mesh = trichart.read_mesh(shared_data / "static_small" / name)
    clean, report = trichart.prepare(mesh, split_non_manifold=split)
    assert clean.GetNumberOfPolys() > 0
    surface, _ = trichart.curvature(clean)
    k = surface.GetPointData().GetArray(tcArrayNames.PrincipalCurvatures())
    assert k.GetNumberOfTuples() == clean.GetNumberOfPoints()
    assert finite(k)
    flags = clean.GetCellData().GetArray(tcArrayNames.NonManifoldEdge())
    flagged = sum(flags.GetValue(i) for i in range(flags.GetNumberOfTuples()))
    if name in ("horse_glmark2.obj", "dragon_vrip_res4.ply.gz"):
        # Both are listed with non-manifold edges in the data README.
        assert flagged > 0 and "non-manifold" in report
    if name == "teapot_npm.off":
        assert "boundary" in report


def test_split_leaves_no_non_manifold_edge(shared_data):
    from vtkmodules.vtkFiltersCore import vtkFeatureEdges

    mesh = trichart.read_mesh(shared_data / "static_small" / "dragon_vrip_res4.ply.gz")
    clean, _ = trichart.prepare(mesh, split_non_manifold=True)
    edges = vtkFeatureEdges()
    edges.SetInputData(clean)
    edges.BoundaryEdgesOff()
    edges.FeatureEdgesOff()
    edges.ManifoldEdgesOff()
    edges.NonManifoldEdgesOn()
    edges.Update()
    assert edges.GetOutput().GetNumberOfLines() == 0


def feature_edge_count(mesh, boundary):
    from vtkmodules.vtkFiltersCore import vtkFeatureEdges

    edges = vtkFeatureEdges()
    edges.SetInputData(mesh)
    edges.FeatureEdgesOff()
    edges.ManifoldEdgesOff()
    edges.SetBoundaryEdges(boundary)
    edges.SetNonManifoldEdges(not boundary)
    edges.Update()
    return edges.GetOutput().GetNumberOfLines()


@pytest.mark.parametrize("name", SMALL)
@pytest.mark.parametrize("split", [False, True])
def test_preparation_counts_match_the_edges_of_its_output(shared_data, name, split):
    # The counts the build checks before the base complex, against VTK's own edge
    # classification of the prepared mesh.
    f = trichart.tcMeshPreparation()
    f.SetInputData(trichart.read_mesh(shared_data / "static_small" / name))
    f.SetSplitNonManifold(split)
    f.Update()
    clean = f.GetOutput()
    boundary = feature_edge_count(clean, True)
    assert f.GetBoundaryEdges() == boundary
    if split:
        assert feature_edge_count(clean, False) == 0
    else:
        assert (f.GetNonManifoldEdges() > 0) == (feature_edge_count(clean, False) > 0)
    flagged = clean.GetPointData().GetArray(tcArrayNames.NonManifoldVertex())
    assert f.GetNonManifoldVertices() <= sum(flagged.GetValue(i)
                                             for i in range(flagged.GetNumberOfTuples()))
    closed = boundary == 0 and f.GetNonOrientableComponents() == 0 and \
        (split or f.GetNonManifoldEdges() + f.GetNonManifoldVertices() == 0)
    assert f.GetClosedManifold() == closed
    # The data README: bunny, elephant and homer are closed manifolds; cow has one pinched
    # vertex; horse and the dragon scan have non-manifold edges; the teapot is open.
    expected = {"bunny_npm.off": True, "elephant.off": True, "homer.off": True,
                "cow.off": split, "teapot_npm.off": False, "horse_glmark2.obj": False,
                "dragon_vrip_res4.ply.gz": False}
    assert f.GetClosedManifold() == expected[name], f.GetReport()


@pytest.mark.parametrize("name,options,message", [
    ("teapot_npm.off", {"split_non_manifold": True}, "boundary edges (close the holes: FillHoles"),
    ("cow.off", {}, "1 non-manifold vertex (split them: SplitNonManifold"),
    ("horse_glmark2.obj", {}, "--split-non-manifold"),
    ("dragon_vrip_res4.ply.gz", {"split_non_manifold": True},
     "1 non-orientable (Moebius-like) component"),
])
def test_build_stops_after_the_preparation_on_a_surface_it_cannot_use(shared_data, tmp_path,
                                                                      name, options, message):
    stages = []
    with pytest.raises(trichart.TriChartError) as error:
        trichart.build(shared_data / "static_small" / name, tmp_path / "x.exr",
                       prepare_options=options,
                       progress=lambda stage, fraction: stages.append(stage))
    assert str(error.value).startswith("prepare: the prepared mesh is not a closed, oriented "
                                       "manifold"), error.value
    assert message in str(error.value)
    assert "curvature" not in stages and "prepare" in stages
    assert not (tmp_path / "x.exr").exists()


@pytest.mark.parametrize("name,importer,triangles,bones", [
    ("wuson/wuson.glb", "glTF2", 3732, 37),
    ("wuson/Testwuson.X", "XFile", 3732, 37),
    ("snake_fbx/animation_with_skeleton.fbx", "FBX", 2112, 14),
    ("snake_fbx/snake_fbx.glb", "glTF2", 2112, 13),
    ("md2/sydney.md2", None, 679, 0),
])
def test_scene_files_are_read_in_their_rest_pose(shared_data, name, importer, triangles, bones):
    # The skinned characters of the data README, through Assimp: the surfaces, counted bones.
    # (The FBX snake counts its root node as a bone.) An MD2 file is its keyframes' sequence.
    reader = trichart.tcMeshReader()
    reader.SetFileName(str(shared_data / "skinned" / name))
    reader.Update()
    report = reader.GetReport()
    mesh = reader.GetOutput()
    if importer is None:
        assert "sequence (md2) of 198 frames" in report and "in the rest pose" in report, report
    else:
        assert "importer: " in report and importer in report, report
        assert "in the rest pose" in report, report
        ids = mesh.GetCellData().GetArray(tcArrayNames.SceneMeshId())
        assert ids is not None and ids.GetNumberOfTuples() == mesh.GetNumberOfCells()
    assert (f"{bones} bones" in report) == (bones > 0), report
    clean, _ = trichart.prepare(mesh)
    assert clean.GetNumberOfPolys() == triangles


def test_md5_files_are_refused_with_the_formats_read(shared_data):
    # Assimp's MD5 importer crashes on damaged files, so the reader does not offer it.
    with pytest.raises(trichart.TriChartError) as error:
        trichart.read_mesh(shared_data / "skinned" / "ffflag_md5" / "ffflag.md5mesh")
    assert "unknown extension" in str(error.value)
    assert "glb gltf fbx x md2" in str(error.value)
