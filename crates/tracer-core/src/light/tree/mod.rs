//! A light tree: a binary bounding-volume hierarchy over lights, each node bounding its lights'
//! positions, their total power and the directions they emit in, so that one light can be
//! picked for a receiving point in proportion to an upper bound on what it gives there (Conty
//! Estevez & Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting";
//! pbrt-v4's `BVHLightSampler` and Cycles' light tree follow the same idea).
//!
//! - A node's importance at a point is its power over the squared distance to its centre, times
//!   the cosine of the smallest angle its emission cone can make with the direction to the
//!   point, times the cosine of the smallest angle that direction can make with the receiver's
//!   normal (two-sided, so the orientation of the normal does not matter). Every bound is
//!   conservative: a node gets importance 0 only where none of its lights can send light.
//! - Picking walks from the root, choosing a child in proportion to the children's
//!   importances; the probability of the light reached is the product of the choices.
//!   [`LightTree::pmf`] finds it again for any light by walking up from its leaf, so that
//!   multiple importance sampling uses exactly the probability the sampler had.
//! - The tree is built binary, then collapsed to eight children per node (`wide.rs`), whose
//!   importances are computed together: three levels for 100 lights instead of seven.
//! - The tree is built once per render (median splits on the longest axis of the centroids:
//!   n log² n, 1,000 lights in well under a millisecond).

mod wide;

#[cfg(target_arch = "x86_64")]
use crate::lanes8::Avx8;
use crate::lanes8::{Lanes8, Mask8, Scalar8};
use glam::Vec3;
use std::f32::consts::{FRAC_PI_2, PI};
use wide::{Child, LANES, Wide};

/// What the tree needs to know of one light: where it is, how much it emits and where to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    pub min: Vec3,
    pub max: Vec3,
    /// Power (any unit shared by all lights of the tree; lumen here).
    pub power: f32,
    /// Unit axis of the cone of surface normals (or of a spot's beam).
    pub axis: Vec3,
    /// Half-angle of the cone of normals around `axis` (π: every direction).
    pub theta_o: f32,
    /// How far past the normals emission reaches (π/2 for a Lambertian surface, 0 for a spot's
    /// beam, which `theta_o` already bounds).
    pub theta_e: f32,
    /// sin θo, cos θo and cos θe, kept for [`LightBounds::importance`].
    trig: [f32; 3],
}

impl LightBounds {
    /// A light at point `p` emitting in every direction.
    pub fn point(p: Vec3, power: f32) -> Self {
        Self {
            min: p,
            max: p,
            power,
            axis: Vec3::Y,
            theta_o: PI,
            theta_e: FRAC_PI_2,
            trig: [0.0; 3],
        }
        .with_trig()
    }

    /// A light within the box `min`..`max` emitting in every direction.
    pub fn around(min: Vec3, max: Vec3, power: f32) -> Self {
        Self {
            min,
            max,
            ..Self::point(min, power)
        }
    }

    /// A light at point `p` emitting only within `half_angle` of unit `axis`.
    pub fn beam(p: Vec3, power: f32, axis: Vec3, half_angle: f32) -> Self {
        Self {
            min: p,
            max: p,
            power,
            axis,
            theta_o: half_angle.clamp(0.0, PI),
            theta_e: 0.0,
            trig: [0.0; 3],
        }
        .with_trig()
    }

    /// A flat Lambertian emitter with corners `vertices` and unit `normal`; `two_sided` when
    /// both faces emit.
    pub fn surface(vertices: &[Vec3], power: f32, normal: Vec3, two_sided: bool) -> Self {
        let (min, max) = vertices
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        Self {
            min,
            max,
            power,
            axis: normal,
            theta_o: if two_sided { PI } else { 0.0 },
            theta_e: FRAC_PI_2,
            trig: [0.0; 3],
        }
        .with_trig()
    }

    fn with_trig(mut self) -> Self {
        self.trig = [self.theta_o.sin(), self.theta_o.cos(), self.theta_e.cos()];
        self
    }

