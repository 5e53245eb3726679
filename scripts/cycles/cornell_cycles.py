#!/usr/bin/env python3
"""raygine's built-in Cornell box rendered by Blender Cycles (bpy), optionally denoised with OIDN.

Run with the bpy virtual environment:

  /work/venv-bpy/bin/python scripts/cycles/cornell_cycles.py --width 320 --height 240 \
      --time 5 --denoise --out /tmp/cycles_5s_oidn.exr
  /work/venv-bpy/bin/python scripts/cycles/cornell_cycles.py --width 160 --height 120 \
      --samples 4096 --no-denoise --light-y 500 --out /tmp/cycles_4096.exr

Scene: the geometry of the Lumicept .shp (`define breps` blocks, placed by `set breps`) and the
materials, point light(s) and camera of its sidecar NAME.raygine.toml, as
scripts/mitsuba/cornell_scene.py reads them: one mesh per brep part, flat (face) normals,
Lambertian BSDFs of colour kd (Blender's faces are two-sided), a perspective camera with the
sidecar's vertical field of view. World background black.

Units: the scene unit (mm) is converted to metres. A point light of I cd becomes a Blender
point light of radius 0, soft falloff off, power P = 4*pi*I W, so that the pixels come out in
cd/m^2 (../shared/BENCHMARK.md).

Handedness: raygine reads .shp scenes left-handed; Cycles is right-handed, so its image is the
mirror image of raygine's. With a left-handed sidecar (the default) this script FLIPS THE IMAGE
LEFT-RIGHT before writing --out, so the EXR compares pixel by pixel with raygine's EXRs
(red wall on the left). --raw-out optionally keeps Cycles' own, unflipped EXR as well.

The --out EXR is linear scene-referred RGB (Rec. 709 primaries, 32-bit float, channels R, G, B):
the denoised image when --denoise is given, otherwise the raw one.

Cycles settings: CPU, --threads threads (2), path tracing, no adaptive sampling, no light tree,
light threshold 0, no clamping, 1024 bounces of every kind, 1-pixel box filter, no path guiding,
Standard view transform (irrelevant for EXR, set anyway). Equal time: --time T sets
scene.cycles.time_limit with a huge sample cap; the actual wall time of the render call is
measured and printed, with Cycles' own split into synchronisation and path-tracing time (from the
render result's metadata), and the number of samples it reached.

With --denoise, OIDN runs inside the render call after the time limit (about 0.8 s at 320x240
on 2 threads, including OIDN's start-up), so render_call_s exceeds --time by that much; raygine's
--time-limit includes its denoising, so for strictly equal wall time give Cycles a --time that
much shorter (or compare at the measured render_call_s). `samples` under --time is the last
progress report's count (Cycles' own metadata only holds the requested cap).

Prints one line starting `cycles ` with the figures: render_call_s (wall time of
bpy.ops.render.render, which includes writing the raw EXR, a few ms), handler_s (render_pre to
render_post), Cycles' own cycles_total_s = cycles_sync_s + cycles_render_s, and setup_s (building
the scene in Python, not in the render call).
"""

import argparse
import warnings
import math
import os
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np

from film import linear_exr_film  # noqa: E402 (this folder)

HERE = Path(__file__).resolve().parent
DEFAULT_SHP = HERE.parent.parent / "assets" / "scenes" / "cornell_box.shp"
UNIT_M = {"mm": 1e-3, "cm": 1e-2, "m": 1.0}
REC709 = np.array([0.2126, 0.7152, 0.0722])


# ---------------------------------------------------------------------------------------------
# .shp reading


def clean_lines(path):
    out = []
    for raw in Path(path).read_text(encoding="utf-8", errors="replace").splitlines():
        cut = raw.split(";", 1)[0].strip()
        if cut:
            out.append(cut)
    return out


