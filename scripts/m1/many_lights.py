#!/usr/bin/env python3
"""BENCHMARK.md M1: scenes with many point lights, written as raygine sidecars (and an OBJ).

  python3 scripts/m1/many_lights.py box N OUT.raygine.toml
      The built-in Cornell box (assets/scenes/cornell_box.raygine.toml) with its light replaced
      by an N x N grid of point lights at y = 540 mm over x 60..496, z -60..-500 mm, each of
      100 / N² cd (the same total as the box's one light).
  python3 scripts/m1/many_lights.py office NX NZ OUT_DIR
      A 30 x 30 x 3 m office (floor, ceiling, four walls, a desk row) as office.obj, and
      office.raygine.toml with NX x NZ point lights of 150 cd each 0.1 m under the ceiling.
"""
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]


def box(n, out):
    base = (ROOT / "assets/scenes/cornell_box.raygine.toml").read_text()
    # Everything but the [[lights]] table of the built-in sidecar.
    keep, skip = [], False
    for line in base.splitlines():
        if line.startswith("[[lights]]"):
            skip = True
            continue
        if skip and line.startswith("["):
            skip = False
        if not skip:
            keep.append(line)
    lights = []
    for i in range(n):
        for j in range(n):
            x = 60 + (496 - 60) * (i + 0.5) / n
            z = -60 - (500 - 60) * (j + 0.5) / n
            lights.append(
                f"[[lights]]\nposition = [{x:.3f}, 540.0, {z:.3f}]\n"
                f"intensity_cd = {100.0 / (n * n):.9g}\n"
            )
    pathlib.Path(out).write_text("\n".join(keep) + "\n\n" + "\n".join(lights))


def office(nx, nz, out_dir):
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    verts, faces = [], []

    def quad(a, b, c, d):
        k = len(verts)
        verts.extend([a, b, c, d])
        faces.append((k + 1, k + 2, k + 3))
        faces.append((k + 1, k + 3, k + 4))

    def cuboid(x0, y0, z0, x1, y1, z1):
        quad((x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0))
        quad((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))
        quad((x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0))
        quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1))
        quad((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0))
        quad((x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1))

    w, h = 30.0, 3.0
    quad((0, 0, 0), (0, 0, w), (w, 0, w), (w, 0, 0))  # floor
    quad((0, h, 0), (w, h, 0), (w, h, w), (0, h, w))  # ceiling
    quad((0, 0, 0), (w, 0, 0), (w, h, 0), (0, h, 0))
    quad((0, 0, w), (0, h, w), (w, h, w), (w, 0, w))
    quad((0, 0, 0), (0, h, 0), (0, h, w), (0, 0, w))
    quad((w, 0, 0), (w, 0, w), (w, h, w), (w, h, 0))
    for k in range(8):  # desks
        x = 2.0 + 3.5 * k
        cuboid(x, 0.0, 4.0, x + 1.6, 0.75, 26.0)
    lines = ["# raygine M1 office (scripts/m1/many_lights.py)"]
    lines += [f"v {x} {y} {z}" for x, y, z in verts]
    lines += [f"f {a} {b} {c}" for a, b, c in faces]
    (out / "office.obj").write_text("\n".join(lines) + "\n")
    toml = [
        'unit = "m"',
        'handedness = "right"',
        "[camera]",
        "position = [1.0, 1.6, 1.0]",
        "look_at = [15.0, 1.0, 15.0]",
        "up = [0.0, 1.0, 0.0]",
        "fov_deg = 60.0",
        "[default_material]",
        "kd = [0.6, 0.6, 0.6]",
    ]
    for i in range(nx):
        for j in range(nz):
            x = w * (i + 0.5) / nx
            z = w * (j + 0.5) / nz
            toml.append(f"[[lights]]\nposition = [{x:.4f}, 2.9, {z:.4f}]\nintensity_cd = 150.0")
    (out / "office.raygine.toml").write_text("\n".join(toml) + "\n")


if __name__ == "__main__":
    if sys.argv[1:2] == ["box"]:
        box(int(sys.argv[2]), sys.argv[3])
    elif sys.argv[1:2] == ["office"]:
        office(int(sys.argv[2]), int(sys.argv[3]), sys.argv[4])
    else:
        sys.exit(__doc__)
