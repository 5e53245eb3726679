//! Integrators answer "what does this camera sample see": luminance per channel along a ray and
//! the illuminance of the first surface, plus the irradiance at a sensor point. They know no
//! tiles, passes or threads (see [`crate::render`]).
//!
//! - [`IntegratorKind::Direct`]: the coursework's model (direct light, mirrors to a depth).
//! - [`IntegratorKind::Path`]: global illumination by unbiased path tracing.
//! - [`IntegratorKind::Bidirectional`]: global illumination by bidirectional path tracing
//!   (light subpaths too, splatted to the film), for lamps close to surfaces and caustics.
//! - [`IntegratorKind::Light`]: global illumination by light tracing: light subpaths joined to
//!   the camera (splats) and to sensors, for diffuse rooms lit by lamps close to surfaces.

mod bdpt;
mod direct;
mod path;

pub use bdpt::{
    BDPT_RR_THRESHOLD, Bidirectional, Eye, LightPicker, MAX_SUBPATH, Splat, Strategies,
};

pub use direct::{DirectBatch, trace as trace_direct, trace_batch as trace_direct_batch};
pub use path::{MAX_VERTICES, PathTracer, RR_THRESHOLD};

use crate::geometry::Ray;
use crate::sampling::SampleRng;
use crate::scene::CameraBasis;
use crate::shading::Prepared;
use glam::Vec3;

/// What one camera sample sees.
// Laid out in order, so the film loads luminance and illuminance as one vector.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct Sample {
    /// Linear luminance per RGB channel, cd/m².
    pub rgb: Vec3,
    /// Illuminance (lx) on the first surface hit (0 on a miss): direct light only in direct
    /// mode, all light in path mode.
    pub illuminance_lx: f32,
    /// Rays traced for this sample.
    pub rays: u32,
    /// The camera ray hit no drawn surface (0 cd/m² here, as in every export). The viewer draws
    /// its backdrop in such pixels, so the background is told apart from unlit surfaces.
    pub missed: bool,
}

/// Which light transport to compute.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum IntegratorKind {
    /// Direct light and mirrors (the coursework's model).
    #[default]
    Direct,
    /// Global illumination (path tracing).
    Path,
    /// Global illumination (bidirectional path tracing).
    Bidirectional,
    /// Global illumination (light tracing).
    Light,
}

impl IntegratorKind {
    /// The global-illumination integrator the viewer opens in and `--gi` names by default.
    pub const DEFAULT_GI: IntegratorKind = IntegratorKind::Bidirectional;

    pub const ALL: [IntegratorKind; 4] = [
        IntegratorKind::Direct,
        IntegratorKind::Path,
        IntegratorKind::Bidirectional,
        IntegratorKind::Light,
    ];

    /// Whether light subpaths are traced and splatted to the film.
    pub fn splats(self) -> bool {
        matches!(self, IntegratorKind::Bidirectional | IntegratorKind::Light)
    }

