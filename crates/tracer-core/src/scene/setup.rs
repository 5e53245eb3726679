//! The editable part of a scene: camera, lights, materials, unit and handedness. Cheap to clone;
//! every render snapshot carries one.

use super::camera::{Camera, DEFAULT_FOV_DEG};
use super::default_light::default_light;
use super::framing::framing_camera;
use super::geometry::Scene;
use super::light::Light;
use super::material::Material;
use super::units::{Handedness, LengthUnit};

#[derive(Clone, Debug, PartialEq)]
pub struct Setup {
    pub unit: LengthUnit,
    pub handedness: Handedness,
    pub camera: Camera,
    pub lights: Vec<Light>,
    /// One material per slot of the scene (`Scene::slots`).
    pub materials: Vec<Material>,
    /// Slots not drawn (hidden breps). Indexed like `materials`.
    pub hidden: Vec<bool>,
    /// Calculation grids measured by `raygine measure` and shown by the viewer.
    pub grids: Vec<crate::measure::Grid>,
    /// Maintenance factor applied to measured illuminance (maintained values; 1: new).
    pub maintenance_factor: f32,
    /// Light from every direction at infinity (None: none, as before).
    pub environment: Option<crate::light::Environment>,
    /// The place, time and orientation of the sidecar's `[daylight]` (None: no daylight).
    pub daylight: Option<crate::light::daylight::Daylight>,
    /// A directional light at infinity the file designs (USD's DistantLight); drawn when no
    /// daylight sun is.
    pub sun: Option<crate::light::DistantSun>,
    /// Eyes where glare is judged (`[[observers]]`).
    pub observers: Vec<super::observer::Observer>,
}

impl Setup {
    /// What a scene without a sidecar gets: what its file designed ([`Scene::design`]), and for
    /// what it did not: neutral grey diffuse, one light just below the top centre of the
    /// bounds, a camera framing the bounds ([`framing_camera`]).
    pub fn defaults(scene: &Scene, unit: LengthUnit) -> Setup {
        let slots = scene.slots.len();
        let design = &scene.design;
        let camera = design
            .camera
            .unwrap_or_else(|| framing_camera(scene, DEFAULT_FOV_DEG));
        let lights = match &design.lights {
            Some(lights) => lights.clone(),
            None => vec![default_light(scene, unit, camera.position)],
        };
        let materials = (0..slots)
            .map(|s| {
                design
                    .materials
                    .get(s)
                    .copied()
                    .flatten()
                    .unwrap_or_default()
            })
            .collect();
        Setup {
            unit,
            handedness: design.handedness.unwrap_or(Handedness::Left),
            camera,
            lights,
            materials,
            hidden: vec![false; slots],
            grids: Vec::new(),
            maintenance_factor: 1.0,
            environment: design.environment.clone(),
            daylight: design.daylight.clone(),
            sun: design.sun,
            observers: Vec::new(),
        }
    }

    pub fn is_hidden(&self, slot: u32) -> bool {
        self.hidden.get(slot as usize).copied().unwrap_or(false)
    }
}
