//! `raygine report`: measure the sidecar's grids, render the scene's view and each grid's plan
//! view (orthographic, from the normal's side), and write the lighting report as a PDF.

use crate::cli::ReportArgs;
use crate::cli_support::{load_scene, map_film_rgb, thread_pool};
use crate::report_pdf::{GridSection, Paper, Picture, Report, ScheduleRow, write_pdf};
use anyhow::{Context, Result, bail};
use glam::Vec3;
use std::path::Path;
use std::time::{Duration, Instant};
use tracer_core::display::DisplaySettings;
use tracer_core::integrator::IntegratorKind;
use tracer_core::light::LightKind;
use tracer_core::measure::requirements::{
    DEFAULT_REQUIREMENTS, DEFAULT_SOURCE, GridCheck, ObserverUgr, Requirements, check,
};
use tracer_core::measure::{Grid, GridResult, MeasureSettings, measure_grids};
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::{Camera, Projection, Scene, Setup};

/// The scene view's width in pixels (its height follows the design's aspect, else 4:3).
const VIEW_WIDTH: u32 = 800;
/// A plan view's longer side in pixels.
const PLAN_PIXELS: u32 = 480;

/// What a report is made with, beside the scene.
#[derive(Clone, Debug)]
pub struct ReportOptions {
    /// The scene's file as the cover names it.
    pub scene_file: String,
    pub measure: MeasureSettings,
    /// Samples per pixel of the scene's view.
    pub view_samples: u32,
    pub paper: Paper,
    pub requirements: Requirements,
    pub requirements_source: String,
    /// `--target-error`, %, for the cover.
    pub target_error_pct: Option<f64>,
    /// Maintained readings already measured for these grids (the viewer's), used instead of
    /// measuring again when they are one per grid, in order.
    pub measured: Option<Vec<GridResult>>,
}

impl ReportOptions {
    /// Options with raygine's requirements table, A4, and `samples` a point.
    pub fn new(scene_file: String, integrator: IntegratorKind, samples: u32) -> Result<Self> {
        Ok(ReportOptions {
            scene_file,
            measure: MeasureSettings {
                integrator,
                max_bounces: None,
                samples,
                time_limit: None,
                target_error: None,
            },
            view_samples: if integrator == IntegratorKind::Direct {
                16
            } else {
                64
            },
            paper: Paper::A4,
            requirements: Requirements::parse(DEFAULT_REQUIREMENTS, DEFAULT_SOURCE)
                .map_err(anyhow::Error::msg)?,
            requirements_source: DEFAULT_SOURCE.to_owned(),
            target_error_pct: None,
            measured: None,
        })
    }
}

