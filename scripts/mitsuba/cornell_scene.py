#!/usr/bin/env python3
"""raygine's built-in Cornell box (or another .shp scene with its sidecar) rendered by Mitsuba 3.

Reads the geometry from the Lumicept text .shp (`define breps NAME ... enddef` blocks and
`set breps NAME` placements) and the materials, light and camera from the sidecar
NAME.raygine.toml, builds a Mitsuba scene dict in memory (one mesh per brep part, face normals
only, two-sided Lambertian BSDFs, point lights, a perspective camera) and renders it.

Units: the scene's lengths stay in the scene unit (mm for the Cornell box). A point light of
I cd is given to Mitsuba as radiant intensity I / unit^2 (I * 1e6 for mm), so that the image
comes out in cd/m^2, as raygine's EXRs do.

Handedness: raygine reads .shp scenes left-handed, so its image is the mirror image of
Mitsuba's (right-handed); with a left-handed sidecar (the default) the image is flipped
left-right before it is saved, so that it can be compared with raygine's pixel by pixel.

Usage (see README.md in this folder):

  cornell_scene.py --integrator ptracer --spp 16384 --out /work/ref/cornell_160x120_ptracer.exr \
      --png /work/ref/cornell_160x120_ptracer.png
  cornell_scene.py --integrator path --seconds 5 --out /tmp/path_5s.exr

Prints one line `integrator=... spp=... seconds=... threads=... variant=... size=WxH`.
"""

import argparse
import math
import os
import sys
import time
import tomllib
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
DEFAULT_SHP = HERE.parent.parent / "assets" / "scenes" / "cornell_box.shp"
UNIT_M = {"mm": 1e-3, "cm": 1e-2, "m": 1.0}
REC709 = np.array([0.2126, 0.7152, 0.0722])


# ---------------------------------------------------------------------------------------------
# .shp reader


def _strip(line):
    """A line without its `;` comment and surrounding blanks."""
    i = line.find(";")
    if i >= 0:
        line = line[:i]
    return line.strip()


def parse_shp(path):
    """Returns (breps, placements).

    breps: {name: {"vertices": (N,3) float64, "triangles": (M,3) int64, "parts": (M,) int64}}
    placements: {name: {"rotation": [..], "translation": [..], "scale": [..]}} (first one wins)
    Blocks other than `define breps` and `set breps` are skipped up to their `enddef`.
    """
    lines = [_strip(l) for l in Path(path).read_text(encoding="utf-8", errors="replace").splitlines()]
    lines = [l for l in lines if l]
    breps, placements = {}, {}
    i = 0

    def numbers(line, kind, n=None):
        vals = [kind(t) for t in line.split()]
        if n is not None and len(vals) != n:
            raise ValueError(f"{path}: expected {n} numbers in {line!r}")
        return vals

    while i < len(lines):
        words = lines[i].split()
        head = [w.lower() for w in words[:2]]
        if head == ["define", "breps"]:
            name = " ".join(words[2:]) if len(words) > 2 else ""
            if name in breps:
                raise ValueError(f"{path}: brep {name!r} defined twice")
            i += 1
            verts, tris, parts = [], [], []
            while lines[i].lower() != "enddef":
                key = lines[i].split()
                kw = key[0].lower()
                if kw == "vertices":
                    n = int(key[1])
                    verts = [numbers(lines[i + 1 + k], float, 3) for k in range(n)]
                    i += 1 + n
                elif kw == "triangles":
                    n = int(key[1])
                    tris = [numbers(lines[i + 1 + k], int, 3) for k in range(n)]
                    i += 1 + n
                elif kw == "parts":
                    # `parts K` then one part index per triangle, on one or more lines.
                    i += 1
                    while len(parts) < len(tris) and lines[i].lower() != "enddef":
                        parts += numbers(lines[i], int)
                        i += 1
                else:
                    raise ValueError(f"{path}: unexpected {lines[i]!r} in brep {name!r}")
            i += 1  # enddef
            if not parts:
                parts = [0] * len(tris)
            breps[name] = {
                "vertices": np.array(verts, dtype=np.float64).reshape(-1, 3),
                "triangles": np.array(tris, dtype=np.int64).reshape(-1, 3),
                "parts": np.array(parts[: len(tris)], dtype=np.int64),
            }
        elif head == ["set", "breps"]:
            name = " ".join(words[2:])
            p = {"rotation": [0.0] * 3, "translation": [0.0] * 3, "scale": [1.0] * 3}
            i += 1
            while lines[i].lower() != "enddef":
                key = lines[i].split()
                if key[0].lower() in p:
                    p[key[0].lower()] = [float(t) for t in key[1:4]]
                i += 1
            i += 1
            placements.setdefault(name, p)
        else:  # any other block: skip to its enddef
            while i < len(lines) and lines[i].lower() != "enddef":
                i += 1
            i += 1
    return breps, placements


