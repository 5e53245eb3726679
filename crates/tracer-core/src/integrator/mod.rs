//! Integrators answer "what does this camera sample see": luminance per channel along a ray and
//! the illuminance of the first surface, plus the irradiance at a sensor point. They know no
//! tiles, passes or threads (see [`crate::render`]).
//!
//! - [`IntegratorKind::Direct`]: the coursework's model (direct light, mirrors to a depth).
//! - [`IntegratorKind::Path`]: global illumination by unbiased path tracing.

mod direct;
mod path;

pub use direct::trace as trace_direct;
pub use path::{MAX_VERTICES, PathTracer, RR_THRESHOLD};

use crate::geometry::Ray;
use crate::sampling::SampleRng;
use crate::shading::Prepared;
use glam::Vec3;

/// What one camera sample sees.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    /// Linear luminance per RGB channel, cd/m².
    pub rgb: Vec3,
    /// Illuminance (lx) on the first surface hit (0 on a miss): direct light only in direct
    /// mode, all light in path mode.
    pub illuminance_lx: f32,
    /// Rays traced for this sample.
    pub rays: u32,
}

/// Which light transport to compute.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum IntegratorKind {
    /// Direct light and mirrors (the coursework's model).
    #[default]
    Direct,
    /// Global illumination (path tracing).
    Path,
}

impl IntegratorKind {
    pub const ALL: [IntegratorKind; 2] = [IntegratorKind::Direct, IntegratorKind::Path];

    /// The command line's name.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorKind::Direct => "direct",
            IntegratorKind::Path => "path",
        }
    }

    /// What the viewer shows.
    pub fn label(self) -> &'static str {
        match self {
            IntegratorKind::Direct => "Direct (coursework)",
            IntegratorKind::Path => "Global illumination",
        }
    }

    pub fn from_name(s: &str) -> Option<Self> {
        match s {
            "direct" => Some(IntegratorKind::Direct),
            "path" | "gi" => Some(IntegratorKind::Path),
            _ => None,
        }
    }
}

impl std::fmt::Display for IntegratorKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// An integrator ready to sample one scene.
#[derive(Debug)]
pub struct Integrator<'a> {
    pub kind: IntegratorKind,
    pub prep: Prepared<'a>,
    /// Path mode: non-delta bounces allowed (None: unlimited).
    pub max_bounces: Option<u32>,
}

impl<'a> Integrator<'a> {
    pub fn new(kind: IntegratorKind, prep: Prepared<'a>, max_bounces: Option<u32>) -> Self {
        Self {
            kind,
            prep,
            max_bounces,
        }
    }

    fn path(&self, rr_threshold: f32) -> PathTracer<'_, 'a> {
        PathTracer {
            prep: &self.prep,
            max_bounces: self.max_bounces.unwrap_or(u32::MAX),
            rr_threshold,
        }
    }

    /// Camera sample number `sample_index` along `ray` (sample 0 takes the cheaper roulette
    /// in path mode).
    pub fn sample(&self, ray: &Ray, rng: &mut SampleRng, sample_index: u32) -> Sample {
        match self.kind {
            IntegratorKind::Direct => direct::trace(&self.prep, ray, rng),
            IntegratorKind::Path => {
                let rr = if sample_index == 0 { 1.0 } else { RR_THRESHOLD };
                self.path(rr).trace(ray, rng)
            }
        }
    }

    /// One estimate of the illuminance (lx) at a sensor at `p` facing unit `n`, and the rays
    /// it took. Direct mode counts direct light only; path mode all light.
    pub fn illuminance(&self, p: Vec3, n: Vec3, rng: &mut SampleRng) -> (f32, u32) {
        let mut rays = 0;
        let tracer = match self.kind {
            IntegratorKind::Direct => PathTracer {
                prep: &self.prep,
                max_bounces: 1,
                rr_threshold: RR_THRESHOLD,
            },
            IntegratorKind::Path => self.path(RR_THRESHOLD),
        };
        let e = tracer.irradiance(p, n, rng, &mut rays);
        (crate::light::luminance(e), rays)
    }
}
