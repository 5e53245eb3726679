//! The human-editable sidecar `NAME.raygine.toml` next to `NAME.shp`: materials, lights, camera,
//! scene unit and handedness. Everything is optional; what is absent comes from the defaults.
//!
//! ```toml
//! unit = "mm"            # mm, cm or m
//! handedness = "left"    # left (Lumicept files) or right (OBJ, glTF)
//! smooth_angle_deg = 45  # crease angle of averaged vertex normals; 0: flat shading
//! emission_scale = 1.0   # cd/m² per unit of OBJ Ke / glTF emissive / USD emissiveColor
//! usd_time = 24.0        # the USD time code attributes are read at (default: their defaults)
//!
//! [camera]
//! position = [278.0, 273.0, 800.0]
//! look_at = [278.0, 273.0, -280.0]
//! fov_deg = 40.0               # vertical; a fisheye's across its circle, at most 180
//! projection = "perspective"   # fisheye-equidistant, fisheye-equisolid, hemispherical,
//!                              # equirectangular, orthographic (with width = scene units)
//!
//! [[lights]]
//! position = [278.0, 548.7, -279.5]
//! intensity_cd = 100.0
//! color = [1.0, 1.0, 1.0]
//!
//! [default_material]     # slots not named below
//! kd = [0.7, 0.7, 0.7]
//!
//! [materials.brs_1]      # every part of brep brs_1; "brs_1/2" names part 2 only; parts
//!                        # a format names also take their name ("room2/proom2_0003")
//! kd = [0.14, 0.45, 0.091]
//! ks = [0.0, 0.0, 0.0]
//! glossiness = 0.0
//! ```

use super::camera::Camera;
use super::environment_spec::EnvironmentSpec;
use super::error::SceneError;
use super::geometry::Scene;
use super::light_spec::{GridContext, GridSpec, LightSpec};
use super::material::Material;
use super::setup::Setup;
use super::units::{Handedness, LengthUnit};
use crate::light::Light;
use crate::measure::{Grid, GridError};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sidecar {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unit: Option<LengthUnit>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub handedness: Option<Handedness>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<Camera>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lights: Option<Vec<LightSpec>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub default_material: Option<Material>,
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub materials: BTreeMap<String, Material>,
    /// Breps (or `brep/part` keys) that are not drawn.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hidden: Vec<String>,
    /// Calculation grids (sensor rectangles).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub grids: Vec<GridSpec>,
    /// Crease angle for vertex normals averaged where the file has none, degrees (default
    /// 45); 0 shades every triangle flat, the file's own normals included.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub smooth_angle_deg: Option<f32>,
    /// Luminance of OBJ `Ke` and glTF emissive (times its strength) per unit, cd/m² (default
    /// 1: glTF's emissive read as nits). Those formats give emission no photometric unit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emission_scale: Option<f32>,
    /// The USD time code attributes are read at (None: their default values).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub usd_time: Option<f64>,
    /// Maintenance factor of measured illuminance (0 < MF <= 1; default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub maintenance_factor: Option<f32>,
    /// Light from every direction at infinity: a map or a uniform sky.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub environment: Option<EnvironmentSpec>,
    /// The environment as read by `parse` (its map loaded once), with its notes.
    #[serde(skip)]
    pub environment_model: Option<(crate::light::Environment, Vec<String>)>,
    /// `[daylight]`: place, local time and orientation (the sun's position).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub daylight: Option<crate::light::daylight::DaylightSpec>,
    /// Eyes where glare is judged: `[[observers]]` with name, position, direction, up.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub observers: Vec<super::observer::Observer>,
    /// The sidecar's folder: luminaire files are relative to it (not part of the file).
    #[serde(skip)]
    pub base_dir: Option<PathBuf>,
    /// The file and text it was read from, so notes name their line (not part of the file).
    #[serde(skip)]
    pub source: Option<super::notes::SourceText>,
}

