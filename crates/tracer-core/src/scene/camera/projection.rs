//! Projections: how a film position turns into a ray and a direction back into a film
//! position, and the density over solid angle of a direction when film positions are drawn
//! uniformly over the image (what a camera sample does). Everything here works in the camera's
//! own frame: `a` along `right`, `b` along `up`, `c` along `forward`.
//!
//! The fisheyes draw their image circle inscribed in the image (diameter the shorter side),
//! centred, `fov_deg` across; pixels outside the circle see nothing. The equirectangular
//! image spans 360° of azimuth across and 180° of elevation down, `forward` at its centre.

use serde::{Deserialize, Serialize};
use std::f32::consts::{FRAC_PI_2, PI};

/// The largest field of view a fisheye takes, degrees.
pub const MAX_FISHEYE_FOV_DEG: f32 = 180.0;

/// How the camera maps directions onto its film, as users choose it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Projection {
    /// A pinhole: straight lines stay straight; `fov_deg` is vertical.
    #[default]
    Perspective,
    /// Fisheye, r ∝ θ (Radiance `-vta`).
    FisheyeEquidistant,
    /// Fisheye, r ∝ 2 sin(θ/2): equal areas of the film see equal solid angles.
    FisheyeEquisolid,
    /// Hemispherical fisheye, r ∝ sin θ (Radiance `-vth`): areas of the film are in
    /// proportion to the projected solid angle, so the film's mean is the illuminance over π.
    Hemispherical,
    /// A 360° x 180° panorama.
    Equirectangular,
    /// Parallel rays along the view direction; `width` in scene units across the image.
    Orthographic,
}

impl Projection {
    pub const ALL: [Projection; 6] = [
        Projection::Perspective,
        Projection::FisheyeEquidistant,
        Projection::FisheyeEquisolid,
        Projection::Hemispherical,
        Projection::Equirectangular,
        Projection::Orthographic,
    ];

    /// The name in sidecars and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Projection::Perspective => "perspective",
            Projection::FisheyeEquidistant => "fisheye-equidistant",
            Projection::FisheyeEquisolid => "fisheye-equisolid",
            Projection::Hemispherical => "hemispherical",
            Projection::Equirectangular => "equirectangular",
            Projection::Orthographic => "orthographic",
        }
    }

    /// A label for menus.
    pub fn label(self) -> &'static str {
        match self {
            Projection::Perspective => "Perspective",
            Projection::FisheyeEquidistant => "Fisheye, equidistant (-vta)",
            Projection::FisheyeEquisolid => "Fisheye, equisolid",
            Projection::Hemispherical => "Hemispherical (-vth)",
            Projection::Equirectangular => "Equirectangular 360°",
            Projection::Orthographic => "Orthographic",
        }
    }

    /// The projection named `name` ([`Projection::name`]).
    pub fn from_name(name: &str) -> Option<Projection> {
        Projection::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The fisheyes' radial law, None for the other projections.
    pub fn radial(self) -> Option<Radial> {
        match self {
            Projection::FisheyeEquidistant => Some(Radial::Equidistant),
            Projection::FisheyeEquisolid => Some(Radial::Equisolid),
            Projection::Hemispherical => Some(Radial::Hemispherical),
            _ => None,
        }
    }

    /// Whether `fov_deg` may reach 180° (the fisheyes).
    pub fn is_fisheye(self) -> bool {
        self.radial().is_some()
    }

    /// Whether the camera has a single eye point (every projection but the orthographic).
    pub fn has_eye_point(self) -> bool {
        self != Projection::Orthographic
    }
}

impl std::fmt::Display for Projection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A fisheye's radius on the film as a function g of the angle θ from the view direction,
/// before scaling (the circle's edge is g(θmax)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Radial {
    /// g = θ.
    Equidistant,
    /// g = 2 sin(θ/2).
    Equisolid,
    /// g = sin θ.
    Hemispherical,
}

