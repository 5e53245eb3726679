//! What the reader accepts: line ends, blanks, comments, number forms, skipped blocks, `.brs`
//! files, and the round trip through `write_shp`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use tracer_core::shp::{self, BrepDef, Placement, ShpDescription, ShpError};

fn parse(text: &str) -> ShpDescription {
    shp::parse_shp(text.as_bytes(), Path::new("t.shp")).unwrap()
}

/// The description with file names and line numbers cleared: what must survive any change of
/// layout or location.
fn geometry(desc: &ShpDescription) -> ShpDescription {
    let mut desc = desc.clone();
    desc.path = PathBuf::new();
    for brep in &mut desc.breps {
        (brep.source, brep.line) = (PathBuf::new(), 0);
    }
    for placement in &mut desc.placements {
        (placement.source, placement.line) = (PathBuf::new(), 0);
    }
    desc
}

const PLAIN: &str = "\
define breps a
vertices 3
1 2 3
4 5 6
7 8 9
triangles 1
0 1 2
enddef
set breps a
rotation 10 20 30
translation 1 2 3
scale 2 2 2
enddef
";

#[test]
fn plain_file() {
    let desc = parse(PLAIN);
    let brep = &desc.breps[0];
    assert_eq!(
        (brep.name.as_str(), brep.line, brep.source.as_path()),
        ("a", 1, Path::new("t.shp"))
    );
    assert_eq!(
        brep.vertices,
        [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0]]
    );
    assert_eq!(brep.triangles, [[0, 1, 2]]);
    assert_eq!(
        (brep.part_count, brep.parts.as_slice()),
        (1, &[0][..]),
        "no parts section: one part"
    );
    let placement = &desc.placements[0];
    assert_eq!(
        (placement.line, placement.rotation_deg),
        (9, [10.0, 20.0, 30.0])
    );
    assert_eq!(
        (placement.translation, placement.scale),
        ([1.0, 2.0, 3.0], [2.0; 3])
    );
}

#[test]
fn line_ends_blanks_and_case_do_not_matter() {
    let want = geometry(&parse(PLAIN));
    let crlf = PLAIN.replace('\n', "\r\n");
    let lone_cr = PLAIN.replace('\n', "\r");
    let tabs = PLAIN.replace(' ', " \t ").replace('\n', " \t\n\n  \t");
    let upper = PLAIN
        .replace("define breps", "DEFINE Breps")
        .replace("vertices", "Vertices")
        .replace("enddef", "EndDef");
    for text in [crlf, lone_cr, tabs, upper, format!("\u{feff}{PLAIN}")] {
        assert_eq!(geometry(&parse(&text)), want, "{text:?}");
    }
    // Line numbers count every kind of line end.
    assert_eq!(parse(&PLAIN.replace('\n', "\r")).placements[0].line, 9);
}

#[test]
fn comments_anywhere() {
    let commented = PLAIN
        .lines()
        .map(|l| format!(";; before\n{l} ;; after: 1 2 3 enddef vertices\n"))
        .collect::<String>();
    assert_eq!(geometry(&parse(&commented)), geometry(&parse(PLAIN)));
    let glued = PLAIN.replace("1 2 3\n", "1 2 3;;no blank before the comment\n");
    assert_eq!(geometry(&parse(&glued)), geometry(&parse(PLAIN)));
}

#[test]
fn number_forms() {
    let text = PLAIN
        .replace("1 2 3\n4 5 6", "1.000000e+000 +2 3E0\n-0 -0.00000 1E-3")
        .replace("0 1 2", "+0 1 2");
    let brep = &parse(&text).breps[0];
    assert_eq!(brep.vertices[0], [1.0, 2.0, 3.0]);
    assert_eq!(brep.vertices[1], [0.0, 0.0, 0.001]);
    assert!(brep.vertices[1][0].is_sign_negative());
    assert_eq!(brep.triangles[0], [0, 1, 2]);
}

#[test]
fn parts_over_any_number_of_lines() {
    let text = "define breps a\nGeoChecked\nvertices 3\n0 0 0\n1 0 0\n0 1 0\ntriangles 4\n0 1 2\n0 2 1\n1 2 0\n2 1 0\nparts 3 ;; Number of parts\n 0  2\n\n1 ;; x\n  2 \nenddef\n";
    let brep = &parse(text).breps[0];
    assert_eq!(
        (brep.part_count, brep.parts.as_slice()),
        (3, &[0, 2, 1, 2][..])
    );
}

#[test]
fn unknown_blocks_are_skipped() {
    let text = format!(
        "ProcessMesh\n  Optimization on \n  TriangleSize 5.00% \nenddef\n\
         Light lamp\n  position 1 2 3\nenddef\n\
         product pproom2\n  attrs\n    A000001\n  mapp\n    none\nenddef\n\
         Diagram d\n  def\n    1.0 2.0\nenddef\n\
         {PLAIN}\
         Camera C000001\n  viewpoint 0 0 0\n  screen\n  1 2 3\nenddef\n"
    );
    assert_eq!(geometry(&parse(&text)), geometry(&parse(PLAIN)));
}

