#!/usr/bin/env python3
"""GGX metal test scene (white-metal sphere on a white-metal plane) rendered by Mitsuba 3.

A reference for raygine's GGX conductor BSDF (direct light only). The scene is built here in
code, and scripts/cycles/metal_cycles.py builds the identical one for Blender Cycles:

- plane: the square x, z in [-2, 2] at y = 0, two triangles, normal +Y;
- sphere: centre (0, 0.5, 0), radius 0.5, a flat-shaded triangle mesh (face normals only):
  rings i = 0..32 (theta = pi i/32), segments j = 0..64 (phi = 2 pi j/64), vertex
  (0.5 sin(theta) cos(phi), 0.5 + 0.5 cos(theta), 0.5 sin(theta) sin(phi)); each quad
  (i, j)-(i+1, j+1) split into (a, b, c), (a, c, d) with a = (i, j), b = (i, j+1),
  c = (i+1, j+1), d = (i+1, j); the degenerate triangle at each pole dropped (3968 triangles,
  all wound counter-clockwise seen from outside: checked numerically);
- materials: `roughconductor`, GGX, Fresnel = 1 (`material: none`), visible-normal sampling;
  sphere alpha = 0.09 (perceptual roughness 0.3), plane alpha = 0.36 (roughness 0.6), one-sided;
- --case point: an isotropic point light of 10 cd at (0, 2, 1);
  --case area: a one-sided rectangle x in [-0.5, 0.5], z in [0.5, 1.5] at y = 2 (two
  triangles), emitting downward only, radiance 100 cd/m^2 (black BSDF);
- camera: perspective at (0, 1.2, 3.5) looking at (0, 0.4, 0), up +Y, vertical field of view
  40 degrees, 160 x 120, 1-pixel box filter; no environment (black);
- integrator `path` with max_depth = 2: emitters seen directly plus exactly one reflection.

Units: metres. Point light intensity 10 is given as radiant intensity (W/sr) and the area light's
radiance as W/(m^2 sr); with lengths in metres the pixels are therefore radiance in the same
unit, read as cd/m^2 (as raygine's EXRs). Right-handed, +Y up: no image flip (unlike
cornell_scene.py; the scene is symmetric in x anyway).

Outputs (for --out DIR/NAME.exr): NAME.exr (linear RGB, float32), NAME.txt (Rec. 709 luminance
Y = 0.2126 R + 0.7152 G + 0.0722 B, one text line per image row, row 0 = top, numbers separated
by blanks), NAME.png (preview: Y/(Y + k) tone curve on RGB, k = --png-knee, then sRGB).
--obj-dir DIR also writes the exact triangles: DIR/metal_sphere.obj (objects `o sphere` and
`o plane`, positions and faces only, 1-based, float32 values printed so that they read back
exactly) and DIR/metal_area_light.obj (`o area_light`, the emitter quad, normal -Y).

--lambert is the unit check: the sphere is left out and the plane becomes a white Lambertian
(`diffuse`, reflectance 1); the script then compares each plane pixel with the analytic value
(point: I cos(theta) / (pi d^2); area: L times the form factor of the rectangle, from Lambert's
polygon formula) and prints the pixel under the light and the mean ratio over the plane.

Usage (mitsuba venv; llvm_ad_rgb needs libLLVM, `apt-get install -y libllvm19`):

  P=/work/peers/mitsuba/bin/python
  $P scripts/mitsuba/metal_scene.py --case point --spp 4096 --out /work/peers/out/mitsuba_point.exr \
      --obj-dir /work/peers/out
  $P scripts/mitsuba/metal_scene.py --case area --spp 4096 --out /work/peers/out/mitsuba_area.exr
  $P scripts/mitsuba/metal_scene.py --case point --spp 1024 --lambert --out /tmp/mitsuba_point_lambert.exr

Prints one line `case=... spp=... seconds=... threads=... variant=... meanY=...` (seconds: the
render only, after loading the scene).
"""

import argparse
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from metal_common import (  # noqa: E402 (after the path is set)
    REC709,
    WIDTH,
    HEIGHT,
    CAM_EYE,
    CAM_TARGET,
    CAM_UP,
    FOV_Y_DEG,
    SPHERE_CENTRE,
    SPHERE_RADIUS,
    RINGS,
    SEGMENTS,
    ALPHA_SPHERE,
    ALPHA_PLANE,
    ROUGHNESS_SPHERE,
    ROUGHNESS_PLANE,
    POINT_POS,
    POINT_CD,
    AREA_Y,
    AREA_X,
    AREA_Z,
    AREA_RADIANCE,
    face_normals,
    sphere_mesh,
    plane_mesh,
    area_mesh,
    write_obj,
    camera_rays,
    plane_hits,
    lambert_point,
    lambert_area,
    lambert_report,
)

# ---------------------------------------------------------------------------------------------
# Mitsuba scene


def mesh(name, v, f, bsdf=None, emitter=None):
    import mitsuba as mi

    props = mi.Properties()
    if bsdf is not None:
        props["bsdf"] = mi.load_dict(bsdf)
    if emitter is not None:
        props["emitter"] = mi.load_dict(emitter)
    m = mi.Mesh(name, len(v), len(f), props=props, has_vertex_normals=False,
                has_vertex_texcoords=False)
    params = mi.traverse(m)
    params["vertex_positions"] = type(params["vertex_positions"])(np.ascontiguousarray(v.ravel()))
    params["faces"] = type(params["faces"])(np.ascontiguousarray(f.ravel()))
    params.update()
    return m


def conductor(alpha):
    return {"type": "roughconductor", "distribution": "ggx", "alpha": alpha,
            "material": "none", "sample_visible": True}


