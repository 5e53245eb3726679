//! Daylight: the place, date and time of day (a slider: the sun moves live and the render
//! restarts), the sky and its scale, and the sun. It edits the sidecar's `[daylight]` as
//! written; a change that does not check (a date like 2026-02-30) is shown in red and the
//! scene keeps the daylight it had.

use tracer_core::light::daylight::{Daylight, DaylightSpec};
use tracer_core::scene::{Handedness, Setup};

/// The skies the menu offers, by their sidecar names.
const SKIES: [(&str, &str); 6] = [
    ("none", "No sky (the sun alone, if it is on)"),
    (
        "cie-overcast",
        "CIE traditional overcast sky: L = Lz (1 + 2 cos θ) / 3",
    ),
    ("uniform", "The same luminance everywhere above the horizon"),
    ("cie:12", "CIE clear sky (ISO 15469 type 12)"),
    ("cie:1", "ISO 15469 type 1: overcast, steep gradation"),
    (
        "perez",
        "Perez all-weather sky from the direct normal and diffuse horizontal illuminances",
    ),
];

/// The draft being edited, and why it does not check (when it does not).
#[derive(Debug, Default)]
pub struct DaylightDraft {
    spec: Option<DaylightSpec>,
    error: Option<String>,
}

/// A first daylight: the summer solstice at noon in central Europe, under an overcast sky of
/// 10,000 lx.
fn first_daylight() -> DaylightSpec {
    DaylightSpec {
        latitude: 52.0,
        longitude: 5.0,
        longitude_convention: None,
        date: "2026-06-21".into(),
        time: "12:00".into(),
        timezone: 1.0,
        daylight_saving: true,
        north: None,
        zenith: None,
        sky: Some("cie-overcast".into()),
        zenith_luminance_cd_m2: None,
        diffuse_horizontal_lx: Some(10_000.0),
        ground_reflectance: None,
        direct_normal_lx: None,
        sun: false,
        sun_normal_illuminance_lx: None,
    }
}

/// Puts `daylight` into `setup`: the sky becomes the environment (no sky: none).
pub fn apply_daylight(setup: &mut Setup, daylight: Option<Daylight>) {
    let right_handed = setup.handedness == Handedness::Right;
    let had_sky = setup.daylight.as_ref().is_some_and(|d| d.sky.is_some());
    match &daylight {
        Some(d) => match d.sky_environment(right_handed) {
            Some(env) => setup.environment = Some(env),
            None if had_sky => setup.environment = None,
            None => {}
        },
        None if had_sky => setup.environment = None,
        None => {}
    }
    setup.daylight = daylight;
}

/// The Daylight section.
pub fn daylight_ui(ui: &mut egui::Ui, setup: &mut Setup, draft: &mut DaylightDraft) {
    let current = setup.daylight.as_ref().map(|d| d.spec.clone());
    let Some(applied) = current else {
        draft.spec = None;
        match setup.sun {
            Some(sun) => {
                let d = glam::Vec3::from(sun.direction).normalize_or_zero();
                ui.label(format!(
                    "No daylight. The file's distant light: {:.0} lx on a plane facing it, {:.2}° \
                     across, {:.1}° above the horizon (a daylight sun replaces it).",
                    sun.normal_illuminance_lx,
                    sun.diameter_deg,
                    d.y.clamp(-1.0, 1.0).asin().to_degrees()
                ));
            }
            None => {
                ui.label("No daylight: the scene is lit by its lights alone.");
            }
        }
        if ui
            .button("Add daylight")
            .on_hover_text("A sky (and optionally the sun) for a place, date and time")
            .clicked()
            && let Ok(d) = first_daylight().to_model()
        {
            apply_daylight(setup, Some(d));
        }
        return;
    };
    // An undo or a reload replaces what was applied: start again from it.
    if draft.error.is_none() || draft.spec.is_none() {
        draft.spec = Some(applied.clone());
    }
    let Some(spec) = draft.spec.as_mut() else {
        return;
    };
    let before = spec.clone();
    place_ui(ui, spec);
    time_ui(ui, spec);
    sky_ui(ui, spec);
    sun_ui(ui, spec);
    if let Some(d) = &setup.daylight {
        let sun = d.sun();
        ui.label(format!(
            "sun: altitude {:.1}°, azimuth {:.1}° (from north through east){}",
            sun.altitude_deg,
            sun.azimuth_deg,
            if sun.altitude_deg <= 0.0 {
                ", below the horizon"
            } else {
                ""
            }
        ))
        .on_hover_text(
            "Apparent altitude (with refraction). The viewport's axis triad shows the sun's \
             direction in yellow",
        );
        if let Some(sky) = &d.sky {
            ui.label(format!(
                "sky: zenith {:.0} cd/m², open horizontal {:.0} lx",
                sky.zenith_luminance_cd_m2,
                sky.horizontal_illuminance()
            ));
        }
    }
    if *spec != before {
        match spec.to_model() {
            Ok(d) => {
                draft.error = None;
                apply_daylight(setup, Some(d));
            }
            Err(e) => draft.error = Some(e),
        }
    }
    if let Some(e) = &draft.error {
        ui.colored_label(egui::Color32::from_rgb(255, 120, 100), e);
    }
    if ui
        .button("Remove daylight")
        .on_hover_text("No sky and no sun (undo brings them back)")
        .clicked()
    {
        draft.spec = None;
        draft.error = None;
        apply_daylight(setup, None);
    }
}

