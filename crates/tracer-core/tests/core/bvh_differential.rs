//! The BVH against brute force over every triangle, on generated and shared meshes.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::bvh_support::{Rng, bounds_of, shared_meshes};
use glam::Vec3;
use rayon::prelude::*;
use tracer_core::bvh::{
    Bvh, Hit, Kernel, PACKET, intersect_brute_force, occluded_brute_force, uv_sphere,
};
use tracer_core::{Aabb, Ray};

/// Random rays for `triangles`: from inside an enlarged box and from far outside towards points
/// in the box, some with a finite `[t_min, t_max]`, some aimed at vertices and edge midpoints.
fn random_rays(triangles: &[[Vec3; 3]], n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Rng::new(seed);
    let b = bounds_of(triangles);
    let (b, c) = if b.is_empty() {
        (
            Aabb {
                min: Vec3::splat(-1.0),
                max: Vec3::ONE,
            },
            Vec3::ZERO,
        )
    } else {
        // Give flat scenes some thickness so rays come from both sides.
        let pad = Vec3::splat(b.radius() * 0.05 + 1e-3);
        (
            Aabb {
                min: b.min - pad,
                max: b.max + pad,
            },
            b.center(),
        )
    };
    let r = b.radius();
    let enlarged = Aabb {
        min: c - (b.max - b.min) * 0.75,
        max: c + (b.max - b.min) * 0.75,
    };
    (0..n)
        .map(|k| {
            let target = if k % 4 == 3 && !triangles.is_empty() {
                let t = triangles[rng.below(triangles.len())];
                let (i, j) = (rng.below(3), rng.below(3));
                (t[i] + t[j]) * 0.5 // a vertex when i == j, else an edge midpoint
            } else {
                rng.in_box(&b)
            };
            let origin = if k % 2 == 0 {
                rng.in_box(&enlarged)
            } else {
                c + rng.unit_vector() * (3.0 * r)
            };
            let mut ray = Ray::new(origin, target - origin);
            if k % 5 == 1 {
                ray.t_max = 1.2 * rng.f32();
                ray.t_min = ray.t_max * 0.5 * rng.f32();
            }
            ray
        })
        .collect()
}

/// Every traversal returns the least (t, triangle index) of the triangles hit, as brute force
/// does (boxes near the best hit are opened with a margin so ties are never skipped): the same
/// hit, bit for bit, even at shared edges and vertices.
fn same_hit(a: Option<Hit>, b: Option<Hit>) -> bool {
    a == b
}

fn with_kernel(bvh: &Bvh, kernel: Kernel) -> Bvh {
    let mut bvh = bvh.clone();
    bvh.set_kernel(kernel);
    bvh
}

/// Packets of `rays` (eight at a time, and three at a time for partly filled packets) give
/// every ray's single-ray answers bit for bit, with both node tests.
fn check_packets(name: &str, bvh: &Bvh, rays: &[Ray]) {
    for kernel in [Kernel::Auto, Kernel::Portable] {
        let bvh = with_kernel(bvh, kernel);
        for size in [PACKET, 3] {
            for chunk in rays.chunks(size) {
                let mut hits = vec![None; chunk.len()];
                bvh.intersect_packet(chunk, &mut hits);
                let mut blocked = vec![false; chunk.len()];
                bvh.occluded_packet(chunk, &mut blocked);
                for (k, ray) in chunk.iter().enumerate() {
                    assert_eq!(hits[k], bvh.intersect(ray), "{name} {kernel:?}: {ray:?}");
                    assert_eq!(blocked[k], bvh.occluded(ray), "{name} {kernel:?}: {ray:?}");
                }
            }
        }
    }
}

