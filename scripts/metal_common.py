"""The GGX metal test scene shared by scripts/mitsuba/metal_scene.py and
scripts/cycles/metal_cycles.py (and mirrored by crates/tracer-core/tests/core/metal_peers.rs):
its constants, its exact triangles, the camera's rays, and the analytic check of a white
Lambertian plane under either light. Plain Python with numpy, so both renderers' venvs import it.
"""

import math
from pathlib import Path

import numpy as np

REC709 = np.array([0.2126, 0.7152, 0.0722])

# ---------------------------------------------------------------------------------------------
# the scene

WIDTH, HEIGHT = 160, 120
CAM_EYE = (0.0, 1.2, 3.5)
CAM_TARGET = (0.0, 0.4, 0.0)
CAM_UP = (0.0, 1.0, 0.0)
FOV_Y_DEG = 40.0
SPHERE_CENTRE, SPHERE_RADIUS, RINGS, SEGMENTS = (0.0, 0.5, 0.0), 0.5, 32, 64
ALPHA_SPHERE, ALPHA_PLANE = 0.09, 0.36
ROUGHNESS_SPHERE, ROUGHNESS_PLANE = 0.3, 0.6  # Cycles: alpha = roughness^2 = 0.09, 0.36
POINT_POS, POINT_CD = (0.0, 2.0, 1.0), 10.0
AREA_Y, AREA_X, AREA_Z, AREA_RADIANCE = 2.0, (-0.5, 0.5), (0.5, 1.5), 100.0


def face_normals(v, f):
    n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    return n / np.linalg.norm(n, axis=1, keepdims=True), np.linalg.norm(n, axis=1) / 2


def sphere_mesh():
    """(vertices (2145, 3) float32, faces (3968, 3) uint32), outward counter-clockwise winding."""
    cx, cy, cz = SPHERE_CENTRE
    r = SPHERE_RADIUS
    verts = []
    for i in range(RINGS + 1):
        th = math.pi * i / RINGS
        for j in range(SEGMENTS + 1):
            ph = 2.0 * math.pi * j / SEGMENTS
            verts.append((cx + r * math.sin(th) * math.cos(ph), cy + r * math.cos(th),
                          cz + r * math.sin(th) * math.sin(ph)))
    idx = lambda i, j: i * (SEGMENTS + 1) + j
    faces = []
    for i in range(RINGS):
        for j in range(SEGMENTS):
            a, b, c, d = idx(i, j), idx(i, j + 1), idx(i + 1, j + 1), idx(i + 1, j)
            if i != 0:  # at the top pole a and b coincide
                faces.append((a, b, c))
            if i != RINGS - 1:  # at the bottom pole c and d coincide
                faces.append((a, c, d))
    v = np.array(verts, np.float64).astype(np.float32)
    f = np.array(faces, np.uint32)
    # winding check: every face normal points away from the centre, no degenerate face left
    n, area = face_normals(v.astype(np.float64), f.astype(np.int64))
    cent = v[f].astype(np.float64).mean(axis=1) - np.array(SPHERE_CENTRE)
    out = np.einsum("ij,ij->i", n, cent / np.linalg.norm(cent, axis=1, keepdims=True))
    if not (out.min() > 0.9 and area.min() > 1e-7):
        raise SystemExit(f"sphere mesh check failed: min n.r = {out.min()}, min area = {area.min()}")
    return v, f


def plane_mesh():
    v = np.array([(-2, 0, -2), (-2, 0, 2), (2, 0, 2), (2, 0, -2)], np.float32)
    f = np.array([(0, 1, 2), (0, 2, 3)], np.uint32)
    n, _ = face_normals(v.astype(np.float64), f.astype(np.int64))
    assert np.allclose(n, [0, 1, 0]), n
    return v, f


def area_mesh():
    """The emitter quad at y = 2, wound so that its normal is -Y (it emits downward)."""
    (x0, x1), (z0, z1), y = AREA_X, AREA_Z, AREA_Y
    v = np.array([(x0, y, z0), (x1, y, z0), (x1, y, z1), (x0, y, z1)], np.float32)
    f = np.array([(0, 1, 2), (0, 2, 3)], np.uint32)
    n, _ = face_normals(v.astype(np.float64), f.astype(np.int64))
    assert np.allclose(n, [0, -1, 0]), n
    return v, f


def write_obj(path, objects):
    """objects: [(name, verts float32, faces 0-based)]; positions and faces only, 1-based."""
    fmt = lambda x: np.format_float_positional(np.float32(x), unique=True, trim="-")
    lines = ["# raygine GGX metal test scene (scripts/mitsuba/metal_scene.py); metres, +Y up"]
    base = 1
    for name, v, f in objects:
        lines.append(f"o {name}")
        lines += [f"v {fmt(p[0])} {fmt(p[1])} {fmt(p[2])}" for p in v]
        lines += [f"f {a + base} {b + base} {c + base}" for a, b, c in f.astype(np.int64)]
        base += len(v)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text("\n".join(lines) + "\n")


