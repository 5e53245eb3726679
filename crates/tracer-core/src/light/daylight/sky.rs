//! Skies as environment lights: the traditional CIE overcast sky (Moon & Spencer), the uniform
//! sky and the 15 CIE general skies (`super::cie_general`), over a ground hemisphere of uniform
//! luminance lit by the sky and the sun.
//!
//! - Uniform: L = Lz everywhere above the horizon; E_h = π Lz.
//! - CIE overcast: L(θ) = Lz (1 + 2 cos θ) / 3, θ from the zenith; E_h = 7π Lz / 9.
//! - General skies: L = Lz f(χ) φ(Z) / (f(Zs) φ(0)); E_h / Lz by quadrature.
//! - Ground (below the horizon): L_g = ρ_g (E_h + E_sun,h) / π, a Lambertian ground of
//!   reflectance ρ_g under the unobstructed sky and sun.
//!
//! A sky becomes a latitude-longitude map (the environment light's, its top row the scene's
//! +Y). The two skies that are symmetric about the zenith hold each row's exact mean luminance
//! (L is linear in cos θ), within 1e-4 of the closed forms with 256 rows. A general sky's texel
//! is the mean of 2 x 2 points spread over its solid angle (its E_h stays within 1e-3 of the
//! quadrature; a map is rebuilt whenever the viewer moves the sun, so it must be quick).

use super::cie_general::{GeneralSky, horizontal_integral};
use super::spec::{Sky, SkyModel};
use crate::light::{Environment, EnvironmentMap, EnvironmentSource, map_direction};
use glam::{DVec3, Vec3};
use std::f64::consts::PI;
use std::path::Path;
use std::sync::Arc;

/// Rows of the sky's map (columns: twice as many).
const ROWS: usize = 256;

/// Points per texel side for the general skies.
const SUPERSAMPLE: usize = 2;

impl Sky {
    /// A sky of `model` (Perez: with its coefficients `perez`), zenith luminance
    /// `zenith_luminance_cd_m2`, over a ground of `ground_reflectance`, the sun at
    /// `sun_zenith_rad`; its E_h / Lz is computed here, once.
    pub fn new(
        model: SkyModel,
        zenith_luminance_cd_m2: f64,
        ground_reflectance: f64,
        sun_zenith_rad: f64,
        perez: Option<super::PerezSky>,
    ) -> Sky {
        let horizontal_over_zenith = match (&model, &perez) {
            (SkyModel::Perez, Some(p)) => {
                horizontal_integral(sun_zenith_rad, |mu, chi| p.over_zenith(mu, chi))
            }
            (model, _) => model.horizontal_over_zenith(sun_zenith_rad),
        };
        Sky {
            model,
            zenith_luminance_cd_m2,
            ground_reflectance,
            sun_zenith_rad,
            perez,
            horizontal_over_zenith,
        }
    }

    /// Luminance (cd/m²) of the sky in unit direction `w` above the horizon (zenith +Y), with
    /// the sun towards unit `sun`.
    pub fn luminance(&self, w: DVec3, sun: DVec3) -> f64 {
        let lz = self.zenith_luminance_cd_m2;
        match self.model {
            SkyModel::Uniform => lz,
            SkyModel::CieOvercast => lz * (1.0 + 2.0 * w.y) / 3.0,
            SkyModel::CieGeneral(t) => match GeneralSky::new(t) {
                Some(g) => {
                    // χ by the chord, accurate near the sun.
                    let chi = 2.0 * ((w - sun).length() * 0.5).min(1.0).asin();
                    lz * g.relative_luminance(w.y, chi, self.sun_zenith_rad)
                }
                None => 0.0,
            },
            SkyModel::Perez => match &self.perez {
                Some(p) => {
                    let chi = 2.0 * ((w - sun).length() * 0.5).min(1.0).asin();
                    lz * p.over_zenith(w.y, chi)
                }
                None => 0.0,
            },
        }
    }

    /// Unobstructed horizontal illuminance (lx) from the sky.
    pub fn horizontal_illuminance(&self) -> f64 {
        self.zenith_luminance_cd_m2 * self.horizontal_over_zenith()
    }

    /// E_h / Lz of this sky.
    pub fn horizontal_over_zenith(&self) -> f64 {
        self.horizontal_over_zenith
    }

    /// The ground's luminance (cd/m²): ρ_g (E_h + `sun_horizontal_lx`) / π.
    pub fn ground_luminance(&self, sun_horizontal_lx: f64) -> f64 {
        self.ground_reflectance * (self.horizontal_illuminance() + sun_horizontal_lx) / PI
    }

