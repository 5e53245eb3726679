//! Denoising for display: Intel Open Image Denoise (OIDN) 2.x, the denoiser of Cycles and most
//! production renderers, loaded at run time ([`locate`] says where it is looked for).
//!
//! Only pictures are denoised. Every number raygine reports (pixel readouts, meters, grids,
//! the noise figure) comes from the film's exact sums, never from a denoised image.
//!
//! The filter is OIDN's `RT` with `hdr` on, guided by albedo and normal images
//! ([`crate::render::GuideFilm`]): the guides are prefiltered by OIDN itself, then the colour is
//! denoised with `cleanAux`, as OIDN's documentation advises for noisy guides.

mod locate;
mod oidn;

pub use locate::{Candidate, ENV_VAR, LIBRARY_NAME, Search, candidates};

use glam::Vec3;
use std::sync::Mutex;

/// The oldest OIDN accepted: 2.0.0 (`version` 20000).
pub const MIN_VERSION: i32 = 20_000;

#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DenoiseError {
    /// `RAYGINE_OIDN=off`.
    #[error("the denoiser is off (RAYGINE_OIDN=off)")]
    Disabled,
    /// No usable library.
    #[error("the denoiser needs Intel Open Image Denoise 2.x: {0}")]
    Unavailable(String),
    /// The library refused the images or failed while denoising.
    #[error("{0}")]
    Failed(String),
}

/// OIDN's quality setting: `High` for final images, `Balanced` (about twice as fast) for the
/// viewer's pictures while samples arrive.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Quality {
    #[default]
    High,
    Balanced,
}

impl Quality {
    /// `OIDN_QUALITY_HIGH` and `OIDN_QUALITY_BALANCED`.
    fn code(self) -> i32 {
        match self {
            Quality::High => 6,
            Quality::Balanced => 5,
        }
    }
}

/// What one denoise works on: linear colour (cd/m² per channel), albedo (0-1) and normal
/// (-1 to 1) guides, all `width` x `height`, row-major.
#[derive(Clone, Copy, Debug)]
pub struct Images<'a> {
    pub width: u32,
    pub height: u32,
    pub color: &'a [Vec3],
    pub albedo: &'a [Vec3],
    pub normal: &'a [Vec3],
}

/// A loaded denoiser with its CPU device, shared by threads (one denoise at a time).
pub struct Denoiser {
    device: Mutex<oidn::CpuDevice>,
    version: i32,
    library: String,
}

impl std::fmt::Debug for Denoiser {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Denoiser")
            .field("version", &self.version)
            .field("library", &self.library)
            .finish()
    }
}

impl Denoiser {
    /// Finds and loads OIDN (see [`locate`]), with a CPU device of `threads` threads (0: all).
    pub fn load(threads: usize) -> Result<Denoiser, DenoiseError> {
        let var = std::env::var(ENV_VAR).ok();
        let Search::Try(places) = candidates(var.as_deref()) else {
            return Err(DenoiseError::Disabled);
        };
        let mut tried = Vec::new();
        for place in &places {
            let name = match place {
                Candidate::File(p) => p.clone().into_os_string(),
                Candidate::System(n) => (*n).into(),
            };
            match oidn::Api::load(&name) {
                Ok(api) => return Self::with_api(api, threads, place.to_string()),
                Err(e) => tried.push(format!("{place}: {e}")),
            }
        }
        Err(DenoiseError::Unavailable(format!(
            "not found (tried {}). Install it with `pip install pyoidn` (in a virtual \
             environment or with --user), or set {ENV_VAR} to the library file or its folder",
            tried.join("; ")
        )))
    }

    fn with_api(api: oidn::Api, threads: usize, library: String) -> Result<Denoiser, DenoiseError> {
        let (device, version) =
            oidn::CpuDevice::new(api, threads).map_err(DenoiseError::Unavailable)?;
        check_version(version, &library)?;
        Ok(Denoiser {
            device: Mutex::new(device),
            version,
            library,
        })
    }

    /// The library's version as OIDN reports it (major * 10000 + minor * 100 + patch).
    pub fn version(&self) -> i32 {
        self.version
    }

