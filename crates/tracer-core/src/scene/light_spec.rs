//! The sidecar's serde form of lights and grids, kept apart from the model types so the file can
//! say things in the user's terms (flux or intensity, optional fields) and be checked once.
//!
//! ```toml
//! [[lights]]                 # kind defaults to "point"
//! position = [0.0, 2.9, 0.0]
//! flux_lm = 1000.0           # or intensity_cd, not both
//!
//! [[lights]]
//! kind = "spot"
//! position = [0.0, 2.9, 0.0]
//! aim = [0.0, -1.0, 0.0]
//! intensity_cd = 500.0       # on the axis
//! cone_deg = 20.0            # full intensity out to here
//! falloff_deg = 35.0         # zero from here (default: cone_deg)
//!
//! [[lights]]
//! kind = "luminaire"
//! file = "panel.ldt"         # IES or EULUMDAT, relative to the sidecar
//! position = [0.0, 2.9, 0.0]
//! shape = "rectangle"        # default "file": the file's luminous opening; "point": none
//! size = [1.2, 0.3]          # an explicit shape's sizes, scene unit
//!
//! [[grids]]
//! name = "floor"
//! origin = [0.0, 0.0, 0.0]
//! u = [4.0, 0.0, 0.0]
//! v = [0.0, 0.0, 4.0]
//! nu = 8
//! nv = 8
//! normal = [0.0, 1.0, 0.0]   # default: u × v normalised
//! ```

use crate::light::{
    Light, LightKind, Luminaire, LuminairePlacement, LuminousShape, ShapeChoice, Spot,
};
use crate::measure::Grid;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::Arc;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LightKindSpec {
    #[default]
    Point,
    Spot,
    Luminaire,
}

/// One `[[lights]]` table.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightSpec {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<LightKindSpec>,
    pub position: [f32; 3],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub intensity_cd: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flux_lm: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aim: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cone_deg: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub falloff_deg: Option<f32>,
    /// Luminaire: IES or EULUMDAT file, relative to the sidecar.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<PathBuf>,
    /// Luminaire: turn of the C planes about the aim, degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation_deg: Option<f32>,
    /// Luminaire: factor on the file's intensities (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multiplier: Option<f32>,
    /// Luminaire: its luminous opening, "file" (default), "point", "rectangle", "disc", "box"
    /// or "cylinder".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shape: Option<String>,
    /// Luminaire: an explicit shape's sizes in the scene unit (see [`LuminousShape::size`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<Vec<f32>>,
}

impl LightSpec {
    /// The model light, or why the table is wrong (`index` names it: `lights[2]`). Luminaire
    /// files are read relative to `base_dir` (the sidecar's folder).
    pub fn to_light(&self, index: usize, base_dir: Option<&Path>) -> Result<Light, String> {
        let at = format!("lights[{index}]");
        let kind = self.kind.unwrap_or_default();
        if kind == LightKindSpec::Luminaire {
            return self.to_luminaire(&at, base_dir);
        }
        if self.file.is_some()
            || self.rotation_deg.is_some()
            || self.multiplier.is_some()
            || self.shape.is_some()
            || self.size.is_some()
        {
            return Err(format!(
                "{at}: file, rotation_deg, multiplier, shape and size belong to kind = \"luminaire\""
            ));
        }
        if !self.position.iter().all(|x| x.is_finite()) {
            return Err(format!("{at}: position must be finite numbers"));
        }
        // Intensity 1 cd first; the flux or intensity given scales it below.
        let mut light = Light {
            position: self.position,
            color: self.color.unwrap_or([1.0; 3]),
            kind: LightKind::Point { intensity_cd: 1.0 },
        };
        if kind == LightKindSpec::Spot {
            light.kind = LightKind::Spot(self.spot(&at)?);
        } else if self.aim.is_some() || self.cone_deg.is_some() || self.falloff_deg.is_some() {
            return Err(format!(
                "{at}: aim, cone_deg and falloff_deg belong to kind = \"spot\""
            ));
        }
        let intensity_cd = match (self.intensity_cd, self.flux_lm) {
            (Some(_), Some(_)) => {
                return Err(format!("{at}: give intensity_cd or flux_lm, not both"));
            }
            (None, None) => return Err(format!("{at}: give intensity_cd or flux_lm")),
            (Some(i), None) => i,
            (None, Some(flux)) => {
                if !(flux.is_finite() && flux >= 0.0) {
                    return Err(format!("{at}: flux_lm must be a finite number >= 0"));
                }
                let per_cd = light.flux_lm();
                if per_cd > 0.0 { flux / per_cd } else { 0.0 }
            }
        };
        if !(intensity_cd.is_finite() && intensity_cd >= 0.0) {
            return Err(format!("{at}: intensity_cd must be a finite number >= 0"));
        }
        if let Some(cd) = light.intensity_cd_mut() {
            *cd = intensity_cd;
        }
        Ok(light)
    }

