//! UsdLux lights. A light's `intensity` × 2^`exposure` × `color` (× its `colorTemperature`'s
//! white when `enableColorTemperature` is set) is the luminance of its emitting surface in cd/m²
//! (nits); with `normalize`, divided by the surface's area in m², so that the intensity is the
//! light's exitance-like total (the emitted flux is π × intensity lumen, whatever the size).
//!
//! - `RectLight` (`width` × `height` in its XY plane), `DiskLight` (`radius`) and
//!   `CylinderLight` (`length` along X, `radius`; its mantle emits, not its caps) become
//!   emissive triangles of a black material, emitting as UsdLux says: rectangles and discs
//!   towards their −Z, cylinders outwards. A disc is a 64-gon and a cylinder a 64-sided prism
//!   of the true area (their radii scaled up so).
//! - `SphereLight` of radius r > 0: an emissive sphere (a geodesic sphere of 1280 triangles of
//!   the true area 4πr²), whose far-field intensity is I = L · π r².
//! - `SphereLight` with `treatAsPoint`, or radius 0: a point light of the sphere's far-field
//!   intensity I = L · π r² cd. A sphere of radius 0 with `normalize` keeps its flux: L = i / 4πr²
//!   gives I = i / 4 cd for intensity i; without `normalize` it would emit nothing and is
//!   noted. With `ShapingAPI`'s `shaping:cone:angle` θ and `softness` s, the point light is a
//!   spot: full out to θ (1 − s), zero from θ. With `shaping:ies:file`, the point emits the
//!   file's distribution (its nadir along the light's −Z) scaled so that its peak is I (the
//!   file is a shape, not absolute candela), or with `shaping:ies:normalize` so that its flux
//!   is the unshaped point's 4π I lm.
//! - `DistantLight` (`angle`, 0.53°): a disc of uniform luminance at infinity towards the
//!   light's +Z (it emits along −Z), drawn as the daylight sun is; with `normalize`, L =
//!   intensity / (π sin²(angle / 2)), so that a plane facing it gets the intensity in lux. One
//!   per scene (a daylight sun replaces it).
//! - `DomeLight`: the environment, uniform at the light's luminance, or its latitude-longitude
//!   `texture:file` (`.hdr`, `.exr`) with texels times intensity × 2^exposure, in OpenEXR's
//!   orientation (the image's centre towards the dome's +Z), turned about the vertical by the
//!   light's transform; its pole is the stage's up axis (DomeLight_1's `poleAxis = "scene"`)
//!   unless `poleAxis = "Y"`. One per scene.
//! - Cones, IES shaping and textures on area lights, and `shaping:focus`: noted, not drawn.

use super::Reader;
use super::values::{self, Time};
use crate::formats::{
    EmissionDescription, FormatError, LightDescription, LightDistribution, MaterialDescription,
    MeshDescription, PartDescription,
};
use crate::light::EmissionSides;
use glam::{DMat3, DMat4, DVec3, Vec3};
use openusd::usd::Prim;
use std::f64::consts::{PI, TAU};

/// Sides of a generated disc and cylinder.
const SEGMENTS: usize = 64;
/// Subdivisions of the icosahedron a sphere light is made of (20 · 4³ triangles).
const SPHERE_LEVELS: usize = 3;

/// The UsdLux light types raygine reads.
pub(super) const LIGHT_TYPES: [&str; 7] = [
    "RectLight",
    "DiskLight",
    "SphereLight",
    "CylinderLight",
    "DistantLight",
    "DomeLight",
    "DomeLight_1",
];

/// Luminance and tint of a light's surface before `normalize`.
struct Output {
    luminance: f64,
    color: [f32; 3],
    normalize: bool,
}

