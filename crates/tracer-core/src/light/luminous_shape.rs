//! The luminous opening of a luminaire: a point, a rectangle, a disc, a box or a vertical
//! cylinder, as IES LM-63 and EULUMDAT files describe it (LIGHTING.md, "Luminous openings").
//!
//! Each point of the opening emits the file's distribution shape with the luminance
//! L(ω) = I(ω) / A_proj(ω), so that the far field is the point model's. Coordinates are the
//! luminaire's own: x along C0 (the length), y along C90 (the width), z along the nadir (the
//! height); the opening is centred on the photometric centre, a flat one in the plane z = 0.

use glam::Vec3;
use std::f32::consts::{PI, TAU};

/// A luminous opening; sizes in metres as read from a file, or in the scene unit once placed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LuminousShape {
    Point,
    /// Flat, emitting from both faces.
    Rectangle {
        length: f32,
        width: f32,
    },
    /// Flat, emitting from both faces.
    Disc {
        diameter: f32,
    },
    /// Every face luminous.
    Box {
        length: f32,
        width: f32,
        height: f32,
    },
    /// The axis along the nadir; the mantle and both ends luminous.
    Cylinder {
        diameter: f32,
        height: f32,
    },
}

/// The names the sidecar's `shape` takes for an explicit shape.
pub const SHAPE_NAMES: [&str; 5] = ["point", "rectangle", "disc", "box", "cylinder"];

