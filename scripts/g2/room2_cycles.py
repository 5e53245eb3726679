#!/usr/bin/env python3
"""G2 (../shared/BENCHMARK.md): a scene dumped by `raybench scene-dump` rendered by Blender Cycles.

  /work/venv-bpy/bin/python scripts/g2/room2_cycles.py /tmp/room2_dump --time 20 \
      --out /tmp/c.exr [--png /tmp/c.png]        # or --samples N

The triangles raygine loaded (custom split normals where raygine shades smoothly, flat
elsewhere), its materials as room2_common.py maps them (Diffuse BSDF + Glossy BSDF, Beckmann,
roughness sqrt(alpha), 0 for the mirror;
Glass BSDF, of IOR 1 for raygine's ior-1 pass-through), its point lights (radius 0, soft falloff
off, P = 4 pi I W per unit tint with geometry in metres: pixels in cd/m^2), its camera (vertical
fov). Black world. CPU path tracing, no adaptive sampling, no light tree, no clamping, 1024
bounces, 1-pixel box filter, no denoising, no guiding. Left-handed scenes come out mirrored in
Cycles: the image is flipped left-right before writing --out, to compare with raygine's EXR.

Equal time: --time T sets scene.cycles.time_limit with a huge sample cap; the wall time of the
render call (which includes Cycles' scene sync and BVH build) is measured and printed as
render_call_s, with Cycles' own path-tracing time from the EXR metadata when it has one.
"""

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import room2_common as rc  # noqa: E402


def material(bpy, m):
    lob = rc.lobes(m)
    mat = bpy.data.materials.new(f"mat{m['index']}")
    if hasattr(mat, "use_nodes"):
        mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    out.target = "CYCLES"
    def glass(ior, colour):
        node = nt.nodes.new("ShaderNodeBsdfGlass")
        node.distribution = "BECKMANN"
        node.inputs["Roughness"].default_value = 0.0  # smooth
        node.inputs["IOR"].default_value = ior
        node.inputs["Color"].default_value = (*colour, 1.0)
        return node.outputs["BSDF"]

    def add(a, b):
        node = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(a, node.inputs[0])
        nt.links.new(b, node.inputs[1])
        return node.outputs["Shader"]

    if lob["glass"] is not None:
        nt.links.new(glass(lob["glass"], (1.0, 1.0, 1.0)), out.inputs["Surface"])
        return mat
    diff = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diff.inputs["Color"].default_value = (*lob["kd"].tolist(), 1.0)
    diff.inputs["Roughness"].default_value = 0.0  # Lambert
    shader = diff.outputs["BSDF"]
    spec = lob["spec"]
    if spec is not None:
        gl = nt.nodes.new("ShaderNodeBsdfGlossy")
        gl.distribution = "BECKMANN" if spec[0] == "rough" else "GGX"
        rough = math.sqrt(spec[2]) if spec[0] == "rough" else 0.0  # Cycles: alpha = roughness^2
        gl.inputs["Roughness"].default_value = rough
        gl.inputs["Color"].default_value = (*spec[1].tolist(), 1.0)
        shader = add(shader, gl.outputs["BSDF"])
    if lob["through"] is not None:
        # IOR 1 glass, not a Transparent BSDF: it passes paths but blocks shadow rays, as in raygine
        shader = add(shader, glass(1.0, lob["through"].tolist()))
    nt.links.new(shader, out.inputs["Surface"])
    return mat


