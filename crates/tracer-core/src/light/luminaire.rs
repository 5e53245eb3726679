//! A goniometric luminaire: a measured distribution (IES or EULUMDAT) placed in the scene
//! with its photometric frame, emitting from a point or from a luminous opening.
//!
//! An opening is sampled uniformly by area. A point x on it with outward normal n sends
//! I(ω) · A · max(0, n·ω) / A_proj(ω) towards ω (I(ω) on a flat opening), which is the
//! luminance L(ω) = I(ω) / A_proj(ω) over its area, and averages to I(ω) over the opening.
//! So each sample is a point light at x with that intensity: E = I' cos θ / R² as for the point
//! model, exact in the near field. No ray finds an opening (it is not geometry): it stays a
//! delta light for MIS, reached by next-event estimation and light subpaths only.

use super::point::{UNIFORM_SPHERE_PDF, incident_from_point, uniform_emission};
use super::{Emission, Incident, LightBounds, LightSource, LuminousShape, Photometry, Receiver};
use glam::Vec3;
use std::sync::Arc;

/// A photometric file as loaded: the distribution and where it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Luminaire {
    pub photometry: Photometry,
    /// The path as the sidecar wrote it (relative to the sidecar, or absolute).
    pub file: std::path::PathBuf,
    /// The file's luminous flux as rendered (lm), integrated once.
    pub flux_lm: f64,
}

impl Luminaire {
    pub fn new(photometry: Photometry, file: std::path::PathBuf) -> Self {
        let flux_lm = photometry.flux_lm();
        Self {
            photometry,
            file,
            flux_lm,
        }
    }
}

/// A measured distribution at `position`, its intensities times `multiplier`.
#[derive(Clone, Debug, PartialEq)]
pub struct GoniometricLight {
    pub position: Vec3,
    pub multiplier: f32,
    /// Colour with Rec. 709 luminance 1.
    pub tint: Vec3,
    pub luminaire: Arc<Luminaire>,
    pub frame: LuminaireFrame,
    /// (metres per scene unit)².
    pub metres_per_unit_sq: f32,
    /// The luminous opening, sizes in the scene unit, in the luminaire's frame.
    pub shape: LuminousShape,
}

impl GoniometricLight {
    /// Intensity (cd) along unit `dir` leaving the light.
    #[inline]
    pub fn intensity_towards(&self, dir: Vec3) -> f32 {
        let (c, gamma) = self.frame.angles_deg(dir);
        self.multiplier * self.luminaire.photometry.intensity(c, gamma)
    }

    /// A point of the opening from `u` and its outward unit normal (zero on a flat opening or
    /// a point), in scene coordinates.
    #[inline]
    pub fn point_on(&self, u: [f32; 2]) -> (Vec3, Vec3) {
        if self.shape == LuminousShape::Point {
            return (self.position, Vec3::ZERO);
        }
        let (p, n) = self.shape.sample(u);
        (
            self.position + self.frame.to_scene(p),
            self.frame.to_scene(n),
        )
    }

    /// What the point of the opening with normal `n` sends along `dir`, relative to I(dir)
    /// (see the module's notes).
    #[inline]
    fn face_factor(&self, n: Vec3, dir: Vec3) -> f32 {
        if n == Vec3::ZERO {
            return 1.0;
        }
        self.shape
            .emission_factor(self.frame.to_local(n), self.frame.to_local(dir))
    }
}

impl LightSource for GoniometricLight {
    /// The file's flux times the multiplier.
    fn power_lm(&self) -> f64 {
        f64::from(self.multiplier) * self.luminaire.flux_lm
    }

    fn bounds(&self) -> LightBounds {
        let h = self.shape.half_extent();
        let f = &self.frame;
        let reach = f.c0.abs() * h.x + f.c90.abs() * h.y + f.nadir.abs() * h.z;
        LightBounds::around(
            self.position - reach,
            self.position + reach,
            self.power_lm() as f32,
        )
    }

    fn is_delta(&self) -> bool {
        true
    }

    fn samples_area(&self) -> bool {
        self.shape != LuminousShape::Point
    }

    /// A point of the opening that faces `at.p` (on a luminous body, only its faces towards the
    /// receiver: see [`LightSource::area_share`]), as a point light.
    #[inline]
    fn sample_incident(&self, at: Receiver, u: [f32; 2]) -> Option<Incident> {
        let (p, n, share) = if self.shape.is_flat() {
            let (p, n) = self.point_on(u);
            (p, n, 1.0)
        } else {
            let r = self.frame.to_local(at.p - self.position);
            let (p, n) = self.shape.sample_facing(r, u)?;
            let share = self.shape.facing_area(r) / self.shape.area();
            (
                self.position + self.frame.to_scene(p),
                self.frame.to_scene(n),
                share,
            )
        };
        let mut s = incident_from_point(p, self.tint, self.metres_per_unit_sq, at, |d| {
            self.intensity_towards(d) * self.face_factor(n, d) * share
        })?;
        s.n = n;
        Some(s)
    }