impl LuminousShape {
    /// The sidecar's name of the shape.
    pub fn name(&self) -> &'static str {
        match self {
            LuminousShape::Point => "point",
            LuminousShape::Rectangle { .. } => "rectangle",
            LuminousShape::Disc { .. } => "disc",
            LuminousShape::Box { .. } => "box",
            LuminousShape::Cylinder { .. } => "cylinder",
        }
    }

    /// Its sizes in the order the sidecar's `size` gives them: [length, width] for a rectangle,
    /// [diameter] for a disc, [length, width, height] for a box, [diameter, height] for a
    /// cylinder, none for a point.
    pub fn size(&self) -> Vec<f32> {
        match *self {
            LuminousShape::Point => Vec::new(),
            LuminousShape::Rectangle { length, width } => vec![length, width],
            LuminousShape::Disc { diameter } => vec![diameter],
            LuminousShape::Box {
                length,
                width,
                height,
            } => vec![length, width, height],
            LuminousShape::Cylinder { diameter, height } => vec![diameter, height],
        }
    }

    /// The shape called `name` with `size` (see [`LuminousShape::size`]), or why not.
    pub fn from_name(name: &str, size: &[f32]) -> Result<LuminousShape, String> {
        let want = match name {
            "point" => 0,
            "rectangle" | "cylinder" => 2,
            "disc" => 1,
            "box" => 3,
            _ => {
                return Err(format!(
                    "unknown shape \"{name}\" (expected file, {})",
                    SHAPE_NAMES.join(", ")
                ));
            }
        };
        let order = match name {
            "rectangle" => "[length, width]",
            "disc" => "[diameter]",
            "box" => "[length, width, height]",
            "cylinder" => "[diameter, height]",
            _ => "none",
        };
        if size.len() != want {
            return Err(format!(
                "shape \"{name}\" takes size = {order} in the scene unit, got {} numbers",
                size.len()
            ));
        }
        if !size.iter().all(|s| s.is_finite() && *s > 0.0) {
            return Err(format!(
                "shape \"{name}\": every size must be a finite number > 0"
            ));
        }
        Ok(match name {
            "rectangle" => LuminousShape::Rectangle {
                length: size[0],
                width: size[1],
            },
            "disc" => LuminousShape::Disc { diameter: size[0] },
            "box" => LuminousShape::Box {
                length: size[0],
                width: size[1],
                height: size[2],
            },
            "cylinder" => LuminousShape::Cylinder {
                diameter: size[0],
                height: size[1],
            },
            _ => LuminousShape::Point,
        })
    }

    /// An IES LM-63 opening from its width (along C90-C270), length (along C0-C180) and height,
    /// in metres, by LM-63-2019's table of luminous shapes; with a note when the file's shape is
    /// one raygine does not draw (it falls back to a point).
    pub fn from_ies(width: f32, length: f32, height: f32) -> (LuminousShape, Option<String>) {
        let (w, l, h) = (width, length, height);
        let shape = match (w, l, h) {
            (0.0, 0.0, 0.0) => Some(LuminousShape::Point),
            _ if w > 0.0 && l > 0.0 && h == 0.0 => Some(LuminousShape::Rectangle {
                length: l,
                width: w,
            }),
            _ if w > 0.0 && l > 0.0 && h > 0.0 => Some(LuminousShape::Box {
                length: l,
                width: w,
                height: h,
            }),
            _ if w < 0.0 && w == l && h == 0.0 => Some(LuminousShape::Disc { diameter: -w }),
            _ if w < 0.0 && w == l && h > 0.0 => Some(LuminousShape::Cylinder {
                diameter: -w,
                height: h,
            }),
            _ => None,
        };
        match shape {
            Some(s) => (s, None),
            None => (
                LuminousShape::Point,
                Some(format!(
                    "its luminous shape (width {w} m, length {l} m, height {h} m) is not a \
                     rectangle, disc, box or vertical cylinder: drawn as a point"
                )),
            ),
        }
    }

    /// A EULUMDAT opening from its length or diameter, width (0: circular) and its heights at
    /// C0, C90, C180 and C270, in metres. Unequal heights become their mean, with a note.
    pub fn from_eulumdat(
        length: f32,
        width: f32,
        heights: [f32; 4],
    ) -> (LuminousShape, Option<String>) {
        let height = heights.iter().sum::<f32>() / 4.0;
        let uneven = heights.iter().any(|h| (h - heights[0]).abs() > 1e-6);
        let note = uneven.then(|| {
            format!(
                "its luminous heights differ ({:?} m at C0, C90, C180, C270): drawn with their \
                 mean, {height} m",
                heights
            )
        });
        if !(length >= 0.0 && width >= 0.0 && heights.iter().all(|h| *h >= 0.0)) {
            return (
                LuminousShape::Point,
                Some(format!(
                    "its luminous area has a negative size (length {length} m, width {width} \
                     m): drawn as a point"
                )),
            );
        }
        let shape = match (length > 0.0, width > 0.0, height > 0.0) {
            (false, _, _) => LuminousShape::Point,
            (true, false, false) => LuminousShape::Disc { diameter: length },
            (true, false, true) => LuminousShape::Cylinder {
                diameter: length,
                height,
            },
            (true, true, false) => LuminousShape::Rectangle { length, width },
            (true, true, true) => LuminousShape::Box {
                length,
                width,
                height,
            },
        };
        (shape, note.filter(|_| shape != LuminousShape::Point))
    }

    /// The same shape with every size times `k` (metres to the scene unit: 1 / metres per
    /// unit).
    pub fn scaled(&self, k: f32) -> LuminousShape {
        match *self {
            LuminousShape::Point => LuminousShape::Point,
            LuminousShape::Rectangle { length, width } => LuminousShape::Rectangle {
                length: length * k,
                width: width * k,
            },
            LuminousShape::Disc { diameter } => LuminousShape::Disc {
                diameter: diameter * k,
            },
            LuminousShape::Box {
                length,
                width,
                height,
            } => LuminousShape::Box {
                length: length * k,
                width: width * k,
                height: height * k,
            },
            LuminousShape::Cylinder { diameter, height } => LuminousShape::Cylinder {
                diameter: diameter * k,
                height: height * k,
            },
        }
    }

    /// Its largest dimension (0 for a point).
    pub fn largest_dimension(&self) -> f32 {
        self.size().into_iter().fold(0.0, f32::max)
    }

    /// Whether it is flat (a point, a rectangle or a disc): every sampled point then carries the
    /// file's intensity unchanged (see [`LuminousShape::emission_factor`]).
    pub fn is_flat(&self) -> bool {
        matches!(
            self,
            LuminousShape::Point | LuminousShape::Rectangle { .. } | LuminousShape::Disc { .. }
        )
    }

    /// The area points are sampled on (one face of a flat shape).
    pub fn area(&self) -> f32 {
        match *self {
            LuminousShape::Point => 0.0,
            LuminousShape::Rectangle { length, width } => length * width,
            LuminousShape::Disc { diameter } => disc_area(diameter),
            LuminousShape::Box {
                length,
                width,
                height,
            } => 2.0 * (length * width + width * height + length * height),
            LuminousShape::Cylinder { diameter, height } => {
                PI * diameter * height + 2.0 * disc_area(diameter)
            }
        }
    }

    /// The area projected onto the plane normal to unit `d` (local coordinates).
    pub fn projected_area(&self, d: Vec3) -> f32 {
        let (x, y, z) = (d.x.abs(), d.y.abs(), d.z.abs());
        match *self {
            LuminousShape::Point => 0.0,
            LuminousShape::Rectangle { length, width } => length * width * z,
            LuminousShape::Disc { diameter } => disc_area(diameter) * z,
            LuminousShape::Box {
                length,
                width,
                height,
            } => length * width * z + width * height * x + length * height * y,
            LuminousShape::Cylinder { diameter, height } => {
                disc_area(diameter) * z + diameter * height * (1.0 - z * z).max(0.0).sqrt()
            }
        }
    }

    /// A point uniform on the shape's area from `u`, with its outward unit normal on a solid
    /// shape (zero on a flat one, which emits from both faces).
    pub fn sample(&self, u: [f32; 2]) -> (Vec3, Vec3) {
        let [u0, u1] = u;
        match *self {
            LuminousShape::Point => (Vec3::ZERO, Vec3::ZERO),
            LuminousShape::Rectangle { length, width } => (
                Vec3::new((u0 - 0.5) * length, (u1 - 0.5) * width, 0.0),
                Vec3::ZERO,
            ),
            LuminousShape::Disc { diameter } => (disc_point(diameter, u0, u1, 0.0), Vec3::ZERO),
            LuminousShape::Box {
                length,
                width,
                height,
            } => {
                let (l, w, h) = (length, width, height);
                // Faces in pairs: ±z (l·w), ±x (w·h), ±y (l·h).
                let pairs = [l * w, w * h, l * h];
                let total: f32 = pairs.iter().sum();
                let mut t = u0 * total;
                let mut axis = 0;
                while axis < 2 && t >= pairs[axis] {
                    t -= pairs[axis];
                    axis += 1;
                }
                // t / pair in [0, 1): the first half the negative face, the second the positive.
                let s = (t / pairs[axis].max(f32::MIN_POSITIVE)).clamp(0.0, 1.0);
                let (sign, a) = if s < 0.5 {
                    (-1.0, s * 2.0)
                } else {
                    (1.0, s * 2.0 - 1.0)
                };
                let (a, b) = (a - 0.5, u1 - 0.5);
                match axis {
                    0 => (Vec3::new(a * l, b * w, sign * h * 0.5), Vec3::Z * sign),
                    1 => (Vec3::new(sign * l * 0.5, a * w, b * h), Vec3::X * sign),
                    _ => (Vec3::new(a * l, sign * w * 0.5, b * h), Vec3::Y * sign),
                }
            }
            LuminousShape::Cylinder { diameter, height } => {
                let mantle = PI * diameter * height;
                let ends = 2.0 * disc_area(diameter);
                let t = u0 * (mantle + ends);
                if t < mantle {
                    let phi = TAU * (t / mantle);
                    let (s, c) = phi.sin_cos();
                    let r = diameter * 0.5;
                    (
                        Vec3::new(r * c, r * s, (u1 - 0.5) * height),
                        Vec3::new(c, s, 0.0),
                    )
                } else {
                    let e = ((t - mantle) / ends).clamp(0.0, 1.0);
                    let (sign, a) = if e < 0.5 {
                        (-1.0, e * 2.0)
                    } else {
                        (1.0, e * 2.0 - 1.0)
                    };
                    (
                        disc_point(diameter, a, u1, sign * height * 0.5),
                        Vec3::Z * sign,
                    )
                }
            }
        }
    }

    /// The area of the faces that face `r` (local): those whose plane has `r` on its outer
    /// side. Only they can send light to `r`. A flat shape's whole area (it emits from both
    /// faces); 0 inside a solid one.
    pub fn facing_area(&self, r: Vec3) -> f32 {
        match *self {
            LuminousShape::Box {
                length,
                width,
                height,
            } => box_facing_areas(Vec3::new(length, width, height), r)
                .iter()
                .sum(),
            LuminousShape::Cylinder { diameter, height } => {
                let (arc, cap) = cylinder_facing(diameter, height, r);
                arc * diameter * 0.5 * height + cap
            }
            _ => self.area(),
        }
    }

    /// A point uniform on the faces that face `r` ([`LuminousShape::facing_area`]) and its
    /// outward normal, as [`LuminousShape::sample`] gives them; None when no face does.
    pub fn sample_facing(&self, r: Vec3, u: [f32; 2]) -> Option<(Vec3, Vec3)> {
        let [u0, u1] = u;
        match *self {
            LuminousShape::Box {
                length,
                width,
                height,
            } => {
                let size = Vec3::new(length, width, height);
                let h = size * 0.5;
                let areas = box_facing_areas(size, r);
                let total: f32 = areas.iter().sum();
                if total <= 0.0 {
                    return None;
                }
                let mut t = u0 * total;
                let mut axis = 0;
                while axis < 2 && (areas[axis] <= 0.0 || t >= areas[axis]) {
                    t -= areas[axis];
                    axis += 1;
                }
                let a = (t / areas[axis].max(f32::MIN_POSITIVE)).clamp(0.0, 1.0) - 0.5;
                let b = u1 - 0.5;
                let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
                let mut p = Vec3::ZERO;
                let sign = r[axis].signum();
                p[axis] = sign * h[axis];
                p[i] = a * size[i];
                p[j] = b * size[j];
                let mut n = Vec3::ZERO;
                n[axis] = sign;
                Some((p, n))
            }
            LuminousShape::Cylinder { diameter, height } => {
                let (arc, cap) = cylinder_facing(diameter, height, r);
                let mantle = arc * diameter * 0.5 * height;
                if mantle + cap <= 0.0 {
                    return None;
                }
                let t = u0 * (mantle + cap);
                if t < mantle {
                    let phi = r.y.atan2(r.x) + arc * (t / mantle - 0.5);
                    let (s, c) = phi.sin_cos();
                    let radius = diameter * 0.5;
                    Some((
                        Vec3::new(radius * c, radius * s, (u1 - 0.5) * height),
                        Vec3::new(c, s, 0.0),
                    ))
                } else {
                    let a = ((t - mantle) / cap).clamp(0.0, 1.0);
                    let sign = r.z.signum();
                    Some((
                        disc_point(diameter, a, u1, sign * height * 0.5),
                        Vec3::Z * sign,
                    ))
                }
            }
            _ => Some(self.sample(u)),
        }
    }

    /// What a point sampled uniformly on the shape ([`LuminousShape::sample`], outward normal
    /// `n`) sends along unit `d`, relative to the file's intensity I(d) treated as a point:
    /// A · max(0, n·d) / A_proj(d) on a solid shape, so that L(d) = I(d) / A_proj(d) on its
    /// faces; 1 on a flat one, whose |n·d| cancels its projected area.
    pub fn emission_factor(&self, n: Vec3, d: Vec3) -> f32 {
        if self.is_flat() || n == Vec3::ZERO {
            return 1.0;
        }
        let cos = n.dot(d);
        if cos <= 0.0 {
            return 0.0;
        }
        let projected = self.projected_area(d);
        if projected > 0.0 {
            self.area() * cos / projected
        } else {
            0.0
        }
    }

    /// The half-extents of its bounding box along x, y and z (local).
    pub fn half_extent(&self) -> Vec3 {
        match *self {
            LuminousShape::Point => Vec3::ZERO,
            LuminousShape::Rectangle { length, width } => Vec3::new(length, width, 0.0) * 0.5,
            LuminousShape::Disc { diameter } => Vec3::new(diameter, diameter, 0.0) * 0.5,
            LuminousShape::Box {
                length,
                width,
                height,
            } => Vec3::new(length, width, height) * 0.5,
            LuminousShape::Cylinder { diameter, height } => {
                Vec3::new(diameter, diameter, height) * 0.5
            }
        }
    }
}