impl Reader<'_> {
    /// Reads the light at `prim` (type `kind`) placed by `world`.
    pub(super) fn light(
        &mut self,
        prim: &Prim,
        kind: &str,
        world: DMat4,
    ) -> Result<(), FormatError> {
        let time = self.time;
        let path = self.path;
        let num = |name: &str, fallback: f64| {
            values::input_scalar(prim, name, time, fallback)
                .map_err(|e| FormatError::new(path, 0, format!("{}: {e}", prim.path().as_str())))
        };
        let output = self.output(prim)?;
        self.desc.lights.get_or_insert_with(Vec::new);
        let name = prim.path().as_str().to_owned();
        match kind {
            "RectLight" => {
                let (w, h) = (num("width", 1.0)?, num("height", 1.0)?);
                let (hw, hh) = (w / 2.0, h / 2.0);
                let corners = vec![
                    [-hw, -hh, 0.0],
                    [hw, -hh, 0.0],
                    [hw, hh, 0.0],
                    [-hw, hh, 0.0],
                ];
                self.emitter(
                    prim,
                    name,
                    world,
                    corners,
                    vec![[0, 2, 1], [0, 3, 2]],
                    output,
                );
            }
            "DiskLight" => {
                let r = num("radius", 0.5)?;
                let (points, triangles) = disc(r);
                self.emitter(prim, name, world, points, triangles, output);
            }
            "CylinderLight" => {
                let (length, r) = (num("length", 1.0)?, num("radius", 0.5)?);
                let (points, triangles) = cylinder(length, r);
                self.emitter(prim, name, world, points, triangles, output);
            }
            "SphereLight" => {
                let r = num("radius", 0.5)?.max(0.0);
                let as_point = values::first_value(prim, &["treatAsPoint"], time)
                    .map_err(|e| FormatError::new(path, 0, e))?
                    .as_ref()
                    .and_then(values::boolean)
                    .unwrap_or(false);
                if r > 0.0 && !as_point {
                    let (points, triangles) = sphere(r);
                    self.emitter(prim, name, world, points, triangles, output);
                } else {
                    self.point_light(prim, name, world, r, output)?;
                }
            }
            "DistantLight" => {
                let angle = num("angle", 0.53)?;
                self.distant_light(prim, world, angle, output);
            }
            "DomeLight" | "DomeLight_1" => self.dome_light(prim, world, output)?,
            other => {
                *self.skipped_lights.entry(other.to_owned()).or_insert(0) += 1;
            }
        }
        Ok(())
    }

    /// A DistantLight: a disc `angle` degrees across towards its +Z, of luminance L (with
    /// `normalize`, L = intensity / (π sin²(angle / 2)), its projected solid angle, so that
    /// the illuminance on a plane facing it is the intensity in lux).
    fn distant_light(&mut self, prim: &Prim, world: DMat4, angle: f64, output: Output) {
        if self.desc.sun.is_some() {
            *self
                .skipped_lights
                .entry("second DistantLight".into())
                .or_insert(0) += 1;
            return;
        }
        let towards = world.transform_vector3(DVec3::Z).normalize_or_zero();
        if towards == DVec3::ZERO || !(angle > 0.0 && angle < 180.0) {
            self.desc.notes.push(format!(
                "{}: a DistantLight with no direction or an angle outside 0-180° (not drawn)",
                self.at(prim)
            ));
            return;
        }
        let projected = PI * (angle / 2.0).to_radians().sin().powi(2);
        let luminance = if output.normalize {
            output.luminance / projected
        } else {
            output.luminance
        };
        if output
            .color
            .iter()
            .any(|&c| (c - output.color[0]).abs() > 1e-3)
        {
            self.desc.notes.push(format!(
                "{}: the DistantLight's colour is drawn white (its luminance kept)",
                self.at(prim)
            ));
        }
        self.desc.sun = Some(crate::light::DistantSun {
            direction: towards.as_vec3().to_array(),
            diameter_deg: angle as f32,
            normal_illuminance_lx: (luminance * projected) as f32,
        });
        self.desc.lights.get_or_insert_with(Vec::new);
    }

    /// A DomeLight: the environment, of luminance L, or its latlong texture times
    /// intensity × 2^exposure in OpenEXR's orientation (the image's centre towards the dome's
    /// +Z, its +X a quarter of the width left of the centre), turned about the pole by the
    /// light's transform.
    fn dome_light(&mut self, prim: &Prim, world: DMat4, output: Output) -> Result<(), FormatError> {
        use crate::light::{Environment, EnvironmentMap, EnvironmentSource};
        if self.desc.environment.is_some() {
            *self
                .skipped_lights
                .entry("second DomeLight".into())
                .or_insert(0) += 1;
            return Ok(());
        }
        // The dome's pole: its +Y, which DomeLight_1's poleAxis = "scene" (the default) aligns
        // with the stage's up axis. The original DomeLight says +Y whatever the stage; files
        // from Z-up tools expect the sky up all the same, so Z-up stages get the turn too
        // unless poleAxis = "Y" says otherwise.
        let pole_axis = values::attr_token(prim, "poleAxis")
            .map_err(|e| self.error_at(prim, e))?
            .unwrap_or_else(|| "scene".into());
        let world = if pole_axis == "Z" || (pole_axis == "scene" && self.z_up) {
            world * DMat4::from_rotation_x(std::f64::consts::FRAC_PI_2)
        } else {
            world
        };
        let pole = world.transform_vector3(DVec3::Y).normalize_or_zero();
        if pole.dot(DVec3::Y) < 0.999 {
            self.desc.notes.push(format!(
                "{}: the dome is tilted; raygine draws it with its pole up (only turns about                  the vertical are kept)",
                self.at(prim)
            ));
        }
        // raygine's map centre looks along −Z turned by rotation_deg about +Y; OpenEXR's looks
        // along the dome's +Z.
        let front = world.transform_vector3(DVec3::Z);
        let rotation_deg = (-front.x).atan2(-front.z).to_degrees() as f32;
        let time = self.time;
        let file = values::first_value(prim, &["inputs:texture:file", "texture:file"], time)
            .map_err(|e| self.error_at(prim, e))?;
        let format = values::first_value(prim, &["inputs:texture:format", "texture:format"], time)
            .map_err(|e| self.error_at(prim, e))?
            .as_ref()
            .and_then(values::token)
            .unwrap_or("automatic")
            .to_owned();
        let file = file
            .as_ref()
            .and_then(|v| v.as_str())
            .map(str::trim)
            .filter(|f| !f.is_empty());
        let map = match file {
            Some(_) if !matches!(format.as_str(), "automatic" | "latlong") => {
                self.desc.notes.push(format!(
                    "{}: a {format} dome texture is not read (latitude-longitude only); the                      dome glows uniformly",
                    self.at(prim)
                ));
                None
            }
            Some(file) => {
                let loaded = if self.is_usdz {
                    self.package_bytes(file).and_then(|bytes| {
                        EnvironmentMap::from_bytes(&bytes, std::path::Path::new(file))
                    })
                } else {
                    let folder = self.path.parent().unwrap_or(std::path::Path::new(""));
                    EnvironmentMap::load(&folder.join(file))
                };
                match loaded {
                    Ok((map, notes)) => {
                        self.desc.notes.extend(notes);
                        Some(map)
                    }
                    Err(e) => {
                        self.desc.notes.push(format!(
                            "{}: the dome's texture {file}: {e}; the dome glows uniformly",
                            self.at(prim)
                        ));
                        None
                    }
                }
            }
            None => None,
        };
        let source = match map {
            Some(map) => {
                if output
                    .color
                    .iter()
                    .any(|&c| (c - output.color[0]).abs() > 1e-3)
                {
                    self.desc.notes.push(format!(
                        "{}: the dome texture's tint (color) is not applied",
                        self.at(prim)
                    ));
                }
                EnvironmentSource::Map(std::sync::Arc::new(map))
            }
            None => EnvironmentSource::Uniform {
                luminance_cd_m2: output.luminance as f32,
                color: output.color,
            },
        };
        let scale = match &source {
            // A texel's luminance times intensity × 2^exposure (the white tint's luminance 1).
            EnvironmentSource::Map(_) => {
                let y = f64::from(crate::light::luminance(Vec3::from(output.color)));
                (output.luminance / y.max(f64::MIN_POSITIVE)) as f32
            }
            EnvironmentSource::Uniform { .. } => 1.0,
        };
        // A uniform dome has no orientation to show.
        let rotation_deg = match &source {
            EnvironmentSource::Map(_) => rotation_deg,
            EnvironmentSource::Uniform { .. } => 0.0,
        };
        self.desc.environment = Some(Environment {
            source,
            scale,
            rotation_deg,
            background: true,
        });
        self.desc.lights.get_or_insert_with(Vec::new);
        Ok(())
    }

    /// intensity × 2^exposure, the colour (times the colour temperature's white) and normalize.
    fn output(&mut self, prim: &Prim) -> Result<Output, FormatError> {
        let time = self.time;
        let err = |e: String| self.error_at(prim, e);
        let intensity = values::input_scalar(prim, "intensity", time, 1.0).map_err(err)?;
        let exposure = values::input_scalar(prim, "exposure", time, 0.0).map_err(err)?;
        let color = values::first_value(prim, &["inputs:color", "color"], time)
            .map_err(err)?
            .as_ref()
            .and_then(values::vec3)
            .unwrap_or([1.0; 3]);
        let mut rgb = color.map(|c| c.max(0.0) as f32);
        let use_temperature = values::first_value(
            prim,
            &["inputs:enableColorTemperature", "enableColorTemperature"],
            time,
        )
        .map_err(err)?
        .as_ref()
        .and_then(values::boolean)
        .unwrap_or(false);
        if use_temperature {
            let kelvin =
                values::input_scalar(prim, "colorTemperature", time, 6500.0).map_err(err)?;
            let white = planckian_rgb(kelvin);
            for (c, w) in rgb.iter_mut().zip(white) {
                *c *= w;
            }
        }
        let normalize = values::first_value(prim, &["inputs:normalize", "normalize"], time)
            .map_err(err)?
            .as_ref()
            .and_then(values::boolean)
            .unwrap_or(false);
        let y = f64::from(crate::light::luminance(Vec3::from(rgb)));
        let luminance = intensity.max(0.0) * exposure.exp2() * y;
        if !luminance.is_finite() {
            return Err(self.error_at(prim, "its intensity × 2^exposure is not finite".into()));
        }
        Ok(Output {
            luminance,
            color: rgb,
            normalize,
        })
    }

    /// An emissive mesh of `points` (the light's own frame) and `triangles` (wound to face the
    /// way the light emits), carried to the scene by `world`.
    fn emitter(
        &mut self,
        prim: &Prim,
        name: String,
        world: DMat4,
        points: Vec<[f64; 3]>,
        mut triangles: Vec<[u32; 3]>,
        output: Output,
    ) {
        if DMat3::from_mat4(world).determinant() < 0.0 {
            // A mirroring transform turns the winding: keep the emitting side.
            for t in &mut triangles {
                t.swap(1, 2);
            }
        }
        let positions: Vec<[f64; 3]> = points
            .iter()
            .map(|p| world.transform_point3(DVec3::from(*p)).to_array())
            .collect();
        let area_m2 = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| DVec3::from(positions[i as usize]));
                (b - a).cross(c - a).length() / 2.0
            })
            .sum::<f64>()
            * self.metres_per_unit
            * self.metres_per_unit;
        if area_m2.is_nan() || area_m2 <= 0.0 {
            self.desc
                .notes
                .push(format!("{}: the light has no area; skipped", self.at(prim)));
            return;
        }
        let luminance = if output.normalize {
            output.luminance / area_m2
        } else {
            output.luminance
        };
        let emission = (luminance > 0.0).then_some(EmissionDescription {
            luminance_cd_m2: luminance as f32,
            color: output.color,
            sides: EmissionSides::Front,
        });
        self.desc.materials.push(MaterialDescription {
            name: name.clone(),
            source: self.path.to_owned(),
            emission,
            ..MaterialDescription::default()
        });
        let material = self.desc.materials.len() - 1;
        self.desc.meshes.push(MeshDescription {
            name,
            source: self.path.to_owned(),
            positions,
            triangles,
            parts: vec![PartDescription {
                name: None,
                material: Some(material),
                smooth: Some(false),
            }],
            ..MeshDescription::default()
        });
        if values::first_value(prim, &["inputs:texture:file", "texture:file"], self.time)
            .ok()
            .flatten()
            .is_some()
        {
            self.desc.notes.push(format!(
                "{}: the light's texture is not drawn (it glows uniformly)",
                self.at(prim)
            ));
        }
        self.note_shaping(prim, false);
    }

    /// A sphere light drawn as a point (`treatAsPoint`, or radius 0).
    fn point_light(
        &mut self,
        prim: &Prim,
        name: String,
        world: DMat4,
        radius: f64,
        output: Output,
    ) -> Result<(), FormatError> {
        // Far-field intensity of a Lambertian sphere: L · π r² (r in metres).
        let r_m = radius * self.metres_per_unit;
        let intensity_cd = if radius > 0.0 {
            let l = if output.normalize {
                output.luminance / (4.0 * PI * r_m * r_m)
            } else {
                output.luminance
            };
            l * PI * r_m * r_m
        } else if output.normalize {
            output.luminance / 4.0
        } else {
            self.desc.notes.push(format!(
                "{}: a sphere light of radius 0 without normalize emits nothing",
                self.at(prim)
            ));
            0.0
        };
        let position = world.transform_point3(DVec3::ZERO).as_vec3().to_array();
        let aim = world
            .transform_vector3(-DVec3::Z)
            .normalize_or_zero()
            .as_vec3();
        let time = self.time;
        let angle = values::input_scalar(prim, "shaping:cone:angle", time, 90.0)
            .map_err(|e| self.error_at(prim, e))?;
        let softness = values::input_scalar(prim, "shaping:cone:softness", time, 0.0)
            .map_err(|e| self.error_at(prim, e))?
            .clamp(0.0, 1.0);
        let intensity_cd = intensity_cd as f32;
        let distribution = if let Some(d) = self.ies_shaping(prim, intensity_cd)? {
            d
        } else if angle < 90.0 && aim != Vec3::ZERO {
            let falloff = angle.clamp(0.0, 90.0) as f32;
            LightDistribution::Spot {
                intensity_cd,
                cone_deg: falloff * (1.0 - softness as f32),
                falloff_deg: falloff,
            }
        } else {
            LightDistribution::Isotropic { intensity_cd }
        };
        self.note_shaping(prim, true);
        if let Some(lights) = &mut self.desc.lights {
            lights.push(LightDescription {
                name,
                source: self.path.to_owned(),
                line: 0,
                position,
                aim: if aim == Vec3::ZERO {
                    [0.0, -1.0, 0.0]
                } else {
                    aim.to_array()
                },
                rotation_deg: 0.0,
                color: output.color,
                distribution,
            });
        }
        Ok(())
    }

    /// `shaping:ies:file` on a point: the file's distribution scaled so that its peak is the
    /// light's intensity, or with `shaping:ies:normalize` so that its flux is the unshaped
    /// light's (4π I lm). None without a file, or with a note when it cannot be read.
    fn ies_shaping(
        &mut self,
        prim: &Prim,
        intensity_cd: f32,
    ) -> Result<Option<LightDistribution>, FormatError> {
        let time = self.time;
        let file =
            values::first_value(prim, &["inputs:shaping:ies:file", "shaping:ies:file"], time)
                .map_err(|e| self.error_at(prim, e))?;
        let Some(file) = file
            .as_ref()
            .and_then(|v| v.as_str())
            .map(str::trim)
            .filter(|f| !f.is_empty())
        else {
            return Ok(None);
        };
        let normalize = values::first_value(
            prim,
            &["inputs:shaping:ies:normalize", "shaping:ies:normalize"],
            time,
        )
        .map_err(|e| self.error_at(prim, e))?
        .as_ref()
        .and_then(values::boolean)
        .unwrap_or(false);
        let read = if self.is_usdz {
            self.package_bytes(file).and_then(|bytes| {
                crate::formats::parse_photometry(&bytes, std::path::Path::new(file))
                    .map_err(|e| e.to_string())
            })
        } else {
            let folder = self.path.parent().unwrap_or(std::path::Path::new(""));
            crate::formats::read_photometry(&folder.join(file)).map_err(|e| e.to_string())
        };
        let photometry = match read {
            Ok(p) => p,
            Err(e) => {
                self.desc.notes.push(format!(
                    "{}: shaping:ies:file {file}: {e}; the light is drawn without it",
                    self.at(prim)
                ));
                return Ok(None);
            }
        };
        let (peak, flux) = (photometry.max_cd(), photometry.flux_lm());
        let k = if normalize {
            4.0 * PI * f64::from(intensity_cd) / flux
        } else {
            f64::from(intensity_cd) / f64::from(peak)
        };
        if !(k.is_finite() && k >= 0.0) {
            self.desc.notes.push(format!(
                "{}: shaping:ies:file {file} emits nothing; the light is drawn without it",
                self.at(prim)
            ));
            return Ok(None);
        }
        Ok(Some(LightDistribution::Goniometric {
            photometry: photometry.scaled(k as f32),
            label: file.to_owned(),
        }))
    }

    /// Notes the ShapingAPI inputs raygine does not draw (`cone` on an area light, IES files,
    /// `focus`).
    fn note_shaping(&mut self, prim: &Prim, cone_drawn: bool) {
        let has = |n: &str| {
            values::first_value(
                prim,
                &[&format!("inputs:shaping:{n}"), &format!("shaping:{n}")],
                Time::Default,
            )
            .ok()
            .flatten()
            .is_some()
        };
        let mut unread = Vec::new();
        if !cone_drawn && has("cone:angle") {
            unread.push("shaping:cone (area lights emit as Lambertian surfaces)");
        }
        if !cone_drawn && has("ies:file") {
            unread.push("shaping:ies:file (on an area light)");
        }
        if has("focus") {
            unread.push("shaping:focus");
        }
        if !unread.is_empty() {
            self.desc.notes.push(format!(
                "{}: not drawn: {}",
                self.at(prim),
                unread.join(", ")
            ));
        }
    }
}