    /// The command line's name.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorKind::Direct => "direct",
            IntegratorKind::Path => "path",
            IntegratorKind::Bidirectional => "bdpt",
            IntegratorKind::Light => "light",
        }
    }

    /// What the viewer shows.
    pub fn label(self) -> &'static str {
        match self {
            IntegratorKind::Direct => "Direct (coursework)",
            IntegratorKind::Path => "Global illumination (path)",
            IntegratorKind::Bidirectional => "Global illumination (bidirectional)",
            IntegratorKind::Light => "Global illumination (light tracing)",
        }
    }

    pub fn from_name(s: &str) -> Option<Self> {
        match s {
            "direct" => Some(IntegratorKind::Direct),
            "path" => Some(IntegratorKind::Path),
            "bdpt" | "bidirectional" => Some(IntegratorKind::Bidirectional),
            "light" | "ptracer" | "light-tracing" => Some(IntegratorKind::Light),
            "gi" => Some(IntegratorKind::DEFAULT_GI),
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
    /// Bidirectional mode: lights by flux.
    lights: LightPicker,
    /// Bidirectional mode: which strategies combine.
    pub strategies: Strategies,
    /// Bidirectional mode: whether camera samples also measure the first surface's illuminance.
    pub pixel_illuminance: bool,
}

impl<'a> Integrator<'a> {
    pub fn new(kind: IntegratorKind, prep: Prepared<'a>, max_bounces: Option<u32>) -> Self {
        let lights = if kind.splats() {
            LightPicker::new(&prep)
        } else {
            LightPicker::default()
        };
        Self {
            kind,
            prep,
            max_bounces,
            lights,
            strategies: Strategies::All,
            pixel_illuminance: true,
        }
    }

    fn bidirectional(&self, eye: Eye, rr_threshold: f32) -> Bidirectional<'_, 'a> {
        Bidirectional {
            prep: &self.prep,
            lights: &self.lights,
            eye,
            max_bounces: self.max_bounces.unwrap_or(u32::MAX),
            rr_threshold,
            strategies: self.strategies,
            light_tracing: self.kind == IntegratorKind::Light,
            splats: true,
        }
    }

    /// Camera sample number `sample_index` along `ray` (unit direction) of the camera `basis`;
    /// contributions to other pixels (bidirectional mode) are pushed to `splats`.
    pub fn sample_camera(
        &self,
        basis: &CameraBasis,
        ray: &Ray,
        rng: &mut SampleRng,
        sample_index: u32,
        splats: &mut Vec<Splat>,
    ) -> Sample {
        if !self.kind.splats() {
            return self.sample(ray, rng, sample_index);
        }
        let camera = self.bidirectional(Eye::Camera(*basis), BDPT_RR_THRESHOLD);
        let first_splat = splats.len();
        let sample = self.bidirectional_sample(&camera, ray, rng, splats);
        combine_splats(splats, first_splat);
        sample
    }

    /// A preview sample along `ray` (unit direction) of the camera `basis`, for a picture with
    /// no film to splat to. Direct and path mode: their own sample. Bidirectional and light
    /// tracing: bidirectional transport without the t = 1 strategies (the power heuristic
    /// renormalised over the rest), so previews show what the mode converges to (a lamp's hot
    /// spot on the ceiling, the light its shades throw), not a path tracer's guess.
    pub fn preview_camera(&self, basis: &CameraBasis, ray: &Ray, rng: &mut SampleRng) -> Sample {
        if !self.kind.splats() {
            return self.sample(ray, rng, 0);
        }
        let camera = Bidirectional {
            light_tracing: false,
            splats: false,
            ..self.bidirectional(Eye::Camera(*basis), BDPT_RR_THRESHOLD)
        };
        let mut none = Vec::new();
        let sample = self.bidirectional_sample(&camera, ray, rng, &mut none);
        debug_assert!(none.is_empty(), "a preview splatted");
        sample
    }

    /// One camera sample of `camera` (bidirectional or light tracing), with the first
    /// surface's illuminance when asked for.
    fn bidirectional_sample(
        &self,
        camera: &Bidirectional<'_, 'a>,
        ray: &Ray,
        rng: &mut SampleRng,
        splats: &mut Vec<Splat>,
    ) -> Sample {
        let mut rays = 0;
        let (estimate, first, illuminance_lx) = bdpt::with_subpaths(|paths| {
            camera.light_subpath(&mut bdpt::light_stream(rng), &mut rays, paths);
            let (estimate, first) = camera.camera_sample(ray, rng, paths, splats);
            let mut illuminance_lx = 0.0;
            if let Some((p, n)) = first.filter(|_| self.pixel_illuminance) {
                // Bidirectional in both modes: a pixel's surface point often lies close to
                // other surfaces (corners, glowing walls), where joining light vertices to it
                // alone is heavy-tailed. It reuses the sample's light subpath.
                let sensor = Bidirectional {
                    light_tracing: false,
                    ..self.bidirectional(Eye::Sensor, BDPT_RR_THRESHOLD)
                };
                let e = sensor.sensor_sample(p, n, &mut bdpt::sensor_stream(rng), paths);
                rays += e.rays;
                illuminance_lx = crate::light::luminance(e.value);
            }
            (estimate, first, illuminance_lx)
        });
        rays += estimate.rays;
        Sample {
            rgb: estimate.value,
            illuminance_lx,
            rays,
            missed: first.is_none(),
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
    /// in path mode). Direct and path mode; the splatting modes path-trace here (their own
    /// transport needs the camera: [`Integrator::sample_camera`], [`Integrator::preview_camera`]).
    pub fn sample(&self, ray: &Ray, rng: &mut SampleRng, sample_index: u32) -> Sample {
        match self.kind {
            IntegratorKind::Direct => direct::trace(&self.prep, ray, rng),
            IntegratorKind::Path | IntegratorKind::Bidirectional | IntegratorKind::Light => {
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
            IntegratorKind::Bidirectional | IntegratorKind::Light => {
                let sensor = self.bidirectional(Eye::Sensor, BDPT_RR_THRESHOLD);
                let e = bdpt::with_subpaths(|paths| {
                    sensor.light_subpath(&mut bdpt::light_stream(rng), &mut rays, paths);
                    sensor.sensor_sample(p, n, rng, paths)
                });
                return (crate::light::luminance(e.value), rays + e.rays);
            }
        };
        let e = tracer.irradiance(p, n, rng, &mut rays);
        (crate::light::luminance(e), rays)
    }
}

/// Joins the splats from `first` on (one light subpath's) that land in the same pixel, so that
/// each pixel receives one value per light subpath: the film's variance of the splats squares
/// whole subpaths' contributions (see `PixelSum::luminance_std_error`).
fn combine_splats(splats: &mut Vec<Splat>, first: usize) {
    let mut end = splats.len();
    let mut i = first;
    while i < end {
        let mut j = i + 1;
        while j < end {
            if (splats[j].x, splats[j].y) == (splats[i].x, splats[i].y) {
                let rgb = splats[j].rgb;
                splats[i].rgb += rgb;
                splats.swap(j, end - 1);
                end -= 1;
            } else {
                j += 1;
            }
        }
        i += 1;
    }
    splats.truncate(end);
}
