//! A material as the sidecar writes it: the coursework's `kd`, `ks`, `glossiness`, or glTF's
//! `base_color`, `metallic`, `roughness`, never both; glass, `ior` and emission with either.
//!
//! ```toml
//! [materials.floor]           # Lambert and Blinn-Phong (kd is required)
//! kd = [0.6, 0.6, 0.6]
//! ks = [0.1, 0.1, 0.1]
//! glossiness = 40.0
//! [materials.reflector]       # metallic-roughness (glTF defaults: 1, 1, 1)
//! base_color = [0.91, 0.92, 0.92]
//! metallic = 1.0
//! roughness = 0.3
//! ior = 1.5                   # F0 of the dielectric layer (0.04 at 1.5)
//! transmission = 0.0          # glTF's thin-walled transmission (metallic-roughness only)
//! [materials.window]          # a thin glass pane: a window as one polygon
//! kind = "pane"
//! ior = 1.52                  # default 1.52
//! transmittance = 0.80        # at normal incidence, for absorbing glazing (default: clear)
//! ```

use super::material::{GLASS_IOR, Glazing, Material, PANE_IOR, Pbr};
use crate::light::EmissionSides;
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialKeys {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transmittance: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kd: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ks: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub glossiness: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base_color: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metallic: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transmission: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kt: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ior: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emission_cd_m2: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emission_color: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emission_sides: Option<EmissionSides>,
}

impl TryFrom<MaterialKeys> for Material {
    type Error = String;

    fn try_from(k: MaterialKeys) -> Result<Self, String> {
        match k.kind.as_deref() {
            None => {}
            Some("pane") => return pane_from(&k),
            Some(other) => {
                return Err(format!(
                    "kind = \"{other}\": the only kind is \"pane\" (a thin glass window); other \
                     materials are told apart by their keys"
                ));
            }
        }
        if k.transmittance.is_some() {
            return Err("transmittance is a pane's (kind = \"pane\")".into());
        }
        let classic: Vec<&str> = [
            ("kd", k.kd.is_some()),
            ("ks", k.ks.is_some()),
            ("glossiness", k.glossiness.is_some()),
        ]
        .iter()
        .filter_map(|&(name, given)| given.then_some(name))
        .collect();
        let gltf: Vec<&str> = [
            ("base_color", k.base_color.is_some()),
            ("metallic", k.metallic.is_some()),
            ("roughness", k.roughness.is_some()),
            ("transmission", k.transmission.is_some()),
        ]
        .iter()
        .filter_map(|&(name, given)| given.then_some(name))
        .collect();
        if k.kt.is_some() && !gltf.is_empty() {
            return Err(
                "kt is the Blinn-Phong model's glass; a metallic-roughness material takes \
                 transmission (0..1) instead"
                    .into(),
            );
        }
        if !classic.is_empty() && !gltf.is_empty() {
            return Err(format!(
                "give kd, ks and glossiness (Blinn-Phong) or base_color, metallic and roughness \
                 (metallic-roughness), not both: this material has {} and {}",
                classic.join(", "),
                gltf.join(", ")
            ));
        }
        let pbr = (!gltf.is_empty()).then(|| {
            let d = Pbr::default();
            Pbr {
                base_color: k.base_color.unwrap_or(d.base_color),
                metallic: k.metallic.unwrap_or(d.metallic),
                roughness: k.roughness.unwrap_or(d.roughness),
                transmission: k.transmission.unwrap_or(d.transmission),
            }
        });
        let kd = match (k.kd, pbr) {
            (Some(kd), _) => kd,
            (None, Some(_)) => [0.0; 3],
            (None, None) => {
                return Err(
                    "give kd (Lambert, with ks and glossiness) or base_color, metallic and \
                     roughness (metallic-roughness)"
                        .into(),
                );
            }
        };
        Ok(Material {
            kd,
            ks: k.ks.unwrap_or([0.0; 3]),
            glossiness: k.glossiness.unwrap_or(0.0),
            kt: k.kt.unwrap_or([0.0; 3]),
            ior: k.ior.unwrap_or(GLASS_IOR),
            emission_cd_m2: k.emission_cd_m2.unwrap_or(0.0),
            emission_color: k.emission_color.unwrap_or([1.0; 3]),
            emission_sides: k.emission_sides.unwrap_or_default(),
            pbr,
            pane: None,
            textures: None,
        })
    }
}

