//! `raygine measure`: the illuminance on every grid of the sidecar, with its statistics, written
//! as CSV and JSON; with `--daylight-factor`, the daylight factor too.

use crate::cli::MeasureArgs;
use crate::cli_support::{load_scene, thread_pool};
use anyhow::{Context, Result, bail};
use serde_json::json;
use std::fmt::Write as _;
use std::io::IsTerminal;
use std::time::{Duration, Instant};
use tracer_core::measure::rounding::Precision;
use tracer_core::measure::{
    DaylightFactorSetup, GridResult, MeasureSettings, measure_grids_with_progress,
};

/// The CSV header, exactly.
pub const CSV_HEADER: &str = "grid,i,j,x,y,z,illuminance_lx,std_error_lx";

/// The columns `--daylight-factor` adds to the CSV.
pub const CSV_DF_COLUMNS: &str = ",daylight_factor_pct,daylight_factor_std_error_pct";

/// The sample cap of `--target-error` when `--samples` is not given.
pub const TARGET_ERROR_CAP: u32 = 65_536;

pub fn run(args: &MeasureArgs) -> Result<()> {
    let started = Instant::now();
    let loaded = load_scene(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    if loaded.setup.grids.is_empty() {
        bail!(
            "the scene has no grids: add [[grids]] tables (name, origin, u, v, nu, nv; or \
             work_plane = true) to its sidecar"
        );
    }
    let samples = match (args.scene.samples, args.target_error) {
        (Some(n), _) => n,
        (None, Some(_)) => TARGET_ERROR_CAP,
        (None, None) => args.scene.samples_or(1),
    };
    let settings = MeasureSettings {
        integrator: args.scene.integrator,
        max_bounces: args.scene.max_bounces,
        samples,
        time_limit: args.scene.time_limit.map(Duration::from_secs_f64),
        target_error: args.target_error.map(|pct| pct / 100.0),
    };
    let df = if args.daylight_factor {
        if args.shard.partial.is_some() {
            bail!("--daylight-factor is not measured in shards yet: measure it on one machine");
        }
        Some(DaylightFactorSetup::new(&loaded.setup).map_err(anyhow::Error::msg)?)
    } else {
        None
    };
    if args.shard.partial.is_some() {
        return crate::shard_cmd::measure_part(args, &loaded, &settings);
    }
    let setup = df.as_ref().map_or(&loaded.setup, |d| &d.setup);
    let pool = thread_pool(&args.scene)?;
    let bar = progress_bar(samples);
    let measured_at = Instant::now();
    let results = pool.install(|| {
        measure_grids_with_progress(&loaded.scene, setup, &settings, &mut |p| {
            bar.set_position(u64::from(p.samples_done));
            if let Some(w) = p.worst_relative_error {
                bar.set_message(format!("worst point at {:.2}x the target error", w));
            }
            true
        })
    });
    bar.finish_and_clear();
    let secs = measured_at.elapsed().as_secs_f64();
    // A daylight factor is a ratio of the room's geometry and surfaces: no maintenance factor.
    let mf = if df.is_some() {
        1.0
    } else {
        f64::from(loaded.setup.maintenance_factor)
    };
    let outdoor = df.as_ref().map(|d| d.outdoor_lx);
    let results: Vec<GridResult> = results.into_iter().map(|r| r.scaled(mf)).collect();
    let unit = loaded.setup.unit.symbol();
    let done = results.first().map_or(0, |r| r.samples);
    write_readings(
        &results,
        unit,
        settings.integrator.name(),
        done,
        ReadingFiles {
            csv: args.csv.as_deref(),
            json: args.json.as_deref(),
            precision: args.precision,
        },
        outdoor,
    )?;
    if mf != 1.0 {
        println!("maintenance factor {mf}: maintained illuminance");
    }
    if let Some(e) = outdoor {
        println!(
            "daylight factor: CIE overcast sky without sun, E_out,h {e:.0} lx on the open \
             horizontal; illuminances below are under that sky"
        );
    }
    for r in &results {
        println!("{}", summary_line(r));
        if let Some(e) = outdoor {
            println!("{}", df_summary_line(r, e));
        }
    }
    let rays: u64 = results.iter().map(|r| r.rays).sum();
    println!(
        "{} integrator, {done} samples a point, {:.1} s, {:.2} Mrays/s, {} threads; positions in {unit}",
        settings.integrator,
        secs,
        rays as f64 / secs.max(1e-9) / 1e6,
        pool.current_num_threads()
    );
    for path in [&args.csv, &args.json].into_iter().flatten() {
        println!("wrote {}", path.display());
    }
    println!("{:.1} s in all", started.elapsed().as_secs_f64());
    Ok(())
}

/// Where the readings go and how precisely.
#[derive(Clone, Copy, Debug)]
pub struct ReadingFiles<'a> {
    pub csv: Option<&'a std::path::Path>,
    pub json: Option<&'a std::path::Path>,
    pub precision: Precision,
}

