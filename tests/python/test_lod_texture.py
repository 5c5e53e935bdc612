"""A textured mesh keeps its texture through the pipeline: the atlas carries the texture and its
coordinates, tcLODMapper colours by them, and the picture matches VTK's own rendering of the
textured input (testing-data/meshes/textured_sphere.glb: a UV sphere with a seam at u = 0 / 1,
one pole vertex per segment, and a checker of 8 hues, scripts/make-textured-sphere.py)."""
import os
import pathlib

import pytest

import trichart
from trichart import tcArrayNames

from imagecompare import differing_inner_pixels, differing_pixels

SIZE = (320, 320)


def atlas_of(mesh):
    """The static pipeline at its defaults, from `mesh` to its atlas."""
    clean, _ = trichart.prepare(mesh)
    surface, _ = trichart.curvature(clean)
    clusters, _ = trichart.cluster(surface)
    features, _, _ = trichart.refine_features(clusters)
    _, parameterized = trichart.base_complex(features)
    patches, _ = trichart.trace_paths(parameterized)
    return trichart.geometry_images(patches)


@pytest.fixture(scope="module")
def sphere(testing_data):
    mesh = trichart.read_mesh(testing_data / "meshes" / "textured_sphere.glb")
    return mesh, atlas_of(mesh)


_WINDOW = []


def window():
    """One off-screen window for every picture of the module: each window is an X connection,
    and opening one after another can fail under Xvfb."""
    from vtkmodules.vtkRenderingCore import vtkRenderWindow

    if not _WINDOW:
        w = vtkRenderWindow()
        w.SetOffScreenRendering(1)
        w.SetMultiSamples(0)
        w.SetSize(*SIZE)
        _WINDOW.append(w)
    return _WINDOW[0]


def render(mapper, texture, path, direction):
    """`mapper` unlit (the pure surface colour) from `direction`, to the PNG `path`."""
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkWindowToImageFilter

    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().LightingOff()
    actor.GetProperty().SetColor(1, 1, 1)
    if texture is not None:
        actor.SetTexture(texture)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0, 0, 0)
    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(0, 0, 0)
    camera.SetPosition(*(4 * c for c in direction))
    camera.SetViewUp(0, 1, 0)
    camera.SetViewAngle(40)
    renderer.ResetCameraClippingRange(-1, 1, -1, 1, -1, 1)
    shown = window()
    previous = shown.GetRenderers().GetFirstRenderer()
    if previous is not None:
        shown.RemoveRenderer(previous)
    shown.AddRenderer(renderer)
    shown.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(shown)
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(str(path))
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    return path


def test_the_atlas_carries_the_texture_and_its_coordinates(sphere):
    mesh, atlas = sphere
    assert atlas.GetNumberOfBlocks() == 3
    textures = atlas.GetBlock(2)
    assert textures.GetMetaData(0).Get(textures.NAME()) == "BaseColor"
    image = textures.GetBlock(0)
    assert image.GetDimensions() == (64, 32, 1)
    ours = image.GetPointData().GetArray("RGBA")
    theirs = mesh.GetFieldData().GetArray(tcArrayNames.BaseColorTexture())
    assert ours.GetNumberOfTuples() == theirs.GetNumberOfTuples() == 64 * 32
    assert all(ours.GetTuple4(t) == theirs.GetTuple4(t) for t in range(0, 2048, 7))
    finest = atlas.GetBlock(1).GetBlock(0).GetPointData()
    assert finest.GetArray(tcArrayNames.TextureCoordinates()).GetNumberOfComponents() == 2


