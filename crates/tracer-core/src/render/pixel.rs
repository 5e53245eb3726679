//! The per-pixel sample loop, written once: one-shot renders and progressive sessions both ask
//! a [`FrameSampler`] for sample `s` of pixel (x, y). Everything a sample draws comes from
//! streams keyed by (pixel, sample index), so any thread count, order or split of the sample
//! range gives the same sums.

use super::RenderSettings;
use super::film::PixelSum;
use super::sampler::pixel_sample_offset;
use crate::integrator::{Integrator, Sample, Splat};
use crate::sampling::SampleRng;
use crate::scene::{CameraBasis, Scene, Setup};
use crate::shading::Prepared;
use std::ops::Range;

/// Stream key of preview samples (never accumulated), apart from every pixel's.
const PREVIEW_STREAM: u64 = 1 << 62;

/// An integrator and a camera for one image.
#[derive(Debug)]
pub struct FrameSampler<'a> {
    pub integrator: Integrator<'a>,
    pub basis: CameraBasis,
}

impl<'a> FrameSampler<'a> {
    pub fn new(scene: &'a Scene, setup: &Setup, settings: &RenderSettings) -> Self {
        let prep = Prepared::new(scene, setup, settings.max_depth);
        let mut integrator = Integrator::new(settings.integrator, prep, settings.max_bounces);
        integrator.pixel_illuminance = settings.pixel_illuminance;
        Self {
            integrator,
            basis: setup
                .camera
                .basis(setup.handedness, settings.width, settings.height),
        }
    }

    /// Sample `s` of pixel (`x`, `y`); contributions it makes to other pixels (bidirectional
    /// mode) go to `splats`.
    pub fn sample(&self, x: u32, y: u32, s: u32, splats: &mut Vec<Splat>) -> Sample {
        let width = self.basis.width;
        let (dx, dy) = pixel_sample_offset(x, y, width, s);
        let ray = self.basis.ray(x as f32 + dx, y as f32 + dy);
        let key = u64::from(y) * u64::from(width) + u64::from(x);
        let mut rng = SampleRng::new(key, s);
        self.integrator
            .sample_camera(&self.basis, &ray, &mut rng, s, splats)
    }

    /// Adds samples `samples` of pixel (`x`, `y`) to `sum` (and their splats to `splats`);
    /// returns the rays traced.
    pub fn add_samples(
        &self,
        x: u32,
        y: u32,
        samples: Range<u32>,
        sum: &mut PixelSum,
        splats: &mut Vec<Splat>,
    ) -> u64 {
        let mut rays = 0;
        for s in samples {
            let sample = self.sample(x, y, s, splats);
            rays += u64::from(sample.rays);
            sum.add(&sample);
        }
        rays
    }

    /// A preview sample at film position (`fx`, `fy`) (a block centre), from its own stream.
    pub fn preview(&self, fx: f32, fy: f32) -> Sample {
        let key = PREVIEW_STREAM ^ (u64::from(fy.to_bits()) << 32 | u64::from(fx.to_bits()));
        let mut rng = SampleRng::new(key, 0);
        self.integrator.sample(&self.basis.ray(fx, fy), &mut rng, 0)
    }
}
