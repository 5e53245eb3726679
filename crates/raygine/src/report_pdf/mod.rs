//! The lighting report as a PDF a designer can hand over: a cover with the settings and the
//! reached error, a view of the scene, per grid a plan drawn from its data (with a rendered
//! orthographic plan view under it) and a statistics table, the luminaire schedule and the
//! requirements check. Every reading is rounded to what its standard error supports.
//!
//! The report is built as plain data ([`Report`]) by the command (`report_cmd`) and drawn here;
//! nothing here renders or measures.

pub mod canvas;
mod plan;

use canvas::{BLACK, Canvas, GREEN, GREY, LIGHT, RED};
use krilla::Document;
use krilla::page::PageSettings;
use tracer_core::measure::requirements::GridCheck;
use tracer_core::measure::rounding::{format_reading, format_std_error};
use tracer_core::measure::{Grid, GridResult};

/// Page sizes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Paper {
    #[default]
    A4,
    Letter,
}

impl Paper {
    pub fn from_name(name: &str) -> Option<Paper> {
        match name.to_ascii_lowercase().as_str() {
            "a4" => Some(Paper::A4),
            "letter" => Some(Paper::Letter),
            _ => None,
        }
    }

    /// Width and height in points.
    pub fn size_pt(self) -> (f32, f32) {
        match self {
            Paper::A4 => (595.28, 841.89),
            Paper::Letter => (612.0, 792.0),
        }
    }
}

/// A picture for the report: RGBA8 pixels and what it shows.
#[derive(Clone, Debug)]
pub struct Picture {
    pub rgba: Vec<u8>,
    pub width: u32,
    pub height: u32,
    pub caption: String,
}

/// One grid's section.
#[derive(Clone, Debug)]
pub struct GridSection {
    pub grid: Grid,
    /// Maintained readings.
    pub result: GridResult,
    /// The rendered orthographic view of the grid's area, from its normal's side.
    pub plan_view: Option<Picture>,
}

/// One row of the luminaire schedule: a luminaire file (or a point or spot light) and where
/// its copies hang.
#[derive(Clone, Debug, PartialEq)]
pub struct ScheduleRow {
    pub label: String,
    pub manufacturer: Option<String>,
    pub name: Option<String>,
    pub catalogue_number: Option<String>,
    /// Flux of one, lm (after its multiplier).
    pub flux_lm: f64,
    pub power_w: Option<f64>,
    pub colour_rendering: Option<String>,
    /// Positions and aims (scene unit).
    pub placements: Vec<([f32; 3], Option<[f32; 3]>)>,
}

/// Everything the report shows.
#[derive(Clone, Debug)]
pub struct Report {
    pub title: String,
    pub scene_file: String,
    pub date: String,
    pub version: String,
    pub unit: String,
    pub integrator: String,
    pub samples: u32,
    /// The worst point's standard error relative to its reading, the target when one was set.
    pub reached_error: String,
    pub maintenance_factor: f64,
    pub paper: Paper,
    pub view: Option<Picture>,
    pub grids: Vec<GridSection>,
    pub schedule: Vec<ScheduleRow>,
    pub checks: Vec<GridCheck>,
    pub requirements_source: String,
}

const MARGIN: f32 = 50.0;

/// The PDF's bytes.
pub fn write_pdf(report: &Report) -> Result<Vec<u8>, String> {
    let font = canvas::font()?;
    let mut doc = Document::new();
    let (pw, ph) = report.paper.size_pt();
    let settings = || PageSettings::from_wh(pw, ph).ok_or("bad paper size".to_owned());
    let mut page_no = 0;
    let mut next_page = |doc: &mut Document, draw: &mut dyn FnMut(&mut Canvas<'_, '_>)| {
        page_no += 1;
        let settings = settings()?;
        let mut page = doc.start_page_with(settings);
        let mut surface = page.surface();
        let mut c = Canvas {
            surface: &mut surface,
            font: font.clone(),
        };
        draw(&mut c);
        let footer = format!(
            "{} · raygine {} · page {page_no}",
            report.title, report.version
        );
        c.text(MARGIN, ph - 25.0, 7.5, GREY, &footer);
        surface.finish();
        page.finish();
        Ok::<(), String>(())
    };
    next_page(&mut doc, &mut |c| cover(c, report, pw))?;
    for g in &report.grids {
        next_page(&mut doc, &mut |c| grid_page(c, report, g, pw, ph))?;
    }
    next_page(&mut doc, &mut |c| schedule_page(c, report, pw))?;
    if !report.checks.is_empty() {
        next_page(&mut doc, &mut |c| checks_page(c, report, pw))?;
    }
    doc.finish()
        .map_err(|e| format!("the PDF could not be written: {e:?}"))
}