impl LuminousShape {
    /// Its edges as line segments in its own coordinates, for drawing: a rectangle's four
    /// sides, a box's twelve edges, a disc's rim and a cylinder's two rims with four lines
    /// between them (circles as `segments`-gons). None for a point.
    pub fn outline(&self, segments: usize) -> Vec<[Vec3; 2]> {
        let ring = |d: f32, z: f32| -> Vec<[Vec3; 2]> {
            let n = segments.max(3);
            let at = |k: usize| {
                let (s, c) = (TAU * k as f32 / n as f32).sin_cos();
                Vec3::new(c * d * 0.5, s * d * 0.5, z)
            };
            (0..n).map(|k| [at(k), at(k + 1)]).collect()
        };
        let rectangle = |l: f32, w: f32, z: f32| -> Vec<[Vec3; 2]> {
            let c = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .map(|(a, b)| Vec3::new(a * l * 0.5, b * w * 0.5, z));
            (0..4).map(|k| [c[k], c[(k + 1) % 4]]).collect()
        };
        match *self {
            LuminousShape::Point => Vec::new(),
            LuminousShape::Rectangle { length, width } => rectangle(length, width, 0.0),
            LuminousShape::Disc { diameter } => ring(diameter, 0.0),
            LuminousShape::Box {
                length,
                width,
                height,
            } => {
                let mut lines = rectangle(length, width, -height * 0.5);
                lines.extend(rectangle(length, width, height * 0.5));
                for [a, _] in rectangle(length, width, -height * 0.5) {
                    lines.push([a, a + Vec3::Z * height]);
                }
                lines
            }
            LuminousShape::Cylinder { diameter, height } => {
                let mut lines = ring(diameter, -height * 0.5);
                lines.extend(ring(diameter, height * 0.5));
                for (x, y) in [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)] {
                    let a = Vec3::new(x * diameter * 0.5, y * diameter * 0.5, -height * 0.5);
                    lines.push([a, a + Vec3::Z * height]);
                }
                lines
            }
        }
    }
}

