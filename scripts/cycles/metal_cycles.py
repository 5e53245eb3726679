#!/usr/bin/env python3
"""GGX metal test scene (white-metal sphere on a white-metal plane) rendered by Blender Cycles.

The Cycles twin of scripts/mitsuba/metal_scene.py (same geometry, materials, lights, camera;
see that file's docstring for the scene), a reference for raygine's GGX conductor BSDF with
direct light only:

- geometry: the plane (2 triangles, normal +Y) and the flat-shaded sphere mesh (3968 triangles,
  face normals only: every polygon `use_smooth = False`, no vertex normals used), built by the
  same code as metal_scene.py (--obj writes the triangles for a diff against its OBJ);
- materials: Principled BSDF, distribution "GGX" (single scattering, no energy compensation;
  "Multiscatter GGX" would add some), Base Color 1, Metallic 1, Specular Tint 1 (Cycles' F82-tint
  metal: F = Schlick(F0 = 1) - b mu (1-mu)^6 with b proportional to 1 - tint = 0, so F = 1),
  Roughness 0.3 (sphere) / 0.6 (plane): Cycles squares it, alpha = 0.09 / 0.36; coat, sheen,
  transmission, emission, thin film all 0. --bsdf glossy uses the plain Glossy BSDF node (GGX,
  no Fresnel) instead: a check that the Principled metal is the bare GGX lobe (measured: the
  same pixels, bit for bit, at the same seed, in both cases);
- --case point: a point light at (0, 2, 1), radius 0, soft falloff off, power P = 4 pi 10 W:
  a radiant intensity of 10 W/sr, so that with lengths in metres the pixels are radiance
  read as cd/m^2;
  --case area: the quad x in [-0.5, 0.5], z in [0.5, 1.5] at y = 2 as a mesh (normal -Y) with an
  Emission shader of strength 100 (radiance 100) gated by Geometry > Backfacing so that its back
  emits nothing, emission sampling FRONT, no BSDF (black), out of the camera's view;
- camera: perspective at (0, 1.2, 3.5) looking at (0, 0.4, 0), +Y up, vertical FOV 40 degrees,
  160 x 120; black world;
- light transport: --max-bounces 0 (default; max, diffuse and glossy bounces): Cycles counts
  bounces after the camera hit, so 0 is direct light only (next-event estimation at the camera
  hit plus its BSDF-sampled ray, which only collects emission, MIS-weighted), as Mitsuba's
  max_depth = 2. Measured: point case, 128 spp, mean Y 0.1312 with 0 bounces (Mitsuba
  max_depth 2: 0.1311), 0.1500 with 1 (Mitsuba max_depth 3: 0.1499), 0.1543 with 2; with 1 the
  sphere's lower half mirrors the lit plane and the plane gets fireflies of light reflected by
  the sphere, with 0 neither.

Cycles settings as in cornell_cycles.py: CPU, --threads threads, path tracing, fixed samples, no
adaptive sampling, no light tree, light threshold 0, no clamping, no denoising, no path
guiding, 1-pixel box filter (pixel_filter_type BOX, filter_width 1), Standard view transform,
shadow terminator offsets 0.

Outputs (for --out DIR/NAME.exr): NAME.exr (Cycles' own linear RGB float32 EXR, scene-referred,
Rec. 709 primaries; no flip, the scene is right-handed), NAME.txt (Rec. 709 luminance
Y = 0.2126 R + 0.7152 G + 0.0722 B, one text line per image row, row 0 = top), NAME.png
(preview: Y/(Y + k) tone curve, k = --png-knee, then sRGB). The EXR is read back with Blender's
image loader (colour space Non-Color: the float values unchanged).

--lambert is the unit check: the sphere is left out and the plane becomes a white Lambertian
(Diffuse BSDF, colour 1, roughness 0); each plane pixel is compared with the analytic value
(point: I cos(theta) / (pi d^2); area: L times the rectangle's form factor) and the pixel under
the light and the mean ratio over the plane are printed.

Usage (bpy venv):

  P=/work/peers/bpy/bin/python
  $P scripts/cycles/metal_cycles.py --case point --spp 2048 --out /work/peers/out/cycles_point.exr
  $P scripts/cycles/metal_cycles.py --case area --spp 2048 --out /work/peers/out/cycles_area.exr
  $P scripts/cycles/metal_cycles.py --case point --spp 256 --lambert --out /tmp/cycles_point_lambert.exr

Prints one line starting `cycles ` with the case, samples, wall time of the render call and
Cycles' own render time, and mean Y.
"""