    /// "2.5.1".
    pub fn version_text(&self) -> String {
        let v = self.version;
        format!("{}.{}.{}", v / 10_000, v / 100 % 100, v % 100)
    }

    /// Where the library was loaded from.
    pub fn library(&self) -> &str {
        &self.library
    }

    /// The denoised colour of `images` (cd/m² per channel, row-major): the guides prefiltered
    /// ([`Denoiser::prefilter`]), then the colour ([`Denoiser::denoise_clean`]).
    pub fn denoise(
        &self,
        images: &Images<'_>,
        quality: Quality,
    ) -> Result<Vec<Vec3>, DenoiseError> {
        let (albedo, normal) = self.prefilter(images, quality)?;
        self.denoise_clean(
            &Images {
                albedo: &albedo,
                normal: &normal,
                ..*images
            },
            quality,
        )
    }

    /// The albedo and normal guides of `images`, denoised by OIDN's own filter (their colour is
    /// not used). Guides converge much faster than the colour, so a caller may keep them for
    /// several [`Denoiser::denoise_clean`] calls.
    pub fn prefilter(
        &self,
        images: &Images<'_>,
        quality: Quality,
    ) -> Result<(Vec<Vec3>, Vec<Vec3>), DenoiseError> {
        let (w, h) = checked_size(images)?;
        let mut albedo = flat(images.albedo);
        let mut normal = flat(images.normal);
        let device = self.device();
        let fail = DenoiseError::Failed;
        let albedo_filter = device.filter("RT").map_err(fail)?;
        let normal_filter = device.filter("RT").map_err(fail)?;
        // SAFETY: the buffers hold w * h RGB triples and outlive the filters (declared before
        // them, dropped after); nothing moves them meanwhile.
        unsafe {
            albedo_filter.set_image("albedo", albedo.as_mut_ptr(), w, h);
            albedo_filter.set_image("output", albedo.as_mut_ptr(), w, h);
            normal_filter.set_image("normal", normal.as_mut_ptr(), w, h);
            normal_filter.set_image("output", normal.as_mut_ptr(), w, h);
        }
        for f in [&albedo_filter, &normal_filter] {
            f.set_int("quality", quality.code());
            f.commit().map_err(fail)?;
            f.execute().map_err(fail)?;
        }
        drop((albedo_filter, normal_filter));
        Ok((unflat(&albedo, false), unflat(&normal, true)))
    }

    /// The denoised colour of `images`, whose guides are clean (prefiltered): `cleanAux` on.
    pub fn denoise_clean(
        &self,
        images: &Images<'_>,
        quality: Quality,
    ) -> Result<Vec<Vec3>, DenoiseError> {
        let (w, h) = checked_size(images)?;
        let (kept, excess) = split_highlights(images.color);
        let mut color = flat(&kept);
        let mut albedo = flat(images.albedo);
        let mut normal = flat(images.normal);
        let mut output = vec![0.0f32; w * h * 3];
        let device = self.device();
        let fail = DenoiseError::Failed;
        let filter = device.filter("RT").map_err(fail)?;
        // SAFETY: as in `prefilter`: the buffers outlive the filter.
        unsafe {
            filter.set_image("color", color.as_mut_ptr(), w, h);
            filter.set_image("albedo", albedo.as_mut_ptr(), w, h);
            filter.set_image("normal", normal.as_mut_ptr(), w, h);
            filter.set_image("output", output.as_mut_ptr(), w, h);
        }
        filter.set_bool("hdr", true);
        filter.set_bool("cleanAux", true);
        filter.set_int("quality", quality.code());
        filter.commit().map_err(fail)?;
        filter.execute().map_err(fail)?;
        drop(filter);
        let mut out = unflat(&output, false);
        for (o, e) in out.iter_mut().zip(&excess) {
            *o += *e;
        }
        Ok(out)
    }

    fn device(&self) -> std::sync::MutexGuard<'_, oidn::CpuDevice> {
        match self.device.lock() {
            Ok(d) => d,
            Err(poisoned) => poisoned.into_inner(),
        }
    }
}

