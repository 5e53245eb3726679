//! The direct integrator's wavefront gives every sample bit for bit as tracing it alone, on a
//! scene that exercises every branch of a walk: mirror chains of different lengths, a glossy
//! lobe, an emissive surface seen and sampled as a light, a point light and a spot, a hidden
//! slot, and rays that miss.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use tracer_core::light::{Light, Spot};
use tracer_core::render::{
    BATCH_SAMPLES, BatchScratch, Film, FrameSampler, RenderSettings, SampleJob, render,
};
use tracer_core::scene::{LoadedScene, builtin_cornell_box};

fn busy_cornell() -> LoadedScene {
    let mut loaded = builtin_cornell_box(None).unwrap();
    let names: Vec<String> = (0..loaded.scene.slots.len() as u32)
        .map(|s| loaded.scene.slot_label(s))
        .collect();
    let slot = |name: &str| names.iter().position(|n| n.contains(name)).unwrap();
    let m = &mut loaded.setup.materials;
    // Mirrors facing each other: chains up to the depth limit.
    m[slot("tall_block")].ks = [0.8, 0.7, 0.6];
    m[slot("red_wall")].ks = [0.5; 3];
    m[slot("short_block")].ks = [0.3; 3];
    m[slot("short_block")].glossiness = 20.0;
    m[slot("ceiling")].emission_cd_m2 = 50.0;
    loaded.setup.hidden = vec![false; names.len()];
    loaded.setup.hidden[slot("green_wall")] = true;
    loaded.setup.lights.push(Light::spot(
        [100.0, 400.0, -100.0],
        Spot {
            intensity_cd: 300.0,
            aim: [0.3, -1.0, -0.2],
            cone_deg: 20.0,
            falloff_deg: 35.0,
        },
    ));
    loaded
}

fn settings() -> RenderSettings {
    RenderSettings {
        width: 72,
        height: 40,
        samples_per_pixel: 3,
        max_depth: 4,
        ..RenderSettings::default()
    }
}

#[test]
fn batches_equal_samples_traced_one_by_one() {
    let loaded = busy_cornell();
    let settings = settings();
    let frame = FrameSampler::new(&loaded.scene, &loaded.setup, &settings);
    let jobs: Vec<SampleJob> = (0..settings.height)
        .flat_map(|y| (0..settings.width).map(move |x| (x, y)))
        .flat_map(|(x, y)| (0..settings.samples_per_pixel).map(move |s| SampleJob { x, y, s }))
        .collect();
    let alone: Vec<_> = jobs
        .iter()
        .map(|j| frame.sample(j.x, j.y, j.s, &mut Vec::new()))
        .collect();
    // The scene does what it is meant to: some misses, mirror chains (more than two rays plus
    // shadow rays), emission seen directly.
    assert!(alone.iter().any(|s| s.missed));
    assert!(alone.iter().any(|s| s.rays >= 8), "no long mirror chain");
    let mut scratch = BatchScratch::default();
    let mut out = Vec::new();
    for size in [1, 7, BATCH_SAMPLES, 1000] {
        let mut batched = Vec::new();
        for chunk in jobs.chunks(size) {
            frame.sample_batch(chunk, &mut scratch, &mut Vec::new(), &mut out);
            batched.extend_from_slice(&out);
        }
        assert_eq!(batched.len(), alone.len());
        for (i, (a, b)) in alone.iter().zip(&batched).enumerate() {
            let bits = |s: &tracer_core::integrator::Sample| {
                (
                    s.rgb.to_array().map(f32::to_bits),
                    s.illuminance_lx.to_bits(),
                    s.rays,
                    s.missed,
                )
            };
            assert_eq!(bits(a), bits(b), "batch size {size}, job {:?}", jobs[i]);
        }
    }
}

#[test]
fn one_shot_film_equals_the_sum_of_single_samples() {
    let loaded = busy_cornell();
    let settings = settings();
    let (film, stats) = render(&loaded.scene, &loaded.setup, &settings);
    let frame = FrameSampler::new(&loaded.scene, &loaded.setup, &settings);
    let mut expected = Film::new(settings.width, settings.height);
    let mut rays = 0u64;
    for y in 0..settings.height {
        for x in 0..settings.width {
            let mut sum = tracer_core::render::PixelSum::default();
            for s in 0..settings.samples_per_pixel {
                let sample = frame.sample(x, y, s, &mut Vec::new());
                rays += u64::from(sample.rays);
                assert!(sum.add(&sample));
            }
            expected.set_pixel((y * settings.width + x) as usize, &sum);
        }
    }
    assert_eq!(
        film.pixels().collect::<Vec<_>>(),
        expected.pixels().collect::<Vec<_>>()
    );
    assert_eq!(stats.rays, rays);
}
