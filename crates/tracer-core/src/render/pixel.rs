//! The per-pixel sample loop, written once: one-shot renders and progressive sessions both ask
//! a [`FrameSampler`] for sample `s` of pixel (x, y). Everything a sample draws comes from
//! streams keyed by (pixel, sample index), so any thread count, order or split of the sample
//! range gives the same sums.

use super::RenderSettings;
use super::camera_rays::camera_rays;
use super::guides::{Guide, trace_guide};
use super::pixel_sum::PixelSum;
use super::sampler::{SampleJob, pixel_sample_offset};
use crate::geometry::Ray;
use crate::integrator::{
    DirectBatch, Integrator, IntegratorKind, IntegratorSettings, Sample, Splat, Want,
    trace_direct_batch,
};
use crate::lit_scene::LitScene;
use crate::sampling::SampleRng;
use crate::scene::{CameraBasis, Scene, Setup};
use std::ops::Range;
use std::sync::atomic::{AtomicU32, Ordering};

/// Stream key of preview samples (never accumulated), apart from every pixel's.
const PREVIEW_STREAM: u64 = 1 << 62;
/// Stream key of the denoiser's guide rays, apart from every pixel's and the previews'.
const GUIDE_STREAM: u64 = 1 << 61;

/// Camera samples traced together: at most this many per batch. Big enough for the wavefront
/// to keep the CPU busy, small enough for its working set to stay in the first-level caches.
pub const BATCH_SAMPLES: usize = 256;

/// Working memory for [`FrameSampler::sample_batch`], reused from batch to batch.
#[derive(Debug, Default)]
pub struct BatchScratch {
    jobs: Vec<SampleJob>,
    samples: Vec<Sample>,
    rays: Vec<Ray>,
    /// Indices of the batch's samples outside the image.
    outside: Vec<u32>,
    direct: DirectBatch,
}

/// An integrator and a camera for one image.
#[derive(Debug)]
pub struct FrameSampler<'a> {
    pub integrator: Box<dyn Integrator + 'a>,
    pub basis: CameraBasis,
    /// Whether the denoiser's guides are traced too ([`super::RenderSettings::guides`]).
    pub guides: bool,
    /// The first sample index whose illuminance is measured: 0 with
    /// [`super::RenderSettings::pixel_illuminance`] (and always in direct mode), else none
    /// until a session asks for it between passes ([`FrameSampler::set_illuminance_from`]).
    /// Earlier samples read 0 lx, so a pixel's illuminance sum holds its samples from here on.
    illuminance_from: AtomicU32,
}

/// [`FrameSampler::illuminance_from`] when no sample measures the illuminance.
pub const NO_ILLUMINANCE: u32 = u32::MAX;

impl<'a> FrameSampler<'a> {
    pub fn new(scene: &'a Scene, setup: &Setup, settings: &RenderSettings) -> Self {
        let lit = LitScene::new(scene, setup, settings.max_depth);
        let integrator = crate::integrator::build(
            settings.integrator,
            lit,
            IntegratorSettings {
                max_bounces: settings.max_bounces,
            },
        );
        // Direct light has the illuminance at no cost: always measured.
        let from = if settings.pixel_illuminance || settings.integrator == IntegratorKind::Direct {
            0
        } else {
            NO_ILLUMINANCE
        };
        Self {
            integrator,
            basis: setup
                .camera
                .basis(setup.handedness, settings.width, settings.height),
            guides: settings.guides,
            illuminance_from: AtomicU32::new(from),
        }
    }

    /// The first sample index whose illuminance is measured ([`NO_ILLUMINANCE`]: none).
    pub fn illuminance_from(&self) -> u32 {
        self.illuminance_from.load(Ordering::Relaxed)
    }

    /// Measure the illuminance of samples `from` on (and of previews). Only between passes:
    /// no sample of index `from` or above may have been traced yet, so every pixel's samples
    /// from there on carry it and none before.
    pub fn set_illuminance_from(&self, from: u32) {
        self.illuminance_from.store(from, Ordering::Relaxed);
    }

    /// What sample `s` is asked for.
    #[inline]
    fn want(&self, s: u32) -> Want {
        Want {
            index: s,
            illuminance: s >= self.illuminance_from(),
        }
    }

    /// Sample `s` of pixel (`x`, `y`); contributions it makes to other pixels (bidirectional
    /// mode) go to `splats`.
    pub fn sample(&self, x: u32, y: u32, s: u32, splats: &mut Vec<Splat>) -> Sample {
        let (ray, mut rng) = self.camera_ray(SampleJob { x, y, s });
        let Some(ray) = ray else {
            return self
                .integrator
                .sample_outside(&self.basis, &mut rng, splats);
        };
        let want = self.want(s);
        let mut sample = self
            .integrator
            .sample_camera(&self.basis, &ray, &mut rng, want, splats);
        if !want.illuminance {
            sample.illuminance_lx = 0.0;
        }
        sample
    }

