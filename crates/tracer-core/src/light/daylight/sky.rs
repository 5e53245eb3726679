//! Skies as environment lights: the traditional CIE overcast sky (Moon & Spencer) and the
//! uniform sky, over a ground hemisphere of uniform luminance lit by them.
//!
//! - Uniform: L = Lz everywhere above the horizon; E_h = π Lz.
//! - CIE overcast: L(θ) = Lz (1 + 2 cos θ) / 3, θ from the zenith; E_h = 7π Lz / 9.
//! - Ground (below the horizon): L_g = ρ_g E_h / π, a Lambertian ground of reflectance ρ_g
//!   under the unobstructed sky.
//!
//! Both skies are symmetric about the zenith; they become a latitude-longitude map (the
//! environment light's, its top row the scene's +Y) whose rows hold the sky's mean luminance
//! over each row's solid angle, exactly (L is linear in cos θ). With 256 rows the horizontal
//! illuminance of the map is within 1e-4 of the closed form.

use super::spec::{Sky, SkyModel};
use crate::light::{Environment, EnvironmentMap, EnvironmentSource};
use glam::Vec3;
use std::f64::consts::PI;
use std::path::Path;
use std::sync::Arc;

/// Rows of the sky's map (columns: twice as many).
const ROWS: usize = 256;

impl Sky {
    /// Luminance (cd/m²) of the sky at cos θ = `cos_zenith` above the horizon.
    pub fn luminance(&self, cos_zenith: f64) -> f64 {
        let lz = self.zenith_luminance_cd_m2;
        match self.model {
            SkyModel::Uniform => lz,
            SkyModel::CieOvercast => lz * (1.0 + 2.0 * cos_zenith) / 3.0,
        }
    }

    /// Unobstructed horizontal illuminance (lx) from the sky.
    pub fn horizontal_illuminance(&self) -> f64 {
        self.zenith_luminance_cd_m2 * self.model.horizontal_over_zenith()
    }

    /// The ground's luminance (cd/m²): ρ_g E_h / π.
    pub fn ground_luminance(&self) -> f64 {
        self.ground_reflectance * self.horizontal_illuminance() / PI
    }

    /// The sky and its ground as an environment light, shown as the background.
    pub fn environment(&self) -> Environment {
        let (w, h) = (2 * ROWS, ROWS);
        let mut texels = Vec::with_capacity(w * h);
        for row in 0..h {
            let (t0, t1) = (row as f64 * PI / h as f64, (row + 1) as f64 * PI / h as f64);
            let l = if t1 <= PI / 2.0 + 1e-12 {
                // The mean of L over the band's solid angle: L is linear in cos θ, and the mean
                // of cos θ over sin θ dθ is (sin² θ1 − sin² θ0) / (2 (cos θ0 − cos θ1)).
                let mean_cos =
                    (t1.sin().powi(2) - t0.sin().powi(2)) / (2.0 * (t0.cos() - t1.cos()));
                self.luminance(mean_cos)
            } else {
                self.ground_luminance()
            };
            texels.extend(std::iter::repeat_n(Vec3::splat(l as f32), w));
        }
        let name = format!("{} sky", self.model.name());
        // Finite, non-negative texels of a 2:1 map: from_texels cannot refuse them.
        let map = EnvironmentMap::from_texels(Path::new(&name), w, h, texels)
            .map(|(map, _)| map)
            .unwrap_or_else(|e| unreachable!("a sky map is always valid: {e}"));
        Environment {
            source: EnvironmentSource::Map(Arc::new(map)),
            scale: 1.0,
            rotation_deg: 0.0,
            background: true,
        }
    }
}

impl SkyModel {
    /// E_h / Lz for the unobstructed sky.
    pub fn horizontal_over_zenith(self) -> f64 {
        match self {
            SkyModel::Uniform => PI,
            SkyModel::CieOvercast => 7.0 * PI / 9.0,
        }
    }

    /// The sidecar's name.
    pub fn name(self) -> &'static str {
        match self {
            SkyModel::Uniform => "uniform",
            SkyModel::CieOvercast => "cie-overcast",
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    /// The map's rows, integrated over a horizontal receiver (∫ L cos θ dω, exact per row),
    /// give the closed forms within 1e-4, and the ground sends ρ_g E_h / π up.
    #[test]
    fn the_map_holds_the_closed_forms() {
        for model in [SkyModel::Uniform, SkyModel::CieOvercast] {
            let sky = Sky {
                model,
                zenith_luminance_cd_m2: 1000.0,
                ground_reflectance: 0.2,
            };
            let Environment {
                source: EnvironmentSource::Map(map),
                ..
            } = sky.environment()
            else {
                unreachable!()
            };
            let h = map.height;
            let mut e = 0.0;
            for row in 0..h / 2 {
                let (t0, t1) = (row as f64 * PI / h as f64, (row + 1) as f64 * PI / h as f64);
                let l = f64::from(map.texels[row * map.width].x);
                e += l * PI * (t1.sin().powi(2) - t0.sin().powi(2));
            }
            let exact = sky.horizontal_illuminance();
            assert!((e / exact - 1.0).abs() < 1e-4, "{model:?}: {e} vs {exact}");
            let ground = f64::from(map.texels[(h - 1) * map.width].x);
            assert!((ground - 0.2 * exact / PI).abs() < 1e-3, "{ground}");
        }
    }
}