def read_shp(path):
    """({name: (verts (N,3), tris (M,3), parts (M,))}, {name: placement dict})."""
    lines = clean_lines(path)
    breps, place = {}, {}
    i, n = 0, len(lines)
    while i < n:
        tok = lines[i].split()
        kind = [t.lower() for t in tok[:2]]
        if kind == ["define", "breps"]:
            name = " ".join(tok[2:])
            verts, tris, parts = [], [], []
            i += 1
            while lines[i].lower() != "enddef":
                t = lines[i].split()
                key = t[0].lower()
                if key == "vertices":
                    cnt = int(t[1])
                    verts = [[float(x) for x in lines[i + 1 + k].split()] for k in range(cnt)]
                    i += cnt + 1
                elif key == "triangles":
                    cnt = int(t[1])
                    tris = [[int(x) for x in lines[i + 1 + k].split()] for k in range(cnt)]
                    i += cnt + 1
                elif key == "parts":
                    i += 1
                    while len(parts) < len(tris) and lines[i].lower() != "enddef":
                        parts.extend(int(x) for x in lines[i].split())
                        i += 1
                else:
                    raise SystemExit(f"{path}: unexpected line {lines[i]!r} in brep {name!r}")
            i += 1
            if len(parts) < len(tris):
                parts = [0] * len(tris)
            breps[name] = (np.array(verts, float).reshape(-1, 3), np.array(tris, int).reshape(-1, 3),
                           np.array(parts[:len(tris)], int))
        elif kind == ["set", "breps"]:
            name = " ".join(tok[2:])
            p = {"rotation": [0.0] * 3, "translation": [0.0] * 3, "scale": [1.0] * 3}
            i += 1
            while lines[i].lower() != "enddef":
                t = lines[i].split()
                if t[0].lower() in p:
                    p[t[0].lower()] = [float(x) for x in t[1:4]]
                i += 1
            i += 1
            place.setdefault(name, p)
        else:
            while i < n and lines[i].lower() != "enddef":
                i += 1
            i += 1
    return breps, place


def placement_matrix(p):
    """p' = T Rz Ry Rx S p (degrees, right-hand rule), raygine's convention."""
    ax, ay, az = (math.radians(v) for v in p["rotation"])
    rx = np.array([[1, 0, 0], [0, math.cos(ax), -math.sin(ax)], [0, math.sin(ax), math.cos(ax)]])
    ry = np.array([[math.cos(ay), 0, math.sin(ay)], [0, 1, 0], [-math.sin(ay), 0, math.cos(ay)]])
    rz = np.array([[math.cos(az), -math.sin(az), 0], [math.sin(az), math.cos(az), 0], [0, 0, 1]])
    return rz @ ry @ rx @ np.diag(p["scale"]), np.array(p["translation"], float)


def kd_for(sidecar, brep, part):
    mats = sidecar.get("materials", {})
    m = mats.get(f"{brep}/{part}", mats.get(brep, sidecar.get("default_material", {})))
    if any(float(v) > 0 for v in m.get("ks", [0, 0, 0])):
        print(f"warning: {brep}/{part} has ks; Cycles gets its diffuse part only", file=sys.stderr)
    return [float(v) for v in m.get("kd", [0.7, 0.7, 0.7])]


# ---------------------------------------------------------------------------------------------
# Blender scene


