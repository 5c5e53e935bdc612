"""Skinned scenes and deforming sequences read over time: time steps, posing, the skeleton
output, the animation choice, and the errors a user meets."""
import pytest

import trichart
from trichart import tcArrayNames


def _points(mesh):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    return vtk_to_numpy(mesh.GetPoints().GetData())


def _field_text(mesh, name):
    array = mesh.GetFieldData().GetAbstractArray(name)
    if array is None:
        return None
    return "\n".join(array.GetValue(k) for k in range(array.GetNumberOfValues()))


def _relative_vertex_distance(mesh, reference):
    """The largest distance of a point of `mesh` to the nearest point of `reference`, and
    back, over the reference's diagonal: the meshes' triangulations of quads may differ."""
    import numpy as np
    a, b = _points(mesh), _points(reference)
    d = np.sqrt(((a[:, None, :] - b[None, :, :]) ** 2).sum(axis=2))
    diagonal = np.linalg.norm(b.max(axis=0) - b.min(axis=0))
    return max(d.min(axis=1).max(), d.min(axis=0).max()) / diagonal


def test_snake_posed_at_each_baked_frame_time_matches_the_baked_frame(shared_data):
    import numpy as np
    fbx = shared_data / "skinned" / "snake_fbx" / "animation_with_skeleton.fbx"
    times = trichart.time_steps(fbx)
    assert times[0] == 0.0 and times[-1] == pytest.approx(20 / 24)
    worst = 0.0
    for k in (0, 7, 13, 20):
        posed = trichart.read_mesh(fbx, time=times[-1] * k / 20)
        baked = trichart.read_mesh(shared_data / "sequences" / "snake_closed_21f" / f"f_{k:04d}.obj")
        worst = max(worst, _relative_vertex_distance(posed, baked))
        assert _field_text(posed, tcArrayNames.AnimationName()) == "Armature|ArmatureAction"
    assert worst <= 1e-4
    rest = trichart.read_mesh(fbx)
    assert _field_text(rest, tcArrayNames.AnimationName()) is None
    assert not np.allclose(_points(rest), _points(trichart.read_mesh(fbx, time=0.5)))
    print(f"snake: largest vertex distance / diagonal {worst:.2e} over 4 baked frames")


def test_skin_arrays_and_skeleton_output(shared_data):
    import numpy as np
    glb = shared_data / "skinned" / "wuson" / "wuson.glb"
    mesh = trichart.read_mesh(glb)
    joints = mesh.GetPointData().GetArray(tcArrayNames.SkinIndices())
    weights = mesh.GetPointData().GetArray(tcArrayNames.SkinWeights())
    assert joints.GetNumberOfComponents() == 4 and weights.GetNumberOfComponents() == 4
    from vtkmodules.util.numpy_support import vtk_to_numpy
    w = vtk_to_numpy(weights)
    assert np.all(w >= 0) and np.allclose(w.sum(axis=1), 1.0, atol=1e-3)
    skeleton = trichart.read_skeleton(glb)
    n = skeleton.GetNumberOfPoints()
    assert n >= 37 and skeleton.GetNumberOfLines() == n - 1  # one root
    names = skeleton.GetPointData().GetAbstractArray(tcArrayNames.JointNames())
    assert "Root" in {names.GetValue(j) for j in range(n)}
    assert vtk_to_numpy(joints).max() < n
    # Posed at another time, the skeleton moves with the mesh.
    later = trichart.read_skeleton(glb, time=0.5, animation="Wuson_Run")
    assert later.GetNumberOfPoints() == n
    assert not np.allclose(_points(later), _points(skeleton))
    parents = vtk_to_numpy(skeleton.GetPointData().GetArray(tcArrayNames.JointParent()))
    assert parents[0] == -1 and all(parents[j] < j for j in range(n))


