//! `raygine glare`: UGR and DGP at the sidecar's observers, each with its standard error, from
//! a 180° fisheye rendered at each eye; the sources found in the image and, for luminaires with
//! a luminous opening, analytically. Prints a summary; writes JSON, CSV and Radiance pictures
//! only when asked.

use crate::cli::GlareArgs;
use crate::cli_support::{check_output_path, load_scene, sampling_settings, thread_pool};
use anyhow::{Context, Result, bail};
use serde_json::json;
use std::fmt::Write as _;
use std::time::{Duration, Instant};
use tracer_core::glare::hdr::{View, write_radiance_hdr};
use tracer_core::glare::{
    Detection, GlareFigures, GlareOptions, ObserverGlare, check_eye, judge_observer, light_names,
    observer_basis, observer_setup, render_in_batches, sun_pixels,
};
use tracer_core::lit_scene::LitScene;
use tracer_core::render::RenderSettings;
use tracer_core::scene::Observer;

/// Samples per pixel of the direct mode's fisheye when --samples is not given (a standard
/// error needs two).
const DIRECT_GLARE_SAMPLES: u32 = 16;

pub fn run(args: &GlareArgs) -> Result<()> {
    let started = Instant::now();
    let loaded = load_scene(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let observers = chosen_observers(&loaded.setup.observers, &args.observer)?;
    for path in [&args.json, &args.csv].into_iter().flatten() {
        check_output_path(path)?;
    }
    if let Some(dir) = args.hdr.as_ref().filter(|d| !d.is_dir()) {
        bail!("--hdr {}: not a directory", dir.display());
    }
    let options = GlareOptions {
        detection: Detection {
            threshold: args.threshold,
            search_radius: args.search_radius,
        },
        low_light: args.dgp_low_light,
    };
    let settings = RenderSettings {
        width: args.size,
        height: args.size,
        pixel_illuminance: false,
        ..sampling_settings(&args.scene, DIRECT_GLARE_SAMPLES)
    };
    if settings.samples_per_pixel < 2 {
        bail!("--samples must be at least 2: a standard error needs two samples a pixel");
    }
    let pool = thread_pool(&args.scene)?;
    let names = light_names(&loaded.setup);
    // Every eye is checked before anything is rendered or written.
    for observer in &observers {
        let setup = observer_setup(&loaded.setup, observer);
        let lit = LitScene::new(&loaded.scene, &setup, settings.max_depth);
        check_eye(&lit, observer).map_err(anyhow::Error::msg)?;
    }
    let mut results = Vec::new();
    for observer in observers {
        let setup = observer_setup(&loaded.setup, observer);
        let lit = LitScene::new(&loaded.scene, &setup, settings.max_depth);
        let at = Instant::now();
        let time_limit = args.scene.time_limit.map(Duration::from_secs_f64);
        let mut last_line = Instant::now();
        let target = settings.samples_per_pixel;
        let mut progress = |s: &tracer_core::render::RenderStats| {
            // A line every few seconds on stderr, so long judgements say where they are.
            if last_line.elapsed().as_secs_f64() >= 5.0 && s.samples_per_pixel < target {
                last_line = Instant::now();
                eprintln!(
                    "observer {}: {}/{target} spp of its fisheye, {:.1} s",
                    observer.name, s.samples_per_pixel, s.elapsed_secs
                );
            }
        };
        // Where samples splat (bidirectional, light), in independent batches: their spread is
        // the figures' error. The pixels the sun may fall in take more samples.
        let sun = sun_pixels(&lit, &observer_basis(&loaded.setup, observer, args.size));
        let (film, batches, stats) = pool.install(|| {
            render_in_batches(
                &loaded.scene,
                &setup,
                &settings,
                &sun,
                time_limit,
                &mut progress,
            )
        });
        if film.rejected_samples() > 0 {
            bail!(
                "observer {}: {} samples were not finite; no glare figures",
                observer.name,
                film.rejected_samples()
            );
        }
        let glare = pool.install(|| {
            judge_observer(
                &lit,
                &setup,
                observer,
                &film,
                batches.as_ref(),
                &options,
                &names,
            )
        });
        let secs = at.elapsed().as_secs_f64();
        print!(
            "{}",
            summary(
                observer,
                &glare,
                &args.threshold,
                stats.samples_per_pixel,
                &settings,
                secs,
                loaded.setup.unit.symbol()
            )
        );
        if let Some(dir) = &args.hdr {
            let path = dir.join(format!("{}.hdr", observer.name));
            // Up made perpendicular to the line of sight: evalglare takes its τ angle from
            // -vu as written (a tilted observer's plain +Y would turn its position indices).
            let basis = observer_basis(&loaded.setup, observer, args.size);
            let view = View {
                position: observer.position,
                direction: basis.forward.to_array(),
                up: basis.up.to_array(),
            };
            write_radiance_hdr(&path, &glare.image, &view)
                .with_context(|| format!("cannot write {}", path.display()))?;
            println!(
                "  wrote {} (evalglare -vta picture, L / 179)",
                path.display()
            );
        }
        results.push((observer, glare, stats.samples_per_pixel));
    }
    if let Some(path) = &args.json {
        tracer_core::export::write_text(path, &json_text(&results, &settings, &options))?;
        println!("wrote {}", path.display());
    }
    if let Some(path) = &args.csv {
        tracer_core::export::write_text(path, &csv_text(&results))?;
        println!("wrote {}", path.display());
    }
    println!("{:.1} s in all", started.elapsed().as_secs_f64());
    Ok(())
}

/// The observers named on the command line (all without names), or why not.
fn chosen_observers<'a>(all: &'a [Observer], names: &[String]) -> Result<Vec<&'a Observer>> {
    if all.is_empty() {
        bail!(
            "the scene has no observers: add [[observers]] tables (name, position, direction, \
             up) to its sidecar, or add one in the viewer's Glare section"
        );
    }
    if names.is_empty() {
        return Ok(all.iter().collect());
    }
    names
        .iter()
        .map(|n| {
            all.iter().find(|o| &o.name == n).ok_or_else(|| {
                let known: Vec<&str> = all.iter().map(|o| o.name.as_str()).collect();
                anyhow::anyhow!(
                    "--observer {n}: the scene has no such observer ({})",
                    known.join(", ")
                )
            })
        })
        .collect()
}