def build_scene(args):
    import bpy
    import mathutils

    shp = Path(args.shp)
    side_path = Path(args.sidecar) if args.sidecar else shp.with_suffix(".raygine.toml")
    sidecar = tomllib.loads(side_path.read_text(encoding="utf-8"))
    unit = UNIT_M[sidecar.get("unit", "mm")]
    breps, place = read_shp(shp)

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene

    # -- geometry: one object per brep part, in metres, flat shaded
    n_tris = 0
    ident = {"rotation": [0.0] * 3, "translation": [0.0] * 3, "scale": [1.0] * 3}
    for name, (verts, tris, parts) in breps.items():
        rot, tr = placement_matrix(place.get(name, ident))
        world = (verts @ rot.T + tr) * unit
        for part in np.unique(parts):
            sel = tris[parts == part]
            used, inv = np.unique(sel, return_inverse=True)
            faces = inv.reshape(-1, 3)
            me = bpy.data.meshes.new(f"{name}_{part}")
            me.from_pydata(world[used].tolist(), [], faces.tolist())
            me.update()
            for poly in me.polygons:
                poly.use_smooth = False
            mat = bpy.data.materials.new(f"mat_{name}_{part}")
            mat.use_nodes = True
            nt = mat.node_tree
            nt.nodes.clear()
            bsdf = nt.nodes.new("ShaderNodeBsdfDiffuse")
            bsdf.inputs["Color"].default_value = (*kd_for(sidecar, name, int(part)), 1.0)
            bsdf.inputs["Roughness"].default_value = 0.0  # Lambert, not Oren-Nayar
            outn = nt.nodes.new("ShaderNodeOutputMaterial")
            outn.target = "CYCLES"
            nt.links.new(bsdf.outputs["BSDF"], outn.inputs["Surface"])
            me.materials.append(mat)
            ob = bpy.data.objects.new(f"{name}_{part}", me)
            scene.collection.objects.link(ob)
            n_tris += len(faces)

    # -- lights: true inverse-square point lights
    lights = sidecar.get("lights", [])
    for li, L in enumerate(lights):
        pos = [float(v) for v in L["position"]]
        if li == 0 and args.light_y is not None:
            pos[1] = args.light_y
        col = np.array(L.get("color", [1.0, 1.0, 1.0]), float)
        y = float(col @ REC709)
        col = col / y if y > 0 else col  # luminance-1 tint: intensity stays in cd
        cd = float(L.get("intensity_cd", 100.0))
        if li == 0 and args.intensity is not None:
            cd = args.intensity
        ld = bpy.data.lights.new(f"light{li}", type="POINT")
        ld.energy = 4.0 * math.pi * cd  # W; intensity P/(4 pi) W/sr with geometry in metres
        ld.color = tuple(col.tolist())
        ld.shadow_soft_size = 0.0  # radius 0: a true point
        if hasattr(ld, "use_soft_falloff"):
            ld.use_soft_falloff = False
        if hasattr(ld, "use_temperature"):
            ld.use_temperature = False
        if hasattr(ld, "exposure"):
            ld.exposure = 0.0
        if hasattr(ld, "use_shadow"):
            ld.use_shadow = True
        if hasattr(ld, "cycles"):
            ld.cycles.max_bounces = 1024
            if hasattr(ld.cycles, "use_multiple_importance_sampling"):
                ld.cycles.use_multiple_importance_sampling = True
        lo = bpy.data.objects.new(f"light{li}", ld)
        lo.location = [v * unit for v in pos]
        scene.collection.objects.link(lo)
        if li == 0:
            light_pos = pos

    # -- camera: looks down its local -Z, +Y up
    cam = sidecar.get("camera", {})
    eye = np.array(cam["position"], float) * unit
    target = np.array(cam["look_at"], float) * unit
    up = np.array(cam.get("up", [0.0, 1.0, 0.0]), float)
    fwd = target - eye
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, up)
    right /= np.linalg.norm(right)
    true_up = np.cross(right, fwd)
    m = mathutils.Matrix.Identity(4)
    for r in range(3):
        m[r][0], m[r][1], m[r][2], m[r][3] = right[r], true_up[r], -fwd[r], eye[r]
    cd_ = bpy.data.cameras.new("camera")
    cd_.type = "PERSP"
    cd_.sensor_fit = "VERTICAL"
    cd_.lens_unit = "FOV"
    cd_.angle_y = math.radians(float(cam.get("fov_deg", 39.3)))
    cd_.clip_start = 1e-3
    cd_.clip_end = 1e3
    co = bpy.data.objects.new("camera", cd_)
    co.matrix_world = m
    scene.collection.objects.link(co)
    scene.camera = co

    # -- world: black
    w = bpy.data.worlds.new("black")
    w.use_nodes = True
    bg = w.node_tree.nodes.get("Background")
    if bg is not None:
        bg.inputs["Strength"].default_value = 0.0
        bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    w.color = (0.0, 0.0, 0.0)
    scene.world = w

    # -- render settings
    c = linear_exr_film(scene, args.width, args.height, args.threads)
    c.samples = args.samples if args.samples else 1 << 24
    c.time_limit = args.time if args.time else 0.0
    c.seed = args.seed
    c.use_animated_seed = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = args.max_bounces
    c.transmission_bounces = c.volume_bounces = c.transparent_max_bounces = 1024
    c.min_light_bounces = 0
    c.min_transparent_bounces = 0
    c.blur_glossy = 0.0
    c.caustics_reflective = c.caustics_refractive = True
    c.light_sampling_threshold = 0.0
    c.use_light_tree = not args.no_light_tree_off  # default False (see --light-tree)
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    if hasattr(c, "use_guiding"):  # path guiding (OpenPGL, CPU only): off unless --guiding
        c.use_guiding = bool(args.guiding)
        if args.guiding:
            c.use_surface_guiding = True
            c.use_volume_guiding = False
            c.use_guiding_direct_light = True
            c.use_guiding_mis_weights = True
    if hasattr(c, "auto_scrambling_distance"):
        c.auto_scrambling_distance = False
    if hasattr(c, "scrambling_distance"):
        c.scrambling_distance = 1.0
    if hasattr(c, "use_layer_samples"):
        c.use_layer_samples = "IGNORE"
    c.use_denoising = bool(args.denoise)
    c.use_preview_denoising = False
    if args.denoise:
        c.denoiser = "OPENIMAGEDENOISE"
        c.denoising_input_passes = "RGB_ALBEDO_NORMAL"
        c.denoising_prefilter = "ACCURATE"
        if hasattr(c, "denoising_quality"):
            c.denoising_quality = "HIGH"
        if hasattr(c, "denoising_use_gpu"):
            c.denoising_use_gpu = False
    vl = scene.view_layers[0]
    vl.use_pass_combined = True
    if hasattr(vl, "cycles"):
        vl.cycles.use_denoising = bool(args.denoise)

    prefs = bpy.context.preferences.addons["cycles"].preferences
    prefs.compute_device_type = "NONE"

    flip = sidecar.get("handedness", "left") == "left"
    return scene, flip, n_tris, light_pos