fn set_material(
    setup: &mut Setup,
    slots: &[u32],
    m: &Material,
    key: &str,
    warnings: &mut Vec<String>,
) {
    let (clamped, changed) = m.clamped();
    if changed {
        warnings.push(format!(
            "material {key}: clamped into range (0..1, Kd + Ks <= 1 per channel)"
        ));
    }
    for &s in slots {
        if let Some(slot) = setup.materials.get_mut(s as usize) {
            // The file's textures stay: the sidecar sets the factors they multiply.
            *slot = Material {
                textures: slot.textures,
                ..clamped
            };
        }
    }
}

fn camera_is_finite(c: &Camera) -> bool {
    [c.position, c.look_at, c.up]
        .iter()
        .flatten()
        .all(|x| x.is_finite())
        && c.fov_deg.is_finite()
        && c.width.is_none_or(f32::is_finite)
}

/// The sidecar path for a scene file: `room.shp` -> `room.raygine.toml`.
pub fn sidecar_path(scene_path: &Path) -> PathBuf {
    scene_path.with_extension("raygine.toml")
}

impl Sidecar {
    /// Parses sidecar text; errors name the file, line and column (toml's message).
    pub fn parse(text: &str, path: &Path) -> Result<Sidecar, SceneError> {
        let mut sidecar: Sidecar = toml::from_str(text).map_err(|e| SceneError::Sidecar {
            path: path.to_owned(),
            message: toml_error_message(text, &e),
        })?;
        sidecar.base_dir = path.parent().map(Path::to_path_buf);
        sidecar.source = Some(super::notes::SourceText {
            path: path.to_owned(),
            text: text.to_owned(),
        });
        let invalid = |message: String| SceneError::Sidecar {
            path: path.to_owned(),
            message,
        };
        sidecar.model_lights().map_err(invalid)?;
        sidecar.model_grids(None).map_err(invalid)?;
        if let Some(camera) = &sidecar.camera
            && camera_is_finite(camera)
            && let Err(message) = camera.check()
        {
            // The message names its key; point at that key's line, else at the table's.
            let key = if message.contains("width") {
                "width"
            } else {
                "fov_deg"
            };
            let line = key_line(text, "camera", key).or_else(|| table_line(text, "camera"));
            return Err(match line {
                Some(line) => invalid(format!("line {line}: {message}")),
                None => invalid(message),
            });
        }
        if let Some(spec) = &sidecar.daylight {
            // Its errors name their key; the table's line says where it is.
            let at_daylight = |message: String| match table_line(text, "daylight") {
                Some(line) => invalid(format!("line {line}: {message}")),
                None => invalid(message),
            };
            let daylight = spec.to_model().map_err(at_daylight)?;
            if daylight.sky.is_some() && sidecar.environment.is_some() {
                return Err(invalid(
                    "give [environment] or a [daylight] sky, not both: the sky is the \
                     environment light"
                        .into(),
                ));
            }
        }
        if let Some(spec) = &sidecar.environment {
            let base = sidecar.base_dir.clone();
            sidecar.environment_model = Some(spec.to_model(base.as_deref()).map_err(invalid)?);
        }
        if let Err(message) = super::observer::check_observers(&sidecar.observers) {
            // Point at the observer's own table when its name is there.
            let line = sidecar
                .observers
                .iter()
                .position(|o| message.contains(&format!("observer {}", o.name)))
                .and_then(|i| nth_line(text, "[[observers]]", i));
            return Err(match line {
                Some(line) => invalid(format!("line {line}: {message}")),
                None => invalid(message),
            });
        }
        if let Some(mf) = sidecar.maintenance_factor
            && !(mf.is_finite() && mf > 0.0 && mf <= 1.0)
        {
            return Err(invalid(format!(
                "maintenance_factor must be above 0 and at most 1, got {mf}"
            )));
        }
        Ok(sidecar)
    }