/// Writes the readings (maintained values) as CSV and JSON, where asked.
pub fn write_readings(
    results: &[GridResult],
    unit: &str,
    integrator: &str,
    samples: u32,
    files: ReadingFiles<'_>,
    df_outdoor_lx: Option<f64>,
) -> Result<()> {
    let precision = files.precision;
    if let Some(path) = files.csv {
        tracer_core::export::write_text(path, &csv(results, df_outdoor_lx, precision))
            .with_context(|| format!("{}: cannot write the CSV", path.display()))?;
    }
    if let Some(path) = files.json {
        let text = json_report(results, unit, integrator, samples, df_outdoor_lx, precision);
        tracer_core::export::write_text(path, &text)
            .with_context(|| format!("{}: cannot write the JSON", path.display()))?;
    }
    Ok(())
}

fn progress_bar(cap: u32) -> indicatif::ProgressBar {
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(u64::from(cap));
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{elapsed_precise} [{bar:30}] {pos}/{len} samples a point {msg}",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// `grid floor: 256 points, Emin 61.2 lx, Eavg 104.5 lx, Emax 150.3 lx, U0 0.59, Emin/Emax 0.41,
/// normal (0.000, 1.000, 0.000)`; points inside objects are counted ("256 points (12 inside
/// objects, left out)").
pub fn summary_line(r: &GridResult) -> String {
    let s = r.statistics();
    let buried = r.buried_count();
    let points = if buried > 0 {
        format!(
            "{} points ({buried} inside objects, left out)",
            r.points.len()
        )
    } else {
        format!("{} points", r.points.len())
    };
    format!(
        "grid {}: {points}, Emin {:.1} lx, Eavg {:.1} lx, Emax {:.1} lx, U0 {:.2}, Emin/Emax {:.2}, normal ({:.3}, {:.3}, {:.3})",
        r.name,
        s.e_min_lx,
        s.e_avg_lx,
        s.e_max_lx,
        s.u0,
        s.emin_over_emax,
        r.normal.x,
        r.normal.y,
        r.normal.z
    )
}

/// `grid floor: DF min 0.85 %, avg 2.10 %, max 6.01 %, uniformity (min/avg) 0.40`, for readings
/// under an overcast sky of `outdoor_lx` on the open horizontal.
pub fn df_summary_line(r: &GridResult, outdoor_lx: f64) -> String {
    let s = r.statistics();
    let pct = |e: f64| 100.0 * e / outdoor_lx;
    format!(
        "grid {}: DF min {:.2} %, avg {:.2} %, max {:.2} %, uniformity (min/avg) {:.2}",
        r.name,
        pct(s.e_min_lx),
        pct(s.e_avg_lx),
        pct(s.e_max_lx),
        s.u0
    )
}

/// The CSV text: the header, then one line a point (i along u, j along v, 0-based); with
/// `df_outdoor_lx`, each point's daylight factor and its standard error in % too. Readings
/// are written at `precision` (positions as the f32 they are, in their shortest form).
pub fn csv(results: &[GridResult], df_outdoor_lx: Option<f64>, precision: Precision) -> String {
    let mut out = String::with_capacity(64 * results.len());
    out.push_str(CSV_HEADER);
    if df_outdoor_lx.is_some() {
        out.push_str(CSV_DF_COLUMNS);
    }
    out.push('\n');
    for r in results {
        for p in &r.points {
            let _ = write!(
                out,
                "{},{},{},{},{},{},{},{}",
                r.name,
                p.i,
                p.j,
                p.position.x,
                p.position.y,
                p.position.z,
                precision.value(p.illuminance_lx, p.std_error_lx),
                precision.std_error(p.std_error_lx)
            );
            if let Some(e) = df_outdoor_lx {
                let (df, se) = (100.0 * p.illuminance_lx / e, 100.0 * p.std_error_lx / e);
                let _ = write!(
                    out,
                    ",{},{}",
                    precision.value(df, se),
                    precision.std_error(se)
                );
            }
            out.push('\n');
        }
    }
    out
}

/// The JSON report: unit, integrator, samples and per grid its statistics and points; with
/// `df_outdoor_lx`, daylight factors (`df_*_pct`, per point `daylight_factor_pct`) too.
pub fn json_report(
    results: &[GridResult],
    unit: &str,
    integrator: &str,
    samples: u32,
    df_outdoor_lx: Option<f64>,
    precision: Precision,
) -> String {
    let pct = |e: f64| df_outdoor_lx.map(|out| 100.0 * e / out);
    // A ratio's standard error from its two terms' relative errors.
    let ratio_se = |r: f64, (a, sa): (f64, f64), (b, sb): (f64, f64)| {
        let rel = |v: f64, s: f64| if v > 0.0 { s / v } else { 0.0 };
        r * (rel(a, sa).powi(2) + rel(b, sb).powi(2)).sqrt()
    };
    let grids: Vec<_> = results
        .iter()
        .map(|r| {
            let s = r.statistics();
            let [se_min, se_avg, se_max] = r.statistics_std_errors();
            let u0_se = ratio_se(s.u0, (s.e_min_lx, se_min), (s.e_avg_lx, se_avg));
            let ratio = ratio_se(s.emin_over_emax, (s.e_min_lx, se_min), (s.e_max_lx, se_max));
            let mut grid = json!({
                "name": r.name,
                "normal": r.normal.to_array(),
                "e_min_lx": precision.value(s.e_min_lx, se_min),
                "e_avg_lx": precision.value(s.e_avg_lx, se_avg),
                "e_max_lx": precision.value(s.e_max_lx, se_max),
                "e_min_std_error_lx": precision.std_error(se_min),
                "e_avg_std_error_lx": precision.std_error(se_avg),
                "e_max_std_error_lx": precision.std_error(se_max),
                "u0": precision.value(s.u0, u0_se),
                "emin_over_emax": precision.value(s.emin_over_emax, ratio),
                "points_inside_objects": r.buried_count(),
                "points": r.points.iter().map(|p| {
                    let mut point = json!({
                    "i": p.i,
                    "j": p.j,
                    "x": p.position.x,
                    "y": p.position.y,
                    "z": p.position.z,
                    "illuminance_lx": precision.value(p.illuminance_lx, p.std_error_lx),
                    "std_error_lx": precision.std_error(p.std_error_lx),
                    "inside_object": p.buried,
                    });
                    if let (Some(df), Some(se)) = (pct(p.illuminance_lx), pct(p.std_error_lx)) {
                        point["daylight_factor_pct"] = json!(precision.value(df, se));
                        point["daylight_factor_std_error_pct"] = json!(precision.std_error(se));
                    }
                    point
                }).collect::<Vec<_>>(),
            });
            if df_outdoor_lx.is_some() {
                let df = |e: f64, se: f64| pct(e).zip(pct(se)).map(|(v, s)| precision.value(v, s));
                grid["df_min_pct"] = json!(df(s.e_min_lx, se_min));
                grid["df_avg_pct"] = json!(df(s.e_avg_lx, se_avg));
                grid["df_max_pct"] = json!(df(s.e_max_lx, se_max));
                grid["df_uniformity"] = json!(precision.value(s.u0, u0_se));
            }
            grid
        })
        .collect();
    let mut doc = json!({
        "unit": unit,
        "integrator": integrator,
        "samples": samples,
        "grids": grids,
    });
    if let Some(e) = df_outdoor_lx {
        doc["daylight_factor"] = json!({
            "sky": "cie-overcast",
            "outdoor_horizontal_lx": e,
        });
    }
    serde_json::to_string_pretty(&doc).unwrap_or_default() + "\n"
}