fn place_ui(ui: &mut egui::Ui, spec: &mut DaylightSpec) {
    ui.horizontal(|ui| {
        ui.label("latitude");
        ui.add(
            egui::DragValue::new(&mut spec.latitude)
                .speed(0.1)
                .range(-90.0..=90.0)
                .suffix("°"),
        )
        .on_hover_text("Degrees north (south negative)");
        let west = spec.longitude_convention.as_deref() == Some("west");
        ui.label(if west {
            "longitude (west +)"
        } else {
            "longitude"
        });
        ui.add(
            egui::DragValue::new(&mut spec.longitude)
                .speed(0.1)
                .range(-180.0..=180.0)
                .suffix("°"),
        )
        .on_hover_text(if west {
            "Degrees west (this file counts west positive, as Integra and Radiance do)"
        } else {
            "Degrees east (west negative)"
        });
    });
}

fn time_ui(ui: &mut egui::Ui, spec: &mut DaylightSpec) {
    ui.horizontal(|ui| {
        ui.label("date");
        ui.add(egui::TextEdit::singleline(&mut spec.date).desired_width(90.0))
            .on_hover_text("Local date, YYYY-MM-DD");
        ui.label("UTC");
        ui.add(
            egui::DragValue::new(&mut spec.timezone)
                .speed(0.25)
                .range(-12.0..=14.0)
                .suffix(" h"),
        )
        .on_hover_text("The time zone, hours east of UTC");
        ui.checkbox(&mut spec.daylight_saving, "summer time")
            .on_hover_text("Daylight saving: clocks one hour ahead");
    });
    // The time of day as minutes on a slider; seconds are dropped once it is moved.
    let mut minutes = minutes_of(&spec.time).unwrap_or(12 * 60);
    let old = minutes;
    ui.add(
        egui::Slider::new(&mut minutes, 0..=24 * 60 - 1)
            .text("local time")
            .custom_formatter(|m, _| format!("{:02}:{:02}", m as u32 / 60, m as u32 % 60))
            .custom_parser(|s| minutes_of(s).map(f64::from)),
    )
    .on_hover_text("Local clock time: the sun moves as you drag, and the render restarts");
    if minutes != old {
        spec.time = format!("{:02}:{:02}", minutes / 60, minutes % 60);
    }
}

/// Minutes after midnight of `HH:MM[:SS]`.
fn minutes_of(text: &str) -> Option<u32> {
    let mut parts = text.trim().split(':');
    let h: u32 = parts.next()?.parse().ok()?;
    let m: u32 = parts.next()?.parse().ok()?;
    (h < 24 && m < 60).then_some(h * 60 + m)
}

