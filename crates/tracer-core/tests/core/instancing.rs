//! Instancing: meshes drawn several times are stored once and reached through a two-level BVH.
//!
//! - Through an identity instance, a mesh draws bit for bit what it draws directly (the built-in
//!   box, every mesh an instance, in every integrator).
//! - Placed copies drawn as instances agree within the noise with the same copies stored flat
//!   (transforms move hits by an ulp, so bit-identity is not asked).
//! - `.shp` blocks that `set breps` one brep several times and glTF nodes sharing a mesh store
//!   its triangles once.
//! - 1000 bunnies (69 M triangles in the picture) load and render in little memory.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::{Film, RenderSettings, render};
use tracer_core::scene::{DEFAULT_SMOOTH_ANGLE_DEG, LoadOptions, Scene, Setup, Sidecar, load};

const BOX_SHP: &str = include_str!("../../../../assets/scenes/cornell_box.shp");
const BOX_SIDECAR: &str = include_str!("../../../../assets/scenes/cornell_box.raygine.toml");

fn with_sidecar(scene: &Scene) -> Setup {
    let sidecar = Sidecar::parse(BOX_SIDECAR, Path::new("cornell_box.raygine.toml")).unwrap();
    sidecar.apply(scene, None, &mut Vec::new())
}

fn render_film(scene: &Scene, setup: &Setup, integrator: IntegratorKind, spp: u32) -> Film {
    let settings = RenderSettings {
        width: 48,
        height: 36,
        samples_per_pixel: spp,
        integrator,
        ..RenderSettings::default()
    };
    render(scene, setup, &settings).0
}

#[test]
fn an_identity_instance_draws_bit_for_bit_what_the_mesh_draws_directly() {
    let desc =
        tracer_core::shp::parse_shp(BOX_SHP.as_bytes(), Path::new("cornell_box.shp")).unwrap();
    let flat = Scene::build(&desc, "box").unwrap();
    let instanced = Scene::build_instanced(&desc, "box", DEFAULT_SMOOTH_ANGLE_DEG).unwrap();
    assert_eq!(flat.instance_count(), 0);
    assert_eq!(instanced.instance_count(), flat.breps.len());
    assert_eq!(instanced.own_triangle_count(), 0);
    assert_eq!(instanced.triangle_count(), flat.triangle_count());
    assert_eq!(instanced.bounds, flat.bounds);
    let setup = with_sidecar(&flat);
    for integrator in [
        IntegratorKind::Direct,
        IntegratorKind::Path,
        IntegratorKind::Bidirectional,
        IntegratorKind::Light,
    ] {
        let a = render_film(&flat, &setup, integrator, 2);
        let b = render_film(&instanced, &setup, integrator, 2);
        let differing = (0..a.len()).filter(|&i| a.pixel(i) != b.pixel(i)).count();
        println!("{integrator:?}: {differing} of {} pixels differ", a.len());
        assert_eq!(differing, 0, "{integrator:?}");
    }
}

/// A floor and a box (the built-in short block's shape) placed three times, rotated, moved and
/// scaled: as one brep with three `set breps` blocks (instances) or three breps (flat).
fn three_blocks(instanced: bool) -> String {
    let block = BOX_SHP
        .split("define breps short_block")
        .nth(1)
        .and_then(|rest| rest.split("enddef").next())
        .unwrap();
    let floor = BOX_SHP
        .split("define breps floor")
        .nth(1)
        .and_then(|rest| rest.split("enddef").next())
        .unwrap();
    let mut text = format!("define breps floor{floor}enddef\n");
    let places = [
        ("0 0 0", "0 0 0", "1 1 1"),
        ("0 30 0", "-150 0 -120", "1 1.5 1"),
        ("0 -70 0", "190 0 140", "0.6 0.6 0.6"),
    ];
    let names: Vec<String> = if instanced {
        vec!["block".into(); 3]
    } else {
        (0..3).map(|i| format!("block{i}")).collect()
    };
    let defined = if instanced { &names[..1] } else { &names[..] };
    for name in defined {
        text += &format!("define breps {name}{block}enddef\n");
    }
    for (name, (rot, tr, sc)) in names.iter().zip(places) {
        text += &format!(
            "set breps {name}\n  rotation {rot}\n  translation {tr}\n  scale {sc}\nenddef\n"
        );
    }
    text
}