def world_from_local(p):
    """raygine's placement convention: p' = T Rz Ry Rx S p, angles in degrees, right-hand rule."""
    rx, ry, rz = (math.radians(a) for a in p["rotation"])
    cx, sx, cy, sy, cz, sz = math.cos(rx), math.sin(rx), math.cos(ry), math.sin(ry), math.cos(rz), math.sin(rz)
    Rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    Ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    Rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    m = np.eye(4)
    m[:3, :3] = Rz @ Ry @ Rx @ np.diag(p["scale"])
    m[:3, 3] = p["translation"]
    return m


# ---------------------------------------------------------------------------------------------
# sidecar and scene


def load_sidecar(shp_path, sidecar_path=None):
    path = Path(sidecar_path) if sidecar_path else Path(shp_path).with_suffix(".raygine.toml")
    if not path.exists():
        sys.exit(f"error: no sidecar {path}; this script needs the scene's camera and light")
    return tomllib.loads(path.read_text(encoding="utf-8"))


def material_for(sidecar, brep, part):
    mats = sidecar.get("materials", {})
    m = mats.get(f"{brep}/{part}", mats.get(brep, sidecar.get("default_material", {})))
    kd = [float(v) for v in m.get("kd", [0.7, 0.7, 0.7])]
    ks = [float(v) for v in m.get("ks", [0.0, 0.0, 0.0])]
    if any(v > 0 for v in ks):
        print(f"warning: {brep}/{part} has ks={ks}; Mitsuba gets its diffuse part only", file=sys.stderr)
    return kd


def build_scene_dict(shp_path=DEFAULT_SHP, sidecar_path=None, width=160, height=120,
                     integrator="ptracer", max_depth=-1, samples_per_pass=None):
    import mitsuba as mi
    import drjit as dr

    sidecar = load_sidecar(shp_path, sidecar_path)
    breps, placements = parse_shp(shp_path)
    unit_m = UNIT_M[sidecar.get("unit", "mm")]

    scene = {"type": "scene"}
    n_tris = 0
    for bi, (name, b) in enumerate(breps.items()):
        m = world_from_local(placements.get(name, {"rotation": [0] * 3, "translation": [0] * 3, "scale": [1] * 3}))
        world = b["vertices"] @ m[:3, :3].T + m[:3, 3]
        for part in np.unique(b["parts"]) if len(b["parts"]) else []:
            tris = b["triangles"][b["parts"] == part]
            used, faces = np.unique(tris, return_inverse=True)
            faces = faces.reshape(-1, 3)
            verts = world[used].astype(np.float32)
            kd = material_for(sidecar, name, int(part))
            props = mi.Properties()
            props["bsdf"] = mi.load_dict({
                "type": "twosided",
                "material": {"type": "diffuse", "reflectance": {"type": "rgb", "value": kd}},
            })
            mesh = mi.Mesh(f"{name}/{part}", len(verts), len(faces), props=props,
                           has_vertex_normals=False, has_vertex_texcoords=False)
            params = mi.traverse(mesh)
            params["vertex_positions"] = dr.ravel(mi.Point3f(verts[:, 0], verts[:, 1], verts[:, 2]))
            params["faces"] = dr.ravel(mi.Vector3u(*(faces[:, k].astype(np.uint32) for k in range(3))))
            params.update()
            scene[f"brep{bi}_{name}_{part}".replace("/", "_").replace(" ", "_")] = mesh
            n_tris += len(faces)

    for li, light in enumerate(sidecar.get("lights", [])):
        colour = np.array(light.get("color", [1.0, 1.0, 1.0]), dtype=np.float64)
        y = float(colour @ REC709)
        colour = colour / y if y > 0 else colour  # a tint of luminance 1: intensity stays in cd
        intensity = float(light.get("intensity_cd", 100.0)) / unit_m**2
        scene[f"light{li}"] = {
            "type": "point",
            "position": [float(v) for v in light["position"]],
            "intensity": {"type": "rgb", "value": (colour * intensity).tolist()},
        }

    cam = sidecar.get("camera", {})
    scene["sensor"] = {
        "type": "perspective",
        "fov_axis": "y",
        "fov": float(cam.get("fov_deg", 39.3)),
        "near_clip": 1e-3 / unit_m,
        "far_clip": 1e3 / unit_m,
        "to_world": mi.ScalarTransform4f().look_at(
            origin=[float(v) for v in cam["position"]],
            target=[float(v) for v in cam["look_at"]],
            up=[float(v) for v in cam.get("up", [0.0, 1.0, 0.0])],
        ),
        "film": {
            "type": "hdrfilm",
            "width": width,
            "height": height,
            "rfilter": {"type": "box"},
            "pixel_format": "rgb",
        },
        "sampler": {"type": "independent"},
    }
    if integrator == "direct":  # one shadow ray per light per sample, as raygine
        integ = {"type": "direct", "emitter_samples": 1, "bsdf_samples": 0}
    else:
        integ = {"type": integrator, "max_depth": max_depth}
    if samples_per_pass:
        integ["samples_per_pass"] = samples_per_pass
    scene["integrator"] = integ
    flip = sidecar.get("handedness", "left") == "left"
    return scene, flip, n_tris