import argparse
import math
import os
import re
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from film import linear_exr_film  # noqa: E402 (this folder)

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
# Blender scene


def new_material(name):
    import bpy

    mat = bpy.data.materials.new(name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    outn = nt.nodes.new("ShaderNodeOutputMaterial")
    outn.target = "CYCLES"
    return mat, nt, outn


def metal_material(name, roughness, kind):
    mat, nt, outn = new_material(name)
    if kind == "principled":
        b = nt.nodes.new("ShaderNodeBsdfPrincipled")
        b.distribution = "GGX"
        vals = {"Base Color": (1.0, 1.0, 1.0, 1.0), "Metallic": 1.0, "Roughness": roughness,
                "Specular IOR Level": 0.5, "Specular Tint": (1.0, 1.0, 1.0, 1.0), "Anisotropic": 0.0,
                "Transmission Weight": 0.0, "Coat Weight": 0.0, "Sheen Weight": 0.0,
                "Subsurface Weight": 0.0, "Emission Strength": 0.0, "Thin Film Thickness": 0.0,
                "Alpha": 1.0}
        for k, v in vals.items():
            if k in b.inputs:
                b.inputs[k].default_value = v
        out = b.outputs["BSDF"]
    else:  # the Glossy BSDF node (ShaderNodeBsdfAnisotropic in Blender 4+): GGX, no Fresnel
        b = nt.nodes.new("ShaderNodeBsdfAnisotropic")
        b.distribution = "GGX"
        b.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        b.inputs["Roughness"].default_value = roughness
        b.inputs["Anisotropy"].default_value = 0.0
        out = b.outputs["BSDF"]
    nt.links.new(out, outn.inputs["Surface"])
    return mat


def lambert_material(name):
    mat, nt, outn = new_material(name)
    b = nt.nodes.new("ShaderNodeBsdfDiffuse")
    b.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    b.inputs["Roughness"].default_value = 0.0  # Lambert, not Oren-Nayar
    nt.links.new(b.outputs["BSDF"], outn.inputs["Surface"])
    return mat


def emitter_material(name, radiance):
    """Emission of strength `radiance` on front faces, nothing on back faces."""
    mat, nt, outn = new_material(name)
    geo = nt.nodes.new("ShaderNodeNewGeometry")
    inv = nt.nodes.new("ShaderNodeMath")
    inv.operation = "SUBTRACT"
    inv.inputs[0].default_value = 1.0
    nt.links.new(geo.outputs["Backfacing"], inv.inputs[1])
    mul = nt.nodes.new("ShaderNodeMath")
    mul.operation = "MULTIPLY"
    mul.inputs[1].default_value = radiance
    nt.links.new(inv.outputs["Value"], mul.inputs[0])
    em = nt.nodes.new("ShaderNodeEmission")
    em.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    nt.links.new(mul.outputs["Value"], em.inputs["Strength"])
    nt.links.new(em.outputs["Emission"], outn.inputs["Surface"])
    mat.cycles.emission_sampling = "FRONT"
    return mat


def add_mesh(scene, name, v, f, mat):
    import bpy

    me = bpy.data.meshes.new(name)
    me.from_pydata(v.astype(np.float64).tolist(), [], f.astype(np.int64).tolist())
    me.update()
    for poly in me.polygons:
        poly.use_smooth = False  # face normals only
    me.materials.append(mat)
    ob = bpy.data.objects.new(name, me)
    for k in ("shadow_terminator_offset", "shadow_terminator_geometry_offset"):
        if hasattr(ob.cycles, k):
            setattr(ob.cycles, k, 0.0)
    for k in ("shadow_terminator_geometry_offset", "shadow_terminator_shading_offset",
              "shadow_terminator_normal_offset"):
        if hasattr(ob, k):
            setattr(ob, k, 0.0)
    scene.collection.objects.link(ob)
    # Blender keeps the vertex order and the winding of from_pydata: check the triangles
    got = np.array([list(p.vertices) for p in me.polygons], np.int64)
    if got.shape != f.shape or not np.array_equal(got, f.astype(np.int64)):
        raise SystemExit(f"{name}: Blender changed the triangles")
    return ob


def build_scene(args):
    import bpy
    import mathutils

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene

    pv, pf = plane_mesh()
    add_mesh(scene, "plane", pv, pf,
             lambert_material("white_lambert") if args.lambert
             else metal_material("plane_metal", ROUGHNESS_PLANE, args.bsdf))
    if not args.lambert:
        sv, sf = sphere_mesh()
        add_mesh(scene, "sphere", sv, sf, metal_material("sphere_metal", ROUGHNESS_SPHERE, args.bsdf))

    if args.case == "point":
        ld = bpy.data.lights.new("point", type="POINT")
        ld.energy = 4.0 * math.pi * POINT_CD  # W; radiant intensity P/(4 pi) = 10 W/sr
        ld.color = (1.0, 1.0, 1.0)
        ld.shadow_soft_size = 0.0  # radius 0: a true point
        for k, v in (("use_soft_falloff", False), ("use_temperature", False), ("exposure", 0.0),
                     ("normalize", True), ("use_shadow", True), ("use_custom_distance", False),
                     ("specular_factor", 1.0), ("diffuse_factor", 1.0)):
            if hasattr(ld, k):
                setattr(ld, k, v)
        ld.cycles.max_bounces = 1024
        ld.cycles.use_multiple_importance_sampling = True
        lo = bpy.data.objects.new("point", ld)
        lo.location = POINT_POS
        scene.collection.objects.link(lo)
    else:
        av, af = area_mesh()
        add_mesh(scene, "area_light", av, af, emitter_material("emitter", AREA_RADIANCE))

    # camera: looks down its local -Z, +Y up
    eye, target, up = (np.array(a, float) for a in (CAM_EYE, CAM_TARGET, CAM_UP))
    fwd = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(fwd, up)
    right /= np.linalg.norm(right)
    true_up = np.cross(right, fwd)
    m = mathutils.Matrix.Identity(4)
    for r in range(3):
        m[r][0], m[r][1], m[r][2], m[r][3] = right[r], true_up[r], -fwd[r], eye[r]
    cam = bpy.data.cameras.new("camera")
    cam.type = "PERSP"
    cam.sensor_fit = "VERTICAL"
    cam.lens_unit = "FOV"
    cam.angle_y = math.radians(FOV_Y_DEG)
    cam.clip_start, cam.clip_end = 1e-3, 1e3
    co = bpy.data.objects.new("camera", cam)
    co.matrix_world = m
    scene.collection.objects.link(co)
    scene.camera = co

    # world: black
    w = bpy.data.worlds.new("black")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        w.use_nodes = True
    bg = w.node_tree.nodes.get("Background")
    if bg is not None:
        bg.inputs["Strength"].default_value = 0.0
        bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    w.color = (0.0, 0.0, 0.0)
    scene.world = w

    c = linear_exr_film(scene, WIDTH, HEIGHT, args.threads)
    c.samples = args.spp
    c.time_limit = 0.0
    c.seed = args.seed
    c.use_animated_seed = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = args.max_bounces
    c.transmission_bounces = c.volume_bounces = args.max_bounces
    c.transparent_max_bounces = 1024
    c.min_light_bounces = 0
    c.min_transparent_bounces = 0
    c.blur_glossy = 0.0
    c.caustics_reflective = c.caustics_refractive = True
    c.light_sampling_threshold = 0.0
    c.use_light_tree = False
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    if hasattr(c, "direct_light_sampling_type"):
        c.direct_light_sampling_type = "MULTIPLE_IMPORTANCE_SAMPLING"
    if hasattr(c, "use_guiding"):
        c.use_guiding = False
    if hasattr(c, "use_fast_gi"):
        c.use_fast_gi = False
    if hasattr(c, "auto_scrambling_distance"):
        c.auto_scrambling_distance = False
    if hasattr(c, "scrambling_distance"):
        c.scrambling_distance = 1.0
    if hasattr(c, "use_layer_samples"):
        c.use_layer_samples = "IGNORE"
    c.use_denoising = False
    c.use_preview_denoising = False
    vl = scene.view_layers[0]
    vl.use_pass_combined = True
    if hasattr(vl, "cycles"):
        vl.cycles.use_denoising = False
    bpy.context.preferences.addons["cycles"].preferences.compute_device_type = "NONE"
    return scene


# ---------------------------------------------------------------------------------------------
# output


def read_exr_bpy(path):
    """(H, W, 3) float32 from an EXR through Blender's loader, row 0 = top, values unchanged."""
    import bpy

    img = bpy.data.images.load(str(path), check_existing=False)
    img.colorspace_settings.name = "Non-Color"
    w, h = img.size
    px = np.empty(w * h * img.channels, np.float32)
    img.pixels.foreach_get(px)
    arr = px.reshape(h, w, img.channels)[::-1, :, :3].copy()  # Blender's rows start at the bottom
    bpy.data.images.remove(img)
    return arr


def write_txt_png(out, arr, png_knee):
    import bpy

    out = Path(out)
    y = arr.astype(np.float64) @ REC709
    np.savetxt(out.with_suffix(".txt"), y, fmt="%.7g", delimiter=" ")
    v = np.clip(arr / (y + png_knee)[..., None], 0.0, 1.0)
    s = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)
    h, w = y.shape
    img = bpy.data.images.new("preview", w, h, alpha=True, float_buffer=False)
    img.colorspace_settings.name = "Non-Color"  # s is already sRGB-encoded
    rgba = np.concatenate([s[::-1], np.ones((h, w, 1))], -1).astype(np.float32)
    img.pixels.foreach_set(rgba.ravel())
    img.filepath_raw = str(out.with_suffix(".png"))
    img.file_format = "PNG"
    img.save()
    bpy.data.images.remove(img)
    return y


