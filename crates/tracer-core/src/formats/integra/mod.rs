//! The Integra (IPUR) bundle beside a `.shp`: `NAME.shp` places brep `NAME` (geometry in
//! `NAME.brs`); `NAME.prb` and the folder `NAME/` hold the design:
//!
//! ```text
//! NAME/NAME.atr  surface attributes ──atr──▶ Attr ──material──▶ MaterialDescription
//! NAME/NAME.prb  (else NAME.prb) part names, part → attribute, texture mappings ──prb──▶ Prb
//! NAME/NAME.lgt  Light, Fixture, Group, Diagram ──lgt──▶ Lgt ──luminaires──▶ LightDescription
//! NAME/NAME.cam  viewpoint and screen corners ──cam──▶ Cam ──▶ CameraDescription
//! ```
//!
//! Every reader parses bytes into plain data with line numbers and refuses bad input with one
//! line naming the file, the line and why ([`IntegraError`]); nothing panics. raygine never
//! writes these files: edits go to the sidecar, which overrides them. The mapping is documented
//! in `docs/integra.md`.

mod atr;
mod cam;
mod error;
mod lgt;
mod lines;
mod luminaires;
mod material;
mod prb;

pub use atr::{Attr, parse_atr};
pub use cam::{Cam, parse_cam};
pub use error::IntegraError;
pub use lgt::{Diagram, Fixture, Geography, Group, Lgt, LgtLight, Reference, parse_lgt};
pub use luminaires::{diagram_photometry, lights_from_lgt};
pub use material::{material_from_attr, srgb_to_linear, unit_tint};
pub use prb::{Prb, PrbItem, parse_prb};

use crate::formats::description::{SceneDescription, SceneFormat};
use std::path::{Path, PathBuf};

/// The files of a bundle that exist (found ignoring ASCII case, as Windows wrote them).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Bundle {
    /// The brep the design applies to (the `.shp` file's stem).
    pub name: String,
    pub folder: Option<PathBuf>,
    pub atr: Option<PathBuf>,
    /// The folder's `.prb`, else the one beside the `.shp`.
    pub prb: Option<PathBuf>,
    pub lgt: Option<PathBuf>,
    pub cam: Option<PathBuf>,
}

impl Bundle {
    /// The bundle beside `shp` (None when there is neither a folder `NAME/` nor `NAME.prb`).
    pub fn beside(shp: &Path) -> Option<Bundle> {
        let dir = shp
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let name = shp.file_stem()?.to_string_lossy().into_owned();
        let folder = find(dir, &name).filter(|f| f.is_dir());
        let in_folder = |ext: &str| {
            folder
                .as_deref()
                .and_then(|f| find(f, &format!("{name}.{ext}")))
                .filter(|p| p.is_file())
        };
        let top_prb = find(dir, &format!("{name}.prb")).filter(|p| p.is_file());
        let bundle = Bundle {
            atr: in_folder("atr"),
            prb: in_folder("prb").or(top_prb),
            lgt: in_folder("lgt"),
            cam: in_folder("cam"),
            folder,
            name,
        };
        let any = bundle.atr.is_some()
            || bundle.prb.is_some()
            || bundle.lgt.is_some()
            || bundle.cam.is_some();
        any.then_some(bundle)
    }
}

/// `dir/file_name`, or the entry of `dir` whose name matches it ignoring ASCII case.
fn find(dir: &Path, file_name: &str) -> Option<PathBuf> {
    let exact = dir.join(file_name);
    if exact.exists() {
        return Some(exact);
    }
    std::fs::read_dir(dir)
        .ok()?
        .flatten()
        .find(|e| {
            e.file_name()
                .to_str()
                .is_some_and(|n| n.eq_ignore_ascii_case(file_name))
        })
        .map(|e| dir.join(e.file_name()))
}

fn read(path: &Path) -> Result<Vec<u8>, IntegraError> {
    let len = std::fs::metadata(path)
        .map_err(|e| IntegraError::new(path, 0, format!("cannot read: {e}")))?
        .len();
    if len > lines::MAX_FILE_BYTES as u64 {
        return Err(IntegraError::new(
            path,
            0,
            format!("{len} bytes: larger than any Integra file"),
        ));
    }
    std::fs::read(path).map_err(|e| IntegraError::new(path, 0, format!("cannot read: {e}")))
}