# ---------------------------------------------------------------------------------------------
# rendering and output


def render_np(scene, spp, seed, flip):
    """Renders and returns (H, W, 3) float32 linear RGB (flipped for left-handed scenes), seconds."""
    import mitsuba as mi
    import drjit as dr

    t0 = time.perf_counter()
    img = mi.render(scene, spp=spp, seed=seed)
    dr.eval(img)
    arr = np.array(img, dtype=np.float32)  # forces completion
    secs = time.perf_counter() - t0
    if flip:
        arr = arr[:, ::-1, :].copy()
    return arr, secs


def write_exr(path, arr):
    import mitsuba as mi

    Path(path).parent.mkdir(parents=True, exist_ok=True)
    mi.Bitmap(np.ascontiguousarray(arr, dtype=np.float32), mi.Bitmap.PixelFormat.RGB).write(str(path))


def write_png(path, arr, exposure_stops=0.0):
    """Exposure 0: 100 cd/m^2 is display white; clamp, then the sRGB curve."""
    import mitsuba as mi

    v = np.clip(arr * (2.0**exposure_stops) / 100.0, 0.0, 1.0)
    s = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)
    u8 = np.ascontiguousarray(np.round(s * 255.0).astype(np.uint8))
    bmp = mi.Bitmap(u8, mi.Bitmap.PixelFormat.RGB)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    bmp.write(str(path))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--shp", default=str(DEFAULT_SHP))
    ap.add_argument("--sidecar", default=None)
    ap.add_argument("--integrator", default="ptracer", choices=["ptracer", "path", "direct"])
    ap.add_argument("--max-depth", type=int, default=-1)
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--spp", type=int, help="samples per pixel")
    g.add_argument("--seconds", type=float,
                   help="equal-time mode: time a warm-up and a probe render, then render the spp that fits")
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--samples-per-pass", type=int, default=None,
                    help="spp per pass (default: 1024 when --spp is a larger multiple of it, else Mitsuba's choice)")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--threads", type=int, default=None, help="default: all cores")
    ap.add_argument("--out", required=True, help="linear RGB EXR (cd/m^2)")
    ap.add_argument("--png", default=None, help="preview PNG, 100 cd/m^2 = white, sRGB")
    args = ap.parse_args()

    if args.variant.startswith("llvm") and "DRJIT_LIBLLVM_PATH" not in os.environ:
        os.environ["DRJIT_LIBLLVM_PATH"] = "/usr/lib/x86_64-linux-gnu/libLLVM-19.so"
    import mitsuba as mi
    import drjit as dr

    mi.set_variant(args.variant)
    if args.threads:
        dr.set_thread_count(args.threads)
    threads = dr.thread_count()

    # Wavefront split: 1024 spp per pass for big fixed-spp renders (16,384 spp x 19,200 pixels
    # would otherwise be one 314M-lane wavefront); Mitsuba's own choice otherwise. Measured at
    # 1024 spp: passes of 64, 256, 1024 spp or none all run within 5 % of each other.
    spp_pass = args.samples_per_pass
    if spp_pass is None and args.spp and args.spp > 1024 and args.spp % 1024 == 0:
        spp_pass = 1024
    if spp_pass and args.spp and args.spp % spp_pass:
        sys.exit(f"error: --spp must be a multiple of --samples-per-pass {spp_pass}")
    d, flip, n_tris = build_scene_dict(args.shp, args.sidecar, args.width, args.height,
                                       args.integrator, args.max_depth, spp_pass)
    scene = mi.load_dict(d)

    if args.seconds is not None:
        # Equal time: a warm-up render (JIT compilation), a timed probe, then the spp that fits.
        warm_spp, probe_spp = 16, 128
        _, warm = render_np(scene, warm_spp, args.seed + 1000, flip)
        _, probe = render_np(scene, probe_spp, args.seed + 2000, flip)
        per_spp = probe / probe_spp
        spp = max(1, int(args.seconds / per_spp))
        print(f"timing: warm-up {warm:.2f} s at {warm_spp} spp, probe {probe:.2f} s at {probe_spp} spp "
              f"({per_spp * 1e3:.2f} ms/spp) -> {spp} spp for {args.seconds} s", file=sys.stderr)
    else:
        spp = args.spp

    arr, secs = render_np(scene, spp, args.seed, flip)
    write_exr(args.out, arr)
    if args.png:
        write_png(args.png, arr)
    y = arr @ REC709.astype(np.float32)
    print(f"integrator={args.integrator} max_depth={args.max_depth} spp={spp} seconds={secs:.2f} "
          f"threads={threads} variant={args.variant} size={args.width}x{args.height} "
          f"triangles={n_tris} meanY={y.mean():.4f} out={args.out}")


if __name__ == "__main__":
    main()
