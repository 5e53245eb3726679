//! Exposure per scene: set automatically on a scene's first view, held while the user edits,
//! the user's own once they set one, and remembered per scene in the preferences (the built-in
//! box and every scene file have their own).
//!
//! The automatic exposure maps the median luminance of the scene's surfaces (pixels where the
//! camera sees nothing are left out) to middle grey: first from the first complete preview, so
//! the first picture is already exposed, then once more from the first full-resolution pass,
//! and then held, so dragging a slider never makes the picture flicker. The continuous "auto
//! exposure" checkbox, like the command line's `--auto-exposure`, is a different thing: it
//! follows the picture pass by pass, and while it is on nothing here changes the exposure.

use serde::{Deserialize, Serialize};
use std::path::Path;
use tracer_core::display::{DisplaySettings, REFERENCE_LUMINANCE};
use tracer_core::light::luminance;
use tracer_core::render::{ProgressiveFilm, SessionStats};

/// The tone curve's input the median luminance is mapped to.
pub const MIDDLE_GREY: f32 = 0.18;

/// One scene's remembered exposure.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneExposure {
    pub stops: f32,
    /// Set by the user (else automatic, from the scene's first view).
    pub by_user: bool,
}

/// The key a scene's view state is stored under: its path, or the built-in box's name.
pub fn scene_key(path: Option<&Path>) -> String {
    match path {
        Some(p) => std::fs::canonicalize(p)
            .unwrap_or_else(|_| p.to_path_buf())
            .display()
            .to_string(),
        None => "builtin:cornell-box".to_owned(),
    }
}

/// The exposure (stops) that maps the median luminance of the film's surfaces to middle grey;
/// None when nothing lit is seen. Pixels for which `outside` (pixel index) says the camera
/// sees nothing (a fisheye's corners, black) are left out like the background.
pub fn median_exposure_stops(
    film: &ProgressiveFilm,
    outside: impl Fn(usize) -> bool,
) -> Option<f32> {
    let n = film.width() as usize * film.height() as usize;
    let mut lum: Vec<f32> = (0..n)
        .filter(|&i| film.background_fraction(i) < 0.5 && !outside(i))
        .map(|i| luminance(film.shown_rgb(i)))
        .filter(|y| y.is_finite())
        .collect();
    if lum.is_empty() {
        return None;
    }
    let mid = lum.len() / 2;
    let (_, median, _) = lum.select_nth_unstable_by(mid, f32::total_cmp);
    let median = *median;
    (median > 1e-9).then(|| (MIDDLE_GREY * REFERENCE_LUMINANCE / median).log2())
}

/// Where the current scene's exposure stands.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Stage {
    /// Nothing set yet: waiting for the first preview of a generation at least this new.
    FirstView {
        from_generation: u64,
        preview_done: bool,
    },
    /// Held: automatic from the first view, or the user's.
    Held,
}

/// The exposure of the scene on screen.
#[derive(Clone, Debug)]
pub struct ExposureKeeper {
    key: String,
    stage: Stage,
    /// The exposure last put into the display settings from here (or seen there), so a change
    /// made by the user is told apart from ours.
    applied: f32,
    auto_was_on: bool,
}

impl ExposureKeeper {
    /// The keeper for a scene just shown: its remembered exposure, or automatic from the first
    /// generation newer than `generation`.
    pub fn for_scene(
        key: String,
        remembered: Option<SceneExposure>,
        display: &mut DisplaySettings,
        generation: u64,
    ) -> Self {
        let stage = match remembered {
            Some(e) if e.stops.is_finite() => {
                display.exposure_stops = e.stops;
                Stage::Held
            }
            _ => Stage::FirstView {
                from_generation: generation + 1,
                preview_done: false,
            },
        };
        Self {
            key,
            stage,
            applied: display.exposure_stops,
            auto_was_on: display.auto_exposure,
        }
    }

    pub fn key(&self) -> &str {
        &self.key
    }

    /// Whether the exposure is settled (automatic from the first view, or the user's).
    pub fn held(&self) -> bool {
        self.stage == Stage::Held
    }

