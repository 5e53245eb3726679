#!/usr/bin/env python3
"""Mitsuba 3 render server for `raybench frames` (BENCHMARK.md F1, F2).

Loads a scene exported by raygine (`scene.json` and `slotN.bin`: float32 corner positions, then
the corners' shading normals, 9 floats per triangle each; two-sided Lambertian Kd per slot,
point lights in Mitsuba's units, the camera), renders twice to warm up the JIT, prints `ready`,
then answers each line on stdin:

    render SEED   ->  ms=<render wall time> mean_y=<mean Rec. 709 luminance, pixels clipped
                      at 1000 cd/m^2>
    exr PATH      ->  writes the last image as linear EXR; prints `ok`
    quit

Integrator `direct` with emitter_samples 1 and bsdf_samples 0: one shadow ray per light per
sample, as raygine's direct mode. Time is the render only, forced to completion.
"""

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

REC709 = np.array([0.2126, 0.7152, 0.0722])


def build(scene_dir, width, height, spp):
    import mitsuba as mi
    import drjit as dr

    spec = json.loads((scene_dir / "scene.json").read_text())
    scene = {"type": "scene"}
    for i, m in enumerate(spec["meshes"]):
        n = int(m["triangles"])
        data = np.fromfile(scene_dir / m["file"], dtype="<f4")
        if data.size != n * 18:
            sys.exit(f"{m['file']}: {data.size} floats, expected {n * 18}")
        pos = data[: n * 9].reshape(-1, 3)
        nrm = data[n * 9:].reshape(-1, 3)
        props = mi.Properties()
        props["bsdf"] = mi.load_dict({
            "type": "twosided",
            "material": {"type": "diffuse", "reflectance": {"type": "rgb", "value": m["kd"]}},
        })
        mesh = mi.Mesh(f"slot{i}", n * 3, n, props=props, has_vertex_normals=True,
                       has_vertex_texcoords=False)
        params = mi.traverse(mesh)
        params["vertex_positions"] = dr.ravel(mi.Point3f(pos[:, 0], pos[:, 1], pos[:, 2]))
        params["vertex_normals"] = dr.ravel(mi.Normal3f(nrm[:, 0], nrm[:, 1], nrm[:, 2]))
        faces = np.arange(n * 3, dtype=np.uint32).reshape(-1, 3)
        params["faces"] = dr.ravel(mi.Vector3u(faces[:, 0], faces[:, 1], faces[:, 2]))
        params.update()
        scene[f"slot{i}"] = mesh
    for i, light in enumerate(spec["lights"]):
        scene[f"light{i}"] = {
            "type": "point",
            "position": light["position"],
            "intensity": {"type": "rgb", "value": light["intensity"]},
        }
    cam = spec["camera"]
    scene["sensor"] = {
        "type": "perspective",
        "fov_axis": "y",
        "fov": cam["fov_deg"],
        "near_clip": spec["near_clip"],
        "far_clip": spec["far_clip"],
        "to_world": mi.ScalarTransform4f().look_at(
            origin=cam["position"], target=cam["look_at"], up=cam["up"]),
        "film": {"type": "hdrfilm", "width": width, "height": height,
                 "rfilter": {"type": "box"}, "pixel_format": "rgb"},
        "sampler": {"type": "independent", "sample_count": spp},
    }
    scene["integrator"] = {"type": "direct", "emitter_samples": 1, "bsdf_samples": 0}
    return mi.load_dict(scene)


def render(scene, spp, seed):
    import mitsuba as mi
    import drjit as dr

    t0 = time.perf_counter()
    img = mi.render(scene, spp=spp, seed=seed)
    dr.eval(img)
    arr = np.array(img, dtype=np.float32)  # forces completion
    return arr, (time.perf_counter() - t0) * 1e3


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene_dir")
    ap.add_argument("--width", type=int, default=1280)
    ap.add_argument("--height", type=int, default=720)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--variant", default="llvm_ad_rgb")
    args = ap.parse_args()
    if args.variant.startswith("llvm") and "DRJIT_LIBLLVM_PATH" not in os.environ:
        os.environ["DRJIT_LIBLLVM_PATH"] = "/usr/lib/x86_64-linux-gnu/libLLVM-19.so"
    try:
        import mitsuba as mi
        import drjit as dr
        mi.set_variant(args.variant)
    except Exception as e:  # reported to raybench, which goes on without the peer
        print(f"cannot load mitsuba {args.variant}: {e}", flush=True)
        return
    if args.threads:
        dr.set_thread_count(args.threads)
    scene = build(Path(args.scene_dir), args.width, args.height, args.spp)
    for seed in (1000, 1001):  # JIT warm-up
        render(scene, args.spp, seed)
    print(f"ready threads={dr.thread_count()} variant={args.variant}", flush=True)
    last = None
    for line in sys.stdin:
        words = line.split()
        if not words or words[0] == "quit":
            break
        if words[0] == "render":
            last, ms = render(scene, args.spp, int(words[1]) if len(words) > 1 else 0)
            # Clipped like raybench's own mean (the Cornell light's hot spot would swamp it).
            mean_y = float(np.minimum(last.reshape(-1, 3) @ REC709, 1000.0).mean())
            print(f"ms={ms:.2f} mean_y={mean_y:.6f}", flush=True)
        elif words[0] == "exr" and last is not None:
            mi.Bitmap(np.ascontiguousarray(last), mi.Bitmap.PixelFormat.RGB).write(words[1])
            print("ok", flush=True)
        else:
            print(f"unknown request: {line.strip()}", flush=True)


if __name__ == "__main__":
    main()
