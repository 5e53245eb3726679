#!/usr/bin/env python3
"""G1 figure of ../shared/BENCHMARK.md: relative RMSE of luminance against a reference.

  g1_rmse.py REFERENCE.exr IMAGE.exr [IMAGE2.exr ...]

Y = 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709) per pixel; the reference's 0.5 % brightest
pixels (the light's hot spot) are removed; over the pixels left:

  rmse_rel = sqrt(mean((Y - Y*)^2)) / mean(Y*)

Also prints mean Y of both over the same pixels, their ratio, and region means (over the kept
pixels of rough boxes that see one surface each in the built-in Cornell box at 160x120 as raygine
shows it, red wall on the left; boxes scale with other image sizes of the same 4:3 camera).

Reads EXRs with mitsuba's Bitmap (any variant, nothing is rendered), else with the `OpenEXR`
or `imageio` package.
"""

import sys

import numpy as np

REC709 = np.array([0.2126, 0.7152, 0.0722])
TRIM = 0.005  # fraction of the reference's brightest pixels removed

# x0, x1, y0, y1 (half-open, pixels) at 160x120, image as raygine shows it (row 0 at the top).
REGIONS = {
    "left_wall(red)": (26, 42, 32, 88),
    "right_wall(green)": (120, 134, 32, 88),
    "floor": (40, 74, 106, 116),
    "ceiling": (50, 110, 6, 20),
    "back_wall": (50, 108, 32, 48),
}


def read_exr(path):
    """(H, W, 3) float64 linear RGB."""
    try:
        import mitsuba as mi

        if mi.variant() is None:
            mi.set_variant("scalar_rgb")
        bmp = mi.Bitmap(path)
        if bmp.pixel_format() not in (mi.Bitmap.PixelFormat.RGB, mi.Bitmap.PixelFormat.RGBA):
            raise SystemExit(f"error: {path}: pixel format {bmp.pixel_format()}, expected RGB(A)")
        arr = np.array(bmp, dtype=np.float64)
    except ImportError:
        try:
            import imageio.v3 as iio

            arr = np.asarray(iio.imread(path), dtype=np.float64)
        except ImportError:
            import OpenEXR
            import Imath

            f = OpenEXR.InputFile(path)
            dw = f.header()["dataWindow"]
            w, h = dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1
            pt = Imath.PixelType(Imath.PixelType.FLOAT)
            arr = np.stack([np.frombuffer(f.channel(c, pt), np.float32).reshape(h, w) for c in "RGB"], -1)
            return arr.astype(np.float64)
    if arr.ndim != 3 or arr.shape[2] < 3:
        raise SystemExit(f"error: {path}: expected an RGB image, got shape {arr.shape}")
    return arr[:, :, :3]


def luminance(arr):
    return arr @ REC709


def compare(ref_y, img_y):
    if ref_y.shape != img_y.shape:
        raise SystemExit(f"error: sizes differ: reference {ref_y.shape[::-1]}, image {img_y.shape[::-1]}")
    n = ref_y.size
    n_drop = int(round(TRIM * n))
    order = np.argsort(ref_y, axis=None, kind="stable")
    keep = np.ones(n, dtype=bool)
    if n_drop:
        keep[order[-n_drop:]] = False
    keep = keep.reshape(ref_y.shape)
    r, y = ref_y[keep], img_y[keep]
    rmse = float(np.sqrt(np.mean((y - r) ** 2)) / np.mean(r))
    return rmse, keep, n_drop


def main(argv):
    if len(argv) < 3:
        raise SystemExit(__doc__)
    ref_y = luminance(read_exr(argv[1]))
    h, w = ref_y.shape
    sx, sy = w / 160.0, h / 120.0
    for path in argv[2:]:
        img_y = luminance(read_exr(path))
        rmse, keep, n_drop = compare(ref_y, img_y)
        mr, mi_ = ref_y[keep].mean(), img_y[keep].mean()
        print(f"{path}: G1 rmse_rel={rmse:.5f} ({rmse * 100:.3f} %)  pixels={keep.sum()} (removed {n_drop} brightest "
              f"of the reference)  meanY ref={mr:.4f} img={mi_:.4f} cd/m2  ratio img/ref={mi_ / mr:.5f}")
        for name, (x0, x1, y0, y1) in REGIONS.items():
            box = (slice(int(y0 * sy), int(y1 * sy)), slice(int(x0 * sx), int(x1 * sx)))
            k = keep[box]
            rm, im = ref_y[box][k].mean(), img_y[box][k].mean()
            print(f"  {name:18s} x{x0}-{x1} y{y0}-{y1}: ref={rm:9.4f}  img={im:9.4f}  ratio={im / rm:.4f}")


if __name__ == "__main__":
    main(sys.argv)