pub fn run(args: &ReportArgs) -> Result<()> {
    let started = Instant::now();
    let loaded = load_scene(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let paper = Paper::from_name(&args.paper)
        .with_context(|| format!("--paper {}: a4 or letter", args.paper))?;
    let samples = match (args.scene.samples, args.target_error) {
        (Some(n), _) => n,
        (None, Some(_)) => crate::measure_cmd::TARGET_ERROR_CAP,
        (None, None) => args.scene.samples_or(16),
    };
    let scene_file = args
        .scene
        .scene_path
        .as_ref()
        .map_or("the built-in Cornell box".to_owned(), |p| {
            p.display().to_string()
        });
    let mut options = ReportOptions::new(scene_file, args.scene.integrator, samples)?;
    options.measure.max_bounces = args.scene.max_bounces;
    options.measure.time_limit = args.scene.time_limit.map(Duration::from_secs_f64);
    options.measure.target_error = args.target_error.map(|pct| pct / 100.0);
    options.target_error_pct = args.target_error;
    options.paper = paper;
    if let Some(v) = args.view_samples {
        options.view_samples = v;
    }
    if let Some(path) = &args.requirements {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("{}: cannot read the requirements", path.display()))?;
        let origin = path.display().to_string();
        options.requirements = Requirements::parse(&text, &origin).map_err(anyhow::Error::msg)?;
        options.requirements_source = origin;
    }
    check_tasks(&loaded.setup, &options.requirements)?;
    // Nothing is half-written: the PDF goes through a temporary file; a folder that is not
    // there is said before the work starts.
    check_folder(&args.output)?;
    let pool = thread_pool(&args.scene)?;
    let report = pool.install(|| build(&loaded.scene, &loaded.setup, &options))?;
    let pdf = write_pdf(&report).map_err(anyhow::Error::msg)?;
    tracer_core::export::write_bytes(&args.output, &pdf)
        .with_context(|| format!("{}: cannot write the report", args.output.display()))?;
    for c in &report.checks {
        println!(
            "grid {}: {} against \"{}\"",
            c.grid,
            if c.passes() { "PASS" } else { "FAIL" },
            c.activity.name
        );
    }
    println!(
        "wrote {} ({} grids, {} samples a point, {:.1} s)",
        args.output.display(),
        report.grids.len(),
        report.samples,
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Every grid's task is in `requirements` (else the error lists the known keys), and every
/// observer it names is in the sidecar.
pub fn check_tasks(setup: &Setup, requirements: &Requirements) -> Result<()> {
    for g in &setup.grids {
        for name in &g.observers {
            if !setup.observers.iter().any(|o| &o.name == name) {
                let known: Vec<&str> = setup.observers.iter().map(|o| o.name.as_str()).collect();
                bail!(
                    "grid {}: unknown observer \"{name}\"; the sidecar's [[observers]] are {}",
                    g.name,
                    if known.is_empty() {
                        "none".to_owned()
                    } else {
                        known.join(", ")
                    }
                );
            }
        }
        if let Some(task) = &g.task {
            requirements
                .activity(task)
                .map_err(|e| anyhow::anyhow!("grid {}: {e}", g.name))?;
        }
    }
    Ok(())
}

/// The PDF's folder exists.
pub fn check_folder(output: &Path) -> Result<()> {
    if let Some(dir) = output.parent().filter(|d| !d.as_os_str().is_empty())
        && !dir.is_dir()
    {
        bail!(
            "{}: the folder {} does not exist",
            output.display(),
            dir.display()
        );
    }
    Ok(())
}

/// Measures, renders and assembles the report (on the current rayon pool).
pub fn build(scene: &Scene, setup: &Setup, options: &ReportOptions) -> Result<Report> {
    check_tasks(setup, &options.requirements)?;
    let mf = f64::from(setup.maintenance_factor);
    let fits = |m: &Vec<GridResult>| {
        m.len() == setup.grids.len()
            && m.iter()
                .zip(&setup.grids)
                .all(|(r, g)| r.name == g.name && r.points.len() == g.point_count())
    };
    let results: Vec<GridResult> = match options.measured.as_ref().filter(|m| fits(m)) {
        Some(m) => m.clone(),
        None => measure_grids(scene, setup, &options.measure)
            .into_iter()
            .map(|r| r.scaled(mf))
            .collect(),
    };
    let done = results.first().map_or(0, |r| r.samples);
    let integrator = options.measure.integrator;
    let view = scene_view(scene, setup, integrator, options.view_samples);
    let grids: Vec<GridSection> = setup
        .grids
        .iter()
        .zip(&results)
        .map(|(grid, result)| GridSection {
            grid: grid.clone(),
            result: result.clone(),
            plan_view: plan_view(scene, setup, grid),
        })
        .collect();
    let schedule = schedule(setup);
    let ra = least_ra(&schedule);
    let mut judged: std::collections::HashMap<String, ObserverUgr> = Default::default();
    let checks: Vec<GridCheck> = grids
        .iter()
        .filter_map(|g| {
            let task = g.grid.task.as_deref()?;
            let activity = options.requirements.activity(task).ok()?;
            let ugr: Vec<ObserverUgr> = if activity.ugr_l.is_some() {
                g.grid
                    .observers
                    .iter()
                    .map(|name| {
                        judged
                            .entry(name.clone())
                            .or_insert_with(|| {
                                observer_ugr(scene, setup, name, integrator, options.view_samples)
                            })
                            .clone()
                    })
                    .collect()
            } else {
                Vec::new()
            };
            Some(check(&g.result, activity, ra, &ugr))
        })
        .collect();
    Ok(Report {
        title: scene.name.clone(),
        scene_file: options.scene_file.clone(),
        date: today(),
        version: env!("CARGO_PKG_VERSION").to_owned(),
        unit: setup.unit.symbol().to_owned(),
        integrator: integrator.label().to_owned(),
        samples: done,
        reached_error: reached_error(&results, options.target_error_pct),
        maintenance_factor: mf,
        paper: options.paper,
        view,
        grids,
        schedule,
        checks,
        requirements_source: options.requirements_source.clone(),
    })
}

/// Builds the report and writes the PDF to `output` (atomically); a line for the user.
pub fn build_and_write(
    scene: &Scene,
    setup: &Setup,
    options: &ReportOptions,
    output: &Path,
) -> Result<String> {
    check_folder(output)?;
    let report = build(scene, setup, options)?;
    let pdf = write_pdf(&report).map_err(anyhow::Error::msg)?;
    tracer_core::export::write_bytes(output, &pdf)
        .with_context(|| format!("{}: cannot write the report", output.display()))?;
    let verdicts: Vec<String> = report
        .checks
        .iter()
        .map(|c| format!("{} {}", c.grid, if c.passes() { "PASS" } else { "FAIL" }))
        .collect();
    Ok(if verdicts.is_empty() {
        format!("wrote the report {}", output.display())
    } else {
        format!(
            "wrote the report {} ({})",
            output.display(),
            verdicts.join(", ")
        )
    })
}

/// "worst point 1.9 % of its reading" (with the floor `measure --target-error` uses: 10 % of
/// its grid's mean), and the target when one was set.
fn reached_error(results: &[GridResult], target_pct: Option<f64>) -> String {
    let mut worst = 0.0f64;
    for r in results {
        let floor = 0.1 * r.statistics().e_avg_lx;
        for p in r.points.iter().filter(|p| !p.buried) {
            let scale = p.illuminance_lx.max(floor);
            if scale > 0.0 {
                worst = worst.max(p.std_error_lx / scale);
            }
        }
    }
    if results.is_empty() {
        return "no grids measured".to_owned();
    }
    let reached = format!(
        "worst point {} % of its reading",
        tracer_core::measure::rounding::format_with(100.0 * worst, 1)
    );
    match target_pct {
        Some(t) => format!("{reached} (target {t} %)"),
        None => reached,
    }
}

/// The scene's camera, rendered and mapped for display (auto exposure), RGBA8.
/// UGR from the 180° fisheye at the observer `name` (image sources, as `raygine glare`), with
/// its standard error; None when no glare source is in view.
fn observer_ugr(
    scene: &Scene,
    setup: &Setup,
    name: &str,
    integrator: IntegratorKind,
    samples: u32,
) -> ObserverUgr {
    let judged = (|| {
        let observer = setup
            .observers
            .iter()
            .find(|o| o.name == name)
            .ok_or_else(|| format!("no observer {name} in the scene"))?;
        let view = tracer_core::glare::observer_setup(setup, observer);
        let settings = RenderSettings {
            width: tracer_core::glare::DEFAULT_IMAGE_SIZE,
            height: tracer_core::glare::DEFAULT_IMAGE_SIZE,
            samples_per_pixel: samples.max(2),
            integrator,
            pixel_illuminance: false,
            ..RenderSettings::default()
        };
        let lit = tracer_core::lit_scene::LitScene::new(scene, &view, settings.max_depth);
        tracer_core::glare::check_eye(&lit, observer)?;
        let basis = tracer_core::glare::observer_basis(setup, observer, settings.width);
        let sun = tracer_core::glare::sun_pixels(&lit, &basis);
        let (film, batches, _) =
            tracer_core::glare::render_in_batches(scene, &view, &settings, &sun, None, &mut |_| {});
        let g = tracer_core::glare::judge_observer(
            &lit,
            &view,
            observer,
            &film,
            batches.as_ref(),
            &Default::default(),
            &tracer_core::glare::light_names(setup),
        );
        Ok(g.from_image.ugr.map(|u| (u, g.from_image.ugr_se)))
    })();
    (name.to_owned(), judged)
}

fn scene_view(
    scene: &Scene,
    setup: &Setup,
    integrator: IntegratorKind,
    samples: u32,
) -> Option<Picture> {
    let aspect = scene
        .design
        .resolution
        .map_or(4.0 / 3.0, |[w, h]| w as f32 / h.max(1) as f32);
    let height = ((VIEW_WIDTH as f32 / aspect).round() as u32).clamp(16, 2000);
    let settings = RenderSettings {
        width: VIEW_WIDTH,
        height,
        samples_per_pixel: samples,
        integrator,
        pixel_illuminance: false,
        ..RenderSettings::default()
    };
    let (film, _) = render(scene, setup, &settings);
    let picture = rgba(&film, false);
    Some(Picture {
        rgba: picture,
        width: VIEW_WIDTH,
        height,
        caption: format!(
            "The scene's camera ({}): {}, {samples} samples per pixel, automatic exposure, \
             not denoised",
            setup.camera.projection,
            integrator.name()
        ),
    })
}

/// The film mapped for display with automatic exposure, RGBA8; `mirror` flips it left-right.
fn rgba(film: &tracer_core::render::Film, mirror: bool) -> Vec<u8> {
    let display = DisplaySettings {
        auto_exposure: true,
        ..DisplaySettings::default()
    };
    let exposure = display.effective_exposure(film);
    let rgb = map_film_rgb(film, &display, exposure).rgb;
    let (w, h) = (film.width as usize, film.height as usize);
    let mut out = Vec::with_capacity(w * h * 4);
    for y in 0..h {
        for x in 0..w {
            let sx = if mirror { w - 1 - x } else { x };
            let i = 3 * (y * w + sx);
            out.extend_from_slice(&[rgb[i], rgb[i + 1], rgb[i + 2], 255]);
        }
    }
    out
}

/// The grid's area seen orthographically from its normal's side (direct light, 16 samples): u
/// to the right and v up, as its plan is drawn. The camera stands just short of the first
/// surface above the grid's centre, so a ceiling does not hide the floor.
fn plan_view(scene: &Scene, base: &Setup, grid: &Grid) -> Option<Picture> {
    let (u, v, n) = (
        Vec3::from(grid.u),
        Vec3::from(grid.v),
        Vec3::from(grid.normal),
    );
    let (lu, lv) = (u.length(), v.length());
    if !(lu > 0.0 && lv > 0.0) {
        return None;
    }
    let centre = Vec3::from(grid.origin) + 0.5 * (u + v);
    // The camera's plane: just short of the farthest first surface over a 5 x 5 sample of the
    // grid (a room's ceiling, not a desk's or a block's top, nor the inside of an object over
    // the centre); over open sky, past the scene's bounds.
    let mut up_to = 0.0f32;
    let mut open = false;
    for k in 0..25 {
        let (fu, fv) = ((k % 5) as f32 / 4.0, (k / 5) as f32 / 4.0);
        let p = Vec3::from(grid.origin) + u * fu + v * fv + n * 1e-3 * lu.max(lv);
        let ray = tracer_core::geometry::Ray::new(p, n);
        match scene.closest_drawn(&ray, &base.hidden) {
            Some(hit) => up_to = up_to.max(hit.t),
            None => open = true,
        }
    }
    let up_to = if open || up_to <= 0.0 {
        let b = &scene.bounds;
        (b.max - centre).length() + (b.min - centre).length()
    } else {
        0.98 * up_to
    };
    let camera = Camera {
        position: (centre + n * up_to).to_array(),
        look_at: centre.to_array(),
        up: v.to_array(),
        fov_deg: 45.0,
        projection: Projection::Orthographic,
        width: Some(lu),
    };
    let (width, height) = if lu >= lv {
        (
            PLAN_PIXELS,
            ((PLAN_PIXELS as f32 * lv / lu).round() as u32).max(8),
        )
    } else {
        (
            ((PLAN_PIXELS as f32 * lu / lv).round() as u32).max(8),
            PLAN_PIXELS,
        )
    };
    let setup = Setup {
        camera,
        ..base.clone()
    };
    let settings = RenderSettings {
        width,
        height,
        samples_per_pixel: 16,
        integrator: IntegratorKind::Direct,
        pixel_illuminance: false,
        ..RenderSettings::default()
    };
    let (film, _) = render(scene, &setup, &settings);
    // In a left-handed scene the camera's picture has u to the left: mirror it to match the plan.
    let basis = camera.basis(setup.handedness, width, height);
    let o = Vec3::from(grid.origin);
    let mirror = match (basis.project(o + 0.5 * v), basis.project(o + u + 0.5 * v)) {
        (Some(a), Some(b)) => b.0 < a.0,
        _ => false,
    };
    Some(Picture {
        rgba: rgba(&film, mirror),
        width,
        height,
        caption: format!(
            "Rendered plan view: orthographic, {} {} across, from the grid's normal side (direct \
             light, 16 samples per pixel)",
            tracer_core::measure::rounding::format_reading(f64::from(lu), 0.0),
            base.unit.symbol()
        ),
    })
}

/// The lights grouped: one row per luminaire file and multiplier, one per point or spot light.
fn schedule(setup: &Setup) -> Vec<ScheduleRow> {
    let mut rows: Vec<(String, ScheduleRow)> = Vec::new();
    for light in &setup.lights {
        let placement = (light.position().to_array(), light.aim());
        let (key, row) = match &light.kind {
            LightKind::Luminaire(l) => {
                let info = &l.luminaire.photometry.info;
                let file = l.luminaire.file.display().to_string();
                let label = l
                    .luminaire
                    .file
                    .file_name()
                    .map_or(file.clone(), |f| f.to_string_lossy().into_owned());
                let label = if l.multiplier == 1.0 {
                    label
                } else {
                    format!("{label} x {}", l.multiplier)
                };
                (
                    format!("{file}|{}", l.multiplier),
                    ScheduleRow {
                        label,
                        manufacturer: info.manufacturer.clone(),
                        name: info.name.clone(),
                        catalogue_number: info.catalogue_number.clone(),
                        flux_lm: f64::from(light.flux_lm()),
                        power_w: info.power_w,
                        colour_rendering: info.colour_rendering.clone(),
                        placements: Vec::new(),
                    },
                )
            }
            _ => (
                format!("{}|{}", light.tag().name(), light.flux_lm()),
                ScheduleRow {
                    label: format!("{} light", light.tag().name()),
                    manufacturer: None,
                    name: None,
                    catalogue_number: None,
                    flux_lm: f64::from(light.flux_lm()),
                    power_w: None,
                    colour_rendering: None,
                    placements: Vec::new(),
                },
            ),
        };
        match rows.iter_mut().find(|(k, _)| *k == key) {
            Some((_, r)) => r.placements.push(placement),
            None => {
                let mut row = row;
                row.placements.push(placement);
                rows.push((key, row));
            }
        }
    }
    rows.into_iter().map(|(_, r)| r).collect()
}

/// The least Ra the luminaire files give as a number (EULUMDAT's lamp data), if any does.
fn least_ra(schedule: &[ScheduleRow]) -> Option<f64> {
    schedule
        .iter()
        .filter_map(|r| r.colour_rendering.as_deref()?.trim().parse::<f64>().ok())
        .reduce(f64::min)
}

/// Today's date (UTC), YYYY-MM-DD.
fn today() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (y, m, d) = civil_from_days((secs / 86_400) as i64);
    format!("{y:04}-{m:02}-{d:02}")
}

/// The proleptic Gregorian date of a day count from 1970-01-01 (Howard Hinnant's algorithm).
fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let y = yoe + era * 400 + i64::from(m <= 2);
    (y, m, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn days_become_dates() {
        assert_eq!(civil_from_days(0), (1970, 1, 1));
        assert_eq!(civil_from_days(20_793), (2026, 12, 6));
        assert_eq!(civil_from_days(11_016), (2000, 2, 29));
    }
}