    /// The lights as model values, or the first table's problem.
    pub fn model_lights(&self) -> Result<Option<Vec<Light>>, String> {
        self.lights
            .as_ref()
            .map(|specs| {
                specs
                    .iter()
                    .enumerate()
                    .map(|(i, s)| s.to_light(i, self.base_dir.as_deref()))
                    .collect::<Result<Vec<_>, _>>()
            })
            .transpose()
    }

    /// The grids as model values, or the first grid's problem (duplicate names too). Work
    /// planes need `context` (the scene's bounds and unit); without it they are only checked.
    pub fn model_grids(&self, context: Option<GridContext>) -> Result<Vec<Grid>, String> {
        let mut grids: Vec<Grid> = Vec::with_capacity(self.grids.len());
        for spec in &self.grids {
            let Some(g) = spec.to_grid(context)? else {
                continue;
            };
            if grids.iter().any(|o| o.name == g.name) {
                return Err(GridError::Duplicate(g.name).to_string());
            }
            grids.push(g);
        }
        Ok(grids)
    }

    /// Reads the sidecar if the file exists (`Ok(None)` when it does not).
    pub fn read_if_present(path: &Path) -> Result<Option<Sidecar>, SceneError> {
        match std::fs::read_to_string(path) {
            Ok(text) => Self::parse(&text, path).map(Some),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(error) => Err(SceneError::SidecarIo {
                path: path.to_owned(),
                error,
            }),
        }
    }

