//! Alpha against geometry: a leaf quad 1 m above a floor, lit by a point light far off at 45°,
//! casts its shadow beside itself. Its mask's opaque texels are a known fraction f of the leaf,
//! so the lit fraction of the floor under the shadow is 1 − f (shadow rays pass the cut-outs),
//! texel by texel where the shadow is sharp; and camera rays see the floor through the holes.
//! For MTL `map_d` (stochastic transparency) the expected lit fraction is 1 − mean alpha.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::textures::png_bytes as png;
use base64::Engine;
use std::path::{Path, PathBuf};
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::{Camera, Light, LoadOptions, Material, Projection, load};

const SIDE: u32 = 32;
/// The mask: 4 x 4 texels, these opaque (6 of 16).
const OPAQUE: [(u32, u32); 6] = [(0, 0), (1, 0), (3, 1), (2, 2), (0, 3), (3, 3)];

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("raygine-alpha-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn mask_png() -> Vec<u8> {
    let mut img = image::RgbaImage::new(4, 4);
    for (x, y, p) in img.enumerate_pixels_mut() {
        let a = if OPAQUE.contains(&(x, y)) { 255 } else { 0 };
        p.0 = [255, 255, 255, a];
    }
    png(img.into())
}

/// A glTF of a floor (x −1..3, z −1..2, y 0) and a leaf (x 0..1, z 0..1, y 1; u along x, v
/// along z) whose material is MASK with the mask as base colour, read NEAREST.
fn leaf_gltf() -> String {
    let quads: [[[f32; 3]; 4]; 2] = [
        [
            [-1.0, 0.0, -1.0],
            [3.0, 0.0, -1.0],
            [3.0, 0.0, 2.0],
            [-1.0, 0.0, 2.0],
        ],
        [
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
        ],
    ];
    let uvs: [[f32; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let indices: [u16; 6] = [0, 3, 2, 0, 2, 1];
    let mut bin = Vec::new();
    for q in &quads {
        q.iter().flatten().for_each(|f| bin.extend(f.to_le_bytes()));
    }
    uvs.iter()
        .flatten()
        .for_each(|f| bin.extend(f.to_le_bytes()));
    indices.iter().for_each(|i| bin.extend(i.to_le_bytes()));
    let b64 = |b: &[u8]| base64::engine::general_purpose::STANDARD.encode(b);
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0,1]}}],
        "nodes":[{{"name":"floor","mesh":0}},{{"name":"leaf","mesh":1}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":3,"material":0}}]}},
                  {{"primitives":[{{"attributes":{{"POSITION":1,"TEXCOORD_0":2}},"indices":3,"material":1}}]}}],
        "materials":[{{"name":"floor"}},
            {{"name":"leaf","alphaMode":"MASK","alphaCutoff":0.5,"doubleSided":true,
              "pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}],
        "textures":[{{"source":0,"sampler":0}}],"samplers":[{{"magFilter":9728}}],
        "images":[{{"uri":"data:image/png;base64,{}"}}],
        "buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}],
        "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":48}},
            {{"buffer":0,"byteOffset":96,"byteLength":32}},{{"buffer":0,"byteOffset":128,"byteLength":12}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,0,-1],"max":[3,0,2]}},
            {{"bufferView":1,"componentType":5126,"count":4,"type":"VEC3","min":[0,1,0],"max":[1,1,1]}},
            {{"bufferView":2,"componentType":5126,"count":4,"type":"VEC2"}},
            {{"bufferView":3,"componentType":5123,"count":6,"type":"SCALAR"}}]}}"#,
        b64(&mask_png()),
        bin.len(),
        b64(&bin)
    )
}

/// An OBJ of the same floor and leaf, the leaf's `map_d` a grey image of code `grey`.
fn leaf_obj(dir: &Path, grey: u8) -> PathBuf {
    let img = image::GrayImage::from_pixel(4, 4, image::Luma([grey]));
    std::fs::write(dir.join("alpha.png"), png(img.into())).unwrap();
    std::fs::write(
        dir.join("leaf.mtl"),
        "newmtl floor\nKd 0.8 0.8 0.8\nnewmtl leaf\nKd 0.1 0.1 0.1\nmap_d alpha.png\n",
    )
    .unwrap();
    let path = dir.join("leaf.obj");
    std::fs::write(
        &path,
        "mtllib leaf.mtl\no floor\nv -1 0 -1\nv 3 0 -1\nv 3 0 2\nv -1 0 2\nusemtl floor\n\
         f 1 4 3 2\no leaf\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\nvt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\n\
         usemtl leaf\nf 5/1 8/4 7/3 6/2\n",
    )
    .unwrap();
    path
}

