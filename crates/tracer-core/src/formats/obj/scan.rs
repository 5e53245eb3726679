//! The line-by-line check of an OBJ file before `tobj` reads it, so every problem is reported
//! with its line: numbers must parse and be finite, face corners must name vertices that exist.
//! Its output is the same file cleaned of what raygine does not draw (lines, points, curves)
//! with every face corner as an absolute `v`, `v/vt`, `v//vn` or `v/vt/vn` reference, which
//! `tobj` then reads without surprises. A texture coordinate that is not a finite number reads
//! as 0 (noted with its line): it only moves a texture, so the file still opens.

use crate::formats::error::{FormatError, check_memory};
use std::fmt::Write;
use std::path::Path;

/// What the check found, and the cleaned text.
#[derive(Debug, Default)]
pub(super) struct Scan {
    pub text: String,
    /// Material libraries named by `mtllib`, with their lines.
    pub libraries: Vec<(usize, String)>,
    pub notes: Vec<String>,
}

/// The text of line `i` (1-based) of `bytes`, as UTF-8 without its comment.
fn lines(bytes: &[u8]) -> impl Iterator<Item = (usize, Result<&str, ()>)> {
    bytes.split(|&b| b == b'\n').enumerate().map(|(i, raw)| {
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        let text = std::str::from_utf8(raw).map_err(|_| ());
        (
            i + 1,
            text.map(|t| t.split('#').next().unwrap_or("").trim()),
        )
    })
}

fn numbers(words: &[&str], path: &Path, line: usize, what: &str) -> Result<Vec<f64>, FormatError> {
    words
        .iter()
        .map(|w| match w.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(FormatError::new(
                path,
                line,
                format!("{what}: `{w}` is not a finite number"),
            )),
        })
        .collect()
}

