//! The wavefront: a batch of camera samples walks its mirror chains in lockstep, one stage at a
//! time over every walk still going (closest hits, shading, shadow rays, adding up).

use super::super::Sample;
use super::matte::{self, Lanes, MatteScratch};
use super::walk::{Contribution, Walk};
use crate::bvh::Hit;
use crate::geometry::Ray;
use crate::lit_scene::LitScene;
use crate::sampling::SampleRng;

/// Working memory of [`trace_batch`], kept between batches so a render allocates it once per
/// thread.
#[derive(Debug, Default)]
pub struct DirectBatch {
    walks: Vec<Walk>,
    /// Indices of the samples that took the walk (in order), and of the walks still going.
    walked: Vec<u32>,
    active: Vec<u32>,
    /// The active walks' rays, and their closest hits.
    rays: Vec<Ray>,
    hits: Vec<Option<Hit>>,
    shadows: Vec<Ray>,
    contributions: Vec<Contribution>,
    blocked: Vec<bool>,
    /// What thin panes let through on each shadow ray (1 without panes).
    through: Vec<f32>,
    matte: MatteScratch,
}

impl DirectBatch {
    /// The random stream of sample `i` of the last batch as its walk left it; None when the
    /// sample ended at a matte first hit, which draws nothing from its stream.
    pub fn final_rng(&self, i: usize) -> Option<SampleRng> {
        let walked = self.walked.binary_search(&(i as u32)).is_ok();
        walked.then(|| self.walks[i].rng.clone())
    }
}

/// Traces the camera samples `rays` (each with its random stream, `rng_of(i)` for `rays[i]`,
/// asked for only by samples that go past their first hit) and writes what each sees to `out`
/// (as long as `rays`): the same samples, bit for bit, as tracing them one by one.
pub fn trace_batch(
    lit: &LitScene<'_>,
    rays: &[Ray],
    rng_of: impl Fn(usize) -> SampleRng,
    batch: &mut DirectBatch,
    out: &mut [Sample],
) {
    trace_batch_with(lit, rays, rng_of, Lanes::Native, batch, out);
}