# ---------------------------------------------------------------------------------------------
# EXR i/o


def read_rgb_exr(path):
    import OpenEXR

    with OpenEXR.File(str(path), separate_channels=True) as f:
        ch = f.channels()
        header = dict(f.header())
        arr = np.stack([np.asarray(ch[k].pixels, np.float32) for k in ("R", "G", "B")], -1)
    return arr, header


def write_rgb_exr(path, arr, extra_header=None):
    import OpenEXR

    arr = np.ascontiguousarray(arr, dtype=np.float32)
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    for k, v in (extra_header or {}).items():
        header[k] = str(v)
    chans = {c: np.ascontiguousarray(arr[:, :, i]) for i, c in enumerate("RGB")}
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with OpenEXR.File(header, chans) as f:
        f.write(str(path))


def meta(header, key):
    """A Cycles figure from the EXR metadata (`cycles.<layer>.<key>`), or None."""
    for k, v in header.items():
        if k.startswith("cycles.") and k.endswith("." + key):
            return v.decode() if isinstance(v, bytes) else str(v)
    return None


def hms_seconds(s):
    """Blender's time strings ("00:01.23", "01:02:03.45", or seconds) to seconds."""
    if s is None:
        return None
    try:
        parts = [float(p) for p in s.strip().split(":")]
    except ValueError:
        return None
    secs = 0.0
    for p in parts:
        secs = secs * 60.0 + p
    return secs