#[test]
fn placed_instances_agree_with_flat_copies_within_the_noise() {
    let load_text = |text: String| {
        let desc = tracer_core::shp::parse_shp(text.as_bytes(), Path::new("blocks.shp")).unwrap();
        Scene::build(&desc, "blocks").unwrap()
    };
    let inst = load_text(three_blocks(true));
    let flat = load_text(three_blocks(false));
    assert_eq!(inst.instance_count(), 3, "{:?}", inst.breps);
    assert_eq!(flat.instance_count(), 0);
    assert_eq!(inst.triangle_count(), flat.triangle_count());
    assert_eq!(
        inst.stored_triangle_count(),
        flat.triangle_count() - 2 * flat.breps[1].triangle_count
    );
    assert_eq!(inst.breps[2].name, "block#2");
    // A small mesh's instance box is its placed vertices' box, padded by a few ulps: the
    // flat scene's, up to the rounding of the transform.
    let size = flat.bounds.extent().max_element();
    let (fb, ib) = (flat.bounds, inst.bounds);
    assert!(ib.min.cmple(fb.min + 1e-3).all() && ib.max.cmpge(fb.max - 1e-3).all());
    let looser = (ib.extent() - fb.extent()).max_element() / size;
    println!(
        "instanced bounds larger than the flat ones by {:.3} % of the scene",
        100.0 * looser
    );
    assert!(looser < 1e-4, "{ib:?} {fb:?}");
    let mut setup = with_sidecar(&flat);
    setup.camera.position = [278.0, 400.0, -500.0];
    setup.camera.look_at = [0.0, 0.0, 0.0];
    for integrator in [IntegratorKind::Direct, IntegratorKind::Path] {
        let a = render_film(&flat, &setup, integrator, 16);
        let b = render_film(&inst, &setup, integrator, 16);
        let (mut sum_a, mut sum_b, mut far) = (0.0, 0.0, 0);
        for i in 0..a.len() {
            let (pa, pb) = (a.pixel(i), b.pixel(i));
            let (ma, mb) = (pa.mean_luminance(), pb.mean_luminance());
            sum_a += ma;
            sum_b += mb;
            let se = pa
                .luminance_std_error()
                .unwrap_or(0.0)
                .hypot(pb.luminance_std_error().unwrap_or(0.0));
            if (ma - mb).abs() > 4.0 * se + 1e-6 * ma.abs().max(mb.abs()) {
                far += 1;
            }
        }
        println!(
            "{integrator:?}: mean luminance flat {:.6} instanced {:.6} cd/m²; {far} of {} \
             pixels differ by more than 4 standard errors",
            sum_a / a.len() as f64,
            sum_b / a.len() as f64,
            a.len()
        );
        assert!(sum_a > 0.0);
        assert!((sum_b / sum_a - 1.0).abs() < 1e-4, "{sum_a} {sum_b}");
        assert!(far <= a.len() / 100, "{far}");
    }
}