    /// The setup this sidecar gives `scene`: the defaults overridden by what the sidecar says.
    /// `unit_override` (the CLI's `--units`) wins over the sidecar. Problems that do not stop a
    /// render (an unknown brep name, a material clamped into range) are pushed to `warnings`.
    pub fn apply(
        &self,
        scene: &Scene,
        unit_override: Option<LengthUnit>,
        warnings: &mut Vec<String>,
    ) -> Setup {
        let unit = unit_override
            .or(self.unit)
            .or(scene.design.unit)
            .unwrap_or_default();
        let first_note = warnings.len();
        let mut setup = Setup::defaults(scene, unit);
        if let Some(h) = self.handedness {
            setup.handedness = h;
        }
        if let Some(c) = self.camera {
            if camera_is_finite(&c) {
                setup.camera = c;
            } else {
                // A NaN or infinite camera renders nothing at all: keep the framing camera.
                warnings.push(
                    "camera: position, look_at, up and fov_deg must be finite numbers; \
                     using the default camera"
                        .to_string(),
                );
            }
        }
        match self.model_lights() {
            Ok(Some(lights)) => setup.lights = lights,
            Ok(None) => {}
            Err(e) => warnings.push(format!("{e}; using the default light")),
        }
        let context = GridContext {
            bounds: scene.bounds,
            metres_per_unit: setup.unit.metres_per_unit(),
        };
        setup.maintenance_factor = self.maintenance_factor.unwrap_or(1.0);
        let environment = match (&self.environment_model, &self.environment) {
            (Some(read), _) => Ok(Some(read.clone())),
            (None, Some(spec)) => spec.to_model(self.base_dir.as_deref()).map(Some),
            (None, None) => Ok(None),
        };
        match environment {
            Ok(Some((env, notes))) => {
                setup.environment = Some(env);
                warnings.extend(notes);
            }
            Ok(None) => {}
            Err(e) => warnings.push(format!("{e}; no environment")),
        }
        // The sidecar's [daylight] replaces the file's (Integra's Geography).
        match self.daylight.as_ref().map(|d| d.to_model()).transpose() {
            Ok(Some(daylight)) => {
                // A sky is the environment light.
                let right_handed = setup.handedness == Handedness::Right;
                if let Some(env) = daylight.sky_environment(right_handed) {
                    setup.environment = Some(env);
                }
                // A daylit scene without lights of its own is lit by the daylight alone, not by
                // the default light a scene without lights gets.
                let daylit = daylight.sky.is_some() || daylight.sun_normal_illuminance_lx.is_some();
                if daylit && self.lights.is_none() && scene.design.lights.is_none() {
                    setup.lights.clear();
                }
                let below = daylight.sun().altitude_deg <= 0.0;
                if below && daylight.sky.is_some() {
                    warnings.push(format!(
                        "daylight: the sun is below the horizon at {} {}; the sky keeps the \
                         luminance given (raygine has no night or twilight sky)",
                        daylight.place_time.date, daylight.place_time.time
                    ));
                }
                if daylight.spec.direct_normal_lx.is_some() && !daylight.spec.sun {
                    warnings.push(
                        "daylight: the Perez sky lights no sun unless sun = true (its \
                         direct_normal_lx shapes the sky only)"
                            .into(),
                    );
                }
                if daylight.sun_normal_illuminance_lx.is_some()
                    && daylight.sun_disc(right_handed).is_none()
                {
                    warnings.push(format!(
                        "daylight: the sun is below the horizon at {} {} (altitude {:.1}°)",
                        daylight.place_time.date,
                        daylight.place_time.time,
                        daylight.sun().altitude_deg
                    ));
                }
                setup.daylight = Some(daylight);
            }
            Ok(None) => {}
            Err(e) => warnings.push(format!("{e}; no daylight")),
        }
        match self.model_grids(Some(context)) {
            Ok(grids) => setup.grids = grids,
            Err(e) => warnings.push(format!("{e}; grids ignored")),
        }
        // (Checked by `parse`.)
        setup.observers = self.observers.clone();
        if let Some(m) = &self.default_material {
            let all: Vec<u32> = (0..scene.slots.len() as u32).collect();
            set_material(&mut setup, &all, m, "default_material", warnings);
        }
        // Whole-brep keys first, so "brep/part" keys refine them.
        let (whole, parts): (Vec<_>, Vec<_>) =
            self.materials.iter().partition(|(k, _)| !k.contains('/'));
        for (key, m) in whole.into_iter().chain(parts) {
            match scene.slots_for_key(key) {
                Some(slots) => set_material(&mut setup, &slots, m, key, warnings),
                None => warnings.push(format!(
                    "material {key}: the scene has no such brep or part"
                )),
            }
        }
        for key in &self.hidden {
            match scene.slots_for_key(key) {
                Some(slots) => slots.iter().for_each(|&s| setup.hidden[s as usize] = true),
                None => warnings.push(format!("hidden {key}: the scene has no such brep or part")),
            }
        }
        for (i, light) in setup.lights.iter().enumerate() {
            if let Some(note) = super::notes::luminaire_near_surface(scene, &setup, i) {
                warnings.push(note);
            }
            if let Some(note) = super::notes::luminaire_shape(&setup, i) {
                warnings.push(note);
            }
            if !light.is_valid() {
                warnings.push(format!(
                    "Light {}: position and intensity must be finite, intensity >= 0",
                    i + 1
                ));
            }
        }
        if let Some(source) = &self.source {
            for note in &mut warnings[first_note..] {
                *note = source.place(note);
            }
        }
        setup
    }

