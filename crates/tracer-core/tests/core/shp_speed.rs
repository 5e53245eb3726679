//! Parse speed on a million triangles: `sphere 1000` of `../shared/BENCHMARK.md` written as a
//! `.shp` (about 40 MB). Ignored by default; run with
//! `cargo test --release -p tracer-core --test shp_speed -- --ignored --nocapture`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::f64::consts::PI;
use std::path::Path;
use std::time::Instant;

use tracer_core::shp::{self, BrepDef, Placement, ShpDescription};

/// A UV sphere of radius 1: `segments` around, `segments / 2` rings, pole triangles only once.
fn sphere(segments: u32) -> BrepDef {
    let rings = segments / 2;
    let mut vertices = Vec::new();
    for r in 0..=rings {
        let theta = PI * f64::from(r) / f64::from(rings);
        for s in 0..=segments {
            let phi = 2.0 * PI * f64::from(s) / f64::from(segments);
            vertices.push([
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ]);
        }
    }
    let index = |r: u32, s: u32| r * (segments + 1) + s;
    let mut triangles = Vec::new();
    for r in 0..rings {
        for s in 0..segments {
            let (a, b, c, d) = (
                index(r, s),
                index(r, s + 1),
                index(r + 1, s),
                index(r + 1, s + 1),
            );
            if r != 0 {
                triangles.push([a, b, c]);
            }
            if r != rings - 1 {
                triangles.push([b, d, c]);
            }
        }
    }
    let parts = vec![0; triangles.len()];
    BrepDef {
        name: "sphere".into(),
        vertices,
        triangles,
        part_count: 1,
        parts,
        ..BrepDef::default()
    }
}

#[test]
#[ignore = "timing: a 40 MB file, run on demand"]
fn million_triangles_parse_fast() {
    let brep = sphere(1000);
    assert_eq!(brep.triangles.len(), 998_000);
    let placement = Placement {
        name: "sphere".into(),
        ..Placement::default()
    };
    let desc = ShpDescription {
        path: "sphere.shp".into(),
        breps: vec![brep],
        placements: vec![placement],
    };
    let text = shp::write_shp(&desc).replace('\n', "\r\n");
    let mut times_ms = Vec::new();
    for _ in 0..5 {
        let start = Instant::now();
        let parsed = shp::parse_shp(text.as_bytes(), Path::new("sphere.shp")).unwrap();
        times_ms.push(start.elapsed().as_secs_f64() * 1e3);
        assert_eq!(parsed.breps[0].triangles.len(), 998_000);
    }
    times_ms.sort_by(f64::total_cmp);
    let median_ms = times_ms[times_ms.len() / 2];
    eprintln!(
        "sphere 1000: {} MB parsed, median of 5 {median_ms:.0} ms (all: {times_ms:.0?})",
        text.len() / 1_000_000
    );
    assert!(median_ms < 1000.0, "{median_ms} ms");
}
