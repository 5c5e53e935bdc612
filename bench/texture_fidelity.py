#!/usr/bin/python3
"""How faithfully a texture survives the pipeline, per mesh: the atlas built at the defaults
(texture seams as feature lines) and again with --no-seam-lines, each drawn by tcLODMapper at
every chart's finest level coloured by the texture, against VTK drawing the textured input
(unlit, the pure texture colour, from four sides), as the share of the pixels inside the surface
(2 pixels from its silhouette) whose colour differs by more than 48 of 255 (the edges of the
checker's squares shift by a pixel or so; a smeared seam or a wrong chart side shows as whole
bands); and the rebuilt finest level's points
and the seam copies among them (a point kept once per side of a texture seam).

A mesh without a texture of its own gets a checker of 8 x 8 hues (256 x 256 texels), so that any
texture coordinates are measured.

  PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 bench/texture_fidelity.py [mesh ...]
      default meshes: testing-data/meshes/textured_sphere.glb and, when ../shared/data is there,
      skinned/wuson/wuson.glb, skinned/snake_fbx/snake_fbx.glb, skinned/md2/sydney.md2
"""
import os
import pathlib
import sys

import numpy
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkWindowToImageFilter)

import trichart
from trichart import tcArrayNames

ROOT = pathlib.Path(__file__).resolve().parents[1]
SIZE = 400
SIDES = ((1, 0.4, 0.6), (-1, 0.3, -0.5), (0.2, 1, -0.3), (-0.3, -0.8, 1))
HUES = numpy.array([(255, 0, 0), (255, 128, 0), (255, 255, 0), (0, 255, 0), (0, 255, 255),
                    (0, 0, 255), (128, 0, 255), (255, 0, 255)])


def add_checker(mesh):
    """Field arrays of a 256 x 256 checker of 8 x 8 squares, each its hue darkened by its row."""
    y, x = numpy.mgrid[0:256, 0:256] // 32
    rgb = HUES[(x + 3 * y) % 8] * (8 - y[..., None]) // 8
    rgba = numpy.concatenate([rgb, numpy.full((256, 256, 1), 255)], axis=2).astype(numpy.uint8)
    array = numpy_to_vtk(rgba.reshape(-1, 4), deep=True)
    size = numpy_to_vtk(numpy.array([[256, 256]], numpy.int32), deep=True)
    for a, name in ((array, tcArrayNames.BaseColorTexture()),
                    (size, tcArrayNames.BaseColorTextureSize())):
        a.SetName(name)
        mesh.GetFieldData().AddArray(a)


class Pictures:
    """One off-screen window for every picture (each window is an X connection)."""

    def __init__(self):
        self.window = vtkRenderWindow()
        self.window.SetOffScreenRendering(1)
        self.window.SetMultiSamples(0)
        self.window.SetSize(SIZE, SIZE)

    def take(self, mapper, texture, side, bounds):
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().LightingOff()
        if texture is not None:
            actor.SetTexture(texture)
        renderer = vtkRenderer()
        renderer.AddActor(actor)
        center = [(bounds[2 * k] + bounds[2 * k + 1]) / 2 for k in range(3)]
        radius = numpy.linalg.norm([bounds[2 * k + 1] - bounds[2 * k] for k in range(3)]) / 2
        norm = numpy.linalg.norm(side)
        camera = renderer.GetActiveCamera()
        camera.SetFocalPoint(*center)
        camera.SetPosition(*(c + 3.2 * radius * s / norm for c, s in zip(center, side)))
        camera.SetViewUp(*((0, 0, 1) if abs(side[1]) > 0.9 * norm else (0, 1, 0)))
        camera.SetViewAngle(40)
        renderer.ResetCameraClippingRange()
        previous = self.window.GetRenderers().GetFirstRenderer()
        if previous is not None:
            self.window.RemoveRenderer(previous)
        self.window.AddRenderer(renderer)
        self.window.Render()
        grab = vtkWindowToImageFilter()
        grab.SetInput(self.window)
        grab.SetInputBufferTypeToRGB()
        grab.Update()
        rgb = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars())
        return rgb.reshape(SIZE, SIZE, 3).astype(int)


