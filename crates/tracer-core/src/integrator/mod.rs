//! Integrators answer "what does this camera sample see": luminance per channel along a ray and
//! the illuminance of the first surface, plus the irradiance at a sensor point. They know no
//! tiles, passes or threads (see [`crate::render`]). Each is a type of its own with its own
//! settings, behind one interface, [`Integrator`] (pbrt-v4's `RayIntegrator` is the model);
//! [`build`] makes the one an [`IntegratorKind`] names.
//!
//! - [`DirectLighting`]: the coursework's model (direct light, mirrors to a depth).
//! - [`PathTracing`]: global illumination by unbiased path tracing.
//! - [`BidirectionalPathTracing`]: global illumination by bidirectional path tracing (light
//!   subpaths too, splatted to the film), for lamps close to surfaces and caustics.
//! - [`LightTracing`]: global illumination by light tracing: light subpaths joined to the camera
//!   (splats) and to sensors, for diffuse rooms lit by lamps close to surfaces.
//!
//! Where an integrator answers a question with another's transport, its docs name it: direct
//! mode's sensors, and light tracing's previews and pixel illuminance.

mod bdpt;
mod direct;
mod kind;
mod path;

pub use bdpt::{
    BDPT_RR_THRESHOLD, Bidirectional, BidirectionalPathTracing, Eye, LightPicker, LightTracing,
    MAX_SUBPATH, Splat, Strategies,
};
pub use direct::{
    DirectBatch, DirectLighting, trace as trace_direct, trace_batch as trace_direct_batch,
};
pub use kind::IntegratorKind;
pub use path::{MAX_VERTICES, PathTracer, PathTracing, RR_THRESHOLD};

use crate::geometry::Ray;
use crate::lit_scene::LitScene;
use crate::sampling::SampleRng;
use crate::scene::CameraBasis;
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

/// What every integrator answers, for the film, the previews and the sensors.
pub trait Integrator: Send + Sync + std::fmt::Debug {
    fn kind(&self) -> IntegratorKind;

    /// The scene as this render sees it.
    fn lit(&self) -> &LitScene<'_>;

    /// Camera sample `want.index` along `ray` (unit direction) of the camera `basis`;
    /// contributions to other pixels (the splatting integrators) are pushed to `splats`, one
    /// per pixel and light subpath. The first surface's illuminance is estimated when
    /// `want.illuminance` (else it may read 0); the luminance does not depend on it.
    fn sample_camera(
        &self,
        basis: &CameraBasis,
        ray: &Ray,
        rng: &mut SampleRng,
        want: Want,
        splats: &mut Vec<Splat>,
    ) -> Sample;

    /// Camera sample `want.index` of a film position outside the image (a fisheye's corners):
    /// no camera ray, so the sample itself is black. The splatting integrators still trace its
    /// light subpath and splat it into the image, since the film divides splats by the
    /// samples of every pixel.
    fn sample_outside(
        &self,
        _basis: &CameraBasis,
        _rng: &mut SampleRng,
        _splats: &mut Vec<Splat>,
    ) -> Sample {
        Sample::default()
    }

    /// A preview sample along `ray` (unit direction) of the camera `basis`, for a picture with
    /// no film to splat to: what the mode converges to, as near as a sample without splats
    /// can show it. The illuminance as for [`Integrator::sample_camera`].
    fn preview_camera(
        &self,
        basis: &CameraBasis,
        ray: &Ray,
        rng: &mut SampleRng,
        illuminance: bool,
    ) -> Sample;

    /// One estimate of the illuminance (lx) at a sensor at `p` facing unit `n`, and the rays
    /// it took.
    fn illuminance(&self, p: Vec3, n: Vec3, rng: &mut SampleRng) -> (f32, u32);
}

/// What a camera sample is asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Want {
    /// The sample's index in its pixel.
    pub index: u32,
    /// Whether to estimate the first surface's illuminance too (path mode traces a second
    /// path for it on surfaces that are not plain Lambertian, the splatting integrators a
    /// sensor subpath; direct mode has it at no cost).
    pub illuminance: bool,
}

/// The settings the integrators take (each uses those that apply to it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IntegratorSettings {
    /// Non-delta bounces allowed in the global-illumination modes (None: unlimited).
    pub max_bounces: Option<u32>,
}

/// The integrator `kind` over `lit`.
pub fn build<'a>(
    kind: IntegratorKind,
    lit: LitScene<'a>,
    settings: IntegratorSettings,
) -> Box<dyn Integrator + 'a> {
    match kind {
        IntegratorKind::Direct => Box::new(DirectLighting { lit }),
        IntegratorKind::Path => Box::new(PathTracing {
            lit,
            max_bounces: settings.max_bounces,
        }),
        IntegratorKind::Bidirectional => Box::new(BidirectionalPathTracing::new(lit, settings)),
        IntegratorKind::Light => Box::new(LightTracing::new(lit, settings)),
    }
}
