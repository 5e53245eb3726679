//! A film as the payload of a part file (see `crate::shard`): the image size, then every pixel's
//! exact sums, row-major, top row first. [`pixel_fields`] is the one list of what a pixel holds;
//! a field added to the film is added there (and to [`pixel_from_fields`]), with
//! `shard::PART_FORMAT` raised so older parts are refused rather than misread.

use super::RenderSettings;
use super::film::Film;
use super::guides::{GuideFilm, GuideSum};
use super::pixel_sum::PixelSum;
use super::square_sum::SquareSum;
use crate::shard::varint::{Decoder, Encoder};

/// Integers a pixel holds in a part.
pub const PIXEL_FIELDS: usize = 13;

/// A pixel's sums in file order.
pub fn pixel_fields(p: &PixelSum) -> [i128; PIXEL_FIELDS] {
    [
        p.rgb[0],
        p.rgb[1],
        p.rgb[2],
        p.illuminance,
        p.luminance_sq.whole,
        i128::from(p.luminance_sq.fine),
        p.splat_rgb[0],
        p.splat_rgb[1],
        p.splat_rgb[2],
        p.splat_luminance_sq.whole,
        i128::from(p.splat_luminance_sq.fine),
        i128::from(p.count),
        i128::from(p.rejected),
    ]
}

/// The pixel [`pixel_fields`] wrote; None when a count or a square's fine part is out of
/// range.
pub fn pixel_from_fields(f: &[i128; PIXEL_FIELDS]) -> Option<PixelSum> {
    let square = |whole: i128, fine: i128| {
        let fine = i64::try_from(fine).ok()?;
        (0..1 << 32)
            .contains(&fine)
            .then_some(SquareSum { whole, fine })
    };
    Some(PixelSum {
        rgb: [f[0], f[1], f[2]],
        illuminance: f[3],
        luminance_sq: square(f[4], f[5])?,
        splat_rgb: [f[6], f[7], f[8]],
        splat_luminance_sq: square(f[9], f[10])?,
        count: u32::try_from(f[11]).ok()?,
        rejected: u32::try_from(f[12]).ok()?,
    })
}

/// Appends one pixel's sums.
pub fn encode_pixel(e: &mut Encoder, p: &PixelSum) {
    for v in pixel_fields(p) {
        e.i128(v);
    }
}

/// Reads one pixel's sums.
pub fn decode_pixel(d: &mut Decoder<'_>) -> Option<PixelSum> {
    let mut f = [0i128; PIXEL_FIELDS];
    for v in &mut f {
        *v = d.i128()?;
    }
    pixel_from_fields(&f)
}

/// The payload of a film.
pub fn encode_film(film: &Film) -> Vec<u8> {
    let mut e = Encoder::default();
    e.u32(film.width);
    e.u32(film.height);
    for p in film.pixels() {
        encode_pixel(&mut e, &p);
    }
    // Then the denoiser's guides, when the film has them: a flag, then per pixel albedo,
    // normal and count.
    match &film.guides {
        None => e.u32(0),
        Some(g) => {
            e.u32(1);
            for p in &g.pixels {
                for v in p.albedo.iter().chain(&p.normal) {
                    e.i128(i128::from(*v));
                }
                e.u32(p.count);
            }
        }
    }
    e.bytes
}

fn decode_guides(d: &mut Decoder<'_>, width: u32, height: u32) -> Result<GuideFilm, String> {
    let mut guides = GuideFilm::new(width, height);
    for (i, p) in guides.pixels.iter_mut().enumerate() {
        let bad = || format!("the guides of pixel {i} are unreadable");
        let mut f = [0i64; 6];
        for v in &mut f {
            *v = d
                .i128()
                .and_then(|x| i64::try_from(x).ok())
                .ok_or_else(bad)?;
        }
        *p = GuideSum {
            albedo: [f[0], f[1], f[2]],
            normal: [f[3], f[4], f[5]],
            count: d.u32().ok_or_else(bad)?,
        };
    }
    Ok(guides)
}

/// The film of a payload, or what is wrong with it.
pub fn decode_film(payload: &[u8]) -> Result<Film, String> {
    let mut d = Decoder::new(payload);
    let (Some(width), Some(height)) = (d.u32(), d.u32()) else {
        return Err("no image size".to_owned());
    };
    if u64::from(width) * u64::from(height) > payload.len() as u64 {
        return Err(format!("{width}x{height} pixels do not fit in the payload"));
    }
    let mut film = Film::new(width, height);
    for i in 0..film.len() {
        let p = decode_pixel(&mut d).ok_or_else(|| format!("pixel {i} is unreadable"))?;
        film.set_pixel(i, &p);
    }
    match d.u32() {
        Some(0) => {}
        Some(1) => film.guides = Some(decode_guides(&mut d, width, height)?),
        _ => return Err("no guide flag after the last pixel".to_owned()),
    }
    if !d.is_at_end() {
        return Err("bytes after the last pixel".to_owned());
    }
    Ok(film)
}

/// What a film's sums depend on besides the scene, setup and sample range: compared verbatim
/// between parts.
pub fn settings_line(s: &RenderSettings) -> String {
    let bounces = s
        .max_bounces
        .map_or_else(|| "none".to_owned(), |n| n.to_string());
    format!(
        "{}x{} {} max_depth={} max_bounces={bounces}",
        s.width,
        s.height,
        s.integrator.name(),
        s.max_depth
    )
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use crate::integrator::Sample;
    use glam::Vec3;

    #[test]
    fn a_film_survives_the_payload_bit_for_bit() {
        let mut film = Film::new(3, 2);
        for i in 0..film.len() {
            let mut p = PixelSum::default();
            for s in 0..i {
                p.add(&Sample {
                    rgb: Vec3::new(s as f32 * 1e6, -0.25, 3.5e-9),
                    illuminance_lx: 1e9,
                    rays: 1,
                    missed: false,
                });
            }
            if i == 5 {
                p.rejected = 3;
            }
            film.set_pixel(i, &p);
        }
        let payload = encode_film(&film);
        assert_eq!(decode_film(&payload).unwrap(), film);
        let mut guided = Film::with_guides(3, 2);
        if let Some(g) = guided.guides.as_mut() {
            g.pixels[4].add(&crate::render::Guide {
                albedo: Vec3::new(0.5, 0.25, 1.0),
                normal: Vec3::new(0.0, -1.0, 0.0),
            });
        }
        let back = decode_film(&encode_film(&guided)).unwrap();
        assert_eq!(back, guided);
        assert!(back.guides.is_some());
        assert!(decode_film(&payload[..payload.len() - 1]).is_err());
        let mut longer = payload.clone();
        longer.push(0);
        assert!(decode_film(&longer).is_err());
    }
}
