#!/usr/bin/env python3
"""G2 (../shared/BENCHMARK.md): a scene dumped by `raybench scene-dump` rendered by Mitsuba 3.

  raybench scene-dump -S ../shared/scenes/ipur-room2/room2.shp --out /tmp/room2_dump
  /work/mitsuba-venv/bin/python scripts/g2/room2_mitsuba.py /tmp/room2_dump \
      --integrator ptracer --seconds 20 --threads 2 --out /tmp/m.exr [--png /tmp/m.png]

The triangles raygine loaded (world coordinates, its vertex normals where it shades smoothly,
face normals elsewhere), its materials and point lights as room2_common.py maps them, its camera
(vertical fov), a 1-pixel box filter. Metres: a point of I cd gets radiant intensity I, so
pixels are cd/m^2 (for mm scenes x 10^6). Left-handed scenes (.shp) come out mirrored in
Mitsuba, so the image is flipped left-right before writing: --out compares pixel by pixel with
raygine's `render --exr`. --threads 1 hangs writing the EXR in Mitsuba 3.9: use 2.

Equal time (--seconds T): a warm-up render (JIT), a timed probe, then the spp that fits in T.
Prints one line `mitsuba integrator=... spp=... seconds=... threads=...`.
"""

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import room2_common as rc  # noqa: E402


def rgb(v):
    """A colour; grey as a uniform spectrum (Mitsuba's RGB reflectances must be <= 1, and the
    rescaled lobes of a blend may exceed 1)."""
    v = [float(x) for x in v]
    if v[0] == v[1] == v[2]:
        return {"type": "spectrum", "value": v[0]}
    return {"type": "rgb", "value": v}


def bsdf_dict(m):
    lob = rc.lobes(m)
    if lob["glass"] is not None:
        return {"type": "dielectric", "int_ior": lob["glass"], "ext_ior": 1.0}
    kd, spec, through = lob["kd"], lob["spec"], lob["through"]
    if through is not None:
        # mask: opacity a times the rest, 1 - a a null (pass-through) interface
        if np.any(through != through[0]):
            raise SystemExit(f"{m['label']}: coloured pass-through not mapped")
        a = 1.0 - float(through[0])
        inner = dict(m, kt=[0.0, 0.0, 0.0], kd=(kd / a).tolist(), ks=(np.array(m["ks"]) / a).tolist())
        return {"type": "mask", "opacity": a, "bsdf": bsdf_dict(inner)}
    diffuse = lambda r: {"type": "diffuse", "reflectance": rgb(r)}  # noqa: E731
    if spec is None:
        return {"type": "twosided", "bsdf": diffuse(kd)}
    if spec[0] == "mirror":
        s = {"type": "conductor", "material": "none", "specular_reflectance": None}
    else:
        s = {"type": "roughconductor", "material": "none", "distribution": "beckmann",
             "alpha": spec[2], "sample_visible": True, "specular_reflectance": None}
    ys, yd = float(spec[1] @ rc.REC709), float(kd @ rc.REC709)
    if yd <= 0:
        s["specular_reflectance"] = rgb(spec[1])
        return {"type": "twosided", "bsdf": s}
    w = ys / (ys + yd)  # blend weight of the specular lobe; both lobes rescaled to match
    s["specular_reflectance"] = rgb(spec[1] / w)
    blend = {"type": "blendbsdf", "weight": w, "a": diffuse(kd / (1 - w)), "b": s}
    return {"type": "twosided", "bsdf": blend}


