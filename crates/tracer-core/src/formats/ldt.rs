//! EULUMDAT (`.ldt`) photometric files: one field a line, intensities in cd per 1000 lm for the
//! C planes the symmetry indicator requires.
//!
//! Absolute candela = value × conversion factor (line 24) × (luminous flux of the first lamp set
//! / 1000). Further lamp sets are alternatives (other lamps for the same luminaire) and are not
//! added.

use super::{MAX_ANGLES, MAX_VALUES, PhotometryFileError, Symmetry, unfold};
use crate::light::{LuminaireInfo, LuminousShape, Photometry, Plane};
use std::path::Path;

struct Lines<'a> {
    lines: Vec<&'a str>,
    next: usize,
    path: &'a Path,
}

impl Lines<'_> {
    fn err(&self, line: usize, reason: impl Into<String>) -> PhotometryFileError {
        PhotometryFileError::new(self.path, line, reason)
    }

    /// The next line's text and its 1-based number.
    fn text(&mut self, what: &str) -> Result<(String, usize), PhotometryFileError> {
        let Some(l) = self.lines.get(self.next) else {
            return Err(self.err(
                self.lines.len(),
                format!("the file ends early: expected {what}"),
            ));
        };
        self.next += 1;
        Ok((l.trim().to_owned(), self.next))
    }

    fn number(&mut self, what: &str) -> Result<(f64, usize), PhotometryFileError> {
        let (t, line) = self.text(what)?;
        // Some writers use a decimal comma.
        let v: f64 = t
            .replace(',', ".")
            .parse()
            .map_err(|_| self.err(line, format!("`{t}` is not a number ({what})")))?;
        if !v.is_finite() {
            return Err(self.err(line, format!("{what} is not a finite number: `{t}`")));
        }
        Ok((v, line))
    }

    fn count(
        &mut self,
        what: &str,
        min: usize,
        max: usize,
    ) -> Result<(usize, usize), PhotometryFileError> {
        let (v, line) = self.number(what)?;
        if v.fract() != 0.0 || v < min as f64 || v > max as f64 {
            return Err(self.err(
                line,
                format!("{what} must be a whole number from {min} to {max}, got {v}"),
            ));
        }
        Ok((v as usize, line))
    }
}

