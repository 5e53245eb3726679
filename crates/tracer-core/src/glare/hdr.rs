//! A glare image as a Radiance picture (RGBE, run-length encoded scanlines) that evalglare
//! reads: grey pixels of L / 179 (Radiance's luminance is 179 · (0.265 R + 0.670 G + 0.065 B)),
//! and a `VIEW= -vta … -vh 180 -vv 180` line with the eye, the line of sight and up.

use super::image::GlareImage;

/// Radiance's luminous efficacy of its RGB white (lm/W).
pub const RADIANCE_EFFICACY: f64 = 179.0;

/// The eye and view of a 180° `-vta` picture, scene coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    pub position: [f32; 3],
    pub direction: [f32; 3],
    pub up: [f32; 3],
}

/// One RGBE quadruple for the grey value `v`.
fn rgbe(v: f64) -> [u8; 4] {
    if v.is_nan() || v <= 1e-32 {
        return [0; 4];
    }
    let e = v.log2().floor() as i32 + 1;
    let m = v / 2f64.powi(e); // [0.5, 1)
    let byte = ((m * 256.0).floor() as i32).clamp(0, 255) as u8;
    let exponent = (e + 128).clamp(0, 255) as u8;
    [byte, byte, byte, exponent]
}

/// Writes one scanline of RGBE pixels in Radiance's run-length form (components apart, runs of
/// equal bytes and literal dumps of up to 127 and 128 bytes).
fn write_scanline(out: &mut Vec<u8>, pixels: &[[u8; 4]]) {
    let w = pixels.len();
    out.extend_from_slice(&[2, 2, (w >> 8) as u8, (w & 0xff) as u8]);
    for c in 0..4 {
        let bytes: Vec<u8> = pixels.iter().map(|p| p[c]).collect();
        let mut i = 0;
        while i < w {
            let mut run = 1;
            while i + run < w && run < 127 && bytes[i + run] == bytes[i] {
                run += 1;
            }
            if run >= 4 {
                out.push(128 + run as u8);
                out.push(bytes[i]);
                i += run;
                continue;
            }
            // A literal dump up to the next run of four (or 128 bytes).
            let start = i;
            while i < w && i - start < 128 {
                let ahead = (i..w.min(i + 4)).all(|j| bytes[j] == bytes[i]) && i + 4 <= w;
                if ahead {
                    break;
                }
                i += 1;
            }
            if i == start {
                continue;
            }
            out.push((i - start) as u8);
            out.extend_from_slice(&bytes[start..i]);
        }
    }
}

/// The picture's bytes.
pub fn radiance_hdr(image: &GlareImage, view: &View) -> Vec<u8> {
    let [px, py, pz] = view.position;
    let [dx, dy, dz] = view.direction;
    let [ux, uy, uz] = view.up;
    let mut out = format!(
        "#?RADIANCE\nSOFTWARE=raygine {}\nFORMAT=32-bit_rle_rgbe\n\
         VIEW= -vta -vp {px} {py} {pz} -vd {dx} {dy} {dz} -vu {ux} {uy} {uz} -vh 180 -vv 180\n\
         \n-Y {} +X {}\n",
        env!("CARGO_PKG_VERSION"),
        image.height,
        image.width
    )
    .into_bytes();
    let w = image.width as usize;
    for row in 0..image.height as usize {
        let pixels: Vec<[u8; 4]> = (0..w)
            .map(|x| rgbe(image.luminance[row * w + x] / RADIANCE_EFFICACY))
            .collect();
        if (8..0x8000).contains(&w) {
            write_scanline(&mut out, &pixels);
        } else {
            for p in pixels {
                out.extend_from_slice(&p);
            }
        }
    }
    out
}

/// Writes the picture to `path` as every export is written (through a temporary file beside
/// it, so a failed write leaves nothing half-written).
pub fn write_radiance_hdr(
    path: &std::path::Path,
    image: &GlareImage,
    view: &View,
) -> Result<(), crate::export::ExportError> {
    crate::export::write_bytes(path, &radiance_hdr(image, view))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Decodes what `write_scanline` wrote (Radiance's reader, for the test).
    fn read_scanline(bytes: &[u8], w: usize) -> (Vec<[u8; 4]>, usize) {
        assert_eq!(&bytes[..2], &[2, 2]);
        assert_eq!(((bytes[2] as usize) << 8) | bytes[3] as usize, w);
        let mut at = 4;
        let mut px = vec![[0u8; 4]; w];
        for c in 0..4 {
            let mut x = 0;
            while x < w {
                let n = bytes[at] as usize;
                at += 1;
                if n > 128 {
                    for p in px.iter_mut().skip(x).take(n - 128) {
                        p[c] = bytes[at];
                    }
                    at += 1;
                    x += n - 128;
                } else {
                    for (k, p) in px.iter_mut().skip(x).take(n).enumerate() {
                        p[c] = bytes[at + k];
                    }
                    at += n;
                    x += n;
                }
            }
        }
        (px, at)
    }

    #[test]
    fn rgbe_round_trips_within_its_precision_and_scanlines_decode() {
        for v in [1e-3, 0.5, 1.0, 3.7, 1234.5, 6.1e6] {
            let [m, _, _, e] = rgbe(v);
            let back = (f64::from(m) + 0.5) * 2f64.powi(i32::from(e) - 136);
            assert!((back / v - 1.0).abs() < 1.0 / 128.0, "{v} -> {back}");
        }
        assert_eq!(rgbe(0.0), [0; 4]);
        let pixels: Vec<[u8; 4]> = (0..300)
            .map(|i| {
                if i % 50 < 20 {
                    [7, 7, 7, 130]
                } else {
                    rgbe(i as f64)
                }
            })
            .collect();
        let mut out = Vec::new();
        write_scanline(&mut out, &pixels);
        let (back, used) = read_scanline(&out, pixels.len());
        assert_eq!(back, pixels);
        assert_eq!(used, out.len());
    }
}
