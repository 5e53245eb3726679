//! An environment map read from a file: a latitude-longitude image (Radiance `.hdr` or
//! OpenEXR, through the `image` crate), 2:1, linear RGB, with the density that samples it.

use super::distribution::Distribution2d;
use crate::light::luminance;
use glam::Vec3;
use std::f32::consts::PI;
use std::path::{Path, PathBuf};

/// A latitude-longitude map: row 0 is the zenith, the last row the nadir; see
/// [`super::EnvironmentLight`] for the directions of its columns.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvironmentMap {
    pub file: PathBuf,
    pub width: usize,
    pub height: usize,
    /// Linear RGB, row by row.
    pub texels: Vec<Vec3>,
    /// Samples a texel by its luminance times the sine of its row's polar angle.
    pub(super) distribution: Distribution2d,
    /// ∫ Y dω over the sphere of the texels' luminance Y (unscaled).
    pub(super) integral: f64,
}

impl EnvironmentMap {
    /// Reads `path`. Texels that are NaN, infinite or negative are read as 0 and reported in
    /// the returned notes; a map that is not twice as wide as high is an error.
    pub fn load(path: &Path) -> Result<(EnvironmentMap, Vec<String>), String> {
        let shown = path.display();
        let image = image::ImageReader::open(path)
            .map_err(|e| format!("{shown}: {e}"))?
            .with_guessed_format()
            .map_err(|e| format!("{shown}: {e}"))?
            .decode()
            .map_err(|e| format!("{shown}: not a readable .hdr or .exr image: {e}"))?
            .to_rgb32f();
        let (width, height) = (image.width() as usize, image.height() as usize);
        let texels: Vec<Vec3> = image
            .pixels()
            .map(|p| Vec3::new(p.0[0], p.0[1], p.0[2]))
            .collect();
        let (map, bad) = Self::from_texels(path, width, height, texels)?;
        let notes = if bad > 0 {
            vec![format!(
                "{shown}: {bad} texels are NaN, infinite or negative; read as 0"
            )]
        } else {
            Vec::new()
        };
        Ok((map, notes))
    }

    /// A map of `texels` (row by row); returns it and how many texels were invalid (set to 0).
    pub fn from_texels(
        path: &Path,
        width: usize,
        height: usize,
        mut texels: Vec<Vec3>,
    ) -> Result<(EnvironmentMap, usize), String> {
        let shown = path.display();
        if width == 0 || height == 0 || texels.len() != width * height {
            return Err(format!("{shown}: an empty environment map"));
        }
        if width != 2 * height {
            return Err(format!(
                "{shown}: a latitude-longitude map is twice as wide as high; this one is \
                 {width} x {height} px"
            ));
        }
        let mut bad = 0;
        for t in &mut texels {
            if !(t.is_finite() && t.min_element() >= 0.0) {
                bad += 1;
                *t = Vec3::ZERO;
            }
        }
        // Each texel's share of the sphere: sin θ dθ dφ at its row's centre.
        let cell = (PI / height as f32) * (2.0 * PI / width as f32);
        let weights: Vec<f32> = texels
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let theta = ((i / width) as f32 + 0.5) / height as f32 * PI;
                luminance(*t) * theta.sin()
            })
            .collect();
        let distribution = Distribution2d::new(&weights, width);
        let integral = distribution.total() * f64::from(cell);
        Ok((
            EnvironmentMap {
                file: path.to_owned(),
                width,
                height,
                texels,
                distribution,
                integral,
            },
            bad,
        ))
    }

    /// The texel at `uv` in [0, 1)² (nearest: the same cells the density samples).
    pub(super) fn texel(&self, uv: [f32; 2]) -> Vec3 {
        let col = ((uv[0] * self.width as f32) as usize).min(self.width - 1);
        let row = ((uv[1] * self.height as f32) as usize).min(self.height - 1);
        self.texels[row * self.width + col]
    }
}