    fn centre(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// The bounds of both.
    fn union(&self, other: &Self) -> Self {
        let (axis, theta_o) = cone_union(self.axis, self.theta_o, other.axis, other.theta_o);
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
            power: self.power + other.power,
            axis,
            theta_o,
            theta_e: self.theta_e.max(other.theta_e),
            trig: [0.0; 3],
        }
        .with_trig()
    }

    /// An upper bound (up to a common factor) on the light these lights send to point `p` on a
    /// surface with unit normal `n` (zero: a point receiving from every direction).
    pub fn importance(&self, p: Vec3, n: Vec3) -> f32 {
        Packed::new(self).importance(p, n)
    }
}

/// A node's bounds as [`Packed::importance`] reads them: its bounding sphere, power and cone.
#[derive(Clone, Copy, Debug)]
struct Packed {
    centre: Vec3,
    radius: f32,
    radius2: f32,
    axis: Vec3,
    power: f32,
    sin_o: f32,
    cos_o: f32,
    cos_e: f32,
    /// θo = π: every direction (points, two-sided surfaces), no cone to test.
    omni: bool,
}

impl Packed {
    fn new(b: &LightBounds) -> Self {
        let [sin_o, cos_o, cos_e] = b.trig;
        let half = (b.max - b.min) * 0.5;
        Self {
            centre: b.centre(),
            radius: half.length(),
            radius2: half.length_squared(),
            axis: b.axis,
            power: b.power,
            sin_o,
            cos_o,
            cos_e,
            omni: b.theta_o >= PI,
        }
    }

    /// See [`LightBounds::importance`]. One square root and one division on the common path.
    #[inline]
    fn importance(&self, p: Vec3, n: Vec3) -> f32 {
        if self.power <= 0.0 {
            return 0.0;
        }
        let d = p - self.centre;
        let dist2 = d.length_squared();
        // Inside the bounding sphere every direction is possible (θb = π).
        let inside = dist2 <= self.radius2;
        if inside && self.radius2 <= 0.0 {
            // `p` at a point light.
            return self.power * 1e12;
        }
        let inv_dist = if inside { 0.0 } else { dist2.sqrt().recip() };
        let mut importance = if inside {
            self.power / self.radius2
        } else {
            self.power * inv_dist * inv_dist
        };
        // sin of the half-angle θb the bounding sphere subtends from `p`.
        let sin_b = (self.radius * inv_dist).min(1.0);
        if !self.omni {
            let (sin_b, cos_b) = if inside {
                (0.0, -1.0)
            } else {
                (sin_b, sin_of(sin_b))
            };
            // Smallest angle between an emission normal and the direction to `p`.
            let to_p = if inside { self.axis } else { d * inv_dist };
            let cos_w = self.axis.dot(to_p).clamp(-1.0, 1.0);
            let (sin_x, cos_x) = sub_clamped(sin_of(cos_w), cos_w, self.sin_o, self.cos_o);
            let (_, cos_p) = sub_clamped(sin_x, cos_x, sin_b, cos_b);
            // Slightly generous, so that rounding never zeroes a light at the edge of its cone.
            if cos_p < self.cos_e - 1e-4 {
                return 0.0;
            }
            importance *= cos_p.max(1e-4);
        }
        if n != Vec3::ZERO && !inside {
            // cos(max(0, θi − θb)) ≤ cos θi + sin θb: looser than the exact bound, but without
            // more square roots on the path every light sample takes.
            let cos_i = n.dot(d).abs() * inv_dist;
            importance *= (cos_i + sin_b).clamp(1e-4, 1.0);
        }
        importance
    }
}

fn sin_of(cos: f32) -> f32 {
    (1.0 - cos * cos).max(0.0).sqrt()
}

/// (sin, cos) of max(0, a − b) for angles a, b in [0, π] given as (sin, cos).
fn sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> (f32, f32) {
    if cos_a >= cos_b {
        // a ≤ b
        (0.0, 1.0)
    } else {
        (sin_a * cos_b - cos_a * sin_b, cos_a * cos_b + sin_a * sin_b)
    }
}