def atlas_of(mesh, seam_lines):
    # As `trichart build --fill-holes --split-non-manifold`: characters are often open.
    clean, _ = trichart.prepare(mesh, fill_holes=True, split_non_manifold=True)
    surface, _ = trichart.curvature(clean)
    clusters, _ = trichart.cluster(surface)
    features, lines, _ = trichart.refine_features(clusters, seam_lines=seam_lines)
    _, parameterized = trichart.base_complex(features)
    patches, _ = trichart.trace_paths(parameterized)
    return trichart.geometry_images(patches), lines.GetNumberOfCells()


def save(rgb, path):
    """The picture `rgb` (rows from the bottom, as VTK reads the window) as a PNG."""
    image = vtkImageData()
    image.SetDimensions(rgb.shape[1], rgb.shape[0], 1)
    image.GetPointData().SetScalars(numpy_to_vtk(rgb.reshape(-1, 3).astype(numpy.uint8), deep=True))
    writer = vtkPNGWriter()
    writer.SetFileName(str(path))
    writer.SetInputData(image)
    writer.Write()


def inner(rgb, margin=2):
    """The pixels the surface covers together with every pixel within `margin` of them: its
    inside, not its silhouette, which the finest level moves by a pixel here and there."""
    covered = rgb.max(axis=2) > 0
    out = covered.copy()
    for dy in range(-margin, margin + 1):
        for dx in range(-margin, margin + 1):
            out &= numpy.roll(numpy.roll(covered, dy, axis=0), dx, axis=1)
    return out


def wrong_share(pictures, mesh, atlas):
    """Share of the pixels inside the surface in both pictures, over SIDES, whose colour
    differs by more than 48, and their count."""
    reference = vtkPolyDataMapper()
    reference.SetInputData(mesh)
    reference.ScalarVisibilityOff()
    lod = trichart.tcLODMapper()
    lod.SetInputData(atlas)
    lod.SetFixedLevel(-1)
    lod.SetColorMode(trichart.tcLODMapper.ColorByTexture)
    texture = trichart.base_color_texture(mesh)
    covered = wrong = 0
    keep = os.environ.get("TRICHART_BENCH_PICTURES")
    for k, side in enumerate(SIDES):
        a = pictures.take(reference, texture, side, mesh.GetBounds())
        b = pictures.take(lod, None, side, mesh.GetBounds())
        if keep:
            save(numpy.concatenate([a, b], axis=1), pathlib.Path(keep) / f"side{k}.png")
        mask = inner(a) & inner(b)
        covered += int(mask.sum())
        wrong += int(((numpy.abs(a - b).max(axis=2) > 48) & mask).sum())
    return wrong / max(covered, 1), covered


def measure(path, pictures):
    mesh = trichart.read_mesh(path)
    if mesh.GetPointData().GetArray(tcArrayNames.TextureCoordinates()) is None:
        print(f"{path.name}: no texture coordinates, skipped")
        return
    own = mesh.GetFieldData().GetArray(tcArrayNames.BaseColorTexture()) is not None
    if not own:
        add_checker(mesh)
    mesh.GetPointData().SetActiveTCoords(tcArrayNames.TextureCoordinates())
    print(f"{path.name}: {mesh.GetNumberOfPolys()} triangles, "
          f"{'its own texture' if own else 'a checker texture'}")
    for seam_lines in (True, False):
        try:
            atlas, lines = atlas_of(mesh, seam_lines)
        except trichart.TriChartError as error:
            print(f"  seam lines {'on ' if seam_lines else 'off'}: {error}")
            continue
        charts = trichart.atlas_charts(atlas).GetNumberOfRows()
        rebuilt = trichart.rebuild(atlas)
        points = vtk_to_numpy(rebuilt.GetPoints().GetData())
        copies = len(points) - len(numpy.unique(points, axis=0))
        share, measured = wrong_share(pictures, mesh, atlas)
        print(f"  seam lines {'on ' if seam_lines else 'off'}: {lines} feature lines, {charts} "
              f"charts; finest level {len(points)} points, {copies} seam copies; "
              f"{100 * share:.2f}% of {measured} pixels inside the surface off by more than 48 of 255")


def main(paths):
    if not paths:
        paths = [ROOT / "testing-data" / "meshes" / "textured_sphere.glb"]
        shared = ROOT.parent / "shared" / "data" / "skinned"
        for name in ("wuson/wuson.glb", "snake_fbx/snake_fbx.glb", "md2/sydney.md2"):
            if (shared / name).is_file():
                paths.append(shared / name)
    pictures = Pictures()
    for path in paths:
        measure(pathlib.Path(path), pictures)


if __name__ == "__main__":
    main(sys.argv[1:])
