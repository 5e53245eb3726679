//! The side panel, menu bar, status bar and windows of the viewer. Each draws what it is given,
//! edits the values it is handed (the document's setup, view settings, its own state) and returns
//! everything else the user asked for as [`Command`]s, which the app applies.

mod camera;
mod daylight;
mod environment;
mod frame;
mod glare;
mod lights;
pub mod materials;
mod measure;
mod menu;
mod notes;
mod observers;
mod polar;
mod reflectance;
mod render;
mod status;
mod texture_maps;
mod widgets;
mod windows;

pub use environment::{EnvironmentMemory, new_sky_cd_m2};
pub use lights::MANY_LIGHTS;
pub use measure::MeasureView;
pub use menu::{MenuBar, menu_bar};
pub use notes::notes_ui;
pub use render::{FalseColourUi, RenderPrefs};
pub use status::{StatusBar, status_bar};
pub use windows::{PathPrompt, RenderImageForm, Windows, windows_ui};

use crate::command::{Command, Commands};
use crate::document::Document;
use crate::unsaved::Switch;
use frame::frame_ui;
use tracer_core::display::DisplaySettings;

/// The panels' own state, kept from frame to frame.
#[derive(Debug, Default)]
pub struct PanelState {
    /// The Lights panel's luminaire file field.
    pub luminaire_path: String,
    /// The light the Lights panel edits when there are too many to show them all.
    pub selected_light: usize,
    /// The side panel scrolls back to its top on the next frame (a scene was opened).
    pub scroll_to_top: bool,
    /// Whether the Notes window (the scene's load warnings) is open.
    pub show_notes: bool,
    /// The Materials panel's filter of breps and parts.
    pub part_filter: String,
    /// Thumbnails of the open scene's textures.
    pub texture_thumbnails: texture_maps::TextureThumbnails,
    /// The Environment section's last sky of each kind.
    pub environment: EnvironmentMemory,
    /// The Daylight section's draft of `[daylight]`.
    pub daylight: daylight::DaylightDraft,
    /// How glare is judged (the Glare section).
    pub glare: tracer_core::glare::GlareOptions,
}

/// What the side panel shows and edits: the document (its setup edited in place; the app makes
/// one undo step of each finished interaction), the render and display settings.
#[derive(Debug)]
pub struct SidePanel<'a> {
    pub doc: &'a mut Document,
    /// Whether a scene is being loaded (the unit cannot change meanwhile).
    pub loading: bool,
    pub render: &'a mut RenderPrefs,
    pub display: &'a mut DisplaySettings,
    pub false_colour: &'a mut FalseColourUi,
    pub denoise: &'a mut crate::denoise_view::DenoiseView,
    pub show_grids: &'a mut bool,
    /// The grids read daylight factors.
    pub daylight_factor: &'a mut bool,
    pub measure: MeasureView,
    /// The observers' latest glare (None while the first refinement runs).
    pub glare: Option<crate::glare_worker::GlareReadings>,
    pub state: &'a mut PanelState,
    /// A luminaire file is being read ("Add luminaire").
    pub adding_luminaire: bool,
    /// An environment map is being read ("Load map…").
    pub loading_environment: bool,
    /// The environment map's thumbnail, once made.
    pub environment_thumbnail: Option<egui::load::SizedTexture>,
    /// The viewport's width over its height.
    pub viewport_aspect: f32,
}

/// All control groups of the side panel.
pub fn controls_ui(ui: &mut egui::Ui, p: SidePanel<'_>, out: &mut Commands) {
    let SidePanel {
        doc,
        loading,
        render,
        display,
        false_colour,
        denoise,
        show_grids,
        daylight_factor,
        measure,
        glare,
        state,
        adding_luminaire,
        loading_environment,
        environment_thumbnail,
        viewport_aspect,
    } = p;
    ui.heading(doc.scene.name.clone());
    ui.label(format!(
        "{}, {} breps",
        doc.scene.triangles_label(),
        doc.scene.breps.len(),
    ));
    let diagonal = doc.scene.bounds.extent().length();
    if let Some(unit) = frame_ui(ui, &mut doc.setup, diagonal, loading) {
        out.push(Command::Switch(Switch::Unit(unit)));
    }
    ui.separator();
    let selected_slot = measure.selected_slot;
    // Many lights (a room's nine luminaires) would push the rest out of sight: folded then.
    egui::CollapsingHeader::new("Lights")
        .default_open(doc.setup.lights.len() <= 3)
        .show(ui, |ui| {
            lights::lights_ui(
                ui,
                doc,
                &mut state.luminaire_path,
                &mut state.selected_light,
                adding_luminaire,
                out,
            );
        });
    // Open where the scene has a sky or daylight; each scene keeps its own fold.
    egui::CollapsingHeader::new("Environment")
        .id_salt(("environment", doc.path.clone()))
        .default_open(doc.setup.environment.is_some() || doc.setup.daylight.is_some())
        .show(ui, |ui| {
            let view = environment::EnvironmentView {
                exposure_stops: display.exposure_stops,
                loading_map: loading_environment,
                thumbnail: environment_thumbnail,
            };
            environment::environment_ui(ui, &mut doc.setup, view, &mut state.environment, out);
            // Daylight (a sky and the sun for a place and time) is part of it: a daylight sky
            // is the environment.
            ui.separator();
            ui.strong("Daylight");
            daylight::daylight_ui(ui, &mut doc.setup, &mut state.daylight);
        });
    egui::CollapsingHeader::new("Camera")
        .default_open(true)
        .show(ui, |ui| {
            camera::camera_ui(ui, doc, render.integrator, viewport_aspect, out)
        });
    egui::CollapsingHeader::new("Materials")
        .default_open(true)
        .show(ui, |ui| {
            materials::materials_ui(
                ui,
                doc,
                selected_slot,
                &mut state.part_filter,
                &mut state.texture_thumbnails,
                out,
            )
        });
    egui::CollapsingHeader::new("Measure")
        .default_open(false)
        .show(ui, |ui| {
            measure::measure_ui(ui, doc, measure, show_grids, daylight_factor, out)
        });
    egui::CollapsingHeader::new("Glare")
        .id_salt(("glare", doc.path.clone()))
        .default_open(!doc.setup.observers.is_empty())
        .show(ui, |ui| glare::glare_ui(ui, doc, glare, &mut state.glare));
    egui::CollapsingHeader::new("Render")
        .default_open(true)
        .show(ui, |ui| {
            render::render_ui(
                ui,
                doc.setup.camera.projection,
                render,
                display,
                false_colour,
            );
            render::denoise_ui(ui, denoise, render.integrator, false_colour.enabled);
        });
}