/// Checks `bytes` as OBJ text and returns the cleaned text.
pub(super) fn scan(bytes: &[u8], path: &Path) -> Result<Scan, FormatError> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    // First pass: how many positions and normals the file defines (faces may name later ones),
    // and how many triangles it will make, checked against memory before anything is built.
    let (mut total_v, mut total_vn, mut total_vt, mut triangles) = (0u64, 0u64, 0u64, 0u64);
    for (line, text) in lines(bytes) {
        let text = text.map_err(|()| FormatError::new(path, line, "not UTF-8 text"))?;
        let mut words = text.split_whitespace();
        match words.next() {
            Some("v") => total_v += 1,
            Some("vn") => total_vn += 1,
            Some("vt") => total_vt += 1,
            Some("f") => triangles += (words.count() as u64).saturating_sub(2),
            _ => {}
        }
    }
    check_memory(path, 0, triangles, total_v)?;
    let mut out = Scan {
        text: String::with_capacity(bytes.len().min(1 << 30)),
        ..Scan::default()
    };
    let (mut v, mut vn, mut vt) = (0u64, 0u64, 0u64);
    let (mut skipped_lines, mut skipped_faces) = (0usize, 0usize);
    // Lines of texture coordinates that were not finite numbers.
    let mut bad_vt: Vec<usize> = Vec::new();
    for (line, text) in lines(bytes) {
        let text = text.map_err(|()| FormatError::new(path, line, "not UTF-8 text"))?;
        let words: Vec<&str> = text.split_whitespace().collect();
        let Some((&key, rest)) = words.split_first() else {
            out.text.push('\n');
            continue;
        };
        match key {
            "v" => {
                let xs = numbers(rest, path, line, "v")?;
                match xs.len() {
                    3 | 6 => {}
                    4 if xs[3] != 0.0 => {}
                    4 => return Err(FormatError::new(path, line, "v: the weight w is 0")),
                    n => {
                        return Err(FormatError::new(
                            path,
                            line,
                            format!("v takes x y z (and w, or r g b), found {n} numbers"),
                        ));
                    }
                }
                v += 1;
                let _ = write!(out.text, "v {} {} {}", xs[0], xs[1], xs[2]);
                if xs.len() == 4 {
                    let _ = write!(out.text, " {}", xs[3]);
                }
            }
            "vn" => {
                let xs = numbers(rest, path, line, "vn")?;
                if xs.len() != 3 {
                    return Err(FormatError::new(
                        path,
                        line,
                        format!("vn takes x y z, found {} numbers", xs.len()),
                    ));
                }
                vn += 1;
                let _ = write!(out.text, "vn {} {} {}", xs[0], xs[1], xs[2]);
            }
            "vt" => {
                if rest.is_empty() || rest.len() > 3 {
                    return Err(FormatError::new(
                        path,
                        line,
                        format!("vt takes u (v (w)), found {} numbers", rest.len()),
                    ));
                }
                let mut uv = [0.0f64; 2];
                for (x, w) in uv.iter_mut().zip(rest) {
                    match w.parse::<f64>() {
                        Ok(n) if n.is_finite() => *x = n,
                        Ok(_) => bad_vt.push(line),
                        Err(_) => {
                            return Err(FormatError::new(
                                path,
                                line,
                                format!("vt: `{w}` is not a number"),
                            ));
                        }
                    }
                }
                vt += 1;
                let _ = write!(out.text, "vt {} {}", uv[0], uv[1]);
            }
            "vp" => {
                numbers(rest, path, line, key)?;
            }
            "f" => {
                if rest.len() < 3 {
                    skipped_faces += 1;
                } else {
                    let so_far = Counts { v, vt, vn };
                    let total = Counts {
                        v: total_v,
                        vt: total_vt,
                        vn: total_vn,
                    };
                    let corners: Vec<Corner> = rest
                        .iter()
                        .map(|c| corner(c, &so_far, &total, path, line))
                        .collect::<Result<_, _>>()?;
                    // tobj gives each corner one index: texture coordinates and normals on
                    // every corner or on none.
                    let textures = corners.iter().all(|c| c.texture.is_some());
                    let normals = corners.iter().all(|c| c.normal.is_some());
                    out.text.push('f');
                    for c in corners {
                        let p = c.position;
                        match (c.texture.filter(|_| textures), c.normal.filter(|_| normals)) {
                            (Some(t), Some(n)) => {
                                let _ = write!(out.text, " {p}/{t}/{n}");
                            }
                            (Some(t), None) => {
                                let _ = write!(out.text, " {p}/{t}");
                            }
                            (None, Some(n)) => {
                                let _ = write!(out.text, " {p}//{n}");
                            }
                            (None, None) => {
                                let _ = write!(out.text, " {p}");
                            }
                        }
                    }
                }
            }
            "l" | "p" | "curv" | "curv2" | "surf" => skipped_lines += 1,
            "mtllib" => {
                let name = text["mtllib".len()..].trim();
                if !name.is_empty() {
                    // One `mtllib` line for tobj, where the first stood: the reader hands it
                    // every library's materials at once.
                    if out.libraries.is_empty() {
                        out.text.push_str("mtllib libraries");
                    }
                    out.libraries.push((line, name.to_owned()));
                }
            }
            "usemtl" => {
                let name = text["usemtl".len()..].trim();
                if name.is_empty() {
                    return Err(FormatError::new(path, line, "usemtl needs a material name"));
                }
                let _ = write!(out.text, "usemtl {name}");
            }
            "o" | "g" => {
                let name = text[1..].trim();
                let _ = write!(out.text, "{key} {name}");
            }
            _ => {}
        }
        out.text.push('\n');
    }
    if skipped_lines > 0 || skipped_faces > 0 {
        out.notes.push(format!(
            "{}: {} line, point or curve elements and {} faces of fewer than 3 corners are not \
             surfaces; skipped",
            path.display(),
            skipped_lines,
            skipped_faces
        ));
    }
    if let Some(first) = bad_vt.first() {
        out.notes.push(format!(
            "{}:{first}: {} texture coordinates are not finite numbers (lines {}); they read \
             as 0",
            path.display(),
            bad_vt.len(),
            bad_vt
                .iter()
                .take(5)
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
                + if bad_vt.len() > 5 { ", ..." } else { "" }
        ));
    }
    Ok(out)
}

/// How many positions, texture coordinates and normals (so far, or in the file).
struct Counts {
    v: u64,
    vt: u64,
    vn: u64,
}

