//! The splatting integrators over the bidirectional transport: [`BidirectionalPathTracing`] and
//! [`LightTracing`], with what both do around one camera sample (the pixel's illuminance, the
//! splats joined per pixel).

use super::{BDPT_RR_THRESHOLD, Bidirectional, Eye, LightPicker, PathScatter, Splat, Strategies};
use crate::geometry::Ray;
use crate::integrator::{Integrator, IntegratorKind, IntegratorSettings, Sample, Want};
use crate::lit_scene::LitScene;
use crate::sampling::SampleRng;
use crate::scene::CameraBasis;
use crate::shading::{Bsdf, Classic};
use glam::Vec3;

/// Bidirectional path tracing: every (s, t) strategy, power-heuristic MIS.
#[derive(Debug)]
pub struct BidirectionalPathTracing<'a> {
    pub lit: LitScene<'a>,
    /// Non-delta bounces allowed (None: unlimited).
    pub max_bounces: Option<u32>,
    /// Which strategies combine.
    pub strategies: Strategies,
    /// Lights by flux.
    lights: LightPicker,
}

/// Light tracing: every light vertex joined to the eye (t = 1) at weight 1; eye subpaths go
/// past their first surface only after a delta lobe.
///
/// Named substitutions: its previews, which have no film to splat to, and its pixel
/// illuminance (a sensor at a pixel's surface point, often close to other surfaces, where
/// joining light vertices alone is heavy-tailed) use bidirectional transport.
#[derive(Debug)]
pub struct LightTracing<'a> {
    pub lit: LitScene<'a>,
    /// Non-delta bounces allowed (None: unlimited).
    pub max_bounces: Option<u32>,
    lights: LightPicker,
}

impl<'a> BidirectionalPathTracing<'a> {
    pub fn new(lit: LitScene<'a>, settings: IntegratorSettings) -> Self {
        Self {
            lights: LightPicker::new(&lit),
            lit,
            max_bounces: settings.max_bounces,
            strategies: Strategies::All,
        }
    }

    /// The transport of a camera sample with its strategies.
    fn camera_transport(&self, basis: &CameraBasis) -> Bidirectional<'_, 'a> {
        Bidirectional {
            strategies: self.strategies,
            ..transport(
                &self.lit,
                &self.lights,
                self.max_bounces,
                Eye::Camera(*basis),
            )
        }
    }
}

impl<'a> LightTracing<'a> {
    pub fn new(lit: LitScene<'a>, settings: IntegratorSettings) -> Self {
        Self {
            lights: LightPicker::with_environment(&lit),
            lit,
            max_bounces: settings.max_bounces,
        }
    }

    /// The transport of a camera sample: light tracing.
    fn camera_transport(&self, basis: &CameraBasis) -> Bidirectional<'_, 'a> {
        Bidirectional {
            light_tracing: true,
            ..transport(
                &self.lit,
                &self.lights,
                self.max_bounces,
                Eye::Camera(*basis),
            )
        }
    }
}

/// The transport for `eye` over `lit` with `lights`.
fn transport<'p, 'a>(
    lit: &'p LitScene<'a>,
    lights: &'p LightPicker,
    max_bounces: Option<u32>,
    eye: Eye,
) -> Bidirectional<'p, 'a> {
    Bidirectional {
        lit,
        lights,
        eye,
        max_bounces: max_bounces.unwrap_or(u32::MAX),
        rr_threshold: BDPT_RR_THRESHOLD,
        strategies: Strategies::All,
        light_tracing: false,
        splats: true,
    }
}

impl Integrator for BidirectionalPathTracing<'_> {
    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Bidirectional
    }

    fn lit(&self) -> &LitScene<'_> {
        &self.lit
    }

    fn sample_camera(
        &self,
        basis: &CameraBasis,
        ray: &Ray,
        rng: &mut SampleRng,
        want: Want,
        splats: &mut Vec<Splat>,
    ) -> Sample {
        let camera = self.camera_transport(basis);
        if self.lit.has_metal_rough() {
            camera_sample::<Bsdf>(&camera, want.illuminance, ray, rng, splats)
        } else {
            camera_sample::<Classic>(&camera, want.illuminance, ray, rng, splats)
        }
    }

    fn sample_outside(
        &self,
        basis: &CameraBasis,
        rng: &mut SampleRng,
        splats: &mut Vec<Splat>,
    ) -> Sample {
        let camera = self.camera_transport(basis);
        if self.lit.has_metal_rough() {
            outside_sample::<Bsdf>(&camera, rng, splats)
        } else {
            outside_sample::<Classic>(&camera, rng, splats)
        }
    }

    /// Bidirectional transport without the t = 1 strategies (the power heuristic renormalised
    /// over the rest), so previews show what the mode converges to (a lamp's hot spot on the
    /// ceiling, the light its shades throw), not a path tracer's guess.
    fn preview_camera(
        &self,
        basis: &CameraBasis,
        ray: &Ray,
        rng: &mut SampleRng,
        illuminance: bool,
    ) -> Sample {
        let camera = transport(
            &self.lit,
            &self.lights,
            self.max_bounces,
            Eye::Camera(*basis),
        );
        preview(&camera, illuminance, ray, rng)
    }

    fn illuminance(&self, p: Vec3, n: Vec3, rng: &mut SampleRng) -> (f32, u32) {
        let sensor = Bidirectional {
            strategies: self.strategies,
            ..transport(&self.lit, &self.lights, self.max_bounces, Eye::Sensor)
        };
        if self.lit.has_metal_rough() {
            sensor_illuminance::<Bsdf>(&sensor, p, n, rng)
        } else {
            sensor_illuminance::<Classic>(&sensor, p, n, rng)
        }
    }
}

