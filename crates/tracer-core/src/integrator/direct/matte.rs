//! First hits on matte surfaces, shaded eight at a time: one AVX register per quantity where
//! the CPU has AVX2 (picked at run time), plain arrays elsewhere.
//!
//! Most camera samples of a lighting scene end at their first hit: a surface that neither
//! glows, nor has a highlight, nor mirrors, lit by point-like lights. For those, the walk's
//! steps (the frame at the hit, each light's illuminance, the shadow rays, the sums) are done
//! here in lanes. Per lane the operations and their order are those of [`Surface::at`],
//! [`LitScene::light_at`] and the walk's `direct_light`, without fused multiply-adds, so the
//! samples equal the walk's bit for bit on every CPU. The other samples take the walk, and so
//! does every sample when emissive triangles are lights (their samples draw random numbers).
//!
//! [`Surface::at`]: crate::shading::Surface::at

// Lane loops index arrays by lane on purpose.
#![allow(clippy::needless_range_loop)]

use super::super::Sample;
use super::walk::Contribution;
use crate::bvh::Hit;
use crate::geometry::Ray;
#[cfg(target_arch = "x86_64")]
use crate::lanes8::Avx8;
use crate::lanes8::{Lanes8, Mask8, Scalar8, ray_columns};
use crate::light::PlacedLight;
use crate::lit_scene::LitScene;
use crate::shading::PreparedMaterial;
use glam::Vec3;

/// Which lanes shade the first hits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Lanes {
    /// AVX where the CPU has AVX2, arrays elsewhere: what renders use.
    Native,
    /// Plain arrays (tests compare them with the native lanes).
    #[cfg_attr(not(test), allow(dead_code))]
    Scalar,
    /// None: every sample takes the walk (tests compare it with the lanes).
    #[cfg_attr(not(test), allow(dead_code))]
    Off,
}

/// Working memory of [`shade_first_hits`], kept between batches.
#[derive(Debug, Default)]
pub(super) struct MatteScratch {
    /// Per material slot: whether a first hit there ends with its direct light.
    matte: Vec<bool>,
    shadows: Vec<Ray>,
    contributions: Vec<Contribution>,
    /// The sample each shadow ray belongs to.
    owners: Vec<u32>,
    blocked: Vec<bool>,
    /// What thin panes let through on each shadow ray (1 without panes).
    through: Vec<f32>,
}

/// Whether a first hit on `mat` takes the lanes: no emission to add, no highlight (it needs
/// the view direction and `powf`), no mirror ray after it. Each test is the walk's own.
fn is_matte(mat: &PreparedMaterial, max_depth: u32) -> bool {
    let glows = mat.emission.max_element() > 0.0;
    let glossy = mat.glossiness > 0.0;
    // The walk ends at depth 0 or where `ks.max_element() <= 0.0` (not for NaN).
    let ends = mat.ks.max_element() <= 0.0;
    let mirrors = max_depth > 0 && !ends;
    !glows && !glossy && !mirrors && mat.pbr.is_none() && mat.pane.is_none()
}

/// Shades the first hits `hits` of the camera rays `rays` where the sample ends (misses, and
/// hits on matte surfaces) and writes those samples to `out`. The indices of the other
/// samples go to `rest`, in order: they take the walk.
pub(super) fn shade_first_hits(
    lit: &LitScene<'_>,
    rays: &[Ray],
    hits: &[Option<Hit>],
    lanes: Lanes,
    scratch: &mut MatteScratch,
    out: &mut [Sample],
    rest: &mut Vec<u32>,
) {
    debug_assert!(rays.len() == hits.len() && rays.len() == out.len());
    if lanes == Lanes::Off
        || !lit.emitters.is_empty()
        || lit.environment.is_some()
        || !lit.lights.iter().all(PlacedLight::is_point)
    {
        rest.extend(0..rays.len() as u32);
        return;
    }
    scratch.matte.clear();
    let max_depth = lit.max_depth;
    scratch
        .matte
        .extend(lit.materials.iter().enumerate().map(|(slot, m)| {
            // Textured slots take the walk, which reads their texture coordinates.
            is_matte(m, max_depth) && !lit.is_textured(slot)
        }));
    if !scratch.matte.contains(&true) {
        // Every surface mirrors, glows or shines (a hall of mirrors): all walk.
        rest.extend(0..rays.len() as u32);
        return;
    }
    scratch.shadows.clear();
    scratch.contributions.clear();
    scratch.owners.clear();
    let mut done = false;
    #[cfg(target_arch = "x86_64")]
    if lanes == Lanes::Native && is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2, the only feature `shade_avx2` is compiled for.
        unsafe { shade_avx2(lit, rays, hits, scratch, out, rest) };
        done = true;
    }
    if !done {
        shade::<Scalar8>(lit, rays, hits, scratch, out, rest);
    }
    // Every lane's shadow rays at once; then each light's share where its ray was free, per
    // sample in the order the lights were visited (as the walk adds them).
    scratch.blocked.clear();
    scratch.blocked.resize(scratch.shadows.len(), false);
    lit.shadow_pass_many(&scratch.shadows, &mut scratch.blocked, &mut scratch.through);
    let entries = scratch.contributions.iter().zip(&scratch.owners);
    let passes = scratch.blocked.iter().zip(&scratch.through);
    for ((c, &owner), (&blocked, &through)) in entries.zip(passes) {
        let sample = &mut out[owner as usize];
        sample.rays += 1;
        if !blocked {
            sample.illuminance_lx += c.illuminance_lx * through;
            sample.rgb += c.rgb * through;
        }
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn shade_avx2(
    lit: &LitScene<'_>,
    rays: &[Ray],
    hits: &[Option<Hit>],
    scratch: &mut MatteScratch,
    out: &mut [Sample],
    rest: &mut Vec<u32>,
) {
    shade::<Avx8>(lit, rays, hits, scratch, out, rest);
}

/// Three lanes: x, y, z.
type V3<L> = [L; 3];

#[inline(always)]
fn dot<L: Lanes8>(a: &V3<L>, b: &V3<L>) -> L {
    a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]))
}