# ---------------------------------------------------------------------------------------------


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--shp", default=str(DEFAULT_SHP))
    ap.add_argument("--sidecar", default=None)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--time", type=float, help="equal-time mode: cycles.time_limit seconds")
    g.add_argument("--samples", type=int, help="fixed samples per pixel")
    ap.add_argument("--max-samples", type=int, default=None,
                    help="sample cap with --time (default 2^24)")
    d = ap.add_mutually_exclusive_group()
    d.add_argument("--denoise", dest="denoise", action="store_true", help="OIDN (albedo+normal)")
    d.add_argument("--no-denoise", dest="denoise", action="store_false")
    ap.set_defaults(denoise=False)
    ap.add_argument("--light-y", type=float, default=None, help="light y in mm (default: sidecar's)")
    ap.add_argument("--intensity", type=float, default=None, help="light intensity, cd (default: sidecar's)")
    ap.add_argument("--light-tree", dest="no_light_tree_off", action="store_true",
                    help="leave Cycles' light tree on (default: off)")
    ap.add_argument("--guiding", action="store_true",
                    help="turn on Cycles' path guiding (not the benchmark's setting; an experiment)")
    ap.add_argument("--max-bounces", type=int, default=1024,
                    help="Cycles' max/diffuse/glossy bounces (0: direct light only); default 1024")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", required=True, help="linear RGB EXR, flipped to raygine's orientation")
    ap.add_argument("--raw-out", default=None, help="also keep Cycles' own (unflipped) EXR here")
    ap.add_argument("--quiet", action="store_true", help="hide Blender's progress output")
    args = ap.parse_args()
    warnings.filterwarnings("ignore", category=DeprecationWarning)

    import bpy

    t_setup0 = time.perf_counter()
    scene, flip, n_tris, light_pos = build_scene(args)
    if args.time and args.max_samples:
        scene.cycles.samples = args.max_samples
    t_setup = time.perf_counter() - t_setup0

    tmpdir = tempfile.mkdtemp(prefix="cycles_cornell_")
    raw_path = args.raw_out or os.path.join(tmpdir, "raw.exr")
    scene.render.filepath = raw_path
    scene.render.use_file_extension = False
    scene.render.use_stamp = False
    # the render result's metadata (Cycles' timings and samples) goes into the EXR header
    for attr in ("use_stamp_date", "use_stamp_time", "use_stamp_render_time", "use_stamp_frame",
                 "use_stamp_camera", "use_stamp_scene", "use_stamp_filename"):
        if hasattr(scene.render, attr):
            setattr(scene.render, attr, True)

    # Timestamps from Blender's render handlers: pre (render starts, before sync) and
    # post (pixels done, before the file is written).
    stamps = {}
    bpy.app.handlers.render_pre.append(lambda *a: stamps.setdefault("pre", time.perf_counter()))
    bpy.app.handlers.render_post.append(lambda *a: stamps.setdefault("post", time.perf_counter()))
    # Progress strings ("... | Sample 123/16777216"): the largest count gives the samples
    # reached under a time limit (the metadata's `samples` is the requested count; the very
    # last report says "Sample 0/..." after the render, so keep the largest).
    import re

    progress = {"max": None}

    def on_stats(stats, *rest):
        for done, _ in re.findall(r"Sample (\d+)/(\d+)", str(stats)):
            progress["max"] = max(progress["max"] or 0, int(done))

    bpy.app.handlers.render_stats.append(on_stats)

    if args.quiet:
        sys.stdout.flush()
        saved = os.dup(1)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 1)
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    t_call = time.perf_counter() - t0
    if args.quiet:
        sys.stdout.flush()
        os.dup2(saved, 1)

    arr, header = read_rgb_exr(raw_path)
    if not args.raw_out:
        import shutil

        shutil.rmtree(tmpdir, ignore_errors=True)
    if flip:
        arr = arr[:, ::-1, :]
    samples = meta(header, "samples")
    if args.time and progress["max"]:
        samples = str(progress["max"])  # last progress report; the true count may be a little higher
    sync_s = hms_seconds(meta(header, "synchronization_time"))
    pt_s = hms_seconds(meta(header, "render_time"))
    total_s = hms_seconds(meta(header, "total_time"))
    handler_s = (stamps["post"] - stamps["pre"]) if "pre" in stamps and "post" in stamps else None
    info = {"renderer": "cycles", "samples": samples, "render_call_s": f"{t_call:.3f}",
            "denoise": "oidn" if args.denoise else "none", "light_y_mm": light_pos[1]}
    write_rgb_exr(args.out, arr, info)

    y = arr.astype(np.float64) @ REC709
    f = lambda v: "?" if v is None else f"{v:.3f}"
    print(f"cycles size={args.width}x{args.height} denoise={'oidn' if args.denoise else 'none'} "
          f"time_limit={args.time or 0} samples={samples} threads={args.threads} "
          f"render_call_s={t_call:.3f} handler_s={f(handler_s)} cycles_total_s={f(total_s)} "
          f"cycles_sync_s={f(sync_s)} cycles_render_s={f(pt_s)} setup_s={t_setup:.3f} "
          f"light=({light_pos[0]:g},{light_pos[1]:g},{light_pos[2]:g})mm triangles={n_tris} "
          f"light_tree={'on' if args.no_light_tree_off else 'off'} guiding={'on' if args.guiding else 'off'} "
          f"flipped={flip} meanY={y.mean():.4f} out={args.out}")


if __name__ == "__main__":
    main()
