//! The luminance image glare is judged from: a 180° equidistant fisheye at the eye (evalglare's
//! `-vta` input). Per pixel: its mean luminance, the standard error of that mean, the direction
//! of its centre in the observer's frame (x right, y up, z along the line of sight) and the solid
//! angle it covers (from the lens' density at its centre, as evalglare takes it).

use crate::render::Film;
use crate::scene::CameraBasis;
use glam::DVec3;

/// A fisheye luminance image with its per-pixel uncertainty and geometry.
#[derive(Clone, Debug, Default)]
pub struct GlareImage {
    pub width: u32,
    pub height: u32,
    /// cd/m²; 0 outside the image circle.
    pub luminance: Vec<f64>,
    /// cd/m², the standard error of each pixel's mean; NaN where it is unknown (one sample).
    pub std_error: Vec<f64>,
    /// Unit directions in the observer's frame; zero outside the image circle.
    pub direction: Vec<DVec3>,
    /// sr; 0 outside the image circle.
    pub solid_angle: Vec<f64>,
    /// cd/m²: the part of each pixel's luminance that luminous openings drawn into it give
    /// ([`super::openings::draw_openings`]); exact, no standard error.
    pub opening: Vec<f64>,
    /// The lens it was rendered through (None for an image made up in a test).
    pub basis: Option<CameraBasis>,
}

impl GlareImage {
    /// The geometry of `basis` (a fisheye), every luminance 0.
    pub fn geometry(basis: &CameraBasis) -> GlareImage {
        let (w, h) = (basis.width, basis.height);
        let n = w as usize * h as usize;
        let mut image = GlareImage {
            width: w,
            height: h,
            luminance: vec![0.0; n],
            std_error: vec![0.0; n],
            direction: vec![DVec3::ZERO; n],
            solid_angle: vec![0.0; n],
            opening: vec![0.0; n],
            basis: Some(*basis),
        };
        let pixels = f64::from(w) * f64::from(h);
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                let Some(ray) = basis.ray(x as f32 + 0.5, y as f32 + 0.5) else {
                    continue;
                };
                let density = f64::from(basis.direction_density(ray.dir));
                if density <= 0.0 {
                    continue;
                }
                let d = ray.dir.as_dvec3();
                image.direction[i] = DVec3::new(
                    d.dot(basis.right.as_dvec3()),
                    d.dot(basis.up.as_dvec3()),
                    d.dot(basis.forward.as_dvec3()),
                )
                .normalize();
                image.solid_angle[i] = 1.0 / (density * pixels);
            }
        }
        image
    }

    /// `film` (rendered through `basis`) as a glare image.
    pub fn from_film(film: &Film, basis: &CameraBasis) -> GlareImage {
        let mut image = GlareImage::geometry(basis);
        for i in 0..image.luminance.len() {
            if image.solid_angle[i] > 0.0 {
                image.luminance[i] = film.mean_luminance(i);
                image.std_error[i] = film.luminance_std_error(i).unwrap_or(f64::NAN);
            }
        }
        image
    }

    /// The pixels inside the image circle.
    pub fn seen(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.solid_angle.len()).filter(|&i| self.solid_angle[i] > 0.0)
    }

    /// The illuminance at the eye on a plane facing the line of sight (lx), Σ L cos θ ω, with its
    /// standard error.
    pub fn illuminance(&self) -> (f64, f64) {
        let (mut e, mut var) = (0.0, 0.0);
        for i in self.seen() {
            let w = self.direction[i].z.max(0.0) * self.solid_angle[i];
            e += self.luminance[i] * w;
            var += (self.std_error[i] * w).powi(2);
        }
        (e, var.sqrt())
    }

    /// The mean luminance of the image circle (cd/m²), Σ L ω / Σ ω (evalglare's image average).
    pub fn mean_luminance(&self) -> f64 {
        let (sum, sr) = self.seen().fold((0.0, 0.0), |(s, w), i| {
            (
                s + self.luminance[i] * self.solid_angle[i],
                w + self.solid_angle[i],
            )
        });
        if sr > 0.0 { sum / sr } else { 0.0 }
    }

    /// The L·ω-weighted mean of the unit directions of `pixels` (observer frame), normalised:
    /// the source's direction, whatever the lens. (evalglare averages film positions instead,
    /// which in its fisheye lands a little nearer the image centre for sources off the axis.)
    pub fn centroid_direction(&self, pixels: &[usize]) -> DVec3 {
        pixels
            .iter()
            .map(|&i| self.luminance[i] * self.solid_angle[i] * self.direction[i])
            .sum::<DVec3>()
            .normalize_or_zero()
    }

    /// Where unit observer-frame direction `d` lands in the image (pixel index), if inside.
    pub fn pixel_towards(&self, basis: &CameraBasis, d: DVec3) -> Option<usize> {
        let w = (basis.right.as_dvec3() * d.x
            + basis.up.as_dvec3() * d.y
            + basis.forward.as_dvec3() * d.z)
            .as_vec3();
        let (x, y) = basis.film_position(w)?;
        let (x, y) = (x.floor() as i64, y.floor() as i64);
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return None;
        }
        Some((y as usize) * self.width as usize + x as usize)
    }
}
