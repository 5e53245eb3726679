#!/usr/bin/env python3
"""Reference illuminances from Radiance for a daylit box room (raygine validation).

Builds the scene files, runs every case with `rtrace -I` (pure Monte Carlo,
no irradiance caching) and prints a JSON document with the results.

Usage (see README.md next to this file):
    python3 -m venv /work/peers/radiance
    /work/peers/radiance/bin/pip install pyradiance
    nice -n 10 /work/peers/radiance/bin/python daylight_room.py [--quick] \
        [--cases overcast_open,overcast_pane,clear_sun_open,perez_open] \
        [--runs 8] [--ad 4096] [--ab 20] [--workdir DIR] [--out results.json]

The Radiance programs are the ones shipped inside the pyradiance wheel
(<site-packages>/pyradiance/bin); their support files (rayinit.cal, ...)
live in <site-packages>/pyradiance/lib, which is put on RAYPATH.

Frames
------
raygine: metres, Y up, right-handed, north = -Z (east = +X, south = +Z).
Radiance: Z up, X east, Y north.  (x, y, z)_raygine -> (X, Y, Z) = (x, -z, y).

Everything is done with ONE rtrace process at a time (the machine is shared).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

# ----------------------------------------------------------------------------
# Radiance binaries from the pyradiance install
# ----------------------------------------------------------------------------
import pyradiance  # noqa: E402  (only used to locate the bundled binaries)

PYRAD_DIR = os.path.dirname(pyradiance.__file__)
RAD_BIN = os.path.join(PYRAD_DIR, "bin")
RAD_LIB = os.path.join(PYRAD_DIR, "lib")


def rad(name):
    """Full path of a bundled Radiance program."""
    return os.path.join(RAD_BIN, name)


# ----------------------------------------------------------------------------
# Constants of the problem
# ----------------------------------------------------------------------------
WHITE_EFFICACY = 179.0          # lm/W, Radiance's white-light efficacy
GROUND_REFL = 0.2               # sky ground reflectance (all cases)
SUN_ALT = 30.3615               # apparent solar altitude, degrees
SUN_AZ_N = 185.8802             # azimuth from north through east, degrees
SUN_AZ_WS = SUN_AZ_N - 180.0    # gensky/gendaylit -ang azimuth: degrees WEST of SOUTH
SUN_DIAM = 0.533                # degrees
SUN_HALF = SUN_DIAM / 2.0
SUN_OMEGA = 2.0 * math.pi * (1.0 - math.cos(math.radians(SUN_HALF)))  # sr

# measurement points (raygine frame), horizontal, facing up (+Y)
POINTS = [(x, 0.8, z) for z in (1.0, 2.0, 3.0, 4.0) for x in (1.0, 2.0, 3.0)]


def to_rad(p):
    """raygine (x, y, z) -> Radiance (X, Y, Z) = (x, -z, y)."""
    x, y, z = p
    return (x, -z, y)


def lux(rgb):
    """Radiance RGB irradiance (W/m2) -> lux."""
    r, g, b = rgb
    return WHITE_EFFICACY * (0.265 * r + 0.670 * g + 0.065 * b)


# ----------------------------------------------------------------------------
# Sun direction (Radiance frame), as gensky computes it from -ang alt az:
#   (-sin(az) cos(alt), -cos(az) cos(alt), sin(alt)), az west of south
# ----------------------------------------------------------------------------
def sun_dir():
    a, z = math.radians(SUN_ALT), math.radians(SUN_AZ_WS)
    return (-math.sin(z) * math.cos(a), -math.cos(z) * math.cos(a), math.sin(a))


# ----------------------------------------------------------------------------
# Scene geometry
# ----------------------------------------------------------------------------
def poly(name, mat, verts_raygine):
    pts = [to_rad(v) for v in verts_raygine]
    s = "%s polygon %s\n0\n0\n%d\n" % (mat, name, 3 * len(pts))
    for p in pts:
        s += "  %.6f %.6f %.6f\n" % p
    return s


def room_rad(pane):
    """Room: 4 x 3 x 5 m, all surfaces grey plastic 0.5 (two-sided polygons).
    South wall z=5 has an opening x in [1,3], y in [0.9,2.1]; with pane=True the
    opening holds one glass polygon (transmissivity 1, n = 1.52)."""
    s = "# raygine daylight test room (Radiance frame: X=x, Y=-z, Z=y)\n"
    s += "void plastic grey\n0\n0\n5 0.5 0.5 0.5 0 0\n\n"
    if pane:
        s += "void glass pane_glass\n0\n0\n4 1 1 1 1.52\n\n"
    s += poly("floor", "grey", [(0, 0, 0), (4, 0, 0), (4, 0, 5), (0, 0, 5)])
    s += poly("ceiling", "grey", [(0, 3, 0), (0, 3, 5), (4, 3, 5), (4, 3, 0)])
    s += poly("wall_x0", "grey", [(0, 0, 0), (0, 0, 5), (0, 3, 5), (0, 3, 0)])
    s += poly("wall_x4", "grey", [(4, 0, 0), (4, 3, 0), (4, 3, 5), (4, 0, 5)])
    s += poly("wall_z0", "grey", [(0, 0, 0), (0, 3, 0), (4, 3, 0), (4, 0, 0)])
    # south wall z = 5, four rectangles around the opening
    s += poly("south_below", "grey", [(0, 0, 5), (4, 0, 5), (4, 0.9, 5), (0, 0.9, 5)])
    s += poly("south_above", "grey", [(0, 2.1, 5), (4, 2.1, 5), (4, 3, 5), (0, 3, 5)])
    s += poly("south_left", "grey", [(0, 0.9, 5), (1, 0.9, 5), (1, 2.1, 5), (0, 2.1, 5)])
    s += poly("south_right", "grey", [(3, 0.9, 5), (4, 0.9, 5), (4, 2.1, 5), (3, 2.1, 5)])
    if pane:
        s += poly("pane", "pane_glass", [(1, 0.9, 5), (3, 0.9, 5), (3, 2.1, 5), (1, 2.1, 5)])
    return s


# ----------------------------------------------------------------------------
# Skies.  We use our own function file sharpsky.cal: the same CIE formulas as
# Radiance's skybright.cal (gensky) and perezlum.cal (gendaylit), but with a
# SHARP horizon.  The stock files blend sky and ground with weights
# (Dz+1.01)^(+-10), which darkens the sky within ~10 deg of the horizon - the
# part of the sky that the back of the room sees through the window.
# ----------------------------------------------------------------------------
SHARPSKY_CAL = r"""{ sharpsky.cal - written for raygine's reference runs.
  Same luminance formulas as Radiance's skybright.cal (CIE clear / overcast)
  and perezlum.cal (Perez all-weather), but sky for Dz > 0 and the uniform
  ground glow for Dz <= 0 (no (Dz+1.01)^10 blending at the horizon).

  cie_sky args: A1 1=CIE clear (1973, ISO 15469 type 12), 2=CIE overcast
                A2 zenith radiance, A3 ground radiance (W/sr/m2),
                A4 F2 normalisation (clear), A5 A6 A7 sun direction
  perez_sky args (as gendaylit writes for perezlum.cal):
                A1 diffuse normalisation, A2 ground radiance,
                A3..A7 Perez a b c d e, A8 A9 A10 sun direction }

