//! Light from every direction at infinity: a uniform sky of one luminance, or a
//! latitude-longitude map ([`EnvironmentMap`]). It is sampled by its luminance (a 2-D
//! piecewise-constant density weighted by sin θ), seen by rays that leave the scene, and drawn
//! as the background unless the backdrop is kept.
//!
//! Directions: the map's top row is the zenith (+Y, the scene's up); its centre column looks
//! towards −Z, and columns to the right turn towards +X in right-handed scenes (towards −X in
//! left-handed ones, so that a `.shp` scene, drawn mirrored, shows the map unmirrored).
//! `rotation_deg` turns the map about +Y.
//!
//! Units: a texel's Rec. 709 luminance times `scale` is its luminance in cd/m² (Radiance maps
//! in W/(sr m²) take `scale = 179`).

mod distribution;
mod map;
mod sun_disc;

pub use map::EnvironmentMap;
pub use sun_disc::{DistantSun, SunDisc};

use super::{Emission, Incident, LightBounds, LightSource, Receiver, luminance};
use crate::sampling::{frame_from_normal, uniform_sphere};
use glam::Vec3;
use std::f32::consts::PI;
use std::sync::Arc;

/// The user's environment: what it emits and how it is turned and scaled.
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    pub source: EnvironmentSource,
    /// cd/m² per unit of the map's luminance (a uniform sky's luminance is not scaled).
    pub scale: f32,
    /// Turn about the scene's up axis, degrees.
    pub rotation_deg: f32,
    /// Camera rays that leave the scene see it (false: the viewer's backdrop stays).
    pub background: bool,
}

/// What an environment emits.
#[derive(Clone, Debug)]
pub enum EnvironmentSource {
    /// The same luminance (cd/m²) from every direction, tinted by `color`.
    Uniform {
        luminance_cd_m2: f32,
        color: [f32; 3],
    },
    Map(Arc<EnvironmentMap>),
}

/// A shared map equals itself without a look at its texels: setups are compared every frame
/// (undo, render restarts), and a 4k map holds 8 million of them.
impl PartialEq for EnvironmentSource {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (
                EnvironmentSource::Uniform {
                    luminance_cd_m2: l1,
                    color: c1,
                },
                EnvironmentSource::Uniform {
                    luminance_cd_m2: l2,
                    color: c2,
                },
            ) => l1 == l2 && c1 == c2,
            (EnvironmentSource::Map(a), EnvironmentSource::Map(b)) => Arc::ptr_eq(a, b) || a == b,
            _ => false,
        }
    }
}

impl Environment {
    /// Whether every number is finite and in range.
    pub fn is_valid(&self) -> bool {
        let source_ok = match &self.source {
            EnvironmentSource::Uniform {
                luminance_cd_m2,
                color,
            } => {
                luminance_cd_m2.is_finite()
                    && *luminance_cd_m2 >= 0.0
                    && color.iter().all(|c| c.is_finite() && *c >= 0.0)
            }
            EnvironmentSource::Map(_) => true,
        };
        source_ok && self.scale.is_finite() && self.scale >= 0.0 && self.rotation_deg.is_finite()
    }
}

/// The unit scene direction of an unturned map's point `uv` ∈ [0, 1)² in a scene of
/// `handedness_sign` (see the module's note on directions).
pub fn map_direction(uv: [f32; 2], handedness_sign: f32) -> Vec3 {
    let phi = (uv[0] - 0.5) * 2.0 * PI;
    let theta = uv[1] * PI;
    let (sin_t, cos_t) = theta.sin_cos();
    Vec3::new(
        handedness_sign * sin_t * phi.sin(),
        cos_t,
        -sin_t * phi.cos(),
    )
}

/// An environment as a render uses it: around the scene's bounding sphere (centre, radius in
/// scene units), for a scene of `handedness_sign` and `metres_per_unit_sq`.
#[derive(Clone, Debug)]
pub struct EnvironmentLight {
    source: Source,
    /// sin and cos of the rotation about +Y.
    turn: (f32, f32),
    handedness_sign: f32,
    centre: Vec3,
    radius: f32,
    metres_per_unit_sq: f32,
    pub background: bool,
    /// The sun's disc (daylight), and the chance that a sampled direction is drawn from it.
    sun: Option<(SunDisc, f32)>,
}

#[derive(Clone, Debug)]
enum Source {
    /// Luminance per channel.
    Uniform(Vec3),
    Map {
        map: Arc<EnvironmentMap>,
        scale: f32,
    },
}

