//! D3 of BENCHMARK.md's denoising targets: milliseconds per denoise (prefiltered guides, then
//! the colour), at the viewer's 1022x810 and at 1920x1080, on the threads given.
//!
//! `cargo run --release -p tracer-core --example denoise_bench -- [THREADS] [RUNS]`

use glam::Vec3;
use std::time::Instant;
use tracer_core::denoise::{Denoiser, Images, Quality};

fn main() {
    let mut args = std::env::args().skip(1);
    let threads: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(2);
    let runs: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(5);
    let denoiser = match Denoiser::load(threads) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    println!(
        "Open Image Denoise {} from {}, {threads} threads",
        denoiser.version_text(),
        denoiser.library()
    );
    for (w, h) in [(1022u32, 810u32), (1920, 1080)] {
        let n = (w * h) as usize;
        // A noisy picture: a hash per pixel, so the network sees something like a render.
        let color: Vec<Vec3> = (0..n)
            .map(|i| {
                let x = (i as u32).wrapping_mul(2_654_435_761) >> 8;
                Vec3::splat(x as f32 / 16_777_216.0 * 200.0)
            })
            .collect();
        let albedo = vec![Vec3::splat(0.6); n];
        let normal = vec![Vec3::Y; n];
        let images = Images {
            width: w,
            height: h,
            color: &color,
            albedo: &albedo,
            normal: &normal,
        };
        for quality in [Quality::High, Quality::Balanced] {
            let mut times = Vec::new();
            for _ in 0..runs {
                let t = Instant::now();
                if let Err(e) = denoiser.denoise(&images, quality) {
                    eprintln!("{e}");
                    std::process::exit(1);
                }
                times.push(t.elapsed().as_secs_f64() * 1e3);
            }
            let first = times[0];
            times.sort_by(f64::total_cmp);
            println!(
                "{w}x{h} {quality:?}: first {first:.0} ms, median {:.0} ms, best {:.0} ms ({runs} runs)",
                times[times.len() / 2],
                times[0]
            );
        }
    }
}