    /// The sidecar that reproduces `setup` for `scene` (every brep's material written out).
    pub fn from_setup(scene: &Scene, setup: &Setup) -> Sidecar {
        let mut materials = BTreeMap::new();
        let mut hidden = Vec::new();
        // The viewer's ground plane is a view aid, not part of the scene's file.
        let breps = match scene.has_ground() {
            true => &scene.breps[..scene.breps.len() - 1],
            false => &scene.breps[..],
        };
        for brep in breps {
            let range = brep.first_slot as usize..(brep.first_slot + brep.part_count) as usize;
            let Some(mats) = setup.materials.get(range.clone()) else {
                continue;
            };
            if mats.iter().all(|m| *m == mats[0]) {
                materials.insert(brep.name.clone(), mats[0]);
            } else {
                for (part, m) in mats.iter().enumerate() {
                    let label = brep.part_label(part as u32);
                    materials.insert(format!("{}/{label}", brep.name), *m);
                }
            }
            let hid = &setup.hidden[range];
            if hid.iter().all(|&h| h) {
                hidden.push(brep.name.clone());
            } else {
                for (part, _) in hid.iter().enumerate().filter(|(_, h)| **h) {
                    let label = brep.part_label(part as u32);
                    hidden.push(format!("{}/{label}", brep.name));
                }
            }
        }
        Sidecar {
            unit: Some(setup.unit),
            handedness: Some(setup.handedness),
            camera: Some(setup.camera),
            lights: Some(setup.lights.iter().map(LightSpec::from_light).collect()),
            default_material: None,
            materials,
            hidden,
            grids: setup.grids.iter().map(GridSpec::from_grid).collect(),
            maintenance_factor: (setup.maintenance_factor != 1.0)
                .then_some(setup.maintenance_factor),
            // A [daylight] sky is written as the sky, not as a map.
            environment: setup
                .environment
                .as_ref()
                .filter(|_| setup.daylight.as_ref().is_none_or(|d| d.sky.is_none()))
                .map(EnvironmentSpec::from_model),
            environment_model: None,
            daylight: setup.daylight.as_ref().map(|d| d.spec.clone()),
            observers: setup.observers.clone(),
            smooth_angle_deg: (scene.smooth_angle_deg
                != super::smoothing::DEFAULT_SMOOTH_ANGLE_DEG)
                .then_some(scene.smooth_angle_deg),
            emission_scale: None,
            usd_time: None,
            base_dir: None,
            source: None,
        }
    }

    /// The sidecar as TOML. Every number is written to 6 significant digits (`0.63`, not the
    /// f32's `0.6300003`), and `-0.0` as `0.0`.
    pub fn to_toml(&self) -> String {
        let written = toml::Value::try_from(self).map(|mut v| {
            tidy_floats(&mut v);
            // Not `to_string_pretty`: it writes every array one number a line.
            toml::to_string(&v)
        });
        match written {
            Ok(Ok(text)) => text,
            Ok(Err(e)) | Err(e) => format!("# cannot write sidecar: {e}\n"),
        }
    }

    /// Luminaire and environment-map files in `dir` or below it written relative to it (the
    /// sidecar's folder), so a folder of scene, sidecar, luminaires and maps can move.
    pub fn relative_to(mut self, dir: &Path) -> Sidecar {
        for light in self.lights.iter_mut().flatten() {
            if let Some(file) = &light.file
                && let Some(rel) = super::notes::relative_below(file, dir)
            {
                light.file = Some(rel);
            }
        }
        if let Some(env) = &mut self.environment
            && let Some(file) = &env.file
            && let Some(rel) = super::notes::relative_below(Path::new(file), dir)
        {
            env.file = Some(rel.display().to_string());
        }
        self
    }
}

/// Rounds every float in `value` to 6 significant digits, and `-0.0` to `0.0`.
fn tidy_floats(value: &mut toml::Value) {
    match value {
        toml::Value::Float(f) => *f = round_significant(*f, 6),
        toml::Value::Array(items) => items.iter_mut().for_each(tidy_floats),
        toml::Value::Table(table) => table.iter_mut().for_each(|(_, v)| tidy_floats(v)),
        _ => {}
    }
}

/// `v` to `digits` significant digits (as the shortest decimal that reads back to it); zero
/// of either sign is `0.0`.
pub fn round_significant(v: f64, digits: i32) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return if v == 0.0 { 0.0 } else { v };
    }
    let text = format!("{:.*e}", (digits - 1).max(0) as usize, v);
    text.parse().unwrap_or(v)
}

