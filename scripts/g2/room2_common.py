"""Shared by room2_mitsuba.py and room2_cycles.py: reads the dump `raybench scene-dump` writes
(triangles.ply + scene.json) and maps raygine's materials and lights to what the peers take.
Needs numpy only.

raygine's model (crates/tracer-core/src/shading/bsdf.rs), per material:
  f = Kd/pi + Ks (g+8)/(8 pi) (n.h)^g   (normalised Blinn-Phong, when glossiness g > 0)
  Ks a perfect mirror when g = 0; Kt a smooth dielectric of index ior.
The peers get:
  - Kd: a Lambertian lobe (two-sided);
  - Ks, g = 0: a perfect mirror of reflectance Ks (no Fresnel);
  - Ks, g > 0: a rough conductor without Fresnel, Beckmann alpha =
    sqrt(2 / (g + 2)) (the usual Blinn-Phong equivalence), reflectance Ks (g+8)/(g+2) so that
    its lobe has the same peak and albedo near normal incidence. APPROXIMATE: away from normal
    incidence the microfacet lobe (with its 1/(cos_i cos_o) and shadowing) differs. Even
    g = 10^5 (room2's windows) stays a lobe: raygine lights it by next-event estimation,
    so the point lights' glints in the windows are a few very bright pixels, which a perfect
    mirror would not show;
  - Kt with ior 1 (room2's windows: Kd + mirror Ks + Kt): raygine's interface without
    refraction or Fresnel reflection, i.e. a delta pass-through of weight Kt that still blocks
    shadow rays (raygine's shadow tests stop at any surface); other ior: a smooth dielectric
    (alone only).
Lights: point lights of I cd with raygine's tint normalised to Rec. 709 luminance 1.
"""

import json
import math
from pathlib import Path

import numpy as np

REC709 = np.array([0.2126, 0.7152, 0.0722])


def read_dump(folder):
    """(scene dict from scene.json, positions (3N,3), normals (3N,3), material per face (N,))."""
    folder = Path(folder)
    desc = json.loads((folder / "scene.json").read_text())
    data = (folder / desc.get("triangles_file", "triangles.ply")).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    nv = next(int(l.split()[2]) for l in header if l.startswith("element vertex"))
    nf = next(int(l.split()[2]) for l in header if l.startswith("element face"))
    verts = np.frombuffer(data, "<f4", nv * 6, end).reshape(nv, 6).astype(np.float64)
    face_t = np.dtype([("n", "u1"), ("idx", "<i4", (3,)), ("mat", "<i4")])
    faces = np.frombuffer(data, face_t, nf, end + nv * 24)
    if not (np.all(faces["n"] == 3) and np.array_equal(faces["idx"].ravel(), np.arange(nv))):
        raise SystemExit(f"{folder}: expected unshared triangles in order")
    return desc, verts[:, :3], verts[:, 3:], faces["mat"].astype(int)


def groups(mats, normals):
    """[(material index, smooth?, face indices)]: one mesh per material and shading kind."""
    smooth = np.any(normals.reshape(-1, 9) != 0.0, axis=1)
    out = []
    for m in np.unique(mats):
        for s in (False, True):
            sel = np.nonzero((mats == m) & (smooth == s))[0]
            if len(sel):
                out.append((int(m), bool(s), sel))
    return out


def lobes(m):
    """The peer's lobes of raygine material m (a scene.json entry):
    {'kd': rgb, 'spec': None | ('mirror', rgb) | ('rough', rgb, alpha), 'glass': None | ior,
    'through': None | rgb (pass-through weight, ior 1)}."""
    kd = np.array(m["kd"], float)
    ks = np.array(m["ks"], float)
    kt = np.array(m.get("kt", [0, 0, 0]), float)
    g = float(m["glossiness"])
    spec = None
    if ks.max() > 0:
        if g <= 0:
            spec = ("mirror", ks)
        else:
            spec = ("rough", ks * (g + 8) / (g + 2), math.sqrt(2.0 / (g + 2)))
    ior = float(m.get("ior", 1.5))
    glass = ior if kt.max() > 0 and abs(ior - 1.0) > 1e-6 else None
    through = kt if kt.max() > 0 and glass is None else None
    if glass is not None and (kd.max() > 0 or spec is not None or np.any(np.abs(kt - 1) > 1e-6)):
        raise SystemExit(f"{m['label']}: glass mixed with other lobes is not mapped")
    return {"kd": kd, "spec": spec, "glass": glass, "through": through}


def light_rgb(light):
    """Point light intensity per channel (cd, luminance-1 tint times intensity)."""
    if light["kind"] != "point":
        raise SystemExit(f"light of kind {light['kind']}: only isotropic points are mapped")
    col = np.maximum(np.array(light["color"], float), 0.0)
    y = float(col @ REC709)
    col = col / y if y > 0 else np.ones(3)
    return col * float(light["intensity_cd"])


def camera_frame(desc):
    """eye, target, up (scene unit), vertical fov degrees, and whether to flip the image
    left-right (raygine's left-handed scenes are the mirror image of a right-handed peer's)."""
    c = desc["camera"]
    return (np.array(c["position"], float), np.array(c["look_at"], float),
            np.array(c["up"], float), float(c["fov_deg"]), desc["handedness"] == "left")


def write_png(path, arr, exposure_stops=0.0):
    """100 cd/m^2 at exposure 0 is display white; clamp, sRGB; written without extra packages."""
    import zlib
    import struct

    v = np.clip(arr * (2.0 ** exposure_stops) / 100.0, 0.0, 1.0)
    s = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)
    u8 = np.round(s * 255.0).astype(np.uint8)
    h, w, _ = u8.shape
    raw = b"".join(b"\x00" + u8[y].tobytes() for y in range(h))

    def chunk(tag, body):
        return struct.pack(">I", len(body)) + tag + body + struct.pack(">I", zlib.crc32(tag + body))

    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))
    Path(path).write_bytes(png)
