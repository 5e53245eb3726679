//! Bidirectional path tracing (Veach's thesis, ch. 10): a subpath from the eye (the camera, or a
//! sensor point measuring illuminance) and one from a light, every pair of their vertices
//! connected, and each strategy weighted by the power heuristic over all strategies that could
//! have produced the same path.
//!
//! - Light subpaths start at points, spots, luminaires and glowing triangles in proportion to
//!   their flux ([`emit`]), so a lamp 0.1 mm under a ceiling lights the ceiling's hot spot, and
//!   that spot lights the room, in every light subpath.
//! - t = 1: a light vertex connected to the camera lands in some pixel: a splat. A sensor is a
//!   point with cosine importance, so light vertices connect to it in the same way.
//! - Unbiased, no clamping: Russian roulette on each subpath's throughput relative to its start.
//! - Deterministic: the light subpath draws from the sample's own stream (split off by purpose),
//!   which is keyed by (pixel or sensor point, sample index).
//! - Densities follow pbrt-v3's bookkeeping (`pdf_fwd`, `pdf_rev` per vertex, delta vertices
//!   remapped to 1 in ratios), written anew here.

mod connect;
mod emit;
mod environment;
mod integrators;
mod vertex;
mod walk;

pub use emit::LightPicker;
pub use integrators::{BidirectionalPathTracing, LightTracing};

use crate::geometry::Ray;
use crate::lit_scene::LitScene;
use crate::sampling::SampleRng;
use crate::scene::{CameraBasis, Lens};
use crate::shading::{Bsdf, Classic, Scatter};
use glam::Vec3;
use std::cell::RefCell;
use vertex::Vertex;

/// A sample's subpaths, reused from sample to sample (one set per thread and scattering
/// model): no allocation per sample.
#[derive(Debug)]
pub struct Subpaths<S> {
    light: Vec<Vertex<S>>,
    eye: Vec<Vertex<S>>,
}

impl<S> Default for Subpaths<S> {
    fn default() -> Self {
        Self {
            light: Vec::new(),
            eye: Vec::new(),
        }
    }
}

/// A scattering model with subpath buffers of its own on each thread.
pub trait PathScatter: Scatter + 'static {
    fn buffers() -> &'static std::thread::LocalKey<RefCell<Subpaths<Self>>>;
}

thread_local! {
    static CLASSIC_SUBPATHS: RefCell<Subpaths<Classic>> = RefCell::default();
    static BSDF_SUBPATHS: RefCell<Subpaths<Bsdf>> = RefCell::default();
}

impl PathScatter for Classic {
    fn buffers() -> &'static std::thread::LocalKey<RefCell<Subpaths<Self>>> {
        &CLASSIC_SUBPATHS
    }
}

impl PathScatter for Bsdf {
    fn buffers() -> &'static std::thread::LocalKey<RefCell<Subpaths<Self>>> {
        &BSDF_SUBPATHS
    }
}

/// Runs `f` with this thread's subpath buffers (fresh ones if they are in use).
pub fn with_subpaths<S: PathScatter, R>(f: impl FnOnce(&mut Subpaths<S>) -> R) -> R {
    S::buffers().with(|cell| match cell.try_borrow_mut() {
        Ok(mut paths) => f(&mut paths),
        Err(_) => f(&mut Subpaths::default()),
    })
}

/// Stream purpose of the light subpath of a sample.
const LIGHT_STREAM: u64 = 0x004C_4947_4854;
/// Stream purpose of the sensor subpath measuring a pixel's illuminance.
const SENSOR_STREAM: u64 = 0x5345_4E53;
/// Stream purpose of the light samples of connections with s = 1.
const CONNECT_STREAM: u64 = 0x434F_4E4E;

/// Relative throughput below which a subpath plays Russian roulette: 1, so every bounce
/// survives with probability equal to its throughput (at most 1). Measured on the Cornell box
/// (BENCHMARK.md G1, 5 s): 0.05 gave 7.4 % relative RMSE, 0.3 gave 8.9 % at lower sample
/// counts, 1 gave 6.5 %: shorter subpaths mean fewer connections per sample, and the light
/// subpaths carry the room's indirect light in any case.
pub const BDPT_RR_THRESHOLD: f32 = 1.0;

/// Most vertices of one subpath. With roulette a path of reflectance 0.9 gets this long with
/// probability below 1e-11; the limit only ends lossless enclosures.
pub const MAX_SUBPATH: usize = 256;

/// A light-subpath contribution that lands in another pixel (t = 1 to the camera).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Splat {
    pub x: u32,
    pub y: u32,
    /// Luminance per channel to add to that pixel's sum, cd/m² (divided by its sample count
    /// like any sample).
    pub rgb: Vec3,
}

