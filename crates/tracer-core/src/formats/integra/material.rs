//! An `.atr` attribute as a neutral material. The mapping (documented in `docs/integra.md`):
//!
//! - `kd` is the luminous diffuse reflectance; `color R G B` (0–255, sRGB-encoded as colour
//!   pickers give it) is decoded to linear RGB and scaled to Rec. 709 luminance 1, so the
//!   reflectance per channel is `kd × tint` and its luminance stays `kd`. A channel above 1 is
//!   clamped to 1 with a note (saturated colours at a high kd ask for more than all the light).
//! - `ks` is the reflectance of the specular lobe (grey), `gs` its Blinn-Phong exponent.
//!   `mirror on|off` is a switch, not a reflectance: with `ks 0` (most attributes) it changes
//!   nothing, and raygine draws `ks` with the lobe `gs` gives whatever the switch says.
//! - `kts`, `ktd`, `eta` become the transmission description (the scene builder says what it
//!   can draw of it).
//! - `SelfLuminance L` (cd/m²) with `SelfLumDirection Pos|Neg|Both` is a Lambertian emitter of
//!   luminance L tinted by `color`, from the front, back or both faces.

use super::atr::Attr;
use crate::formats::description::{
    EmissionDescription, MaterialDescription, TransmissionDescription,
};
use crate::light::{EmissionSides, luminance};
use glam::Vec3;
use std::path::Path;

/// `kd` of an attribute that does not give one (IPUR's own default).
pub const DEFAULT_KD: f64 = 0.5;

/// The sRGB transfer function undone: an 8-bit-scale value (0–255) to linear 0..=1.
pub fn srgb_to_linear(value_0_255: f64) -> f32 {
    let v = (value_0_255 / 255.0).clamp(0.0, 1.0) as f32;
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// The attribute's colour as a linear tint of luminance 1 (white when it has none or black).
pub fn unit_tint(color: Option<[f64; 3]>) -> Vec3 {
    let Some(c) = color else {
        return Vec3::ONE;
    };
    let linear = Vec3::from(c.map(srgb_to_linear));
    let y = luminance(linear);
    if y > 0.0 && y.is_finite() {
        linear / y
    } else {
        Vec3::ONE
    }
}

/// The material an attribute describes; clamped channels are noted in `notes`.
pub fn material_from_attr(
    attr: &Attr,
    path: &Path,
    notes: &mut Vec<String>,
) -> MaterialDescription {
    let tint = unit_tint(attr.color);
    let kd = attr.kd.unwrap_or(DEFAULT_KD) as f32;
    let wanted = tint * kd;
    let diffuse = wanted.min(Vec3::ONE).max(Vec3::ZERO);
    if wanted.max_element() > 1.0 {
        notes.push(format!(
            "{}:{}: attribute {}: colour {:?} at kd {kd} asks for a reflectance of \
             [{:.3}, {:.3}, {:.3}]; clamped to 1 per channel",
            path.display(),
            attr.line,
            attr.name,
            attr.color.unwrap_or([255.0; 3]),
            wanted.x,
            wanted.y,
            wanted.z
        ));
    }
    let ks = attr.ks.unwrap_or(0.0) as f32;
    let transmission =
        (attr.kts.is_some() || attr.ktd.is_some()).then(|| TransmissionDescription {
            specular: attr.kts.unwrap_or(0.0) as f32,
            diffuse: attr.ktd.unwrap_or(0.0) as f32,
            ior: attr.eta.unwrap_or(1.0) as f32,
        });
    let emission = attr
        .self_luminance
        .filter(|&l| l > 0.0)
        .map(|l| EmissionDescription {
            luminance_cd_m2: l as f32,
            color: tint.to_array(),
            sides: match attr
                .self_lum_direction
                .as_deref()
                .map(str::to_ascii_lowercase)
                .as_deref()
            {
                Some("pos") => EmissionSides::Front,
                Some("neg") => EmissionSides::Back,
                _ => EmissionSides::Both,
            },
        });
    MaterialDescription {
        name: attr.name.clone(),
        source: path.to_owned(),
        line: attr.line,
        diffuse: diffuse.to_array(),
        specular: [ks; 3],
        glossiness: if ks > 0.0 {
            attr.gs.unwrap_or(0.0) as f32
        } else {
            0.0
        },
        transmission,
        emission,
        metal_rough: None,
        maps: None,
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn tint_keeps_kd_as_the_luminous_reflectance() {
        let attr = Attr {
            kd: Some(0.5),
            color: Some([255.0, 248.0, 228.0]),
            ..Attr::default()
        };
        let mut notes = Vec::new();
        let m = material_from_attr(&attr, Path::new("r.atr"), &mut notes);
        assert!((luminance(Vec3::from(m.diffuse)) - 0.5).abs() < 1e-5);
        assert!(notes.is_empty());
        // sRGB 188 is linear 0.5 (to 3 decimals): decoded, not divided by 255.
        assert!((srgb_to_linear(188.0) - 0.5029).abs() < 1e-3);
    }

    #[test]
    fn saturated_colours_clamp_with_a_note() {
        // Orange-brown 154 67 0: linear red 0.323, luminance 0.109, so kd 0.3413 wants red 1.01.
        let attr = Attr {
            name: "a000020".into(),
            line: 7,
            kd: Some(0.3413),
            color: Some([154.0, 67.0, 0.0]),
            ..Attr::default()
        };
        let mut notes = Vec::new();
        let m = material_from_attr(&attr, Path::new("r.atr"), &mut notes);
        assert_eq!(m.diffuse[0], 1.0);
        assert_eq!(m.diffuse[2], 0.0);
        assert_eq!(notes.len(), 1);
        assert!(
            notes[0].starts_with("r.atr:7: attribute a000020"),
            "{}",
            notes[0]
        );
    }
}
