//! Per-render constants derived once from a scene and its setup, so the per-ray code does no
//! conversions: light tints scaled to luminance 1, spot profiles, Kd / π, highlight
//! normalisation, emission, the emitter table, the unit factor and the front side.

use crate::bvh::{Hit, PACKET};
use crate::geometry::Ray;
use crate::light::LightKind;
use crate::light::{EmissiveTriangle, EmitterTable, Luminaire, LuminaireFrame, SpotProfile};
use crate::scene::{Handedness, Scene, Setup};
use glam::Vec3;
use std::sync::Arc;

/// Fewer rays than this go one by one: a packet's set-up and lanes cost more than it saves on
/// a few rays (the hits are the same either way).
const MIN_PACKET: usize = 4;

#[derive(Clone, Debug)]
pub struct PreparedLight {
    pub position: Vec3,
    pub intensity_cd: f32,
    /// Colour with Rec. 709 luminance 1.
    pub tint: Vec3,
    /// How the intensity depends on direction.
    pub profile: Profile,
}

/// The angular dependence of a light's intensity.
#[derive(Clone, Debug)]
pub enum Profile {
    Isotropic,
    Spot(SpotProfile),
    /// A measured distribution (cd, already times the multiplier) in its frame.
    Goniometric(Arc<Luminaire>, LuminaireFrame),
}

impl PreparedLight {
    /// Intensity (cd) towards unit direction `dir` (from the light).
    pub fn intensity_towards(&self, dir: Vec3) -> f32 {
        match &self.profile {
            Profile::Isotropic => self.intensity_cd,
            Profile::Spot(p) => self.intensity_cd * p.factor(dir),
            Profile::Goniometric(table, frame) => {
                let (c, gamma) = frame.angles_deg(dir);
                self.intensity_cd * table.photometry.intensity(c, gamma)
            }
        }
    }
}

#[derive(Clone, Copy, Debug)]
pub struct PreparedMaterial {
    pub kd_over_pi: Vec3,
    pub ks: Vec3,
    pub glossiness: f32,
    /// (g + 8) / (8π), the normalisation of the Blinn-Phong lobe.
    pub highlight_norm: f32,
    /// Weight of the glass interface per channel, and the refractive index behind the front.
    pub kt: Vec3,
    pub ior: f32,
    /// Emitted luminance per channel, cd/m² (zero for surfaces that are not lights).
    pub emission: Vec3,
}

/// Everything the integrator needs for one render.
#[derive(Debug)]
pub struct Prepared<'a> {
    pub scene: &'a Scene,
    pub lights: Vec<PreparedLight>,
    pub materials: Vec<PreparedMaterial>,
    /// Emissive triangles of drawn surfaces.
    pub emitters: EmitterTable,
    /// +1 when the front normal is (v1 − v0) × (v2 − v0) (right-handed scenes), −1 when it is
    /// its negation (left-handed, as `.shp` files are mirror images).
    pub front_sign: f32,
    /// (metres per scene unit)², to turn squared scene distances into m².
    pub metres_per_unit_sq: f32,
    /// Offset of secondary ray origins along the normal, scene units.
    pub epsilon: f32,
    pub max_depth: u32,
    /// True when some slot is hidden (then hits on hidden slots are skipped).
    any_hidden: bool,
    hidden: Vec<bool>,
}

impl<'a> Prepared<'a> {
    pub fn new(scene: &'a Scene, setup: &Setup, max_depth: u32) -> Self {
        let handedness_sign = match setup.handedness {
            Handedness::Right => 1.0,
            Handedness::Left => -1.0,
        };
        let lights = setup
            .lights
            .iter()
            .filter(|l| l.is_valid())
            .map(|l| {
                let (intensity_cd, profile) = match (l.kind, &l.luminaire) {
                    (LightKind::Luminaire, Some(lum)) => (
                        l.multiplier,
                        Profile::Goniometric(Arc::clone(lum), l.luminaire_frame(handedness_sign)),
                    ),
                    (LightKind::Spot, _) => (
                        l.intensity_cd,
                        l.spot_profile().map_or(Profile::Isotropic, Profile::Spot),
                    ),
                    _ => (l.intensity_cd, Profile::Isotropic),
                };
                PreparedLight {
                    position: l.position(),
                    intensity_cd: intensity_cd.max(0.0),
                    tint: l.tint(),
                    profile,
                }
            })
            .collect();
        let clamped: Vec<_> = (0..scene.slots.len())
            .map(|slot| {
                setup
                    .materials
                    .get(slot)
                    .copied()
                    .unwrap_or_default()
                    .clamped()
                    .0
            })
            .collect();
        let materials: Vec<PreparedMaterial> = clamped
            .iter()
            .map(|m| PreparedMaterial {
                kd_over_pi: m.kd() / std::f32::consts::PI,
                ks: m.ks(),
                glossiness: m.glossiness,
                highlight_norm: (m.glossiness + 8.0) / (8.0 * std::f32::consts::PI),
                kt: m.kt(),
                ior: m.ior,
                emission: m.emission(),
            })
            .collect();
        let mpu = setup.unit.metres_per_unit();
        let hidden: Vec<bool> = (0..scene.slots.len())
            .map(|s| setup.is_hidden(s as u32))
            .collect();
        let front_sign = match setup.handedness {
            Handedness::Right => 1.0,
            Handedness::Left => -1.0,
        };
        let emitters = emitter_table(scene, &clamped, &materials, &hidden, front_sign);
        Prepared {
            scene,
            lights,
            materials,
            emitters,
            front_sign,
            metres_per_unit_sq: mpu * mpu,
            epsilon: scene.ray_epsilon(),
            max_depth,
            any_hidden: hidden.iter().any(|&h| h),
            hidden,
        }
    }

