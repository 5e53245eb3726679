//! The benchmark meshes: the shared scanned meshes (`scenes/meshes/NAME.shp`) and generated UV
//! spheres (`sphere-N`), as world-space triangle soups named by file stem.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use glam::Vec3;
use tracer_core::bvh::uv_sphere;
use tracer_core::scene::{self, LoadOptions};
use tracer_core::shp::{BrepDef, ShpDescription, write_shp};

/// The default mesh list of BENCHMARK.md.
pub const DEFAULT_MESHES: [&str; 4] = ["stanford-bunny", "nefertiti", "ogre", "sphere-1000"];

#[derive(Clone, Debug)]
pub struct Mesh {
    pub name: String,
    pub triangles: Vec<[Vec3; 3]>,
    /// The `.shp` it came from; `None` for generated meshes.
    pub path: Option<PathBuf>,
}

/// `sphere-N` -> `Some(N)`.
pub fn sphere_segments(name: &str) -> Option<u32> {
    name.strip_prefix("sphere-")
        .or_else(|| name.strip_prefix("sphere "))
        .and_then(|n| n.parse().ok())
}

/// Loads a mesh by name: `sphere-N` is generated, anything else is `scenes/meshes/NAME.shp`.
pub fn load(name: &str, shared: &Path) -> anyhow::Result<Mesh> {
    if let Some(n) = sphere_segments(name) {
        if n < 3 {
            bail!("{name}: a sphere needs at least 3 segments");
        }
        return Ok(Mesh {
            name: format!("sphere-{n}"),
            triangles: uv_sphere(n),
            path: None,
        });
    }
    let path = shared.join("scenes/meshes").join(format!("{name}.shp"));
    let loaded = scene::load(&path, &LoadOptions::default())
        .with_context(|| format!("cannot load mesh {name}"))?;
    Ok(Mesh {
        name: name.to_owned(),
        triangles: loaded.scene.triangles().collect(),
        path: Some(path),
    })
}

/// A one-brep description of a triangle soup, vertices shared where they are bit-identical.
pub fn description_of(name: &str, triangles: &[[Vec3; 3]]) -> ShpDescription {
    let mut index: HashMap<[u32; 3], u32> = HashMap::new();
    let mut vertices = Vec::new();
    let mut tris = Vec::with_capacity(triangles.len());
    for tri in triangles {
        let mut ids = [0u32; 3];
        for (id, v) in ids.iter_mut().zip(tri) {
            let key = v.to_array().map(f32::to_bits);
            *id = *index.entry(key).or_insert_with(|| {
                vertices.push(v.to_array().map(f64::from));
                (vertices.len() - 1) as u32
            });
        }
        tris.push(ids);
    }
    ShpDescription {
        path: PathBuf::from(format!("{name}.shp")),
        breps: vec![BrepDef {
            name: name.to_owned(),
            source: PathBuf::from(format!("{name}.shp")),
            line: 0,
            vertices,
            parts: vec![0; tris.len()],
            triangles: tris,
            part_count: 1,
        }],
        placements: Vec::new(),
    }
}

/// The `.shp` path L3 loads for a mesh: its own file, or a generated one written once into `dir`.
pub fn shp_path(mesh: &Mesh, dir: &Path) -> anyhow::Result<PathBuf> {
    if let Some(p) = &mesh.path {
        return Ok(p.clone());
    }
    let path = dir.join(format!("{}.shp", mesh.name));
    if !path.is_file() {
        std::fs::create_dir_all(dir)?;
        let text = write_shp(&description_of(&mesh.name, &mesh.triangles));
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_names() {
        assert_eq!(sphere_segments("sphere-1000"), Some(1000));
        assert_eq!(sphere_segments("sphere 64"), Some(64));
        assert_eq!(sphere_segments("stanford-bunny"), None);
    }

    #[test]
    fn sphere_1000_has_998000_triangles() {
        let mesh = load("sphere-1000", Path::new("/nonexistent")).unwrap();
        assert_eq!(mesh.triangles.len(), 998_000);
    }

    #[test]
    fn generated_shp_loads_back_with_the_same_triangles() {
        let dir = std::env::temp_dir().join(format!("raybench-test-{}", std::process::id()));
        let mesh = load("sphere-16", Path::new("/nonexistent")).unwrap();
        let path = shp_path(&mesh, &dir).unwrap();
        let loaded = scene::load(&path, &LoadOptions::default()).unwrap();
        assert_eq!(loaded.scene.triangles().collect::<Vec<_>>(), mesh.triangles);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
