//! The setup a scene file designs: its materials, lights, camera and unit in model terms. A
//! scene's defaults start from it; a sidecar overrides it. Formats without any of these leave
//! the parts empty and raygine's own defaults apply.

use super::camera::Camera;
use super::material::{Material, Pbr};
use super::units::{Handedness, LengthUnit};
use crate::formats::{LightDescription, LightDistribution, MaterialDescription, SceneDescription};
use crate::light::{Light, LightKind, Luminaire, LuminairePlacement, Spot};
use std::sync::Arc;

/// What the file says, per slot where it applies.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Design {
    /// One entry per material slot: the file's material, or None for raygine's default.
    pub materials: Vec<Option<Material>>,
    /// The file's lights (None: the format has no lights; the default light is used).
    pub lights: Option<Vec<Light>>,
    pub camera: Option<Camera>,
    pub unit: Option<LengthUnit>,
    /// The handedness of the file's frame, when the format fixes it (OBJ, glTF: right).
    pub handedness: Option<Handedness>,
    /// The image size the camera was designed for (width, height), pixels.
    pub resolution: Option<[u32; 2]>,
    /// Place, time and orientation for the sun (Integra's `Geography`).
    pub daylight: Option<crate::light::daylight::Daylight>,
    /// The file's environment (USD's DomeLight).
    pub environment: Option<crate::light::Environment>,
    /// The file's directional light at infinity (USD's DistantLight).
    pub sun: Option<crate::light::DistantSun>,
    /// Non-fatal findings (the reader's and the mapping's), for the user.
    pub notes: Vec<String>,
}

impl Design {
    /// Maps the description's materials onto the material slots (`slot_count` in all; mesh i's
    /// parts start at `first_slots[i]`), and its lights, camera and unit onto the model.
    /// `texture_sets[i]` is the scene's texture set of described material i, if any.
    pub fn from_description(
        desc: &SceneDescription,
        first_slots: &[u32],
        slot_count: usize,
        texture_sets: &[Option<u32>],
    ) -> Design {
        let mut notes = desc.notes.clone();
        let models: Vec<Material> = desc
            .materials
            .iter()
            .enumerate()
            .map(|(i, m)| Material {
                textures: texture_sets.get(i).copied().flatten(),
                ..material_from_description(m, &mut notes)
            })
            .collect();
        let mut materials = vec![None; slot_count];
        for (mesh, &first_slot) in desc.meshes.iter().zip(first_slots) {
            for (part, p) in mesh.parts.iter().enumerate() {
                let slot = first_slot as usize + part;
                if let (Some(m), Some(out)) = (
                    p.material.and_then(|i| models.get(i)),
                    materials.get_mut(slot),
                ) {
                    *out = Some(*m);
                }
            }
        }
        let lights: Option<Vec<Light>> = desc
            .lights
            .as_ref()
            .map(|ls| ls.iter().map(light_from_description).collect());
        // A surface that glows, a sky or a sun lights the scene: no warning then.
        let glows = materials.iter().flatten().any(|m| m.emission_cd_m2 > 0.0)
            || desc.environment.is_some()
            || desc.sun.is_some();
        if lights.as_ref().is_some_and(Vec::is_empty) && !glows {
            notes.push(format!(
                "{}: the scene designs no light that is on: the picture stays dark until a \
                 light is added (Lights panel or sidecar)",
                desc.path.display()
            ));
        }
        let camera = desc.camera.map(|c| Camera {
            position: c.position,
            look_at: c.look_at,
            up: c.up,
            fov_deg: c.fov_deg,
            ..Camera::default()
        });
        let unit = desc.metres_per_unit.and_then(|m| {
            LengthUnit::ALL
                .into_iter()
                .find(|u| (u.metres_per_unit() - m).abs() <= 1e-6 * m)
        });
        Design {
            materials,
            lights,
            camera,
            unit,
            handedness: match desc.format {
                crate::formats::SceneFormat::Obj
                | crate::formats::SceneFormat::Gltf
                | crate::formats::SceneFormat::Usd => Some(Handedness::Right),
                _ => None,
            },
            resolution: desc.camera.and_then(|c| c.resolution),
            daylight: desc
                .daylight
                .as_ref()
                .and_then(|d| d.to_model().map_err(|e| notes.push(e)).ok()),
            environment: desc.environment.clone(),
            sun: desc.sun,
            notes,
        }
    }
}