    /// The spot's shape (intensity 1 cd), checked.
    fn spot(&self, at: &str) -> Result<Spot, String> {
        let aim = self
            .aim
            .ok_or_else(|| format!("{at}: a spot needs aim = [x, y, z]"))?;
        let cone = self
            .cone_deg
            .ok_or_else(|| format!("{at}: a spot needs cone_deg (degrees)"))?;
        let falloff = self.falloff_deg.unwrap_or(cone);
        if !aim.iter().all(|x| x.is_finite()) || glam::Vec3::from(aim).length_squared() <= 0.0 {
            return Err(format!("{at}: aim must be a finite, non-zero direction"));
        }
        if !(cone.is_finite() && (0.0..=180.0).contains(&cone)) {
            return Err(format!(
                "{at}: cone_deg must be between 0 and 180, got {cone}"
            ));
        }
        if !(falloff.is_finite() && (cone..=180.0).contains(&falloff)) {
            return Err(format!(
                "{at}: falloff_deg must be between cone_deg ({cone}) and 180, got {falloff}"
            ));
        }
        Ok(Spot {
            intensity_cd: 1.0,
            aim,
            cone_deg: cone,
            falloff_deg: falloff,
        })
    }

    fn to_luminaire(&self, at: &str, base_dir: Option<&Path>) -> Result<Light, String> {
        if self.intensity_cd.is_some() || self.cone_deg.is_some() || self.falloff_deg.is_some() {
            return Err(format!(
                "{at}: a luminaire takes its intensities from its file: use multiplier or \
                 flux_lm, not intensity_cd, cone_deg or falloff_deg"
            ));
        }
        let file = self
            .file
            .as_ref()
            .ok_or_else(|| format!("{at}: a luminaire needs file = \"NAME.ies\" (or .ldt)"))?;
        let full = match base_dir {
            Some(dir) if file.is_relative() => dir.join(file),
            _ => file.clone(),
        };
        let photometry =
            crate::formats::read_photometry(&full).map_err(|e| format!("{at}: {e}"))?;
        let aim = self.aim.unwrap_or([0.0, -1.0, 0.0]);
        if !aim.iter().all(|x| x.is_finite()) || glam::Vec3::from(aim).length_squared() <= 0.0 {
            return Err(format!("{at}: aim must be a finite, non-zero direction"));
        }
        let rotation_deg = self.rotation_deg.unwrap_or(0.0);
        if !rotation_deg.is_finite() {
            return Err(format!("{at}: rotation_deg must be a finite number"));
        }
        if !self.position.iter().all(|x| x.is_finite()) {
            return Err(format!("{at}: position must be finite numbers"));
        }
        let luminaire = Luminaire::new(photometry, file.clone());
        let file_flux = luminaire.flux_lm;
        let multiplier = match (self.multiplier, self.flux_lm) {
            (Some(_), Some(_)) => {
                return Err(format!("{at}: give multiplier or flux_lm, not both"));
            }
            (Some(m), None) => m,
            (None, Some(flux)) if file_flux > 0.0 => flux / file_flux as f32,
            (None, Some(_)) => {
                return Err(format!("{at}: the file emits no light to scale to flux_lm"));
            }
            (None, None) => 1.0,
        };
        if !(multiplier.is_finite() && multiplier >= 0.0) {
            return Err(format!(
                "{at}: multiplier and flux_lm must be finite and not negative"
            ));
        }
        let shape = self.shape_choice().map_err(|e| format!("{at}: {e}"))?;
        Ok(Light {
            position: self.position,
            color: self.color.unwrap_or([1.0; 3]),
            kind: LightKind::Luminaire(LuminairePlacement {
                luminaire: Arc::new(luminaire),
                aim,
                rotation_deg,
                multiplier,
                shape,
            }),
        })
    }