    /// The denoiser's guide of sample `s` of pixel (`x`, `y`): the same camera ray as the
    /// sample's, its own random stream (an empty guide outside the image).
    pub fn guide(&self, x: u32, y: u32, s: u32) -> Guide {
        let (ray, _) = self.camera_ray(SampleJob { x, y, s });
        let Some(ray) = ray else {
            return Guide::default();
        };
        let key = u64::from(y) * u64::from(self.basis.width) + u64::from(x);
        let mut rng = SampleRng::new(GUIDE_STREAM ^ key, s);
        trace_guide(self.integrator.lit(), &ray, &mut rng)
    }

    /// The camera ray of a sample (None outside the image) and its random stream.
    #[inline]
    fn camera_ray(&self, SampleJob { x, y, s }: SampleJob) -> (Option<Ray>, SampleRng) {
        let width = self.basis.width;
        let (dx, dy) = pixel_sample_offset(x, y, width, s);
        let ray = self.basis.ray(x as f32 + dx, y as f32 + dy);
        (ray, self.sample_rng(SampleJob { x, y, s }))
    }

    /// The random stream of a sample, keyed by its pixel and sample index.
    #[inline]
    fn sample_rng(&self, SampleJob { x, y, s }: SampleJob) -> SampleRng {
        let key = u64::from(y) * u64::from(self.basis.width) + u64::from(x);
        SampleRng::new(key, s)
    }

    /// The samples `jobs` (at most [`BATCH_SAMPLES`] is best), written to `out` in the same
    /// order: equal, bit for bit, to calling [`FrameSampler::sample`] for each. Direct light is
    /// traced as a wavefront; the other integrators go sample by sample.
    pub fn sample_batch(
        &self,
        jobs: &[SampleJob],
        scratch: &mut BatchScratch,
        splats: &mut Vec<Splat>,
        out: &mut Vec<Sample>,
    ) {
        out.clear();
        if self.integrator.kind() != IntegratorKind::Direct {
            out.extend(jobs.iter().map(|j| self.sample(j.x, j.y, j.s, splats)));
            return;
        }
        camera_rays(&self.basis, jobs, &mut scratch.rays, &mut scratch.outside);
        out.resize(jobs.len(), Sample::default());
        trace_direct_batch(
            self.integrator.lit(),
            &scratch.rays,
            |i| self.sample_rng(jobs[i]),
            &mut scratch.direct,
            out,
        );
        // Film positions outside the image traced a stand-in ray: they are black.
        for &i in &scratch.outside {
            out[i as usize] = Sample::default();
        }
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

    /// For each (x, y, samples) of `pixels`, those samples of pixel (x, y), traced in batches
    /// of [`BATCH_SAMPLES`]; `add` receives runs of samples of one pixel (a pixel's samples may
    /// come in several runs). Returns the rays traced.
    pub fn for_each_sample(
        &self,
        pixels: impl IntoIterator<Item = (u32, u32, Range<u32>)>,
        scratch: &mut BatchScratch,
        splats: &mut Vec<Splat>,
        mut add: impl FnMut(u32, u32, &[Sample]),
    ) -> u64 {
        let mut rays = 0u64;
        let mut jobs = std::mem::take(&mut scratch.jobs);
        let mut out = std::mem::take(&mut scratch.samples);
        let mut flush = |jobs: &mut Vec<SampleJob>, scratch: &mut BatchScratch| {
            self.sample_batch(jobs, scratch, splats, &mut out);
            rays += out.iter().map(|s| u64::from(s.rays)).sum::<u64>();
            let mut start = 0;
            while start < jobs.len() {
                let (x, y) = (jobs[start].x, jobs[start].y);
                let len = jobs[start..]
                    .iter()
                    .take_while(|j| j.x == x && j.y == y)
                    .count();
                add(x, y, &out[start..start + len]);
                start += len;
            }
            jobs.clear();
        };
        jobs.clear();
        for (x, y, samples) in pixels {
            // A pixel's samples go in as runs, as many as the batch has room for.
            let mut s = samples.start;
            while s < samples.end {
                let room = (BATCH_SAMPLES - jobs.len()) as u32;
                let end = samples.end.min(s.saturating_add(room));
                jobs.extend((s..end).map(|s| SampleJob { x, y, s }));
                s = end;
                if jobs.len() == BATCH_SAMPLES {
                    flush(&mut jobs, scratch);
                }
            }
        }
        if !jobs.is_empty() {
            flush(&mut jobs, scratch);
        }
        scratch.jobs = jobs;
        scratch.samples = out;
        rays
    }

    /// A preview sample at film position (`fx`, `fy`) (a block centre), from its own stream.
    pub fn preview(&self, fx: f32, fy: f32) -> Sample {
        self.preview_sample(fx, fy, 0)
    }

    /// Preview sample number `index` at film position (`fx`, `fy`): the mode's own transport
    /// without splats ([`Integrator::preview_camera`]), from a stream apart from every pixel's.
    pub fn preview_sample(&self, fx: f32, fy: f32, index: u32) -> Sample {
        let key = PREVIEW_STREAM ^ (u64::from(fy.to_bits()) << 32 | u64::from(fx.to_bits()));
        let mut rng = SampleRng::new(key, index);
        let illuminance = self.illuminance_from() != NO_ILLUMINANCE;
        let Some(ray) = self.basis.ray(fx, fy) else {
            return Sample::default();
        };
        self.integrator
            .preview_camera(&self.basis, &ray, &mut rng, illuminance)
    }
}