#[inline(always)]
fn add<L: Lanes8>(a: &V3<L>, b: &V3<L>) -> V3<L> {
    [a[0].add(b[0]), a[1].add(b[1]), a[2].add(b[2])]
}

#[inline(always)]
fn sub<L: Lanes8>(a: &V3<L>, b: &V3<L>) -> V3<L> {
    [a[0].sub(b[0]), a[1].sub(b[1]), a[2].sub(b[2])]
}

/// `a` times the lanes `s`, per component (glam's `Vec3 * f32`).
#[inline(always)]
fn scale<L: Lanes8>(a: &V3<L>, s: L) -> V3<L> {
    [a[0].mul(s), a[1].mul(s), a[2].mul(s)]
}

/// `a w + b u + c v`, added in that order (barycentric interpolation).
#[inline(always)]
fn blend<L: Lanes8>(a: &V3<L>, b: &V3<L>, c: &V3<L>, w: L, u: L, v: L) -> V3<L> {
    add(&add(&scale(a, w), &scale(b, u)), &scale(c, v))
}

#[inline(always)]
fn select<L: Lanes8>(m: L::Mask, a: &V3<L>, b: &V3<L>) -> V3<L> {
    [
        L::select(m, a[0], b[0]),
        L::select(m, a[1], b[1]),
        L::select(m, a[2], b[2]),
    ]
}

#[inline(always)]
fn splat<L: Lanes8>(v: Vec3) -> V3<L> {
    [L::splat(v.x), L::splat(v.y), L::splat(v.z)]
}

#[inline(always)]
fn to_arrays<L: Lanes8>(a: &V3<L>) -> [[f32; 8]; 3] {
    [a[0].to_array(), a[1].to_array(), a[2].to_array()]
}

/// Lane `j` of each component from `get(j)` (plain loads only, so the closure needs no AVX).
#[inline(always)]
fn gather<L: Lanes8>(get: impl Fn(usize) -> Vec3) -> V3<L> {
    let mut c = [[0.0f32; 8]; 3];
    for j in 0..8 {
        let v = get(j);
        c[0][j] = v.x;
        c[1][j] = v.y;
        c[2][j] = v.z;
    }
    [
        L::from_array(c[0]),
        L::from_array(c[1]),
        L::from_array(c[2]),
    ]
}

/// The lanes of one chunk of up to eight samples whose first hit is shaded here; lanes past
/// them repeat the first one, so every lane reads valid triangles.
struct Chunk {
    /// Bit `j`: lane `j` holds such a sample.
    live: u32,
    /// Sample index, triangle and material slot per lane.
    sample: [usize; 8],
    prim: [usize; 8],
    slot: [usize; 8],
    t: [f32; 8],
    u: [f32; 8],
    v: [f32; 8],
}

