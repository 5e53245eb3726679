//! Properties of the `.shp` reader and writer on random scenes: what `write_shp` writes reads
//! back as the same breps (vertices bit for bit, triangles, parts) and placements, whatever the
//! line ends, blanks and comments; and random damage to a valid file gives a scene or an error,
//! never a panic. Case counts are kept moderate so the file runs in seconds.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use proptest::prelude::*;
use tracer_core::scene::Scene;
use tracer_core::shp::{BrepDef, Placement, ShpDescription, parse_brs, parse_shp, write_shp};

const PATH: &str = "prop.shp";

/// A finite coordinate: ordinary values, the extremes, zeros of both signs and subnormals.
fn coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -1.0e4..1.0e4f64,
        1 => any::<f64>().prop_filter("finite", |x| x.is_finite()),
        1 => Just(-0.0),
        1 => Just(f64::MIN_POSITIVE / 4.0),
    ]
}

/// One brep: `vertices` vertices, triangles over them, parts over `part_count`.
fn brep(index: usize) -> impl Strategy<Value = BrepDef> {
    (1usize..30, 1u32..6).prop_flat_map(move |(vertex_count, part_count)| {
        let vertices =
            prop::collection::vec([coordinate(), coordinate(), coordinate()], vertex_count);
        let index_ = 0..vertex_count as u32;
        let triangles = prop::collection::vec(
            ([index_.clone(), index_.clone(), index_], 0..part_count),
            0..40,
        );
        (vertices, triangles, "[A-Za-z_][A-Za-z0-9_.-]{0,8}").prop_map(
            move |(vertices, triangles, stem)| BrepDef {
                name: format!("{stem}{index}"),
                vertices,
                part_count,
                parts: triangles.iter().map(|(_, p)| *p).collect(),
                triangles: triangles.into_iter().map(|(t, _)| t).collect(),
                ..BrepDef::default()
            },
        )
    })
}

fn placement(name: String) -> impl Strategy<Value = Placement> {
    let triple = || [coordinate(), coordinate(), coordinate()];
    (triple(), triple(), triple()).prop_map(move |(rotation_deg, translation, scale)| Placement {
        name: name.clone(),
        rotation_deg,
        translation,
        scale,
        ..Placement::default()
    })
}

/// A scene of 1 to 4 breps, at least one triangle, some of the breps placed.
fn description() -> impl Strategy<Value = ShpDescription> {
    (1usize..5)
        .prop_flat_map(|n| (0..n).map(brep).collect::<Vec<_>>())
        .prop_filter("some triangle", |breps| {
            breps.iter().any(|b| !b.triangles.is_empty())
        })
        .prop_flat_map(|breps| {
            let placed: Vec<_> = breps
                .iter()
                .enumerate()
                .filter(|(i, _)| i % 2 == 0)
                .map(|(_, b)| placement(b.name.clone()))
                .collect();
            (Just(breps), placed)
        })
        .prop_map(|(breps, placements)| ShpDescription {
            breps,
            placements,
            ..ShpDescription::default()
        })
}

/// What the reader should give back: the written content, with file and lines aside.
fn content(desc: &ShpDescription) -> (Vec<BrepDef>, Vec<Placement>) {
    let breps = desc
        .breps
        .iter()
        .map(|b| BrepDef {
            source: Default::default(),
            line: 0,
            ..b.clone()
        })
        .collect();
    let placements = desc
        .placements
        .iter()
        .map(|p| Placement {
            source: Default::default(),
            line: 0,
            ..p.clone()
        })
        .collect();
    (breps, placements)
}

/// Bit patterns, so that -0.0 and 0.0 differ and every digit counts.
fn bits(breps: &[BrepDef]) -> Vec<Vec<[u64; 3]>> {
    breps
        .iter()
        .map(|b| b.vertices.iter().map(|v| v.map(f64::to_bits)).collect())
        .collect()
}