/// Bundles of eight rays like a pixel's camera samples: one origin, directions a little
/// apart, towards random points of the box (some bundles with a finite `t_max`, some looking
/// away from it).
fn coherent_rays(triangles: &[[Vec3; 3]], bundles: usize, seed: u64) -> Vec<Ray> {
    let b = bounds_of(triangles);
    if b.is_empty() {
        return Vec::new();
    }
    let size = b.extent().length().max(1e-3);
    let centre = b.min + b.extent() * 0.5;
    let mut rng = Rng::new(seed);
    let mut rays = Vec::new();
    for k in 0..bundles {
        let origin = centre + rng.unit_vector() * size * (0.6 + 2.0 * rng.f32());
        // Some bundles look away from the scene (packets that end at the root).
        let target = if k % 7 == 3 {
            origin + (origin - centre)
        } else {
            rng.in_box(&b)
        };
        let spread = size * 1e-3 * rng.f32();
        for _ in 0..PACKET {
            let aim = target + rng.unit_vector() * spread;
            let mut ray = Ray::new(origin, (aim - origin).normalize());
            if k % 5 == 0 {
                ray.t_max = (aim - origin).length() * rng.f32();
            }
            rays.push(ray);
        }
    }
    rays
}

/// Bundles of eight rays from different origins, like shadow rays from a pixel's hits to one
/// light: origins spread over a patch (from tiny to a third of the scene), towards one point
/// (ending just short of it, or some from `t_min` above zero) or all in one direction.
fn converging_rays(triangles: &[[Vec3; 3]], bundles: usize, seed: u64) -> Vec<Ray> {
    let b = bounds_of(triangles);
    if b.is_empty() {
        return Vec::new();
    }
    let size = b.extent().length().max(1e-3);
    let mut rng = Rng::new(seed);
    let mut rays = Vec::new();
    for k in 0..bundles {
        let centre = rng.in_box(&b);
        let spread = size * [1e-4, 1e-2, 0.3][k % 3] * rng.f32();
        let light = centre + rng.unit_vector() * size * (0.2 + rng.f32());
        let direction = rng.unit_vector();
        for _ in 0..PACKET {
            let origin = centre + rng.unit_vector() * spread;
            let mut ray = if k % 2 == 0 {
                let to_light = light - origin;
                let mut ray = Ray::new(origin, to_light.normalize());
                ray.t_max = to_light.length() * (1.0 - 1e-4);
                ray
            } else {
                Ray::new(origin, direction)
            };
            if k % 4 == 1 {
                ray.t_min = size * 1e-3 * rng.f32();
            }
            rays.push(ray);
        }
    }
    rays
}

/// Builds, validates and compares `intersect` and `occluded` with brute force on `n` rays.
/// Returns how many rays hit.
fn check(name: &str, triangles: &[[Vec3; 3]], n: usize) -> usize {
    let rays = random_rays(triangles, n, 0x5EED ^ triangles.len() as u64);
    check_rays(name, triangles, &rays)
}

/// [`check`] on the given rays.
fn check_rays(name: &str, triangles: &[[Vec3; 3]], rays: &[Ray]) -> usize {
    let n = rays.len();
    let bvh = Bvh::build(triangles);
    bvh.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(bvh.triangle_count(), triangles.len());
    let results: Vec<(Option<Hit>, Option<bool>)> = rays
        .par_iter()
        .enumerate()
        .map(|(k, ray)| {
            let any = (k % 8 == 0).then(|| occluded_brute_force(triangles, ray));
            (intersect_brute_force(triangles, ray), any)
        })
        .collect();
    let portable = with_kernel(&bvh, Kernel::Portable);
    check_packets(name, &bvh, rays);
    check_packets(name, &bvh, &coherent_rays(triangles, n / 16 + 1, n as u64));
    check_packets(
        name,
        &bvh,
        &converging_rays(triangles, n / 16 + 1, n as u64),
    );
    let mut hits = 0;
    for (ray, (expected, any)) in rays.iter().zip(results) {
        let got = bvh.intersect(ray);
        assert!(
            same_hit(got, expected),
            "{name}: {ray:?}: bvh {got:?}, brute force {expected:?}"
        );
        assert_eq!(
            bvh.occluded(ray),
            expected.is_some(),
            "{name}: occluded {ray:?}"
        );
        // Every node test finds the same hit, whatever order it opens boxes in.
        let other = portable.intersect(ray);
        assert!(same_hit(other, got), "{name}: portable {other:?} {ray:?}");
        assert_eq!(portable.occluded(ray), got.is_some(), "{name}: {ray:?}");
        if let Some(any) = any {
            assert_eq!(
                any,
                expected.is_some(),
                "{name}: occluded_brute_force {ray:?}"
            );
        }
        hits += usize::from(expected.is_some());
    }
    println!(
        "{name}: {} triangles, {n} rays, {hits} hits, {} nodes",
        triangles.len(),
        bvh.node_count()
    );
    assert!(
        triangles.is_empty() || hits > 0,
        "{name}: no ray hit anything"
    );
    hits
}