    fn area_share(&self, p: Vec3) -> f32 {
        if self.shape.is_flat() {
            1.0
        } else {
            let r = self.frame.to_local(p - self.position);
            self.shape.facing_area(r) / self.shape.area()
        }
    }

    fn incident_pdf(&self, _origin: Vec3, _wi: Vec3, _distance: f32) -> f32 {
        0.0
    }

    fn emitted(&self, dir: Vec3) -> Vec3 {
        self.tint * (self.intensity_towards(dir) / self.metres_per_unit_sq)
    }

    /// A point of the opening (its density folded into the point-light model: see the
    /// module's notes), and a direction uniform over the sphere (the distribution is not
    /// importance-sampled).
    fn sample_emission(&self, u_point: [f32; 2], u_dir: [f32; 2]) -> Option<Emission> {
        let (p, n) = self.point_on(u_point);
        Some(Emission {
            n,
            ..uniform_emission(p, u_dir)
        })
    }

    fn emission_dir_pdf(&self, _dir: Vec3) -> f32 {
        UNIFORM_SPHERE_PDF
    }

    fn emission_point_pdf(&self) -> f32 {
        1.0
    }

    fn normal(&self) -> Vec3 {
        Vec3::ZERO
    }

    fn emission_cosine(&self, n: Vec3, dir: Vec3) -> f32 {
        self.face_factor(n, dir)
    }
}

/// The orientation of a goniometric distribution in the scene: the nadir (γ = 0) along the aim;
/// at rotation 0 the C0 plane contains +X projected perpendicular to the aim (+Z when the aim is
/// parallel to X); C angles increase counter-clockwise in the picture raygine draws, looking
/// along the aim from behind the luminaire (LM-63 type C). As `.shp` scenes are drawn mirrored
/// (left-handed), the C90 direction is `aim × C0` there and `C0 × aim` in right-handed scenes,
/// so a file's C90 lobe lands in the same place on screen in both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LuminaireFrame {
    pub nadir: Vec3,
    pub c0: Vec3,
    pub c90: Vec3,
}

impl LuminaireFrame {
    pub fn new(aim: Vec3, rotation_deg: f32, handedness_sign: f32) -> Self {
        let nadir = aim.try_normalize().unwrap_or(Vec3::NEG_Y);
        let reference = if nadir.cross(Vec3::X).length_squared() < 1e-8 {
            Vec3::Z
        } else {
            Vec3::X
        };
        let c0 = (reference - nadir * nadir.dot(reference)).normalize();
        let c90 = c0.cross(nadir) * handedness_sign.signum();
        // Turn the C planes by the rotation, counter-clockwise as C angles run.
        let (s, c) = rotation_deg.to_radians().sin_cos();
        let c0r = c0 * c + c90 * s;
        let c90r = c90 * c - c0 * s;
        Self {
            nadir,
            c0: c0r,
            c90: c90r,
        }
    }

    /// `local` (x along C0, y along C90, z along the nadir) in scene coordinates.
    #[inline]
    pub fn to_scene(&self, local: Vec3) -> Vec3 {
        self.c0 * local.x + self.c90 * local.y + self.nadir * local.z
    }

    /// Scene vector `v` in the frame's coordinates (see [`LuminaireFrame::to_scene`]).
    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.c0), v.dot(self.c90), v.dot(self.nadir))
    }

    /// (C, γ) in degrees of the unit direction `dir` leaving the luminaire.
    pub fn angles_deg(&self, dir: Vec3) -> (f32, f32) {
        let gamma = dir.dot(self.nadir).clamp(-1.0, 1.0).acos().to_degrees();
        let c = dir.dot(self.c90).atan2(dir.dot(self.c0)).to_degrees();
        (c.rem_euclid(360.0), gamma)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn luminaire_frame_turns_counter_clockwise_with_rotation() {
        let f = LuminaireFrame::new(Vec3::NEG_Y, 0.0, 1.0);
        assert!((f.c0 - Vec3::X).length() < 1e-6);
        assert!((f.c90 - Vec3::NEG_Z).length() < 1e-6, "{}", f.c90);
        let turned = LuminaireFrame::new(Vec3::NEG_Y, 90.0, 1.0);
        assert!((turned.c0 - f.c90).length() < 1e-6);
        let (c, g) = f.angles_deg(Vec3::new(0.0, -1.0, -1.0).normalize());
        assert!(
            (c - 90.0).abs() < 1e-3 && (g - 45.0).abs() < 1e-3,
            "{c} {g}"
        );
        // Aim along X: C0 along +Z.
        let side = LuminaireFrame::new(Vec3::X, 0.0, 1.0);
        assert!((side.c0 - Vec3::Z).length() < 1e-6);
    }
}