def test_color_by_texture_matches_vtk_rendering_the_textured_input(sphere, tmp_path):
    from vtkmodules.vtkRenderingCore import vtkPolyDataMapper

    mesh, atlas = sphere
    temp = pathlib.Path(os.environ.get("TRICHART_TEMP", tmp_path))
    temp.mkdir(parents=True, exist_ok=True)
    for name, direction in (("seam", (1, 0, 0)), ("back", (-1, 0.3, 0)), ("pole", (0, 1, 0.2))):
        reference = vtkPolyDataMapper()
        reference.SetInputData(mesh)
        reference.ScalarVisibilityOff()
        expected = render(reference, trichart.base_color_texture(mesh), temp / f"texture_vtk_{name}.png",
                          direction)
        lod = trichart.tcLODMapper()
        lod.SetInputData(atlas)
        lod.SetFixedLevel(-1)
        lod.SetColorMode(trichart.tcLODMapper.ColorByTexture)
        actual = render(lod, None, temp / f"texture_lod_{name}.png", direction)
        # The finest level lies within a fraction of a pixel of the sphere; only pixels on the
        # edges of the checker's squares and of the silhouette may differ.
        wrong = differing_pixels(actual, expected, 48)
        assert wrong < 0.01 * SIZE[0] * SIZE[1], f"{name}: {wrong} pixels differ ({actual})"
        # Without the texture the picture is the actor's white: it cannot pass by accident.
        lod.SetColorMode(trichart.tcLODMapper.ColorByActor)
        plain = render(lod, None, temp / f"texture_plain_{name}.png", direction)
        assert differing_pixels(plain, expected, 48) > 0.1 * SIZE[0] * SIZE[1]


def mesh_triangles(mesh):
    from vtkmodules.util.numpy_support import vtk_to_numpy

    return vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3)


def triangle_coordinates(mesh):
    """Per triangle of `mesh`, its corners' TextureCoordinates (#F x 3 x 2) and positions."""
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy

    triangles = mesh_triangles(mesh)
    uv = vtk_to_numpy(mesh.GetPointData().GetArray(tcArrayNames.TextureCoordinates()))
    points = vtk_to_numpy(mesh.GetPoints().GetData())
    return uv[triangles], points, numpy.asarray(uv)


def test_rebuilt_mesh_splits_the_seam_so_each_side_keeps_its_coordinates(sphere):
    import numpy

    _, atlas = sphere
    mesh = trichart.rebuild(atlas)
    corners, points, uv = triangle_coordinates(mesh)
    # Away from the poles (where u turns all the way round a point) a triangle spans a few
    # percent of u; one that reached across the seam (a welded point carrying the other side's u)
    # would span almost all of it.
    span = corners[:, :, 0].max(axis=1) - corners[:, :, 0].min(axis=1)
    y = numpy.abs(points[mesh_triangles(mesh)][:, :, 1]).max(axis=1)
    assert span[y < 0.98].max() < 0.1, span[y < 0.98].max()
    assert span.max() < 0.5, span.max()
    # The seam's points come twice: the same position, u = 0 on one copy and 1 on the other.
    _, first, counts = numpy.unique(points, axis=0, return_index=True, return_counts=True)
    doubled = numpy.flatnonzero(counts > 1)
    assert len(doubled) >= 9, len(doubled)
    assert len(points) - len(first) == int((counts - 1).sum())


def test_gltf_export_carries_the_texture_and_its_coordinates(sphere, tmp_path):
    import json
    import struct

    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy

    mesh, atlas = sphere
    out = tmp_path / "sphere.glb"
    lods = trichart.export_gltf(atlas, out)
    data = out.read_bytes()
    length = struct.unpack_from("<I", data, 12)[0]
    gltf = json.loads(data[20:20 + length])
    material = gltf["materials"][0]["pbrMetallicRoughness"]
    assert material["baseColorTexture"]["index"] == 0
    assert material.get("baseColorFactor", [1, 1, 1, 1]) == [1, 1, 1, 1]  # white: the default
    assert gltf["images"][0]["mimeType"] == "image/png" and "bufferView" in gltf["images"][0]
    assert gltf["samplers"][0]["wrapS"] == 10497  # REPEAT
    assert "TEXCOORD_0" in gltf["meshes"][0]["primitives"][0]["attributes"]
    assert not any(name.startswith("_") for name in gltf["meshes"][0]["primitives"][0]["attributes"])
    # Read back by the mesh reader (Assimp): the texture byte for byte (PNG is lossless) and
    # LOD 0's coordinates those of the rebuilt finest level (Assimp flips v back).
    read = trichart.read_mesh(out)
    fd = read.GetFieldData()
    assert numpy.array_equal(vtk_to_numpy(fd.GetArray(tcArrayNames.BaseColorTexture())),
                             vtk_to_numpy(mesh.GetFieldData().GetArray(
                                 tcArrayNames.BaseColorTexture())))
    rebuilt = trichart.rebuild(atlas)
    assert read.GetNumberOfPoints() == rebuilt.GetNumberOfPoints()
    assert read.GetNumberOfPolys() == lods[0]["triangles"] == rebuilt.GetNumberOfPolys()
    ours = vtk_to_numpy(rebuilt.GetPointData().GetArray(tcArrayNames.TextureCoordinates()))
    theirs = vtk_to_numpy(read.GetPointData().GetArray(tcArrayNames.TextureCoordinates()))
    assert numpy.abs(ours - theirs).max() < 1e-6