/// The smallest cone (axis, half-angle) holding the cones (a, θa) and (b, θb).
fn cone_union(a: Vec3, theta_a: f32, b: Vec3, theta_b: f32) -> (Vec3, f32) {
    if theta_a >= PI || theta_b >= PI {
        return (a, PI);
    }
    let theta_d = a.dot(b).clamp(-1.0, 1.0).acos();
    if (theta_d + theta_b).min(PI) <= theta_a {
        return (a, theta_a);
    }
    if (theta_d + theta_a).min(PI) <= theta_b {
        return (b, theta_b);
    }
    let theta_o = (theta_a + theta_d + theta_b) * 0.5;
    if theta_o >= PI {
        return (a, PI);
    }
    // Turn `a` towards `b` by θo − θa.
    let turn = theta_o - theta_a;
    let Some(perp) = (b - a * theta_d.cos()).try_normalize() else {
        return (a, PI);
    };
    let axis = (a * turn.cos() + perp * turn.sin()).normalize_or(a);
    // A little slack against rounding in the rotation.
    (axis, (theta_o + 1e-3).min(PI))
}

#[derive(Clone, Copy, Debug)]
enum Node {
    /// A light, by its index in the build's list.
    Leaf(u32),
    /// Two children: the first right after this node, the second at this index.
    Inner(u32),
}

/// The tree over a list of lights (see the module docs).
#[derive(Clone, Debug, Default)]
pub struct LightTree {
    /// Wide nodes, the root first.
    wide: Vec<Wide>,
    /// Each wide node's parent (node, lane); the root's node is `u32::MAX`.
    parent: Vec<(u32, u8)>,
    /// Per light: its wide node and lane, or None for a light left out (no power).
    leaf_of: Vec<Option<(u32, u8)>>,
    /// One light in all.
    single: bool,
    /// The CPU has AVX2: importances eight lanes in one register.
    #[cfg(target_arch = "x86_64")]
    avx2: bool,
}

/// The binary tree of the build.
#[derive(Default)]
struct Binary {
    nodes: Vec<Node>,
    bounds: Vec<LightBounds>,
}

impl Binary {
    /// Builds the subtree of `items` at depth `depth`; returns its bounds.
    fn build(&mut self, lights: &[LightBounds], items: &mut [u32], depth: u8) -> LightBounds {
        let here = self.nodes.len();
        self.nodes.push(Node::Leaf(0));
        self.bounds.push(lights[items[0] as usize]);
        if items.len() == 1 || depth >= 63 {
            // (Depth 63 needs 2⁶³ lights with median splits: only identical centroids at
            // depth would get here, and then the first light stands for none of the rest.)
            let light = items[0];
            self.nodes[here] = Node::Leaf(light);
            return self.bounds[here];
        }
        let (lo, hi) = items
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &i| {
                let c = lights[i as usize].centre();
                (lo.min(c), hi.max(c))
            });
        let extent = hi - lo;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        let mid = items.len() / 2;
        items.select_nth_unstable_by(mid, |&a, &b| {
            let ca = lights[a as usize].centre()[axis];
            let cb = lights[b as usize].centre()[axis];
            ca.total_cmp(&cb)
        });
        let (first, second) = items.split_at_mut(mid);
        let a = self.build(lights, first, depth + 1);
        let second_index = self.nodes.len() as u32;
        let b = self.build(lights, second, depth + 1);
        self.nodes[here] = Node::Inner(second_index);
        self.bounds[here] = a.union(&b);
        self.bounds[here]
    }
}

/// A light picked by [`LightTree::sample`] and the probability of picking it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Picked {
    pub light: u32,
    pub pmf: f32,
}

