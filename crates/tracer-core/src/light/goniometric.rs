//! Goniometric distributions: luminous intensity tabulated over C planes and γ angles (CIE type
//! C), as IES LM-63 and EULUMDAT files give it, with the file's symmetry already unfolded.
//!
//! γ = 0 is the photometric nadir (the luminaire's aim); C angles turn about it. Between table
//! entries the intensity is interpolated bilinearly in (C, γ), so images show no steps; C wraps
//! at 360°; outside the table's γ range the intensity is zero.

use super::LuminousShape;
use std::f64::consts::PI;

/// A complete (0–360°) intensity table in candela.
#[derive(Clone, Debug, PartialEq)]
pub struct Photometry {
    /// C angles (degrees), ascending, first 0, last 360 (a copy of the 0 plane).
    c_deg: Vec<f32>,
    /// γ angles (degrees), ascending, within 0..=180.
    gamma_deg: Vec<f32>,
    /// Intensity (cd) of plane i at γ j: `cd[i * gamma_deg.len() + j]`.
    cd: Vec<f32>,
    /// The luminous opening as the file gives it, metres.
    pub shape: LuminousShape,
    /// Why the file's opening was not taken as it is (a shape raygine does not draw).
    pub shape_note: Option<String>,
    /// What the file says about the luminaire (for schedules and reports; boxed, as few read it).
    pub info: Box<LuminaireInfo>,
}

/// What a photometric file says about its luminaire, as far as it says it: IES keywords
/// (`[MANUFAC]`, `[LUMINAIRE]`, `[LUMCAT]`) and input watts; EULUMDAT's header and lamp data.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LuminaireInfo {
    pub manufacturer: Option<String>,
    pub name: Option<String>,
    pub catalogue_number: Option<String>,
    /// Electrical input power (W), where the file gives one above 0.
    pub power_w: Option<f64>,
    /// Colour rendering (Ra) as the file gives it (EULUMDAT's lamp data).
    pub colour_rendering: Option<String>,
}

/// Why a table is not a distribution.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PhotometryError {
    #[error("{0}")]
    Invalid(String),
}

/// One C plane given by a file: its angle (degrees) and intensities at the γ angles (cd).
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    pub c_deg: f32,
    pub cd: Vec<f32>,
}

impl Photometry {
    /// A distribution from planes that cover 0..360° (or 0..=360°); planes are sorted by angle,
    /// a plane at 360 is added as a copy of the 0 plane. A single plane means rotational symmetry.
    pub fn from_planes(
        gamma_deg: Vec<f32>,
        mut planes: Vec<Plane>,
        shape: LuminousShape,
    ) -> Result<Photometry, PhotometryError> {
        let bad = |m: &str| Err(PhotometryError::Invalid(m.to_owned()));
        if gamma_deg.is_empty() || planes.is_empty() {
            return bad("no angles");
        }
        if gamma_deg.windows(2).any(|w| w[1] <= w[0])
            || gamma_deg[0] < 0.0
            || gamma_deg[gamma_deg.len() - 1] > 180.0
        {
            return bad("γ angles must ascend within 0..180");
        }
        if planes.iter().any(|p| p.cd.len() != gamma_deg.len()) {
            return bad("a plane has the wrong number of values");
        }
        if planes
            .iter()
            .flat_map(|p| &p.cd)
            .any(|v| !v.is_finite() || *v < 0.0)
        {
            return bad("intensities must be finite and not negative");
        }
        if planes.len() == 1 {
            let mut other = planes[0].clone();
            planes[0].c_deg = 0.0;
            other.c_deg = 360.0;
            planes.push(other);
        }
        planes.sort_by(|a, b| a.c_deg.total_cmp(&b.c_deg));
        planes.dedup_by(|a, b| a.c_deg == b.c_deg);
        if planes[0].c_deg != 0.0 {
            return bad("the C planes must start at 0°");
        }
        let last = planes[planes.len() - 1].c_deg;
        if last < 360.0 {
            let mut wrap = planes[0].clone();
            wrap.c_deg = 360.0;
            planes.push(wrap);
        } else if last > 360.0 {
            return bad("C angles above 360°");
        }
        let c_deg = planes.iter().map(|p| p.c_deg).collect();
        let cd = planes.into_iter().flat_map(|p| p.cd).collect();
        Ok(Photometry {
            c_deg,
            gamma_deg,
            cd,
            shape,
            shape_note: None,
            info: Box::default(),
        })
    }

    /// The same with what the file says about its luminaire.
    pub fn with_info(mut self, info: LuminaireInfo) -> Photometry {
        self.info = Box::new(info);
        self
    }

    /// The same with a note on its opening (see [`Photometry::shape_note`]).
    pub fn with_shape_note(mut self, note: Option<String>) -> Photometry {
        self.shape_note = note;
        self
    }

    /// Largest dimension of the luminous opening, metres (0: a point).
    pub fn opening_m(&self) -> f32 {
        self.shape.largest_dimension()
    }

    /// Scales every intensity by `k`.
    pub fn scaled(mut self, k: f32) -> Photometry {
        self.cd.iter_mut().for_each(|v| *v *= k);
        self
    }

