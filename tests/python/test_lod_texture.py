"""A textured mesh keeps its texture through the pipeline: the atlas carries the texture and its
coordinates, tcLODMapper colours by them, and the picture matches VTK's own rendering of the
textured input (testing-data/meshes/textured_sphere.glb: a UV sphere with a seam at u = 0 / 1,
one pole vertex per segment, and a checker of 8 hues, scripts/make-textured-sphere.py)."""
import os
import pathlib

import pytest

import trichart
from trichart import tcArrayNames

from imagecompare import differing_pixels

SIZE = (320, 320)


@pytest.fixture(scope="module")
def sphere(testing_data):
    mesh = trichart.read_mesh(testing_data / "meshes" / "textured_sphere.glb")
    clean, _ = trichart.prepare(mesh)
    surface, _ = trichart.curvature(clean)
    clusters, _ = trichart.cluster(surface)
    features, _, _ = trichart.refine_features(clusters)
    _, parameterized = trichart.base_complex(features)
    patches, _ = trichart.trace_paths(parameterized)
    return mesh, trichart.geometry_images(patches)


def input_texture(mesh):
    """The reader's BaseColorTexture field as a vtkTexture (linear, mipmapped, repeated)."""
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkRenderingCore import vtkTexture

    fd = mesh.GetFieldData()
    size = fd.GetArray(tcArrayNames.BaseColorTextureSize())
    image = vtkImageData()
    image.SetDimensions(int(size.GetComponent(0, 0)), int(size.GetComponent(0, 1)), 1)
    image.GetPointData().SetScalars(fd.GetArray(tcArrayNames.BaseColorTexture()))
    texture = vtkTexture()
    texture.SetInputData(image)
    texture.InterpolateOn()
    texture.MipmapOn()
    texture.RepeatOn()
    return texture


def render(mapper, texture, path, direction):
    """`mapper` unlit (the pure surface colour) from `direction`, to the PNG `path`."""
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkRenderer, vtkRenderWindow,
                                             vtkWindowToImageFilter)

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
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(*SIZE)
    window.AddRenderer(renderer)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
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
        expected = render(reference, input_texture(mesh), temp / f"texture_vtk_{name}.png",
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
