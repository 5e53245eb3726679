//! IES LM-63 photometric files: the headers of 1986/1991 (none or `IESNA91`), 1995, 2002 and
//! 2019, `TILT=NONE` and `TILT=INCLUDE` (the tilt table is read and not applied: it describes a
//! lamp tilted away from its photometered position), photometric type C.
//!
//! Absolute candela = value × candela multiplier × ballast factor × ballast-lamp factor. With
//! relative photometry (lumens per lamp > 0) the values are already candela for the rated lamps.

use super::{MAX_ANGLES, MAX_VALUES, PhotometryFileError, Symmetry, unfold};
use crate::light::{LuminaireInfo, LuminousShape, Photometry, Plane};
use std::path::Path;

/// A number token and the line it is on.
struct Token<'a> {
    text: &'a str,
    line: usize,
}

struct Numbers<'a> {
    tokens: Vec<Token<'a>>,
    next: usize,
    path: &'a Path,
    last_line: usize,
}

impl<'a> Numbers<'a> {
    fn err(&self, line: usize, reason: impl Into<String>) -> PhotometryFileError {
        PhotometryFileError::new(self.path, line, reason)
    }

    fn number(&mut self, what: &str) -> Result<(f64, usize), PhotometryFileError> {
        let Some(t) = self.tokens.get(self.next) else {
            return Err(self.err(
                self.last_line,
                format!("the file ends early: expected {what}"),
            ));
        };
        self.next += 1;
        let v: f64 = t
            .text
            .parse()
            .map_err(|_| self.err(t.line, format!("`{}` is not a number ({what})", t.text)))?;
        if !v.is_finite() {
            return Err(self.err(
                t.line,
                format!("{what} is not a finite number: `{}`", t.text),
            ));
        }
        Ok((v, t.line))
    }

    fn count(&mut self, what: &str, max: usize) -> Result<usize, PhotometryFileError> {
        let (v, line) = self.number(what)?;
        if v.fract() != 0.0 || v < 1.0 || v > max as f64 {
            return Err(self.err(
                line,
                format!("{what} must be a whole number from 1 to {max}, got {v}"),
            ));
        }
        Ok(v as usize)
    }

    fn list(&mut self, n: usize, what: &str) -> Result<Vec<(f64, usize)>, PhotometryFileError> {
        (0..n).map(|_| self.number(what)).collect()
    }
}