/// Cheap checks on many more rays: `occluded` agrees with `intersect`, and the reported
/// triangle alone gives the same hit.
fn self_consistent(name: &str, triangles: &[[Vec3; 3]], n: usize) {
    let bvh = Bvh::build(triangles);
    for ray in random_rays(triangles, n, 99) {
        let hit = bvh.intersect(&ray);
        assert_eq!(bvh.occluded(&ray), hit.is_some(), "{name}: {ray:?}");
        if let Some(hit) = hit {
            let alone = intersect_brute_force(&triangles[hit.prim as usize..][..1], &ray);
            assert_eq!(
                alone.map(|h| (h.t, h.u, h.v)),
                Some((hit.t, hit.u, hit.v)),
                "{name}"
            );
        }
    }
}

#[test]
fn spheres_match_brute_force() {
    check("sphere 64", &uv_sphere(64), 20_000);
    check("sphere 200", &uv_sphere(200), 10_000);
}

#[test]
fn random_soup_matches_brute_force() {
    let mut rng = Rng::new(7);
    let soup: Vec<[Vec3; 3]> = (0..5000)
        .map(|_| {
            let c = Vec3::new(rng.f32(), rng.f32(), rng.f32()) * 10.0;
            let s = 0.05 + rng.f32();
            [
                c + rng.unit_vector() * s,
                c + rng.unit_vector() * s,
                c + rng.unit_vector() * s,
            ]
        })
        .collect();
    check("soup", &soup, 20_000);
}

#[test]
fn degenerate_scenes_match_brute_force() {
    assert_eq!(check("empty", &[], 200), 0);
    check("one", &[[Vec3::ZERO, Vec3::X, Vec3::Y]], 2000);
    let tri = [
        Vec3::new(1.0, 2.0, 3.0),
        Vec3::new(2.0, 2.5, 3.0),
        Vec3::new(1.0, 3.0, 3.5),
    ];
    check("identical", &vec![tri; 1000], 2000);
    // Nested triangles sharing one centroid: binning finds no split.
    let nested: Vec<[Vec3; 3]> = (1..=300)
        .map(|i| tri.map(|v| (v - Vec3::splat(2.0)) * i as f32 * 0.01))
        .collect();
    check("same centroid", &nested, 2000);
    // A flat 60 x 60 grid of quads in the plane y = 0.5.
    let mut plane = Vec::new();
    for i in 0..60 {
        for j in 0..60 {
            let p = |a: i32, b: i32| Vec3::new((i + a) as f32, 0.5, (j + b) as f32);
            plane.push([p(0, 0), p(1, 0), p(1, 1)]);
            plane.push([p(0, 0), p(1, 1), p(0, 1)]);
        }
    }
    check("plane", &plane, 10_000);
    // Zero-area triangles (points and segments) among real ones.
    let mut mixed = uv_sphere(16);
    for k in 0..200 {
        let p = Vec3::splat(k as f32 * 0.01 - 1.0);
        mixed.push([p, p, p]);
        mixed.push([p, p + Vec3::X, p + 2.0 * Vec3::X]);
    }
    check("degenerate triangles", &mixed, 5000);
    // Far from the origin, where absolute rounding is large.
    let far: Vec<[Vec3; 3]> = uv_sphere(32).iter().map(|t| t.map(|v| v + 1e4)).collect();
    check("far sphere", &far, 5000);
}