/// Label and value rows, two columns.
fn rows(c: &mut Canvas<'_, '_>, x: f32, mut y: f32, rows: &[(&str, String)]) -> f32 {
    for (label, value) in rows {
        c.text(x, y, 9.5, GREY, label);
        c.text(x + 150.0, y, 9.5, BLACK, value);
        y += 15.0;
    }
    y
}

fn cover(c: &mut Canvas<'_, '_>, r: &Report, pw: f32) {
    c.text(MARGIN, 90.0, 22.0, BLACK, "Lighting report");
    c.text(MARGIN, 118.0, 14.0, BLACK, &r.title);
    c.line((MARGIN, 130.0), (pw - MARGIN, 130.0), 0.8, BLACK);
    let mf = if r.maintenance_factor == 1.0 {
        "1 (readings are new values)".to_owned()
    } else {
        format!("{} (readings are maintained values)", r.maintenance_factor)
    };
    let y = rows(
        c,
        MARGIN,
        155.0,
        &[
            ("Scene", r.scene_file.clone()),
            ("Date", r.date.clone()),
            ("Software", format!("raygine {}", r.version)),
            ("Scene unit", r.unit.clone()),
            ("Light transport", r.integrator.clone()),
            ("Samples per point", r.samples.to_string()),
            ("Reached standard error", r.reached_error.clone()),
            ("Maintenance factor", mf),
            ("Grids", r.grids.len().to_string()),
        ],
    );
    c.text(
        MARGIN,
        y + 6.0,
        8.0,
        GREY,
        "Readings come from the unbiased sums, never from a denoised picture; each is rounded to what its",
    );
    c.text(
        MARGIN,
        y + 17.0,
        8.0,
        GREY,
        "standard error supports (3 significant figures at most).",
    );
    if let Some(view) = &r.view {
        let top = y + 35.0;
        let w = pw - 2.0 * MARGIN;
        let h = w * view.height as f32 / view.width.max(1) as f32;
        let h = h.min(360.0);
        let w = h * view.width as f32 / view.height.max(1) as f32;
        c.image(
            view.rgba.clone(),
            (view.width, view.height),
            MARGIN,
            top,
            w,
            h,
        );
        c.text(MARGIN, top + h + 13.0, 8.5, GREY, &view.caption);
    }
}