# ---------------------------------------------------------------------------------------------
# analytic checks (white Lambertian plane)


def camera_rays(width=WIDTH, height=HEIGHT, sub=(0.5, 0.5)):
    """Origins (3,) and unit directions (H, W, 3) through the point `sub` of each pixel."""
    eye, tgt, up = (np.array(a, float) for a in (CAM_EYE, CAM_TARGET, CAM_UP))
    fwd = (tgt - eye) / np.linalg.norm(tgt - eye)
    right = np.cross(fwd, up)
    right /= np.linalg.norm(right)
    tup = np.cross(right, fwd)
    t = math.tan(math.radians(FOV_Y_DEG) / 2)
    px = (np.arange(width) + sub[0]) / width * 2 - 1
    py = 1 - (np.arange(height) + sub[1]) / height * 2
    X, Y = np.meshgrid(px * t * width / height, py * t)
    d = fwd + X[..., None] * right + Y[..., None] * tup
    return eye, d / np.linalg.norm(d, axis=-1, keepdims=True)


def plane_hits(width=WIDTH, height=HEIGHT):
    """World points (H, W, 3) where the pixel-centre rays meet y = 0 (NaN where they miss)."""
    eye, d = camera_rays(width, height)
    t = -eye[1] / d[..., 1]
    p = eye + t[..., None] * d
    bad = (t <= 0) | (np.abs(p[..., 0]) > 2) | (np.abs(p[..., 2]) > 2)
    p[bad] = np.nan
    return p


def lambert_point(p):
    """Radiance of a white Lambertian plane (normal +Y) at points p under the point light."""
    r = np.array(POINT_POS) - p
    d2 = (r * r).sum(-1)
    cos = r[..., 1] / np.sqrt(d2)
    return POINT_CD * cos / (math.pi * d2)


def lambert_area(p):
    """Same under the area light: L * form factor (Lambert's polygon formula, normal +Y)."""
    (x0, x1), (z0, z1), y = AREA_X, AREA_Z, AREA_Y
    quad = np.array([(x0, y, z0), (x1, y, z0), (x1, y, z1), (x0, y, z1)], float)
    acc = np.zeros(p.shape[:-1])
    for k in range(4):
        a = quad[k] - p
        b = quad[(k + 1) % 4] - p
        a /= np.linalg.norm(a, axis=-1, keepdims=True)
        b /= np.linalg.norm(b, axis=-1, keepdims=True)
        c = np.cross(a, b)
        theta = np.arccos(np.clip((a * b).sum(-1), -1, 1))
        acc += theta * c[..., 1] / np.linalg.norm(c, axis=-1)
    return AREA_RADIANCE * np.abs(acc) / (2 * math.pi)


def lambert_report(case, y_img):
    """Prints the check; y_img is the rendered luminance (H, W)."""
    p = plane_hits(*y_img.shape[::-1])
    expect = lambert_point(p) if case == "point" else lambert_area(p)
    under = np.array([0.0, 0.0, 1.0])  # straight under the point light / the area light's centre
    dist = np.linalg.norm(np.nan_to_num(p, nan=1e9) - under, axis=-1)
    r, c = np.unravel_index(np.argmin(dist), dist.shape)
    exact = lambert_point(under) if case == "point" else lambert_area(under)
    win = (slice(r - 1, r + 2), slice(c - 1, c + 2))
    inner = np.isfinite(p[..., 0]) & (np.abs(np.nan_to_num(p[..., 0])) < 1.8) & \
        (np.abs(np.nan_to_num(p[..., 2])) < 1.8)
    ratio = y_img[inner] / expect[inner]
    print(f"lambert check ({case}): exact radiance under the light at (0,0,1) = {float(exact):.5f} "
          f"cd/m^2; pixel (row {r}, col {c}) centre hits ({p[r, c, 0]:.4f}, 0, {p[r, c, 2]:.4f}): "
          f"expected {expect[r, c]:.5f}, rendered {y_img[r, c]:.5f} (ratio {y_img[r, c] / expect[r, c]:.4f}); "
          f"3x3 mean expected {expect[win].mean():.5f} rendered {y_img[win].mean():.5f} "
          f"(ratio {y_img[win].mean() / expect[win].mean():.4f}); all {inner.sum()} plane pixels "
          f"with |x|,|z| < 1.8: mean ratio {ratio.mean():.4f}, sd {ratio.std():.4f}, "
          f"sum ratio {y_img[inner].sum() / expect[inner].sum():.4f}")