/// A pane takes `ior` and `transmittance` only.
fn pane_from(k: &MaterialKeys) -> Result<Material, String> {
    let stray: Vec<&str> = [
        ("kd", k.kd.is_some()),
        ("ks", k.ks.is_some()),
        ("glossiness", k.glossiness.is_some()),
        ("base_color", k.base_color.is_some()),
        ("metallic", k.metallic.is_some()),
        ("roughness", k.roughness.is_some()),
        ("transmission", k.transmission.is_some()),
        ("kt", k.kt.is_some()),
        ("emission_cd_m2", k.emission_cd_m2.is_some()),
        ("emission_color", k.emission_color.is_some()),
        ("emission_sides", k.emission_sides.is_some()),
    ]
    .iter()
    .filter_map(|&(name, given)| given.then_some(name))
    .collect();
    if !stray.is_empty() {
        return Err(format!(
            "a pane (kind = \"pane\") takes ior and transmittance only, not {}",
            stray.join(", ")
        ));
    }
    let ior = k.ior.unwrap_or(PANE_IOR);
    crate::shading::Pane::new(ior, k.transmittance)?;
    Ok(Material {
        kd: [0.0; 3],
        ior,
        pane: Some(Glazing {
            transmittance: k.transmittance,
        }),
        ..Material::default()
    })
}

impl From<Material> for MaterialKeys {
    /// The keys that give `m` back: kd, ks and glossiness always for a Blinn-Phong material,
    /// the others when they differ from their defaults.
    fn from(m: Material) -> Self {
        if let Some(g) = m.pane {
            return MaterialKeys {
                kind: Some("pane".into()),
                ior: (m.ior != PANE_IOR).then_some(m.ior),
                transmittance: g.transmittance,
                ..MaterialKeys::default()
            };
        }
        let (kd, ks, glossiness) = match m.pbr {
            None => (Some(m.kd), Some(m.ks), Some(m.glossiness)),
            Some(_) => (None, None, None),
        };
        MaterialKeys {
            kind: None,
            transmittance: None,
            kd,
            ks,
            glossiness,
            base_color: m.pbr.map(|p| p.base_color),
            metallic: m.pbr.map(|p| p.metallic),
            roughness: m.pbr.map(|p| p.roughness),
            transmission: m.pbr.map(|p| p.transmission).filter(|&t| t != 0.0),
            kt: (m.kt != [0.0; 3]).then_some(m.kt),
            ior: (m.ior != GLASS_IOR).then_some(m.ior),
            emission_cd_m2: (m.emission_cd_m2 != 0.0).then_some(m.emission_cd_m2),
            emission_color: (m.emission_color != [1.0; 3]).then_some(m.emission_color),
            emission_sides: (m.emission_sides != EmissionSides::Both).then_some(m.emission_sides),
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn keys_round_trip_and_the_two_models_exclude_each_other() {
        let classic: Material = toml::from_str("kd = [0.5, 0.5, 0.5]\nglossiness = 10.0").unwrap();
        assert!(classic.pbr.is_none() && classic.glossiness == 10.0);
        let text = toml::to_string(&classic).unwrap();
        assert!(text.contains("kd = ") && text.contains("ks = ") && !text.contains("metallic"));
        assert_eq!(toml::from_str::<Material>(&text).unwrap(), classic);

        let metal: Material =
            toml::from_str("base_color = [0.9, 0.8, 0.7]\nroughness = 0.3").unwrap();
        let pbr = metal.pbr.unwrap();
        assert_eq!((pbr.metallic, pbr.roughness), (1.0, 0.3));
        let text = toml::to_string(&metal).unwrap();
        assert!(
            !text.contains("kd") && text.contains("roughness = 0.3"),
            "{text}"
        );
        assert_eq!(toml::from_str::<Material>(&text).unwrap(), metal);

        let both = toml::from_str::<Material>("kd = [0.5, 0.5, 0.5]\nmetallic = 0.0")
            .unwrap_err()
            .to_string();
        assert!(
            both.contains("not both") && both.contains("kd and metallic"),
            "{both}"
        );
        let none = toml::from_str::<Material>("ior = 1.4")
            .unwrap_err()
            .to_string();
        assert!(none.contains("give kd"), "{none}");
        assert!(toml::from_str::<Material>("kd = [0.5, 0.5, 0.5]\nshine = 1.0").is_err());

        let pane: Material = toml::from_str("kind = \"pane\"\ntransmittance = 0.8").unwrap();
        assert_eq!(pane.ior, PANE_IOR);
        assert_eq!(pane.pane.unwrap().transmittance, Some(0.8));
        let text = toml::to_string(&pane).unwrap();
        assert!(
            text.contains("kind = \"pane\"") && !text.contains("kd"),
            "{text}"
        );
        assert_eq!(toml::from_str::<Material>(&text).unwrap(), pane);
        let e = |t: &str| toml::from_str::<Material>(t).unwrap_err().to_string();
        assert!(e("kind = \"pane\"\nkd = [0.5, 0.5, 0.5]").contains("ior and transmittance only"));
        assert!(e("kind = \"mirror\"").contains("the only kind is"));
        assert!(e("kd = [0.5, 0.5, 0.5]\ntransmittance = 0.5").contains("pane's"));
        assert!(e("kind = \"pane\"\ntransmittance = 0.99").contains("at most 0.9183"));
    }
}