    /// Intensity (cd) at C angle `c_deg` (any value; wraps) and γ `gamma_deg`.
    pub fn intensity(&self, c_deg: f32, gamma_deg: f32) -> f32 {
        let g = &self.gamma_deg;
        let (g0, g1) = (g[0], g[g.len() - 1]);
        if !(gamma_deg >= g0 && gamma_deg <= g1) {
            return 0.0;
        }
        let c = c_deg.rem_euclid(360.0);
        let (ci, ct) = bracket(&self.c_deg, c);
        let (gi, gt) = bracket(g, gamma_deg);
        let n = g.len();
        let at = |i: usize, j: usize| self.cd[i * n + j];
        let gj1 = (gi + 1).min(n - 1);
        let ci1 = (ci + 1).min(self.c_deg.len() - 1);
        let a = at(ci, gi) + (at(ci, gj1) - at(ci, gi)) * gt;
        let b = at(ci1, gi) + (at(ci1, gj1) - at(ci1, gi)) * gt;
        a + (b - a) * ct
    }

    /// Luminous flux (lm): ∫ I dω over the sphere of the interpolated distribution (midpoint
    /// rule, 0.25° steps).
    pub fn flux_lm(&self) -> f64 {
        let (nc, ng) = (1440usize, 720usize);
        let dc = 360.0 / nc as f64;
        let dg = 180.0 / ng as f64;
        let mut sum = 0.0;
        for j in 0..ng {
            let gamma = (j as f64 + 0.5) * dg;
            let mut ring = 0.0;
            for i in 0..nc {
                ring += f64::from(self.intensity(((i as f64 + 0.5) * dc) as f32, gamma as f32));
            }
            sum += ring * gamma.to_radians().sin();
        }
        sum * dc.to_radians() * dg.to_radians()
    }

    /// The largest intensity in the table (cd).
    pub fn max_cd(&self) -> f32 {
        self.cd.iter().copied().fold(0.0, f32::max)
    }

    /// γ range of the table (degrees).
    pub fn gamma_range(&self) -> (f32, f32) {
        (self.gamma_deg[0], self.gamma_deg[self.gamma_deg.len() - 1])
    }
}

/// The index i with `xs[i] <= x <= xs[i + 1]` and the fraction between them (0 past the ends).
fn bracket(xs: &[f32], x: f32) -> (usize, f32) {
    if xs.len() < 2 {
        return (0, 0.0);
    }
    let i = xs.partition_point(|&v| v <= x).clamp(1, xs.len() - 1) - 1;
    let span = xs[i + 1] - xs[i];
    let t = if span > 0.0 {
        ((x - xs[i]) / span).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (i, t)
}

/// Solid angle helper for tests: the flux of I(γ) = I0 cos γ over the lower hemisphere is π I0.
pub fn cosine_flux(i0: f64) -> f64 {
    PI * i0
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    fn table(gamma: &[f32], f: impl Fn(f32, f32) -> f32, cs: &[f32]) -> Photometry {
        let planes = cs
            .iter()
            .map(|&c| Plane {
                c_deg: c,
                cd: gamma.iter().map(|&g| f(c, g)).collect(),
            })
            .collect();
        Photometry::from_planes(gamma.to_vec(), planes, LuminousShape::Point).unwrap()
    }

    #[test]
    fn isotropic_and_cosine_fluxes() {
        let gamma: Vec<f32> = (0..=36).map(|i| i as f32 * 5.0).collect();
        let iso = table(&gamma, |_, _| 100.0, &[0.0]);
        let exact = 4.0 * PI * 100.0;
        assert!(
            (iso.flux_lm() / exact - 1.0).abs() < 1e-4,
            "{}",
            iso.flux_lm()
        );
        let down: Vec<f32> = (0..=18).map(|i| i as f32 * 5.0).collect();
        let cos = table(
            &down,
            |_, g| (1000.0 * g.to_radians().cos()).max(0.0),
            &[0.0],
        );
        // Piecewise-linear cos γ at 5° steps lies just under the curve.
        let rel = cos.flux_lm() / cosine_flux(1000.0) - 1.0;
        assert!(rel.abs() < 2e-3, "{rel}");
    }

    #[test]
    fn interpolation_is_continuous_and_wraps() {
        let gamma = [0.0, 90.0, 180.0];
        let p = table(&gamma, |c, g| c + g, &[0.0, 90.0, 180.0, 270.0]);
        assert_eq!(p.intensity(45.0, 0.0), 45.0);
        assert_eq!(p.intensity(0.0, 45.0), 45.0);
        // Between 270 and 360 (= the 0 plane, value 0) the value falls back to the 0 plane.
        assert!((p.intensity(315.0, 0.0) - 135.0).abs() < 1e-4);
        assert_eq!(p.intensity(-45.0, 0.0), p.intensity(315.0, 0.0));
        let half = table(&[0.0, 90.0], |_, _| 5.0, &[0.0]);
        assert_eq!(half.intensity(0.0, 90.0), 5.0);
        assert_eq!(half.intensity(0.0, 90.5), 0.0);
    }
}