/// Picks the lanes of the samples `base ..` (`hits` of one chunk) into `c`: misses are
/// written to `out` and the samples that go on to the walk to `rest`. False when no lane is
/// left.
#[inline(always)]
fn pick(
    lit: &LitScene<'_>,
    matte: &[bool],
    base: usize,
    hits: &[Option<Hit>],
    c: &mut Chunk,
    out: &mut [Sample],
    rest: &mut Vec<u32>,
) -> bool {
    let scene = lit.scene;
    c.live = 0;
    for (j, hit) in hits.iter().enumerate() {
        let i = base + j;
        let Some(hit) = hit else {
            out[i] = Sample {
                rays: 1,
                missed: true,
                ..Sample::default()
            };
            continue;
        };
        let prim = hit.prim as usize;
        let slot = scene.slot(hit.prim) as usize;
        if !matte[slot] {
            rest.push(i as u32);
            continue;
        }
        out[i] = Sample {
            rays: 1,
            ..Sample::default()
        };
        c.live |= 1 << j;
        (c.sample[j], c.prim[j], c.slot[j]) = (i, prim, slot);
        (c.t[j], c.u[j], c.v[j]) = (hit.t, hit.u, hit.v);
    }
    if c.live == 0 {
        return false;
    }
    let first = c.live.trailing_zeros() as usize;
    for j in 0..8 {
        if c.live & (1 << j) == 0 {
            (c.sample[j], c.prim[j], c.slot[j]) = (c.sample[first], c.prim[first], c.slot[first]);
            (c.t[j], c.u[j], c.v[j]) = (c.t[first], c.u[first], c.v[first]);
        }
    }
    true
}

/// The frame at the hits, as [`crate::shading::Surface::at`] computes it per hit.
struct Frame<L> {
    p: V3<L>,
    ns: V3<L>,
    origin: V3<L>,
}

/// (Plain loops and straight-line lane calls: a closure would not inherit the caller's AVX
/// target feature. The closures given to `gather` only load.)
#[inline(always)]
fn shade<L: Lanes8>(
    lit: &LitScene<'_>,
    rays: &[Ray],
    hits: &[Option<Hit>],
    scratch: &mut MatteScratch,
    out: &mut [Sample],
    rest: &mut Vec<u32>,
) {
    let zero = L::splat(0.0);
    let metres_sq = L::splat(lit.metres_per_unit_sq);
    let shadow_t_max = L::splat(LitScene::shadow_ray(Vec3::ZERO, Vec3::X).t_max);
    let mut c = Chunk {
        live: 0,
        sample: [0; 8],
        prim: [0; 8],
        slot: [0; 8],
        t: [0.0; 8],
        u: [0.0; 8],
        v: [0.0; 8],
    };
    for (k, chunk_hits) in hits.chunks(8).enumerate() {
        if !pick(lit, &scratch.matte, k * 8, chunk_hits, &mut c, out, rest) {
            continue;
        }
        let frame = frame::<L>(lit, rays, &c);
        let kd: V3<L> = gather(|j| lit.materials[c.slot[j]].kd_over_pi);
        for light in &lit.lights {
            // LitScene::light_at: E = I cos θ / R², R in metres.
            let pos = splat::<L>(light.position());
            let to_light = sub(&pos, &frame.p);
            let dist2 = dot(&to_light, &to_light);
            let length = dist2.sqrt();
            let wi = [
                to_light[0].div(length),
                to_light[1].div(length),
                to_light[2].div(length),
            ];
            let cos = dot(&frame.ns, &wi);
            // dist2 > 0 (NaN passes, as in `light_at`), cos θ > 0 (also `Surface::lit_from`).
            let mut facing = cos.gt(zero).and_not(dist2.le(zero)).bits() & c.live;
            if facing == 0 {
                continue;
            }
            let intensity = match light.uniform_intensity() {
                Some(i) => L::splat(i),
                None => {
                    let w = to_arrays(&wi);
                    let mut towards = [0.0f32; 8];
                    for j in 0..8 {
                        if facing & (1 << j) != 0 {
                            let dir = -Vec3::new(w[0][j], w[1][j], w[2][j]);
                            towards[j] = light.intensity_towards(dir);
                        }
                    }
                    L::from_array(towards)
                }
            };
            facing &= !intensity.le(zero).bits();
            if facing == 0 {
                continue;
            }
            let e = intensity.mul(cos).div(dist2.mul(metres_sq));
            let tint = splat::<L>(light.tint());
            let to = sub(&pos, &frame.origin);
            // One shadow ray and one contribution per lane, written whole.
            let rays = L::transpose([
                frame.origin[0],
                frame.origin[1],
                frame.origin[2],
                to[0],
                to[1],
                to[2],
                zero,
                shadow_t_max,
            ]);
            let shares = L::transpose([
                e,
                tint[0].mul(e).mul(kd[0]),
                tint[1].mul(e).mul(kd[1]),
                tint[2].mul(e).mul(kd[2]),
                zero,
                zero,
                zero,
                zero,
            ]);
            let mut left = facing;
            while left != 0 {
                let j = left.trailing_zeros() as usize;
                left &= left - 1;
                let [ox, oy, oz, dx, dy, dz, t_min, t_max] = rays[j].to_array();
                scratch.shadows.push(Ray {
                    origin: Vec3::new(ox, oy, oz),
                    dir: Vec3::new(dx, dy, dz),
                    t_min,
                    t_max,
                });
                let [e, r, g, b, ..] = shares[j].to_array();
                scratch.contributions.push(Contribution {
                    illuminance_lx: e,
                    rgb: Vec3::new(r, g, b),
                });
                scratch.owners.push(c.sample[j] as u32);
            }
        }
    }
}