/// The same text as another writer might lay it out: CRLF or LF, leading blanks and tabs,
/// trailing comments on some lines.
fn restyle(text: &str, crlf: bool, pad: &str, comment_every: usize) -> String {
    let end = if crlf { "\r\n" } else { "\n" };
    text.lines()
        .enumerate()
        .map(|(i, line)| {
            let mut out = format!("{pad}{line}");
            if comment_every > 0 && i % comment_every == 0 {
                out.push_str(" ;; Number of things");
            }
            out + end
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn written_scenes_read_back_the_same(
        desc in description(),
        crlf in any::<bool>(),
        pad in prop_oneof![Just(""), Just("  "), Just("\t "), Just(" \t")],
        comment_every in 0usize..4,
    ) {
        let text = restyle(&write_shp(&desc), crlf, pad, comment_every);
        let back = parse_shp(text.as_bytes(), Path::new(PATH))
            .map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        prop_assert_eq!(bits(&back.breps), bits(&desc.breps));
        prop_assert_eq!(content(&back), content(&desc));
        prop_assert!(back.breps.iter().all(|b| b.source == Path::new(PATH) && b.line > 0));
        // The scene builds from it: one world triangle per triangle, in order, or a clear
        // error for a placement that sends a vertex to infinity.
        if let Ok(scene) = Scene::build(&back, "prop") {
            let total: usize = desc.breps.iter().map(|b| b.triangles.len()).sum();
            prop_assert_eq!(scene.triangle_count(), total);
            prop_assert_eq!(scene.slots.len(), desc.breps.iter().map(|b| b.part_count as usize).sum::<usize>());
        }
    }

    #[test]
    fn damaged_files_give_a_scene_or_an_error(
        desc in description(),
        edits in prop::collection::vec((any::<prop::sample::Index>(), 0u8..4, any::<u8>()), 1..12),
        cut in any::<prop::sample::Index>(),
        truncate in any::<bool>(),
    ) {
        let mut bytes = write_shp(&desc).into_bytes();
        for (at, op, byte) in edits {
            let i = at.index(bytes.len().max(1));
            let interesting = b" \n\r;-+.e0123456789";
            match op {
                0 if i < bytes.len() => bytes[i] = byte,
                1 => bytes.insert(i.min(bytes.len()), interesting[byte as usize % interesting.len()]),
                2 if i < bytes.len() => { bytes.remove(i); }
                _ => {
                    // Duplicate a slice: repeated lines and sections.
                    let end = (i + byte as usize).min(bytes.len());
                    let copy = bytes[i.min(end)..end].to_vec();
                    bytes.splice(end..end, copy);
                }
            }
        }
        if truncate {
            bytes.truncate(cut.index(bytes.len() + 1));
        }
        if let Ok(desc) = parse_shp(&bytes, Path::new(PATH)) {
            let _ = Scene::build(&desc, "prop");
        }
        let _ = parse_brs(&bytes, Path::new("prop.brs"), "prop");
    }
}

/// `.brs` files are the brep sections alone: the body of a written brep reads back the same.
#[test]
fn brep_bodies_read_back_as_brs() {
    let mut runner = proptest::test_runner::TestRunner::new(ProptestConfig {
        cases: 64,
        ..ProptestConfig::default()
    });
    runner
        .run(&brep(0), |brep| {
            let desc = ShpDescription {
                breps: vec![brep.clone()],
                ..ShpDescription::default()
            };
            let text = write_shp(&desc);
            let body: String = text
                .lines()
                .filter(|l| !l.starts_with("define") && !l.starts_with("enddef"))
                .map(|l| format!("{l}\n"))
                .collect();
            let back = parse_brs(body.as_bytes(), Path::new("prop.brs"), &brep.name)
                .map_err(|e| TestCaseError::fail(e.to_string()))?;
            prop_assert_eq!(&back.vertices, &brep.vertices);
            prop_assert_eq!(&back.triangles, &brep.triangles);
            prop_assert_eq!(back.part_count, brep.part_count);
            prop_assert_eq!(&back.parts, &brep.parts);
            Ok(())
        })
        .unwrap();
}
