//! glTF's metallic-roughness materials (also in `docs/formats.md`). raygine draws them with
//! glTF 2.0 Appendix B's model (`crate::shading::MetalRough`):
//!
//! - `baseColorFactor` (RGB; alpha unused), `metallicFactor`, `roughnessFactor`;
//! - `KHR_materials_ior`: the dielectric layer's F0 = ((ior − 1) / (ior + 1))², 0.04 at the
//!   default 1.5;
//! - `KHR_materials_transmission`: thin-walled transmission of the dielectric (its rough
//!   spread drawn smooth, noted);
//! - emission: emissive factor × `KHR_materials_emissive_strength`, read as
//!   `emission_scale` cd/m² per unit (1 by default: nits), noted once per material;
//! - textures, alpha blending and masks are not used (noted).
//!
//! The description also carries a Blinn-Phong approximation for readers that want one: Kd =
//! c (1 − metallic)(1 − T)(1 − F0), Ks = c metallic + F0 (1 − metallic) with glossiness
//! g = 2 / α⁴ − 2 for α = roughness² (the Beckmann-equivalent exponent; below 1 Ks joins Kd,
//! above 10 000 a mirror).

use crate::formats::{
    EmissionDescription, MaterialDescription, MetalRoughDescription, TransmissionDescription,
};
use crate::light::EmissionSides;
use std::path::Path;

/// Dielectric reflectance at normal incidence of glTF's metallic-roughness model.
const F0: f32 = 0.04;

pub(super) fn to_description(
    m: &::gltf::Material<'_>,
    path: &Path,
    emission_scale: f32,
    notes: &mut Vec<String>,
) -> MaterialDescription {
    let index = m
        .index()
        .map_or_else(|| "default".to_owned(), |i| i.to_string());
    let name = m
        .name()
        .map_or_else(|| format!("material{index}"), str::to_owned);
    let at = format!("{}: material {name}", path.display());
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, _] = pbr.base_color_factor();
    let base = [r, g, b].map(|c| c.clamp(0.0, 1.0));
    let metallic = pbr.metallic_factor().clamp(0.0, 1.0);
    let roughness = pbr.roughness_factor().clamp(0.0, 1.0);
    let transmission = m
        .transmission()
        .map_or(0.0, |t| t.transmission_factor().clamp(0.0, 1.0));
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
    let ior = m.ior().unwrap_or(1.5);
    let metal_rough = MetalRoughDescription {
        base_color: base,
        metallic,
        roughness,
        transmission,
        ior,
    };
    if transmission > 0.0 && roughness > 0.0 {
        notes.push(format!(
            "{at}: transmission is drawn smooth (thin-walled, no rough spread of roughness \
             {roughness})"
        ));
    }
    let transmission = (transmission > 0.0).then_some(TransmissionDescription {
        specular: transmission * (1.0 - metallic),
        diffuse: 0.0,
        ior,
    });
    let strength = m.emissive_strength().unwrap_or(1.0).max(0.0);
    let emissive = m.emissive_factor().map(|c| c.max(0.0) * strength);
    let sides = if m.double_sided() {
        EmissionSides::Both
    } else {
        EmissionSides::Front
    };
    let emission =
        EmissionDescription::from_unitless(emissive, emission_scale, sides, &at, "emissive", notes);
    let textured = pbr.base_color_texture().is_some()
        || pbr.metallic_roughness_texture().is_some()
        || m.emissive_texture().is_some()
        || m.normal_texture().is_some();
    if textured {
        notes.push(format!(
            "{at}: textures are not supported; drawn untextured"
        ));
    }
    if m.alpha_mode() != ::gltf::material::AlphaMode::Opaque {
        notes.push(format!(
            "{at}: alpha blending and masks are not supported; drawn opaque"
        ));
    }
    MaterialDescription {
        name,
        source: path.to_owned(),
        line: 0,
        diffuse,
        specular,
        glossiness,
        transmission,
        emission,
        metal_rough: Some(metal_rough),
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    fn material(json: &str) -> MaterialDescription {
        let doc = ::gltf::Gltf::from_slice(
            format!(r#"{{"asset":{{"version":"2.0"}},"materials":[{json}]}}"#).as_bytes(),
        )
        .expect("valid");
        let m = doc.materials().next().expect("one material");
        to_description(&m, Path::new("t.gltf"), 1.0, &mut Vec::new())
    }

    #[test]
    fn factors_and_extensions_become_the_metallic_roughness_model() {
        let m = material(
            r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.9,0.8,0.7,0.5],"metallicFactor":0.25,"roughnessFactor":0.4},
                "extensions":{"KHR_materials_ior":{"ior":1.33},"KHR_materials_transmission":{"transmissionFactor":0.6}}}"#,
        );
        let mr = m.metal_rough.expect("metallic-roughness");
        assert_eq!(mr.base_color, [0.9, 0.8, 0.7]);
        assert_eq!((mr.metallic, mr.roughness), (0.25, 0.4));
        assert_eq!((mr.transmission, mr.ior), (0.6, 1.33));
        // glTF's defaults: white, metallic 1, roughness 1, ior 1.5, no transmission.
        let d = material("{}").metal_rough.expect("metallic-roughness");
        assert_eq!(
            d,
            MetalRoughDescription {
                base_color: [1.0; 3],
                metallic: 1.0,
                roughness: 1.0,
                transmission: 0.0,
                ior: 1.5
            }
        );
    }

    #[test]
    fn metallic_roughness_maps_as_documented() {
        // A smooth-ish dielectric: Kd = c (1 - 0.04), lobe 0.04 with g = 2 / r^4 - 2.
        let m = material(
            r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.5,0.5,1],"metallicFactor":0,"roughnessFactor":0.5}}"#,
        );
        assert!((m.diffuse[0] - 0.48).abs() < 1e-6, "{:?}", m.diffuse);
        assert!((m.specular[0] - 0.04).abs() < 1e-6);
        assert!((m.glossiness - 30.0).abs() < 1e-3, "{}", m.glossiness);
        // glTF's default material (white, metallic 1, roughness 1) is a white diffuser.
        let d = material("{}");
        assert_eq!((d.specular, d.glossiness), ([0.0; 3], 0.0));
        assert!((d.diffuse[0] - 1.0).abs() < 1e-6, "{:?}", d.diffuse);
        // Roughness 0 is a mirror of the base colour for a metal.
        let mirror = material(
            r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.9,0.8,0.7,1],"roughnessFactor":0}}"#,
        );
        assert_eq!(mirror.glossiness, 0.0);
        assert!((mirror.specular[1] - 0.8).abs() < 1e-6);
    }
}
