#!/usr/bin/python3
"""The glTF export (`trichart export`) against gltfpack, Debian's meshoptimizer tool, in one run:
per LOD of TriChart's chain, its triangles, Hausdorff and RMS error against the prepared input
(percent of the diagonal) and bytes, next to `gltfpack -si R` at the same triangle ratio (floats,
-noq, the same precision as ours; and its default 14-bit quantized positions, bytes only), then
the whole chain's file against the sum of gltfpack's files.

  PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 bench/gltf_export.py [mesh ...]
      default meshes: testing-data/meshes/bunny_npm.off and, when ../shared/data is there,
      static_medium/bunny_glmark2.obj
"""
import json
import os
import pathlib
import shutil
import struct
import subprocess
import sys
import tempfile

import numpy
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

import trichart

ROOT = pathlib.Path(__file__).resolve().parents[1]


def glb_meshes(path):
    """(positions, triangles, bytes) of every mesh of a GLB with float positions."""
    data = pathlib.Path(path).read_bytes()
    json_length = struct.unpack_from("<I", data, 12)[0]
    gltf = json.loads(data[20:20 + json_length])
    start = 20 + json_length + 8
    types = {5126: numpy.float32, 5125: numpy.uint32, 5123: numpy.uint16, 5121: numpy.uint8}
    widths = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}

    def read(index):
        a = gltf["accessors"][index]
        view = gltf["bufferViews"][a["bufferView"]]
        offset = start + view.get("byteOffset", 0) + a.get("byteOffset", 0)
        stride = view.get("byteStride", 0)
        dtype = numpy.dtype(types[a["componentType"]])
        n = widths[a["type"]]
        if stride and stride != n * dtype.itemsize:  # interleaved: gather by stride
            rows = numpy.frombuffer(data, numpy.uint8, a["count"] * stride, offset)
            rows = rows.reshape(-1, stride)[:, :n * dtype.itemsize].copy()
            return rows.view(dtype).reshape(-1, n)
        return numpy.frombuffer(data, dtype, a["count"] * n, offset).reshape(-1, n)

    meshes = []
    for mesh in gltf["meshes"]:
        p = mesh["primitives"][0]
        used = {p["indices"], *p["attributes"].values()}
        size = sum(gltf["bufferViews"][gltf["accessors"][i]["bufferView"]]["byteLength"]
                   for i in used)
        meshes.append((read(p["attributes"]["POSITION"]), read(p["indices"]).reshape(-1, 3),
                       size))
    return meshes


def polydata(positions, triangles):
    mesh = vtkPolyData()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(numpy.ascontiguousarray(positions, dtype=numpy.float64),
                                deep=True))
    mesh.SetPoints(points)
    cells = vtkCellArray()
    offsets = numpy.arange(0, 3 * len(triangles) + 1, 3, dtype=numpy.int64)
    cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True),
                  numpy_to_vtkIdTypeArray(triangles.astype(numpy.int64).ravel(), deep=True))
    mesh.SetPolys(cells)
    return mesh


def error(positions, triangles, reference):
    _, f = trichart.surface_distance(polydata(positions, triangles), reference)
    return 100 * f["hausdorff"] / f["diagonal"], 100 * f["rms"] / f["diagonal"]


def gltfpack(source, ratio, out, quantized):
    command = ["gltfpack", "-i", str(source), "-o", str(out), "-si", f"{ratio:.6f}"]
    subprocess.run(command + ([] if quantized else ["-noq"]), check=True,
                   capture_output=True, text=True)
    return out.stat().st_size


def bench(mesh_path, work):
    atlas_path = work / "atlas.exr"
    trichart.build(mesh_path, atlas_path)
    atlas = trichart.read_atlas(atlas_path)
    chain = work / "chain.glb"
    trichart.export_gltf(atlas, chain)
    reference, _ = trichart.prepare(trichart.read_mesh(mesh_path))
    source = work / "input.obj"
    trichart.write_mesh(reference, source)
    triangles = reference.GetNumberOfPolys()
    print(f"\n== {pathlib.Path(mesh_path).name}: {triangles} triangles, "
          f"{chain.stat().st_size} bytes for the whole chain")
    print(f"{'LOD':>3} {'tris':>8} {'H %':>8} {'RMS %':>8} {'bytes':>9} | {'gltfpack tris':>13} "
          f"{'H %':>8} {'RMS %':>8} {'bytes':>9} {'quantized':>9} | {'H/peer':>6} {'bytes/peer':>10}")
    total_float = total_quantized = 0
    for k, (positions, faces, size) in enumerate(glb_meshes(chain)):
        h, rms = error(positions, faces, reference)
        ratio = min(1.0, len(faces) / triangles)
        peer = work / f"gltfpack{k}.glb"
        total_float += gltfpack(source, ratio, peer, quantized=False)
        total_quantized += gltfpack(source, ratio, work / f"gltfpack{k}q.glb", quantized=True)
        peer_positions, peer_faces, _ = glb_meshes(peer)[0]
        peer_h, peer_rms = error(peer_positions, peer_faces, reference)
        print(f"{k:>3} {len(faces):>8} {h:>8.4f} {rms:>8.4f} {size:>9} | {len(peer_faces):>13} "
              f"{peer_h:>8.4f} {peer_rms:>8.4f} {peer.stat().st_size:>9} "
              f"{(work / f'gltfpack{k}q.glb').stat().st_size:>9} | "
              f"{h / peer_h if peer_h else float('inf'):>6.2f} "
              f"{size / peer.stat().st_size:>10.2f}")
    print(f"whole chain: {chain.stat().st_size} bytes in one file; gltfpack's files at the same "
          f"ratios: {total_float} bytes as floats, {total_quantized} quantized")


def main(argv):
    meshes = argv or [str(ROOT / "testing-data" / "meshes" / "bunny_npm.off")]
    shared = ROOT.parent / "shared" / "data" / "static_medium" / "bunny_glmark2.obj"
    if not argv and shared.exists():
        meshes.append(str(shared))
    if not shutil.which("gltfpack"):
        print("gltfpack is not installed (scripts/install-deps.sh installs it)")
        return 1
    for mesh in meshes:
        with tempfile.TemporaryDirectory() as folder:
            bench(mesh, pathlib.Path(folder))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
