//! Every kind of bad input, each as a small inline file: the message names the file, the line
//! and the reason.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use tracer_core::shp::{self, ShpError};

const FILE: &str = "scenes/box.shp";

/// A valid scene; tests replace one line (numbers on the right) to break it.
const BOX: &str = "\
;; a test box
define breps brs_1
vertices 4 ;; Number of vertices
0 0 0
1 0 0
0 1 0
0 0 1
triangles 2
0 1 2
0 2 3
parts 2
0 1
enddef
set breps brs_1
  rotation 0 0 0
enddef
";

fn with_line(number: usize, text: &str) -> String {
    let mut lines: Vec<&str> = BOX.lines().collect();
    lines[number - 1] = text;
    lines.join("\n") + "\n"
}

fn parse_err(text: impl AsRef<[u8]>) -> ShpError {
    shp::parse_shp(text.as_ref(), Path::new(FILE)).unwrap_err()
}

/// The error is on `line` of `FILE`, and its message says so and contains every `needle`.
fn assert_error(err: &ShpError, line: usize, needles: &[&str]) {
    let message = err.to_string();
    assert_eq!(err.path(), Path::new(FILE), "{message}");
    assert_eq!(err.line(), Some(line), "{message}");
    assert!(
        message.starts_with(&format!("{FILE}: line {line}: ")),
        "{message}"
    );
    for needle in needles {
        assert!(message.contains(needle), "`{needle}` not in: {message}");
    }
}

struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("raygine-shp-errors-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[test]
fn the_base_file_is_valid() {
    let desc = shp::parse_shp(BOX.as_bytes(), Path::new(FILE)).unwrap();
    assert_eq!(desc.breps[0].parts, [0, 1]);
}

#[test]
fn unreadable_file() {
    let path = Path::new("/nonexistent-raygine-dir/box.shp");
    let err = shp::load(path).unwrap_err();
    assert!(matches!(err, ShpError::Io { .. }));
    assert_eq!((err.path(), err.line()), (path, None));
    assert!(
        err.to_string()
            .starts_with("/nonexistent-raygine-dir/box.shp: cannot read the file: "),
        "{err}"
    );
}

#[test]
fn binary_input() {
    let esri = [
        0x00, 0x00, 0x27, 0x0A, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x27, 0x10,
    ];
    let with_nul = format!("{}\0\n{BOX}", &BOX[..20]);
    let control: Vec<u8> = (0..200u8)
        .map(|i| if i % 3 == 0 { 0x01 } else { b'a' })
        .collect();
    for bytes in [&esri[..], with_nul.as_bytes(), &control] {
        let err = parse_err(bytes);
        assert!(matches!(err, ShpError::Binary { .. }), "{err}");
        assert_eq!(err.line(), None);
        assert_eq!(
            err.to_string(),
            "scenes/box.shp: this is a binary file, not a Lumicept text .shp (an ESRI shapefile?)"
        );
    }
}

#[test]
fn non_utf8_text() {
    let mut bytes = with_line(2, "define breps brX").into_bytes();
    let at = bytes.iter().position(|&b| b == b'X').unwrap();
    bytes[at] = 0xE9;
    assert_error(&parse_err(&bytes), 2, &["not UTF-8", "column 16"]);
    // UTF-16 text is caught by its byte order mark.
    let utf16: Vec<u8> = [0xFF, 0xFE]
        .into_iter()
        .chain(BOX.bytes().flat_map(|b| [b, 0]))
        .collect();
    assert_error(&parse_err(utf16), 1, &["not UTF-8"]);
}

#[test]
fn non_finite_coordinates() {
    for (token, line) in [("nan", 4), ("inf", 5), ("-1e400", 6), ("1e309", 7)] {
        let err = parse_err(with_line(line, &format!("0 {token} 0")));
        assert!(matches!(err, ShpError::NonFinite { .. }), "{err}");
        assert_error(
            &err,
            line,
            &[
                &format!("`{token}` is not a finite number"),
                "vertex",
                "brs_1",
            ],
        );
    }
    let err = parse_err(with_line(15, "  rotation 0 0 1e999"));
    assert_error(
        &err,
        15,
        &[
            "`1e999` is not a finite number",
            "rotation of `set breps brs_1`",
        ],
    );
}

#[test]
fn missing_numbers() {
    let err = parse_err(with_line(5, "1 0"));
    assert!(matches!(err, ShpError::MissingNumber { .. }));
    assert_error(
        &err,
        5,
        &["vertex 1 of brep brs_1 needs 3 numbers, found 2"],
    );
    assert_error(
        &parse_err(with_line(9, "0 1")),
        9,
        &["triangle 0 of brep brs_1 needs 3 numbers, found 2"],
    );
    assert_error(
        &parse_err(with_line(3, "vertices")),
        3,
        &["`vertices` needs 1 numbers, found 0"],
    );
    assert_error(
        &parse_err(with_line(15, "rotation 1 2")),
        15,
        &["rotation", "needs 3 numbers, found 2"],
    );
    // The parts list is cut short by `enddef`.
    assert_error(
        &parse_err(with_line(12, "0")),
        13,
        &["`parts` list of brep brs_1", "needs 2 numbers, found 1"],
    );
}

#[test]
fn file_ends_early() {
    // Room for a fourth vertex, judged by bytes and lines left, but no fourth vertex.
    let cut = "define breps brs_1\r\nvertices 4\r\n0.0 0.0 0.0\r\n1.0 0.0 0.0\r\n0.0 1.0 0.0\r\n;; the end\r\n";
    let err = parse_err(cut);
    assert!(matches!(err, ShpError::UnexpectedEnd { .. }), "{err}");
    assert_error(
        &err,
        6,
        &[
            "the file ends early",
            "brep brs_1 announces 4 vertices, the file has 3",
        ],
    );
    let cut = BOX.lines().take(11).collect::<Vec<_>>().join("\n");
    assert_error(
        &parse_err(&cut),
        11,
        &["ends early", "`parts` list of brep brs_1"],
    );
}

#[test]
fn malformed_numbers() {
    let err = parse_err(with_line(6, "0 1.2.3 0"));
    assert!(matches!(err, ShpError::MalformedNumber { .. }));
    assert_error(
        &err,
        6,
        &["vertex 2 of brep brs_1", "`1.2.3` is not a number"],
    );
    assert_error(
        &parse_err(with_line(10, "0 -2 3")),
        10,
        &["triangle 1 of brep brs_1", "`-2` is not a whole number"],
    );
    assert_error(
        &parse_err(with_line(10, "0 2.0 3")),
        10,
        &["`2.0` is not a whole number"],
    );
    assert_error(
        &parse_err(with_line(8, "triangles two")),
        8,
        &["`triangles`", "`two` is not a whole number"],
    );
    assert_error(
        &parse_err(with_line(3, "vertices 4294967296")),
        3,
        &["`4294967296` is not a whole number"],
    );
    assert_error(
        &parse_err(with_line(12, "0 x1")),
        12,
        &["`parts` list", "cut short by `x1`"],
    );
    assert_error(
        &parse_err(with_line(12, "0 1,")),
        12,
        &["part of triangle 1", "`1,` is not a part index"],
    );
}

#[test]
fn counts_larger_than_the_file() {
    let err = parse_err(with_line(3, "vertices 999999999"));
    assert!(
        matches!(
            err,
            ShpError::CountTooLarge {
                count: 999_999_999,
                ..
            }
        ),
        "{err}"
    );
    assert_error(
        &err,
        3,
        &["`vertices 999999999` announces more vertices than the rest of the file can hold"],
    );
    let err = parse_err(with_line(8, "triangles 4000000000"));
    assert_error(
        &err,
        8,
        &["`triangles 4000000000` announces more triangles"],
    );
    // Just one more than there are lines left is caught too (blank lines fill bytes, not items).
    let padded = with_line(3, "vertices 40") + &"\n".repeat(5);
    assert_error(&parse_err(padded), 3, &["announces more vertices"]);
}

#[test]
fn extra_values() {
    let err = parse_err(with_line(4, "0 0 0 1"));
    assert!(matches!(err, ShpError::ExtraValue { .. }), "{err}");
    assert_error(
        &err,
        4,
        &[
            "vertex 0 of brep brs_1",
            "unexpected `1` after the 3 expected values",
        ],
    );
    assert_error(
        &parse_err(with_line(12, "0 1 1")),
        12,
        &["`parts` list", "unexpected `1` after the 2"],
    );
    assert_error(
        &parse_err(with_line(11, "parts 2 3")),
        11,
        &["`parts`", "unexpected `3`"],
    );
}

#[test]
fn vertex_index_out_of_range() {
    let text = with_line(10, "0 2 3").replace("0 1 2\n", "0 1 7\n");
    let err = parse_err(text);
    assert!(
        matches!(err, ShpError::VertexOutOfRange { vertex: 7, .. }),
        "{err}"
    );
    assert_eq!(
        err.to_string(),
        "scenes/box.shp: line 9: triangle 0 of brep brs_1 uses vertex 7, but the brep has 4 vertices"
    );
    assert_error(
        &parse_err(with_line(10, "0 2 4")),
        10,
        &["triangle 1 of brep brs_1 uses vertex 4"],
    );
}

#[test]
fn part_index_out_of_range() {
    let err = parse_err(with_line(12, "0 2"));
    assert!(
        matches!(
            err,
            ShpError::PartOutOfRange {
                part: 2,
                part_count: 2,
                ..
            }
        ),
        "{err}"
    );
    assert_error(
        &err,
        12,
        &["triangle 1 of brep brs_1 is in part 2, but the brep declares 2 parts"],
    );
    assert_error(
        &parse_err(with_line(11, "parts 0")),
        12,
        &["triangle 0", "declares 0 parts"],
    );
    let err = parse_err(with_line(11, "parts 4000000000"));
    assert!(matches!(err, ShpError::TooManyParts { .. }), "{err}");
    assert_error(
        &err,
        11,
        &["brep brs_1 declares 4000000000 parts but has only 2 triangles"],
    );
}

#[test]
fn placed_brep_that_is_nowhere() {
    let dir = TempDir::new("missing");
    let path = dir.0.join("box.shp");
    std::fs::write(&path, BOX.replace("set breps brs_1", "set breps lamp")).unwrap();
    let err = shp::load(&path).unwrap_err();
    assert!(matches!(err, ShpError::MissingBrep { .. }), "{err}");
    assert_eq!((err.path(), err.line()), (path.as_path(), Some(14)));
    let message = err.to_string();
    let expected_brs = dir.0.join("lamp.brs");
    assert!(
        message.contains("`set breps lamp` places a brep that is neither defined"),
        "{message}"
    );
    assert!(
        message.contains(&expected_brs.display().to_string()),
        "{message}"
    );
    // parse_shp keeps such a placement for the caller.
    let desc = shp::parse_shp(&std::fs::read(&path).unwrap(), &path).unwrap();
    assert_eq!(desc.placements[0].name, "lamp");
}

#[test]
fn errors_inside_a_brs_name_the_brs() {
    let dir = TempDir::new("brs");
    let path = dir.0.join("room.shp");
    std::fs::write(&path, "set breps room\nenddef\n").unwrap();
    std::fs::write(
        dir.0.join("room.brs"),
        "vertices 3\n0 0 0\n1 0 0\n0 1 0\ntriangles 1\n0 1 3\n",
    )
    .unwrap();
    let err = shp::load(&path).unwrap_err();
    assert_eq!(
        (err.path(), err.line()),
        (dir.0.join("room.brs").as_path(), Some(6))
    );
    assert!(
        err.to_string()
            .contains("room.brs: line 6: triangle 0 of brep room uses vertex 3"),
        "{err}"
    );
}

#[test]
fn scene_without_triangles() {
    for text in [
        "",
        ";; nothing\n",
        "ProcessMesh\nenddef\n",
        "define breps a\nvertices 1\n0 0 0\nenddef\nset breps a\nenddef\n",
    ] {
        let err = parse_err(text);
        assert!(matches!(err, ShpError::NoTriangles { .. }), "{err}");
        assert_eq!(err.line(), None);
        assert_eq!(
            err.to_string(),
            "scenes/box.shp: the scene has no triangles (no brep with a `triangles` section)"
        );
    }
}

#[test]
fn duplicate_brep() {
    let block: String = BOX
        .lines()
        .skip(1)
        .take(12)
        .map(|l| format!("{l}\n"))
        .collect();
    let err = parse_err(format!("{BOX}{block}"));
    assert!(
        matches!(err, ShpError::DuplicateBrep { first_line: 2, .. }),
        "{err}"
    );
    assert_error(&err, 17, &["brep brs_1 is defined twice (first at line 2)"]);
}

#[test]
fn missing_enddef_at_end_of_file() {
    let cut = BOX.lines().take(12).collect::<Vec<_>>().join("\n");
    let err = parse_err(&cut);
    assert!(matches!(err, ShpError::MissingEnddef { .. }), "{err}");
    assert_error(
        &err,
        2,
        &[
            "`define breps brs_1` block opened here has no `enddef`",
            "ends at line 12",
        ],
    );
    let cut = BOX.lines().take(15).collect::<Vec<_>>().join("\n");
    assert_error(
        &parse_err(&cut),
        14,
        &["`set breps brs_1` block", "no `enddef`"],
    );
    let unknown = format!("{BOX}\nLight lamp\n  position 1 2 3\n");
    assert_error(
        &parse_err(unknown),
        18,
        &[
            "`Light lamp` block opened here has no `enddef`",
            "ends at line 19",
        ],
    );
}

#[test]
fn unexpected_keywords() {
    let err = parse_err(with_line(11, "colors 2"));
    assert!(matches!(err, ShpError::UnexpectedKeyword { .. }), "{err}");
    assert_error(
        &err,
        11,
        &["unexpected `colors` in brep brs_1; expected `parts P` or `enddef`"],
    );
    assert_error(
        &parse_err(with_line(15, "  spin 0 0 0")),
        15,
        &[
            "unexpected `spin` in `set breps brs_1`",
            "`rotation`, `translation`, `scale` or `enddef`",
        ],
    );
    assert_error(
        &parse_err(with_line(16, "  rotation 1 1 1")),
        16,
        &["`rotation` was given at line 15"],
    );
    // A section cut short by the next keyword.
    assert_error(
        &parse_err(with_line(3, "vertices 5")),
        8,
        &["unexpected `triangles` in vertex 4 of brep brs_1; expected 3 numbers"],
    );
    // Sections out of order.
    assert_error(
        &parse_err(with_line(3, "triangles 4")),
        3,
        &[
            "unexpected `triangles` in brep brs_1",
            "expected `GeoChecked` or `vertices N`",
        ],
    );
    // A geometry block inside a skipped one means an `enddef` went missing.
    let text = format!("Light lamp\n  position 1 2 3\n{BOX}");
    assert_error(
        &parse_err(text),
        4,
        &[
            "unexpected `define breps` in the `Light lamp` block opened at line 1",
            "`enddef` first",
        ],
    );
    assert_error(
        &parse_err(format!("enddef\n{BOX}")),
        1,
        &["unexpected `enddef` in the top level"],
    );
    assert_error(
        &parse_err(format!("{BOX}1 2 3\n")),
        17,
        &["unexpected `1` in the top level"],
    );
    assert_error(
        &parse_err(with_line(2, "define breps a b")),
        2,
        &["unexpected `b` in `define breps a`"],
    );
}

#[test]
fn missing_brep_name() {
    let err = parse_err(with_line(2, "define breps"));
    assert!(matches!(err, ShpError::MissingName { .. }), "{err}");
    assert_error(&err, 2, &["`define breps` needs a brep name"]);
    assert_error(
        &parse_err(with_line(14, "Set Breps ;; brs_1")),
        14,
        &["`Set breps` needs a brep name"],
    );
}
