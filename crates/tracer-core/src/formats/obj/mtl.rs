//! MTL materials in raygine's model. The mapping (also in `docs/formats.md`):
//!
//! | MTL | raygine |
//! |-----|---------|
//! | `Kd` | diffuse reflectance Kd, times the opacity `d` |
//! | `Ks`, `Ns` > 0 | the normalised Blinn-Phong lobe: Ks (times `d`), glossiness g = Ns |
//! | `Ks`, `Ns` 0 or absent, `illum` 3-7 | a mirror of reflectance Ks |
//! | `Ks`, `Ns` 0 or absent, other `illum` | no lobe (noted) |
//! | `d` < 1 (or `Tr` > 0) | clear transmission Kt = 1 − d with index `Ni` (default 1: a thin sheet) |
//! | `Ke` | a Lambertian emitter of luminance `emission_scale` × Y(Ke) cd/m² (noted) |
//! | `Pr`, `Pm` (the PBR extension) | glTF's metallic-roughness model instead of the lobes above: base colour Kd, roughness Pr (default 1), metallic Pm (default 0), transmission 1 − d, F0 from `Ni` (default 1.5) |
//! | `Ka` | not used |
//! | texture maps | see `super::maps` |
//!
//! MTL's Ks with Ns is the legacy, unnormalised Phong highlight; raygine's lobe is normalised,
//! so a highlight's peak differs while Ks stays the fraction of light the lobe reflects.

use crate::formats::error::FormatError;
use crate::formats::{
    EmissionDescription, MaterialDescription, MetalRoughDescription, TransmissionDescription,
};
use crate::light::EmissionSides;
use std::collections::HashMap;
use std::path::Path;

/// Checks an MTL file line by line (numbers that tobj would reject or read as NaN) and returns
/// the line of each `newmtl`.
pub(super) fn check(bytes: &[u8], path: &Path) -> Result<HashMap<String, usize>, FormatError> {
    let mut lines = HashMap::new();
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = i + 1;
        let text = std::str::from_utf8(raw.strip_suffix(b"\r").unwrap_or(raw))
            .map_err(|_| FormatError::new(path, line, "not UTF-8 text"))?;
        let text = text.split('#').next().unwrap_or("").trim();
        let mut words = text.split_whitespace();
        let Some(key) = words.next() else { continue };
        let rest: Vec<&str> = words.collect();
        let want = match key {
            "Ka" | "Kd" | "Ks" | "Ke" => 3,
            "Ns" | "Ni" | "d" | "Tr" | "Pr" | "Pm" => 1,
            "illum" => {
                if rest.len() != 1 || rest[0].parse::<u8>().is_err() {
                    return Err(FormatError::new(
                        path,
                        line,
                        format!(
                            "illum takes a whole number 0-10, found `{}`",
                            rest.join(" ")
                        ),
                    ));
                }
                continue;
            }
            "newmtl" => {
                let name = text["newmtl".len()..].trim();
                if name.is_empty() {
                    return Err(FormatError::new(path, line, "newmtl needs a material name"));
                }
                lines.entry(name.to_owned()).or_insert(line);
                continue;
            }
            _ => continue,
        };
        let ok = rest.len() == want
            && rest
                .iter()
                .all(|w| w.parse::<f32>().is_ok_and(f32::is_finite));
        if !ok {
            return Err(FormatError::new(
                path,
                line,
                format!(
                    "{key} takes {want} finite number{}, found `{}`",
                    if want > 1 { "s" } else { "" },
                    rest.join(" ")
                ),
            ));
        }
    }
    Ok(lines)
}