impl LightTree {
    /// The tree over `lights`; lights without power (or with invalid bounds) are never picked.
    pub fn new(lights: &[LightBounds]) -> Self {
        let mut items: Vec<u32> = (0..lights.len() as u32)
            .filter(|&i| {
                let l = &lights[i as usize];
                l.power > 0.0 && l.power.is_finite() && l.min.is_finite() && l.max.is_finite()
            })
            .collect();
        let mut binary = Binary::default();
        if !items.is_empty() {
            binary.build(lights, &mut items, 0);
        }
        let packed: Vec<Packed> = binary.bounds.iter().map(Packed::new).collect();
        let c = wide::collapse(&binary.nodes, &packed, lights.len());
        LightTree {
            wide: c.wide,
            parent: c.parent,
            leaf_of: c.leaf_of,
            single: binary.nodes.len() == 1,
            #[cfg(target_arch = "x86_64")]
            avx2: std::is_x86_feature_detected!("avx2"),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.wide.is_empty()
    }

    /// Whether the tree holds one light, which every pick returns (no random number needed).
    pub fn is_single(&self) -> bool {
        self.single
    }

    /// Picks a light for point `p` with unit normal `n` (zero: no surface) with `u` in [0, 1).
    /// None when no light can reach `p`.
    #[inline]
    pub fn sample(&self, p: Vec3, n: Vec3, u: f32) -> Option<Picked> {
        if self.wide.is_empty() {
            return None;
        }
        if self.single {
            // One light: always it (whatever it gives here), as `pmf` says.
            let Child::Light(light) = self.wide[0].child(0) else {
                return None;
            };
            return Some(Picked { light, pmf: 1.0 });
        }
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is set only where the CPU has AVX2, the feature `sample_avx2` is
            // compiled for.
            return unsafe { self.sample_avx2(p, n, u) };
        }
        self.sample_with::<Scalar8>(p, n, u)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn sample_avx2(&self, p: Vec3, n: Vec3, u: f32) -> Option<Picked> {
        self.sample_with::<Avx8>(p, n, u)
    }

    /// [`LightTree::sample`] below the root, in lanes `L` (both kinds round alike).
    #[inline(always)]
    fn sample_with<L: Lanes8>(&self, p: Vec3, n: Vec3, u: f32) -> Option<Picked> {
        let mut node = 0usize;
        let mut pmf = 1.0f32;
        let mut u = u.clamp(0.0, 1.0 - f32::EPSILON);
        loop {
            let w = &self.wide[node];
            let lanes = w.importances::<L>(p, n);
            let sums = lanes.prefix_sum();
            let (imp, prefix) = (lanes.to_array(), sums.to_array());
            let total = prefix[LANES - 1];
            if total.is_nan() || total <= 0.0 {
                return None;
            }
            // The lane whose share of `total` holds u · total: the running sums do not
            // decrease, so it is the number of them at or below the target (the last lane with
            // importance when rounding runs past the end).
            let target = u * total;
            let mut lane = sums.le(L::splat(target)).bits().count_ones() as usize;
            if lane == LANES {
                lane = imp.iter().rposition(|&i| i > 0.0).unwrap_or(0);
            }
            let before = if lane == 0 { 0.0 } else { prefix[lane - 1] };
            let share = imp[lane];
            pmf *= share / total;
            u = ((target - before) / share).clamp(0.0, 1.0 - f32::EPSILON);
            match w.child(lane) {
                Child::Light(light) => return Some(Picked { light, pmf }),
                Child::Node(next) => node = next as usize,
            }
        }
    }

    /// The probability with which [`LightTree::sample`] at (`p`, `n`) picks `light`.
    pub fn pmf(&self, p: Vec3, n: Vec3, light: u32) -> f32 {
        let Some(Some(leaf)) = self.leaf_of.get(light as usize).copied() else {
            return 0.0;
        };
        if self.single {
            return 1.0;
        }
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: as in `sample`.
            return unsafe { self.pmf_avx2(p, n, leaf) };
        }
        self.pmf_with::<Scalar8>(p, n, leaf)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn pmf_avx2(&self, p: Vec3, n: Vec3, leaf: (u32, u8)) -> f32 {
        self.pmf_with::<Avx8>(p, n, leaf)
    }

    /// The choices from the leaf (wide node, lane) up to the root, multiplied root first as
    /// `sample_with` multiplies them, so that both give the same bits.
    #[inline(always)]
    fn pmf_with<L: Lanes8>(&self, p: Vec3, n: Vec3, leaf: (u32, u8)) -> f32 {
        let (mut node, mut lane) = leaf;
        let mut shares = [0.0f32; MAX_DEPTH];
        let mut depth = 0;
        loop {
            let lanes = self.wide[node as usize].importances::<L>(p, n);
            let total = lanes.prefix_sum().to_array()[LANES - 1];
            let imp = lanes.to_array();
            if total.is_nan() || total <= 0.0 || depth == MAX_DEPTH {
                return 0.0;
            }
            shares[depth] = imp[lane as usize] / total;
            depth += 1;
            if node == 0 {
                break;
            }
            (node, lane) = self.parent[node as usize];
        }
        shares[..depth]
            .iter()
            .rev()
            .fold(1.0, |pmf, share| pmf * share)
    }
}

/// Deeper than any wide tree gets (the binary build stops at depth 64, and a wide level spans
/// at least one binary level).
const MAX_DEPTH: usize = 64;

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    fn grid(n: usize) -> Vec<LightBounds> {
        (0..n * n)
            .map(|k| {
                let p = Vec3::new((k % n) as f32, 3.0, (k / n) as f32);
                LightBounds::point(p, 1.0 + (k % 3) as f32)
            })
            .collect()
    }