impl Integrator for LightTracing<'_> {
    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Light
    }

    fn lit(&self) -> &LitScene<'_> {
        &self.lit
    }

    fn sample_camera(
        &self,
        basis: &CameraBasis,
        ray: &Ray,
        rng: &mut SampleRng,
        want: Want,
        splats: &mut Vec<Splat>,
    ) -> Sample {
        let camera = self.camera_transport(basis);
        if self.lit.has_metal_rough() {
            camera_sample::<Bsdf>(&camera, want.illuminance, ray, rng, splats)
        } else {
            camera_sample::<Classic>(&camera, want.illuminance, ray, rng, splats)
        }
    }

    fn sample_outside(
        &self,
        basis: &CameraBasis,
        rng: &mut SampleRng,
        splats: &mut Vec<Splat>,
    ) -> Sample {
        let camera = self.camera_transport(basis);
        if self.lit.has_metal_rough() {
            outside_sample::<Bsdf>(&camera, rng, splats)
        } else {
            outside_sample::<Classic>(&camera, rng, splats)
        }
    }

    /// Substitution: bidirectional transport without splats, as for
    /// [`BidirectionalPathTracing`] (light tracing proper can only splat).
    fn preview_camera(
        &self,
        basis: &CameraBasis,
        ray: &Ray,
        rng: &mut SampleRng,
        illuminance: bool,
    ) -> Sample {
        let camera = transport(
            &self.lit,
            &self.lights,
            self.max_bounces,
            Eye::Camera(*basis),
        );
        preview(&camera, illuminance, ray, rng)
    }

    fn illuminance(&self, p: Vec3, n: Vec3, rng: &mut SampleRng) -> (f32, u32) {
        let sensor = Bidirectional {
            light_tracing: true,
            ..transport(&self.lit, &self.lights, self.max_bounces, Eye::Sensor)
        };
        if self.lit.has_metal_rough() {
            sensor_illuminance::<Bsdf>(&sensor, p, n, rng)
        } else {
            sensor_illuminance::<Classic>(&sensor, p, n, rng)
        }
    }
}

/// A preview sample: `camera`'s transport without the t = 1 strategies.
fn preview(
    camera: &Bidirectional<'_, '_>,
    illuminance: bool,
    ray: &Ray,
    rng: &mut SampleRng,
) -> Sample {
    let camera = Bidirectional {
        splats: false,
        ..*camera
    };
    let mut none = Vec::new();
    // The full Bsdf only where a material needs it (`shading::Scatter`).
    let sample = if camera.lit.has_metal_rough() {
        camera_sample::<Bsdf>(&camera, illuminance, ray, rng, &mut none)
    } else {
        camera_sample::<Classic>(&camera, illuminance, ray, rng, &mut none)
    };
    debug_assert!(none.is_empty(), "a preview splatted");
    sample
}

/// One camera sample of `camera`, with the first surface's illuminance when asked for
/// (bidirectional in both modes, reusing the sample's light subpath); its splats are joined
/// per pixel.
fn camera_sample<S: PathScatter>(
    camera: &Bidirectional<'_, '_>,
    illuminance: bool,
    ray: &Ray,
    rng: &mut SampleRng,
    splats: &mut Vec<Splat>,
) -> Sample {
    let first_splat = splats.len();
    let mut rays = 0;
    let (estimate, first, illuminance_lx) = super::with_subpaths::<S, _>(|paths| {
        camera.light_subpath(&mut super::light_stream(rng), &mut rays, paths);
        let (estimate, first) = camera.camera_sample(ray, rng, paths, splats);
        let mut illuminance_lx = 0.0;
        if let Some((p, n)) = first.filter(|_| illuminance) {
            let sensor = Bidirectional {
                light_tracing: false,
                eye: Eye::Sensor,
                ..*camera
            };
            let e = sensor.sensor_sample(p, n, &mut super::sensor_stream(rng), paths);
            rays += e.rays;
            illuminance_lx = crate::light::luminance(e.value);
        }
        (estimate, first, illuminance_lx)
    });
    rays += estimate.rays;
    combine_splats(splats, first_splat);
    Sample {
        rgb: estimate.value,
        illuminance_lx,
        rays,
        // The environment, when shown, is the background.
        missed: first.is_none()
            && !camera
                .lit
                .environment
                .as_ref()
                .is_some_and(|e| e.background),
    }
}

/// A camera sample outside the image: its light subpath, joined to the eye (t = 1) only.
fn outside_sample<S: PathScatter>(
    camera: &Bidirectional<'_, '_>,
    rng: &mut SampleRng,
    splats: &mut Vec<Splat>,
) -> Sample {
    let Eye::Camera(basis) = camera.eye else {
        return Sample::default();
    };
    let first_splat = splats.len();
    let mut rays = 0;
    super::with_subpaths::<S, _>(|paths| {
        camera.light_subpath(&mut super::light_stream(rng), &mut rays, paths);
        rays += camera.eye_splats(basis.origin, paths, splats);
    });
    combine_splats(splats, first_splat);
    // Black, not the viewer's backdrop: `missed` stays false.
    Sample {
        rays,
        ..Sample::default()
    }
}

/// One sensor estimate of `sensor` at `p` facing `n`: (lx, rays).
fn sensor_illuminance<S: PathScatter>(
    sensor: &Bidirectional<'_, '_>,
    p: Vec3,
    n: Vec3,
    rng: &mut SampleRng,
) -> (f32, u32) {
    let mut rays = 0;
    let e = super::with_subpaths::<S, _>(|paths| {
        sensor.light_subpath(&mut super::light_stream(rng), &mut rays, paths);
        sensor.sensor_sample(p, n, rng, paths)
    });
    (crate::light::luminance(e.value), rays + e.rays)
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