fn grid_page(c: &mut Canvas<'_, '_>, r: &Report, g: &GridSection, pw: f32, ph: f32) {
    let grid = &g.grid;
    let res = &g.result;
    c.text(MARGIN, 70.0, 15.0, BLACK, &format!("Grid {}", grid.name));
    let spacing_u = glam::Vec3::from(grid.u).length() / grid.nu.max(1) as f32;
    let spacing_v = glam::Vec3::from(grid.v).length() / grid.nv.max(1) as f32;
    let task = grid
        .task
        .as_deref()
        .map_or(String::new(), |t| format!(" · task {t}"));
    c.text(
        MARGIN,
        86.0,
        8.5,
        GREY,
        &format!(
            "{} x {} points, spacing {} x {} {}, normal ({:.2}, {:.2}, {:.2}){task}",
            grid.nu,
            grid.nv,
            format_reading(f64::from(spacing_u), 0.0),
            format_reading(f64::from(spacing_v), 0.0),
            r.unit,
            grid.normal[0],
            grid.normal[1],
            grid.normal[2]
        ),
    );
    let top = 100.0;
    let w = pw - 2.0 * MARGIN;
    let used = plan::draw(c, grid, res, &r.unit, (MARGIN, top), w, 300.0);
    // The statistics table.
    let s = res.statistics();
    let [se_min, se_avg, se_max] = res.statistics_std_errors();
    let rel = |v: f64, se: f64| if v > 0.0 { se / v } else { 0.0 };
    let u0_se = s.u0 * (rel(s.e_min_lx, se_min).powi(2) + rel(s.e_avg_lx, se_avg).powi(2)).sqrt();
    let ratio_se = s.emin_over_emax
        * (rel(s.e_min_lx, se_min).powi(2) + rel(s.e_max_lx, se_max).powi(2)).sqrt();
    let reading = |v: f64, se: f64, unit: &str| {
        format!(
            "{} {unit}  ± {}",
            format_reading(v, se),
            format_std_error(se)
        )
    };
    let buried = res.buried_count();
    let mut y = top + used + 20.0;
    c.text(
        MARGIN,
        y,
        11.0,
        BLACK,
        "Statistics (maintained values, ± one standard error)",
    );
    y += 18.0;
    let mut table = vec![
        ("Emin", reading(s.e_min_lx, se_min, "lx")),
        ("Eavg", reading(s.e_avg_lx, se_avg, "lx")),
        ("Emax", reading(s.e_max_lx, se_max, "lx")),
        ("U0 = Emin / Eavg", reading(s.u0, u0_se, "")),
        ("Emin / Emax", reading(s.emin_over_emax, ratio_se, "")),
        ("Maintenance factor", format!("{}", r.maintenance_factor)),
        (
            "Points",
            format!(
                "{} measured of {}",
                res.points.len() - buried,
                res.points.len()
            ),
        ),
    ];
    if buried > 0 {
        table.push((
            "Inside or under objects",
            format!("{buried} points, crossed out, left out of the statistics"),
        ));
    }
    y = rows(c, MARGIN, y, &table);
    if let Some(view) = &g.plan_view {
        let room = ph - 60.0 - (y + 10.0);
        if room > 80.0 {
            let h = room.min(260.0);
            let w = (h * view.width as f32 / view.height.max(1) as f32).min(pw - 2.0 * MARGIN);
            let h = w * view.height as f32 / view.width.max(1) as f32;
            c.image(
                view.rgba.clone(),
                (view.width, view.height),
                MARGIN,
                y + 5.0,
                w,
                h,
            );
            c.text(MARGIN, y + h + 17.0, 8.0, GREY, &view.caption);
        }
    }
}