/// "18.4 ± 0.1" with the error to two significant figures and the value to match.
fn with_error(value: f64, se: f64, min_decimals: usize) -> String {
    if !se.is_finite() {
        return format!("{value:.min_decimals$} ± ? (one sample a pixel)");
    }
    let decimals = if se > 0.0 {
        ((1.0 - se.log10().floor()) as i64).clamp(min_decimals as i64, min_decimals as i64 + 2)
            as usize
    } else {
        min_decimals
    };
    format!("{value:.decimals$} ± {se:.decimals$}")
}

/// Where the figures' standard errors come from.
fn errors_from(f: &GlareFigures) -> String {
    match f.error_batches {
        Some(k) => format!(
            "from the spread of {k} independent batches of samples (this integrator's light \
             subpaths splat into many pixels, so their errors are not independent)"
        ),
        None => "from the pixels' own standard errors (independent pixels)".to_owned(),
    }
}

fn figures_lines(out: &mut String, f: &GlareFigures) {
    let ugr = match (f.ugr, f.ugr_evalglare_index) {
        (Some(u), Some(e)) => format!(
            "{} (with evalglare's position index: {e:.2})",
            with_error(u, f.ugr_se, 1)
        ),
        (Some(u), None) => with_error(u, f.ugr_se, 1),
        (None, _) if f.sources.is_empty() => "— (no glare source)".to_owned(),
        (None, _) => "— (no background luminance)".to_owned(),
    };
    let correction = if f.low_light_applied {
        "low-light correction applied"
    } else if f.low_light_asked {
        "low-light correction asked, Ev ≥ 1000 lx: none"
    } else {
        "no low-light correction"
    };
    let _ = writeln!(
        out,
        "    UGR {ugr}   DGP {} ({correction})   Lb {} cd/m²",
        with_error(f.dgp, f.dgp_se, 3),
        with_error(f.lb, f.lb_se, 1)
    );
    let _ = writeln!(out, "    ± {}", errors_from(f));
    for s in &f.sources {
        let (up, right) = s.angles_deg();
        let flag = if s.outside_cie117() {
            "  [outside CIE 117's 0.0003–0.1 sr]"
        } else {
            ""
        };
        let _ = writeln!(
            out,
            "    {}: L {} cd/m², ω {:.5} sr, p {:.2} by {}, {up:+.1}° up, {right:+.1}° right{flag}",
            s.label,
            with_error(s.luminance, s.luminance_se, 0),
            s.solid_angle,
            s.position_index,
            s.index_rule.label()
        );
    }
    for note in f.notes() {
        let _ = writeln!(out, "    note: {note}");
    }
}

