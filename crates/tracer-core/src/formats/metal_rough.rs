//! What glTF's and USD's metallic-roughness materials mean in raygine's classic terms: the
//! Blinn-Phong approximation a [`MaterialDescription`] carries beside the model itself, and the
//! thin-walled transmission. One mapping for every reader that has the model, so that the same
//! material read from a `.gltf` and a `.usda` is the same material.
//!
//! Kd = c (1 − metallic)(1 − T)(1 − F0), Ks = c metallic + F0 (1 − metallic) with glossiness
//! g = 2 / α⁴ − 2 for α = roughness² (the Beckmann-equivalent exponent; below 1 Ks joins Kd,
//! above 10 000 a mirror); F0 = ((ior − 1) / (ior + 1))² is 0.04 at glTF's default 1.5 (the
//! classic approximation keeps glTF's 0.04).

use super::{MaterialDescription, MetalRoughDescription, TransmissionDescription};

/// Dielectric reflectance at normal incidence of glTF's metallic-roughness model.
const F0: f32 = 0.04;

/// A material of the metallic-roughness model (values clamped to their ranges here), with the
/// classic approximation filled in; the caller names it and adds emission and maps. `at` names
/// the material in notes.
pub(crate) fn material(
    model: MetalRoughDescription,
    at: &str,
    notes: &mut Vec<String>,
) -> MaterialDescription {
    let base = model.base_color.map(|c| c.clamp(0.0, 1.0));
    let metallic = model.metallic.clamp(0.0, 1.0);
    let roughness = model.roughness.clamp(0.0, 1.0);
    let transmission = model.transmission.clamp(0.0, 1.0);
    let alpha = roughness * roughness;
    let glossiness = if alpha > 0.0 {
        2.0 / (alpha * alpha) - 2.0
    } else {
        f32::INFINITY
    };
    let ks = base.map(|c| c * metallic + F0 * (1.0 - metallic));
    let mut diffuse = base.map(|c| c * (1.0 - metallic) * (1.0 - transmission) * (1.0 - F0));
    let (specular, glossiness) = if glossiness < 1.0 {
        // So rough that the lobe reflects about as a Lambertian surface does: its reflectance
        // joins Kd (a rough metal is not black).
        for (d, k) in diffuse.iter_mut().zip(ks) {
            *d += k;
        }
        ([0.0; 3], 0.0)
    } else {
        (
            ks,
            if glossiness > 10_000.0 {
                0.0
            } else {
                glossiness
            },
        )
    };
    if transmission > 0.0 && roughness > 0.0 {
        notes.push(format!(
            "{at}: transmission is drawn smooth (thin-walled, no rough spread of roughness \
             {roughness})"
        ));
    }
    let ior = model.ior;
    MaterialDescription {
        diffuse,
        specular,
        glossiness,
        transmission: (transmission > 0.0).then_some(TransmissionDescription {
            specular: transmission * (1.0 - metallic),
            diffuse: 0.0,
            ior,
        }),
        metal_rough: Some(MetalRoughDescription {
            base_color: base,
            metallic,
            roughness,
            transmission,
            ior,
        }),
        ..MaterialDescription::default()
    }
}