/// The area of the face of a box of `size` across each axis that faces `r` (local), 0 where
/// `r` lies between the two faces.
fn box_facing_areas(size: Vec3, r: Vec3) -> [f32; 3] {
    let faces = Vec3::new(size.y * size.z, size.x * size.z, size.x * size.y);
    std::array::from_fn(|k| {
        if r[k].abs() > size[k] * 0.5 {
            faces[k]
        } else {
            0.0
        }
    })
}

/// What of a cylinder faces `r` (local): the angle of its mantle, and the area of the end
/// towards `r` (0 when `r` lies between the ends).
fn cylinder_facing(diameter: f32, height: f32, r: Vec3) -> (f32, f32) {
    let cap = if r.z.abs() > height * 0.5 {
        disc_area(diameter)
    } else {
        0.0
    };
    (mantle_arc(diameter, r), cap)
}

/// The angle of a cylinder's mantle that faces `r` (local): 2 acos(R / ρ) from a distance ρ
/// off the axis beyond the radius R, else 0.
fn mantle_arc(diameter: f32, r: Vec3) -> f32 {
    let rho = (r.x * r.x + r.y * r.y).sqrt();
    let radius = diameter * 0.5;
    if rho > radius {
        2.0 * (radius / rho).clamp(-1.0, 1.0).acos()
    } else {
        0.0
    }
}

