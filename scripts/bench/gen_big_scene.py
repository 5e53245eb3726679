#!/usr/bin/env python3
"""Big benchmark scene: a G x G grid of UV spheres (varied radius and tessellation) on a floor.

Writes, with the same triangles in each (same vertex order, same index order):
  STEM.shp  Lumicept text: one brep `big`, welded vertices, one part, plus `set breps` identity
  STEM.glb  binary glTF 2.0: one node, one mesh, one primitive (POSITION f32 + u32 indices),
            one material (grey Lambertian-ish PBR), no camera, no lights
  STEM.tri  raw dump for the Embree harness: b"TRI1", u32 nverts, u32 ntris,
            nverts*3 f32 positions, ntris*3 u32 indices (little-endian)

Coordinates are metres-like numbers (spacing 1.0 between sphere centres; floor at y = 0,
+Y up); pass `--units m` to raygine for the .shp so its default light is scaled as for glTF.

Sphere k with n segments (n even) follows BENCHMARK.md's `sphere N`: n/2 rings, polar angle
pi*r/(n/2), azimuth 2*pi*s/n, degenerate pole triangles left out, so it has n*n - 2*n
triangles; here vertices are welded (poles once, ring seams shared). n is picked sphere by
sphere so the total lands as close as possible to --triangles.

Usage: python3 gen_big.py --triangles 10000000 [--grid 10] [--out-dir DIR] [--stem big]
       [--formats shp,glb,tri]
Needs numpy.
"""

import argparse
import json
import math
import os
import struct
import sys
import time

import numpy as np


def sphere(n, centre, radius):
    """Welded UV sphere: vertices (float64 Nx3), triangles (uint32 Mx3), outward CCW."""
    rings = n // 2
    ring_ids = np.arange(1, rings)  # interior rings 1..rings-1
    th = np.pi * ring_ids / rings
    ph = 2.0 * np.pi * np.arange(n) / n
    st, ct = np.sin(th)[:, None], np.cos(th)[:, None]
    x = (st * np.cos(ph)[None, :]).ravel()
    y = np.repeat(np.cos(th), n)
    z = (st * np.sin(ph)[None, :]).ravel()
    ring_v = np.stack([x, y, z], axis=1)
    verts = np.concatenate([[[0.0, 1.0, 0.0]], ring_v, [[0.0, -1.0, 0.0]]])
    top, bottom = 0, len(verts) - 1

    def vid(r, s):  # r in 1..rings-1, s any int (wraps)
        return 1 + (r - 1) * n + (s % n)

    s = np.arange(n)
    tris = []
    # Top cap: pole, ring 1 at s+1, ring 1 at s  (orientation fixed below if needed)
    tris.append(np.stack([np.full(n, top), vid(1, s + 1), vid(1, s)], axis=1))
    for r in range(1, rings - 1):
        a, b = vid(r, s), vid(r, s + 1)
        c, d = vid(r + 1, s), vid(r + 1, s + 1)
        tris.append(np.stack([a, b, d], axis=1))
        tris.append(np.stack([a, d, c], axis=1))
    tris.append(np.stack([np.full(n, bottom), vid(rings - 1, s), vid(rings - 1, s + 1)], axis=1))
    tris = np.concatenate(tris).astype(np.int64)
    assert len(tris) == n * n - 2 * n, (len(tris), n)
    # Orientation: make normals point outward (CCW seen from outside, right-handed).
    p = verts[tris]
    nrm = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    outward = np.einsum("ij,ij->i", nrm, p.mean(axis=1))
    if (outward < 0).mean() > 0.5:
        tris = tris[:, [0, 2, 1]]
        outward = -outward
    assert (outward > 0).all(), "inconsistent sphere winding"
    return verts * radius + np.asarray(centre), tris


def build(total, grid):
    count = grid * grid
    budget = total - 2  # two floor triangles
    if budget < count * 8:
        sys.exit(f"--triangles {total} is too few for a {grid}x{grid} grid")
    verts, tris, offset, made = [], [], 0, 0
    rng = np.random.default_rng(12345)
    for k in range(count):
        left = count - k
        want = (budget - made) / left
        n = 1.0 + math.sqrt(1.0 + want)  # n*n - 2n = want
        lo = max(4, int(math.floor(n / 2.0)) * 2)
        hi = lo + 2
        n = lo if abs(lo * lo - 2 * lo - want) <= abs(hi * hi - 2 * hi - want) else hi
        gx, gz = k % grid, k // grid
        radius = 0.25 + 0.2 * rng.random()
        centre = (gx + 0.5 + 0.05 * rng.standard_normal(),
                  radius,
                  -(gz + 0.5 + 0.05 * rng.standard_normal()))
        v, t = sphere(n, centre, radius)
        verts.append(v)
        tris.append(t + offset)
        offset += len(v)
        made += len(t)
    # Floor: a square under the grid with a margin, normal +Y (CCW from above).
    m = 1.0
    x0, x1, z0, z1 = -m, grid + m, -(grid + m), m
    fv = np.array([[x0, 0, z0], [x1, 0, z0], [x1, 0, z1], [x0, 0, z1]], dtype=np.float64)
    ft = np.array([[0, 2, 1], [0, 3, 2]], dtype=np.int64) + offset
    pf = fv[ft - offset]
    assert (np.cross(pf[:, 1] - pf[:, 0], pf[:, 2] - pf[:, 0])[:, 1] > 0).all()
    verts.append(fv)
    tris.append(ft)
    v = np.concatenate(verts).astype(np.float32)
    t = np.concatenate(tris).astype(np.uint32)
    return v, t