def build_scene_dict(case, lambert=False, width=WIDTH, height=HEIGHT, max_depth=2):
    import mitsuba as mi

    white = {"type": "diffuse", "reflectance": {"type": "rgb", "value": [1.0, 1.0, 1.0]}}
    scene = {"type": "scene"}
    pv, pf = plane_mesh()
    scene["plane"] = mesh("plane", pv, pf, white if lambert else conductor(ALPHA_PLANE))
    if not lambert:
        sv, sf = sphere_mesh()
        scene["sphere"] = mesh("sphere", sv, sf, conductor(ALPHA_SPHERE))
    if case == "point":
        scene["light"] = {"type": "point", "position": list(POINT_POS),
                          "intensity": {"type": "rgb", "value": [POINT_CD] * 3}}
    else:
        av, af = area_mesh()
        scene["light"] = mesh("area_light", av, af,
                              bsdf={"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.0] * 3}},
                              emitter={"type": "area",
                                       "radiance": {"type": "rgb", "value": [AREA_RADIANCE] * 3}})
    scene["sensor"] = {
        "type": "perspective",
        "fov_axis": "y",
        "fov": FOV_Y_DEG,
        "near_clip": 1e-3,
        "far_clip": 1e3,
        "to_world": mi.ScalarTransform4f().look_at(origin=list(CAM_EYE), target=list(CAM_TARGET),
                                                   up=list(CAM_UP)),
        "film": {"type": "hdrfilm", "width": width, "height": height,
                 "rfilter": {"type": "box"}, "pixel_format": "rgb"},
        "sampler": {"type": "independent"},
    }
    scene["integrator"] = {"type": "path", "max_depth": max_depth, "hide_emitters": False}
    return scene


# ---------------------------------------------------------------------------------------------
# output


def write_outputs(out, arr, png_knee):
    """NAME.exr, NAME.txt (luminance, row 0 = top), NAME.png next to it."""
    import mitsuba as mi

    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    mi.Bitmap(np.ascontiguousarray(arr, dtype=np.float32), mi.Bitmap.PixelFormat.RGB).write(str(out))
    y = arr.astype(np.float64) @ REC709
    np.savetxt(out.with_suffix(".txt"), y, fmt="%.7g", delimiter=" ")
    v = np.clip(arr / (arr.astype(np.float64) @ REC709 + png_knee)[..., None], 0.0, 1.0)
    s = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)
    u8 = np.ascontiguousarray(np.round(s * 255.0).astype(np.uint8))
    mi.Bitmap(u8, mi.Bitmap.PixelFormat.RGB).write(str(out.with_suffix(".png")))
    return y


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--case", required=True, choices=["point", "area"])
    ap.add_argument("--spp", type=int, default=4096)
    ap.add_argument("--out", required=True, help="linear RGB EXR (cd/m^2); .txt and .png beside it")
    ap.add_argument("--lambert", action="store_true",
                    help="unit check: plane only, white Lambertian; prints the analytic comparison")
    ap.add_argument("--obj-dir", default=None, help="also write metal_sphere.obj, metal_area_light.obj here")
    ap.add_argument("--max-depth", type=int, default=2, help="path max_depth (2 = direct light only)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--variant", default="llvm_ad_rgb", help="llvm_ad_rgb (needs libLLVM) or scalar_rgb")
    ap.add_argument("--threads", type=int, default=None, help="default: all cores (never 1, see README)")
    ap.add_argument("--png-knee", type=float, default=None,
                    help="preview tone curve Y/(Y+k); default 1 (point) or 10 (area) cd/m^2")
    args = ap.parse_args()

    if args.obj_dir:
        sv, sf = sphere_mesh()
        pv, pf = plane_mesh()
        av, af = area_mesh()
        write_obj(Path(args.obj_dir) / "metal_sphere.obj", [("sphere", sv, sf), ("plane", pv, pf)])
        write_obj(Path(args.obj_dir) / "metal_area_light.obj", [("area_light", av, af)])
        print(f"wrote {args.obj_dir}/metal_sphere.obj (sphere {len(sv)} v {len(sf)} f, plane 4 v 2 f), "
              f"metal_area_light.obj", file=sys.stderr)

    if args.variant.startswith("llvm") and "DRJIT_LIBLLVM_PATH" not in os.environ:
        os.environ["DRJIT_LIBLLVM_PATH"] = "/usr/lib/x86_64-linux-gnu/libLLVM-19.so"
    import mitsuba as mi
    import drjit as dr

    mi.set_variant(args.variant)
    if args.threads:
        dr.set_thread_count(args.threads)
    threads = dr.thread_count()

    d = build_scene_dict(args.case, args.lambert, max_depth=args.max_depth)
    spp_pass = 1024 if args.spp > 1024 and args.spp % 1024 == 0 else None
    if spp_pass and not args.variant.startswith("scalar"):
        d["integrator"]["samples_per_pass"] = spp_pass
    scene = mi.load_dict(d)

    t0 = time.perf_counter()
    img = mi.render(scene, spp=args.spp, seed=args.seed)
    arr = np.array(img, dtype=np.float32)
    secs = time.perf_counter() - t0

    knee = args.png_knee if args.png_knee is not None else (1.0 if args.case == "point" else 10.0)
    y = write_outputs(args.out, arr, knee)
    if args.lambert:
        lambert_report(args.case, y)
    print(f"case={args.case} lambert={args.lambert} integrator=path max_depth={args.max_depth} "
          f"spp={args.spp} seconds={secs:.2f} threads={threads} variant={args.variant} "
          f"size={arr.shape[1]}x{arr.shape[0]} meanY={y.mean():.5f} maxY={y.max():.3f} out={args.out}")


if __name__ == "__main__":
    main()
