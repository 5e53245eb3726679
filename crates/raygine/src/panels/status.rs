//! The status bar: the render's progress, the scene's figures, the viewport's size, a load in
//! progress (with Cancel) and the UI's frame time.

use crate::command::{Command, Commands};
use crate::document::Document;
use crate::file_ops::PendingLoad;
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::SessionStats;

/// What the status bar shows.
#[derive(Debug)]
pub struct StatusBar<'a> {
    pub stats: SessionStats,
    pub paused: bool,
    pub integrator: IntegratorKind,
    pub doc: &'a Document,
    pub viewport_px: [u32; 2],
    pub loading: Option<&'a PendingLoad>,
    /// The 95th percentile of recent frame intervals while rendering, ms.
    pub p95_frame_ms: Option<f32>,
    /// The viewport shows a denoised picture: of how many samples per pixel, made in how many
    /// seconds.
    pub denoised: Option<(u32, f64)>,
    /// A file is being written in the background (an export, the sidecar, the PDF report).
    pub writing: bool,
}

/// One line at the bottom; what does not fit is cut off at the window's edge. It never wraps:
/// a second line would shrink the viewport, whose new size restarts the render, whose new
/// figures could unwrap it again (a narrow window restarted the render every frame).
pub fn status_bar(ui: &mut egui::Ui, s: StatusBar<'_>, out: &mut Commands) {
    egui::Panel::bottom("status").show(ui, |ui| {
        ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Extend);
        ui.horizontal(|ui| {
            let state = if s.paused {
                "paused"
            } else if s.stats.finished {
                "converged"
            } else {
                "rendering"
            };
            ui.label(format!(
                "{state} · {} · {:.1}/{} spp · {} · {:.1} Mrays/s · {}{}",
                s.integrator.label(),
                s.stats.samples_done(),
                s.stats.target_spp,
                s.stats.pass,
                s.stats.mrays_per_sec(),
                duration(s.stats.elapsed_secs),
                match s.stats.eta_secs().filter(|_| !s.paused) {
                    Some(eta) => format!(" · {} left", duration(eta)),
                    None => String::new(),
                }
            ))
            .on_hover_text(
                "Full samples per pixel done (with the running pass's share) of the target, the \
                 pass running, the rays traced per second, the time since the render started and \
                 the time left to the target at the rate so far",
            );
            if let Some(noise) = s.stats.relative_noise {
                ui.label(format!("noise ±{:.1} %", noise * 100.0))
                    .on_hover_text(
                        "Remaining noise: RMS standard error of the pixels' luminance over the \
                     mean luminance, from the summed squares of the samples",
                    );
            }
            if let Some((spp, secs)) = s.denoised {
                ui.label("denoised display · readouts unbiased")
                    .on_hover_text(format!(
                        "The picture is denoised (from {spp} spp, in {secs:.1} s); every number \
                     shown comes from the raw, unbiased sums. D shows the raw picture."
                    ));
            }
            ui.separator();
            ui.label(format!(
                "{} tris · BVH {:.0} ms · parse {:.0} ms",
                s.doc.scene.triangle_count(),
                s.doc.scene.bvh_build_secs * 1e3,
                s.doc.parse_secs * 1e3
            ));
            ui.separator();
            ui.label(format!(
                "{}x{} px · {} threads",
                s.viewport_px[0], s.viewport_px[1], s.stats.threads
            ));
            if let Some(l) = s.loading {
                ui.separator();
                ui.spinner();
                ui.label(format!(
                    "loading {} ({:.1} s)",
                    l.path.file_name().map_or_else(
                        || l.path.display().to_string(),
                        |n| n.to_string_lossy().into_owned()
                    ),
                    l.started.elapsed().as_secs_f32()
                ));
                if ui
                    .button("Cancel")
                    .on_hover_text("Keep the current scene")
                    .clicked()
                {
                    out.push(Command::CancelLoad);
                }
            }
            if s.writing {
                ui.separator();
                ui.spinner();
                ui.label("writing a file…").on_hover_text(
                    "An export or the PDF report is being written in the background (a report \
                     measures its grids and renders its views first); the banner says when it \
                     is done",
                );
            }
            if let Some(p95) = s.p95_frame_ms {
                ui.separator();
                ui.label(format!("UI p95 {p95:.0} ms"));
            }
        });
    });
}

/// A duration for the status bar: "4.2 s", "3 min 05 s", "1 h 02 min".
pub fn duration(secs: f64) -> String {
    if !secs.is_finite() || secs < 0.0 {
        return "—".to_owned();
    }
    if secs < 60.0 {
        return format!("{secs:.1} s");
    }
    let whole = secs.round() as u64;
    if whole < 3600 {
        format!("{} min {:02} s", whole / 60, whole % 60)
    } else {
        format!("{} h {:02} min", whole / 3600, (whole % 3600) / 60)
    }
}

#[cfg(test)]
mod tests {
    use super::duration;

    #[test]
    fn durations_read_in_the_largest_sensible_unit() {
        assert_eq!(duration(4.24), "4.2 s");
        assert_eq!(duration(185.0), "3 min 05 s");
        assert_eq!(duration(3720.0), "1 h 02 min");
        assert_eq!(duration(f64::NAN), "—");
    }
}