fn schedule_page(c: &mut Canvas<'_, '_>, r: &Report, pw: f32) {
    c.text(MARGIN, 70.0, 15.0, BLACK, "Luminaire schedule");
    let mut y = 95.0;
    let (mut total_flux, mut total_w, mut all_w) = (0.0, 0.0, true);
    let cols = [
        MARGIN,
        MARGIN + 210.0,
        MARGIN + 290.0,
        MARGIN + 350.0,
        MARGIN + 420.0,
    ];
    for (x, h) in cols
        .iter()
        .zip(["Luminaire", "Flux (lm)", "Count", "Power (W)", "Ra"])
    {
        c.text(*x, y, 8.5, GREY, h);
    }
    y += 5.0;
    c.line((MARGIN, y), (pw - MARGIN, y), 0.5, BLACK);
    y += 13.0;
    for row in &r.schedule {
        let n = row.placements.len();
        total_flux += row.flux_lm * n as f64;
        match row.power_w {
            Some(w) => total_w += w * n as f64,
            None => all_w = false,
        }
        c.text(cols[0], y, 9.0, BLACK, &row.label);
        c.text(cols[1], y, 9.0, BLACK, &format_reading(row.flux_lm, 0.0));
        c.text(cols[2], y, 9.0, BLACK, &n.to_string());
        let power = row
            .power_w
            .map_or("not given".to_owned(), |w| format_reading(w, 0.0));
        c.text(cols[3], y, 9.0, BLACK, &power);
        let ra = row.colour_rendering.clone().unwrap_or("not given".into());
        c.text(cols[4], y, 9.0, BLACK, &ra);
        y += 12.0;
        let detail: Vec<String> = [
            row.manufacturer
                .as_ref()
                .map(|m| format!("manufacturer {m}")),
            row.name.as_ref().map(|m| format!("name {m}")),
            row.catalogue_number
                .as_ref()
                .map(|m| format!("catalogue no. {m}")),
        ]
        .into_iter()
        .flatten()
        .collect();
        if !detail.is_empty() {
            c.text(cols[0] + 10.0, y, 7.5, GREY, &detail.join(" · "));
            y += 11.0;
        }
        for (p, aim) in row.placements.iter().take(12) {
            let aim = aim.map_or(String::new(), |a| {
                format!(", aim ({:.2}, {:.2}, {:.2})", a[0], a[1], a[2])
            });
            c.text(
                cols[0] + 10.0,
                y,
                7.5,
                GREY,
                &format!("at ({}, {}, {}) {}{aim}", p[0], p[1], p[2], r.unit),
            );
            y += 10.0;
        }
        if row.placements.len() > 12 {
            c.text(
                cols[0] + 10.0,
                y,
                7.5,
                GREY,
                &format!("… and {} more", n - 12),
            );
            y += 10.0;
        }
        y += 6.0;
    }
    c.line((MARGIN, y), (pw - MARGIN, y), 0.5, BLACK);
    y += 14.0;
    let count: usize = r.schedule.iter().map(|s| s.placements.len()).sum();
    c.text(
        MARGIN,
        y,
        9.5,
        BLACK,
        &format!(
            "Total: {count} light{}, {} lm",
            if count == 1 { "" } else { "s" },
            format_reading(total_flux, 0.0)
        ),
    );
    y += 14.0;
    let efficacy = if all_w && total_w > 0.0 {
        format!(
            "{} W, {} lm/W",
            format_reading(total_w, 0.0),
            format_reading(total_flux / total_w, 0.0)
        )
    } else {
        "power: not given by every luminaire file, so no lm/W".to_owned()
    };
    c.text(MARGIN, y, 9.5, BLACK, &efficacy);
}

fn checks_page(c: &mut Canvas<'_, '_>, r: &Report, pw: f32) {
    c.text(MARGIN, 70.0, 15.0, BLACK, "Requirements check");
    c.text(
        MARGIN,
        86.0,
        8.0,
        GREY,
        &format!("Requirements: {}", r.requirements_source),
    );
    let mut y = 110.0;
    for check in &r.checks {
        let verdict = if check.passes() { "PASS" } else { "FAIL" };
        let colour = if check.passes() { GREEN } else { RED };
        c.text(MARGIN, y, 11.0, colour, verdict);
        c.text(
            MARGIN + 45.0,
            y,
            11.0,
            BLACK,
            &format!("grid {}: {}", check.grid, check.activity.name),
        );
        y += 13.0;
        c.text(MARGIN + 45.0, y, 7.5, GREY, &check.activity.source);
        y += 14.0;
        let cols = [
            MARGIN + 10.0,
            MARGIN + 200.0,
            MARGIN + 280.0,
            MARGIN + 360.0,
            MARGIN + 420.0,
        ];
        for (x, h) in cols
            .iter()
            .zip(["Requirement", "Value", "Required", "Margin", "Beyond 2 SE"])
        {
            c.text(*x, y, 8.0, GREY, h);
        }
        y += 4.0;
        c.line((cols[0], y), (pw - MARGIN, y), 0.4, LIGHT);
        y += 11.0;
        for line in &check.lines {
            let mark = if line.passes() { GREEN } else { RED };
            c.text(cols[0], y, 8.5, BLACK, &line.what);
            c.text(
                cols[1],
                y,
                8.5,
                BLACK,
                &format_reading(line.value, line.std_error),
            );
            c.text(cols[2], y, 8.5, BLACK, &format_reading(line.required, 0.0));
            c.text(
                cols[3],
                y,
                8.5,
                mark,
                &format_reading(line.margin(), line.std_error),
            );
            let sure = if line.certain() {
                "yes"
            } else {
                "no: within the uncertainty"
            };
            c.text(cols[4], y, 8.5, BLACK, sure);
            y += 12.0;
        }
        for n in &check.not_checked {
            c.text(cols[0], y, 8.0, GREY, n);
            y += 11.0;
        }
        y += 14.0;
    }
}