/// A TOML error as one line: `line N: `the line's text`: reason` (the reason is what the
/// reader or a key's check said), without the multi-line snippet the error's own text has.
fn toml_error_message(text: &str, e: &toml::de::Error) -> String {
    let reason = e.message().trim_end().replace('\n', " ");
    let Some(span) = e.span().filter(|s| s.start <= text.len()) else {
        return reason;
    };
    let line = text[..span.start].matches('\n').count() + 1;
    let shown: String = text[span.start..]
        .lines()
        .next()
        .unwrap_or("")
        .trim()
        .chars()
        .take(60)
        .collect();
    if shown.is_empty() {
        format!("line {line}: {reason}")
    } else {
        format!("line {line}: `{shown}`: {reason}")
    }
}

/// The line of the table header `[name]` in `text`, if it has one.
fn table_line(text: &str, name: &str) -> Option<usize> {
    let header = format!("[{name}]");
    text.lines()
        .position(|l| l.trim_start().starts_with(&header))
        .map(|i| i + 1)
}

/// The line of the `n`-th (0-based) `header` line (e.g. `[[observers]]`) of `text`.
fn nth_line(text: &str, header: &str, n: usize) -> Option<usize> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| l.trim_start().starts_with(header))
        .nth(n)
        .map(|(i, _)| i + 1)
}

