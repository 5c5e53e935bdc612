#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora (tests/fuzz/corpus/<target>/): small, valid files of
every variant each reader accepts, from which the fuzzers mutate. Run it from anywhere; the
atlas seeds need the `trichart` package of a build (PYTHONPATH=build/lib/python3.11/dist-packages)
and are kept as they are when it is absent. The files are committed; this script says how they
were made and makes them again after a format change."""
import base64
import gzip
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")
ROOT = os.path.dirname(os.path.dirname(HERE))

# The unit tetrahedron, faces outward, and the cube of testing-data/meshes/cube.off.
TET = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TET_FACES = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
CUBE = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
CUBE_QUADS = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]


def write(target, name, data):
    folder = os.path.join(CORPUS, target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def off_seeds():
    shutil.copyfile(os.path.join(ROOT, "testing-data", "meshes", "cube.off"),
                    os.path.join(CORPUS, "off", "cube.off"))
    points = "\n".join(" ".join(str(c) for c in p) for p in TET)
    faces = "\n".join("3 " + " ".join(str(i) for i in f) for f in TET_FACES)
    write("off", "tet_counts_on_keyword_line.off", f"OFF 4 4 6\n{points}\n{faces}\n")
    write("off", "tet_comments_crlf.off",
          "# a tetrahedron\r\nOFF\r\n\r\n# counts\r\n4 4 0\r\n" +
          points.replace("\n", "\r\n") + "\r\n# faces\r\n" + faces.replace("\n", "\r\n") + "\r\n")
    write("off", "tet_colours.off", "COFF\n4 4 0\n" +
          "\n".join(" ".join(str(c) for c in p) + " 255 0 0 255" for p in TET) + "\n" +
          "\n".join("3 " + " ".join(str(i) for i in f) + " 0.5 0.5 0.5" for f in TET_FACES) + "\n")
    write("off", "tet_normals_texture.off", "STNOFF\n4 4 0\n" +
          "\n".join(" ".join(str(c) for c in p) + " 0 0 1 0.5 0.5" for p in TET) + "\n" +
          faces + "\n")
    write("off", "tet_homogeneous.off", "4OFF\n4 4 0\n" +
          "\n".join(" ".join(str(2 * c) for c in p) + " 2" for p in TET) + "\n" + faces + "\n")
    write("off", "tet_dimension.off", "nOFF\n3\n4 4 0\n" + points + "\n" + faces + "\n")
    write("off", "cube_quads_edges.off", "OFF\n8 6 12\n" +
          "\n".join(" ".join(str(c) for c in p) for p in CUBE) + "\n" +
          "\n".join("4 " + " ".join(str(i) for i in q) for q in CUBE_QUADS) + "\n" +
          "2 0 1\n2 1 3\n")
    write("off", "tet_nan_inf.off", "OFF\n4 4 0\n0 0 0\n1 nan 0\n0 1 inf\n0 0 -1e308\n" +
          faces + "\n")


def ply(fmt, points, faces, index="int", count="uchar", coord="float", extra=""):
    """A PLY file of `points` and `faces` in format `fmt`, with a colour per vertex."""
    header = (f"ply\nformat {fmt} 1.0\ncomment a seed\nobj_info made by make_seeds.py\n"
              f"element vertex {len(points)}\nproperty {coord} x\nproperty {coord} y\n"
              f"property {coord} z\nproperty uchar red\nelement face {len(faces)}\n"
              f"property list {count} {index} vertex_indices\n{extra}end_header\n")
    if fmt == "ascii":
        body = "".join(" ".join(str(c) for c in p) + " 7\n" for p in points)
        body += "".join(f"{len(f)} " + " ".join(str(i) for i in f) + "\n" for f in faces)
        return header.encode() + body.encode()
    order = "<" if fmt == "binary_little_endian" else ">"
    codes = {"uchar": "B", "ushort": "H", "int": "i", "uint": "I", "float": "f", "double": "d"}
    body = b"".join(struct.pack(order + codes[coord] * 3 + "B", *p, 7) for p in points)
    body += b"".join(struct.pack(order + codes[count] + codes[index] * len(f), len(f), *f)
                     for f in faces)
    return header.encode() + body


def ply_seeds():
    seeds = {
        "tet_ascii.ply": ply("ascii", TET, TET_FACES),
        "tet_binary_little_endian.ply": ply("binary_little_endian", TET, TET_FACES),
        "tet_binary_big_endian.ply": ply("binary_big_endian", TET, TET_FACES),
        "cube_quads_double_uint.ply": ply("binary_little_endian", CUBE, CUBE_QUADS, "uint",
                                          "uchar", "double"),
        "cube_quads_ushort_big.ply": ply("binary_big_endian", CUBE, CUBE_QUADS, "ushort", "uint"),
        "cube_quads_ascii.ply": ply("ascii", CUBE, CUBE_QUADS),
    }
    seeds["tet_ascii_crlf.ply"] = seeds["tet_ascii.ply"].replace(b"\n", b"\r\n")
    for name, data in seeds.items():
        write("ply", name, data)
        # mtime 0: the same bytes every run.
        write("ply_gz", name + ".gz", gzip.compress(data, mtime=0))


def obj_seeds():
    write("obj", "tet.obj", "# a tetrahedron\nmtllib none.mtl\no tet\n" +
          "".join(f"v {x} {y} {z}\n" for x, y, z in TET) +
          "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\ng part\nusemtl red\ns off\n" +
          "f -4 -2 -3\nf 1/1 2/2 4/3\nf 1//1 4//1 3//1\nf 2/1/1 3/2/1 4/3/1\n")
    write("obj", "cube_quads.obj", "".join(f"v {x} {y} {z}\n" for x, y, z in CUBE) +
          "".join("f " + " ".join(str(i + 1) for i in q) + "\n" for q in CUBE_QUADS) +
          "l 1 2\np 3\n")
    write("obj", "tet_colours_crlf.obj", "".join(f"v {x} {y} {z} 1 0 0\r\n" for x, y, z in TET) +
          "".join("f " + " ".join(str(i + 1) for i in f) + "\r\n" for f in TET_FACES))


def tet_buffer():
    return (b"".join(struct.pack("<3f", *p) for p in TET) +
            b"".join(struct.pack("<3H", *f) for f in TET_FACES))


def gltf_json(uri):
    buffer = {"byteLength": 72}
    if uri:
        buffer["uri"] = "data:application/octet-stream;base64," + \
            base64.b64encode(tet_buffer()).decode()
    return {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0, "translation": [10, 0, 0]},
                  {"translation": [0, 5, 0], "children": [2]},
                  {"mesh": 0, "scale": [-1, 1, 1]}],
        "meshes": [{"name": "tet", "primitives": [{"attributes": {"POSITION": 0},
                                                   "indices": 1, "mode": 4}]}],
        "buffers": [buffer],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 1]},
                      {"bufferView": 1, "componentType": 5123, "count": 12,
                       "type": "SCALAR"}]}


def glb():
    text = json.dumps(gltf_json(False), separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    binary = tet_buffer()
    chunks = struct.pack("<I4s", len(text), b"JSON") + text + \
        struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def md2():
    """A one-frame MD2 model of the tetrahedron (one skin name, texture coordinates, an empty
    GL command list: Assimp refuses a frame that ends the file)."""
    skin = b"tet.pcx".ljust(64, b"\0")
    st = struct.pack("<6h", 0, 0, 64, 0, 0, 64)
    tris = b"".join(struct.pack("<3h3h", *f, 0, 1, 2) for f in TET_FACES)
    frame = struct.pack("<3f3f16s", 1, 1, 1, 0, 0, 0, b"frame0") + \
        b"".join(struct.pack("<4B", *p, 0) for p in TET)
    glcmds = struct.pack("<i", 0)
    offsets, offset = [], 68
    for part in (skin, st, tris, frame, glcmds):
        offsets.append(offset)
        offset += len(part)
    header = struct.pack("<4s16i", b"IDP2", 8, 64, 64, len(frame), 1, len(TET), 3,
                         len(TET_FACES), 1, 1, *offsets, offset)
    return header + skin + st + tris + frame + glcmds


def scene_seeds():
    write("scene", "tet.gltf", json.dumps(gltf_json(True), indent=1))
    write("scene", "tet.glb", glb())
    write("scene", "tet.x", "xof 0303txt 0032\nFrame root {\n FrameTransformMatrix {\n"
          "  1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0,0.0,2.0,0.0,0.0,1.0;;\n }\n"
          " Mesh tet {\n  4;\n" +
          ",\n".join(f"  {x:.1f};{y:.1f};{z:.1f};" for x, y, z in TET) + ";\n  4;\n" +
          ",\n".join("  3;" + ",".join(str(i) for i in f) + ";" for f in TET_FACES) +
          ";\n }\n}\n")
    indices = []
    for f in TET_FACES:
        indices += [f[0], f[1], -f[2] - 1]
    write("scene", "tet.fbx",
          "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n\tFBXHeaderVersion: 1003\n"
          "\tFBXVersion: 7400\n}\nObjects:  {\n"
          "\tGeometry: 1000, \"Geometry::tet\", \"Mesh\" {\n"
          f"\t\tVertices: *12 {{\n\t\t\ta: {','.join(str(c) for p in TET for c in p)}\n\t\t}}\n"
          f"\t\tPolygonVertexIndex: *12 {{\n\t\t\ta: {','.join(str(i) for i in indices)}\n"
          "\t\t}\n\t\tGeometryVersion: 124\n\t}\n"
          "\tModel: 2000, \"Model::tet\", \"Mesh\" {\n\t\tVersion: 232\n\t}\n}\n"
          "Connections:  {\n\tC: \"OO\",1000,2000\n\tC: \"OO\",2000,0\n}\n")
    write("scene", "tet.md2", md2())


def stl_seeds():
    def normal(a, b, c):
        u = [b[i] - a[i] for i in range(3)]
        v = [c[i] - a[i] for i in range(3)]
        return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    tris = [[TET[i] for i in f] for f in TET_FACES]
    ascii_stl = "solid tet\n" + "".join(
        " facet normal {} {} {}\n  outer loop\n".format(*normal(*t)) +
        "".join("   vertex {} {} {}\n".format(*p) for p in t) + "  endloop\n endfacet\n"
        for t in tris) + "endsolid tet\n"
    write("stl", "tet_ascii.stl", ascii_stl)
    write("stl", "tet_ascii_crlf.stl", ascii_stl.replace("\n", "\r\n"))
    for name, header in (("tet_binary.stl", b"binary tetrahedron"),
                         ("tet_binary_solid_header.stl", b"solid but binary")):
        body = b"".join(struct.pack("<12fH", *normal(*t), *[c for p in t for c in p], 0)
                        for t in tris)
        write("stl", name, header.ljust(80, b"\0") + struct.pack("<I", len(tris)) + body)


def height_seeds():
    grid = "1 2 3\n4 -9999 6\n7 8 9\n"
    write("height", "hill.asc", "ncols 3\nnrows 3\nxllcorner 500000\nyllcorner 4100000\n"
          "cellsize 10\nNODATA_value -9999\n" + grid)
    write("height", "centre.asc", "NCOLS 2\nNROWS 2\nXLLCENTER 0.5\nYLLCENTER 0.5\n"
          "DX 1\nDY 2\n0 1\n2 3\n")
    pixels = b"".join(struct.pack(">H", 100 + k) for k in range(12))
    write("height", "ramp16.pgm", b"P5\n4 3\n65535\n" + pixels)
    write("height", "ramp8.pgm", b"P5\n4 3\n255\n" + bytes(range(12)))
    write("height", "ramp_ascii.pgm", "P2\n3 2\n9\n0 1 2\n3 4 5\n")
    row = bytes([0, 64, 128, 255])  # 4 x 2, 8-bit grey, rows padded to 4 bytes
    palette = b"".join(bytes([g, g, g, 0]) for g in range(256))
    header = struct.pack("<2sIHHI", b"BM", 14 + 40 + 1024 + 8, 0, 0, 14 + 40 + 1024)
    info = struct.pack("<IiiHHIIiiII", 40, 4, 2, 1, 8, 0, 8, 2835, 2835, 256, 256)
    write("height", "grey.bmp", header + info + palette + row + row)


def have_trichart():
    try:
        import trichart  # noqa: F401
    except ImportError:
        return False
    return True


# Atlas seeds of an older format version, kept as they are (the writer no longer makes them,
# the reader still reads them): version 3 (float texels) of the two atlases below.
KEPT_ATLAS_SEEDS = ("cube_v3.exr", "bunny_coarse_v3.exr")


def atlas_seeds():
    """Atlases written by `trichart build` (the whole pipeline), so the seeds are files the
    atlas writer makes (version 4: Position and Normal as lattice codes): the cube (12 charts,
    all at level 2) and the bundled bunny coarsely (64 charts at levels 1 and 2)."""
    if not have_trichart():
        print("make_seeds: no trichart package; the atlas seeds are kept as they are")
        return
    meshes = os.path.join(ROOT, "testing-data", "meshes")
    runs = {"cube.exr": ["cube.off", "--clusters", "2"],
            "bunny_coarse.exr": ["bunny_npm.off", "--clusters", "4", "--base-faces", "20",
                                 "--max-level", "2"]}
    with tempfile.TemporaryDirectory() as tmp:
        for name, (mesh, *options) in runs.items():
            out = os.path.join(tmp, name)
            subprocess.run([sys.executable, "-m", "trichart", "build",
                            os.path.join(meshes, mesh), "-o", out, "-q"] + options, check=True,
                           stdout=subprocess.DEVNULL)
            with open(out, "rb") as f:
                write("atlas", name, f.read())


def cli_seeds():
    """Command lines, one per file (shlex syntax), that the CLI's parser accepts."""
    lines = {
        "build.txt": "build mesh.off -o atlas.exr",
        "build_all.txt": "build mesh.ply.gz -o atlas.exr --stages out --clusters 8 "
                         "--crease-angle 45 --base-faces 50 --max-error 0 --max-level 3 "
                         "--budget 1000 --split-non-manifold --fill-holes --max-hole-edges 30 "
                         "--remove-slivers --stretch-iterations 2 --no-fit --no-image -q",
        "mesh.txt": "mesh atlas.exr --level 2 -o mesh.vtp",
        "eval.txt": "eval mesh.obj atlas.exr --samples 1000",
        "prepare.txt": "prepare mesh.stl -o clean.vtp --merge-tolerance 1e-6 --fill-holes "
                       "--max-hole-edges 0 --split-non-manifold --remove-slivers",
        "info.txt": "info",
        "help.txt": "build --help",
    }
    for name, line in lines.items():
        write("cli", name, line + "\n")


def main():
    for target in ("off", "ply", "ply_gz", "obj", "scene", "stl", "cli", "height") + \
            (("atlas",) if have_trichart() else ()):
        folder = os.path.join(CORPUS, target)
        if target == "atlas":
            for name in os.listdir(folder):
                if name not in KEPT_ATLAS_SEEDS:
                    os.remove(os.path.join(folder, name))
            continue
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder)
    off_seeds()
    ply_seeds()
    obj_seeds()
    scene_seeds()
    stl_seeds()
    atlas_seeds()
    cli_seeds()
    height_seeds()


if __name__ == "__main__":
    main()