impl EnvironmentLight {
    pub fn new(
        env: &Environment,
        handedness_sign: f32,
        centre: Vec3,
        radius: f32,
        metres_per_unit_sq: f32,
    ) -> Self {
        let source = match &env.source {
            EnvironmentSource::Uniform {
                luminance_cd_m2,
                color,
            } => Source::Uniform(super::unit_luminance_tint(*color) * luminance_cd_m2.max(0.0)),
            EnvironmentSource::Map(map) => Source::Map {
                map: Arc::clone(map),
                scale: env.scale.max(0.0),
            },
        };
        let angle = env.rotation_deg.to_radians();
        Self {
            source,
            turn: angle.sin_cos(),
            handedness_sign,
            centre,
            radius: radius.max(1e-6),
            metres_per_unit_sq,
            background: env.background,
            sun: None,
        }
    }

    /// This environment with the sun's disc added. Directions are drawn from the disc with a
    /// chance in proportion to its share of ∫ L dω, kept within 5-95 % (all of them when the
    /// rest is black).
    pub fn with_sun(mut self, sun: SunDisc) -> Self {
        let rest = self.integral();
        let pick = if rest > 0.0 {
            (sun.integral() / (sun.integral() + rest)).clamp(0.05, 0.95) as f32
        } else {
            1.0
        };
        self.sun = Some((sun, pick));
        self
    }

    /// A black environment that only holds the sun (daylight without a sky). It is not the
    /// background: camera rays that leave the scene keep the backdrop.
    pub fn sun_only(sun: SunDisc, centre: Vec3, radius: f32, metres_per_unit_sq: f32) -> Self {
        let black = Environment {
            source: EnvironmentSource::Uniform {
                luminance_cd_m2: 0.0,
                color: [1.0; 3],
            },
            scale: 1.0,
            rotation_deg: 0.0,
            background: false,
        };
        Self::new(&black, 1.0, centre, radius, metres_per_unit_sq).with_sun(sun)
    }

    /// The sun's disc, when there is one.
    pub fn sun(&self) -> Option<&SunDisc> {
        self.sun.as_ref().map(|(s, _)| s)
    }

    /// The map's point [0, 1)² for unit direction `w` (towards the sky), and sin θ there.
    fn uv_of(&self, w: Vec3) -> ([f32; 2], f32) {
        let (s, c) = self.turn;
        // Undo the turn about +Y.
        let x = c * w.x - s * w.z;
        let z = s * w.x + c * w.z;
        let phi = (self.handedness_sign * x).atan2(-z);
        let cos_theta = w.y.clamp(-1.0, 1.0);
        let u = (0.5 + phi / (2.0 * PI)).clamp(0.0, 1.0 - f32::EPSILON);
        let v = (cos_theta.acos() / PI).clamp(0.0, 1.0 - f32::EPSILON);
        ([u, v], (1.0 - cos_theta * cos_theta).max(0.0).sqrt())
    }

    /// The unit direction of the map's point `uv`, and sin θ there.
    fn dir_of(&self, uv: [f32; 2]) -> (Vec3, f32) {
        let d = map_direction(uv, self.handedness_sign);
        let (s, c) = self.turn;
        let sin_t = (uv[1] * PI).sin();
        (Vec3::new(c * d.x + s * d.z, d.y, -s * d.x + c * d.z), sin_t)
    }

    /// Luminance per channel arriving from unit direction `w` (pointing at the sky).
    pub fn radiance(&self, w: Vec3) -> Vec3 {
        let rest = match &self.source {
            Source::Uniform(l) => *l,
            Source::Map { map, scale } => map.texel(self.uv_of(w).0) * *scale,
        };
        match &self.sun {
            Some((sun, _)) => rest + Vec3::splat(sun.radiance(w)),
            None => rest,
        }
    }

    /// Density (1/sr) with which [`EnvironmentLight::sample_dir`] gives `w`.
    pub fn dir_pdf(&self, w: Vec3) -> f32 {
        match &self.sun {
            Some((sun, pick)) => pick * sun.pdf(w) + (1.0 - pick) * self.rest_pdf(w),
            None => self.rest_pdf(w),
        }
    }