/// Which strategies combine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategies {
    /// Every (s, t).
    All,
    /// Path tracing (s ≤ 1) and light tracing (t = 1) only.
    PathAndLightTracing,
}

impl Strategies {
    fn allowed(self, s: usize, t: usize) -> bool {
        match self {
            Strategies::All => true,
            Strategies::PathAndLightTracing => s <= 1 || t == 1,
        }
    }
}

/// The first vertex of an eye subpath.
#[derive(Clone, Copy, Debug)]
pub enum Eye {
    /// A pinhole camera: importance 1 / (A cos⁴ θ) over its film of area A at unit distance.
    Camera(CameraBasis),
    /// A point measuring illuminance: importance 1 over the hemisphere of its normal.
    Sensor,
}

/// Bidirectional transport over a prepared scene, for one eye.
#[derive(Clone, Copy, Debug)]
pub struct Bidirectional<'p, 'a> {
    pub lit: &'p LitScene<'a>,
    pub lights: &'p LightPicker,
    pub eye: Eye,
    /// Non-delta bounces allowed (u32::MAX: unlimited).
    pub max_bounces: u32,
    /// Relative throughput below which roulette starts.
    pub rr_threshold: f32,
    pub strategies: Strategies,
    /// Light tracing: every light vertex is joined to the eye (t = 1) with weight 1, and the
    /// eye subpath goes on past its first surface only when a delta lobe (mirror, glass)
    /// scattered it there; such paths, which no light vertex can be joined to, take the
    /// bidirectional strategies with t ≥ 3 and their usual weights (see `connect_all`).
    pub light_tracing: bool,
    /// Whether the camera's t = 1 strategies run (their contributions land in other pixels, as
    /// splats). Without them (previews, which have no film to splat to) the power heuristic is
    /// renormalised over the other strategies, so every path is still counted once. Only paths
    /// that t = 1 alone can make go missing: a point light's caustic through glass or off a
    /// mirror, seen directly (a glowing triangle's caustic is still found, by s = 0).
    pub splats: bool,
}

/// What one camera sample of the bidirectional integrator gives.
#[derive(Clone, Copy, Debug, Default)]
pub struct EyeEstimate {
    /// Luminance per channel (camera) or irradiance per channel (sensor).
    pub value: Vec3,
    pub rays: u32,
}

impl Bidirectional<'_, '_> {
    /// For the camera: the film position the eye sees along unit direction `w`, if in the
    /// image (never for the orthographic camera, whose importance is a delta in direction).
    fn film_position(&self, w: Vec3) -> Option<(f32, f32)> {
        match self.eye {
            Eye::Camera(b) => b.film_position(w),
            Eye::Sensor => None,
        }
    }

