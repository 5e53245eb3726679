#!/usr/bin/env python3
"""G2 figure of ../shared/BENCHMARK.md (the G1 definition) for any image size, with region means
that do not assume the Cornell box.

  g2_rmse.py [--grid CxR] [--avg OUT.exr] REFERENCE.exr IMAGE.exr [IMAGE2.exr ...]

rmse_rel = sqrt(mean((Y - Y*)^2)) / mean(Y*) over the pixels left after removing the
reference's 0.5 % brightest (Y Rec. 709; scripts/mitsuba/g1_rmse.py does the arithmetic and
reads the EXRs). Region means: the image cut into a C x R grid of tiles (default 4x3, row 0 at
the top as raygine shows it), mean Y of the kept pixels of each tile, image over reference.
--avg writes the mean of REFERENCE and the images (for a reference made of several renders).
"""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "mitsuba"))
from g1_rmse import compare, luminance, read_exr  # noqa: E402


def main(argv):
    grid, avg = (4, 3), None
    while argv and argv[0].startswith("--"):
        if argv[0] == "--grid":
            grid = tuple(int(v) for v in argv[1].lower().split("x"))
        elif argv[0] == "--avg":
            avg = argv[1]
        else:
            raise SystemExit(__doc__)
        argv = argv[2:]
    if len(argv) < 2:
        raise SystemExit(__doc__)
    ref = read_exr(argv[0])
    ref_y = luminance(ref)
    h, w = ref_y.shape
    cols, rows = grid
    images = [ref]
    for path in argv[1:]:
        img = read_exr(path)
        images.append(img)
        img_y = luminance(img)
        rmse, keep, n_drop = compare(ref_y, img_y)
        mr, mi_ = ref_y[keep].mean(), img_y[keep].mean()
        print(f"{path}: G2 rmse_rel={rmse:.5f} ({rmse * 100:.2f} %) meanY ref={mr:.4f} "
              f"img={mi_:.4f} ratio={mi_ / mr:.4f} (removed {n_drop} brightest)")
        cells = []
        for r in range(rows):
            for c in range(cols):
                box = (slice(r * h // rows, (r + 1) * h // rows), slice(c * w // cols, (c + 1) * w // cols))
                k = keep[box]
                cells.append(f"{img_y[box][k].mean() / ref_y[box][k].mean():.3f}")
            cells.append("|")
        print("  tile ratios (rows top to bottom): " + " ".join(cells[:-1]))
    if avg:
        import mitsuba as mi

        mean = np.mean(images, axis=0).astype(np.float32)
        mi.Bitmap(np.ascontiguousarray(mean), mi.Bitmap.PixelFormat.RGB).write(avg)
        print(f"wrote {avg} (mean of {len(images)})")


if __name__ == "__main__":
    main(sys.argv[1:])