/// A `.glb` of one mesh (`positions`, `triangles`) drawn by one node per transform (glTF
/// column-major 4x4 matrices).
pub fn instanced_glb(
    positions: &[[f32; 3]],
    triangles: &[[u32; 3]],
    transforms: &[[f32; 16]],
) -> Vec<u8> {
    let mut bin = Vec::new();
    positions
        .iter()
        .flatten()
        .for_each(|f| bin.extend(f.to_le_bytes()));
    let index_offset = bin.len();
    triangles
        .iter()
        .flatten()
        .for_each(|i| bin.extend(i.to_le_bytes()));
    let (mut min, mut max) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in positions {
        for a in 0..3 {
            min[a] = min[a].min(p[a]);
            max[a] = max[a].max(p[a]);
        }
    }
    let nodes: Vec<String> = transforms
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let m: Vec<String> = m.iter().map(|x| format!("{x:?}")).collect();
            format!(
                r#"{{"name":"copy{i}","mesh":0,"matrix":[{}]}}"#,
                m.join(",")
            )
        })
        .collect();
    let roots: Vec<String> = (0..transforms.len()).map(|i| i.to_string()).collect();
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[{}]}}],"nodes":[{}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
        "buffers":[{{"byteLength":{}}}],
        "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{}}},{{"buffer":0,"byteOffset":{},"byteLength":{}}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":{},"type":"VEC3","min":{:?},"max":{:?}}},
            {{"bufferView":1,"componentType":5125,"count":{},"type":"SCALAR"}}]}}"#,
        roots.join(","),
        nodes.join(","),
        bin.len(),
        index_offset,
        index_offset,
        bin.len() - index_offset,
        positions.len(),
        min,
        max,
        triangles.len() * 3
    );
    let mut json = json.into_bytes();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out
}

/// A grid of `n` copies of a mesh `size` across, each turned about y and scaled a little.
fn grid_transforms(n: usize, size: f32) -> Vec<[f32; 16]> {
    let side = (n as f32).sqrt().ceil() as usize;
    (0..n)
        .map(|i| {
            let (x, z) = ((i % side) as f32, (i / side) as f32);
            let angle = i as f32 * 0.7;
            let s = 1.0 + 0.1 * (i % 3) as f32;
            let (c, sn) = (angle.cos() * s, angle.sin() * s);
            [
                c,
                0.0,
                -sn,
                0.0,
                0.0,
                s,
                0.0,
                0.0,
                sn,
                0.0,
                c,
                0.0,
                x * 1.5 * size,
                0.0,
                z * 1.5 * size,
                1.0,
            ]
        })
        .collect()
}

