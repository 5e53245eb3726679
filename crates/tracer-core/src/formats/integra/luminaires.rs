//! `.lgt` fixtures as neutral lights. Each `Fixture` that is switched on (and whose groups are)
//! places its `Light`: an isotropic point of `TotalFlux` lm times the groups' `Power` %, tinted
//! by `intensity`, or the `Diagram` it names, aimed along `Direction` and turned by `Rotation`.
//! A diagram's `theta N` values span 0–180° in N − 1 steps from the aim; tables do not
//! integrate to their `NormalFlux`, so they are scaled by `TotalFlux / NormalFlux`.

use super::error::IntegraError;
use super::lgt::{Diagram, Fixture, Lgt, LgtLight};
use crate::formats::description::{LightDescription, LightDistribution};
use crate::light::{Photometry, Plane};
use std::path::Path;

/// The lights the fixtures place; what is skipped or drawn otherwise is noted in `notes`.
pub fn lights_from_lgt(
    lgt: &Lgt,
    path: &Path,
    notes: &mut Vec<String>,
) -> Result<Vec<LightDescription>, IntegraError> {
    let mut out = Vec::new();
    let mut used_diagrams: Vec<&str> = Vec::new();
    for fixture in &lgt.fixtures {
        let Some(light_ref) = &fixture.light else {
            return Err(IntegraError::new(
                path,
                fixture.line,
                format!("fixture {} names no `Light`", fixture.name),
            ));
        };
        let Some(light) = lgt.lights.iter().find(|l| l.name == light_ref.name) else {
            return Err(IntegraError::new(
                path,
                light_ref.line,
                format!(
                    "fixture {} uses light {}, which the file does not define",
                    fixture.name, light_ref.name
                ),
            ));
        };
        let (on, power) = switch_and_power(lgt, fixture);
        if !on {
            notes.push(format!(
                "{}:{}: fixture {} is switched off: not lit",
                path.display(),
                fixture.line,
                fixture.name
            ));
            continue;
        }
        let Some(position) = fixture.position else {
            return Err(IntegraError::new(
                path,
                fixture.line,
                format!("fixture {} has no `Position`", fixture.name),
            ));
        };
        let flux_lm = light_flux(light, path)? * power;
        let distribution = match &light.diagram {
            Some(d) => {
                used_diagrams.push(&d.name);
                diagram_distribution(lgt, light, path, flux_lm, notes)?
            }
            None => LightDistribution::Isotropic {
                intensity_cd: isotropic_cd(flux_lm),
            },
        };
        note_unsupported(light, path, notes);
        out.push(LightDescription {
            name: fixture.name.clone(),
            source: path.to_owned(),
            line: fixture.line,
            position: position.map(|x| x as f32),
            aim: fixture
                .direction
                .filter(|d| d.iter().any(|&x| x != 0.0))
                .unwrap_or([0.0, -1.0, 0.0])
                .map(|x| x as f32),
            rotation_deg: fixture.rotation.unwrap_or(0.0) as f32,
            color: light.intensity.unwrap_or([1.0; 3]).map(|x| x as f32),
            distribution,
        });
    }
    let mut skipped: Vec<String> = lgt
        .skipped
        .iter()
        .map(|(k, n, _)| format!("{k} {n}"))
        .collect();
    skipped.extend(
        lgt.diagrams
            .iter()
            .filter(|d| !used_diagrams.contains(&d.name.as_str()))
            .map(|d| format!("Diagram {}", d.name)),
    );
    if !skipped.is_empty() {
        notes.push(format!(
            "{}: not used, skipped: {}",
            path.display(),
            skipped.join(", ")
        ));
    }
    Ok(out)
}

/// Whether the fixture is lit (its own switch and every group's), and the groups' power
/// factor (1 = 100 %).
fn switch_and_power(lgt: &Lgt, fixture: &Fixture) -> (bool, f64) {
    let mut on = fixture.switch.unwrap_or(true);
    let mut power = 1.0;
    for group in &lgt.groups {
        if group.members.iter().any(|m| m.name == fixture.name) {
            on &= group.switch.unwrap_or(true);
            power *= group.power_percent.unwrap_or(100.0) / 100.0;
        }
    }
    (on, power)
}