/// The line of `key = ...` inside the table `[table]` of `text`, if both are there.
fn key_line(text: &str, table: &str, key: &str) -> Option<usize> {
    let start = table_line(text, table)?;
    text.lines()
        .enumerate()
        .skip(start)
        .take_while(|(_, l)| !l.trim_start().starts_with('['))
        .find(|(_, l)| {
            l.trim_start()
                .strip_prefix(key)
                .is_some_and(|rest| rest.trim_start().starts_with('='))
        })
        .map(|(i, _)| i + 1)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use crate::scene::Projection;
    use crate::shp::parse_shp;

    /// `[[observers]]`: kept through apply and back to TOML; a zero direction, a NaN or a name
    /// given twice is an error naming the observer and its table's line.
    #[test]
    fn observers_round_trip_and_bad_ones_are_errors() {
        let good = "[[observers]]\nname = \"desk\"\nposition = [1.0, 1.2, 2.0]\n\
                    direction = [0.0, 0.0, -1.0]\n";
        let sidecar = Sidecar::parse(good, Path::new("s.raygine.toml")).unwrap();
        let scene = scene();
        let setup = sidecar.apply(&scene, None, &mut Vec::new());
        assert_eq!(setup.observers.len(), 1);
        assert_eq!(setup.observers[0].up, [0.0, 1.0, 0.0], "up defaults to +Y");
        let text = Sidecar::from_setup(&scene, &setup).to_toml();
        let again = Sidecar::parse(&text, Path::new("s.raygine.toml")).unwrap();
        assert_eq!(again.observers, setup.observers, "{text}");
        for (bad, want) in [
            (
                format!("{good}[[observers]]\nname = \"door\"\nposition = [0.0, 1.0, 0.0]\ndirection = [0.0, 0.0, 0.0]\n"),
                "line 5: observer door: direction must not be zero",
            ),
            (
                format!("{good}[[observers]]\nname = \"desk\"\nposition = [0.0, 1.0, 0.0]\ndirection = [1.0, 0.0, 0.0]\n"),
                "observer desk: a second observer has that name",
            ),
            (
                "[[observers]]\nname = \"w\"\nposition = [nan, 1.0, 0.0]\ndirection = [1.0, 0.0, 0.0]\n".to_owned(),
                "line 1: observer w: position must be finite numbers",
            ),
        ] {
            let err = Sidecar::parse(&bad, Path::new("s.raygine.toml"))
                .unwrap_err()
                .to_string();
            assert!(err.contains(want), "{err}\nwanted {want}");
        }
    }

    /// Projections' limits are errors that name the key and its line.
    #[test]
    fn camera_limits_are_errors_naming_the_key() {
        // Line 1 unit, 2 [camera], 3 look_at, then the keys from line 4.
        let cases = [
            (
                "projection = \"fisheye-equidistant\"\nfov_deg = 190.0",
                "line 5: camera: fov_deg of a fisheye-equidistant camera must be above 0 and at \
                 most 180°, got 190",
            ),
            (
                "fov_deg = 0.0\nprojection = \"hemispherical\"",
                "line 4: camera: fov_deg of a hemispherical camera",
            ),
            (
                "fov_deg = 180.0",
                "line 4: camera: fov_deg of a perspective camera must be above 0 and below 180°",
            ),
            (
                "projection = \"orthographic\"\nwidth = -2.0",
                "line 5: camera: width (the orthographic image's width in scene units) must be \
                 above 0, got -2",
            ),
            (
                "width = 0.0\nprojection = \"orthographic\"",
                "line 4: camera: width",
            ),
        ];
        for (keys, want) in cases {
            let text = format!(
                "unit = \"m\"\n[camera]\nlook_at = [0.0, 0.0, 0.0]\n{keys}\n\
                 position = [0.0, 0.0, 1.0]\n"
            );
            let err = Sidecar::parse(&text, Path::new("s.raygine.toml"))
                .expect_err(keys)
                .to_string();
            assert!(err.contains(want), "{keys}:\n{err}\nwanted {want}");
        }
        let bad = "[camera]\nprojection = \"fisheye\"\n";
        let err = Sidecar::parse(bad, Path::new("s.raygine.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("line 2") && err.contains("fisheye-equidistant"),
            "an unknown projection lists the known ones: {err}"
        );
        for p in Projection::ALL {
            let fov = if p.is_fisheye() { 180.0 } else { 60.0 };
            let text = format!(
                "[camera]\nposition = [0.0, 0.0, 1.0]\nlook_at = [0.0, 0.0, 0.0]\n\
                 projection = \"{p}\"\nfov_deg = {fov}\nwidth = 3.0\n"
            );
            let sidecar = Sidecar::parse(&text, Path::new("s.raygine.toml")).unwrap();
            let camera = sidecar.camera.unwrap();
            assert_eq!((camera.projection, camera.width), (p, Some(3.0)));
        }
    }

    /// Errors are one line with the line number, the line's text and the reason; a
    /// `[daylight]` error gives the table's line.
    #[test]
    fn errors_name_the_line() {
        let path = Path::new("room.raygine.toml");
        let e = |text: &str| Sidecar::parse(text, path).unwrap_err().to_string();
        let pane = e("unit = \"m\"\n\n[materials.window]\nkind = \"pane\"\ntransmittance = 1.5\n");
        assert!(
            pane.starts_with(
                "room.raygine.toml: line 3: `[materials.window]`: pane: transmittance"
            ),
            "{pane}"
        );
        assert!(
            !pane.contains('|') && !pane.contains("TOML parse error"),
            "{pane}"
        );
        let unclosed = e("[camera\n");
        assert!(
            unclosed.starts_with("room.raygine.toml: line 1: "),
            "{unclosed}"
        );
        let day = e(
            "unit = \"m\"\n[daylight]\nlatitude = 100.0\nlongitude = 0.0\n\
                     date = \"2026-01-01\"\ntime = \"12:00\"\ntimezone = 0.0\n",
        );
        assert!(
            day.starts_with("room.raygine.toml: line 2: daylight: latitude = 100"),
            "{day}"
        );
    }

    #[test]
    fn written_numbers_have_no_float_noise() {
        assert_eq!(round_significant(f64::from(0.630_000_3_f32), 6), 0.63);
        assert_eq!(round_significant(f64::from(0.065_000_004_f32), 6), 0.065);
        assert_eq!(round_significant(-0.0, 6), 0.0);
        assert!(round_significant(-0.0, 6).is_sign_positive());
        assert_eq!(round_significant(-279.499_99, 6), -279.5);
        let mut sidecar = Sidecar::default();
        sidecar.materials.insert(
            "red".into(),
            Material {
                kd: [0.630_000_3, 0.065_000_004, 0.049_999_982],
                ..Material::default()
            },
        );
        sidecar.camera = Some(Camera {
            position: [-0.0, 273.0, -800.0],
            look_at: [278.0, 273.0, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_deg: 39.0,
            ..Camera::default()
        });
        let text = sidecar.to_toml();
        assert!(text.contains("kd = [0.63, 0.065, 0.05]"), "{text}");
        assert!(!text.contains("-0.0"), "{text}");
        assert_eq!(
            Sidecar::parse(&text, Path::new("x.raygine.toml"))
                .unwrap()
                .camera,
            sidecar.camera.map(|c| Camera {
                position: [0.0, 273.0, -800.0],
                ..c
            })
        );
    }

    /// A map in the sidecar's folder (or below it) is written relative to it; one elsewhere
    /// keeps its whole path.
    #[test]
    fn map_files_beside_the_sidecar_are_written_relative_to_it() {
        let dir = Path::new("/scenes/room");
        let with_map = |file: &str| Sidecar {
            environment: Some(EnvironmentSpec {
                file: Some(file.to_owned()),
                ..EnvironmentSpec::default()
            }),
            ..Sidecar::default()
        };
        let file = |s: Sidecar| s.environment.and_then(|e| e.file);
        assert_eq!(
            file(with_map("/scenes/room/maps/sky.hdr").relative_to(dir)),
            Some(Path::new("maps").join("sky.hdr").display().to_string())
        );
        assert_eq!(
            file(with_map("/elsewhere/sky.hdr").relative_to(dir)),
            Some("/elsewhere/sky.hdr".to_owned())
        );
    }

    fn scene() -> Scene {
        let text = "define breps a\nvertices 3\n0 0 0\n1 0 0\n0 1 0\ntriangles 1\n0 1 2\nenddef\n";
        let desc = parse_shp(text.as_bytes(), Path::new("s.shp")).unwrap();
        Scene::build(&desc, "s").unwrap()
    }

    /// Regression (found while tabulating bad inputs): a sidecar camera with NaN or infinite
    /// numbers was taken silently and rendered an all-black picture.
    #[test]
    fn non_finite_camera_falls_back_to_the_default_with_a_warning() {
        let scene = scene();
        let defaults = Setup::defaults(&scene, LengthUnit::Mm);
        for camera in [
            "position = [nan, 0.0, 1.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_deg = 40.0",
            "position = [0.0, 0.0, 1.0]\nlook_at = [0.0, inf, 0.0]\nfov_deg = 40.0",
            "position = [0.0, 0.0, 1.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0.0, -inf, 0.0]\nfov_deg = 40.0",
            "position = [0.0, 0.0, 1.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_deg = nan",
        ] {
            let text = format!("[camera]\n{camera}\n");
            let sidecar = Sidecar::parse(&text, Path::new("s.raygine.toml")).unwrap();
            let mut warnings = Vec::new();
            let setup = sidecar.apply(&scene, None, &mut warnings);
            assert_eq!(setup.camera, defaults.camera, "{camera}");
            assert_eq!(warnings.len(), 1, "{camera}: {warnings:?}");
            assert!(
                warnings[0].starts_with("s.raygine.toml:1: camera: "),
                "the note names the file and the line of [camera]: {warnings:?}"
            );
        }
        let good =
            "[camera]\nposition = [0.0, 0.0, 9.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_deg = 30.0\n";
        let mut warnings = Vec::new();
        let setup = Sidecar::parse(good, Path::new("s.raygine.toml"))
            .unwrap()
            .apply(&scene, None, &mut warnings);
        assert_eq!(setup.camera.position, [0.0, 0.0, 9.0]);
        assert!(warnings.is_empty(), "{warnings:?}");
    }
}