/// Parses EULUMDAT text (see the module docs).
pub fn parse(text: &str, path: &Path) -> Result<Photometry, PhotometryFileError> {
    let mut l = Lines {
        lines: text.lines().collect(),
        next: 0,
        path,
    };
    let (manufacturer, _) = l.text("the manufacturer")?;
    l.number("the type indicator")?;
    let (isym, isym_line) = l.count("the symmetry indicator", 0, 4)?;
    let (mc, mc_line) = l.count("the number of C planes", 1, MAX_ANGLES)?;
    l.number("the distance between C planes")?;
    let (ng, _) = l.count("the number of γ angles", 1, MAX_ANGLES)?;
    l.number("the distance between γ angles")?;
    l.text("the report number")?;
    let (name, _) = l.text("the luminaire name")?;
    let (number, _) = l.text("the luminaire number")?;
    l.text("the file name")?;
    l.text("the date and user")?;
    for what in [
        "the luminaire length or diameter",
        "the luminaire width",
        "the luminaire height",
    ] {
        l.number(what)?;
    }
    let mm = |v: f64| (v / 1000.0) as f32;
    let length = mm(l.number("the luminous area length or diameter")?.0);
    let width = mm(l.number("the luminous area width")?.0);
    let mut heights = [0.0f32; 4];
    for (h, what) in heights.iter_mut().zip([
        "the luminous area height C0",
        "the luminous area height C90",
        "the luminous area height C180",
        "the luminous area height C270",
    ]) {
        *h = mm(l.number(what)?.0);
    }
    let (shape, shape_note) = LuminousShape::from_eulumdat(length, width, heights);
    l.number("the downward flux fraction")?;
    l.number("the light output ratio")?;
    let (conversion, conv_line) = l.number("the conversion factor for luminous intensities")?;
    l.number("the tilt during measurement")?;
    let (sets, sets_line) = l.count("the number of lamp sets", 1, 1000)?;
    let mut first_flux = None;
    let (mut watts, mut ra) = (0.0f64, None);
    for _ in 0..sets {
        l.number("the number of lamps")?;
        l.text("the lamp type")?;
        let (flux, line) = l.number("the lamp set's luminous flux")?;
        if flux < 0.0 {
            return Err(l.err(line, format!("negative lamp flux {flux}")));
        }
        first_flux.get_or_insert(flux);
        l.text("the colour temperature")?;
        let (rendering, _) = l.text("the colour rendering")?;
        ra.get_or_insert(rendering);
        watts += l.number("the wattage")?.0;
    }
    let lamp_flux = first_flux.ok_or_else(|| l.err(sets_line, "no lamp set"))?;
    for _ in 0..10 {
        l.number("a direct ratio")?;
    }
    let planes_given = match isym {
        0 => mc,
        1 => 1,
        2 | 3 => mc / 2 + 1,
        _ => mc / 4 + 1,
    };
    if isym >= 2 && mc % if isym == 4 { 4 } else { 2 } != 0 {
        return Err(l.err(
            mc_line,
            format!(
                "symmetry {isym} needs a number of C planes divisible by {}",
                if isym == 4 { 4 } else { 2 }
            ),
        ));
    }
    if planes_given.saturating_mul(ng) > MAX_VALUES {
        return Err(l.err(
            mc_line,
            format!("{planes_given} x {ng} intensities: more than {MAX_VALUES}"),
        ));
    }
    let mut c_angles = Vec::with_capacity(mc);
    for _ in 0..mc {
        c_angles.push(l.number("a C angle")?);
    }
    let mut gammas = Vec::with_capacity(ng);
    for _ in 0..ng {
        gammas.push(l.number("a γ angle")?);
    }
    for (what, list) in [("C", &c_angles), ("γ", &gammas)] {
        for w in list.windows(2) {
            if w[1].0 <= w[0].0 {
                return Err(l.err(
                    w[1].1,
                    format!("{what} angles must ascend: {} follows {}", w[1].0, w[0].0),
                ));
            }
        }
    }
    if c_angles.iter().any(|(c, _)| !(0.0..360.0).contains(c)) {
        return Err(l.err(c_angles[0].1, "C angles must lie within 0..360"));
    }
    if gammas.iter().any(|(g, _)| !(0.0..=180.0).contains(g)) {
        return Err(l.err(gammas[0].1, "γ angles must lie within 0..180"));
    }
    // Which C planes the file lists, in file order.
    let listed: Vec<f64> = match isym {
        0 => c_angles.iter().map(|c| c.0).collect(),
        1 => vec![0.0],
        2 => c_angles.iter().take(mc / 2 + 1).map(|c| c.0).collect(),
        3 => c_angles
            .iter()
            .skip(3 * mc / 4)
            .chain(c_angles.iter().take(mc / 4 + 1))
            .map(|c| c.0)
            .collect(),
        _ => c_angles.iter().take(mc / 4 + 1).map(|c| c.0).collect(),
    };
    if listed.len() != planes_given {
        return Err(l.err(
            isym_line,
            format!("symmetry {isym} with {mc} C planes does not give whole planes"),
        ));
    }
    let scale = conversion * lamp_flux / 1000.0;
    if scale < 0.0 {
        return Err(l.err(conv_line, "the conversion factor must not be negative"));
    }
    let mut planes = Vec::with_capacity(planes_given);
    for c in listed {
        let mut cd = Vec::with_capacity(ng);
        for _ in 0..ng {
            let (v, line) = l.number("an intensity (cd/klm)")?;
            if v < 0.0 {
                return Err(l.err(line, format!("negative intensity {v}")));
            }
            cd.push((v * scale) as f32);
        }
        planes.push(Plane {
            c_deg: c as f32,
            cd,
        });
    }
    let symmetry = match isym {
        0 => Symmetry::None,
        1 => Symmetry::Rotational,
        2 => Symmetry::AboutC0C180,
        3 => Symmetry::AboutC90C270,
        _ => Symmetry::Quadrants,
    };
    let gamma = gammas.iter().map(|(g, _)| *g as f32).collect();
    let given = |t: String| (!t.is_empty()).then_some(t);
    let info = LuminaireInfo {
        manufacturer: given(manufacturer),
        name: given(name),
        catalogue_number: given(number),
        power_w: (watts > 0.0 && watts.is_finite()).then_some(watts),
        colour_rendering: ra.and_then(given),
    };
    Photometry::from_planes(gamma, unfold(symmetry, planes), shape)
        .map(|p| p.with_shape_note(shape_note).with_info(info))
        .map_err(|e| PhotometryFileError::new(path, 0, e.to_string()))
}