#[test]
fn placement_defaults_and_empty_breps() {
    let text = "define breps empty\nenddef\ndefine breps a\nvertices 3\n0 0 0\n1 0 0\n0 1 0\ntriangles 1\n0 1 2\nenddef\nset breps a\n  scale 1 2 3\nenddef\nset breps a\nenddef\n";
    let desc = parse(text);
    assert_eq!(desc.breps[0].vertices.len(), 0);
    let want = Placement {
        name: "a".into(),
        source: "t.shp".into(),
        line: 11,
        scale: [1.0, 2.0, 3.0],
        ..Placement::default()
    };
    assert_eq!(desc.placements[0], want);
    assert_eq!(
        (desc.placements[1].rotation_deg, desc.placements[1].scale),
        ([0.0; 3], [1.0; 3])
    );
}

#[test]
fn round_trip_through_write_shp() {
    let brep = BrepDef {
        name: "brs_0".into(),
        vertices: vec![
            [0.1, -0.0, 1e-7],
            [1e21, -123.456789012345, f64::MIN_POSITIVE],
            [3.0, 2.0, 1.0],
            [5e-324, 7.0, 8.0],
        ],
        triangles: (0..23).map(|i| [i % 4, (i + 1) % 4, (i + 2) % 4]).collect(),
        part_count: 3,
        parts: (0..23).map(|i| i % 3).collect(),
        ..BrepDef::default()
    };
    let placement = Placement {
        name: "brs_0".into(),
        rotation_deg: [90.0, 0.5, -1.0 / 3.0],
        translation: [1.0, 2.0, 3.0],
        ..Placement::default()
    };
    let desc = ShpDescription {
        path: "x.shp".into(),
        breps: vec![brep],
        placements: vec![placement.clone(), placement],
    };
    let text = shp::write_shp(&desc);
    assert!(!text.contains('\r'));
    assert!(text.find("define breps").unwrap() < text.find("set breps").unwrap());
    let back = parse(&text);
    assert_eq!(geometry(&back), geometry(&desc));
    for (a, b) in back.breps[0]
        .vertices
        .iter()
        .flatten()
        .zip(desc.breps[0].vertices.iter().flatten())
    {
        assert_eq!(a.to_bits(), b.to_bits(), "bit-exact: {a} vs {b}");
    }
    // A second trip writes the same text.
    assert_eq!(shp::write_shp(&back), text);
}

#[test]
fn real_files_round_trip() {
    let Some(shared) = raygine_fixtures::shared("scenes") else {
        return;
    };
    for file in [
        "cornell/cornel_box0.shp",
        "ipur-room2/room2.shp",
        "meshes/teapot.shp",
    ] {
        let desc = shp::load(&shared.join(file)).unwrap();
        assert_eq!(
            geometry(&parse(&shp::write_shp(&desc))),
            geometry(&desc),
            "{file}"
        );
    }
}

#[test]
fn brs_files() {
    let path = Path::new("dir/room.brs");
    let text = ";; created by IPUR\r\n\r\nvertices 3 ;; number of vertices\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\ntriangles 2\r\n0 1 2\r\n2 1 0\r\nparts 2\r\n0 1 \r\n\r\nshading\r\n0 0 \r\n";
    let brep = shp::parse_brs(text.as_bytes(), path, "room").unwrap();
    assert_eq!(
        (brep.name.as_str(), brep.source.as_path(), brep.line),
        ("room", path, 3)
    );
    assert_eq!(
        (brep.triangles.len(), brep.part_count, brep.parts.as_slice()),
        (2, 2, &[0, 1][..])
    );

    let short_shading = text.replace("shading\r\n0 0 ", "shading\r\n0");
    let err = shp::parse_brs(short_shading.as_bytes(), path, "room").unwrap_err();
    assert!(matches!(err, ShpError::UnexpectedEnd { .. }), "{err}");
    assert!(
        err.to_string()
            .starts_with("dir/room.brs: line 14: the file ends early: the `shading` list"),
        "{err}"
    );

    let trailing = format!("{text}vertices 1\r\n");
    let err = shp::parse_brs(trailing.as_bytes(), path, "room").unwrap_err();
    assert!(err.to_string().contains("line 15: unexpected `vertices` in the .brs file of brep room; expected nothing after `shading`"), "{err}");

    let err = shp::parse_brs(b";; empty\n", path, "room").unwrap_err();
    assert!(
        err.to_string().contains("has no `vertices N` section"),
        "{err}"
    );
    let err = shp::parse_brs(b"define breps room\n", path, "room").unwrap_err();
    assert!(
        err.to_string().contains("line 1: unexpected `define`"),
        "{err}"
    );
}

#[test]
fn load_finds_brs_files_beside_the_shp() {
    let dir = std::env::temp_dir().join(format!("raygine-shp-format-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shp_path = dir.join("scene.shp");
    let text = "set breps Chair\nenddef\nset breps chair\ntranslation 1 0 0\nenddef\nset breps Chair\nenddef\ndefine breps own\nvertices 3\n0 0 0\n1 0 0\n0 1 0\ntriangles 1\n0 1 2\nenddef\n";
    std::fs::write(&shp_path, text).unwrap();
    // Only a lower-case file: `Chair` finds it by case-insensitive match, and is loaded once.
    std::fs::write(
        dir.join("chair.brs"),
        "vertices 3\n0 0 0\n1 0 0\n0 1 0\ntriangles 1\n0 1 2\n",
    )
    .unwrap();
    let result = shp::load(&shp_path);
    let _ = std::fs::remove_dir_all(&dir);
    let desc = result.unwrap();
    let names: Vec<_> = desc.breps.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["own", "Chair", "chair"]);
    assert_eq!(desc.breps[1].source, dir.join("chair.brs"));
    assert_eq!(desc.placements.len(), 3);
}