    /// Closest hit on a drawn surface.
    pub fn closest_visible(&self, ray: &Ray) -> Option<Hit> {
        if self.any_hidden {
            self.scene.closest_drawn(ray, &self.hidden)
        } else {
            self.scene.bvh.intersect(ray)
        }
    }

    /// [`Prepared::closest_visible`] of each of `rays` into `out` (as long), eight at a time
    /// through the tree (the same hits bit for bit).
    pub fn closest_visible_many(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        if self.any_hidden {
            for (o, r) in out.iter_mut().zip(rays) {
                *o = self.closest_visible(r);
            }
            return;
        }
        for (r, o) in rays.chunks(PACKET).zip(out.chunks_mut(PACKET)) {
            if r.len() < MIN_PACKET {
                for (o, r) in o.iter_mut().zip(r) {
                    *o = self.scene.bvh.intersect(r);
                }
            } else {
                self.scene.bvh.intersect_packet(r, o);
            }
        }
    }

    /// The ray of a shadow test from `origin` towards `origin + to_target`, stopping just short
    /// of the end point.
    pub fn shadow_ray(origin: Vec3, to_target: Vec3) -> Ray {
        let mut ray = Ray::new(origin, to_target);
        ray.t_max = 1.0 - 1e-4;
        ray
    }

    /// [`Prepared::occluded`] of each shadow ray (see [`Prepared::shadow_ray`]) into `out`,
    /// eight at a time through the tree.
    pub fn occluded_many(&self, rays: &[Ray], out: &mut [bool]) {
        if self.any_hidden {
            for (o, r) in out.iter_mut().zip(rays) {
                *o = self.closest_visible(r).is_some();
            }
            return;
        }
        for (r, o) in rays.chunks(PACKET).zip(out.chunks_mut(PACKET)) {
            if r.len() < MIN_PACKET {
                for (o, r) in o.iter_mut().zip(r) {
                    *o = self.scene.bvh.occluded(r);
                }
            } else {
                self.scene.bvh.occluded_packet(r, o);
            }
        }
    }

    /// Whether a drawn surface blocks the segment `origin .. origin + to_target` (exclusive of
    /// the end point).
    pub fn occluded(&self, origin: Vec3, to_target: Vec3) -> bool {
        let ray = Self::shadow_ray(origin, to_target);
        if !self.any_hidden {
            return self.scene.bvh.occluded(&ray);
        }
        // With hidden breps, walk the closest hits and ignore hidden ones.
        self.closest_visible(&ray).is_some()
    }

    /// Direct light from the point-like `light` at `p` on a surface of unit normal `n`: the unit
    /// direction to the light and the illuminance it gives there, E = I(ω) cos θ / R² in lx
    /// (R in metres), before shadowing. None when it gives none (behind the surface, no
    /// intensity that way, or the light at `p`).
    pub fn light_at(&self, light: &PreparedLight, p: Vec3, n: Vec3) -> Option<(Vec3, f32)> {
        let to_light = light.position - p;
        let dist2 = to_light.length_squared();
        if dist2 <= 0.0 {
            return None;
        }
        let wi = to_light / dist2.sqrt();
        let cos_theta = n.dot(wi);
        if cos_theta <= 0.0 {
            return None;
        }
        let intensity = light.intensity_towards(-wi);
        if intensity <= 0.0 {
            return None;
        }
        Some((
            wi,
            intensity * cos_theta / (dist2 * self.metres_per_unit_sq),
        ))
    }

    /// The unit front normal of triangle `prim` (see `front_sign`).
    pub fn front_normal(&self, prim: u32) -> Vec3 {
        self.scene.normals[prim as usize] * self.front_sign
    }

    /// The material of triangle `prim`.
    pub fn material_of(&self, prim: u32) -> &PreparedMaterial {
        &self.materials[self.scene.triangle_slots[prim as usize] as usize]
    }
}

/// The emitter table of every drawn triangle whose material emits.
fn emitter_table(
    scene: &Scene,
    models: &[crate::scene::Material],
    materials: &[PreparedMaterial],
    hidden: &[bool],
    front_sign: f32,
) -> EmitterTable {
    let emissive = |slot: usize| materials[slot].emission.max_element() > 0.0 && !hidden[slot];
    if !(0..materials.len()).any(emissive) {
        return EmitterTable::default();
    }
    let triangles: Vec<EmissiveTriangle> = scene
        .triangle_slots
        .iter()
        .enumerate()
        .filter(|(_, slot)| emissive(**slot as usize))
        .map(|(t, &slot)| EmissiveTriangle {
            triangle: t as u32,
            vertices: scene.triangles[t],
            front: scene.normals[t] * front_sign,
            radiance: materials[slot as usize].emission,
            sides: models[slot as usize].emission_sides,
        })
        .collect();
    EmitterTable::new(scene.triangles.len(), &triangles)
}
