//! Small pictures of environment maps for the Environment section: each map is averaged down
//! and tone-mapped on a background job the first time it is shown, then kept as an egui
//! texture, so a frame never walks a map's millions of texels.

use crate::file_ops::Job;
use glam::Vec3;
use std::sync::{Arc, Weak};
use tracer_core::display::{ToneMap, linear_to_srgb};
use tracer_core::light::{Environment, EnvironmentMap, EnvironmentSource};

/// The thumbnails' width, pixels (their height is half of it); a narrower map keeps its width.
pub const THUMBNAIL_WIDTH: usize = 256;

/// Maps whose thumbnails are kept: undo and redo between a few maps find theirs at once.
const KEPT: usize = 4;

/// Thumbnails of the maps shown lately, and the one being made.
#[derive(Default)]
pub struct MapThumbnails {
    /// Most recent last. A map is held weakly: a map no setup uses any more is freed.
    made: Vec<(Weak<EnvironmentMap>, egui::TextureHandle)>,
    making: Option<(Weak<EnvironmentMap>, Job<egui::ColorImage>)>,
    /// The map whose thumbnail could not be made: not tried again.
    failed: Weak<EnvironmentMap>,
}

impl std::fmt::Debug for MapThumbnails {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MapThumbnails")
            .field("made", &self.made.len())
            .field("making", &self.making.is_some())
            .finish()
    }
}

fn is(weak: &Weak<EnvironmentMap>, map: &Arc<EnvironmentMap>) -> bool {
    std::ptr::eq(weak.as_ptr(), Arc::as_ptr(map))
}

impl MapThumbnails {
    /// Takes a finished thumbnail, and starts one for the environment's map when it has none.
    /// Returns why a thumbnail could not be made, once.
    pub fn update(&mut self, ctx: &egui::Context, env: Option<&Environment>) -> Option<String> {
        let mut failed = None;
        if let Some(result) = self.making.as_ref().and_then(|(_, job)| job.poll())
            && let Some((map, _)) = self.making.take()
        {
            match result {
                Ok(image) => {
                    let texture =
                        ctx.load_texture("environment map", image, egui::TextureOptions::LINEAR);
                    self.made.retain(|(m, _)| m.strong_count() > 0);
                    if self.made.len() >= KEPT {
                        self.made.drain(..1);
                    }
                    self.made.push((map, texture));
                }
                Err(e) => {
                    failed = Some(e);
                    self.failed = map;
                }
            }
        }
        let Some(EnvironmentSource::Map(map)) = env.map(|e| &e.source) else {
            return failed;
        };
        let known = self.made.iter().any(|(m, _)| is(m, map))
            || self.making.as_ref().is_some_and(|(m, _)| is(m, map))
            || is(&self.failed, map);
        if !known {
            let shared = Arc::clone(map);
            let job = Job::start(
                "raygine-thumbnail",
                "the environment map's thumbnail",
                ctx,
                move || Ok(thumbnail_image(&shared, THUMBNAIL_WIDTH)),
            );
            // A thumbnail still being made for a map no longer shown is dropped with its job.
            self.making = Some((Arc::downgrade(map), job));
        }
        failed
    }

    /// The thumbnail of `map`, once made.
    pub fn get(&self, map: &Arc<EnvironmentMap>) -> Option<&egui::TextureHandle> {
        self.made
            .iter()
            .rev()
            .find(|(m, _)| is(m, map))
            .map(|(_, t)| t)
    }
}

/// `map` averaged down to `width` x `width / 2` pixels (box filter; a narrower map keeps its
/// size), its log-average luminance shown as middle grey through the filmic curve, in sRGB.
pub fn thumbnail_image(map: &EnvironmentMap, width: usize) -> egui::ColorImage {
    let width = width.min(map.width).max(1);
    let height = (width / 2).clamp(1, map.height.max(1));
    let mut sums = vec![(Vec3::ZERO, 0u32); width * height];
    for (i, texel) in map.texels.iter().enumerate() {
        let (row, col) = (i / map.width, i % map.width);
        let cell = (row * height / map.height) * width + col * width / map.width;
        if let Some((sum, n)) = sums.get_mut(cell) {
            *sum += *texel;
            *n += 1;
        }
    }
    let means: Vec<Vec3> = sums
        .iter()
        .map(|(sum, n)| *sum / (*n).max(1) as f32)
        .collect();
    // The map's look, whatever its scale: the log-average of its lit cells at middle grey.
    let (log_sum, lit) = means
        .iter()
        .map(|c| tracer_core::light::luminance(*c))
        .filter(|y| *y > 1e-9 && y.is_finite())
        .fold((0.0f64, 0u32), |(s, n), y| (s + f64::from(y.ln()), n + 1));
    let exposure = if lit > 0 {
        0.18 / (log_sum / f64::from(lit)).exp() as f32
    } else {
        1.0
    };
    let encode = |c: f32| (linear_to_srgb(c) * 255.0 + 0.5).clamp(0.0, 255.0) as u8;
    let pixels = means
        .iter()
        .map(|c| {
            let m = ToneMap::Filmic.apply(*c * exposure);
            egui::Color32::from_rgb(encode(m.x), encode(m.y), encode(m.z))
        })
        .collect();
    egui::ColorImage::new([width, height], pixels)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use std::path::Path;

    fn map(width: usize, texels: Vec<Vec3>) -> EnvironmentMap {
        EnvironmentMap::from_texels(Path::new("t.hdr"), width, width / 2, texels)
            .unwrap()
            .0
    }

    /// Each thumbnail pixel is the mean of its block: a map with a bright top half and a dark
    /// bottom half stays so, and its mean level shows as middle grey whatever its scale.
    #[test]
    fn thumbnails_average_blocks_and_ignore_the_scale() {
        let (w, h) = (64, 32);
        let texels = |scale: f32| {
            (0..w * h)
                .map(|i| Vec3::splat(if i / w < h / 2 { 4.0 } else { 1.0 } * scale))
                .collect::<Vec<_>>()
        };
        let image = thumbnail_image(&map(w, texels(1.0)), 16);
        assert_eq!(image.size, [16, 8]);
        let top = image.pixels[0];
        let bottom = image.pixels[16 * 7];
        assert!(top.r() > bottom.r(), "{top:?} vs {bottom:?}");
        assert_eq!(top.r(), top.g());
        let scaled = thumbnail_image(&map(w, texels(1000.0)), 16);
        assert_eq!(scaled.pixels, image.pixels);
        // A map narrower than asked keeps its size; a black one stays black.
        let small = thumbnail_image(&map(4, vec![Vec3::ZERO; 8]), 16);
        assert_eq!(small.size, [4, 2]);
        assert!(small.pixels.iter().all(|p| p.r() == 0));
    }
}