    /// A direction towards the sky from `u`, and its density (1/sr).
    pub fn sample_dir(&self, u: [f32; 2]) -> Option<(Vec3, f32)> {
        let Some((sun, pick)) = &self.sun else {
            return self.sample_rest(u);
        };
        let w = if u[0] < *pick {
            sun.sample([u[0] / pick, u[1]])
        } else {
            self.sample_rest([((u[0] - pick) / (1.0 - pick)).min(1.0 - f32::EPSILON), u[1]])?
                .0
        };
        let pdf = self.dir_pdf(w);
        (pdf.is_finite() && pdf > 0.0).then_some((w, pdf))
    }

    /// [`EnvironmentLight::dir_pdf`] without the sun.
    fn rest_pdf(&self, w: Vec3) -> f32 {
        match &self.source {
            Source::Uniform(_) => 1.0 / (4.0 * PI),
            Source::Map { map, .. } => {
                let (uv, sin_t) = self.uv_of(w);
                if sin_t <= 0.0 {
                    return 0.0;
                }
                map.distribution.density(uv) / (2.0 * PI * PI * sin_t)
            }
        }
    }

    /// [`EnvironmentLight::sample_dir`] without the sun.
    fn sample_rest(&self, u: [f32; 2]) -> Option<(Vec3, f32)> {
        match &self.source {
            Source::Uniform(l) => {
                (l.max_element() > 0.0).then(|| (uniform_sphere(u[0], u[1]), 1.0 / (4.0 * PI)))
            }
            Source::Map { map, .. } => {
                let (uv, density) = map.distribution.sample(u)?;
                let (w, sin_t) = self.dir_of(uv);
                if sin_t <= 0.0 || density <= 0.0 {
                    return None;
                }
                // (A faint texel beside one 10⁴⁴ times brighter: the density underflows.)
                let pdf = density / (2.0 * PI * PI * sin_t);
                (pdf.is_finite() && pdf > 0.0).then_some((w, pdf))
            }
        }
    }

    /// ∫ Y dω over the sphere (cd/m² sr).
    fn integral(&self) -> f64 {
        let rest = match &self.source {
            Source::Uniform(l) => f64::from(luminance(*l)) * 4.0 * std::f64::consts::PI,
            Source::Map { map, scale } => map.integral * f64::from(*scale),
        };
        rest + self.sun.as_ref().map_or(0.0, |(s, _)| s.integral())
    }
}

impl LightSource for EnvironmentLight {
    /// The flux through a disc the size of the scene's bounding sphere (lm).
    fn power_lm(&self) -> f64 {
        let area_m2 =
            std::f64::consts::PI * f64::from(self.radius * self.radius * self.metres_per_unit_sq);
        area_m2 * self.integral()
    }

    /// Not in the light tree (it has no position): the sampler picks it on its own.
    fn bounds(&self) -> LightBounds {
        LightBounds::point(self.centre, 0.0)
    }

    fn is_delta(&self) -> bool {
        false
    }

    fn sample_incident(&self, at: Receiver, u: [f32; 2]) -> Option<Incident> {
        let (w, pdf) = self.sample_dir(u)?;
        let tint = self.radiance(w);
        if tint.max_element() <= 0.0 {
            return None;
        }
        // Beyond everything in the scene.
        let reach = 2.0 * (self.radius + (at.origin - self.centre).length());
        Some(Incident {
            wi: w,
            target: at.origin + w * reach,
            tint,
            level: 1.0,
            pdf,
            delta: false,
            n: Vec3::ZERO,
        })
    }

    fn incident_pdf(&self, _origin: Vec3, wi: Vec3, _distance: f32) -> f32 {
        self.dir_pdf(wi)
    }

    fn emitted(&self, dir: Vec3) -> Vec3 {
        self.radiance(-dir)
    }

    /// A direction by the map, then a point on the disc across the bounding sphere facing it.
    fn sample_emission(&self, u_point: [f32; 2], u_dir: [f32; 2]) -> Option<Emission> {
        let (w, pdf_dir) = self.sample_dir(u_dir)?;
        let (b1, b2) = frame_from_normal(w);
        let r = u_point[0].sqrt() * self.radius;
        let phi = 2.0 * PI * u_point[1];
        let p = self.centre + w * self.radius + (b1 * phi.cos() + b2 * phi.sin()) * r;
        Some(Emission {
            p,
            n: Vec3::ZERO,
            dir: -w,
            pdf_point: 1.0 / (PI * self.radius * self.radius),
            pdf_dir,
        })
    }

