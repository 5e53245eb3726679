//! Hints when the picture is black: "every pixel is 0 cd/m²" (no light reaches what the camera
//! sees) is told apart from "black at this exposure" (light is there, the display maps it to
//! black), and lights outside the scene's bounds are named.

use tracer_core::display::DisplaySettings;
use tracer_core::geometry::Aabb;
use tracer_core::render::ProgressiveFilm;
use tracer_core::scene::{Setup, luminance};

/// Displayed values below this (linear, 1 = display white) look black.
const BLACK_DISPLAY: f32 = 0.002;

/// The film's brightness, measured once per pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilmLevels {
    pub generation: u64,
    /// The stage measured at (see `RaygineApp::update_picture_hint`).
    pub passes_done: u32,
    /// Largest pixel luminance, cd/m².
    pub max_cd_m2: f32,
    /// The 99th percentile of pixel luminance, cd/m².
    pub p99_cd_m2: f32,
}

impl FilmLevels {
    /// Measures `film`; `passes_done` tags the stage it was measured at.
    pub fn measure(film: &ProgressiveFilm, passes_done: u32) -> Self {
        let n = film.width() as usize * film.height() as usize;
        let mut max_cd_m2 = 0.0f32;
        // The percentile from every 7th pixel: plenty for a hint, and quick under the lock.
        let mut sample = Vec::with_capacity(n / 7 + 1);
        for i in 0..n {
            let l = luminance(film.shown_rgb(i));
            max_cd_m2 = max_cd_m2.max(l);
            if i % 7 == 0 {
                sample.push(l);
            }
        }
        let p99_cd_m2 = if sample.is_empty() {
            0.0
        } else {
            let k = ((sample.len() as f32 * 0.99) as usize).min(sample.len() - 1);
            *sample.select_nth_unstable_by(k, f32::total_cmp).1
        };
        Self {
            generation: film.generation,
            passes_done,
            max_cd_m2,
            p99_cd_m2,
        }
    }
}

/// Numbers (1-based) of the lights outside the scene's bounds.
pub fn lights_outside(setup: &Setup, bounds: &Aabb) -> Vec<usize> {
    setup
        .lights
        .iter()
        .enumerate()
        .filter(|(_, l)| {
            let p = l.position();
            !bounds.contains(&Aabb { min: p, max: p })
        })
        .map(|(i, _)| i + 1)
        .collect()
}

/// The hint for a picture, if it is black. `full_pass` says whether every pixel has had at
/// least one full sample (before that, "all zero" is not yet known).
pub fn picture_hint(
    levels: &FilmLevels,
    full_pass: bool,
    display: &DisplaySettings,
    exposure_stops: f32,
    outside: &[usize],
) -> Option<String> {
    let where_lights = match outside {
        [] => String::new(),
        [one] => format!(" Light {one} is outside the scene's bounds."),
        many => format!(
            " Lights {} are outside the scene's bounds.",
            many.iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    if levels.max_cd_m2 <= 0.0 {
        return full_pass.then(|| {
            format!("Every pixel is 0 cd/m²: no light reaches what the camera sees.{where_lights}")
        });
    }
    if display.auto_exposure || display.false_colour.is_some() {
        return None;
    }
    // The picture's bright end: the 99th percentile (a lamp's hot spot must not hide a black
    // picture), or the brightest pixel when fewer than 1 % of the pixels are lit.
    let bright = if levels.p99_cd_m2 > 0.0 {
        levels.p99_cd_m2
    } else {
        levels.max_cd_m2
    };
    let shown = bright * DisplaySettings::scale_for(exposure_stops);
    if shown >= BLACK_DISPLAY {
        return None;
    }
    let stops = (0.5 / shown.max(f32::MIN_POSITIVE)).log2().ceil();
    Some(format!(
        "Black at this exposure: the brightest pixels are about {} cd/m². Raise the exposure \
         by about {stops:.0} stops, or turn on auto exposure.",
        crate::format::format_value(bright)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn levels(max: f32, p99: f32) -> FilmLevels {
        FilmLevels {
            generation: 1,
            passes_done: 5,
            max_cd_m2: max,
            p99_cd_m2: p99,
        }
    }

    #[test]
    fn all_zero_and_too_dark_get_different_hints() {
        let d = DisplaySettings::default();
        let zero = picture_hint(&levels(0.0, 0.0), true, &d, 0.0, &[2]).unwrap_or_default();
        assert!(zero.starts_with("Every pixel is 0 cd/m²"), "{zero}");
        assert!(zero.contains("Light 2 is outside"), "{zero}");
        assert_eq!(picture_hint(&levels(0.0, 0.0), false, &d, 0.0, &[]), None);
        let dark = picture_hint(&levels(50.0, 30.0), true, &d, -12.0, &[]).unwrap_or_default();
        assert!(dark.starts_with("Black at this exposure"), "{dark}");
        assert_eq!(picture_hint(&levels(50.0, 30.0), true, &d, 0.0, &[]), None);
        let auto = DisplaySettings {
            auto_exposure: true,
            ..d
        };
        assert_eq!(
            picture_hint(&levels(50.0, 30.0), true, &auto, -12.0, &[]),
            None
        );
    }
}