    /// Called every frame. Takes a user's change of the exposure (or of auto exposure) as
    /// theirs; on the first view sets it from the film. Returns what to remember for this
    /// scene when that changed.
    pub fn update(
        &mut self,
        display: &mut DisplaySettings,
        stats: &SessionStats,
        film: impl FnOnce() -> Option<f32>,
    ) -> Option<SceneExposure> {
        let user_moved = display.exposure_stops != self.applied;
        let auto_toggled = display.auto_exposure != self.auto_was_on;
        self.auto_was_on = display.auto_exposure;
        if user_moved || auto_toggled {
            self.applied = display.exposure_stops;
            self.stage = Stage::Held;
            return Some(SceneExposure {
                stops: display.exposure_stops,
                by_user: true,
            });
        }
        let Stage::FirstView {
            from_generation,
            preview_done,
        } = self.stage
        else {
            return None;
        };
        if display.auto_exposure || stats.generation < from_generation {
            return None;
        }
        let full = stats.samples_per_pixel >= 1;
        let preview = stats.first_preview_secs.is_some();
        if !(full || (preview && !preview_done)) {
            return None;
        }
        let stops = film()?;
        display.exposure_stops = stops;
        self.applied = stops;
        if full {
            self.stage = Stage::Held;
            Some(SceneExposure {
                stops,
                by_user: false,
            })
        } else {
            self.stage = Stage::FirstView {
                from_generation,
                preview_done: true,
            };
            None
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use glam::Vec3;
    use tracer_core::integrator::Sample;
    use tracer_core::render::Tile;

    fn film_of(values: &[f32]) -> ProgressiveFilm {
        let mut f = ProgressiveFilm::new(1, values.len() as u32, 1);
        for (x, &v) in values.iter().enumerate() {
            let tile = Tile {
                x0: x as u32,
                y0: 0,
                x1: x as u32 + 1,
                y1: 1,
            };
            f.fill_preview(
                &tile,
                &Sample {
                    rgb: Vec3::splat(v),
                    missed: v < 0.0,
                    ..Sample::default()
                },
            );
        }
        f
    }

    /// The median of the surfaces (not of the background) lands on middle grey.
    #[test]
    fn the_median_surface_maps_to_middle_grey() {
        // Background pixels (missed, drawn as -1 here) are left out: the median is 50.
        let film = film_of(&[-1.0, -1.0, -1.0, 10.0, 50.0, 400.0]);
        let stops = median_exposure_stops(&film, |_| false).unwrap();
        let shown = 50.0 * DisplaySettings::scale_for(stops);
        assert!((shown - MIDDLE_GREY).abs() < 1e-5, "{shown}");
        assert_eq!(
            median_exposure_stops(&film_of(&[-1.0, 0.0]), |_| false),
            None
        );
        // Pixels outside the image are left out too: the median of 10 and 400 is 400.
        let stops = median_exposure_stops(&film, |i| i == 4).unwrap();
        let shown = 400.0 * DisplaySettings::scale_for(stops);
        assert!((shown - MIDDLE_GREY).abs() < 1e-4, "{shown}");
    }

    fn stats(generation: u64, preview: bool, spp: u32) -> SessionStats {
        SessionStats {
            generation,
            first_preview_secs: preview.then_some(0.05),
            samples_per_pixel: spp,
            ..SessionStats::default()
        }
    }

    #[test]
    fn first_view_sets_it_then_holds_it_and_the_user_wins() {
        let mut d = DisplaySettings::default();
        let mut k = ExposureKeeper::for_scene("a".into(), None, &mut d, 4);
        // The old generation's film is not this scene's.
        assert_eq!(k.update(&mut d, &stats(4, true, 1), || Some(3.0)), None);
        assert_eq!(d.exposure_stops, 0.0);
        // First preview: provisional, not remembered yet.
        assert_eq!(k.update(&mut d, &stats(5, true, 0), || Some(-2.0)), None);
        assert_eq!(d.exposure_stops, -2.0);
        assert!(!k.held());
        // First full pass: final and remembered.
        let kept = k.update(&mut d, &stats(5, true, 1), || Some(-2.5));
        assert_eq!(
            kept,
            Some(SceneExposure {
                stops: -2.5,
                by_user: false
            })
        );
        // Edits restart the render: the exposure holds.
        assert_eq!(k.update(&mut d, &stats(6, true, 1), || Some(9.0)), None);
        assert_eq!(d.exposure_stops, -2.5);
        // The user's own.
        d.exposure_stops = 1.0;
        let kept = k.update(&mut d, &stats(6, true, 2), || Some(9.0));
        assert_eq!(
            kept,
            Some(SceneExposure {
                stops: 1.0,
                by_user: true
            })
        );
        // A remembered scene comes back as it was.
        let mut d2 = DisplaySettings::default();
        let k2 = ExposureKeeper::for_scene("a".into(), kept, &mut d2, 9);
        assert!(k2.held());
        assert_eq!(d2.exposure_stops, 1.0);
    }
}