    /// The sky and its ground as an environment light, shown as the background: the sun (for
    /// the general skies' shape) towards scene direction `sun`, the ground lit by the sky and
    /// `sun_horizontal_lx`, in a scene of `handedness_sign` (the map's columns).
    pub fn environment(
        &self,
        sun: Vec3,
        sun_horizontal_lx: f64,
        handedness_sign: f32,
    ) -> Environment {
        let (w, h) = (2 * ROWS, ROWS);
        let ground = self.ground_luminance(sun_horizontal_lx);
        let sun = sun.as_dvec3().normalize_or(DVec3::Y);
        let mut texels = Vec::with_capacity(w * h);
        for row in 0..h {
            let (t0, t1) = (row as f64 * PI / h as f64, (row + 1) as f64 * PI / h as f64);
            if t0 >= PI / 2.0 - 1e-12 {
                texels.extend(std::iter::repeat_n(Vec3::splat(ground as f32), w));
                continue;
            }
            match self.model {
                SkyModel::Uniform | SkyModel::CieOvercast => {
                    // The mean of L over the band's solid angle: L is linear in cos θ, and the
                    // mean of cos θ over sin θ dθ is (sin² θ1 − sin² θ0) / (2 (cos θ0 − cos θ1)).
                    let mean_cos =
                        (t1.sin().powi(2) - t0.sin().powi(2)) / (2.0 * (t0.cos() - t1.cos()));
                    let l = self.luminance(DVec3::new(0.0, mean_cos, 0.0), sun);
                    texels.extend(std::iter::repeat_n(Vec3::splat(l as f32), w));
                }
                SkyModel::CieGeneral(_) | SkyModel::Perez => {
                    for col in 0..w {
                        let l = self.texel_mean(row, col, w, h, sun, handedness_sign);
                        texels.push(Vec3::splat(l as f32));
                    }
                }
            }
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

    /// The mean luminance over texel (`row`, `col`) of a `w` x `h` map, by points equally
    /// spaced in cos θ (equal solid angles) and in φ.
    fn texel_mean(
        &self,
        row: usize,
        col: usize,
        w: usize,
        h: usize,
        sun: DVec3,
        handedness_sign: f32,
    ) -> f64 {
        let (c0, c1) = (
            (row as f64 * PI / h as f64).cos(),
            ((row + 1) as f64 * PI / h as f64).cos(),
        );
        let mut sum = 0.0;
        for i in 0..SUPERSAMPLE {
            let cos_t = c0 + (c1 - c0) * (i as f64 + 0.5) / SUPERSAMPLE as f64;
            let v = (cos_t.clamp(-1.0, 1.0).acos() / PI) as f32;
            for j in 0..SUPERSAMPLE {
                let u = ((col as f64 + (j as f64 + 0.5) / SUPERSAMPLE as f64) / w as f64) as f32;
                let dir = map_direction([u, v], handedness_sign).as_dvec3();
                let dir = DVec3::new(dir.x, cos_t, dir.z);
                sum += self.luminance(dir.normalize(), sun);
            }
        }
        sum / (SUPERSAMPLE * SUPERSAMPLE) as f64
    }
}

impl SkyModel {
    /// E_h / Lz for the unobstructed sky, the sun at `sun_zenith` radians.
    pub fn horizontal_over_zenith(self, sun_zenith: f64) -> f64 {
        match self {
            SkyModel::Uniform => PI,
            SkyModel::CieOvercast => 7.0 * PI / 9.0,
            SkyModel::CieGeneral(t) => {
                GeneralSky::new(t).map_or(0.0, |g| g.horizontal_over_zenith(sun_zenith))
            }
            // Its coefficients are the sky's own: `Sky::horizontal_over_zenith`.
            SkyModel::Perez => 0.0,
        }
    }

    /// The sidecar's name.
    pub fn name(self) -> String {
        match self {
            SkyModel::Uniform => "uniform".into(),
            SkyModel::CieOvercast => "cie-overcast".into(),
            SkyModel::CieGeneral(t) => format!("cie:{t}"),
            SkyModel::Perez => "perez".into(),
        }
    }

    /// Whether the sky's shape depends on where the sun is.
    pub fn follows_the_sun(self) -> bool {
        matches!(self, SkyModel::CieGeneral(_) | SkyModel::Perez)
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
            let sky = Sky::new(model, 1000.0, 0.2, 0.5, None);
            let Environment {
                source: EnvironmentSource::Map(map),
                ..
            } = sky.environment(Vec3::Y, 0.0, 1.0)
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

    /// A general sky's map integrates to its quadrature E_h over a horizontal receiver within
    /// 0.1 %, whatever the handedness, and its brightest texel lies beside the sun.
    #[test]
    fn general_skies_keep_their_illuminance_and_their_sun() {
        let sun = Vec3::new(0.4, 0.6, 0.5).normalize();
        for (t, sign) in [(1, 1.0), (12, 1.0), (12, -1.0), (15, -1.0)] {
            let sky = Sky::new(
                SkyModel::CieGeneral(t),
                1000.0,
                0.2,
                f64::from(sun.y).acos(),
                None,
            );
            let Environment {
                source: EnvironmentSource::Map(map),
                ..
            } = sky.environment(sun, 0.0, sign)
            else {
                unreachable!()
            };
            let (w, h) = (map.width, map.height);
            let (mut e, mut brightest) = (0.0, (0.0f32, 0usize));
            for row in 0..h / 2 {
                let (t0, t1) = (row as f64 * PI / h as f64, (row + 1) as f64 * PI / h as f64);
                let band = PI * (t1.sin().powi(2) - t0.sin().powi(2)) / w as f64;
                for col in 0..w {
                    let l = map.texels[row * w + col].x;
                    e += f64::from(l) * band;
                    if l > brightest.0 {
                        brightest = (l, row * w + col);
                    }
                }
            }
            let exact = sky.horizontal_illuminance();
            assert!((e / exact - 1.0).abs() < 1e-3, "cie:{t}: {e} vs {exact}");
            let (row, col) = (brightest.1 / w, brightest.1 % w);
            let uv = [(col as f32 + 0.5) / w as f32, (row as f32 + 0.5) / h as f32];
            let towards = map_direction(uv, sign);
            if t != 1 {
                assert!(towards.dot(sun) > 0.99, "cie:{t}: {towards} vs {sun}");
            }
        }
    }
}