    /// The luminaire's opening from `shape` and `size`.
    fn shape_choice(&self) -> Result<ShapeChoice, String> {
        match self.shape.as_deref().unwrap_or("file") {
            "file" => match self.size {
                Some(_) => Err("size belongs to an explicit shape, not shape = \"file\"".into()),
                None => Ok(ShapeChoice::File),
            },
            name => {
                let size = self.size.as_deref().unwrap_or(&[]);
                LuminousShape::from_name(name, size).map(ShapeChoice::Explicit)
            }
        }
    }

    /// The table that reproduces `light` (intensity in candela).
    pub fn from_light(light: &Light) -> LightSpec {
        let base = LightSpec {
            position: light.position,
            color: Some(light.color),
            ..LightSpec::default()
        };
        match &light.kind {
            LightKind::Point { intensity_cd } => LightSpec {
                intensity_cd: Some(*intensity_cd),
                ..base
            },
            LightKind::Spot(s) => LightSpec {
                kind: Some(LightKindSpec::Spot),
                intensity_cd: Some(s.intensity_cd),
                aim: Some(s.aim),
                cone_deg: Some(s.cone_deg),
                falloff_deg: Some(s.falloff_deg),
                ..base
            },
            LightKind::Luminaire(l) => LightSpec {
                kind: Some(LightKindSpec::Luminaire),
                aim: Some(l.aim),
                file: Some(l.luminaire.file.clone()),
                rotation_deg: Some(l.rotation_deg),
                multiplier: Some(l.multiplier),
                shape: match l.shape {
                    ShapeChoice::File => None,
                    ShapeChoice::Explicit(shape) => Some(shape.name().to_owned()),
                },
                size: match l.shape {
                    ShapeChoice::Explicit(shape) if shape != LuminousShape::Point => {
                        Some(shape.size())
                    }
                    _ => None,
                },
                ..base
            },
        }
    }
}

/// One `[[grids]]` table: an explicit rectangle (`origin`, `u`, `v`), or `work_plane = true`
/// (a horizontal rectangle at `height` over the scene's floor, `margin` in from its walls).
/// Without `nu`/`nv` the points follow EN 12464-1's automatic spacing.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    pub name: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub origin: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub u: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub v: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nu: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nv: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal: Option<[f32; 3]>,
    /// A work plane over the floor (the bottom of the scene's bounds).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub work_plane: Option<bool>,
    /// Work plane: height above the floor, scene unit (default 0.75 m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f32>,
    /// Work plane: distance kept from the walls, scene unit (default 0.5 m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub margin: Option<f32>,
    /// The activity the report checks this grid against (a key of the requirements table).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub task: Option<String>,
    /// Observers whose glare the report judges this grid by.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub observers: Vec<String>,
}

/// EN 12464-1's automatic grid spacing (m) for a rectangle whose longer side is `d_m` metres:
/// p = 0.2 × 5^log₁₀(d).
pub fn en12464_spacing_m(d_m: f32) -> f32 {
    0.2 * 5f32.powf(d_m.max(1e-6).log10())
}

/// What a work plane needs to know about the scene.
#[derive(Clone, Copy, Debug)]
pub struct GridContext {
    pub bounds: crate::Aabb,
    pub metres_per_unit: f32,
}