def meta(header_text, key):
    m = re.search(r"cycles\.[^.]*\." + re.escape(key) + r"\s*[:=]\s*([^\s,]+)", header_text)
    return m.group(1) if m else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--case", required=True, choices=["point", "area"])
    ap.add_argument("--spp", type=int, default=2048, help="samples per pixel (fixed)")
    ap.add_argument("--out", required=True, help="linear RGB EXR (cd/m^2); .txt and .png beside it")
    ap.add_argument("--lambert", action="store_true",
                    help="unit check: plane only, white Lambertian; prints the analytic comparison")
    ap.add_argument("--bsdf", default="principled", choices=["principled", "glossy"],
                    help="Principled BSDF metal (default) or the plain Glossy BSDF node (check)")
    ap.add_argument("--max-bounces", type=int, default=0,
                    help="Cycles' max/diffuse/glossy bounces; 0 = direct light only (see docstring)")
    ap.add_argument("--obj", default=None, help="also write the sphere and plane triangles here (OBJ)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--png-knee", type=float, default=None,
                    help="preview tone curve Y/(Y+k); default 1 (point) or 10 (area) cd/m^2")
    ap.add_argument("--quiet", action="store_true", help="hide Blender's progress output")
    args = ap.parse_args()
    warnings.filterwarnings("ignore", category=DeprecationWarning)

    if args.obj:
        sv, sf = sphere_mesh()
        pv, pf = plane_mesh()
        write_obj(args.obj, [("sphere", sv, sf), ("plane", pv, pf)])

    import bpy

    scene = build_scene(args)
    out = Path(args.out).resolve()
    out.parent.mkdir(parents=True, exist_ok=True)
    scene.render.filepath = str(out)
    scene.render.use_file_extension = False
    scene.render.use_stamp = False
    for attr in ("use_stamp_date", "use_stamp_time", "use_stamp_render_time", "use_stamp_frame",
                 "use_stamp_camera", "use_stamp_scene", "use_stamp_filename"):
        if hasattr(scene.render, attr):
            setattr(scene.render, attr, True)  # metadata (incl. Cycles' timings) into the header

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

    arr = read_exr_bpy(out)
    knee = args.png_knee if args.png_knee is not None else (1.0 if args.case == "point" else 10.0)
    y = write_txt_png(out, arr, knee)
    if args.lambert:
        lambert_report(args.case, y)
    print(f"cycles case={args.case} lambert={args.lambert} bsdf={args.bsdf} "
          f"max_bounces={args.max_bounces} samples={args.spp} threads={args.threads} "
          f"render_call_s={t_call:.2f} size={arr.shape[1]}x{arr.shape[0]} blender={bpy.app.version_string} "
          f"meanY={y.mean():.5f} maxY={y.max():.3f} out={out}")


if __name__ == "__main__":
    main()
