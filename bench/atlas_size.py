#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Prints where the bytes of TriChart atlas files go: per file its size, its chart samples (every
sample of every chart's finest level, the texels the compact parts store), bytes per sample and
per input triangle, and the bytes of the metadata and of each attribute's parts.

    python3 bench/atlas_size.py ATLAS.exr [...]

It reads the OpenEXR container itself (header attributes, offset tables, chunk sizes; the
layout of docs/atlas-format.md and of the OpenEXR file layout document), so it needs nothing
beyond the standard library."""
import json
import struct
import sys
import zlib
from collections import defaultdict


def read_headers(data):
    """The headers of a multi-part OpenEXR file, each a dict name -> (type, raw bytes), and the
    offset just past them."""
    magic, flags = struct.unpack_from("<ii", data, 0)
    if magic != 20000630:
        raise ValueError("not an OpenEXR file")
    if not flags & 0x1000:
        raise ValueError("not a multi-part OpenEXR file")
    pos, headers = 8, []
    while data[pos] != 0:
        header = {}
        while data[pos] != 0:
            name_end = data.index(b"\0", pos)
            type_end = data.index(b"\0", name_end + 1)
            (size,) = struct.unpack_from("<i", data, type_end + 1)
            value = data[type_end + 5 : type_end + 5 + size]
            header[data[pos:name_end].decode()] = (data[name_end + 1 : type_end].decode(), value)
            pos = type_end + 5 + size
        headers.append(header)
        pos += 1
    return headers, pos + 1


def sizes(path):
    data = open(path, "rb").read()
    headers, pos = read_headers(data)
    metadata = headers[0]["trichartAtlasZ"][1]
    table = json.loads(zlib.decompress(metadata))
    chunk_counts = [struct.unpack("<i", h["chunkCount"][1])[0] for h in headers]
    pos += 8 * sum(chunk_counts)
    part_bytes = defaultdict(int)
    for _ in range(sum(chunk_counts)):
        part, _y, size = struct.unpack_from("<iii", data, pos)
        name = headers[part]["name"][1].decode()
        part_bytes[name.rsplit(".", 1)[0]] += 12 + size
        pos += 12 + size
    samples = sum((2**c["maxLevel"] + 1) * (2**c["maxLevel"] + 2) // 2 for c in table["charts"])
    return table, len(data), len(metadata), samples, part_bytes


def main(paths):
    for path in paths:
        table, total, metadata, samples, parts = sizes(path)
        triangles = table["inputTriangles"]
        print(f"{path}: version {table['version']}, {len(table['charts'])} charts, "
              f"{samples} samples ({samples / table['inputPoints']:.2f} x the input's "
              f"{table['inputPoints']} points)")
        print(f"  {total} bytes: {total / samples:.2f} per sample, "
              f"{total / triangles:.2f} per input triangle ({triangles})")
        print(f"  metadata {metadata} bytes ({metadata / samples:.2f} per sample)")
        for name, size in parts.items():
            print(f"  {name} parts {size} bytes ({size / samples:.2f} per sample)")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