def build(args):
    import bpy
    import mathutils

    desc, pos, nrm, mats = rc.read_dump(args.dump)
    scale = float(desc["metres_per_unit"])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    made = {}
    for mi_, smooth, sel in rc.groups(mats, nrm):
        idx = (3 * sel[:, None] + np.arange(3)).ravel()
        me = bpy.data.meshes.new(f"m{mi_}_{int(smooth)}")
        me.from_pydata((pos[idx] * scale).tolist(), [], np.arange(len(idx)).reshape(-1, 3).tolist())
        me.update()
        for poly in me.polygons:
            poly.use_smooth = smooth
        if smooth:
            # loops of a fresh from_pydata mesh follow the vertex order of each face
            loop_v = np.empty(len(me.loops), int)
            me.loops.foreach_get("vertex_index", loop_v)
            me.normals_split_custom_set(nrm[idx][loop_v].tolist())
        if mi_ not in made:
            made[mi_] = material(bpy, desc["materials"][mi_])
        me.materials.append(made[mi_])
        ob = bpy.data.objects.new(me.name, me)
        scene.collection.objects.link(ob)
    for i, light in enumerate(desc["lights"]):
        col = rc.light_rgb(light)  # cd per channel
        peak = float(col.max())
        ld = bpy.data.lights.new(f"light{i}", type="POINT")
        ld.color = tuple((col / peak).tolist())
        ld.energy = 4.0 * math.pi * peak  # W: intensity P / (4 pi) W/sr per unit colour
        ld.shadow_soft_size = 0.0
        for attr, val in (("use_soft_falloff", False), ("use_temperature", False),
                          ("exposure", 0.0), ("use_shadow", True)):
            if hasattr(ld, attr):
                setattr(ld, attr, val)
        if hasattr(ld, "cycles"):
            ld.cycles.max_bounces = 1024
        lo = bpy.data.objects.new(f"light{i}", ld)
        lo.location = [float(x) * scale for x in light["position"]]
        scene.collection.objects.link(lo)

    eye, target, up, fov, flip = rc.camera_frame(desc)
    eye, target = eye * scale, target * scale
    fwd = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(fwd, up)
    right /= np.linalg.norm(right)
    true_up = np.cross(right, fwd)
    mw = mathutils.Matrix.Identity(4)
    for r in range(3):  # Blender cameras look down local -Z with +Y up
        mw[r][0], mw[r][1], mw[r][2], mw[r][3] = right[r], true_up[r], -fwd[r], eye[r]
    cam = bpy.data.cameras.new("camera")
    cam.type = "PERSP"
    cam.sensor_fit = "VERTICAL"
    cam.angle_y = math.radians(fov)
    cam.clip_start, cam.clip_end = 1e-3, 1e4
    co = bpy.data.objects.new("camera", cam)
    co.matrix_world = mw
    scene.collection.objects.link(co)
    scene.camera = co

    w = bpy.data.worlds.new("black")
    if hasattr(w, "use_nodes"):
        w.use_nodes = True
    bg = w.node_tree.nodes.get("Background") if w.node_tree else None
    if bg is not None:
        bg.inputs["Strength"].default_value = 0.0
    w.color = (0.0, 0.0, 0.0)
    scene.world = w

    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y, r.resolution_percentage = args.width, args.height, 100
    r.threads_mode = "FIXED"
    r.threads = args.threads
    r.use_compositing = False
    r.use_sequencer = False
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_mode = "RGB"
    r.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    c = scene.cycles
    c.device = "CPU"
    c.use_adaptive_sampling = False
    c.samples = args.samples if args.samples else 1 << 24
    c.time_limit = args.time if args.time else 0.0
    c.seed = args.seed
    c.use_animated_seed = False
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = 1024
    c.transmission_bounces = c.volume_bounces = c.transparent_max_bounces = 1024
    c.min_light_bounces = 0
    c.blur_glossy = 0.0
    c.caustics_reflective = c.caustics_refractive = True
    c.light_sampling_threshold = 0.0
    c.use_light_tree = False
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    if hasattr(c, "use_guiding"):
        c.use_guiding = False
    c.use_denoising = False
    c.use_preview_denoising = False
    if hasattr(scene.view_layers[0], "cycles"):
        scene.view_layers[0].cycles.use_denoising = False
    bpy.context.preferences.addons["cycles"].preferences.compute_device_type = "NONE"
    return scene, flip, len(mats)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("dump")
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--samples", type=int)
    g.add_argument("--time", type=float)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=194)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", required=True)
    ap.add_argument("--png")
    args = ap.parse_args()

    import bpy
    import OpenEXR

    t0 = time.perf_counter()
    scene, flip, ntri = build(args)
    setup_s = time.perf_counter() - t0
    with tempfile.TemporaryDirectory() as tmp:
        raw = Path(tmp) / "raw.exr"
        scene.render.filepath = str(raw)
        t1 = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        call_s = time.perf_counter() - t1
        with OpenEXR.File(str(raw), separate_channels=True) as f:
            ch = f.channels()
            header = {k: (v.decode() if isinstance(v, bytes) else str(v)) for k, v in f.header().items()}
            arr = np.stack([np.asarray(ch[k].pixels, np.float32) for k in "RGB"], -1)
    if flip:
        arr = arr[:, ::-1, :]
    arr = np.ascontiguousarray(arr)
    chans = {c: np.ascontiguousarray(arr[:, :, i]) for i, c in enumerate("RGB")}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    with OpenEXR.File({"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage},
                      chans) as f:
        f.write(args.out)
    if args.png:
        rc.write_png(args.png, arr)
    meta = {k.split(".")[-1]: v for k, v in header.items() if k.startswith("cycles.")}
    y = arr @ rc.REC709.astype(np.float32)
    print(f"cycles samples={args.samples or 'time'} render_call_s={call_s:.2f} setup_s={setup_s:.2f} "
          f"cycles_render={meta.get('render_time', '?')} cycles_total={meta.get('total_time', '?')} "
          f"threads={args.threads} size={args.width}x{args.height} triangles={ntri} "
          f"meanY={y.mean():.4f} out={args.out}")


if __name__ == "__main__":
    main()