/// A face corner's absolute 1-based indices.
struct Corner {
    position: u64,
    texture: Option<u64>,
    normal: Option<u64>,
}

/// One face corner `v`, `v/vt`, `v//vn` or `v/vt/vn` as absolute 1-based indices; negative
/// indices count back from the last defined so far.
fn corner(
    text: &str,
    so_far: &Counts,
    total: &Counts,
    path: &Path,
    line: usize,
) -> Result<Corner, FormatError> {
    let mut parts = text.split('/');
    let resolve = |word: &str, so_far: u64, total: u64, what: &str| -> Result<u64, FormatError> {
        let bad = |why: String| FormatError::new(path, line, format!("f: corner `{text}`: {why}"));
        let i: i64 = word
            .parse()
            .map_err(|_| bad(format!("`{word}` is not a whole number")))?;
        let absolute = if i < 0 {
            (so_far as i64).checked_add(i + 1).unwrap_or(0)
        } else {
            i
        };
        if absolute < 1 || absolute as u64 > total {
            return Err(bad(format!(
                "{what} {i} does not exist (the file has {total})"
            )));
        }
        Ok(absolute as u64)
    };
    let position = resolve(parts.next().unwrap_or(""), so_far.v, total.v, "vertex")?;
    let texture = match parts.next() {
        Some(w) if !w.is_empty() => Some(resolve(w, so_far.vt, total.vt, "texture coordinate")?),
        _ => None,
    };
    let normal = match parts.next() {
        Some(w) if !w.is_empty() => Some(resolve(w, so_far.vn, total.vn, "normal")?),
        _ => None,
    };
    if parts.next().is_some() {
        return Err(FormatError::new(
            path,
            line,
            format!("f: corner `{text}` has more than v/vt/vn"),
        ));
    }
    Ok(Corner {
        position,
        texture,
        normal,
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        scan(text.as_bytes(), Path::new("m.obj"))
            .expect_err("refused")
            .to_string()
    }

    #[test]
    fn problems_are_reported_with_their_line() {
        assert_eq!(
            err("v 0 0 0\nv 1 nan 0\n"),
            "m.obj:2: v: `nan` is not a finite number"
        );
        assert_eq!(
            err("v 0 0\n"),
            "m.obj:1: v takes x y z (and w, or r g b), found 2 numbers"
        );
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
            "m.obj:4: f: corner `4`: vertex 4 does not exist (the file has 3)"
        );
        assert_eq!(
            err("v 0 0 0\nf 1 -2 1\n"),
            "m.obj:2: f: corner `-2`: vertex -2 does not exist (the file has 1)"
        );
        assert_eq!(err("usemtl\n"), "m.obj:1: usemtl needs a material name");
        let bytes = scan(b"v 0 0 0\n\xff\n", Path::new("m.obj"));
        assert_eq!(
            bytes.expect_err("refused").to_string(),
            "m.obj:2: not UTF-8 text"
        );
    }

    #[test]
    fn faces_are_rewritten_with_absolute_indices_and_consistent_normals() {
        let s = scan(
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf -3/1/1 -2/1/1 -1/1/1\nf 1 2/1 3//1\nl 1 2\n",
            Path::new("m.obj"),
        )
        .expect("valid");
        let faces: Vec<&str> = s.text.lines().filter(|l| l.starts_with('f')).collect();
        assert_eq!(faces, ["f 1/1/1 2/1/1 3/1/1", "f 1 2 3"]);
        assert_eq!(s.notes.len(), 1, "{:?}", s.notes);
        // A NaN texture coordinate is noted with its line and reads as 0.
        let s = scan(b"v 0 0 0\nvt 0.5 nan\nvt inf 1\n", Path::new("m.obj")).expect("valid");
        assert!(s.text.contains("vt 0.5 0\nvt 0 1"), "{}", s.text);
        assert!(
            s.notes[0].starts_with("m.obj:2: 2 texture coordinates"),
            "{:?}",
            s.notes
        );
        assert!(err("vt 1 2 3 4\n").contains("vt takes u"));
        assert!(
            err("v 0 0 0\nvt 0 0\nf 1/2 1/1 1/1\n").contains("texture coordinate 2 does not exist")
        );
    }
}