/// A disc of radius `r` in the XY plane facing −Z: a 64-gon of the disc's area.
fn disc(r: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let n = SEGMENTS as f64;
    let rr = r * (TAU / (n * (TAU / n).sin())).sqrt();
    let mut points = vec![[0.0; 3]];
    points.extend((0..SEGMENTS).map(|i| {
        let a = TAU * i as f64 / n;
        [rr * a.cos(), rr * a.sin(), 0.0]
    }));
    let triangles = (0..SEGMENTS as u32)
        .map(|i| [0, (i + 1) % SEGMENTS as u32 + 1, i + 1])
        .collect();
    (points, triangles)
}

/// A cylinder's mantle along X (`length`), radius `r`, facing out: a 64-sided prism of the
/// mantle's area.
fn cylinder(length: f64, r: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let n = SEGMENTS as f64;
    // The prism's perimeter 2 n r' sin(π/n) equals the circle's 2πr.
    let rr = r * PI / (n * (PI / n).sin());
    let half = length / 2.0;
    let mut points = Vec::with_capacity(2 * SEGMENTS);
    for i in 0..SEGMENTS {
        let a = TAU * i as f64 / n;
        let (y, z) = (rr * a.cos(), rr * a.sin());
        points.push([-half, y, z]);
        points.push([half, y, z]);
    }
    let m = SEGMENTS as u32;
    let triangles = (0..m)
        .flat_map(|i| {
            let j = (i + 1) % m;
            let (a, b, c, d) = (2 * i, 2 * i + 1, 2 * j, 2 * j + 1);
            [[a, c, b], [b, c, d]]
        })
        .collect();
    (points, triangles)
}