/// Parses LM-63 text (see the module docs).
pub fn parse(text: &str, path: &Path) -> Result<Photometry, PhotometryFileError> {
    let lines: Vec<&str> = text.lines().collect();
    let tilt_at = lines
        .iter()
        .position(|l| l.trim_start().to_ascii_uppercase().starts_with("TILT"))
        .ok_or_else(|| PhotometryFileError::new(path, 0, "no TILT= line: not an IES LM-63 file"))?;
    let tilt = lines[tilt_at].trim();
    let value = tilt.split_once('=').map(|(_, v)| v.trim()).ok_or_else(|| {
        PhotometryFileError::new(
            path,
            tilt_at + 1,
            "TILT must be TILT=NONE, TILT=INCLUDE or TILT=<file>",
        )
    })?;
    let mut tokens = Vec::new();
    for (i, line) in lines.iter().enumerate().skip(tilt_at + 1) {
        for t in line
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|t| !t.is_empty())
        {
            tokens.push(Token {
                text: t,
                line: i + 1,
            });
        }
    }
    let mut nums = Numbers {
        tokens,
        next: 0,
        path,
        last_line: lines.len(),
    };
    match value.to_ascii_uppercase().as_str() {
        "NONE" => {}
        "INCLUDE" => {
            nums.number("the lamp-to-luminaire geometry")?;
            let n = nums.count("the number of tilt angles", MAX_ANGLES)?;
            nums.list(n, "a tilt angle")?;
            nums.list(n, "a tilt multiplying factor")?;
        }
        _ => {
            return Err(PhotometryFileError::new(
                path,
                tilt_at + 1,
                format!(
                    "TILT={value} names a separate tilt file, which raygine does not read; use TILT=NONE or TILT=INCLUDE"
                ),
            ));
        }
    }
    let (_lamps, _) = nums.number("the number of lamps")?;
    let (_lumens, _) = nums.number("the lumens per lamp")?;
    let (multiplier, m_line) = nums.number("the candela multiplier")?;
    let n_vert = nums.count("the number of vertical angles", MAX_ANGLES)?;
    let n_horiz = nums.count("the number of horizontal angles", MAX_ANGLES)?;
    if n_vert * n_horiz > MAX_VALUES {
        return Err(nums.err(
            m_line,
            format!("{n_vert} x {n_horiz} intensities: more than {MAX_VALUES}"),
        ));
    }
    let (ptype, p_line) = nums.number("the photometric type")?;
    match ptype as i64 {
        1 if ptype.fract() == 0.0 => {}
        2 => {
            return Err(nums.err(
                p_line,
                "photometric type B (floodlights) is not supported: convert the file to type C",
            ));
        }
        3 => return Err(nums.err(p_line, "photometric type A (automotive) is not supported")),
        _ => {
            return Err(nums.err(
                p_line,
                format!("photometric type must be 1 (C), 2 (B) or 3 (A), got {ptype}"),
            ));
        }
    }
    let (units, u_line) = nums.number("the units type")?;
    let metres_per_unit = match units as i64 {
        1 => 0.3048,
        2 => 1.0,
        _ => {
            return Err(nums.err(
                u_line,
                format!("units type must be 1 (feet) or 2 (metres), got {units}"),
            ));
        }
    };
    let mut opening = [0.0f32; 3];
    for (size, what) in opening
        .iter_mut()
        .zip(["the width", "the length", "the height"])
    {
        *size = (nums.number(what)?.0 * metres_per_unit) as f32;
    }
    let (shape, shape_note) = LuminousShape::from_ies(opening[0], opening[1], opening[2]);
    let (ballast, b_line) = nums.number("the ballast factor")?;
    let (ballast_lamp, _) = nums.number("the ballast-lamp photometric factor")?;
    let (watts, _) = nums.number("the input watts")?;
    let scale = multiplier * ballast * ballast_lamp;
    if scale < 0.0 {
        return Err(nums.err(
            b_line,
            "the candela multiplier and ballast factors must not be negative",
        ));
    }
    let vert = nums.list(n_vert, "a vertical angle")?;
    let horiz = nums.list(n_horiz, "a horizontal angle")?;
    ascending(&vert, "vertical", path)?;
    ascending(&horiz, "horizontal", path)?;
    let (v0, v1) = (vert[0].0, vert[n_vert - 1].0);
    let vertical_ok = matches!((v0, v1), (0.0, 90.0) | (90.0, 180.0) | (0.0, 180.0));
    if !vertical_ok {
        return Err(PhotometryFileError::new(
            path,
            vert[0].1,
            format!("vertical angles run {v0}..{v1}; type C needs 0-90, 90-180 or 0-180"),
        ));
    }
    let (h0, h1) = (horiz[0].0, horiz[n_horiz - 1].0);
    let symmetry = match (n_horiz, h0, h1) {
        (1, 0.0, _) => Symmetry::Rotational,
        (_, 0.0, 90.0) => Symmetry::Quadrants,
        (_, 0.0, 180.0) | (_, 180.0, 360.0) => Symmetry::AboutC0C180,
        (_, 90.0, 270.0) => Symmetry::AboutC90C270,
        (_, 0.0, 360.0) => Symmetry::None,
        _ => {
            return Err(PhotometryFileError::new(
                path,
                horiz[0].1,
                format!(
                    "horizontal angles run {h0}..{h1}; type C needs a single 0, 0-90, 0-180, 0-360, 90-270 or 180-360"
                ),
            ));
        }
    };
    let mut planes = Vec::with_capacity(n_horiz);
    for (c, _) in &horiz {
        let values = nums.list(n_vert, "a candela value")?;
        let mut cd = Vec::with_capacity(n_vert);
        for (v, line) in values {
            if v < 0.0 {
                return Err(PhotometryFileError::new(
                    path,
                    line,
                    format!("negative intensity {v}"),
                ));
            }
            cd.push((v * scale) as f32);
        }
        planes.push(Plane {
            c_deg: *c as f32,
            cd,
        });
    }
    let gamma = vert.iter().map(|(g, _)| *g as f32).collect();
    let info = LuminaireInfo {
        manufacturer: keyword(&lines[..tilt_at], "MANUFAC"),
        name: keyword(&lines[..tilt_at], "LUMINAIRE"),
        catalogue_number: keyword(&lines[..tilt_at], "LUMCAT"),
        power_w: (watts > 0.0 && watts.is_finite()).then_some(watts),
        colour_rendering: None,
    };
    Photometry::from_planes(gamma, unfold(symmetry, planes), shape)
        .map(|p| p.with_shape_note(shape_note).with_info(info))
        .map_err(|e| PhotometryFileError::new(path, 0, e.to_string()))
}

/// The text of keyword line `[NAME] text` among the header lines, if there is one.
fn keyword(header: &[&str], name: &str) -> Option<String> {
    let tag = format!("[{name}]");
    header.iter().find_map(|l| {
        let l = l.trim();
        let rest = l
            .get(..tag.len())?
            .eq_ignore_ascii_case(&tag)
            .then(|| &l[tag.len()..])?;
        let text = rest.trim();
        (!text.is_empty()).then(|| text.to_owned())
    })
}

fn ascending(values: &[(f64, usize)], what: &str, path: &Path) -> Result<(), PhotometryFileError> {
    for w in values.windows(2) {
        if w[1].0 <= w[0].0 {
            return Err(PhotometryFileError::new(
                path,
                w[1].1,
                format!("{what} angles must ascend: {} follows {}", w[1].0, w[0].0),
            ));
        }
    }
    if values.iter().any(|(v, _)| !(0.0..=360.0).contains(v)) {
        return Err(PhotometryFileError::new(
            path,
            values[0].1,
            format!("{what} angles must lie within 0..360"),
        ));
    }
    Ok(())
}