cie_sky = if(Dz, select(A1, clearsky, overcastsky), A3);
cie_cosg = Dx*A5 + Dy*A6 + Dz*A7;
clearsky = A2 * (.91 + 10*exp(-3*Acos(cie_cosg)) + .45*cie_cosg*cie_cosg)
           * if(Dz - .01, 1 - exp(-.32/Dz), 1) / A4;
overcastsky = A2 * (1 + 2*Dz)/3;

perez_sky = if(Dz, perezsky, A2);
pz_cosg = Dx*A8 + Dy*A9 + Dz*A10;
pz_dz = if(Dz - .01, Dz, .01);
perezsky = A1 * (1 + A3*exp(A4/pz_dz)) * (1 + A5*exp(A6*Acos(pz_cosg)) + A7*pz_cosg*pz_cosg);
"""


def sky_luminance_np(kind, args, dx, dy, dz, blend=False):
    """numpy replica of sharpsky.cal above Dz > 0 (for the independent E_h).
    blend=True: replica of the stock skybright.cal / perezlum.cal horizon
    blending  (w L + G / w) / (w + 1/w),  w = (Dz + 1.01)^10."""
    if blend:
        w = (dz + 1.01) ** 10
        g = args[2] if kind == "cie" else args[1]
        return (w * sky_luminance_np(kind, args, dx, dy, dz) + g / w) / (w + 1 / w)
    if kind == "cie":
        t, lz, _g, f2, sx, sy, sz = args
        if t == 2:
            return lz * (1 + 2 * dz) / 3
        cg = np.clip(dx * sx + dy * sy + dz * sz, -1, 1)
        grad = np.where(dz > .01, 1 - np.exp(-.32 / np.maximum(dz, 1e-9)), 1.0)
        return lz * (.91 + 10 * np.exp(-3 * np.arccos(cg)) + .45 * cg * cg) * grad / f2
    else:
        a1, _g, a, b, c, d, e, sx, sy, sz = args
        cg = np.clip(dx * sx + dy * sy + dz * sz, -1, 1)
        pdz = np.where(dz > .01, dz, .01)
        return a1 * (1 + a * np.exp(b / pdz)) * (1 + c * np.exp(d * np.arccos(cg)) + e * cg * cg)


def sky_horizontal(kind, args, n_mu=4000, n_phi=8000, blend=False):
    """Horizontal illuminance (W/m2 'visible') of the sky above the horizon:
    E = int_0^2pi int_0^1 L(mu, phi) mu dmu dphi, midpoint rule in mu = cos(zenith)."""
    mu = (np.arange(n_mu) + 0.5) / n_mu
    tot = 0.0
    for k in range(n_phi // 1000):  # chunks, to keep memory small
        phi = (np.arange(k * 1000, (k + 1) * 1000) + 0.5) * 2 * math.pi / n_phi
        M, P = np.meshgrid(mu, phi, indexing="ij")
        s = np.sqrt(1 - M * M)
        L = sky_luminance_np(kind, args, s * np.sin(P), s * np.cos(P), M, blend)
        tot += float(np.sum(L * M))
    return tot * (1.0 / n_mu) * (2 * math.pi / n_phi)


def run(cmd, **kw):
    """Run a command (list), return stdout text.  Prints the command on stderr."""
    print("+ " + " ".join(cmd), file=sys.stderr, flush=True)
    return subprocess.run(cmd, check=True, capture_output=True, text=True, **kw).stdout


def gensky_text(args):
    return run([rad("gensky")] + args)


def parse_skyfunc_args(text):
    """Numbers of the last real-argument line after 'brightfunc skyfunc'."""
    lines = text.splitlines()
    i = [k for k, l in enumerate(lines) if "brightfunc skyfunc" in l][-1]
    return [float(v) for v in lines[i + 3].split()[1:]]


def make_sky(case):
    """Return (sky scene text, sky info dict) for a case."""
    info = {}
    sd = sun_dir()
    glow = ("\nskyfunc glow sky_glow\n0\n0\n4 1 1 1 0\n"
            "\nsky_glow source sky\n0\n0\n4 0 0 1 360\n")
    ang = ["-ang", "%.4f" % SUN_ALT, "%.4f" % SUN_AZ_WS]
    if case.startswith("overcast"):
        e_dif = 10000.0
        cmd = ang + ["-c", "-B", "%.6f" % (e_dif / WHITE_EFFICACY), "-g", str(GROUND_REFL)]
        txt = gensky_text(cmd)
        g = parse_skyfunc_args(txt)
        info["gensky_command"] = "gensky " + " ".join(cmd)
        info["gensky_output_args"] = g
        lz = e_dif / WHITE_EFFICACY / (7 * math.pi / 9)        # W/sr/m2, exact
        ground = GROUND_REFL * e_dif / WHITE_EFFICACY / math.pi
        args = [2, lz, ground, 1, sd[0], sd[1], sd[2]]
        info.update(kind="CIE overcast (gensky -c), sharp horizon",
                    zenith_luminance_cd_m2=lz * WHITE_EFFICACY,
                    gensky_zenith_luminance_cd_m2=g[1] * WHITE_EFFICACY,
                    ground_glow_cd_m2=ground * WHITE_EFFICACY,
                    gensky_ground_glow_cd_m2=g[2] * WHITE_EFFICACY,
                    diffuse_horizontal_target_lux=e_dif,
                    diffuse_horizontal_analytic_lux=7 * math.pi / 9 * lz * WHITE_EFFICACY)
        sky = "void brightfunc skyfunc\n2 cie_sky sharpsky.cal\n0\n7 %s\n" % " ".join("%.9g" % v for v in args)
        info["skyfunc_args"] = args
        info["sky_kind"] = "cie"
        if case.endswith("_blend"):
            sky = sky.replace("2 cie_sky sharpsky.cal", "2 skybr skybright.cal")
            info["kind"] += " -- BUT stock skybright.cal horizon blending (sensitivity run)"
        return sky + glow, info
    if case.startswith("clear"):
        e_dif, e_sun = 10000.0, 80000.0
        cmd = ang + ["-s", "-B", "%.6f" % (e_dif / WHITE_EFFICACY), "-g", str(GROUND_REFL)]
        txt = gensky_text(cmd)
        g = parse_skyfunc_args(txt)  # [1, Lz, ground, F2, sx, sy, sz]
        # renormalise Lz so that OUR sharp-horizon sky gives exactly e_dif
        # (gensky -B uses a polynomial fit for the normalisation)
        e_per_lz = sky_horizontal("cie", [1, 1.0, 0, g[3], sd[0], sd[1], sd[2]])
        lz = e_dif / WHITE_EFFICACY / e_per_lz
        ground = GROUND_REFL * (e_dif + e_sun * math.sin(math.radians(SUN_ALT))) / WHITE_EFFICACY / math.pi
        args = [1, lz, ground, g[3], sd[0], sd[1], sd[2]]
        sun_rad = e_sun / WHITE_EFFICACY / SUN_OMEGA
        sky = ("void light solar\n0\n0\n3 %.9g %.9g %.9g\n\n"
               "solar source sun\n0\n0\n4 %.9f %.9f %.9f %.4f\n\n"
               % (sun_rad, sun_rad, sun_rad, sd[0], sd[1], sd[2], SUN_DIAM))
        sky += "void brightfunc skyfunc\n2 cie_sky sharpsky.cal\n0\n7 %s\n" % " ".join("%.9g" % v for v in args)
        # value of the distribution AT the zenith: A2 * f(Zs) * phi(0) / F2, with
        # phi(0) = 1 - exp(-.32) = 0.27385 while gensky's F2 uses 0.274 (and F2 is
        # printed with 4 digits), so it differs from the A2 parameter by ~0.06 %
        lz_true = float(sky_luminance_np("cie", args, np.array(0.0), np.array(0.0), np.array(1.0)))
        lz_true_gs = float(sky_luminance_np("cie", g, np.array(0.0), np.array(0.0), np.array(1.0)))
        info.update(kind="CIE clear sky without sun (gensky -s; ISO 15469 type 12), sharp horizon, + own sun",
                    gensky_command="gensky " + " ".join(cmd), gensky_output_args=g,
                    zenith_luminance_cd_m2=lz_true * WHITE_EFFICACY,
                    skyfunc_A2_cd_m2=lz * WHITE_EFFICACY,
                    gensky_zenith_luminance_cd_m2=lz_true_gs * WHITE_EFFICACY,
                    gensky_A2_cd_m2=g[1] * WHITE_EFFICACY,
                    ground_glow_cd_m2=ground * WHITE_EFFICACY,
                    gensky_ground_glow_cd_m2=g[2] * WHITE_EFFICACY,
                    sun_radiance_W_sr_m2=sun_rad, sun_luminance_cd_m2=sun_rad * WHITE_EFFICACY,
                    sun_solid_angle_sr=SUN_OMEGA, sun_direction_radiance=sd,
                    sun_normal_lux=e_sun, sun_horizontal_lux=e_sun * math.sin(math.radians(SUN_ALT)),
                    diffuse_horizontal_target_lux=e_dif,
                    diffuse_horizontal_integrated_lux=lz * e_per_lz * WHITE_EFFICACY,
                    diffuse_horizontal_with_gensky_Lz_lux=g[1] * e_per_lz * WHITE_EFFICACY)
        info["skyfunc_args"] = args
        info["sky_kind"] = "cie"
        if case.endswith("_blend"):
            sky = sky.replace("2 cie_sky sharpsky.cal", "2 skybr skybright.cal")
            info["kind"] += " -- BUT stock skybright.cal horizon blending (sensitivity run)"
        return sky + glow, info
    if case.startswith("perez"):
        e_dn, e_dif = 60000.0, 15000.0
        cmd = ang + ["-L", "%.1f" % e_dn, "%.1f" % e_dif, "-g", str(GROUND_REFL)]
        txt = run([rad("gendaylit")] + cmd)
        g = parse_skyfunc_args(txt)   # [A1, ground, a, b, c, d, e, sx, sy, sz]
        sun_line = [l for l in txt.splitlines() if l.startswith("3 ")][0].split()
        sun_rad_gdl = float(sun_line[1])
        gsd = g[7:10]
        e_per_a1 = sky_horizontal("perez", [1.0, 0] + g[2:7] + gsd)
        a1 = e_dif / WHITE_EFFICACY / e_per_a1          # renormalised (sharp horizon)
        ground = GROUND_REFL * (e_dif + e_dn * math.sin(math.radians(SUN_ALT))) / WHITE_EFFICACY / math.pi
        args = [a1, ground] + g[2:7] + gsd
        lz = float(sky_luminance_np("perez", args, np.array(0.0), np.array(0.0), np.array(1.0)))
        lz_gdl = float(sky_luminance_np("perez", g, np.array(0.0), np.array(0.0), np.array(1.0)))
        sky = ("void light solar\n0\n0\n3 %.9g %.9g %.9g\n\n"
               "solar source sun\n0\n0\n4 %.9f %.9f %.9f %.4f\n\n"
               % (sun_rad_gdl, sun_rad_gdl, sun_rad_gdl, gsd[0], gsd[1], gsd[2], SUN_DIAM))
        sky += "void brightfunc skyfunc\n2 perez_sky sharpsky.cal\n0\n10 %s\n" % " ".join("%.9g" % v for v in args)
        info.update(kind="Perez all-weather (gendaylit -L), sharp horizon, gendaylit's sun",
                    gendaylit_command="gendaylit " + " ".join(cmd), gendaylit_output_args=g,
                    gendaylit_header=[l for l in txt.splitlines() if l.startswith("#")],
                    zenith_luminance_cd_m2=lz * WHITE_EFFICACY,
                    gendaylit_zenith_luminance_cd_m2=lz_gdl * WHITE_EFFICACY,
                    ground_glow_cd_m2=ground * WHITE_EFFICACY,
                    gendaylit_ground_glow_cd_m2=g[1] * WHITE_EFFICACY,
                    sun_radiance_W_sr_m2=sun_rad_gdl, sun_luminance_cd_m2=sun_rad_gdl * WHITE_EFFICACY,
                    sun_normal_lux_from_radiance=sun_rad_gdl * SUN_OMEGA * WHITE_EFFICACY,
                    sun_direction_radiance=gsd,
                    diffuse_horizontal_target_lux=e_dif,
                    diffuse_horizontal_integrated_lux=a1 * e_per_a1 * WHITE_EFFICACY,
                    diffuse_horizontal_with_gendaylit_A1_lux=g[0] * e_per_a1 * WHITE_EFFICACY)
        info["skyfunc_args"] = args
        info["sky_kind"] = "perez"
        if case.endswith("_blend"):
            sky = sky.replace("2 perez_sky sharpsky.cal", "2 skybright perezlum.cal")
            info["kind"] += " -- BUT stock perezlum.cal horizon blending (sensitivity run)"
        return sky + glow, info
    raise ValueError(case)


# ----------------------------------------------------------------------------
# rtrace
# ----------------------------------------------------------------------------
def rtrace_opts(ad, ab, lw):
    # -I+ irradiance at points; -h- no header; -u+ uncorrelated random sampling
    # (seeded from time(0) in Radiance's reset_random(): runs must start in
    # different seconds, see wait_new_second()); -aa 0 -as 0 no cache, no
    # super-sampling; -lr 0 Russian roulette (unbiased) below weight -lw;
    # -ab hard limit of ambient bounces; -dj 0 -ds 0 -dt 0 -dc 1 -dr 0:
    # sun = one shadow ray to its centre (no point is near a penumbra),
    # every source tested, no virtual relays.
    return ["-h-", "-I+", "-u+", "-aa", "0", "-as", "0", "-ad", str(ad), "-ab", str(ab),
            "-lr", "0", "-lw", "%g" % lw, "-dj", "0", "-ds", "0", "-dt", "0", "-dc", "1",
            "-dr", "0"]


_last_second = [-1]


def wait_new_second():
    """rtrace -u+ seeds drand48 with time(0) (Radiance's reset_random()), so two
    runs that start within the same second are IDENTICAL.  We start a run only
    once the clock has passed the second in which the previous run ENDED, so
    every run gets a strictly larger seed."""
    while int(time.time()) <= _last_second[0]:
        time.sleep(0.05)


def mark_run_end():
    _last_second[0] = int(time.time())


def rtrace_points(octree, pts_rad, opts, cwd):
    inp = "".join("%.6f %.6f %.6f 0 0 1\n" % p for p in pts_rad)
    wait_new_second()
    cmd = [rad("rtrace")] + opts + [octree]
    out = run(cmd, input=inp, cwd=cwd)
    mark_run_end()
    vals = [lux([float(v) for v in l.split()[:3]]) for l in out.strip().splitlines()]
    assert len(vals) == len(pts_rad), out
    return vals, cmd


def oconv(files, octree, cwd):
    with open(os.path.join(cwd, octree), "wb") as f:
        cmd = [rad("oconv")] + files
        print("+ " + " ".join(cmd) + " > " + octree, file=sys.stderr, flush=True)
        subprocess.run(cmd, check=True, stdout=f, cwd=cwd)


def stats(samples):
    a = np.array(samples)
    n = len(a)
    m = float(a.mean())
    se = float(a.std(ddof=1) / math.sqrt(n)) if n > 1 else float("nan")
    return m, se


# ----------------------------------------------------------------------------
# Glass transmission test
# ----------------------------------------------------------------------------
def glass_test(wd):
    """A large glass pane (transmissivity 1, n 1.52) in the plane Y=0 with a
    uniform glow of radiance 1 behind it (everything else black): rtrace's
    radiance of a ray through the pane = its transmittance."""
    with open(os.path.join(wd, "glasstest.rad"), "w") as f:
        f.write("void glass g\n0\n0\n4 1 1 1 1.52\n\n"
                "g polygon pane\n0\n0\n12\n -100 0 -100  100 0 -100  100 0 100  -100 0 100\n\n"
                "void glow white\n0\n0\n4 1 1 1 0\n\n"
                "white polygon back\n0\n0\n12\n -1000 50 -1000  1000 50 -1000  1000 50 1000  -1000 50 1000\n")
    oconv(["glasstest.rad"], "glasstest.oct", wd)
    res = {}
    inp = ""
    angles = [0, 30, 45, 60]
    for a in angles:
        r = math.radians(a)
        inp += "0 -1 0 %.9f %.9f 0\n" % (math.sin(r), math.cos(r))
    cmd = [rad("rtrace"), "-h-", "-ab", "0", "-lr", "0", "-lw", "1e-9", "glasstest.oct"]
    out = run(cmd, input=inp, cwd=wd)
    for a, l in zip(angles, out.strip().splitlines()):
        res["%d_deg" % a] = float(l.split()[1])
    # Formula in LIGHTING.md: T = 1/2[(1-Rs)/(1+Rs) + (1-Rp)/(1+Rp)]
    n = 1.52
    formula = {}
    for a in angles:
        ti = math.radians(a)
        tt = math.asin(math.sin(ti) / n)
        ci, ct = math.cos(ti), math.cos(tt)
        rs = ((ci - n * ct) / (ci + n * ct)) ** 2
        rp = ((ct - n * ci) / (ct + n * ci)) ** 2
        formula["%d_deg" % a] = 0.5 * ((1 - rs) / (1 + rs) + (1 - rp) / (1 + rp))
    return {"command": " ".join(cmd), "rtrace_transmittance": res, "formula": formula}


# ----------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="3 runs, -ad 512 (smoke test)")
    ap.add_argument("--cases", default="overcast_open,overcast_pane,clear_sun_open,perez_open")
    ap.add_argument("--runs", type=int, default=8)
    ap.add_argument("--ad", type=int, default=4096)
    ap.add_argument("--ab", type=int, default=20)
    ap.add_argument("--lw", type=float, default=1e-7)
    ap.add_argument("--workdir", default="/tmp/raygine_radiance")
    ap.add_argument("--out", default=None, help="also write the JSON here")
    a = ap.parse_args()
    if a.quick:
        a.runs, a.ad = 3, 512
    os.makedirs(a.workdir, exist_ok=True)
    wd = a.workdir
    os.environ["RAYPATH"] = os.pathsep.join([".", RAD_LIB])
    version = run([rad("rtrace"), "-version"]).strip()

    with open(os.path.join(wd, "sharpsky.cal"), "w") as f:
        f.write(SHARPSKY_CAL)
    for pane in (False, True):
        with open(os.path.join(wd, "room_%s.rad" % ("pane" if pane else "open")), "w") as f:
            f.write(room_rad(pane))

    opts = rtrace_opts(a.ad, a.ab, a.lw)
    result = {
        "radiance_version": version,
        "pyradiance_version": getattr(pyradiance, "__version__", "?"),
        "frame": "points in raygine frame (m, Y up, north=-Z); Radiance (X,Y,Z)=(x,-z,y)",
        "settings": {"rtrace_options": " ".join(opts), "runs_per_point": a.runs,
                     "seeding": "rtrace -u+ seeds drand48 with time(0); each run is a separate "
                                "process started in a new second",
                     "lux": "179*(0.265R+0.670G+0.065B)"},
        "glass_test": glass_test(wd),
        "cases": {},
    }
    pts_rad = [to_rad(p) for p in POINTS]
    for case in a.cases.split(","):
        t0 = time.time()
        sky, info = make_sky(case)
        kind = info.pop("sky_kind")
        with open(os.path.join(wd, "sky_%s.rad" % case), "w") as f:
            f.write(sky)
        blend = case.endswith("_blend")
        room = "room_pane.rad" if "pane" in case else "room_open.rad"
        oconv(["sky_%s.rad" % case, room], "%s.oct" % case, wd)
        oconv(["sky_%s.rad" % case], "sky_%s.oct" % case, wd)
        # unobstructed outdoor point: sky only, -ab 1 (sky seen directly) + sun direct
        outdoor = []
        for _ in range(a.runs):
            v, _c = rtrace_points("sky_%s.oct" % case, [(0, 0, 0)], rtrace_opts(a.ad * 4, 1, a.lw), wd)
            outdoor += v
        om, ose = stats(outdoor)
        sun_h = 0.0
        if "sun_horizontal_lux" in info:
            sun_h = info["sun_horizontal_lux"]
        elif "sun_normal_lux_from_radiance" in info:
            sun_h = info["sun_normal_lux_from_radiance"] * math.sin(math.radians(SUN_ALT))
        e_sky_int = sky_horizontal(kind, info["skyfunc_args"], blend=blend) * WHITE_EFFICACY
        info["outdoor_horizontal"] = {
            "rtrace_mean_lux": om, "rtrace_se_lux": ose,
            "independent_sky_integral_lux": e_sky_int, "sun_horizontal_lux": sun_h,
            "independent_total_lux": e_sky_int + sun_h}
        # direct sun alone (-ab 0 gives only the direct part: the sky glow is
        # not a light source, it is reached only by ambient rays)
        if "sun" in sky:
            v, _c = rtrace_points("%s.oct" % case, pts_rad, rtrace_opts(a.ad, 0, a.lw), wd)
            info["direct_sun_only_lux"] = [{"point": p, "lux": x} for p, x in zip(POINTS, v)]
        # the actual runs
        samples = [[] for _ in POINTS]
        for r in range(a.runs):
            v, cmd = rtrace_points("%s.oct" % case, pts_rad, opts, wd)
            for i, x in enumerate(v):
                samples[i].append(x)
        distinct = len({tuple(s[i] for s in samples) for i in range(a.runs)}) == a.runs
        pts = []
        for p, s in zip(POINTS, samples):
            m, se = stats(s)
            pts.append({"point": p, "lux": m, "se": se, "se_pct": 100 * se / m if m else None,
                        "runs": s})
        info["command"] = "cd %s && rtrace %s %s.oct < points" % (wd, " ".join(opts), case)
        info["runs_all_distinct"] = distinct
        info["points"] = pts
        info["wall_time_s"] = time.time() - t0
        result["cases"][case] = info
        print("case %s done in %.0f s" % (case, info["wall_time_s"]), file=sys.stderr, flush=True)
        if a.out:  # write incrementally
            with open(a.out, "w") as f:
                json.dump(result, f, indent=1)
    txt = json.dumps(result, indent=1)
    print(txt)
    if a.out:
        with open(a.out, "w") as f:
            f.write(txt)


if __name__ == "__main__":
    main()