impl GridSpec {
    /// The grid, or why not; work planes need `context` (None: checked later, `Ok(None)`).
    pub fn to_grid(&self, context: Option<GridContext>) -> Result<Option<Grid>, String> {
        let name = &self.name;
        let (origin, u, v, normal) = if self.work_plane == Some(true) {
            if self.origin.is_some() || self.u.is_some() || self.v.is_some() {
                return Err(format!(
                    "grid {name}: a work plane takes height and margin, not origin, u and v"
                ));
            }
            let Some(ctx) = context else {
                return Ok(None);
            };
            let in_units = |metres: f64| (metres / f64::from(ctx.metres_per_unit)) as f32;
            let height = self.height.unwrap_or(in_units(0.75));
            let margin = self.margin.unwrap_or(in_units(0.5));
            if !(height.is_finite() && margin.is_finite() && margin >= 0.0) {
                return Err(format!(
                    "grid {name}: height and margin must be finite, margin >= 0"
                ));
            }
            let b = ctx.bounds;
            let (sx, sz) = (b.extent().x - 2.0 * margin, b.extent().z - 2.0 * margin);
            if sx <= 0.0 || sz <= 0.0 {
                return Err(format!(
                    "grid {name}: the wall margin {margin} leaves no area"
                ));
            }
            let origin = [b.min.x + margin, b.min.y + height, b.min.z + margin];
            (
                origin,
                [sx, 0.0, 0.0],
                [0.0, 0.0, sz],
                Some(self.normal.unwrap_or([0.0, 1.0, 0.0])),
            )
        } else {
            if self.height.is_some() || self.margin.is_some() {
                return Err(format!(
                    "grid {name}: height and margin belong to work_plane = true"
                ));
            }
            match (self.origin, self.u, self.v) {
                (Some(o), Some(u), Some(v)) => (o, u, v, self.normal),
                _ => {
                    return Err(format!(
                        "grid {name}: give origin, u and v (a rectangle), or work_plane = true"
                    ));
                }
            }
        };
        let (nu, nv) = match (self.nu, self.nv) {
            (Some(a), Some(b)) => (a, b),
            (None, None) => {
                // EN 12464-1 spacing needs metres: without a context assume metres.
                let mpu = context.map_or(1.0, |c| c.metres_per_unit);
                let (lu, lv) = (
                    glam::Vec3::from(u).length() * mpu,
                    glam::Vec3::from(v).length() * mpu,
                );
                if !(lu.is_finite() && lv.is_finite()) {
                    return Err(format!(
                        "grid {name}: origin, u and v must be finite numbers"
                    ));
                }
                let p = en12464_spacing_m(lu.max(lv));
                let count = |l: f32| ((l / p).ceil() as u32).clamp(1, 1000);
                (count(lu), count(lv))
            }
            _ => return Err(format!("grid {name}: give both nu and nv, or neither")),
        };
        Grid::new(name, origin, u, v, nu, nv, normal)
            .map(|g| {
                Some(Grid {
                    task: self.task.clone(),
                    observers: self.observers.clone(),
                    ..g
                })
            })
            .map_err(|e| e.to_string())
    }

    pub fn from_grid(g: &Grid) -> GridSpec {
        GridSpec {
            name: g.name.clone(),
            origin: Some(g.origin),
            u: Some(g.u),
            v: Some(g.v),
            nu: Some(g.nu),
            nv: Some(g.nv),
            normal: Some(g.normal),
            task: g.task.clone(),
            observers: g.observers.clone(),
            ..GridSpec::default()
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    fn spec(text: &str) -> LightSpec {
        toml::from_str(text).unwrap_or_default()
    }

    #[test]
    fn flux_and_intensity_are_exclusive_and_convert() {
        let both = spec("position = [0.0, 0.0, 0.0]\nintensity_cd = 1.0\nflux_lm = 2.0");
        assert!(
            both.to_light(0, None)
                .is_err_and(|e| e.contains("not both"))
        );
        let flux = spec("position = [0.0, 0.0, 0.0]\nflux_lm = 1000.0");
        let l = flux.to_light(0, None).unwrap_or_default();
        assert!(
            (l.intensity_cd().unwrap_or(0.0) - 1000.0 / (4.0 * std::f32::consts::PI)).abs() < 1e-3
        );
        let spot = spec(
            "kind = \"spot\"\nposition = [0.0, 0.0, 0.0]\naim = [0.0, -1.0, 0.0]\n\
             intensity_cd = 10.0\ncone_deg = 10.0\nfalloff_deg = 5.0",
        );
        assert!(
            spot.to_light(3, None)
                .is_err_and(|e| e.starts_with("lights[3]"))
        );
        let point_with_aim =
            spec("position = [0.0, 0.0, 0.0]\nintensity_cd = 1.0\naim = [0.0, 1.0, 0.0]");
        assert!(point_with_aim.to_light(0, None).is_err());
    }
}