/// Adds what the bundle designs to `desc` (read from the `.shp`): part names and materials of
/// brep `bundle.name`, the lights, the camera, metres as the unit. Findings that do not stop
/// the load go to `desc.notes`.
pub fn read_bundle(bundle: &Bundle, desc: &mut SceneDescription) -> Result<(), IntegraError> {
    desc.format = SceneFormat::Integra;
    desc.metres_per_unit = Some(1.0);
    let attrs = match &bundle.atr {
        Some(p) => parse_atr(&read(p)?, p)?,
        None => Vec::new(),
    };
    if let Some(p) = &bundle.prb {
        let prb = parse_prb(&read(p)?, p)?;
        assign_parts(bundle, &prb, p, &attrs, bundle.atr.as_deref(), desc);
    }
    if let Some(p) = &bundle.lgt {
        let lgt = parse_lgt(&read(p)?, p)?;
        desc.lights = Some(lights_from_lgt(&lgt, p, &mut desc.notes)?);
        desc.daylight = lgt
            .geography
            .as_ref()
            .and_then(|g| g.to_daylight(p, &mut desc.notes));
    }
    if let Some(p) = &bundle.cam
        && let Some(cam) = parse_cam(&read(p)?, p)?
    {
        desc.camera = Some(cam.to_camera(p)?);
    }
    Ok(())
}

/// Names the parts of the bundle's brep and gives each its attribute's material.
fn assign_parts(
    bundle: &Bundle,
    prb: &Prb,
    prb_path: &Path,
    attrs: &[Attr],
    atr_path: Option<&Path>,
    desc: &mut SceneDescription,
) {
    let single = desc.meshes.len() == 1;
    let Some(mesh_index) = desc
        .meshes
        .iter()
        .position(|m| m.name.eq_ignore_ascii_case(&bundle.name))
        .or(single.then_some(0))
    else {
        desc.notes.push(format!(
            "{}: no brep is named {}: its parts are not assigned",
            prb_path.display(),
            bundle.name
        ));
        return;
    };
    let part_count = desc.meshes[mesh_index].parts.len();
    if prb.parts.len() != part_count || prb.attrs.len() != part_count {
        desc.notes.push(format!(
            "{}: {} part names and {} attributes for the {part_count} parts of brep {}; \
             parts without one keep their number or raygine's default material",
            prb_path.display(),
            prb.parts.len(),
            prb.attrs.len(),
            desc.meshes[mesh_index].name
        ));
    }
    let atr_path = atr_path.map_or_else(|| prb_path.with_extension("atr"), Path::to_path_buf);
    let mut material_of_attr: Vec<(usize, usize)> = Vec::new();
    for part in 0..part_count {
        let name = prb.parts.get(part).map(|p| p.name.clone());
        let material = prb.attrs.get(part).and_then(|id| {
            let Some(ai) = attrs
                .iter()
                .position(|a| a.name.eq_ignore_ascii_case(&id.name))
            else {
                desc.notes.push(format!(
                    "{}:{}: attribute {} is not in {}: part {part} gets the default material",
                    prb_path.display(),
                    id.line,
                    id.name,
                    atr_path.display()
                ));
                return None;
            };
            if let Some(&(_, mi)) = material_of_attr.iter().find(|(a, _)| *a == ai) {
                return Some(mi);
            }
            let attr = &attrs[ai];
            if !attr.textures.is_empty() {
                desc.notes.push(format!(
                    "{}:{}: attribute {}: texture keys are not supported; drawn untextured",
                    atr_path.display(),
                    attr.textures[0].0,
                    attr.name
                ));
            }
            desc.materials
                .push(material_from_attr(attr, &atr_path, &mut desc.notes));
            let mi = desc.materials.len() - 1;
            material_of_attr.push((ai, mi));
            Some(mi)
        });
        // `shading flat|smooth` of the part's attribute; smooth parts get vertex normals
        // averaged within the crease angle (the .brs holds none).
        let smooth = prb
            .attrs
            .get(part)
            .and_then(|id| attrs.iter().find(|a| a.name.eq_ignore_ascii_case(&id.name)))
            .and_then(|a| a.smooth);
        desc.meshes[mesh_index].parts[part] = crate::formats::PartDescription {
            name,
            material,
            smooth,
        };
    }
    let mapped: Vec<String> = prb
        .mapp
        .iter()
        .enumerate()
        .filter(|(_, m)| !m.name.eq_ignore_ascii_case("none"))
        .map(|(i, _)| {
            prb.parts
                .get(i)
                .map_or_else(|| i.to_string(), |p| p.name.clone())
        })
        .collect();
    if !mapped.is_empty() {
        desc.notes.push(format!(
            "{}:{}: parts {} have texture maps whose image files are not in the bundle \
             (Integra `mapp` / `.tpa` maps are not read); drawn untextured",
            prb_path.display(),
            prb.mapp[0].line,
            mapped.join(", ")
        ));
    }
}