impl Radial {
    fn g(self, theta: f32) -> f32 {
        match self {
            Radial::Equidistant => theta,
            Radial::Equisolid => 2.0 * (0.5 * theta).sin(),
            Radial::Hemispherical => theta.sin(),
        }
    }

    /// θ for radius `g` (within the law's range).
    fn theta(self, g: f32) -> f32 {
        match self {
            Radial::Equidistant => g,
            Radial::Equisolid => 2.0 * (0.5 * g).clamp(-1.0, 1.0).asin(),
            Radial::Hemispherical => g.clamp(-1.0, 1.0).asin(),
        }
    }

    /// g(θ) g'(θ) / sin θ: the film area per solid angle, over the scale's square.
    fn area_per_sr(self, theta: f32) -> f32 {
        match self {
            Radial::Equidistant => {
                if theta < 1e-4 {
                    1.0
                } else {
                    theta / theta.sin()
                }
            }
            Radial::Equisolid => 1.0,
            Radial::Hemispherical => theta.cos().max(0.0),
        }
    }
}

/// The projection resolved for an image of known size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lens {
    /// Perspective: the basis' `half_width` and `half_height` (tangents) say it all.
    Pinhole,
    Fisheye {
        radial: Radial,
        /// The circle's centre and radius, pixels.
        centre: (f32, f32),
        radius_px: f32,
        /// Half the field of view, radians, and g of it.
        theta_max: f32,
        g_max: f32,
    },
    Equirectangular,
    /// Half the image's extent in scene units across and down.
    Orthographic {
        half_width: f32,
        half_height: f32,
    },
}

impl Lens {
    /// The fisheye `radial` of full angle `fov` (radians, at most π) on a `width` x `height`
    /// film.
    pub fn fisheye(radial: Radial, fov: f32, width: u32, height: u32) -> Lens {
        let theta_max = (0.5 * fov).clamp(1e-3, FRAC_PI_2);
        Lens::Fisheye {
            radial,
            centre: (0.5 * width as f32, 0.5 * height as f32),
            radius_px: 0.5 * width.min(height) as f32,
            theta_max,
            g_max: radial.g(theta_max),
        }
    }

    /// The direction (camera frame, unit) seen at film position (`x`, `y`) of a `width` x
    /// `height` film, or None outside the image circle. Not for the pinhole or the
    /// orthographic lens.
    pub fn direction(&self, x: f32, y: f32, width: u32, height: u32) -> Option<[f32; 3]> {
        match *self {
            Lens::Fisheye {
                radial,
                centre,
                radius_px,
                g_max,
                ..
            } => {
                let dx = (x - centre.0) / radius_px;
                let dy = (centre.1 - y) / radius_px;
                let rho = (dx * dx + dy * dy).sqrt();
                if rho > 1.0 {
                    return None;
                }
                let theta = radial.theta(rho * g_max);
                let (sin, cos) = theta.sin_cos();
                if rho <= 0.0 {
                    return Some([0.0, 0.0, 1.0]);
                }
                Some([sin * dx / rho, sin * dy / rho, cos])
            }
            Lens::Equirectangular => {
                let azimuth = (x / width as f32 - 0.5) * 2.0 * PI;
                let elevation = (0.5 - y / height as f32) * PI;
                let (sin_az, cos_az) = azimuth.sin_cos();
                let (sin_el, cos_el) = elevation.sin_cos();
                Some([cos_el * sin_az, sin_el, cos_el * cos_az])
            }
            Lens::Pinhole | Lens::Orthographic { .. } => None,
        }
    }

