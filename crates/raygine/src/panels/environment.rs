//! Environment: light from every direction beyond the scene. None, a uniform sky (luminance in
//! cd/m², colour) or a latitude-longitude map (read on a background job; its scale and a
//! thumbnail); for both, the turn about the scene's up axis and whether the camera sees the sky
//! behind the scene. Edited in place like the lights; a map is read through "Load map…".

use crate::command::{Command, Commands};
use crate::file_ops::DialogPurpose;
use tracer_core::display::REFERENCE_LUMINANCE;
use tracer_core::light::{Environment, EnvironmentMap, EnvironmentSource};
use tracer_core::scene::Setup;

/// A new uniform sky's luminance, cd/m²: light grey at the picture's exposure (a daylight
/// 1,000 cd/m² would be white in most scenes until the exposure is lowered), two significant
/// digits.
pub fn new_sky_cd_m2(exposure_stops: f32) -> f32 {
    let shown_grey = 0.5 * REFERENCE_LUMINANCE / exposure_stops.clamp(-40.0, 40.0).exp2();
    let step = 10f32.powf(shown_grey.log10().floor() - 1.0);
    (shown_grey / step).round() * step
}

/// The kinds the section offers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    None,
    Uniform,
    Map,
}

fn kind_of(env: Option<&Environment>) -> Kind {
    match env.map(|e| &e.source) {
        None => Kind::None,
        Some(EnvironmentSource::Uniform { .. }) => Kind::Uniform,
        Some(EnvironmentSource::Map(_)) => Kind::Map,
    }
}

/// The last sky of each kind shown, so None, Uniform and Map can be flipped through without
/// losing a sky's numbers or reading its map again.
#[derive(Debug, Default)]
pub struct EnvironmentMemory {
    uniform: Option<Environment>,
    map: Option<Environment>,
}

impl EnvironmentMemory {
    fn remember(&mut self, env: Option<&Environment>) {
        match kind_of(env) {
            Kind::None => {}
            Kind::Uniform => self.uniform = env.cloned(),
            Kind::Map => self.map = env.cloned(),
        }
    }

    /// The sky of kind `to` (turned and shown as `now` is; a first uniform sky of
    /// `new_sky_cd_m2`), or None when there is no map to go back to.
    fn switched(
        &self,
        now: Option<&Environment>,
        to: Kind,
        new_sky_cd_m2: f32,
    ) -> Option<Option<Environment>> {
        let remembered = match to {
            Kind::None => return Some(None),
            Kind::Uniform => self.uniform.clone().unwrap_or(Environment {
                source: EnvironmentSource::Uniform {
                    luminance_cd_m2: new_sky_cd_m2,
                    color: [1.0; 3],
                },
                scale: 1.0,
                rotation_deg: 0.0,
                background: true,
            }),
            Kind::Map => self.map.clone()?,
        };
        Some(Some(match now {
            Some(e) => Environment {
                rotation_deg: e.rotation_deg,
                background: e.background,
                ..remembered
            },
            None => remembered,
        }))
    }
}

/// What the section shows besides the setup it edits.
#[derive(Debug)]
pub struct EnvironmentView {
    /// The picture's exposure (a new uniform sky is made to show at it).
    pub exposure_stops: f32,
    /// A map is being read ("Load map…").
    pub loading_map: bool,
    /// The current map's thumbnail, once made.
    pub thumbnail: Option<egui::load::SizedTexture>,
}

/// The environment, edited in place; reading a map is asked for.
pub fn environment_ui(
    ui: &mut egui::Ui,
    setup: &mut Setup,
    view: EnvironmentView,
    memory: &mut EnvironmentMemory,
    out: &mut Commands,
) {
    memory.remember(setup.environment.as_ref());
    let current = kind_of(setup.environment.as_ref());
    let mut chosen = current;
    ui.horizontal(|ui| {
        ui.radio_value(&mut chosen, Kind::None, "None")
            .on_hover_text("No light from beyond the scene");
        ui.radio_value(&mut chosen, Kind::Uniform, "Uniform")
            .on_hover_text("The same luminance from every direction");
        ui.radio_value(&mut chosen, Kind::Map, "Map")
            .on_hover_text("A latitude-longitude .hdr or .exr image around the scene");
        if view.loading_map {
            ui.spinner().on_hover_text("Reading the map");
        }
    });
    if chosen != current {
        let new_sky = new_sky_cd_m2(view.exposure_stops);
        match memory.switched(setup.environment.as_ref(), chosen, new_sky) {
            Some(env) => setup.environment = env,
            None => out.push(Command::PromptPath(DialogPurpose::EnvironmentMap)),
        }
    }
    let Some(env) = &mut setup.environment else {
        return;
    };
    let Environment {
        source,
        scale,
        rotation_deg,
        background,
    } = env;
    match source {
        EnvironmentSource::Uniform {
            luminance_cd_m2,
            color,
        } => uniform_ui(ui, luminance_cd_m2, color),
        EnvironmentSource::Map(map) => map_ui(ui, map, scale, view.thumbnail, out),
    }
    ui.add(
        egui::Slider::new(rotation_deg, -180.0..=180.0)
            .text("rotation (°)")
            // A sidecar's 270° stays 270° until the slider is moved.
            .clamping(egui::SliderClamping::Edits)
            .update_while_editing(false),
    )
    .on_hover_text(
        "Turn of the sky about the scene's up axis, degrees (a uniform sky looks the same \
         at any turn; the turn is kept for a map)",
    );
    ui.checkbox(background, "Sky as background").on_hover_text(
        "Camera rays that leave the scene see the sky. Off: the viewer's backdrop stays \
         behind the scene (the sky still lights it)",
    );
}