/// A described material as raygine's model draws it: glTF's metallic-roughness when the
/// description has it; else diffuse and specular reflectance and the lobe's glossiness carry over (clamped into range, with a note), emission becomes a
/// Lambertian emitter, clear transmission becomes glass (Kt, ior; the global-illumination
/// integrators trace it), diffuse transmission is noted once per material and absorbed.
pub fn material_from_description(m: &MaterialDescription, notes: &mut Vec<String>) -> Material {
    let mut out = Material {
        kd: m.diffuse,
        ks: m.specular,
        glossiness: m.glossiness,
        ..Material::default()
    };
    if let Some(e) = m.emission {
        out.emission_cd_m2 = e.luminance_cd_m2;
        out.emission_color = e.color;
        out.emission_sides = e.sides;
    }
    if let Some(mr) = m.metal_rough {
        // glTF's model replaces the Blinn-Phong approximation and the glass.
        out = Material {
            kd: [0.0; 3],
            ks: [0.0; 3],
            glossiness: 0.0,
            ior: mr.ior,
            pbr: Some(Pbr {
                base_color: mr.base_color,
                metallic: mr.metallic,
                roughness: mr.roughness,
                transmission: mr.transmission,
            }),
            ..out
        };
        note_ior(m, mr.ior, notes);
    } else if let Some(t) = m.transmission {
        // Clear transmission is the smooth dielectric (glass): Kt with the index behind the
        // front face; an index of 1 is a thin sheet that does not bend light.
        if t.specular > 0.0 {
            out.kt = [t.specular; 3];
            out.ior = t.ior;
            note_ior(m, t.ior, notes);
        }
        if t.diffuse > 0.0 {
            notes.push(format!(
                "{}:{}: material {}: diffuse transmission {} (frosted) is not in raygine's \
                 material model; that part is absorbed",
                m.source.display(),
                m.line,
                m.name,
                t.diffuse
            ));
        }
    }
    let (clamped, changed) = out.clamped();
    if changed {
        notes.push(format!(
            "{}:{}: material {}: clamped into range (0..1, Kd + Ks + Kt <= 1 per channel)",
            m.source.display(),
            m.line,
            m.name
        ));
    }
    clamped
}

/// A note when a described index of refraction is clamped into 1..4.
fn note_ior(m: &MaterialDescription, ior: f32, notes: &mut Vec<String>) {
    if !(1.0..=4.0).contains(&ior) {
        notes.push(format!(
            "{}:{}: material {}: index of refraction {ior} is outside 1..4; clamped",
            m.source.display(),
            m.line,
            m.name,
        ));
    }
}

/// A described light as a model light: isotropic sources become point lights, spots spots, tabulated ones luminaires (multiplier 1: the table is already in candela).
pub fn light_from_description(l: &LightDescription) -> Light {
    let kind = match &l.distribution {
        LightDistribution::Isotropic { intensity_cd } => LightKind::Point {
            intensity_cd: *intensity_cd,
        },
        LightDistribution::Spot {
            intensity_cd,
            cone_deg,
            falloff_deg,
        } => LightKind::Spot(Spot {
            intensity_cd: *intensity_cd,
            aim: l.aim,
            cone_deg: *cone_deg,
            falloff_deg: falloff_deg.max(*cone_deg),
        }),
        LightDistribution::Goniometric { photometry, label } => {
            LightKind::Luminaire(LuminairePlacement {
                aim: l.aim,
                rotation_deg: l.rotation_deg,
                ..LuminairePlacement::new(Arc::new(Luminaire::new(
                    photometry.clone(),
                    label.into(),
                )))
            })
        }
    };
    Light {
        position: l.position,
        color: l.color,
        kind,
    }
}