def write_rows(f, arr, fmt, chunk=200_000):
    for i in range(0, len(arr), chunk):
        part = arr[i:i + chunk]
        f.write(("\n".join(fmt % tuple(r) for r in part.tolist()) + "\n").encode())


def write_shp(path, v, t):
    with open(path, "wb") as f:
        f.write(b";; Written by gen_big.py (raygine benchmark scene)\n\n")
        f.write(b"ProcessMesh\n  Optimization off\n  Subdivision off\nenddef\n\n")
        f.write(b"define breps big\nGeoChecked\n")
        f.write(f"vertices {len(v)} ;; Number of vertices\n".encode())
        write_rows(f, v, "  %.6f %.6f %.6f")
        f.write(f"triangles {len(t)} ;; Number of triangles\n".encode())
        write_rows(f, t, " %d %d %d")
        f.write(b"parts 1 ;; Number of parts\n")
        full, rest = divmod(len(t), 10)
        line = b" 0 0 0 0 0 0 0 0 0 0\n"
        step = 100_000
        for i in range(0, full, step):
            f.write(line * min(step, full - i))
        if rest:
            f.write(b" 0" * rest + b"\n")
        f.write(b"enddef\n\n")
        f.write(b"set breps big\n  rotation 0 0 0\n  translation 0 0 0\n  scale 1 1 1\nenddef\n")


def pad4(b, fill):
    return b + fill * ((4 - len(b) % 4) % 4)


def write_glb(path, v, t):
    pos = v.astype("<f4").tobytes()
    idx = t.astype("<u4").tobytes()
    binary = pos + idx  # pos length is a multiple of 4
    doc = {
        "asset": {"version": "2.0", "generator": "gen_big.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "big", "mesh": 0}],
        "meshes": [{"name": "big", "primitives": [
            {"attributes": {"POSITION": 0}, "indices": 1, "material": 0, "mode": 4}]}],
        "materials": [{"name": "grey", "doubleSided": True, "pbrMetallicRoughness": {
            "baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0,
            "roughnessFactor": 1.0}}],
        "buffers": [{"byteLength": len(binary)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos), "target": 34962},
            {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx), "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": int(len(v)), "type": "VEC3",
             "min": [float(x) for x in v.min(axis=0)], "max": [float(x) for x in v.max(axis=0)]},
            {"bufferView": 1, "componentType": 5125, "count": int(t.size), "type": "SCALAR"},
        ],
    }
    js = pad4(json.dumps(doc, separators=(",", ":")).encode(), b" ")
    binary = pad4(binary, b"\0")
    length = 12 + 8 + len(js) + 8 + len(binary)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, length))
        f.write(struct.pack("<I4s", len(js), b"JSON"))
        f.write(js)
        f.write(struct.pack("<I4s", len(binary), b"BIN\0"))
        f.write(binary)


def write_tri(path, v, t):
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"TRI1", len(v), len(t)))
        f.write(v.astype("<f4").tobytes())
        f.write(t.astype("<u4").tobytes())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--triangles", type=int, default=10_000_000)
    ap.add_argument("--grid", type=int, default=10, help="spheres per side (default 10)")
    ap.add_argument("--out-dir", default=os.path.dirname(os.path.abspath(__file__)))
    ap.add_argument("--stem", default="big")
    ap.add_argument("--formats", default="shp,glb,tri")
    a = ap.parse_args()
    t0 = time.time()
    v, t = build(a.triangles, a.grid)
    print(f"built {len(t):,} triangles, {len(v):,} vertices in {time.time() - t0:.1f} s; "
          f"bounds {v.min(axis=0).tolist()} .. {v.max(axis=0).tolist()}")
    os.makedirs(a.out_dir, exist_ok=True)
    writers = {"shp": write_shp, "glb": write_glb, "tri": write_tri}
    for fmt in a.formats.split(","):
        path = os.path.join(a.out_dir, f"{a.stem}.{fmt}")
        t1 = time.time()
        writers[fmt](path, v, t)
        print(f"wrote {path}: {os.path.getsize(path):,} bytes in {time.time() - t1:.1f} s")


if __name__ == "__main__":
    main()