/// Highlights far brighter than the rest of the picture (a lamp's hot spot a few pixels wide,
/// right under a point light) are kept out of the filter: the network spreads them over their
/// neighbours, which then read many times too bright. Each pixel's luminance above
/// [`HIGHLIGHT_FACTOR`] times the picture's 99th percentile is split off (colour scaled, hue
/// kept), and added back after denoising, unfiltered.
fn split_highlights(color: &[Vec3]) -> (Vec<Vec3>, Vec<Vec3>) {
    let lum = |c: &Vec3| c.dot(crate::light::LUMINANCE_WEIGHTS);
    let mut ys: Vec<f32> = color.iter().map(lum).filter(|y| y.is_finite()).collect();
    if ys.is_empty() {
        return (color.to_vec(), vec![Vec3::ZERO; color.len()]);
    }
    let k = (ys.len() - 1) * 99 / 100;
    let p99 = *ys.select_nth_unstable_by(k, f32::total_cmp).1;
    let limit = p99.max(0.0) * HIGHLIGHT_FACTOR;
    color
        .iter()
        .map(|c| {
            let y = lum(c);
            if limit > 0.0 && y > limit {
                let kept = *c * (limit / y);
                (kept, *c - kept)
            } else {
                (*c, Vec3::ZERO)
            }
        })
        .unzip()
}

/// See [`split_highlights`]. Chosen on the built-in box (80x60, bidirectional, 4 spp, against
/// 256 spp): relative RMSE of the denoised luminance 87 % without the split (the hot spot under
/// the lamp smeared over the ceiling), 12.1 % at 2-3, 12.3 % at 4, 13.6 % at 8, 14.6 % at 1.
pub const HIGHLIGHT_FACTOR: f32 = 3.0;

fn checked_size(images: &Images<'_>) -> Result<(usize, usize), DenoiseError> {
    let (w, h) = (images.width as usize, images.height as usize);
    let n = w * h;
    if n == 0
        || [images.color, images.albedo, images.normal]
            .iter()
            .any(|i| i.len() != n)
    {
        return Err(DenoiseError::Failed(format!(
            "the colour and guide images do not match the size {w}x{h}"
        )));
    }
    Ok((w, h))
}

fn flat(v: &[Vec3]) -> Vec<f32> {
    v.iter().flat_map(|p| p.to_array()).collect()
}

/// RGB triples back to vectors; colours and albedos are kept non-negative (the network may
/// undershoot), normals keep their sign.
fn unflat(v: &[f32], signed: bool) -> Vec<Vec3> {
    v.chunks_exact(3)
        .map(|c| {
            let p = Vec3::new(c[0], c[1], c[2]);
            if signed { p } else { p.max(Vec3::ZERO) }
        })
        .collect()
}

/// The denoised picture of a film rendered with guides ([`crate::render::RenderSettings::guides`]):
/// its mean colour per pixel, denoised; an error when the film has no guides.
pub fn denoise_film(
    denoiser: &Denoiser,
    film: &crate::render::Film,
    quality: Quality,
) -> Result<Vec<Vec3>, DenoiseError> {
    let Some(guides) = &film.guides else {
        return Err(DenoiseError::Failed(
            "the film has no albedo and normal guides to denoise with".to_owned(),
        ));
    };
    let color = film.mean_rgb_all();
    let (albedo, normal) = (guides.albedo_image(), guides.normal_image());
    denoiser.denoise(
        &Images {
            width: film.width,
            height: film.height,
            color: &color,
            albedo: &albedo,
            normal: &normal,
        },
        quality,
    )
}

/// Refuses versions below 2.0 with the version found.
fn check_version(version: i32, library: &str) -> Result<(), DenoiseError> {
    if version < MIN_VERSION {
        return Err(DenoiseError::Unavailable(format!(
            "{library} is version {}.{}.{}; raygine needs 2.0 or newer",
            version / 10_000,
            version / 100 % 100,
            version % 100
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn versions_below_two_are_refused_with_the_version_found() {
        let err = check_version(10_402, "/x/libOpenImageDenoise.so.1").unwrap_err();
        assert_eq!(
            err.to_string(),
            "the denoiser needs Intel Open Image Denoise 2.x: /x/libOpenImageDenoise.so.1 is \
             version 1.4.2; raygine needs 2.0 or newer"
        );
        assert!(check_version(20_000, "x").is_ok());
        assert!(check_version(20_501, "x").is_ok());
    }
}