fn light_flux(light: &LgtLight, path: &Path) -> Result<f64, IntegraError> {
    match light.total_flux {
        Some(f) if f >= 0.0 => Ok(f),
        Some(f) => Err(IntegraError::new(
            path,
            light.line,
            format!(
                "light {}: `TotalFlux` must not be negative, found {f}",
                light.name
            ),
        )),
        None => Err(IntegraError::new(
            path,
            light.line,
            format!("light {} has no `TotalFlux` (lm)", light.name),
        )),
    }
}

/// Features of a light raygine does not draw, each said once per light.
fn note_unsupported(light: &LgtLight, path: &Path, notes: &mut Vec<String>) {
    let note = format!("{}:{}: light {}: ", path.display(), light.line, light.name);
    if let Some(kind) = &light.kind
        && !kind.name.eq_ignore_ascii_case("point")
    {
        let msg = format!("type `{}` is not supported; drawn as a point", kind.name);
        push_once(notes, note.clone() + &msg);
    }
    if let Some((true, _)) = light.spot {
        let msg = "`SpotLight on` is not supported (the file gives no cone); drawn without it";
        push_once(notes, note + msg);
    }
}

fn push_once(notes: &mut Vec<String>, note: String) {
    if !notes.contains(&note) {
        notes.push(note);
    }
}

/// The distribution of a light that names a diagram (isotropic, with a note, when the diagram
/// is of a kind raygine does not read).
fn diagram_distribution(
    lgt: &Lgt,
    light: &LgtLight,
    path: &Path,
    flux_lm: f64,
    notes: &mut Vec<String>,
) -> Result<LightDistribution, IntegraError> {
    let Some(reference) = &light.diagram else {
        return Ok(LightDistribution::Isotropic {
            intensity_cd: isotropic_cd(flux_lm),
        });
    };
    let Some(diagram) = lgt.diagrams.iter().find(|d| d.name == reference.name) else {
        return Err(IntegraError::new(
            path,
            reference.line,
            format!(
                "light {} uses diagram {}, which the file does not define",
                light.name, reference.name
            ),
        ));
    };
    match diagram_photometry(diagram, flux_lm) {
        Ok(photometry) => Ok(LightDistribution::Goniometric {
            photometry,
            label: format!("{}#{}", path.display(), diagram.name),
        }),
        Err(why) => {
            push_once(
                notes,
                format!(
                    "{}:{}: diagram {} (used by light {}): {why}; drawn as an isotropic point",
                    path.display(),
                    diagram.line,
                    diagram.name,
                    light.name
                ),
            );
            Ok(LightDistribution::Isotropic {
                intensity_cd: isotropic_cd(flux_lm),
            })
        }
    }
}

/// An axially symmetric diagram as a distribution in candela: `theta N` angles from 0 to 180°,
/// values scaled by `flux_lm / NormalFlux`.
/// The intensity (cd) of an isotropic source of `flux_lm`: Φ / 4π.
fn isotropic_cd(flux_lm: f64) -> f32 {
    flux_lm as f32 / (4.0 * std::f32::consts::PI)
}

pub fn diagram_photometry(d: &Diagram, flux_lm: f64) -> Result<Photometry, String> {
    if d.composed.is_some() {
        return Err("composed diagrams (tables by angle) are not supported".into());
    }
    if !d
        .kind
        .as_deref()
        .is_some_and(|k| k.eq_ignore_ascii_case("AxiSymmetrical"))
    {
        return Err(format!(
            "type `{}` is not supported (only AxiSymmetrical)",
            d.kind.as_deref().unwrap_or("(none)")
        ));
    }
    let theta = d.theta.unwrap_or(0) as usize;
    if d.phi.unwrap_or(1) != 1 || theta < 2 || d.values.len() != theta {
        return Err(
            "an AxiSymmetrical table needs `phi 1` and `theta` of at least 2 values".into(),
        );
    }
    let normal = d.normal_flux.unwrap_or(0.0);
    if normal <= 0.0 {
        return Err("`NormalFlux` must be above 0".into());
    }
    let step = 180.0 / (theta - 1) as f64;
    let gamma_deg = (0..theta).map(|i| (i as f64 * step) as f32).collect();
    let scale = flux_lm / normal;
    let cd = d.values.iter().map(|v| (v * scale) as f32).collect();
    Photometry::from_planes(
        gamma_deg,
        vec![Plane { c_deg: 0.0, cd }],
        crate::light::LuminousShape::Point,
    )
    .map_err(|e| e.to_string())
}
