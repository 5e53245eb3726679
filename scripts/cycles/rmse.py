#!/usr/bin/env python3
"""Relative RMSE of luminance of a candidate EXR against a reference EXR (BENCHMARK.md, G1/D1).

  /work/venv-bpy/bin/python scripts/cycles/rmse.py CANDIDATE.exr REFERENCE.exr \
      [--layer denoised] [--ref-layer LAYER] [--trim 0.005]

Both images: linear RGB, same size, same orientation (raygine's: red wall on the left;
cornell_cycles.py already writes its --out flipped to it). No flipping is done here
(--flip-candidate mirrors the candidate left-right, for an unflipped Cycles/Mitsuba EXR).

Y = 0.2126 R + 0.7152 G + 0.0722 B per pixel. The reference's brightest `trim` fraction of pixels
(0.5 %: the light's hot spot) is removed; over the pixels left

  rmse_rel = sqrt(mean((Y - Y*)^2)) / mean(Y*)

Also prints mean Y and Y* over the kept pixels and over the kept pixels of five boxes given as
fractions of the image (each sees one surface of the built-in Cornell box as raygine shows it).

--layer / --ref-layer pick channels `LAYER.R, LAYER.G, LAYER.B` (raygine's --denoise EXR has the
raw image in R, G, B and the denoised one in denoised.R, .G, .B); default: plain R, G, B.
--layer applies to the candidate only.
"""

import argparse
import sys

import numpy as np

REC709 = np.array([0.2126, 0.7152, 0.0722])

# name: (x0, x1, y0, y1) as fractions of width/height, row 0 at the top, raygine's orientation.
REGIONS = {
    "left_wall": (0.165, 0.26, 0.27, 0.73),
    "right_wall": (0.75, 0.835, 0.27, 0.73),
    "back_wall": (0.31, 0.675, 0.27, 0.40),
    "floor": (0.25, 0.46, 0.885, 0.965),
    "ceiling": (0.31, 0.69, 0.05, 0.165),
}


def read_exr(path, layer=None):
    """(H, W, 3) float64 from channels R, G, B or LAYER.R, LAYER.G, LAYER.B."""
    import OpenEXR

    with OpenEXR.File(str(path), separate_channels=True) as f:
        ch = f.channels()
        names = [f"{layer}.{c}" if layer else c for c in "RGB"]
        missing = [n for n in names if n not in ch]
        if missing:
            sys.exit(f"error: {path}: no channel(s) {missing}; it has {sorted(ch)}")
        return np.stack([np.asarray(ch[n].pixels, np.float64) for n in names], -1)


def box(shape, frac):
    h, w = shape
    x0, x1, y0, y1 = frac
    return slice(int(round(y0 * h)), int(round(y1 * h))), slice(int(round(x0 * w)), int(round(x1 * w)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("candidate")
    ap.add_argument("reference")
    ap.add_argument("--layer", default=None, help="candidate channel layer, e.g. denoised")
    ap.add_argument("--ref-layer", default=None, help="reference channel layer")
    ap.add_argument("--trim", type=float, default=0.005, help="reference's brightest fraction removed")
    ap.add_argument("--flip-candidate", action="store_true", help="mirror the candidate left-right first")
    args = ap.parse_args()

    c = read_exr(args.candidate, args.layer)
    r = read_exr(args.reference, args.ref_layer)
    if args.flip_candidate:
        c = c[:, ::-1, :]
    if c.shape != r.shape:
        sys.exit(f"error: sizes differ: candidate {c.shape[1]}x{c.shape[0]}, reference {r.shape[1]}x{r.shape[0]}")
    y, ys = c @ REC709, r @ REC709
    bad = ~np.isfinite(y)
    if bad.any():
        print(f"warning: {bad.sum()} non-finite candidate pixels (counted as 0)", file=sys.stderr)
        y = np.where(bad, 0.0, y)

    n = ys.size
    n_drop = int(round(args.trim * n))
    order = np.argsort(ys, axis=None, kind="stable")
    keep = np.ones(n, bool)
    if n_drop:
        keep[order[n - n_drop:]] = False
    keep = keep.reshape(ys.shape)

    d = (y - ys)[keep]
    mref = ys[keep].mean()
    rmse_rel = np.sqrt(np.mean(d * d)) / mref
    mc = y[keep].mean()
    print(f"rmse_rel={rmse_rel:.5f} ({100 * rmse_rel:.2f} %) mean_Y={mc:.4f} mean_Yref={mref:.4f} "
          f"ratio={mc / mref:.4f} kept={keep.sum()}/{n} size={ys.shape[1]}x{ys.shape[0]} "
          f"candidate={args.candidate}{'[' + args.layer + ']' if args.layer else ''} reference={args.reference}")
    for name, frac in REGIONS.items():
        sl = box(ys.shape, frac)
        k = keep[sl]
        if not k.any():
            continue
        a, b = y[sl][k].mean(), ys[sl][k].mean()
        dd = (y[sl] - ys[sl])[k]
        print(f"  {name:11s} mean_Y={a:10.4f} mean_Yref={b:10.4f} ratio={a / b:.4f} "
              f"rmse_rel={np.sqrt(np.mean(dd * dd)) / b:.4f} pixels={k.sum()}")


if __name__ == "__main__":
    main()