fn shared_dir() -> Option<std::path::PathBuf> {
    raygine_fixtures::shared("models").and_then(|p| Some(p.parent()?.to_path_buf()))
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir =
        std::env::temp_dir().join(format!("raygine-instancing-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn gltf_nodes_sharing_a_mesh_store_it_once_and_draw_it_everywhere() {
    // A unit tetrahedron, four nodes.
    let positions = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let triangles = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    let transforms = grid_transforms(4, 1.0);
    let dir = temp_dir("gltf");
    let path = dir.join("tetras.glb");
    std::fs::write(&path, instanced_glb(&positions, &triangles, &transforms)).unwrap();
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    let scene = &loaded.scene;
    assert_eq!(scene.triangle_count(), 16);
    assert_eq!(scene.stored_triangle_count(), 4);
    assert_eq!(scene.instance_count(), 4);
    let names: Vec<&str> = scene.breps.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["copy0", "copy1", "copy2", "copy3"]);
    // Every copy is where its node puts it: a ray down onto each copy's (0.2, y, 0.2) corner
    // region hits the top face x + y + z = 1 (in the copy's frame) of that copy.
    for (k, m) in transforms.iter().enumerate() {
        let world = glam::Mat4::from_cols_array(m);
        let local = glam::Vec3::new(0.2, 0.0, 0.2);
        let p = world.transform_point3(local);
        let ray = tracer_core::geometry::Ray::new(p + glam::Vec3::Y * 10.0, glam::Vec3::NEG_Y);
        let hit = scene.intersect(&ray).expect("the copy is there");
        assert_eq!(scene.slots[scene.slot(hit.prim) as usize].brep, k as u32);
        let top = world.transform_point3(glam::Vec3::new(0.2, 0.6, 0.2));
        assert!(
            (ray.at(hit.t) - top).length() < 1e-4,
            "copy {k}: hit {} expected {top}",
            ray.at(hit.t)
        );
        assert!(scene.occluded(&ray));
        let normal = scene.normal(hit.prim);
        let expected = (world
            .inverse()
            .transpose()
            .transform_vector3(glam::Vec3::ONE))
        .normalize();
        assert!(
            (normal.dot(expected).abs() - 1.0).abs() < 1e-5,
            "{normal} {expected}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The issue's figure: 1000 bunnies (69 M triangles in the picture) load with one copy of the
/// bunny and render; the geometry held stays far under 1 GB.
#[test]
fn a_thousand_bunnies_render_from_one_copy() {
    let Some(shared) = shared_dir() else {
        println!("skipped: ../shared (the bunny) is absent");
        return;
    };
    let bunny = load(
        &shared.join("models/stanford-bunny.obj"),
        &LoadOptions::default(),
    )
    .unwrap();
    let tris: Vec<[glam::Vec3; 3]> = bunny.scene.triangles().collect();
    let positions: Vec<[f32; 3]> = tris.iter().flatten().map(|p| p.to_array()).collect();
    let triangles: Vec<[u32; 3]> = (0..tris.len() as u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    let size = bunny.scene.bounds.extent().max_element();
    let dir = temp_dir("bunnies");
    let path = dir.join("bunnies.glb");
    std::fs::write(
        &path,
        instanced_glb(&positions, &triangles, &grid_transforms(1000, size)),
    )
    .unwrap();
    let started = std::time::Instant::now();
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    let load_secs = started.elapsed().as_secs_f64();
    let scene = &loaded.scene;
    assert_eq!(scene.instance_count(), 1000);
    assert_eq!(scene.triangle_count(), 1000 * tris.len());
    assert_eq!(scene.stored_triangle_count(), tris.len());
    let bytes = scene.geometry_bytes();
    println!(
        "1000 bunnies: {} triangles in the picture, {} stored; geometry {:.1} MB; loaded in {load_secs:.2} s",
        scene.triangle_count(),
        scene.stored_triangle_count(),
        bytes as f64 / 1e6
    );
    assert!(bytes < 100_000_000, "{bytes}");
    let settings = RenderSettings {
        width: 64,
        height: 48,
        samples_per_pixel: 1,
        integrator: IntegratorKind::Direct,
        ..RenderSettings::default()
    };
    let (film, _) = render(scene, &loaded.setup, &settings);
    let lit = (0..film.len())
        .filter(|&i| film.pixel(i).mean_luminance() > 0.0)
        .count();
    println!("  {lit} of {} pixels lit", film.len());
    assert!(lit > film.len() / 10, "{lit}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A placement that flattens a reused mesh (scale 0) or throws it to infinity draws nothing
/// and says so; the scene keeps its other copies.
#[test]
fn a_flattened_or_infinite_instance_is_noted_not_fatal() {
    let text = "define breps tent\nvertices 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\ntriangles 2\n0 1 2\n\
                0 2 3\nenddef\n\
                set breps tent\n  rotation 0 0 0\n  translation 0 0 0\n  scale 1 1 1\nenddef\n\
                set breps tent\n  rotation 0 0 0\n  translation 4 0 0\n  scale 0 0 0\nenddef\n\
                set breps tent\n  rotation 0 0 0\n  translation 8 0 0\n  scale 1 1 1\nenddef\n";
    let desc = tracer_core::shp::parse_shp(text.as_bytes(), Path::new("tents.shp")).unwrap();
    let scene = Scene::build(&desc, "tents").unwrap();
    assert_eq!(scene.instance_count(), 2);
    assert_eq!(scene.triangle_count(), 4);
    assert_eq!(scene.breps[1].name, "tent#2");
    assert_eq!(scene.breps[1].triangle_count, 0);
    assert!(scene.brep_triangles(1).is_empty());
    let note = scene.design.notes.iter().find(|n| n.contains("tent#2"));
    println!("{note:?}");
    assert!(
        note.is_some_and(|n| n.contains("not invertible") && n.contains("tents.shp")),
        "{:?}",
        scene.design.notes
    );
    // The third copy is at x = 8.
    let ray = tracer_core::geometry::Ray::new(glam::Vec3::new(8.2, 0.2, 5.0), glam::Vec3::NEG_Z);
    let hit = scene.intersect(&ray).unwrap();
    assert_eq!(scene.slots[scene.slot(hit.prim) as usize].brep, 2);
}