    fn emission_dir_pdf(&self, dir: Vec3) -> f32 {
        self.dir_pdf(-dir)
    }

    fn emission_point_pdf(&self) -> f32 {
        1.0 / (PI * self.radius * self.radius)
    }

    fn normal(&self) -> Vec3 {
        Vec3::ZERO
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use std::path::Path;

    fn map_light(
        texels: Vec<Vec3>,
        width: usize,
        sign: f32,
        rotation_deg: f32,
    ) -> EnvironmentLight {
        let (map, _) =
            EnvironmentMap::from_texels(Path::new("t.hdr"), width, width / 2, texels).unwrap();
        let env = Environment {
            source: EnvironmentSource::Map(Arc::new(map)),
            scale: 1.0,
            rotation_deg,
            background: true,
        };
        EnvironmentLight::new(&env, sign, Vec3::ZERO, 1.0, 1.0)
    }

    #[test]
    fn directions_and_map_points_round_trip() {
        for sign in [1.0, -1.0] {
            let light = map_light(vec![Vec3::ONE; 32], 8, sign, 30.0);
            for k in 0..200 {
                let uv = [
                    (k as f32 * 0.618_034).fract(),
                    0.02 + 0.96 * (k as f32 / 200.0),
                ];
                let (w, _) = light.dir_of(uv);
                let (back, _) = light.uv_of(w);
                let du = (back[0] - uv[0]).abs();
                // (u = 0 and u = 1 are the same meridian.)
                assert!(
                    du.min(1.0 - du) < 1e-4 && (back[1] - uv[1]).abs() < 1e-4,
                    "{uv:?} -> {back:?}"
                );
            }
        }
        // The centre column looks towards −Z, the top row is +Y.
        let light = map_light(vec![Vec3::ONE; 32], 8, 1.0, 0.0);
        let (w, _) = light.dir_of([0.5, 0.5]);
        assert!((w - Vec3::NEG_Z).length() < 1e-5, "{w}");
        assert!(light.uv_of(Vec3::Y).0[1] < 1e-5);
        // Right-handed: right of centre turns towards +X; left-handed: towards −X.
        assert!(light.dir_of([0.75, 0.5]).0.x > 0.99);
        let mirrored = map_light(vec![Vec3::ONE; 32], 8, -1.0, 0.0);
        assert!(mirrored.dir_of([0.75, 0.5]).0.x < -0.99);
    }

    /// Densities integrate to 1 over the sphere, and match the sampler.
    #[test]
    fn densities_are_normalised_and_match_samples() {
        let width = 16;
        let texels: Vec<Vec3> = (0..width * width / 2)
            .map(|i| Vec3::splat(((i * 37) % 11) as f32))
            .collect();
        let light = map_light(texels, width, 1.0, 40.0);
        let n = 400_000;
        let mut integral = 0.0f64;
        for i in 0..n {
            let w = uniform_sphere((i as f32 + 0.5) / n as f32, (i as f32 * 0.618_034).fract());
            integral += f64::from(light.dir_pdf(w)) * 4.0 * std::f64::consts::PI / n as f64;
        }
        assert!((integral - 1.0).abs() < 0.01, "{integral}");
        for k in 0..500 {
            let u = [
                (k as f32 * 0.754_877).fract(),
                (k as f32 * 0.569_84).fract(),
            ];
            if let Some((w, pdf)) = light.sample_dir(u) {
                assert!(
                    (pdf - light.dir_pdf(w)).abs() <= 1e-3 * pdf,
                    "{pdf} vs {}",
                    light.dir_pdf(w)
                );
                assert!(light.radiance(w).max_element() > 0.0);
            }
        }
    }

    #[test]
    fn bad_maps_are_refused_or_cleaned() {
        let err = EnvironmentMap::from_texels(Path::new("sky.hdr"), 6, 2, vec![Vec3::ONE; 12]);
        assert!(err.unwrap_err().contains("sky.hdr"));
        let (map, bad) = EnvironmentMap::from_texels(
            Path::new("sky.hdr"),
            4,
            2,
            vec![
                Vec3::NAN,
                Vec3::splat(-1.0),
                Vec3::ONE,
                Vec3::ONE,
                Vec3::ONE,
                Vec3::ONE,
                Vec3::ONE,
                Vec3::ONE,
            ],
        )
        .unwrap();
        assert_eq!(bad, 2);
        assert_eq!(map.texels[0], Vec3::ZERO);
    }
}
