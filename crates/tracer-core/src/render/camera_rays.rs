//! The camera rays of a batch of samples, eight at a time: the sample positions per sample
//! (each pixel's sequence shift hashed once for its run of samples), the directions in vector
//! lanes (AVX where the CPU has AVX2, chosen at run time). Per ray the
//! operations and their order are [`CameraBasis::ray`]'s, so the rays are the same bit for
//! bit (the wavefront test compares whole samples with single ones).

use super::sampler::{MAX_OFFSET, R2_STEP, SampleJob, pixel_shift, sample_offset};
use crate::geometry::Ray;
#[cfg(target_arch = "x86_64")]
use crate::lanes8::Avx8;
use crate::lanes8::{Lanes8, Scalar8};
use crate::scene::{CameraBasis, Lens};
use glam::Vec3;

/// Chunks of eight per block of [`lane_rays`]' two passes (a batch's worth).
const BLOCK_CHUNKS: usize = 32;

/// 0, 1, ..., 7.
const LANE_INDEX: [f32; 8] = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0];

/// The first job of `chunk` when it is eight consecutive samples of one pixel.
#[inline(always)]
fn one_pixel_run(chunk: &[SampleJob]) -> Option<SampleJob> {
    let first = *chunk.first()?;
    let run = chunk.len() == 8
        && first.s <= u32::MAX - 7
        && chunk
            .iter()
            .zip(first.s..)
            .all(|(j, s)| j.x == first.x && j.y == first.y && j.s == s);
    run.then_some(first)
}

/// The camera ray of each of `jobs`, into `rays` (cleared first; the batch traces the rays
/// from that slice as they are). Film positions outside the image (a fisheye's corners) get a
/// stand-in ray that hits nothing, and their indices go to `outside` (cleared first).
pub(super) fn camera_rays(
    basis: &CameraBasis,
    jobs: &[SampleJob],
    rays: &mut Vec<Ray>,
    outside: &mut Vec<u32>,
) {
    rays.clear();
    outside.clear();
    if !matches!(basis.lens, Lens::Pinhole) {
        // The other projections one ray at a time (their directions need trigonometry, and
        // the wavefront's cost is in the tracing).
        let width = basis.width;
        for (i, job) in jobs.iter().enumerate() {
            let (dx, dy) = super::pixel_sample_offset(job.x, job.y, width, job.s);
            rays.push(
                basis
                    .ray(job.x as f32 + dx, job.y as f32 + dy)
                    .unwrap_or_else(|| {
                        outside.push(i as u32);
                        Ray {
                            t_max: 0.0,
                            ..Ray::new(basis.origin, basis.forward)
                        }
                    }),
            );
        }
        return;
    }
    #[cfg(target_arch = "x86_64")]
    if is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2, the only feature `rays_avx2` is compiled for.
        unsafe { lane_rays_avx2(basis, jobs, rays) };
        return;
    }
    lane_rays::<Scalar8>(basis, jobs, rays);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn lane_rays_avx2(basis: &CameraBasis, jobs: &[SampleJob], rays: &mut Vec<Ray>) {
    lane_rays::<Avx8>(basis, jobs, rays);
}