/// Rays that stress the box test's rounding: direction components exactly zero with the
/// origin exactly on box planes (through vertices of an axis-aligned grid and a sphere), and
/// origins thousands of radii away aimed at vertices and edge midpoints.
#[test]
fn axis_parallel_and_distant_rays_match_brute_force() {
    let mut plane = Vec::new();
    for i in 0..30 {
        for j in 0..30 {
            let p = |a: i32, b: i32| Vec3::new((i + a) as f32 * 0.5, 0.5, (j + b) as f32 * 0.5);
            plane.push([p(0, 0), p(1, 0), p(1, 1)]);
            plane.push([p(0, 0), p(1, 1), p(0, 1)]);
        }
    }
    let sphere: Vec<[Vec3; 3]> = uv_sphere(48)
        .iter()
        .map(|t| t.map(|v| v * 3.0 + Vec3::new(7.0, -2.0, 0.5)))
        .collect();
    let mut rng = Rng::new(21);
    for (name, triangles) in [("grid", plane), ("sphere", sphere)] {
        let b = bounds_of(&triangles);
        let mut rays = Vec::new();
        for _ in 0..4000 {
            let t = triangles[rng.below(triangles.len())];
            let (i, j) = (rng.below(3), rng.below(3));
            let target = (t[i] + t[j]) * 0.5;
            // Along an axis, from outside the bounds, through the point exactly.
            let axis = rng.below(3);
            let sign = if rng.f32() < 0.5 { 1.0 } else { -1.0 };
            let mut dir = Vec3::ZERO;
            dir[axis] = sign;
            let mut origin = target;
            origin[axis] = if sign > 0.0 {
                b.min[axis] - 1.0
            } else {
                b.max[axis] + 1.0
            };
            rays.push(Ray::new(origin, dir));
            // From far away.
            let origin = b.center() + rng.unit_vector() * (5000.0 * b.radius());
            rays.push(Ray::new(origin, target - origin));
        }
        check_rays(&format!("{name} stress rays"), &triangles, &rays);
    }
}

#[test]
fn empty_bvh_reports_nothing() {
    let bvh = Bvh::build(&[]);
    assert_eq!(bvh.validate(), Ok(()));
    assert_eq!((bvh.triangle_count(), bvh.node_count()), (0, 0));
    assert!(bvh.bounds().is_empty());
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    assert_eq!(bvh.intersect(&ray), None);
    assert!(!bvh.occluded(&ray));
}

#[test]
fn shared_meshes_match_brute_force() {
    for (name, triangles) in shared_meshes() {
        // Brute force costs triangles x rays; keep the file within seconds.
        let n = (120_000_000 / triangles.len().max(1)).clamp(1_500, 20_000);
        check(&name, &triangles, n);
        self_consistent(&name, &triangles, 20_000);
    }
}

/// Rays from inside a closed sphere, many through exact vertices and edge midpoints, must all
/// hit (the triangle test is inclusive at edges).
#[test]
fn closed_sphere_does_not_leak() {
    let sphere = uv_sphere(64);
    let built = Bvh::build(&sphere);
    let mut rng = Rng::new(11);
    let mut targets: Vec<Vec3> = sphere
        .iter()
        .flat_map(|t| {
            [
                t[0],
                (t[0] + t[1]) * 0.5,
                (t[1] + t[2]) * 0.5,
                (t[2] + t[0]) * 0.5,
            ]
        })
        .collect();
    targets.extend((0..20_000).map(|_| rng.unit_vector()));
    for kernel in [Kernel::Auto, Kernel::Portable] {
        let bvh = with_kernel(&built, kernel);
        for origin in [Vec3::ZERO, Vec3::new(0.1, -0.2, 0.3)] {
            for &target in &targets {
                let ray = Ray::new(origin, target - origin);
                let hit = bvh.intersect(&ray);
                assert!(hit.is_some() && bvh.occluded(&ray), "leak: {ray:?}");
                let p = ray.at(hit.unwrap().t);
                assert!((p.length() - 1.0).abs() < 5e-3, "hit off the sphere at {p}");
            }
        }
    }
}

#[test]
fn hit_reports_original_index_and_barycentrics() {
    let tris = uv_sphere(32);
    let bvh = Bvh::build(&tris);
    let mut rng = Rng::new(3);
    for _ in 0..2000 {
        let ray = Ray::new(
            rng.unit_vector() * 3.0,
            -rng.unit_vector() * 0.2 - Vec3::ZERO,
        );
        let ray = Ray::new(ray.origin, -ray.origin + ray.dir);
        let Some(hit) = bvh.intersect(&ray) else {
            continue;
        };
        let [a, b, c] = tris[hit.prim as usize];
        let p = a + (b - a) * hit.u + (c - a) * hit.v;
        assert!((p - ray.at(hit.t)).length() < 1e-5, "{hit:?}");
    }
}