/// A uniform sky's luminance (a drag changes it by about 0.5 % a point; ÷2 and ×2) and tint.
fn uniform_ui(ui: &mut egui::Ui, luminance_cd_m2: &mut f32, color: &mut [f32; 3]) {
    ui.horizontal(|ui| {
        let label = ui.label("luminance");
        let speed = f64::from(luminance_cd_m2.abs().max(1e-6)) * 0.005;
        let decimals = (2 - luminance_cd_m2.abs().max(1e-9).log10().floor() as i32).clamp(0, 9);
        ui.add(
            egui::DragValue::new(luminance_cd_m2)
                .speed(speed)
                .range(0.0..=1.0e9)
                .max_decimals(decimals as usize)
                .suffix(" cd/m²")
                .update_while_editing(false),
        )
        .labelled_by(label.id)
        .on_hover_text(
            "Luminance of the sky in every direction, cd/m² (overcast daylight: a few \
             thousand). Drag for fine changes, or double-click and type",
        );
        if ui
            .small_button("÷2")
            .on_hover_text("Halve the sky's luminance")
            .clicked()
        {
            *luminance_cd_m2 *= 0.5;
        }
        if ui
            .small_button("×2")
            .on_hover_text("Double the sky's luminance")
            .clicked()
        {
            *luminance_cd_m2 *= 2.0;
        }
    });
    ui.horizontal(|ui| {
        ui.color_edit_button_rgb(color);
        ui.label("sky colour (tint, normalised to luminance 1)");
    });
}

/// The map's file and size, "Load map…", its scale and thumbnail.
fn map_ui(
    ui: &mut egui::Ui,
    map: &EnvironmentMap,
    scale: &mut f32,
    thumbnail: Option<egui::load::SizedTexture>,
    out: &mut Commands,
) {
    ui.horizontal(|ui| {
        let name = map.file.file_name().map_or_else(
            || map.file.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        ui.label(format!("{name}, {} × {} px", map.width, map.height))
            .on_hover_text(map.file.display().to_string());
        if ui
            .button("Load map…")
            .on_hover_text("Read another latitude-longitude .hdr or .exr map")
            .clicked()
        {
            out.push(Command::PromptPath(DialogPurpose::EnvironmentMap));
        }
    });
    ui.horizontal(|ui| {
        let label = ui.label("scale");
        let speed = f64::from(scale.abs().max(1e-6)) * 0.005;
        let decimals = (2 - scale.abs().max(1e-9).log10().floor() as i32).clamp(0, 9);
        ui.add(
            egui::DragValue::new(scale)
                .speed(speed)
                .range(0.0..=1.0e9)
                .max_decimals(decimals as usize)
                .update_while_editing(false),
        )
        .labelled_by(label.id)
        .on_hover_text(
            "Luminance in cd/m² of a texel whose value has luminance 1 (maps in W/(sr·m²), \
             as Radiance writes them: 179)",
        );
        ui.label("cd/m² per unit");
    });
    let width = ui.available_width().clamp(64.0, 256.0);
    let size = egui::vec2(width, width / 2.0);
    match thumbnail {
        Some(texture) => {
            ui.add(egui::Image::new(texture).fit_to_exact_size(size))
                .on_hover_text(
                    "The map as stored: the top edge is straight up, the middle looks along \
                     −Z before the rotation",
                );
        }
        None => {
            ui.allocate_ui(size, |ui| {
                ui.centered_and_justified(|ui| ui.spinner());
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Flipping through the kinds keeps each sky's numbers and carries the turn and the
    /// background choice across; Map without a map read yet asks for one.
    #[test]
    fn switching_kinds_remembers_each_sky() {
        let mut memory = EnvironmentMemory::default();
        assert_eq!(memory.switched(None, Kind::Map, 50.0), None);
        let uniform = memory.switched(None, Kind::Uniform, 50.0).flatten();
        let Some(mut sky) = uniform else {
            panic!("a uniform sky");
        };
        assert_eq!(
            sky.source,
            EnvironmentSource::Uniform {
                luminance_cd_m2: 50.0,
                color: [1.0; 3]
            }
        );
        sky.source = EnvironmentSource::Uniform {
            luminance_cd_m2: 5.0,
            color: [1.0, 0.5, 0.5],
        };
        memory.remember(Some(&sky));
        let turned = Environment {
            rotation_deg: 30.0,
            background: false,
            ..sky.clone()
        };
        let back = memory
            .switched(Some(&turned), Kind::Uniform, 50.0)
            .flatten();
        assert_eq!(back, Some(turned));
        assert_eq!(memory.switched(Some(&sky), Kind::None, 50.0), Some(None));
    }

    /// A new sky shows light grey at the exposure: 50 cd/m² at 0 stops, 4× less at +2 stops,
    /// in two significant digits.
    #[test]
    fn a_new_sky_suits_the_exposure() {
        assert_eq!(new_sky_cd_m2(0.0), 50.0);
        assert_eq!(new_sky_cd_m2(2.0), 13.0);
        assert_eq!(new_sky_cd_m2(-0.197), 57.0);
        assert!((new_sky_cd_m2(10.0) - 0.049).abs() < 1e-6);
    }
}