/// (Loops and straight-line lane calls only: a closure would not inherit the AVX feature.)
#[inline(always)]
fn lane_rays<L: Lanes8>(basis: &CameraBasis, jobs: &[SampleJob], rays: &mut Vec<Ray>) {
    let width = basis.width;
    let mut shift_of = (u32::MAX, u32::MAX);
    let mut shift = (0.0, 0.0);
    let (one, two) = (L::splat(1.0), L::splat(2.0));
    let (w, h) = (L::splat(width as f32), L::splat(basis.height as f32));
    let (hw, hh) = (L::splat(basis.half_width), L::splat(basis.half_height));
    let (f, r, u) = (basis.forward, basis.right, basis.up);
    let (max_offset, centre) = (L::splat(MAX_OFFSET), L::splat(0.5));
    // Lanes 1..8 (lane 0 of a run starting at sample 0 is the pixel's centre).
    let after_first = L::from_array(LANE_INDEX).gt(L::splat(0.0));
    // Two passes per block: the film positions, then the directions. The second pass is
    // short and branch-free, so the CPU overlaps one chunk's divisions and square root with
    // the next chunk's instead of waiting on each chain.
    let mut positions = [([0.0f32; 8], [0.0f32; 8]); BLOCK_CHUNKS];
    for block in jobs.chunks(8 * BLOCK_CHUNKS) {
        for (chunk, position) in block.chunks(8).zip(positions.iter_mut()) {
            *position = if let Some(job) = one_pixel_run(chunk) {
                // Eight consecutive samples of one pixel (the common case): the offsets in
                // lanes.
                if shift_of != (job.x, job.y) {
                    shift_of = (job.x, job.y);
                    shift = pixel_shift(job.x, job.y, width);
                }
                let mut dx = L::fract_steps(shift.0, job.s, R2_STEP.0).min_or(max_offset);
                let mut dy = L::fract_steps(shift.1, job.s, R2_STEP.1).min_or(max_offset);
                if job.s == 0 {
                    dx = L::select(after_first, dx, centre);
                    dy = L::select(after_first, dy, centre);
                }
                (
                    L::splat(job.x as f32).add(dx).to_array(),
                    L::splat(job.y as f32).add(dy).to_array(),
                )
            } else {
                let mut fx = [0.0f32; 8];
                let mut fy = [0.0f32; 8];
                for (i, job) in chunk.iter().enumerate() {
                    if shift_of != (job.x, job.y) {
                        shift_of = (job.x, job.y);
                        shift = pixel_shift(job.x, job.y, width);
                    }
                    let (dx, dy) = sample_offset(shift, job.s);
                    fx[i] = job.x as f32 + dx;
                    fy[i] = job.y as f32 + dy;
                }
                (fx, fy)
            };
        }
        for (chunk, (fx, fy)) in block.chunks(8).zip(&positions) {
            let (fx, fy) = (L::from_array(*fx), L::from_array(*fy));
            // CameraBasis::ray: screen position, then forward + right sx + up sy, normalised.
            let sx = two.mul(fx).div(w).sub(one).mul(hw);
            let sy = one.sub(two.mul(fy).div(h)).mul(hh);
            let dx = L::splat(f.x)
                .add(L::splat(r.x).mul(sx))
                .add(L::splat(u.x).mul(sy));
            let dy = L::splat(f.y)
                .add(L::splat(r.y).mul(sx))
                .add(L::splat(u.y).mul(sy));
            let dz = L::splat(f.z)
                .add(L::splat(r.z).mul(sx))
                .add(L::splat(u.z).mul(sy));
            let length = dx.mul(dx).add(dy.mul(dy)).add(dz.mul(dz)).sqrt();
            let scale = one.div(length);
            // One ray per lane, written whole: origin, direction and `Ray::new`'s interval.
            let o = basis.origin;
            let columns = L::transpose([
                L::splat(o.x),
                L::splat(o.y),
                L::splat(o.z),
                dx.mul(scale),
                dy.mul(scale),
                dz.mul(scale),
                L::splat(0.0),
                L::splat(f32::INFINITY),
            ]);
            // (Extended from sized iterators: no capacity check per ray.)
            rays.extend(columns[..chunk.len()].iter().map(|column| {
                let [ox, oy, oz, x, y, z, t_min, t_max] = column.to_array();
                Ray {
                    origin: Vec3::new(ox, oy, oz),
                    dir: Vec3::new(x, y, z),
                    t_min,
                    t_max,
                }
            }));
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use crate::scene::{Camera, Handedness};

    #[test]
    fn both_lane_kinds_give_the_rays_of_camera_basis_bit_for_bit() {
        let camera = Camera {
            position: [0.3, 1.7, 4.0],
            look_at: [-0.2, 0.4, -1.0],
            up: [0.1, 1.0, 0.0],
            fov_deg: 53.0,
            ..Camera::default()
        };
        let basis = camera.basis(Handedness::Left, 317, 211);
        let runs = |jobs: &[SampleJob]| {
            jobs.chunks(8)
                .filter(|c| one_pixel_run(c).is_some())
                .count()
        };
        let mut jobs: Vec<SampleJob> = (0..3000u32)
            .map(|i| SampleJob {
                x: (i * 7) % 317,
                y: (i / 5) % 211,
                s: i % 37,
            })
            .collect();
        // Runs of consecutive samples of one pixel (the lanes' own offsets), from sample 0
        // and from later ones, with chunks of eight falling at every alignment.
        for (k, first) in [0u32, 0, 3, 8, 1000, 0, 17].into_iter().enumerate() {
            let (x, y) = (29 * k as u32 % 317, 13 * k as u32 % 211);
            jobs.extend((first..first + 8 + 5 * k as u32).map(|s| SampleJob { x, y, s }));
        }
        let expected: Vec<Ray> = jobs
            .iter()
            .map(|j| {
                let (dx, dy) = super::super::pixel_sample_offset(j.x, j.y, 317, j.s);
                basis.ray(j.x as f32 + dx, j.y as f32 + dy).unwrap()
            })
            .collect();
        assert!(runs(&jobs) >= 5, "the runs reach the lanes' path");
        let mut kinds: Vec<Vec<Ray>> = Vec::new();
        let mut rays = Vec::new();
        lane_rays::<Scalar8>(&basis, &jobs, &mut rays);
        kinds.push(rays);
        let mut rays = Vec::new();
        camera_rays(&basis, &jobs, &mut rays, &mut Vec::new());
        kinds.push(rays);
        for rays in kinds {
            assert_eq!(rays.len(), jobs.len());
            for (k, (ray, want)) in rays.iter().zip(&expected).enumerate() {
                assert_eq!(
                    ray.dir.to_array().map(f32::to_bits),
                    want.dir.to_array().map(f32::to_bits),
                    "job {k}"
                );
                assert_eq!(ray.origin, want.origin);
            }
        }
    }
}