fn summary(
    o: &Observer,
    g: &ObserverGlare,
    threshold: &f64,
    spp: u32,
    settings: &RenderSettings,
    secs: f64,
    unit: &str,
) -> String {
    let mut out = String::new();
    let [x, y, z] = o.position;
    let [dx, dy, dz] = o.direction;
    let _ = writeln!(
        out,
        "observer {}: eye ({x}, {y}, {z}) {unit}, looking ({dx}, {dy}, {dz}); {}x{} fisheye \
         (180°, equidistant), {spp} spp {}, {secs:.1} s",
        o.name, settings.width, settings.height, settings.integrator
    );
    let f = &g.from_image;
    let _ = writeln!(
        out,
        "  Ev {} lx (at the eye, facing the line of sight)",
        with_error(f.ev, f.ev_se, 1)
    );
    let rule = if *threshold > 100.0 {
        format!("above {threshold} cd/m²")
    } else {
        format!(
            "above {threshold} × the mean luminance = {:.1} cd/m²",
            g.threshold_cd_m2
        )
    };
    let _ = writeln!(
        out,
        "  from the image ({rule}): {} source(s)",
        f.sources.len()
    );
    figures_lines(&mut out, f);
    match &g.analytic {
        Some(a) => {
            let _ = writeln!(
                out,
                "  from the luminaires' openings (L = I / A_proj, ω of the part the eye sees; \
                 drawn into {} pixels of the image): {} source(s)",
                g.opening_pixels,
                a.sources.len()
            );
            figures_lines(&mut out, a);
        }
        None => {
            let _ = writeln!(
                out,
                "  from the luminaires' openings: no luminaire has one (point lights have no \
                 luminous area; glowing surfaces, windows and the sun are found in the image)"
            );
        }
    }
    out
}

fn figures_json(f: &GlareFigures) -> serde_json::Value {
    json!({
        "ev_lx": f.ev, "ev_std_error_lx": f.ev_se,
        "lb_cd_m2": f.lb, "lb_std_error_cd_m2": f.lb_se,
        "ugr": f.ugr, "ugr_std_error": f.ugr_se,
        "ugr_with_evalglare_position_index": f.ugr_evalglare_index,
        "dgp": f.dgp, "dgp_std_error": f.dgp_se,
        "std_errors_from": f.error_batches.map_or("pixels".to_owned(), |k| format!("{k} batches")),
        "dgp_low_light_asked": f.low_light_asked,
        "dgp_low_light_applied": f.low_light_applied,
        "notes": f.notes(),
        "sources": f.sources.iter().map(|s| {
            let (up, right) = s.angles_deg();
            json!({
                "label": s.label,
                "position_index_evalglare": tracer_core::glare::position_index::evalglare_index(s.direction),
                "luminance_cd_m2": s.luminance,
                "luminance_std_error_cd_m2": s.luminance_se,
                "solid_angle_sr": s.solid_angle,
                "position_index": s.position_index,
                "position_index_rule": s.index_rule.label(),
                "elevation_deg": up,
                "azimuth_right_deg": right,
                "pixels": s.pixels.len(),
                "outside_cie117_range": s.outside_cie117(),
            })
        }).collect::<Vec<_>>(),
    })
}

fn json_text(
    results: &[(&Observer, ObserverGlare, u32)],
    settings: &RenderSettings,
    options: &GlareOptions,
) -> String {
    let doc = json!({
        "integrator": settings.integrator.name(),
        "image_size_px": settings.width,
        "threshold": options.detection.threshold,
        "search_radius_rad": options.detection.search_radius,
        "observers": results.iter().map(|(o, g, spp)| json!({
            "name": o.name,
            "position": o.position,
            "direction": o.direction,
            "up": o.up,
            "samples_per_pixel": spp,
            "threshold_cd_m2": g.threshold_cd_m2,
            "from_image": figures_json(&g.from_image),
            "analytic": g.analytic.as_ref().map(figures_json),
        })).collect::<Vec<_>>(),
    });
    serde_json::to_string_pretty(&doc).unwrap_or_default() + "\n"
}

fn csv_text(results: &[(&Observer, ObserverGlare, u32)]) -> String {
    let mut out = String::from(
        "observer,sources_from,sources,ev_lx,ev_se_lx,lb_cd_m2,lb_se_cd_m2,ugr,ugr_se,dgp,dgp_se,\
         dgp_low_light_applied\n",
    );
    for (o, g, _) in results {
        let ways = [
            ("image", Some(&g.from_image)),
            ("luminaires", g.analytic.as_ref()),
        ];
        for (way, f) in ways {
            let Some(f) = f else { continue };
            let ugr = f.ugr.map_or(String::new(), |u| format!("{u:.3}"));
            let _ = writeln!(
                out,
                "{},{way},{},{:.3},{:.3},{:.3},{:.3},{ugr},{:.3},{:.4},{:.4},{}",
                o.name,
                f.sources.len(),
                f.ev,
                f.ev_se,
                f.lb,
                f.lb_se,
                f.ugr_se,
                f.dgp,
                f.dgp_se,
                f.low_light_applied
            );
        }
    }
    out
}