    /// Film position of the unit direction `d` (camera frame), or None where the film does
    /// not see it. Not for the pinhole or the orthographic lens.
    pub fn film_position(&self, d: [f32; 3], width: u32, height: u32) -> Option<(f32, f32)> {
        let [a, b, c] = d;
        match *self {
            Lens::Fisheye {
                radial,
                centre,
                radius_px,
                theta_max,
                g_max,
            } => {
                let side = (a * a + b * b).sqrt();
                let theta = side.atan2(c);
                if theta > theta_max {
                    return None;
                }
                let rho = radial.g(theta) / g_max * radius_px;
                if side <= 0.0 {
                    return Some(centre);
                }
                Some((centre.0 + rho * a / side, centre.1 - rho * b / side))
            }
            Lens::Equirectangular => {
                let azimuth = a.atan2(c);
                let elevation = b.clamp(-1.0, 1.0).asin();
                Some((
                    (azimuth / (2.0 * PI) + 0.5) * width as f32,
                    (0.5 - elevation / PI) * height as f32,
                ))
            }
            Lens::Pinhole | Lens::Orthographic { .. } => None,
        }
    }

    /// Density per sr of the direction `d` (camera frame, unit, seen by the film) when film
    /// positions are drawn uniformly over the whole `width` x `height` image: film area per
    /// solid angle over the image's area. Not for the pinhole or the orthographic lens.
    pub fn direction_density(&self, d: [f32; 3], width: u32, height: u32) -> f32 {
        let [a, b, c] = d;
        let area = width as f32 * height as f32;
        match *self {
            Lens::Fisheye {
                radial,
                radius_px,
                g_max,
                ..
            } => {
                let theta = (a * a + b * b).sqrt().atan2(c);
                let scale = radius_px / g_max;
                scale * scale * radial.area_per_sr(theta) / area
            }
            Lens::Equirectangular => {
                // Film area per sr: (W / 2π)(H / π) / cos(elevation).
                let cos_el = (a * a + c * c).sqrt().max(1e-7);
                1.0 / (2.0 * PI * PI * cos_el)
            }
            Lens::Pinhole | Lens::Orthographic { .. } => 0.0,
        }
    }

    /// Whether film position (`x`, `y`) lies inside the image (the fisheye's circle).
    pub fn sees(&self, x: f32, y: f32) -> bool {
        match *self {
            Lens::Fisheye {
                centre, radius_px, ..
            } => {
                let (dx, dy) = (x - centre.0, y - centre.1);
                dx * dx + dy * dy <= radius_px * radius_px
            }
            _ => true,
        }
    }

    /// Whether pixel (`x`, `y`) lies wholly outside the image circle (then it is black and
    /// takes no camera ray).
    pub fn pixel_outside(&self, x: u32, y: u32) -> bool {
        match *self {
            Lens::Fisheye {
                centre, radius_px, ..
            } => {
                // The pixel's point closest to the centre.
                let near = |lo: f32, c: f32| c.clamp(lo, lo + 1.0) - c;
                let dx = near(x as f32, centre.0);
                let dy = near(y as f32, centre.1);
                dx * dx + dy * dy > radius_px * radius_px
            }
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn names_round_trip_and_parse_in_toml() {
        for p in Projection::ALL {
            assert_eq!(Projection::from_name(p.name()), Some(p));
            let text = format!("p = \"{}\"", p.name());
            #[derive(Deserialize)]
            struct T {
                p: Projection,
            }
            let t: T = toml::from_str(&text).unwrap_or_else(|e| panic!("{text}: {e}"));
            assert_eq!(t.p, p);
        }
        assert_eq!(Projection::from_name("fisheye"), None);
    }

    #[test]
    fn directions_and_film_positions_are_inverse() {
        for lens in [
            Lens::fisheye(Radial::Equidistant, PI, 200, 160),
            Lens::fisheye(Radial::Equisolid, 2.5, 200, 160),
            Lens::fisheye(Radial::Hemispherical, PI, 160, 200),
            Lens::Equirectangular,
        ] {
            for (x, y) in [(100.0, 80.0), (37.5, 60.25), (120.0, 150.0), (101.0, 79.0)] {
                let Some(d) = lens.direction(x, y, 200, 160) else {
                    continue;
                };
                let (bx, by) = lens.film_position(d, 200, 160).unwrap();
                assert!(
                    (bx - x).abs() < 1e-3 && (by - y).abs() < 1e-3,
                    "{lens:?} {x} {y}"
                );
            }
        }
    }
}