    #[test]
    fn pmfs_add_up_to_one_and_match_the_sampler() {
        let lights = grid(10);
        let tree = LightTree::new(&lights);
        let (p, n) = (Vec3::new(2.5, 0.0, 7.0), Vec3::Y);
        let total: f64 = (0..lights.len() as u32)
            .map(|i| f64::from(tree.pmf(p, n, i)))
            .sum();
        assert!((total - 1.0).abs() < 1e-5, "{total}");
        // Frequencies of picks against the pmf.
        let k = 200_000;
        let mut counts = vec![0u32; lights.len()];
        for i in 0..k {
            let u = (i as f32 + 0.5) / k as f32;
            let picked = tree.sample(p, n, u).expect("a light");
            assert!(
                (picked.pmf - tree.pmf(p, n, picked.light)).abs() <= 1e-6 * picked.pmf.max(1.0)
            );
            counts[picked.light as usize] += 1;
        }
        for (i, &c) in counts.iter().enumerate() {
            let expected = f64::from(tree.pmf(p, n, i as u32)) * f64::from(k);
            assert!(
                (f64::from(c) - expected).abs() <= 4.0 * expected.sqrt() + 2.0,
                "light {i}: {c} picks, expected {expected}"
            );
        }
        // Nearer lights are likelier.
        let near = tree.pmf(p, n, 72); // (2, 3, 7)
        let far = tree.pmf(p, n, 9); // (9, 3, 0)
        assert!(near > 4.0 * far, "{near} vs {far}");
    }

    #[test]
    fn one_sided_surfaces_behind_get_nothing_and_beams_only_their_cone() {
        let tri = [
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(1.0, 2.0, 0.0),
            Vec3::new(0.0, 2.0, 1.0),
        ];
        let down = LightBounds::surface(&tri, 1.0, Vec3::NEG_Y, false);
        assert!(down.importance(Vec3::new(0.3, 0.0, 0.3), Vec3::Y) > 0.0);
        assert_eq!(down.importance(Vec3::new(0.3, 4.0, 0.3), Vec3::Y), 0.0);
        // Two-sided: both.
        let both = LightBounds::surface(&tri, 1.0, Vec3::NEG_Y, true);
        assert!(both.importance(Vec3::new(0.3, 4.0, 0.3), Vec3::Y) > 0.0);
        let spot = LightBounds::beam(Vec3::ZERO, 1.0, Vec3::NEG_Y, 0.5);
        assert!(spot.importance(Vec3::new(0.0, -3.0, 1.0), Vec3::Y) > 0.0);
        assert_eq!(spot.importance(Vec3::new(0.0, -1.0, 3.0), Vec3::Y), 0.0);
        // A node holding both keeps both reachable.
        let tree = LightTree::new(&[down, spot]);
        assert!(tree.pmf(Vec3::new(0.3, 0.0, 0.3), Vec3::Y, 0) > 0.0);
        assert!(tree.pmf(Vec3::new(0.0, -3.0, 1.0), Vec3::Y, 1) > 0.0);
        assert_eq!(tree.pmf(Vec3::new(0.0, -1.0, 3.0), Vec3::Y, 1), 0.0);
    }

