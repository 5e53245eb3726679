//! The scene as one render sees it: the scene's geometry with its setup resolved once into
//! what the per-ray code needs, with no conversions left: lights with their tints scaled to
//! luminance 1 and their profiles, material constants, the emitter table, the hidden parts, the
//! unit factor and the front side. Integrators, sensors and guides all sample a [`LitScene`].

mod light_sampler;
mod lights;
mod surface_maps;
mod visibility;

pub use light_sampler::{LightSampler, TreeLight};

use crate::light::daylight::SUN_DIAMETER_DEG;
use crate::light::{
    EmitterTable, EnvironmentLight, LightHandle, LightSource, PlacedLight, SunDisc,
};
use crate::scene::{Handedness, Scene, Setup};
use crate::shading::PreparedMaterial;
use glam::Vec3;

/// Everything the integrator needs for one render.
#[derive(Debug)]
pub struct LitScene<'a> {
    pub scene: &'a Scene,
    pub lights: Vec<PlacedLight>,
    pub materials: Vec<PreparedMaterial>,
    /// Emissive triangles of drawn surfaces.
    pub emitters: EmitterTable,
    /// The light tree over `lights` and `emitters`.
    pub light_sampler: LightSampler,
    /// Light from every direction at infinity (path and direct modes).
    pub environment: Option<EnvironmentLight>,
    /// +1 when the front normal is (v1 − v0) × (v2 − v0) (right-handed scenes), −1 when it is
    /// its negation (left-handed, as `.shp` files are mirror images).
    pub front_sign: f32,
    /// Metres per scene unit.
    pub metres_per_unit: f32,
    /// (metres per scene unit)², to turn squared scene distances into m².
    pub metres_per_unit_sq: f32,
    /// Offset of secondary ray origins along the normal, scene units.
    pub epsilon: f32,
    pub max_depth: u32,
    /// True when some slot is hidden (then hits on hidden slots are skipped).
    any_hidden: bool,
    hidden: Vec<bool>,
    /// Whether some material is metallic-roughness or a pane (else the classic lobes are all
    /// the integrators need: `shading::Scatter`).
    metal_rough: bool,
    /// Whether some material is a pane (shadow rays then pass panes, weighted).
    panes: bool,
    /// Which slots textures shade or cut.
    maps: surface_maps::SlotMaps,
}

impl<'a> LitScene<'a> {
    pub fn new(scene: &'a Scene, setup: &Setup, max_depth: u32) -> Self {
        let handedness_sign = match setup.handedness {
            Handedness::Right => 1.0,
            Handedness::Left => -1.0,
        };
        let mpu = setup.unit.metres_per_unit();
        let lights: Vec<PlacedLight> = setup
            .lights
            .iter()
            .filter(|l| l.is_valid())
            .map(|l| PlacedLight::new(l, handedness_sign, mpu * mpu))
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
        let materials: Vec<PreparedMaterial> = clamped.iter().map(PreparedMaterial::new).collect();
        let maps = surface_maps::SlotMaps::new(scene, &clamped);
        let hidden: Vec<bool> = (0..scene.slots.len())
            .map(|s| setup.is_hidden(s as u32))
            .collect();
        let front_sign = match setup.handedness {
            Handedness::Right => 1.0,
            Handedness::Left => -1.0,
        };
        let emitters = lights::emitter_table(scene, &clamped, &materials, &hidden, front_sign);
        let light_sampler = LightSampler::new(
            lights.iter().map(PlacedLight::bounds).collect(),
            emitters.light_bounds(mpu),
        );
        let b = scene.bounds;
        let (mut centre, mut radius) = ((b.min + b.max) * 0.5, (b.max - b.min).length() * 0.5);
        if !(centre.is_finite() && radius.is_finite() && radius > 0.0) {
            // An empty scene.
            (centre, radius) = (Vec3::ZERO, 1.0);
        }
        let environment = setup
            .environment
            .as_ref()
            .filter(|e| e.is_valid())
            .map(|e| EnvironmentLight::new(e, handedness_sign, centre, radius, mpu * mpu));
        // Daylight's sun joins the environment (or is all of it); else the file's.
        let sun = setup
            .daylight
            .as_ref()
            .and_then(|d| {
                let (dir, e_n) = d.sun_disc(setup.handedness == Handedness::Right)?;
                Some(SunDisc::new(dir, SUN_DIAMETER_DEG, e_n))
            })
            .or_else(|| setup.sun.as_ref().and_then(crate::light::DistantSun::disc));
        let environment = match (environment, sun) {
            (Some(env), Some(sun)) => Some(env.with_sun(sun)),
            (None, Some(sun)) => Some(EnvironmentLight::sun_only(sun, centre, radius, mpu * mpu)),
            (env, None) => env,
        };
        let panes = materials.iter().any(|m| m.pane.is_some());
        let metal_rough = panes || materials.iter().any(|m| m.pbr.is_some());
        LitScene {
            scene,
            lights,
            materials,
            emitters,
            light_sampler,
            environment,
            front_sign,
            metres_per_unit: mpu,
            metres_per_unit_sq: mpu * mpu,
            epsilon: scene.ray_epsilon(),
            max_depth,
            any_hidden: hidden.iter().any(|&h| h),
            hidden,
            metal_rough,
            panes,
            maps,
        }
    }

    /// Whether some material needs the full [`crate::shading::Bsdf`]: metallic-roughness or a
    /// pane.
    pub fn has_metal_rough(&self) -> bool {
        self.metal_rough
    }

    /// Whether some material is a thin pane.
    pub fn has_panes(&self) -> bool {
        self.panes
    }

    /// The unit front normal of triangle `prim` (see `front_sign`).
    pub fn front_normal(&self, prim: u32) -> Vec3 {
        self.scene.normal(prim) * self.front_sign
    }

    /// The light `light` names (None for a glowing triangle that is not in the table).
    #[inline]
    pub fn light(&self, light: TreeLight) -> Option<LightHandle<'_>> {
        match light {
            TreeLight::Placed(i) => self.lights.get(i as usize).map(LightHandle::Placed),
            TreeLight::Triangle(t) => {
                let index = self.emitters.index_of(t)?;
                self.emitters
                    .light(index, self.metres_per_unit)
                    .map(LightHandle::Triangle)
            }
        }
    }

    /// The material of triangle `prim`.
    pub fn material_of(&self, prim: u32) -> &PreparedMaterial {
        &self.materials[self.scene.slot(prim) as usize]
    }
}