fn disc_area(diameter: f32) -> f32 {
    PI * diameter * diameter * 0.25
}

/// A point uniform on a disc of `diameter` in the plane z = `z`.
fn disc_point(diameter: f32, u: f32, v: f32, z: f32) -> Vec3 {
    let r = diameter * 0.5 * u.max(0.0).sqrt();
    let (s, c) = (TAU * v).sin_cos();
    Vec3::new(r * c, r * s, z)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use crate::sampling::uniform_sphere;

    const SHAPES: [LuminousShape; 4] = [
        LuminousShape::Rectangle {
            length: 1.2,
            width: 0.3,
        },
        LuminousShape::Disc { diameter: 0.4 },
        LuminousShape::Box {
            length: 0.6,
            width: 0.2,
            height: 0.1,
        },
        LuminousShape::Cylinder {
            diameter: 0.3,
            height: 0.5,
        },
    ];

    /// `n²` well-spread numbers in [0, 1)²: a Fibonacci lattice (fine in each coordinate, so
    /// that small faces get their share).
    fn grid(n: usize) -> impl Iterator<Item = [f32; 2]> {
        let count = n * n;
        let golden = 0.618_033_988_749_895_f64;
        (0..count).map(move |i| {
            [
                ((i as f64 + 0.5) / count as f64) as f32,
                ((i as f64 * golden).fract()) as f32,
            ]
        })
    }

    /// Cauchy's formula: a convex body's projected area averaged over directions is a quarter
    /// of its surface (a flat shape counts both faces).
    #[test]
    fn projected_area_averages_to_a_quarter_of_the_surface() {
        for shape in SHAPES {
            let n = 400;
            let mean = grid(n)
                .map(|u| shape.projected_area(uniform_sphere(u[0], u[1])))
                .sum::<f32>()
                / (n * n) as f32;
            let surface = if shape.is_flat() {
                2.0 * shape.area()
            } else {
                shape.area()
            };
            assert!(
                (mean / (surface / 4.0) - 1.0).abs() < 2e-3,
                "{shape:?}: {mean} vs {}",
                surface / 4.0
            );
        }
    }

    /// The sampled points lie on the surface, and towards every direction their emission
    /// factors average to 1 (the far field is the point model's).
    #[test]
    fn sampled_points_send_the_file_intensity_on_average() {
        for shape in SHAPES {
            for d in [
                Vec3::Z,
                Vec3::new(0.3, -0.4, 0.866).normalize(),
                Vec3::new(1.0, 0.2, 0.0).normalize(),
                Vec3::new(-0.5, 0.7, -0.5).normalize(),
            ] {
                let n = 300;
                let mean = grid(n)
                    .map(|u| {
                        let (p, normal) = shape.sample(u);
                        let h = shape.half_extent();
                        assert!(
                            p.abs().cmple(h + Vec3::splat(1e-5)).all(),
                            "{shape:?}: {p} outside {h}"
                        );
                        shape.emission_factor(normal, d)
                    })
                    .sum::<f32>()
                    / (n * n) as f32;
                assert!((mean - 1.0).abs() < 3e-3, "{shape:?} towards {d}: {mean}");
            }
        }
    }

    /// Sampling only the faces that face a receiver, weighted by their area, sends it what the
    /// whole surface does: Σ over faces of ∫ max(0, n·d) dA / A_proj, with d towards it.
    #[test]
    fn facing_faces_carry_all_the_light_a_receiver_gets() {
        for shape in SHAPES {
            for r in [
                Vec3::new(0.05, 0.02, 0.6),
                Vec3::new(0.4, 0.1, 0.05),
                Vec3::new(-0.3, 0.35, -0.4),
                Vec3::new(0.0, 0.05, -0.4),
            ] {
                // Receiver's view: per sample, factor(n, d) over the density 1 / area.
                let weigh = |p: Vec3, n: Vec3, area: f32| {
                    let d = (r - p).normalize();
                    let k = if shape.is_flat() {
                        1.0
                    } else {
                        shape.emission_factor(n, d) / shape.area() * area
                    };
                    // The kernel cos / R² of a unit receiver facing the shape's centre.
                    k * (-d).dot(-r.normalize()).max(0.0) / (r - p).length_squared()
                };
                let n = 300;
                let all = grid(n)
                    .map(|u| {
                        let (p, normal) = shape.sample(u);
                        weigh(p, normal, shape.area())
                    })
                    .sum::<f32>()
                    / (n * n) as f32;
                let facing_area = shape.facing_area(r);
                let facing = grid(n)
                    .map(|u| {
                        shape.sample_facing(r, u).map_or(0.0, |(p, normal)| {
                            let d = (r - p).normalize();
                            assert!(shape.is_flat() || normal.dot(d) > -1e-4);
                            weigh(p, normal, facing_area)
                        })
                    })
                    .sum::<f32>()
                    / (n * n) as f32;
                assert!(
                    (facing / all - 1.0).abs() < 5e-3,
                    "{shape:?} at {r}: facing {facing} vs all {all}"
                );
            }
        }
    }

    #[test]
    fn file_fields_give_the_lm63_and_eulumdat_shapes() {
        assert_eq!(
            LuminousShape::from_ies(0.3, 1.2, 0.0).0,
            LuminousShape::Rectangle {
                length: 1.2,
                width: 0.3
            }
        );
        assert_eq!(
            LuminousShape::from_ies(-0.2, -0.2, 0.0).0,
            LuminousShape::Disc { diameter: 0.2 }
        );
        assert_eq!(
            LuminousShape::from_ies(-0.2, -0.2, 0.4).0,
            LuminousShape::Cylinder {
                diameter: 0.2,
                height: 0.4
            }
        );
        assert!(matches!(
            LuminousShape::from_ies(0.2, 0.2, 0.1).0,
            LuminousShape::Box { .. }
        ));
        // A sphere (all negative) is not drawn: a point, with a note.
        let (s, note) = LuminousShape::from_ies(-0.2, -0.2, -0.2);
        assert_eq!(s, LuminousShape::Point);
        assert!(note.is_some_and(|n| n.contains("drawn as a point")));
        assert_eq!(
            LuminousShape::from_ies(0.0, 0.0, 0.0),
            (LuminousShape::Point, None)
        );
        assert_eq!(
            LuminousShape::from_eulumdat(0.15, 0.0, [0.0; 4]).0,
            LuminousShape::Disc { diameter: 0.15 }
        );
        let (boxed, note) = LuminousShape::from_eulumdat(0.6, 0.3, [0.1, 0.1, 0.2, 0.2]);
        assert!(matches!(boxed, LuminousShape::Box { height, .. } if (height - 0.15).abs() < 1e-6));
        assert!(note.is_some());
        assert!(LuminousShape::from_name("disc", &[0.2, 0.1]).is_err());
        assert!(LuminousShape::from_name("sphere", &[0.2]).is_err());
        assert!(LuminousShape::from_name("box", &[0.2, 0.1, -1.0]).is_err());
        assert_eq!(
            LuminousShape::from_name("cylinder", &[0.2, 0.4]),
            Ok(LuminousShape::Cylinder {
                diameter: 0.2,
                height: 0.4
            })
        );
    }
}
