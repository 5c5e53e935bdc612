#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes the textured test sphere: testing-data/meshes/textured_sphere.glb (embedded PNG) and
textured_sphere.obj + .mtl + .png (the same sphere and image), with the standard library only.

The sphere: radius 1, y up, 32 segments around and 16 rings (bands) from the north pole (y = 1)
to the south pole, as exporters make it: a seam of duplicated vertices at u = 0 / 1 and one pole
vertex per segment. Longitude phi = atan2(-z, x) in [0, 2 pi) runs with u = phi / (2 pi); polar
angle theta = acos(y) runs with the image's rows, the north pole at the image's top row.

The image (64 x 32): 8 x 4 squares of 8 x 8 pixels; square (column c, row r counted from the
image's top) has the hue HUES[c] scaled by (4 - r) / 4, integer division, so that a flipped v
(dark rows at the top) or a wrong seam (hue of the wrong column) shows, and tests can compute the
expected colour exactly (tests/vtk/TestMeshReader.cxx, tests/core/io/test_mesh_texture.cpp).

Usage: /usr/bin/python3 scripts/make-textured-sphere.py [output folder]
"""

import json
import math
import os
import struct
import sys
import zlib

SEGMENTS = 32
RINGS = 16
WIDTH, HEIGHT = 64, 32
SQUARE = 8
HUES = [(255, 0, 0), (255, 128, 0), (255, 255, 0), (0, 255, 0),
        (0, 255, 255), (0, 0, 255), (128, 0, 255), (255, 0, 255)]


def checker_colour(column, row):
    """RGB of square (column, row), row 0 at the image's top."""
    return tuple(c * (4 - row) // 4 for c in HUES[column])


def png_bytes():
    """The checker image as an 8-bit RGB PNG, rows top to bottom (as PNG stores them)."""
    raw = bytearray()
    for y in range(HEIGHT):
        raw.append(0)  # filter type None
        for x in range(WIDTH):
            raw.extend(checker_colour(x // SQUARE, y // SQUARE))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", WIDTH, HEIGHT, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
            chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b""))


def position(ring, segment):
    theta = math.pi * ring / RINGS
    phi = 2.0 * math.pi * segment / SEGMENTS
    p = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
    return tuple(0.0 if abs(c) < 1e-12 else c for c in p)


def sphere():
    """Vertices (position, u, row fraction t = theta / pi) and faces (triangles at the poles,
    quads between), counter-clockwise seen from outside. Pole rows: one vertex per segment at the
    segment's middle u."""
    vertices, index = [], {}
    for ring in range(RINGS + 1):
        pole = ring in (0, RINGS)
        for segment in range(SEGMENTS if pole else SEGMENTS + 1):
            u = (segment + 0.5) / SEGMENTS if pole else segment / SEGMENTS
            index[ring, segment] = len(vertices)
            vertices.append((position(ring, segment), u, ring / RINGS))
    faces = []
    for ring in range(RINGS):
        for s in range(SEGMENTS):
            a, b = index[ring, s], index[ring + 1, s]
            if ring == 0:
                faces.append((a, b, index[ring + 1, s + 1]))
            elif ring == RINGS - 1:
                faces.append((a, b, index[ring, s + 1]))
            else:
                faces.append((a, b, index[ring + 1, s + 1], index[ring, s + 1]))
    return vertices, faces


def triangulate(faces):
    """Quads (a, b, c, d) as triangles (a, b, c), (a, c, d)."""
    triangles = []
    for f in faces:
        triangles += [(f[0], f[k], f[k + 1]) for k in range(1, len(f) - 1)]
    return triangles


def check_outward(vertices, triangles):
    volume = 0.0
    for t in triangles:
        a, b, c = (vertices[i][0] for i in t)
        volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                   a[2] * (b[0] * c[1] - b[1] * c[0]))
    assert volume > 0.0, "triangles face inward"


def write_glb(path, vertices, triangles, png):
    """glTF stores v with its origin at the image's top: v = theta / pi."""
    def pad(data, fill=b"\0"):
        return data + fill * (-len(data) % 4)

    positions = b"".join(struct.pack("<3f", *v[0]) for v in vertices)
    texcoords = b"".join(struct.pack("<2f", v[1], v[2]) for v in vertices)
    indices = b"".join(struct.pack("<3H", *t) for t in triangles)
    blobs = [positions, texcoords, indices, png]
    views, binary = [], b""
    for blob in blobs:
        views.append({"buffer": 0, "byteOffset": len(binary), "byteLength": len(blob)})
        binary += pad(blob)
    n = len(vertices)
    lows = [min(v[0][k] for v in vertices) for k in range(3)]
    highs = [max(v[0][k] for v in vertices) for k in range(3)]
    gltf = {
        "asset": {"version": "2.0", "generator": "TriChart scripts/make-textured-sphere.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "sphere"}],
        "meshes": [{"name": "sphere", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
            "indices": 3, "material": 0}]}],
        "materials": [{"name": "checker", "pbrMetallicRoughness": {
            "baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 1.0}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9728, "minFilter": 9728}],
        "images": [{"bufferView": 3, "mimeType": "image/png"}],
        "buffers": [{"byteLength": len(binary)}],
        "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
             "min": lows, "max": highs},
            # A unit sphere's normal is its position: NORMAL reads POSITION's bytes.
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5123, "count": 3 * len(triangles),
             "type": "SCALAR"}],
    }
    text = pad(json.dumps(gltf, separators=(",", ":")).encode(), b" ")
    body = (struct.pack("<II", len(text), 0x4E4F534A) + text +
            struct.pack("<II", len(binary), 0x004E4942) + binary)
    with open(path, "wb") as out:
        out.write(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


def number(value):
    return "%.5g" % value


def write_obj(folder, vertices, faces, png):
    """OBJ stores v with its origin at the image's bottom: v = 1 - theta / pi. Positions are shared
    (a pole and the seam are one v each); texture coordinates are one vt per glTF vertex."""
    name = "textured_sphere"
    with open(os.path.join(folder, name + ".png"), "wb") as out:
        out.write(png)
    with open(os.path.join(folder, name + ".mtl"), "w") as out:
        out.write("# TriChart textured test sphere (scripts/make-textured-sphere.py)\n"
                  "newmtl checker\nKd 1 1 1\nmap_Kd %s.png\n" % name)
    positions, lines, v_of = {}, [], []
    for p, _, _ in vertices:
        key = tuple(number(c) for c in p)
        if key not in positions:
            positions[key] = len(positions) + 1
            lines.append("v %s %s %s\n" % key)
        v_of.append(positions[key])
    lines += ["vt %s %s\n" % (number(u), number(1.0 - t)) for _, u, t in vertices]
    lines.append("usemtl checker\n")
    for f in faces:
        lines.append("f " + " ".join("%d/%d" % (v_of[i], i + 1) for i in f) + "\n")
    with open(os.path.join(folder, name + ".obj"), "w") as out:
        out.write("# TriChart textured test sphere (scripts/make-textured-sphere.py)\n"
                  "mtllib %s.mtl\n" % name)
        out.writelines(lines)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "testing-data",
                                                                 "meshes")
    vertices, faces = sphere()
    triangles = triangulate(faces)
    check_outward(vertices, triangles)
    png = png_bytes()
    write_glb(os.path.join(folder, "textured_sphere.glb"), vertices, triangles, png)
    write_obj(folder, vertices, faces, png)
    print("%d vertices, %d triangles (%d OBJ faces), %d-byte PNG" %
          (len(vertices), len(triangles), len(faces), len(png)))


if __name__ == "__main__":
    main()
