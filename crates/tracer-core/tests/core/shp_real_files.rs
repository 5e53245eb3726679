//! The reader against the real scenes in `../shared/scenes/` (skipped when absent).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::PathBuf;
use std::time::Instant;

use tracer_core::shp::{self, ShpDescription};

fn shared() -> Option<PathBuf> {
    raygine_fixtures::shared("scenes").and_then(|p| Some(p.parent()?.to_path_buf()))
}

fn totals(desc: &ShpDescription) -> (usize, usize) {
    let vertices = desc.breps.iter().map(|b| b.vertices.len()).sum();
    let triangles = desc.breps.iter().map(|b| b.triangles.len()).sum();
    (vertices, triangles)
}

#[test]
fn cornell_box_has_five_breps() {
    let Some(shared) = shared() else { return };
    let desc = shp::load(&shared.join("scenes/cornell/cornel_box0.shp")).unwrap();
    assert_eq!(desc.breps.len(), 5);
    assert_eq!(totals(&desc), (79, 64));
    let names: Vec<_> = desc.breps.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["brs_0", "brs_1", "brs_2", "brs_3", "brs_4"]);
    assert_eq!(desc.placements.len(), 5);
    for placement in &desc.placements {
        assert_eq!(placement.rotation_deg, [0.0; 3]);
        assert_eq!(placement.translation, [0.0; 3]);
        assert_eq!(placement.scale, [1.0; 3]);
    }
    let floor = &desc.breps[0];
    assert_eq!(floor.line, 11);
    assert_eq!(floor.vertices[0], [114.555, 0.0, -116.556]);
    assert_eq!(floor.triangles[0], [12, 4, 24]);
    assert_eq!(
        (floor.part_count, floor.parts.len()),
        (1, floor.triangles.len())
    );
    assert_eq!(desc.placements[0].line, 204);
    assert_eq!(desc.placements[1].line, 210);
    assert_eq!(desc.breps[4].line, 160);
}

#[test]
fn cornell_box_lf_copy_reads_the_same() {
    let Some(shared) = shared() else { return };
    let crlf = shp::load(&shared.join("scenes/cornell/cornel_box0.shp")).unwrap();
    let mut lf = shp::load(&shared.join("scenes/cornell/cornel_box0_lf.shp")).unwrap();
    lf.path = crlf.path.clone();
    for brep in &mut lf.breps {
        brep.source = crlf.path.clone();
    }
    for placement in &mut lf.placements {
        placement.source = crlf.path.clone();
    }
    assert_eq!(lf, crlf);
}

#[test]
fn room2_loads_its_brs() {
    let Some(shared) = shared() else { return };
    let path = shared.join("scenes/ipur-room2/room2.shp");
    let parsed = shp::parse_shp(&std::fs::read(&path).unwrap(), &path).unwrap();
    assert!(
        parsed.breps.is_empty(),
        "parse_shp must not load .brs files"
    );
    assert_eq!(parsed.placements[0].name, "room2");
    let desc = shp::load(&path).unwrap();
    assert_eq!(desc.breps.len(), 1);
    let room = &desc.breps[0];
    assert_eq!(room.source.file_name().unwrap(), "room2.brs");
    assert_eq!(room.line, 4);
    assert_eq!(
        (room.vertices.len(), room.triangles.len(), room.part_count),
        (8872, 11452, 20)
    );
    assert_eq!(room.vertices[0], [-12.3444, 2.4384, -16.7640]);
    assert!(room.parts.contains(&19));
}

#[test]
fn meshes_have_benchmark_triangle_counts() {
    let Some(shared) = shared() else { return };
    for (stem, triangles) in [
        ("stanford-bunny", 69_451),
        ("nefertiti", 99_938),
        ("ogre", 124_008),
    ] {
        let path = shared.join(format!("scenes/meshes/{stem}.shp"));
        let bytes = std::fs::read(&path).unwrap();
        let start = Instant::now();
        let desc = shp::parse_shp(&bytes, &path).unwrap();
        let elapsed_ms = start.elapsed().as_secs_f64() * 1e3;
        eprintln!("{stem}: {} bytes parsed in {elapsed_ms:.1} ms", bytes.len());
        assert_eq!(desc.breps.len(), 1, "{stem}");
        assert_eq!(totals(&desc).1, triangles, "{stem}");
    }
    let teapot = shp::load(&shared.join("scenes/meshes/teapot.shp")).unwrap();
    assert!(totals(&teapot).1 > 0);
}

#[test]
fn other_room2_files_are_skipped_blocks() {
    // The sibling files hold only blocks this reader skips: each reads as "no triangles",
    // proving every block in them closes where the reader thinks it does.
    let Some(shared) = shared() else { return };
    let dir = shared.join("scenes/ipur-room2/room2");
    for file in [
        "room2.atr",
        "room2.lgt",
        "room2.cam",
        "room2.cfg",
        "room2.prb",
        "room2.tpa",
    ] {
        let path = dir.join(file);
        let err = shp::parse_shp(&std::fs::read(&path).unwrap(), &path).unwrap_err();
        assert!(
            matches!(err, shp::ShpError::NoTriangles { .. }),
            "{file}: {err}"
        );
    }
}