def test_vertex_colours_reach_the_renderer_and_the_export(testing_data, tmp_path):
    # The sphere with a colour per point from its position (as a PLY's red, green, blue
    # properties read): the atlas resamples Colors, ColorByVertexColors draws them as VTK draws
    # the input's colours, and the export writes them as COLOR_0.
    import json
    import struct

    import numpy
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkRenderingCore import vtkPolyDataMapper

    mesh = trichart.read_mesh(testing_data / "meshes" / "textured_sphere.glb")
    points = vtk_to_numpy(mesh.GetPoints().GetData())
    rgba = numpy.empty((len(points), 4), numpy.uint8)
    rgba[:, :3] = numpy.clip(numpy.round((points + 1) * 127.5), 0, 255)
    rgba[:, 3] = 255
    colors = numpy_to_vtk(rgba, deep=True)
    colors.SetName(tcArrayNames.Colors())
    mesh.GetPointData().AddArray(colors)
    mesh.GetPointData().RemoveArray(tcArrayNames.TextureCoordinates())
    atlas = atlas_of(mesh)
    assert atlas.GetNumberOfBlocks() == 2  # no texture to carry
    temp = pathlib.Path(os.environ.get("TRICHART_TEMP", tmp_path))
    reference = vtkPolyDataMapper()
    reference.SetInputData(mesh)
    reference.SetScalarModeToUsePointFieldData()
    reference.SelectColorArray(tcArrayNames.Colors())
    reference.SetColorModeToDirectScalars()
    reference.ScalarVisibilityOn()
    expected = render(reference, None, temp / "colors_vtk.png", (1, 0.5, 0.7))
    lod = trichart.tcLODMapper()
    lod.SetInputData(atlas)
    lod.SetFixedLevel(-1)
    lod.SetColorMode(trichart.tcLODMapper.ColorByVertexColors)
    actual = render(lod, None, temp / "colors_lod.png", (1, 0.5, 0.7))
    # Smooth colours: the two pictures agree within a few levels inside the sphere (one wrong
    # vertex colour shows as a streak of tens of pixels), and nearly everywhere at its edge.
    assert differing_inner_pixels(actual, expected, 12) < 10
    assert differing_pixels(actual, expected, 12) < 0.01 * SIZE[0] * SIZE[1]
    lod.SetColorMode(trichart.tcLODMapper.ColorByActor)
    plain = render(lod, None, temp / "colors_plain.png", (1, 0.5, 0.7))
    assert differing_pixels(plain, expected, 12) > 0.1 * SIZE[0] * SIZE[1]

    out = tmp_path / "colors.glb"
    trichart.export_gltf(atlas, out)
    data = out.read_bytes()
    gltf = json.loads(data[20:20 + struct.unpack_from("<I", data, 12)[0]])
    primitive = gltf["meshes"][0]["primitives"][0]
    assert "COLOR_0" in primitive["attributes"] and "TEXCOORD_0" not in primitive["attributes"]
    assert "images" not in gltf
    read = trichart.read_mesh(out)
    back = vtk_to_numpy(read.GetPointData().GetArray(tcArrayNames.Colors())).astype(int)
    read_points = vtk_to_numpy(read.GetPoints().GetData())
    # The resampled colours still follow the position rule within a level or two.
    assert numpy.abs(back[:, :3] - (read_points + 1) * 127.5).max() < 3