    /// Importance of the eye vertex `eye` towards unit `w`. The camera's, times the eye's
    /// cosine ([`vertex::Vertex::cosine`]), is the density of `w` over the film
    /// ([`CameraBasis::direction_density`]): 1 / (A cos⁴ θ) for the pinhole with its cos θ;
    /// the other projections count no cosine at the eye (it may look sideways or back).
    fn eye_importance<S: Scatter>(&self, eye: &Vertex<S>, w: Vec3) -> f32 {
        match self.eye {
            Eye::Camera(b) => camera_density(&b, w, 4),
            Eye::Sensor => {
                if eye.n.dot(w) > 0.0 {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }

    /// The cosine at the eye towards unit `w` that a connection's geometry term carries:
    /// the pinhole's and the sensor's against their axis (0 behind), 1 for the other
    /// projections (their importance holds it).
    fn eye_cosine(&self, axis: Vec3, w: Vec3) -> f32 {
        match self.eye {
            Eye::Camera(b) if !matches!(b.lens, Lens::Pinhole) => 1.0,
            _ => axis.dot(w).max(0.0),
        }
    }

    /// Density per sr with which the eye sends its subpath along unit `w` (0 for the
    /// orthographic camera: a delta).
    fn eye_direction_pdf<S: Scatter>(&self, eye: &Vertex<S>, w: Vec3) -> f32 {
        match self.eye {
            Eye::Camera(b) => camera_density(&b, w, 3),
            Eye::Sensor => vertex::cosine_pdf(eye.n, w),
        }
    }

    /// Luminance along the camera ray `ray` (unit direction) by every strategy, with the light
    /// subpath in `paths` ([`Bidirectional::light_subpath`]); light-tracing contributions to
    /// other pixels go to `splats`. Also returns the first surface vertex.
    pub fn camera_sample<S: Scatter>(
        &self,
        ray: &Ray,
        rng: &mut SampleRng,
        paths: &mut Subpaths<S>,
        splats: &mut Vec<Splat>,
    ) -> (EyeEstimate, Option<(Vec3, Vec3)>) {
        let mut rays = 0;
        let eye = self.eye_vertex(ray.origin);
        let camera = &mut paths.eye;
        camera.clear();
        camera.push(eye);
        let pdf_dir = self.eye_direction_pdf(&eye, ray.dir);
        let escape = self.walk(*ray, Vec3::ONE, pdf_dir, false, rng, camera, &mut rays);
        let first = camera.get(1).map(|v| (v.p, v.shading_facing(v.wo)));
        let mut connect_rng = rng.split(CONNECT_STREAM);
        let mut value = self.connect_all(camera, &paths.light, &mut connect_rng, splats, &mut rays);
        if let Some(e) = escape {
            value += self.hit_environment(camera, &e);
        }
        (EyeEstimate { value, rays }, first)
    }

    /// The t = 1 strategies alone, for a camera sample with no camera ray (outside a
    /// fisheye's image circle): the light subpath in `paths` joined to the eye at `origin`,
    /// as splats. Returns the rays traced.
    pub fn eye_splats<S: Scatter>(
        &self,
        origin: Vec3,
        paths: &mut Subpaths<S>,
        splats: &mut Vec<Splat>,
    ) -> u32 {
        let mut rays = 0;
        let camera = &mut paths.eye;
        camera.clear();
        camera.push(self.eye_vertex(origin));
        // (t = 1 samples nothing: the stream is unused.)
        let mut no_rng = SampleRng::new(0, 0);
        let _ = self.connect_all(camera, &paths.light, &mut no_rng, splats, &mut rays);
        rays
    }

    fn eye_vertex<S: Scatter>(&self, origin: Vec3) -> Vertex<S> {
        let mut eye = Vertex::new(vertex::Kind::Eye, origin, self.forward(), Vec3::ONE, 1.0);
        eye.pdf_fwd = 1.0;
        eye
    }

    /// Irradiance per channel at `p` from the side of unit `n` (a sensor), by every strategy,
    /// with the light subpath in `paths`.
    pub fn sensor_sample<S: Scatter>(
        &self,
        p: Vec3,
        n: Vec3,
        rng: &mut SampleRng,
        paths: &mut Subpaths<S>,
    ) -> EyeEstimate {
        let mut rays = 0;
        let eye = Vertex::new(vertex::Kind::Eye, p, n, Vec3::ONE, 1.0);
        let sensor = &mut paths.eye;
        sensor.clear();
        sensor.push(eye);
        let (u, v) = rng.next_2d();
        let wi = crate::sampling::to_world(crate::sampling::cosine_hemisphere(u, v), n);
        let pdf = vertex::cosine_pdf(n, wi);
        let mut escape = None;
        if pdf > 0.0 {
            let origin = p + n * self.lit.epsilon;
            // W cos θ / pdf = π for cosine sampling.
            let beta = Vec3::splat(std::f32::consts::PI);
            escape = self.walk(
                Ray::new(origin, wi),
                beta,
                pdf,
                false,
                rng,
                sensor,
                &mut rays,
            );
        }
        let mut connect_rng = rng.split(CONNECT_STREAM);
        // A sensor adds its t = 1 strategies to its own value: nothing is pushed here.
        let mut no_splats = Vec::new();
        let mut value = self.connect_all(
            sensor,
            &paths.light,
            &mut connect_rng,
            &mut no_splats,
            &mut rays,
        );
        if let Some(e) = escape {
            value += self.hit_environment(sensor, &e);
        }
        if self.lit.environment.is_some() {
            value += self.sensor_environment(&sensor[0], &mut connect_rng, &mut rays);
        }
        EyeEstimate { value, rays }
    }

    fn forward(&self) -> Vec3 {
        match self.eye {
            Eye::Camera(b) => b.forward,
            Eye::Sensor => Vec3::ZERO,
        }
    }
}

/// The camera's density of unit direction `w` over its film (0 off the film): the pinhole's
/// 1 / (A cos^`cos_power` θ) (4: its importance, 3: its direction density), the other
/// projections' [`CameraBasis::direction_density`] either way (no cosine at their eye).
fn camera_density(b: &CameraBasis, w: Vec3, cos_power: i32) -> f32 {
    if b.film_position(w).is_none() {
        return 0.0;
    }
    match b.lens {
        Lens::Pinhole => {
            let cos = b.forward.dot(w);
            1.0 / (4.0 * b.half_width * b.half_height * cos.powi(cos_power))
        }
        _ => b.direction_density(w),
    }
}

/// Light subpaths and the sample's streams, for the integrator front end.
pub fn light_stream(rng: &SampleRng) -> SampleRng {
    rng.split(LIGHT_STREAM)
}

/// The stream of the sensor subpath that measures a camera sample's illuminance.
pub fn sensor_stream(rng: &SampleRng) -> SampleRng {
    rng.split(SENSOR_STREAM)
}