def build(folder, width, height, integrator, max_depth):
    import mitsuba as mi

    desc, pos, nrm, mats = rc.read_dump(folder)
    scale = float(desc["metres_per_unit"])  # geometry to metres
    d = {"type": "scene", "integrator": {"type": integrator, "max_depth": max_depth}}
    if integrator == "ptracer":
        d["integrator"]["hide_emitters"] = False
    bsdfs = {}
    for mi_, smooth, sel in rc.groups(mats, nrm):
        m = desc["materials"][mi_]
        if mi_ not in bsdfs:
            bsdfs[mi_] = mi.load_dict(bsdf_dict(m))
        props = mi.Properties()
        props["bsdf"] = bsdfs[mi_]
        n = len(sel)
        mesh = mi.Mesh(f"m{mi_}_{int(smooth)}", 3 * n, n, props=props, has_vertex_normals=smooth)
        idx = (3 * sel[:, None] + np.arange(3)).ravel()
        p = mi.traverse(mesh)
        p["vertex_positions"] = mi.Float((pos[idx] * scale).astype(np.float32).ravel())
        p["faces"] = mi.UInt32(np.arange(3 * n, dtype=np.uint32))
        if smooth:
            p["vertex_normals"] = mi.Float(nrm[idx].astype(np.float32).ravel())
        p.update()
        d[f"mesh_{mi_}_{int(smooth)}"] = mesh
    for i, light in enumerate(desc["lights"]):
        d[f"light_{i}"] = {"type": "point", "position": [float(x) * scale for x in light["position"]],
                           "intensity": rgb(rc.light_rgb(light))}
    eye, target, up, fov, flip = rc.camera_frame(desc)
    d["camera"] = {
        "type": "perspective", "fov": fov, "fov_axis": "y",
        "near_clip": 1e-3, "far_clip": 1e4,
        "to_world": mi.ScalarTransform4f().look_at(origin=(eye * scale).tolist(),
                                                   target=(target * scale).tolist(),
                                                   up=up.tolist()),
        "film": {"type": "hdrfilm", "width": width, "height": height, "pixel_format": "rgb",
                 "rfilter": {"type": "box"}},
        "sampler": {"type": "independent", "sample_count": 1},
    }
    return mi.load_dict(d), flip, len(mats)


def render_np(scene, spp, seed, flip, spp_pass):
    """(H, W, 3) float32 linear RGB, seconds. Big spp in passes, averaged."""
    import mitsuba as mi
    import drjit as dr

    t0 = time.perf_counter()
    passes = max(1, -(-spp // spp_pass)) if spp_pass else 1
    acc = None
    done = 0
    for k in range(passes):
        n = min(spp - done, spp_pass) if spp_pass else spp
        img = mi.render(scene, spp=n, seed=seed * 100003 + k)
        dr.eval(img)
        a = np.array(img, dtype=np.float64) * n
        acc = a if acc is None else acc + a
        done += n
    arr = (acc / done).astype(np.float32)
    secs = time.perf_counter() - t0
    if flip:
        arr = arr[:, ::-1, :].copy()
    return arr, secs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("dump", help="folder written by raybench scene-dump")
    ap.add_argument("--integrator", default="ptracer", choices=["ptracer", "path"])
    ap.add_argument("--max-depth", type=int, default=-1)
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--spp", type=int)
    g.add_argument("--seconds", type=float)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=194)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--spp-pass", type=int, default=256, help="spp per mi.render call (0: one)")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", required=True)
    ap.add_argument("--png")
    args = ap.parse_args()

    if args.variant.startswith("llvm"):
        os.environ.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM-19.so")
    import mitsuba as mi
    import drjit as dr

    mi.set_variant(args.variant)
    dr.set_thread_count(args.threads)
    scene, flip, ntri = build(args.dump, args.width, args.height, args.integrator, args.max_depth)
    if args.seconds is not None:
        _, warm = render_np(scene, 16, args.seed + 1000, flip, 0)
        _, probe = render_np(scene, 64, args.seed + 2000, flip, 0)
        per_spp = probe / 64
        spp = max(1, int(args.seconds / per_spp))
        spp_pass = 0  # one call, as timed by the probe
        print(f"timing: warm-up {warm:.2f} s, probe {probe:.2f} s at 64 spp "
              f"({per_spp * 1e3:.2f} ms/spp) -> {spp} spp for {args.seconds} s", file=sys.stderr)
    else:
        spp, spp_pass = args.spp, args.spp_pass
    arr, secs = render_np(scene, spp, args.seed, flip, spp_pass)
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    mi.Bitmap(np.ascontiguousarray(arr), mi.Bitmap.PixelFormat.RGB).write(args.out)
    if args.png:
        rc.write_png(args.png, arr)
    y = arr @ rc.REC709.astype(np.float32)
    print(f"mitsuba integrator={args.integrator} spp={spp} seconds={secs:.2f} "
          f"threads={dr.thread_count()} variant={args.variant} size={args.width}x{args.height} "
          f"triangles={ntri} meanY={y.mean():.4f} out={args.out}")


if __name__ == "__main__":
    main()
