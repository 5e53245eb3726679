//! `raybench scene-dump`: writes the scene raygine loaded (as `raygine render -S` loads it, with
//! its sidecar) so that other renderers can be given exactly the same thing:
//!
//! - `triangles.ply`: binary little-endian PLY, three unshared vertices per triangle in world
//!   coordinates (the scene unit) with the vertex normals raygine shades with (all zero for a
//!   flat triangle), and per face its material index (`material`, the slot);
//! - `scene.json`: the unit (and metres per unit), the handedness, the camera, the lights and
//!   the materials (indexed like `material` in the PLY), and counts.
//!
//! Hidden slots are left out of the PLY. Nothing is converted: values are raygine's own
//! (reflectances, Blinn-Phong glossiness, candela, cd/m²).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context;
use serde_json::{Value, json};
use tracer_core::scene::{self, Handedness, LoadOptions, LoadedScene};

#[derive(Clone, Debug)]
pub struct Options {
    pub scene: PathBuf,
    pub sidecar: Option<PathBuf>,
    pub units: Option<scene::LengthUnit>,
    /// Folder to write `triangles.ply` and `scene.json` into (created if missing).
    pub out: PathBuf,
}

pub fn run(options: &Options) -> anyhow::Result<()> {
    let load = LoadOptions {
        unit: options.units,
        sidecar: options.sidecar.as_deref(),
        ..LoadOptions::default()
    };
    let loaded = scene::load(&options.scene, &load)
        .with_context(|| format!("cannot load {}", options.scene.display()))?;
    for warning in &loaded.warnings {
        eprintln!("warning: {warning}");
    }
    std::fs::create_dir_all(&options.out)
        .with_context(|| format!("cannot create {}", options.out.display()))?;
    let ply = options.out.join("triangles.ply");
    let (written, smooth) = write_ply(&loaded, &ply)?;
    let mut description = describe(&loaded);
    description["triangles_file"] = json!("triangles.ply");
    description["triangle_count"] = json!(written);
    description["smooth_triangle_count"] = json!(smooth);
    description["source"] = json!(options.scene.display().to_string());
    let json_path = options.out.join("scene.json");
    std::fs::write(&json_path, serde_json::to_string_pretty(&description)?)
        .with_context(|| format!("cannot write {}", json_path.display()))?;
    println!(
        "scene-dump scene={} triangles={written} smooth={smooth} materials={} lights={} out={}",
        loaded.scene.name,
        loaded.setup.materials.len(),
        loaded.setup.lights.len(),
        options.out.display()
    );
    Ok(())
}

/// Writes the visible triangles; returns how many, and how many carry vertex normals.
fn write_ply(loaded: &LoadedScene, path: &Path) -> anyhow::Result<(usize, usize)> {
    let scene = &loaded.scene;
    let visible: Vec<u32> = (0..scene.triangle_count() as u32)
        .filter(|&t| !loaded.setup.is_hidden(scene.slot(t)))
        .collect();
    let mut out = Vec::with_capacity(visible.len() * (3 * 24 + 17) + 512);
    write!(
        out,
        "ply\nformat binary_little_endian 1.0\ncomment raygine scene {} (scene unit)\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         property float nx\nproperty float ny\nproperty float nz\n\
         element face {}\nproperty list uchar int vertex_indices\nproperty int material\n\
         end_header\n",
        scene.name,
        visible.len() * 3,
        visible.len()
    )?;
    let mut smooth = 0;
    for &t in &visible {
        let corners = scene.smooth_corners(t);
        smooth += usize::from(corners.is_some());
        let normals = corners.unwrap_or([glam::Vec3::ZERO; 3]);
        for (p, n) in scene.triangle(t).iter().zip(normals) {
            for x in p.to_array().into_iter().chain(n.to_array()) {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
    }
    for (i, &t) in visible.iter().enumerate() {
        out.push(3);
        let first = i32::try_from(3 * i).context("too many triangles for PLY indices")?;
        for k in 0..3 {
            out.extend_from_slice(&(first + k).to_le_bytes());
        }
        let material = i32::try_from(scene.slot(t)).context("slot out of range")?;
        out.extend_from_slice(&material.to_le_bytes());
    }
    std::fs::write(path, out).with_context(|| format!("cannot write {}", path.display()))?;
    Ok((visible.len(), smooth))
}

/// Unit, handedness, camera, lights and materials as JSON.
fn describe(loaded: &LoadedScene) -> Value {
    let setup = &loaded.setup;
    let scene = &loaded.scene;
    let materials: Vec<Value> = setup
        .materials
        .iter()
        .enumerate()
        .map(|(slot, m)| {
            json!({
                "index": slot,
                "label": scene.slot_label(slot as u32),
                "hidden": setup.hidden.get(slot).copied().unwrap_or(false),
                "kd": m.kd,
                "ks": m.ks,
                "glossiness": m.glossiness,
                "kt": m.kt,
                "ior": m.ior,
                "emission_cd_m2": m.emission_cd_m2,
                "emission_color": m.emission_color,
                "emission_sides": format!("{:?}", m.emission_sides).to_lowercase(),
            })
        })
        .collect();
    let lights: Vec<Value> = setup.lights.iter().map(|l| json!(l.summary())).collect();
    let camera = &setup.camera;
    json!({
        "name": scene.name,
        "unit": setup.unit.symbol(),
        "metres_per_unit": setup.unit.metres_per_unit(),
        "handedness": match setup.handedness {
            Handedness::Left => "left",
            Handedness::Right => "right",
        },
        "camera": {
            "position": camera.position,
            "look_at": camera.look_at,
            "up": camera.up,
            "fov_deg": camera.fov_deg,
            "fov_axis": "vertical",
        },
        "lights": lights,
        "materials": materials,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    /// The box's dump: 30 triangles of 24-byte vertices and 17-byte faces after the header,
    /// the light and camera of its sidecar in the JSON.
    #[test]
    fn the_cornell_box_dumps_its_triangles_lights_and_camera() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let out = std::env::temp_dir().join(format!("raygine-scene-dump-{}", std::process::id()));
        run(&Options {
            scene: root.join("assets/scenes/cornell_box.shp"),
            sidecar: None,
            units: None,
            out: out.clone(),
        })
        .unwrap();
        let ply = std::fs::read(out.join("triangles.ply")).unwrap();
        let end = b"end_header\n";
        let body = ply.windows(end.len()).position(|w| w == end).unwrap() + end.len();
        assert_eq!(ply.len() - body, 30 * (3 * 24 + 17));
        let json: Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("scene.json")).unwrap())
                .unwrap();
        assert_eq!(json["triangle_count"], 30);
        assert_eq!(json["lights"].as_array().unwrap().len(), 1);
        assert!(json["camera"].is_object(), "{json}");
        std::fs::remove_dir_all(&out).unwrap();
    }
}