def test_animation_chosen_by_name_or_index_and_a_wrong_name_lists_them(shared_data):
    x = shared_data / "skinned" / "wuson" / "Testwuson.X"
    names = trichart.animation_names(x)
    assert names == ["Wuson_Run", "Wuson_Walk", "Wuson_Bind"]
    assert trichart.time_steps(x, animation="Wuson_Walk") == trichart.time_steps(x, animation=1)
    assert trichart.time_steps(x, animation=1)[-1] == pytest.approx(17280 / 4800)
    assert trichart.time_steps(x, animation="Wuson_Bind") == (0.0,)
    with pytest.raises(trichart.TriChartError, match="Wuson_Walk' \\(1\\)"):
        trichart.time_steps(x, animation="Dance")
    # The bind pose: no time steps, the rest mesh whatever the time.
    reader_rest = trichart.read_mesh(x, bind_pose=True, time=1.0)
    import numpy as np
    assert np.array_equal(_points(reader_rest), _points(trichart.read_mesh(x)))


def test_sequences_from_a_folder_a_pattern_and_md2(shared_data, tmp_path):
    import numpy as np
    folder = shared_data / "sequences" / "frankie_run_19f"
    assert trichart.time_steps(folder) == tuple(float(k) for k in range(19))
    frame = trichart.read_mesh(folder, time=3.7)
    direct = trichart.read_mesh(folder / "Frankie_Run_0003.obj")
    assert np.allclose(_points(frame), _points(direct), atol=1e-5)
    pattern = str(shared_data / "sequences" / "snake_closed_21f" / "f_001?.obj")
    assert len(trichart.time_steps(pattern)) == 10
    md2 = shared_data / "skinned" / "md2" / "sydney.md2"
    steps = trichart.time_steps(md2)
    assert len(steps) == 198
    first, later = trichart.read_mesh(md2, time=0), trichart.read_mesh(md2, time=40)
    assert first.GetNumberOfPoints() == later.GetNumberOfPoints()
    assert not np.allclose(_points(first), _points(later))
    assert "frame 40" in _field_text(later, tcArrayNames.ReaderReport())


def test_a_frame_with_other_connectivity_is_named(tmp_path):
    tet = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"
    other = tet.replace("3 1 2 3", "3 1 3 2")
    (tmp_path / "f_0.off").write_text(tet)
    (tmp_path / "f_1.off").write_text(tet)
    (tmp_path / "f_2.off").write_text(other)
    with pytest.raises(trichart.TriChartError, match="frame 2 \\(f_2.off\\)"):
        trichart.read_mesh(tmp_path)
    assert trichart.time_steps(tmp_path / "f_0.off") == ()


def _cli(*args):
    import subprocess
    import sys
    return subprocess.run([sys.executable, "-m", "trichart", *map(str, args)],
                          capture_output=True, text=True, timeout=300)


def test_the_command_line_lists_animations_and_writes_posed_meshes(shared_data, tmp_path):
    glb = shared_data / "skinned" / "wuson" / "wuson.glb"
    r = _cli("pose", glb, "--animation", "Wuson_Walk")
    assert r.returncode == 0, r.stderr
    assert "animation 1: Wuson_Walk" in r.stdout and "to 3.6 s" in r.stdout
    r = _cli("pose", glb, "--animation", "1", "--time", "1.2", "-o", tmp_path / "walk.ply",
             "--skeleton", tmp_path / "bones.vtp")
    assert r.returncode == 0, r.stderr
    posed = trichart.read_mesh(tmp_path / "walk.ply")
    direct = trichart.read_mesh(glb, time=1.2, animation="Wuson_Walk")
    import numpy as np
    assert np.allclose(_points(posed), _points(direct), atol=1e-4)
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    bones = vtkXMLPolyDataReader()
    bones.SetFileName(str(tmp_path / "bones.vtp"))
    bones.Update()
    joints = trichart.read_skeleton(glb, time=1.2, animation=1)
    assert bones.GetOutput().GetNumberOfPoints() == joints.GetNumberOfPoints() > 30
    assert np.allclose(_points(bones.GetOutput()), _points(joints))
    r = _cli("pose", glb, "-o", tmp_path / "x.ply")
    assert r.returncode != 0 and "--time" in r.stderr
    r = _cli("pose", glb, "--animation", "Dance", "--time", "1")
    assert r.returncode == 2 and "Wuson_Run' (0)" in r.stderr