fn sky_ui(ui: &mut egui::Ui, spec: &mut DaylightSpec) {
    let name = spec.sky.clone().unwrap_or_else(|| "none".into());
    ui.horizontal(|ui| {
        ui.label("sky");
        egui::ComboBox::from_id_salt("daylight sky")
            .selected_text(name.clone())
            .show_ui(ui, |ui| {
                let mut chosen = name.clone();
                for (sky, hint) in SKIES {
                    ui.selectable_value(&mut chosen, sky.to_owned(), sky)
                        .on_hover_text(hint);
                }
                for t in 2..=15 {
                    if t == 12 {
                        continue;
                    }
                    let sky = format!("cie:{t}");
                    ui.selectable_value(&mut chosen, sky.clone(), sky)
                        .on_hover_text("ISO 15469 / CIE S 011 general sky");
                }
                if chosen != name {
                    set_sky(spec, &chosen);
                }
            });
    });
    if spec.sky.as_deref() == Some("perez") {
        for (label, value, hint) in [
            (
                "direct normal",
                &mut spec.direct_normal_lx,
                "The sun's illuminance on a plane facing it, lx",
            ),
            (
                "diffuse horizontal",
                &mut spec.diffuse_horizontal_lx,
                "The sky's illuminance on the open horizontal, lx",
            ),
        ] {
            ui.horizontal(|ui| {
                ui.label(label);
                let v = value.get_or_insert(10_000.0);
                let speed = v.abs().max(1.0) * 0.005;
                ui.add(
                    egui::DragValue::new(v)
                        .speed(speed)
                        .range(0.0..=150_000.0)
                        .suffix(" lx"),
                )
                .on_hover_text(hint);
            });
        }
    } else if spec.sky.as_deref().is_some_and(|s| s != "none") {
        ui.horizontal(|ui| {
            let lz = spec.zenith_luminance_cd_m2.is_some();
            let (label, value, hint) = if lz {
                (
                    "zenith luminance",
                    spec.zenith_luminance_cd_m2.get_or_insert(3000.0),
                    "The sky's luminance at the zenith, cd/m²",
                )
            } else {
                (
                    "diffuse horizontal",
                    spec.diffuse_horizontal_lx.get_or_insert(10_000.0),
                    "The sky's illuminance on the open horizontal, lx (overcast: 5,000-20,000)",
                )
            };
            ui.label(label);
            let speed = value.abs().max(1.0) * 0.005;
            ui.add(
                egui::DragValue::new(value)
                    .speed(speed)
                    .range(1.0..=200_000.0)
                    .suffix(if lz { " cd/m²" } else { " lx" }),
            )
            .on_hover_text(hint);
        });
    }
}

/// `sky` by name, with the scale a sky needs (kept when there was one).
fn set_sky(spec: &mut DaylightSpec, sky: &str) {
    if sky == "none" {
        spec.sky = None;
        spec.zenith_luminance_cd_m2 = None;
        spec.diffuse_horizontal_lx = None;
        spec.direct_normal_lx = None;
        spec.ground_reflectance = None;
        return;
    }
    spec.sky = Some(sky.to_owned());
    if sky == "perez" {
        // Perez gives the sun its own illuminance, and takes no zenith luminance.
        spec.zenith_luminance_cd_m2 = None;
        spec.sun_normal_illuminance_lx = None;
        spec.direct_normal_lx.get_or_insert(60_000.0);
        spec.diffuse_horizontal_lx.get_or_insert(15_000.0);
        return;
    }
    spec.direct_normal_lx = None;
    if spec.sun && spec.sun_normal_illuminance_lx.is_none() {
        spec.sun_normal_illuminance_lx = Some(80_000.0);
    }
    if spec.zenith_luminance_cd_m2.is_none() && spec.diffuse_horizontal_lx.is_none() {
        spec.diffuse_horizontal_lx = Some(10_000.0);
    }
}

fn sun_ui(ui: &mut egui::Ui, spec: &mut DaylightSpec) {
    if spec.sky.as_deref() == Some("perez") {
        ui.checkbox(&mut spec.sun, "sun").on_hover_text(
            "A disc 0.533° across; the Perez sky gives it its direct normal illuminance",
        );
        return;
    }
    ui.horizontal(|ui| {
        if ui
            .checkbox(&mut spec.sun, "sun")
            .on_hover_text("A disc 0.533° across that casts penumbrae")
            .changed()
        {
            spec.sun_normal_illuminance_lx = spec.sun.then_some(80_000.0);
        }
        if let Some(e) = &mut spec.sun_normal_illuminance_lx {
            ui.add(
                egui::DragValue::new(e)
                    .speed(200.0)
                    .range(0.0..=150_000.0)
                    .suffix(" lx"),
            )
            .on_hover_text(
                "The sun's illuminance on a plane facing it, lx (clear day: 70,000-100,000)",
            );
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minutes_read_clock_times() {
        assert_eq!(minutes_of("07:30"), Some(450));
        assert_eq!(minutes_of("23:59:10"), Some(1439));
        assert_eq!(minutes_of("24:00"), None);
        assert_eq!(minutes_of("noon"), None);
    }

    #[test]
    fn the_first_daylight_checks() {
        let d = first_daylight()
            .to_model()
            .unwrap_or_else(|e| panic!("{e}"));
        assert!(d.sun().altitude_deg > 55.0);
    }
}
