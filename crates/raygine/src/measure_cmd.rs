//! `raygine measure`: the illuminance on every grid of the sidecar, written as CSV.

use crate::cli::MeasureArgs;
use crate::render_cmd::{load_scene, thread_pool};
use anyhow::{Context, Result, bail};
use std::fmt::Write as _;
use std::time::{Duration, Instant};
use tracer_core::measure::{GridResult, MeasureSettings, measure_grids};

/// The CSV header, exactly.
pub const CSV_HEADER: &str = "grid,i,j,x,y,z,illuminance_lx,std_error_lx";

pub fn run(args: &MeasureArgs) -> Result<()> {
    let started = Instant::now();
    let loaded = load_scene(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    if loaded.setup.grids.is_empty() {
        bail!(
            "the scene has no grids: add [[grids]] tables (name, origin, u, v, nu, nv) to its \\
             sidecar"
        );
    }
    let settings = MeasureSettings {
        integrator: args.scene.integrator,
        max_bounces: args.scene.max_bounces,
        samples: args.scene.samples_or(1),
        time_limit: args.scene.time_limit.map(Duration::from_secs_f64),
    };
    let pool = thread_pool(&args.scene)?;
    let measured_at = Instant::now();
    let results = pool.install(|| measure_grids(&loaded.scene, &loaded.setup, &settings));
    let secs = measured_at.elapsed().as_secs_f64();
    let text = csv(&results);
    tracer_core::export::write_text(&args.csv, &text)
        .with_context(|| format!("{}: cannot write the CSV", args.csv.display()))?;
    let unit = loaded.setup.unit.symbol();
    for r in &results {
        let (min, max) = r
            .points
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
                (lo.min(p.illuminance_lx), hi.max(p.illuminance_lx))
            });
        println!(
            "grid {}: {} points, Emin {:.1} lx, Eavg {:.1} lx, Emax {:.1} lx, normal ({:.3}, {:.3}, {:.3})",
            r.name,
            r.points.len(),
            min,
            r.mean_lx(),
            max,
            r.normal.x,
            r.normal.y,
            r.normal.z
        );
    }
    let samples = results.first().map_or(0, |r| r.samples);
    let rays: u64 = results.iter().map(|r| r.rays).sum();
    println!(
        "{} integrator, {samples} samples a point, {:.1} s, {:.2} Mrays/s, {} threads; positions in {unit}",
        settings.integrator,
        secs,
        rays as f64 / secs.max(1e-9) / 1e6,
        pool.current_num_threads()
    );
    println!(
        "wrote {} ({:.1} s in all)",
        args.csv.display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The CSV text: the header, then one line a point (i along u, j along v, 0-based).
pub fn csv(results: &[GridResult]) -> String {
    let mut out = String::with_capacity(64 * results.len());
    out.push_str(CSV_HEADER);
    out.push('\n');
    for r in results {
        for p in &r.points {
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{}",
                r.name,
                p.i,
                p.j,
                p.position.x,
                p.position.y,
                p.position.z,
                p.illuminance_lx,
                p.std_error_lx
            );
        }
    }
    out
}