/// The frame at the chunk's hits: the hit point, the geometric normal towards the ray, and
/// on smooth triangles the interpolated normal and the lifted origin (Hanika's terminator
/// fix), each step as `Surface::at` does it.
#[inline(always)]
fn frame<L: Lanes8>(lit: &LitScene<'_>, rays: &[Ray], c: &Chunk) -> Frame<L> {
    let scene = lit.scene;
    let (zero, one) = (L::splat(0.0), L::splat(1.0));
    let [ox, oy, oz, dx, dy, dz, _, _] = ray_columns::<L>(|j| &rays[c.sample[j]]);
    let (o, d) = ([ox, oy, oz], [dx, dy, dz]);
    let p = add(&o, &scale(&d, L::from_array(c.t)));
    let n: V3<L> = gather(|j| scene.normal(c.prim[j] as u32));
    let minus_one = L::splat(-1.0);
    let ng = select(dot(&n, &d).gt(zero), &scale(&n, minus_one), &n);
    let eps = L::splat(lit.epsilon);
    let flat_origin = add(&p, &scale(&ng, eps));
    let flat = Frame {
        p,
        ns: ng,
        origin: flat_origin,
    };
    if !scene.any_smooth() {
        return flat;
    }
    // `Surface::at`'s test: a triangle whose first corner normal is zero is flat (a NaN
    // component differs from zero, as for `Vec3`'s `!=`).
    let corners: [[Vec3; 3]; 8] =
        std::array::from_fn(|j| scene.smooth_corners(c.prim[j] as u32).unwrap_or_default());
    let c0: V3<L> = gather(|j| corners[j][0]);
    let smooth = c0[0].ne(zero).or(c0[1].ne(zero)).or(c0[2].ne(zero));
    if smooth.bits() & c.live == 0 {
        return flat;
    }
    let (u, v) = (L::from_array(c.u), L::from_array(c.v));
    let w = one.sub(u).sub(v);
    let c1: V3<L> = gather(|j| corners[j][1]);
    let c2: V3<L> = gather(|j| corners[j][2]);
    let interpolated = blend(&c0, &c1, &c2, w, u, v);
    // The vertex normals on the side the ray came from.
    let sign = L::select(dot(&interpolated, &ng).lt(zero), minus_one, one);
    let s = scale(&interpolated, sign);
    // `try_normalize`: the reciprocal length, used when finite and positive.
    let rcp = one.div(dot(&s, &s).sqrt());
    let inf = L::splat(f32::INFINITY);
    let normalised = rcp.gt(zero).and(rcp.lt(inf));
    let ns_smooth = select(normalised, &scale(&s, rcp), &ng);
    let vertices: [[Vec3; 3]; 8] = std::array::from_fn(|j| scene.triangle(c.prim[j] as u32));
    let l0 = lift(&p, &c0, sign, &gather(|j| vertices[j][0]));
    let l1 = lift(&p, &c1, sign, &gather(|j| vertices[j][1]));
    let l2 = lift(&p, &c2, sign, &gather(|j| vertices[j][2]));
    let lifted = blend(&l0, &l1, &l2, w, u, v);
    let finite = lifted[0]
        .abs()
        .lt(inf)
        .and(lifted[1].abs().lt(inf))
        .and(lifted[2].abs().lt(inf));
    let lifted = select(finite, &lifted, &p);
    Frame {
        p,
        ns: select(smooth, &ns_smooth, &ng),
        origin: select(smooth, &add(&lifted, &scale(&ng, eps)), &flat_origin),
    }
}

/// Hit point `p` lifted onto the tangent plane of corner `vertex` with normal `normal`
/// (turned by `sign`) when below it: `p - n min((p - v)·n, 0)`.
#[inline(always)]
fn lift<L: Lanes8>(p: &V3<L>, normal: &V3<L>, sign: L, vertex: &V3<L>) -> V3<L> {
    let n = scale(normal, sign);
    let below = dot(&sub(p, vertex), &n).min_or(L::splat(0.0));
    sub(p, &scale(&n, below))
}