/// [`trace_batch`] with the first hits on matte surfaces shaded in `lanes`.
pub(super) fn trace_batch_with(
    lit: &LitScene<'_>,
    rays: &[Ray],
    rng_of: impl Fn(usize) -> SampleRng,
    lanes: Lanes,
    batch: &mut DirectBatch,
    out: &mut [Sample],
) {
    debug_assert!(rays.len() == out.len());
    batch.hits.clear();
    batch.hits.resize(rays.len(), None);
    lit.closest_visible_many(rays, &mut batch.hits);
    // Samples that end at their first hit are done in lanes; the rest walk.
    batch.walked.clear();
    matte::shade_first_hits(
        lit,
        rays,
        &batch.hits,
        lanes,
        &mut batch.matte,
        out,
        &mut batch.walked,
    );
    if batch.walked.is_empty() {
        return;
    }
    // The walks start from their camera rays' hits, moved to the front (indices ascend),
    // unless every sample walks.
    let all_walk = batch.walked.len() == rays.len();
    if !all_walk {
        batch.rays.clear();
        batch
            .rays
            .extend(batch.walked.iter().map(|&i| rays[i as usize]));
        for (k, &i) in batch.walked.iter().enumerate() {
            batch.hits[k] = batch.hits[i as usize];
        }
        batch.hits.truncate(batch.walked.len());
    }
    // Walks are restarted in place, field by field: building each on the stack and copying
    // it in made the CPU read back stores it could not forward (a tenth of a frame).
    batch.walks.truncate(rays.len());
    batch.walks.resize_with(rays.len(), Walk::default);
    for &i in &batch.walked {
        batch.walks[i as usize].restart(rng_of(i as usize));
    }
    batch.active.clone_from(&batch.walked);
    let mut first = true;
    while !batch.active.is_empty() {
        let walks = &mut batch.walks;
        if !first {
            batch.hits.clear();
            batch.hits.resize(batch.rays.len(), None);
            lit.closest_visible_many(&batch.rays, &mut batch.hits);
        }
        let current: &[Ray] = if first && all_walk { rays } else { &batch.rays };
        batch.shadows.clear();
        batch.contributions.clear();
        let steps = batch.active.iter().zip(&batch.hits).zip(current);
        for ((&i, &hit), ray) in steps {
            walks[i as usize].shade(lit, ray, hit, &mut batch.shadows, &mut batch.contributions);
        }
        batch.blocked.clear();
        batch.blocked.resize(batch.shadows.len(), false);
        lit.shadow_pass_many(&batch.shadows, &mut batch.blocked, &mut batch.through);
        batch.active.retain(|&i| {
            let walk = &mut walks[i as usize];
            walk.resolve(&batch.contributions, &batch.blocked, &batch.through);
            walk.advance()
        });
        batch.rays.clear();
        batch
            .rays
            .extend(batch.active.iter().map(|&i| walks[i as usize].next_ray));
        first = false;
    }
    for &i in &batch.walked {
        out[i as usize] = batch.walks[i as usize].sample;
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;
    use crate::light::{Light, Spot};
    use crate::sampling::uniform_sphere;
    use crate::scene::{LengthUnit, Scene, Setup, builtin_cornell_box};
    use glam::Vec3;

    fn bits(s: &Sample) -> ([u32; 3], u32, u32, bool) {
        (
            s.rgb.to_array().map(f32::to_bits),
            s.illuminance_lx.to_bits(),
            s.rays,
            s.missed,
        )
    }

    /// Traces `rays` with the walk alone, with native lanes and with plain-array lanes, in
    /// batches of `size`; checks that all three give the same samples bit for bit and returns
    /// them with the number of samples the lanes finished.
    fn compare(lit: &LitScene<'_>, rays: &[Ray], size: usize) -> (Vec<Sample>, usize) {
        let rngs: Vec<SampleRng> = (0..rays.len() as u64)
            .map(|k| SampleRng::new(k, 3))
            .collect();
        let mut runs = Vec::new();
        let mut in_lanes = 0;
        for lanes in [Lanes::Off, Lanes::Native, Lanes::Scalar] {
            let mut batch = DirectBatch::default();
            let mut all = Vec::new();
            for (r, g) in rays.chunks(size).zip(rngs.chunks(size)) {
                let mut out = vec![Sample::default(); r.len()];
                trace_batch_with(lit, r, |i| g[i].clone(), lanes, &mut batch, &mut out);
                if lanes == Lanes::Native {
                    in_lanes += r.len() - batch.walked.len();
                }
                all.extend(out);
            }
            runs.push(all);
        }
        for (k, run) in runs.iter().enumerate().skip(1) {
            for (i, (want, got)) in runs[0].iter().zip(run).enumerate() {
                assert_eq!(
                    bits(want),
                    bits(got),
                    "lanes {k}, sample {i}: {want:?} {got:?}"
                );
            }
        }
        (runs.swap_remove(0), in_lanes)
    }

    #[test]
    fn matte_lanes_equal_the_walk_in_a_busy_cornell_box() {
        let mut loaded = builtin_cornell_box(None).unwrap();
        let names: Vec<String> = (0..loaded.scene.slots.len() as u32)
            .map(|s| loaded.scene.slot_label(s))
            .collect();
        let slot = |name: &str| names.iter().position(|n| n.contains(name)).unwrap();
        let m = &mut loaded.setup.materials;
        m[slot("tall_block")].ks = [0.8, 0.7, 0.6];
        m[slot("short_block")].glossiness = 20.0;
        m[slot("short_block")].ks = [0.2; 3];
        loaded.setup.hidden = vec![false; names.len()];
        loaded.setup.hidden[slot("green_wall")] = true;
        let first = loaded.setup.lights[0].position;
        loaded.setup.lights.push(Light::spot(
            [first[0] - 150.0, first[1] - 20.0, first[2] + 60.0],
            Spot {
                intensity_cd: 300.0,
                aim: [0.3, -1.0, -0.2],
                cone_deg: 20.0,
                falloff_deg: 35.0,
            },
        ));
        loaded.setup.lights.push(Light {
            color: [1.0, 0.5, 0.2],
            ..Light::point([first[0] + 120.0, first[1] - 200.0, first[2] - 90.0], 40.0)
        });
        let basis = loaded.setup.camera.basis(loaded.setup.handedness, 97, 61);
        let mut rng = SampleRng::new(5, 0);
        let rays: Vec<Ray> = (0..6000)
            .map(|_| {
                let (x, y) = rng.next_2d();
                // Past the film's edges too, so some rays miss through the hidden wall.
                basis.ray(x * 117.0 - 10.0, y * 71.0 - 5.0).unwrap()
            })
            .collect();
        // Without mirror rays (depth 0) the highlight alone sends a hit to the walk.
        for (depth, size) in [(4, 1), (4, 5), (4, 8), (4, 256), (0, 256)] {
            let lit = LitScene::new(&loaded.scene, &loaded.setup, depth);
            let (samples, in_lanes) = compare(&lit, &rays, size);
            // Every branch is taken: lanes, walks (mirror, highlight), misses, shadows.
            assert!(in_lanes > rays.len() / 2, "{in_lanes} in lanes");
            let walked = if depth > 0 { 200 } else { 50 };
            assert!(in_lanes + walked < rays.len(), "{in_lanes} in lanes");
            assert!(samples.iter().any(|s| s.missed));
            let shadowed = samples
                .iter()
                .filter(|s| !s.missed && s.rays == 4 && s.illuminance_lx == 0.0);
            assert!(shadowed.count() > 10, "few samples in every light's shadow");
            assert!(
                samples.iter().any(|s| s.rays == 2),
                "no sample lit by one light"
            );
        }
    }

    #[test]
    fn matte_lanes_equal_the_walk_on_a_smooth_coarse_sphere() {
        let mut scene = Scene::build(crate::test_scenes::sphere(6, 12), "sphere").unwrap();
        assert!(scene.any_smooth());
        // Every third triangle flat (a zero first corner marks it; the others are left, so
        // shading it smooth would show): lanes of one chunk mix flat and smooth frames.
        for corners in scene.own.corner_normals.iter_mut().step_by(3) {
            corners[0] = Vec3::ZERO;
        }
        let mut setup = Setup::defaults(&scene, LengthUnit::M);
        setup.lights = vec![
            Light::point([1.5, 0.4, 0.3], 10.0),
            Light::point([-0.2, -2.0, 0.9], 3.0),
        ];
        let lit = LitScene::new(&scene, &setup, 5);
        let mut rng = SampleRng::new(9, 0);
        let rays: Vec<Ray> = (0..4000)
            .map(|_| {
                let (u, v) = rng.next_2d();
                let dir = uniform_sphere(u, v);
                let (a, b) = rng.next_2d();
                let jitter = Vec3::new(a - 0.5, b - 0.5, a * b - 0.25) * 0.9;
                Ray::new(dir * 3.0, -dir + jitter)
            })
            .collect();
        let (samples, in_lanes) = compare(&lit, &rays, 256);
        assert_eq!(in_lanes, rays.len(), "every sample ends at its first hit");
        assert!(samples.iter().any(|s| s.missed));
        let lit = samples.iter().filter(|s| s.illuminance_lx > 0.0).count();
        assert!(lit > rays.len() / 4, "{lit} lit");
    }

    #[test]
    fn everything_walks_in_a_hall_of_mirrors() {
        let mut loaded = builtin_cornell_box(None).unwrap();
        for m in &mut loaded.setup.materials {
            m.ks = [0.4; 3];
        }
        let lit = LitScene::new(&loaded.scene, &loaded.setup, 5);
        let basis = loaded.setup.camera.basis(loaded.setup.handedness, 40, 30);
        let rays: Vec<Ray> = (0..1200)
            .map(|i| basis.ray((i % 40) as f32, (i / 40) as f32).unwrap())
            .collect();
        let (samples, in_lanes) = compare(&lit, &rays, 256);
        assert_eq!(in_lanes, 0);
        assert!(samples.iter().any(|s| s.rays > 6), "no mirror chain");
    }

    #[test]
    fn everything_walks_when_emissive_triangles_are_lights() {
        let mut loaded = builtin_cornell_box(None).unwrap();
        loaded.setup.materials[0].emission_cd_m2 = 20.0;
        let lit = LitScene::new(&loaded.scene, &loaded.setup, 2);
        let basis = loaded.setup.camera.basis(loaded.setup.handedness, 40, 30);
        let rays: Vec<Ray> = (0..1200)
            .map(|i| basis.ray((i % 40) as f32, (i / 40) as f32).unwrap())
            .collect();
        let (_, in_lanes) = compare(&lit, &rays, 256);
        assert_eq!(in_lanes, 0);
    }
}