/// One MTL material as raygine's model; findings go to `notes`.
pub(super) fn to_description(
    m: &tobj::Material,
    source: &Path,
    line: usize,
    emission_scale: f32,
    notes: &mut Vec<String>,
) -> MaterialDescription {
    let at = format!("{}:{line}: material {}", source.display(), m.name);
    let d = m
        .dissolve
        .or_else(|| {
            m.unknown_param
                .get("Tr")
                .and_then(|t| t.trim().parse::<f32>().ok())
                .map(|tr| 1.0 - tr)
        })
        .unwrap_or(1.0)
        .clamp(0.0, 1.0);
    let kd = m.diffuse.unwrap_or([0.8; 3]).map(|c| c * d);
    let ks = m.specular.unwrap_or([0.0; 3]).map(|c| c * d);
    let ns = m.shininess.unwrap_or(0.0).max(0.0);
    let mirror_illum = m.illumination_model.is_some_and(|i| (3..=7).contains(&i));
    let has_ks = ks.iter().any(|&c| c > 0.0);
    let (specular, glossiness) = if !has_ks {
        ([0.0; 3], 0.0)
    } else if ns > 0.0 {
        (ks, ns)
    } else if mirror_illum {
        (ks, 0.0)
    } else {
        notes.push(format!(
            "{at}: Ks without Ns (and illum {}) is neither a highlight nor a mirror; not drawn",
            m.illumination_model
                .map_or("absent".to_owned(), |i| i.to_string())
        ));
        ([0.0; 3], 0.0)
    };
    let transmission = (d < 1.0).then(|| TransmissionDescription {
        specular: 1.0 - d,
        diffuse: 0.0,
        ior: m
            .optical_density
            .filter(|n| n.is_finite() && *n > 0.0)
            .unwrap_or(1.0),
    });
    let emission = m.emissive.and_then(|ke| {
        EmissionDescription::from_unitless(
            ke,
            emission_scale,
            EmissionSides::Both,
            &at,
            "Ke",
            notes,
        )
    });
    let maps = super::maps::maps(m, source, &at, notes);
    let number = |key: &str| {
        m.unknown_param
            .get(key)
            .and_then(|t| t.trim().parse::<f32>().ok())
            .filter(|x| x.is_finite())
    };
    let (pr, pm) = (number("Pr"), number("Pm"));
    let metal_rough = (pr.is_some() || pm.is_some()).then(|| MetalRoughDescription {
        base_color: m.diffuse.unwrap_or([0.8; 3]).map(|c| c.clamp(0.0, 1.0)),
        metallic: pm.unwrap_or(0.0).clamp(0.0, 1.0),
        roughness: pr.unwrap_or(1.0).clamp(0.0, 1.0),
        transmission: 1.0 - d,
        ior: m
            .optical_density
            .filter(|n| n.is_finite() && *n > 0.0)
            .unwrap_or(1.5),
    });
    MaterialDescription {
        name: m.name.clone(),
        source: source.to_owned(),
        line,
        diffuse: kd,
        specular,
        glossiness,
        transmission,
        emission,
        metal_rough,
        maps: (!maps.is_empty()).then(|| Box::new(maps)),
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    fn material(text: &str) -> (MaterialDescription, Vec<String>) {
        let (mats, _) = tobj::load_mtl_buf(&mut text.as_bytes()).expect("mtl");
        let mut notes = Vec::new();
        let d = to_description(&mats[0], Path::new("m.mtl"), 1, 2.0, &mut notes);
        (d, notes)
    }

    #[test]
    fn kd_ks_ns_d_ni_and_ke_map_as_documented() {
        let (m, notes) =
            material("newmtl a\nKd 0.5 0.4 0.3\nKs 0.2 0.2 0.2\nNs 50\nd 0.5\nNi 1.5\nKe 1 1 1\n");
        assert_eq!(m.diffuse, [0.25, 0.2, 0.15]);
        assert_eq!(m.specular, [0.1; 3]);
        assert_eq!(m.glossiness, 50.0);
        let t = m.transmission.expect("d < 1");
        assert_eq!((t.specular, t.ior), (0.5, 1.5));
        let e = m.emission.expect("Ke");
        assert!((e.luminance_cd_m2 - 2.0).abs() < 1e-5);
        assert_eq!(notes.len(), 1, "{notes:?}");
    }

    #[test]
    fn pr_and_pm_give_the_metallic_roughness_model() {
        let (m, _) = material("newmtl a\nKd 0.9 0.6 0.3\nPr 0.35\nPm 1\nNi 1.4\n");
        let mr = m.metal_rough.expect("Pr, Pm");
        assert_eq!(mr.base_color, [0.9, 0.6, 0.3]);
        assert_eq!((mr.metallic, mr.roughness, mr.ior), (1.0, 0.35, 1.4));
        assert_eq!(mr.transmission, 0.0);
        // Either key alone: the other takes its default (metallic 0, roughness 1).
        let (m, _) = material("newmtl a\nKd 0.5 0.5 0.5\nPr 0.2\nd 0.75\n");
        let mr = m.metal_rough.expect("Pr");
        assert_eq!(
            (mr.metallic, mr.roughness, mr.transmission),
            (0.0, 0.2, 0.25)
        );
        let (m, _) = material("newmtl a\nKd 0.5 0.5 0.5\nKs 0.1 0.1 0.1\nNs 20\n");
        assert!(m.metal_rough.is_none());
        let e = check(b"newmtl a\nPr rough\n", Path::new("m.mtl")).expect_err("bad");
        assert_eq!(
            e.to_string(),
            "m.mtl:2: Pr takes 1 finite number, found `rough`"
        );
    }

    #[test]
    fn ks_without_ns_is_a_mirror_only_for_the_reflective_illumination_models() {
        let (m, _) = material("newmtl a\nKs 0.9 0.9 0.9\nillum 3\n");
        assert_eq!((m.specular, m.glossiness), ([0.9; 3], 0.0));
        let (m, notes) = material("newmtl a\nKs 0.9 0.9 0.9\nillum 2\n");
        assert_eq!(m.specular, [0.0; 3]);
        assert_eq!(notes.len(), 1);
    }

    #[test]
    fn bad_numbers_are_reported_with_their_line() {
        let e = check(b"newmtl a\nKd 0.5 x 0.3\n", Path::new("m.mtl")).expect_err("bad");
        assert_eq!(
            e.to_string(),
            "m.mtl:2: Kd takes 3 finite numbers, found `0.5 x 0.3`"
        );
        let e = check(b"newmtl a\nNs inf\n", Path::new("m.mtl")).expect_err("bad");
        assert_eq!(
            e.to_string(),
            "m.mtl:2: Ns takes 1 finite number, found `inf`"
        );
    }
}