    #[test]
    fn cone_unions_hold_both_cones() {
        let mut rng = crate::sampling::SampleRng::new(7, 0);
        for _ in 0..2000 {
            let a = crate::sampling::uniform_sphere(rng.next_f32(), rng.next_f32());
            let b = crate::sampling::uniform_sphere(rng.next_f32(), rng.next_f32());
            let (ta, tb) = (rng.next_f32() * 1.5, rng.next_f32() * 1.5);
            let (axis, theta) = cone_union(a, ta, b, tb);
            let angle = |x: Vec3, y: Vec3| x.dot(y).clamp(-1.0, 1.0).acos();
            assert!(
                angle(axis, a) + ta <= theta + 1e-3,
                "{a} {ta} {b} {tb} -> {axis} {theta}"
            );
            assert!(
                angle(axis, b) + tb <= theta + 1e-3,
                "{a} {ta} {b} {tb} -> {axis} {theta}"
            );
        }
    }

    #[test]
    fn wide_lanes_give_the_scalar_importance() {
        // Points, beams and surfaces, one-sided and two-sided, at receivers outside and inside
        // the bounds, with and without a normal.
        let mut rng = crate::sampling::SampleRng::new(11, 0);
        let mut lights = Vec::new();
        for k in 0..60 {
            let p = Vec3::new(
                rng.next_f32() * 8.0,
                2.0 + rng.next_f32(),
                rng.next_f32() * 8.0,
            );
            let dir = crate::sampling::uniform_sphere(rng.next_f32(), rng.next_f32());
            lights.push(match k % 4 {
                0 => LightBounds::point(p, 1.0 + rng.next_f32()),
                1 => LightBounds::beam(p, 2.0, dir, 0.2 + rng.next_f32()),
                n => {
                    let tri = [p, p + Vec3::X * 0.5, p + Vec3::Z * 0.5];
                    LightBounds::surface(&tri, 0.5, dir, n == 3)
                }
            });
        }
        let tree = LightTree::new(&lights);
        let packed: Vec<Packed> = lights.iter().map(Packed::new).collect();
        for _ in 0..500 {
            let p = Vec3::new(
                rng.next_f32() * 9.0,
                rng.next_f32() * 3.0,
                rng.next_f32() * 9.0,
            );
            let n = if rng.next_f32() < 0.2 {
                Vec3::ZERO
            } else {
                crate::sampling::uniform_sphere(rng.next_f32(), rng.next_f32())
            };
            for (node, w) in tree.wide.iter().enumerate() {
                let imp = w.importances::<Scalar8>(p, n).to_array();
                for (lane, &got) in imp.iter().enumerate() {
                    if let wide::Child::Light(l) = w.child(lane) {
                        let want = packed[l as usize].importance(p, n);
                        assert!(
                            (got - want).abs() <= 1e-5 * want.max(1e-12),
                            "node {node} lane {lane} light {l}: {got} vs {want}"
                        );
                    }
                }
            }
        }
        // Every light sits in exactly one lane, and the pmfs still add up to one.
        let placed = tree.leaf_of.iter().filter(|l| l.is_some()).count();
        assert_eq!(placed, lights.len());
        let p = Vec3::new(4.0, 0.0, 4.0);
        let total: f32 = (0..lights.len() as u32)
            .map(|i| tree.pmf(p, Vec3::Y, i))
            .sum();
        assert!((total - 1.0).abs() < 1e-4, "{total}");
    }

    #[test]
    fn lights_without_power_are_never_picked() {
        let mut lights = grid(3);
        lights[4].power = 0.0;
        let tree = LightTree::new(&lights);
        assert_eq!(tree.pmf(Vec3::ZERO, Vec3::Y, 4), 0.0);
        assert!(
            LightTree::new(&[])
                .sample(Vec3::ZERO, Vec3::Y, 0.5)
                .is_none()
        );
    }
}
