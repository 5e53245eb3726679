//! Wavefront OBJ scenes with their MTL material libraries, read by `tobj` after a line-by-line
//! check of our own (`scan`), so every problem names its line.
//!
//! - `o` and `g` become breps (repeated names are one brep); within a brep each material is a
//!   part named after it, so sidecar keys read `brep/material`. Faces before any `o`/`g` belong
//!   to a brep named after the file.
//! - Polygons are triangulated as fans; `vn` normals are used for smooth shading when every
//!   corner of a face has one (else raygine averages normals itself).
//! - Positions are in the scene unit: the sidecar's `unit` or `--units` (OBJ says none).
//!   Right-handed, Y up.
//! - Materials map as `mtl` documents; `emission_scale` turns `Ke` into cd/m².

mod maps;
mod mtl;
mod scan;

use super::error::{FormatError, read_limited};
use super::{MeshDescription, PartDescription, ReadOptions, SceneDescription, SceneFormat};
use std::collections::HashMap;
use std::path::Path;

/// Reads an OBJ file and the MTL libraries it names from its folder.
pub fn read(path: &Path, options: &ReadOptions) -> Result<SceneDescription, FormatError> {
    let bytes = read_limited(path, "the OBJ file")?;
    let folder = path.parent().unwrap_or(Path::new("")).to_owned();
    let libraries = |name: &str| -> Option<(std::path::PathBuf, Vec<u8>)> {
        let file = folder.join(name);
        read_limited(&file, "the material library")
            .ok()
            .map(|b| (file, b))
    };
    parse(&bytes, path, &libraries, options)
}

/// A material library's file and bytes by the name `mtllib` gives (None: not found).
pub type LibraryLoader<'a> = dyn Fn(&str) -> Option<(std::path::PathBuf, Vec<u8>)> + 'a;

/// Parses OBJ bytes; `libraries` loads the MTL files it names.
pub fn parse(
    bytes: &[u8],
    path: &Path,
    libraries: &LibraryLoader<'_>,
    options: &ReadOptions,
) -> Result<SceneDescription, FormatError> {
    let scan = scan::scan(bytes, path)?;
    let mut notes = scan.notes;
    // The libraries, checked line by line, then parsed by tobj.
    let mut materials: Vec<(tobj::Material, std::path::PathBuf, usize)> = Vec::new();
    for (line, name) in &scan.libraries {
        let Some((file, text)) = libraries(name).or_else(|| {
            // `mtllib a.mtl b.mtl` names two files.
            let mut all: Option<(std::path::PathBuf, Vec<u8>)> = None;
            for part in name.split_whitespace() {
                let (f, mut t) = libraries(part)?;
                match &mut all {
                    Some((_, acc)) => {
                        acc.push(b'\n');
                        acc.append(&mut t);
                    }
                    None => all = Some((f, t)),
                }
            }
            all
        }) else {
            notes.push(format!(
                "{}:{line}: material library {name} not found; its materials get the default",
                path.display()
            ));
            continue;
        };
        let lines = mtl::check(&text, &file)?;
        let (mats, _) = tobj::load_mtl_buf(&mut text.as_slice())
            .map_err(|e| FormatError::new(&file, 0, format!("not a material library: {e}")))?;
        for m in mats {
            let l = lines.get(&m.name).copied().unwrap_or(0);
            materials.push((m, file.clone(), l));
        }
    }
    // tobj resolves `usemtl` names against the libraries it loaded itself: hand it the same
    // materials in the same order.
    let merged: Vec<tobj::Material> = materials.iter().map(|(m, _, _)| m.clone()).collect();
    let load = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..tobj::LoadOptions::default()
    };
    let names: HashMap<String, usize> = merged
        .iter()
        .enumerate()
        .rev()
        .map(|(i, m)| (m.name.clone(), i))
        .collect();
    let (models, _) = tobj::load_obj_buf(&mut scan.text.as_bytes(), &load, |_| {
        Ok((merged.clone(), names.clone()))
    })
    .map_err(|e| FormatError::new(path, 0, format!("not an OBJ file: {e}")))?;

    let stem = path
        .file_stem()
        .map_or_else(|| "obj".to_owned(), |s| s.to_string_lossy().into_owned());
    let mut desc = SceneDescription {
        path: path.to_owned(),
        format: SceneFormat::Obj,
        ..SceneDescription::default()
    };
    let mut material_index: HashMap<usize, usize> = HashMap::new();
    let mut brep_of: HashMap<String, usize> = HashMap::new();
    // Whether every group of a brep so far came with normals.
    let mut normals_ok: Vec<bool> = Vec::new();
    for model in &models {
        let mesh = &model.mesh;
        if mesh.indices.is_empty() {
            continue;
        }
        let name = if model.name.is_empty() || model.name == "unnamed_object" {
            stem.clone()
        } else {
            model.name.clone()
        };
        let b = *brep_of.entry(name.clone()).or_insert_with(|| {
            desc.meshes.push(MeshDescription {
                name,
                source: path.to_owned(),
                line: 0,
                ..MeshDescription::default()
            });
            normals_ok.push(true);
            desc.meshes.len() - 1
        });
        let part_name = mesh
            .material_id
            .and_then(|i| materials.get(i))
            .map_or_else(|| "default".to_owned(), |(m, _, _)| m.name.clone());
        let material = mesh.material_id.filter(|&i| i < materials.len()).map(|i| {
            *material_index.entry(i).or_insert_with(|| {
                let (m, file, line) = &materials[i];
                let d = mtl::to_description(m, file, *line, options.emission_scale(), &mut notes);
                desc.materials.push(d);
                desc.materials.len() - 1
            })
        });
        let out = &mut desc.meshes[b];
        let part = match out
            .parts
            .iter()
            .position(|p| p.name.as_deref() == Some(part_name.as_str()))
        {
            Some(p) => p,
            None => {
                out.parts.push(PartDescription {
                    name: Some(part_name),
                    material,
                    smooth: None,
                });
                out.parts.len() - 1
            }
        };
        let base = out.positions.len() as u32;
        let count = mesh.positions.len() / 3;
        out.positions.extend(
            mesh.positions
                .chunks_exact(3)
                .map(|p| [f64::from(p[0]), f64::from(p[1]), f64::from(p[2])]),
        );
        // Normals only when every vertex of the brep has one.
        normals_ok[b] &= mesh.normals.len() == count * 3;
        if normals_ok[b] {
            out.normals
                .extend(mesh.normals.chunks_exact(3).map(|n| [n[0], n[1], n[2]]));
        } else {
            out.normals.clear();
        }
        // Texture coordinates (OBJ's v up the image, stored as the image's 1 − v), when the
        // brep has them; vertices without read (0, 0).
        if mesh.texcoords.len() == count * 2 || !out.uvs[0].is_empty() {
            out.uvs[0].resize(base as usize, [0.0; 2]);
            if mesh.texcoords.len() == count * 2 {
                out.uvs[0].extend(mesh.texcoords.chunks_exact(2).map(|t| {
                    let fix = |x: f32| if x.is_finite() { x } else { 0.0 };
                    [fix(t[0]), 1.0 - fix(t[1])]
                }));
            } else {
                out.uvs[0].resize(base as usize + count, [0.0; 2]);
            }
        }
        for t in mesh.indices.chunks_exact(3) {
            out.triangles.push([t[0] + base, t[1] + base, t[2] + base]);
            out.triangle_parts.push(part as u32);
        }
    }
    if desc.meshes.is_empty() {
        return Err(FormatError::new(path, 0, "no faces: nothing to draw"));
    }
    desc.notes = notes;
    Ok(desc)
}