def test_a_skinned_atlas_keeps_the_skin_and_poses_like_the_input(shared_data, tmp_path):
    """The snake built into an atlas: the Skin attribute and the rig survive the file, the
    rebuilt mesh carries SkinIndices / SkinWeights, and every rebuilt point that is an input
    vertex (the charts' corners) poses exactly where the input's vertex does, at every time."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    fbx = shared_data / "skinned" / "snake_fbx" / "animation_with_skeleton.fbx"
    trichart.build(fbx, tmp_path / "snake.exr")
    atlas = trichart.read_atlas(tmp_path / "snake.exr")
    finest = trichart.rebuild(atlas)
    weights = vtk_to_numpy(finest.GetPointData().GetArray(tcArrayNames.SkinWeights()))
    joints = vtk_to_numpy(finest.GetPointData().GetArray(tcArrayNames.SkinIndices()))
    assert weights.shape[1] == 4 and np.all(weights >= 0)
    assert joints.min() >= 0 and joints.max() < 17
    assert _field_text(finest, tcArrayNames.Rig()) is not None

    rest, _ = trichart.prepare(trichart.read_mesh(fbx))
    p, q = _points(finest), _points(rest)
    diagonal = np.linalg.norm(q.max(axis=0) - q.min(axis=0))
    nearest = np.sqrt(((p[:, None, :] - q[None, :, :]) ** 2).sum(axis=2))
    match = nearest.argmin(axis=1)
    on_vertex = nearest.min(axis=1) < 3e-5 * diagonal  # the lattice step: about 1e-5
    assert on_vertex.sum() >= 100
    duration = trichart.time_steps(fbx)[-1]
    for t in (0.25 * duration, 0.6 * duration, duration):
        posed = _points(trichart.pose(finest, t))
        reference = _points(trichart.read_mesh(fbx, time=t, animation=0))
        reference_rest = _points(trichart.pose(rest, t))
        assert np.allclose(posed[on_vertex], reference_rest[match[on_vertex]],
                           atol=1e-4 * diagonal)
        assert len(reference) == 2464  # the reader's points, before the merge
    # The command line: the posed finest level per frame, and a posed mesh at one time.
    import json
    r = _cli("eval", fbx, tmp_path / "snake.exr", "--frames", "3", "--json")
    assert r.returncode == 0, r.stderr
    figures = json.loads(r.stdout)
    assert [f["time"] for f in figures["frames"]] == pytest.approx([0, duration / 2, duration])
    assert figures["rest"]["hausdorff_fraction"] < 0.002
    assert all(f["hausdorff_fraction"] < 0.02 for f in figures["frames"])
    r = _cli("mesh", tmp_path / "snake.exr", "--time", str(duration), "-o", tmp_path / "end.vtp")
    assert r.returncode == 0, r.stderr
    end = trichart.read_mesh(tmp_path / "end.vtp")
    assert np.allclose(_points(end), _points(trichart.pose(finest, duration)), atol=1e-6 * diagonal)
    r = _cli("eval", fbx, fbx.parent.parent / "wuson" / "wuson.glb", "--frames", "3")
    assert r.returncode == 2 and "atlas" in r.stderr
    with pytest.raises(trichart.TriChartError, match="SkinIndices"):
        trichart.pose(trichart.prepare(trichart.read_mesh(
            shared_data / "sequences" / "snake_closed_21f" / "f_0000.obj"))[0], 0.5)


def test_a_sequence_builds_into_a_skinned_atlas_through_its_proxy_bones(shared_data, tmp_path):
    """The snake's baked frames, without a skeleton: the reader fits proxy bones, the build
    keeps them, and posed at its frames the finest level stays within twice its rest error of
    the frames themselves (the fit's error included)."""
    import json
    folder = shared_data / "sequences" / "snake_closed_21f"
    rest = trichart.read_mesh(folder)
    assert rest.GetPointData().GetArray(tcArrayNames.SkinWeights()) is not None
    assert "proxy bones: " in _field_text(rest, tcArrayNames.ReaderReport())
    plain = trichart.read_mesh(folder, proxy_bones=False)
    assert plain.GetPointData().GetArray(tcArrayNames.SkinWeights()) is None
    trichart.build(folder, tmp_path / "sequence.exr")
    r = _cli("eval", folder, tmp_path / "sequence.exr", "--frames", "5", "--json")
    assert r.returncode == 0, r.stderr
    figures = json.loads(r.stdout)
    print(f"snake sequence: rest {figures['rest']['hausdorff_fraction']:.3e}, largest frame / "
          f"rest {figures['largest_ratio_to_rest']:.2f}")
    assert figures["largest_ratio_to_rest"] <= 2.0


def test_a_skinned_atlas_exports_to_gltf_and_plays_back(shared_data, tmp_path):
    """wuson built, exported with its skin and animations, read back by the reader (Assimp):
    the same animations, and posed at a time of Walk the export's finest level lies on the
    atlas's finest level posed alike (its weights sum to 1, so glTF's normalization is moot)."""
    glb = shared_data / "skinned" / "wuson" / "wuson.glb"
    trichart.build(glb, tmp_path / "wuson.exr",
                   prepare_options={"fill_holes": True, "split_non_manifold": True})
    r = _cli("export", tmp_path / "wuson.exr", "-o", tmp_path / "lods.glb")
    assert r.returncode == 0, r.stderr
    assert trichart.animation_names(tmp_path / "lods.glb") == trichart.animation_names(glb)
    finest = trichart.rebuild(trichart.read_atlas(tmp_path / "wuson.exr"))
    for time, reference, bound in ((None, finest, 1e-6),
                                   (1.2, trichart.pose(finest, 1.2, animation="Wuson_Walk"), 1e-4)):
        lod0 = _first_scene_mesh(trichart.read_mesh(tmp_path / "lods.glb", time=time,
                                                    animation="Wuson_Walk"))
        assert lod0.GetNumberOfPolys() == finest.GetNumberOfPolys()
        _, f = trichart.surface_distance(lod0, reference)
        assert f["hausdorff"] / f["diagonal"] < bound, (time, f)


def _first_scene_mesh(mesh):
    """The cells of scene mesh 0 (the export's LOD 0) of a mesh the reader read."""
    from vtkmodules.vtkFiltersCore import vtkThreshold
    from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
    lod0 = vtkThreshold()
    lod0.SetInputData(mesh)
    lod0.SetInputArrayToProcess(0, 0, 0, 1, tcArrayNames.SceneMeshId())
    lod0.SetLowerThreshold(0)
    lod0.SetUpperThreshold(0)
    surface = vtkGeometryFilter()
    surface.SetInputConnection(lod0.GetOutputPort())
    surface.Update()
    return surface.GetOutput()


def test_frames_read_through_one_reader_are_each_as_read_alone(shared_data):
    """read_frames poses one reader at each time; the rest pose after a posed one is the rest
    pose again, not the last pose kept."""
    import numpy as np
    glb = shared_data / "skinned" / "wuson" / "wuson.glb"
    posed, rest, later = trichart.read_frames(glb, [0.5, None, 1.0], animation=1)
    assert np.array_equal(_points(rest), _points(trichart.read_mesh(glb)))
    assert np.array_equal(_points(later), _points(trichart.read_mesh(glb, time=1.0, animation=1)))
    assert not np.array_equal(_points(posed), _points(rest))


def test_skin_lines_make_the_joints_boundaries_feature_lines(shared_data):
    """skin_lines: on the snake, the boundaries between the faces its joints dominate join the
    feature lines (off by default: the lines of the curvature clusters alone)."""
    fbx = shared_data / "skinned" / "snake_fbx" / "animation_with_skeleton.fbx"
    prepared, _ = trichart.prepare(trichart.read_mesh(fbx))
    clusters, _ = trichart.cluster(trichart.curvature(prepared)[0])
    plain = trichart.refine_features(clusters)[1].GetNumberOfCells()
    skinned = trichart.refine_features(clusters, skin_lines=True)[1].GetNumberOfCells()
    print(f"snake: {plain} feature lines, {skinned} with the skin's")
    assert skinned > plain


def _rigid_frames(tmp_path, count):
    """A tetrahedron turned about z and moved along x, one OFF frame per step."""
    import math
    corners = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"
    for k in range(count):
        c, s = math.cos(0.3 * k), math.sin(0.3 * k)
        points = "".join(f"{c * x - s * y + 0.5 * k} {s * x + c * y} {z}\n"
                         for x, y, z in corners)
        (tmp_path / f"f_{k}.off").write_text(f"OFF\n4 4 0\n{points}{faces}")
    return tmp_path


def test_deformation_clustering_fits_a_rigid_sequence_exactly(tmp_path, testing_data):
    clusters, lines, fit = trichart.deformation_clustering(_rigid_frames(tmp_path, 4))
    assert clusters.GetNumberOfPolys() == 4 and len(fit["rms"]) == 4
    assert clusters.GetCellData().GetArray(tcArrayNames.ClusterId()).GetRange() == (0.0, 1.0)
    assert max(fit["rms"]) < 1e-5 and max(fit["max"]) < 1e-5  # one rigid motion per frame
    assert clusters.GetPointData().GetArray(tcArrayNames.SkinWeights()) is not None
    assert lines.GetNumberOfCells() > 0
    with pytest.raises(trichart.TriChartError, match="needs a sequence of several frames"):
        trichart.deformation_clustering(testing_data / "meshes" / "bunny_npm.off")


def test_deformation_clusters_of_the_shared_sequences_beat_the_rigid_baseline(shared_data):
    for name in ("snake_closed_21f", "frankie_run_19f"):
        clusters, lines, fit = trichart.deformation_clustering(shared_data / "sequences" / name)
        frames = len(fit["rms"])
        assert frames == len(trichart.time_steps(shared_data / "sequences" / name)) > 10
        total = (sum(r * r for r in fit["rms"][1:]) / (frames - 1)) ** 0.5
        rigid = (sum(r * r for r in fit["rigid_rms"][1:]) / (frames - 1)) ** 0.5
        assert total <= 0.005 and total <= 0.5 * rigid, (name, total, rigid)
        boundary = clusters.GetPointData().GetArray(tcArrayNames.FeatureVertex())
        on_lines = {lines.GetPointData().GetArray(tcArrayNames.InputPointId()).GetValue(k)
                    for k in range(lines.GetNumberOfPoints())}
        assert {p for p in range(clusters.GetNumberOfPoints()) if boundary.GetValue(p)} == on_lines


def test_a_skinned_scene_is_grouped_by_its_dominant_joints(shared_data):
    fbx = shared_data / "skinned" / "snake_fbx" / "animation_with_skeleton.fbx"
    clusters, lines, fit = trichart.deformation_clustering(fbx)
    ids = clusters.GetCellData().GetArray(tcArrayNames.ClusterId())
    assert len({ids.GetValue(k) for k in range(ids.GetNumberOfTuples())}) > 5
    assert lines.GetNumberOfCells() > 0 and fit == {"rms": [], "max": [], "rigid_rms": []}