/// Renders a 1 x 1 m square of the floor with its corner at (`x0`, 0), straight down, in
/// direct mode with the light far off towards +x at 45°; `hide_leaf` hides the leaf.
fn view(path: &Path, x0: f32, hide_leaf: bool, spp: u32) -> Vec<f64> {
    let mut loaded = load(path, &LoadOptions::default()).unwrap();
    let scene = &loaded.scene;
    let setup = &mut loaded.setup;
    let slot_of = |name: &str| {
        let b = scene.breps.iter().find(|b| b.name == name).unwrap();
        b.first_slot as usize
    };
    let (floor, leaf) = (slot_of("floor"), slot_of("leaf"));
    // Lambertian floor and leaf (the leaf keeps its textures: the mask).
    setup.materials[floor] = Material {
        kd: [0.8; 3],
        ..Material::default()
    };
    setup.materials[leaf] = Material {
        kd: [0.1; 3],
        textures: setup.materials[leaf].textures,
        ..Material::default()
    };
    assert!(setup.materials[leaf].textures.is_some());
    setup.hidden = vec![false; scene.slots.len()];
    setup.hidden[leaf] = hide_leaf;
    setup.lights = vec![Light::point([1000.5, 1001.0, 0.5], 1.0e9)];
    setup.camera = Camera {
        position: [x0 + 0.5, 5.0, 0.5],
        look_at: [x0 + 0.5, 0.0, 0.5],
        up: [0.0, 0.0, -1.0],
        projection: Projection::Orthographic,
        width: Some(1.0),
        ..Camera::default()
    };
    let settings = RenderSettings {
        width: SIDE,
        height: SIDE,
        samples_per_pixel: spp,
        integrator: IntegratorKind::Direct,
        ..RenderSettings::default()
    };
    let (film, _) = render(&loaded.scene, &loaded.setup, &settings);
    (0..(SIDE * SIDE) as usize)
        .map(|i| film.mean_luminance(i))
        .collect()
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

#[test]
fn a_masked_leaf_lets_light_through_its_cut_outs_and_its_shadow_has_the_masks_area() {
    let dir = scratch("mask");
    let path = dir.join("leaf.gltf");
    std::fs::write(&path, leaf_gltf()).unwrap();
    // The shadow falls on x −1..0 (the leaf is 1 m up, the light at 45° towards +x).
    let lit = view(&path, -1.0, true, 16);
    let shadowed = view(&path, -1.0, false, 16);
    let f = OPAQUE.len() as f64 / 16.0;
    let ratio = mean(&shadowed) / mean(&lit);
    println!(
        "lit fraction under the shadow {ratio:.4}, 1 − f = {:.4} (mask area {f})",
        1.0 - f
    );
    assert!((ratio - (1.0 - f)).abs() < 0.01, "{ratio}");
    // Texel by texel: the middle of each texel's shadow is dark exactly where it is opaque.
    for ty in 0..4 {
        for tx in 0..4 {
            let i = ((8 * ty + 4) * SIDE + 8 * tx + 4) as usize;
            let dark = shadowed[i] < 0.5 * lit[i];
            assert_eq!(dark, OPAQUE.contains(&(tx, ty)), "texel ({tx}, {ty})");
        }
    }
    // From above the leaf, camera rays see the lit floor through the holes and the leaf
    // (reflectance 0.1 against the floor's 0.8, under the same illuminance) elsewhere.
    let floor = view(&path, 0.0, true, 16);
    let seen = view(&path, 0.0, false, 16);
    for ty in 0..4 {
        for tx in 0..4 {
            let i = ((8 * ty + 4) * SIDE + 8 * tx + 4) as usize;
            let want = if OPAQUE.contains(&(tx, ty)) {
                floor[i] * 0.1 / 0.8
            } else {
                floor[i]
            };
            assert!(
                (seen[i] / want - 1.0).abs() < 0.01,
                "texel ({tx}, {ty}): {} vs {want}",
                seen[i]
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_obj_map_d_is_stochastic_transparency_with_the_expected_shadow() {
    let dir = scratch("blend");
    // Code 77: alpha 77 / 255 = 0.302 everywhere.
    let path = leaf_obj(&dir, 77);
    let lit = view(&path, -1.0, true, 64);
    let shadowed = view(&path, -1.0, false, 64);
    let alpha = 77.0 / 255.0;
    // Away from the shadow's edges (a margin of 2 pixels).
    let inner = |v: &[f64]| {
        let mut s = Vec::new();
        for y in 2..SIDE - 2 {
            for x in 2..SIDE - 2 {
                s.push(v[(y * SIDE + x) as usize]);
            }
        }
        mean(&s)
    };
    let ratio = inner(&shadowed) / inner(&lit);
    println!("lit fraction under a leaf of alpha {alpha:.4}: {ratio:.4}");
    assert!((ratio - (1.0 - alpha)).abs() < 0.01, "{ratio}");
    let _ = std::fs::remove_dir_all(&dir);
}