/// A geodesic sphere of radius `r` (an icosahedron subdivided [`SPHERE_LEVELS`] times), scaled
/// so that its area is the sphere's 4πr², wound to face out.
fn sphere(r: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut points: Vec<DVec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|p| DVec3::from(*p).normalize())
    .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..SPHERE_LEVELS {
        let mut middle = std::collections::HashMap::new();
        let mut mid = |a: u32, b: u32, points: &mut Vec<DVec3>| {
            *middle.entry((a.min(b), a.max(b))).or_insert_with(|| {
                points.push(((points[a as usize] + points[b as usize]) / 2.0).normalize());
                points.len() as u32 - 1
            })
        };
        triangles = triangles
            .iter()
            .flat_map(|&[a, b, c]| {
                let ab = mid(a, b, &mut points);
                let bc = mid(b, c, &mut points);
                let ca = mid(c, a, &mut points);
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    let area: f64 = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| points[i as usize]);
            (b - a).cross(c - a).length() / 2.0
        })
        .sum();
    let scale = r * (4.0 * PI / area).sqrt();
    (
        points.iter().map(|p| (*p * scale).to_array()).collect(),
        triangles,
    )
}

/// The linear Rec. 709 white of a Planckian radiator at `kelvin` (1667–25 000 K, clamped),
/// luminance 1: its chromaticity by Kang et al. (2002)'s cubic fits of the Planckian locus,
/// then XYZ → linear sRGB (IEC 61966-2-1).
pub(super) fn planckian_rgb(kelvin: f64) -> [f32; 3] {
    let t = kelvin.clamp(1667.0, 25_000.0);
    let (t1, t2, t3) = (1e3 / t, 1e6 / (t * t), 1e9 / (t * t * t));
    let x = if t <= 4000.0 {
        -0.266_123_9 * t3 - 0.234_358_9 * t2 + 0.877_695_6 * t1 + 0.179_910
    } else {
        -3.025_846_9 * t3 + 2.107_037_9 * t2 + 0.222_634_7 * t1 + 0.240_390
    };
    let y = if t <= 2222.0 {
        -1.106_381_4 * x.powi(3) - 1.348_110_20 * x * x + 2.185_558_32 * x - 0.202_196_83
    } else if t <= 4000.0 {
        -0.954_947_6 * x.powi(3) - 1.374_185_93 * x * x + 2.091_370_15 * x - 0.167_488_67
    } else {
        3.081_758 * x.powi(3) - 5.873_386_7 * x * x + 3.751_129_9 * x - 0.370_014_83
    };
    let (big_x, big_y, big_z) = (x / y, 1.0, (1.0 - x - y) / y);
    let r = 3.240_454_2 * big_x - 1.537_138_5 * big_y - 0.498_531_4 * big_z;
    let g = -0.969_266_0 * big_x + 1.876_010_8 * big_y + 0.041_556_0 * big_z;
    let b = 0.055_643_4 * big_x - 0.204_025_9 * big_y + 1.057_225_2 * big_z;
    let rgb = [r, g, b].map(|c| c.max(0.0) as f32);
    let lum = crate::light::luminance(Vec3::from(rgb));
    rgb.map(|c| c / lum)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn area(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> f64 {
        triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| DVec3::from(points[i as usize]));
                (b - a).cross(c - a).length() / 2.0
            })
            .sum()
    }

    #[test]
    fn generated_emitters_have_the_true_area_and_face_the_way_usdlux_says() {
        let (p, t) = disc(0.3);
        assert!((area(&p, &t) / (PI * 0.09) - 1.0).abs() < 1e-12);
        for tri in &t {
            let [a, b, c] = tri.map(|i| DVec3::from(p[i as usize]));
            assert!((b - a).cross(c - a).z < 0.0, "a disc faces -Z");
        }
        let (p, t) = cylinder(2.0, 0.25);
        assert!((area(&p, &t) / (TAU * 0.25 * 2.0) - 1.0).abs() < 1e-12);
        let (p, t) = sphere(0.5);
        assert!((area(&p, &t) / (PI) - 1.0).abs() < 1e-12);
        assert_eq!(t.len(), 1280);
        for tri in &t {
            let [a, b, c] = tri.map(|i| DVec3::from(p[i as usize]));
            let n = (b - a).cross(c - a);
            assert!(n.dot(a + b + c) > 0.0, "sphere triangles face out");
        }
    }

    /// Chromaticities of the Planckian locus (CIE 15:2004 tables; Illuminant A is a Planckian
    /// radiator at 2856 K: x = 0.44757, y = 0.40745).
    #[test]
    fn colour_temperature_follows_the_planckian_locus() {
        let xy = |rgb: [f32; 3]| {
            let [r, g, b] = rgb.map(f64::from);
            let x = 0.412_456_4 * r + 0.357_576_1 * g + 0.180_437_5 * b;
            let y = 0.212_672_9 * r + 0.715_152_2 * g + 0.072_175_0 * b;
            let z = 0.019_333_9 * r + 0.119_192_0 * g + 0.950_304_1 * b;
            (x / (x + y + z), y / (x + y + z))
        };
        let (x, y) = xy(planckian_rgb(2856.0));
        assert!(
            (x - 0.44757).abs() < 0.001 && (y - 0.40745).abs() < 0.001,
            "{x} {y}"
        );
        // 6500 K on the locus: (0.3135, 0.3237) (not D65, which lies above it).
        let (x, y) = xy(planckian_rgb(6500.0));
        assert!(
            (x - 0.3135).abs() < 0.001 && (y - 0.3237).abs() < 0.001,
            "{x} {y}"
        );
        let warm = planckian_rgb(2700.0);
        assert!(warm[0] > warm[1] && warm[1] > warm[2]);
    }
}
