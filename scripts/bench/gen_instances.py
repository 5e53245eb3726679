#!/usr/bin/env python3
"""Instancing benchmark scene: N copies of one OBJ mesh on a grid, as a binary glTF.

Writes STEM.glb: one mesh (the OBJ's triangles, fan-triangulated, POSITION f32 + u32 indices)
drawn by N nodes, each turned about +Y by 0.7 rad per copy and scaled by 1, 1.1 or 1.2, on a
square grid with 1.5 mesh-widths between copies; plus a floor node (its own mesh) under them.
raygine stores the shared mesh once (a two-level BVH); a reader that flattens nodes stores it
N times.

Usage: python3 gen_instances.py --obj ../shared/models/stanford-bunny.obj --copies 1000
       [--out-dir DIR] [--stem bunnies] [--flatten]
Needs numpy.
"""

import argparse
import json
import math
import os
import struct

import numpy as np


def read_obj(path):
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append([float(x) for x in parts[1:4]])
            elif parts[0] == "f":
                ids = [int(p.split("/")[0]) for p in parts[1:]]
                ids = [i - 1 if i > 0 else len(verts) + i for i in ids]
                for k in range(1, len(ids) - 1):
                    tris.append([ids[0], ids[k], ids[k + 1]])
    return np.array(verts, dtype=np.float32), np.array(tris, dtype=np.uint32)


def node_matrix(i, side, size):
    angle = i * 0.7
    s = 1.0 + 0.1 * (i % 3)
    c, sn = math.cos(angle) * s, math.sin(angle) * s
    x, z = (i % side) * 1.5 * size, (i // side) * 1.5 * size
    # Column-major 4x4.
    return [c, 0, -sn, 0, 0, s, 0, 0, sn, 0, c, 0, x, 0, z, 1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--obj", required=True)
    ap.add_argument("--copies", type=int, default=1000)
    ap.add_argument("--out-dir", default=".")
    ap.add_argument("--stem", default="bunnies")
    ap.add_argument("--flatten", action="store_true",
                    help="one glTF mesh per node (same accessors): the same picture, no reuse")
    a = ap.parse_args()
    verts, tris = read_obj(a.obj)
    lo, hi = verts.min(axis=0), verts.max(axis=0)
    # Stand the mesh on y = 0.
    verts = verts - np.array([0, lo[1], 0], dtype=np.float32)
    size = float((hi - lo).max())
    side = math.ceil(math.sqrt(a.copies))
    extent = side * 1.5 * size
    floor = np.array(
        [[-size, 0, -size], [extent, 0, -size], [extent, 0, extent], [-size, 0, extent]],
        dtype=np.float32,
    )
    floor_tris = np.array([[0, 2, 1], [0, 3, 2]], dtype=np.uint32)
    blobs, views, accessors = [], [], []

    def add(array, component, kind, minmax=False):
        data = array.tobytes()
        offset = sum(len(b) for b in blobs)
        blobs.append(data + b"\0" * ((4 - len(data) % 4) % 4))
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data)})
        acc = {"bufferView": len(views) - 1, "componentType": component,
               "count": int(array.size // (3 if kind == "VEC3" else 1)), "type": kind}
        if minmax:
            acc["min"] = array.min(axis=0).tolist()
            acc["max"] = array.max(axis=0).tolist()
        accessors.append(acc)
        return len(accessors) - 1

    mesh_pos = add(verts, 5126, "VEC3", True)
    mesh_idx = add(tris.reshape(-1), 5125, "SCALAR")
    floor_pos = add(floor, 5126, "VEC3", True)
    floor_idx = add(floor_tris.reshape(-1), 5125, "SCALAR")
    copies = a.copies if a.flatten else 1
    nodes = [{"name": f"copy{i}", "mesh": i if a.flatten else 0,
              "matrix": node_matrix(i, side, size)} for i in range(a.copies)]
    nodes.append({"name": "floor", "mesh": copies})
    doc = {
        "asset": {"version": "2.0", "generator": "raygine scripts/bench/gen_instances.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": [
            {"primitives": [{"attributes": {"POSITION": mesh_pos}, "indices": mesh_idx}]}
        ] * copies + [
            {"primitives": [{"attributes": {"POSITION": floor_pos}, "indices": floor_idx}]},
        ],
        "buffers": [{"byteLength": sum(len(b) for b in blobs)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * ((4 - len(js) % 4) % 4)
    bin_ = b"".join(blobs)
    total = 12 + 8 + len(js) + 8 + len(bin_)
    os.makedirs(a.out_dir, exist_ok=True)
    path = os.path.join(a.out_dir, a.stem + ".glb")
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, total))
        f.write(struct.pack("<I4s", len(js), b"JSON") + js)
        f.write(struct.pack("<I4s", len(bin_), b"BIN\0") + bin_)
    print(f"{path}: {a.copies} copies of {len(tris)} triangles "
          f"({a.copies * len(tris)} in the picture), floor {extent:.3g} across")


if __name__ == "__main__":
    main()
