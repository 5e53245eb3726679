//! What the app shows to its UI tests and smoke scripts: read-only views of its state, and the
//! few inputs a test cannot give through widgets (values panels edit in place, a finished native
//! dialog, a machine without the denoiser). Everything else a test does goes through the
//! widgets, the keyboard or [`RaygineApp::apply`], as a user's actions do.

use super::RaygineApp;
use crate::denoise_view::{Availability, DenoiseView};
use crate::document::Document;
use crate::file_ops::{DialogPurpose, PendingDialog};
use crate::history::History;
use crate::measure_worker::MeasureWorker;
use crate::panels::{PathPrompt, RenderImageForm, RenderPrefs};
use crate::prefs::Prefs;
use crate::render_worker::RenderWorker;
use crate::unsaved::Switch;
use crate::viewport_ui::HoverInfo;
use std::path::PathBuf;
use std::time::Duration;
use tracer_core::display::DisplaySettings;
use tracer_core::scene::Setup;

/// Reading the state.
impl RaygineApp {
    /// The open scene, its setup, path and warnings.
    pub fn document(&self) -> &Document {
        &self.doc
    }

    pub fn history(&self) -> &History {
        &self.history
    }

    /// The background render: generations, statistics and the film.
    pub fn worker(&self) -> &RenderWorker {
        &self.worker
    }

    /// The grids' background measurement.
    /// The observers' latest glare (None while the first refinement runs).
    pub fn glare_readings(&self) -> Option<crate::glare_worker::GlareReadings> {
        self.glare.readings()
    }

    pub fn measure(&self) -> &MeasureWorker {
        &self.measure
    }

    pub fn denoise(&self) -> &DenoiseView {
        &self.denoise
    }

    pub fn render_prefs(&self) -> &RenderPrefs {
        &self.render
    }

    /// The display settings as the user set them (see `effective_display` for what is shown).
    pub fn display(&self) -> &DisplaySettings {
        &self.display
    }

    /// The preferences kept between runs (recent files, exposures per scene).
    pub fn prefs(&self) -> &Prefs {
        &self.prefs
    }

    /// The egui context the app draws with.
    pub fn context(&self) -> &egui::Context {
        &self.ctx
    }

    /// The error banner's text, while it shows.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// The notice banner's text, while it shows.
    pub fn notice(&self) -> Option<&str> {
        self.notice.as_deref()
    }

    /// Why the picture is black, when it is.
    pub fn picture_hint(&self) -> Option<&str> {
        self.picture_hint.as_deref()
    }

    /// Whether the last frame drew a picture.
    pub fn picture_drawn(&self) -> bool {
        self.picture_drawn
    }

    /// The scene's exposure is held (set automatically once, or by the user).
    pub fn exposure_held(&self) -> bool {
        self.exposure.held()
    }

    pub fn false_colour_on(&self) -> bool {
        self.false_colour.enabled
    }

    pub fn paused(&self) -> bool {
        self.paused
    }

    pub fn selected_slot(&self) -> Option<u32> {
        self.selected_slot
    }

    /// The path window, while it is open.
    pub fn prompt(&self) -> Option<&PathPrompt> {
        self.prompt.as_ref()
    }

    /// A scene switch or quit waiting for the user's answer about unsaved edits.
    pub fn pending_switch(&self) -> Option<&Switch> {
        self.pending_switch.as_ref()
    }

    /// A scene is being read in the background.
    pub fn loading(&self) -> bool {
        self.loading.is_some()
    }

    /// Files still being written in the background.
    pub fn writing(&self) -> bool {
        !self.writes.is_empty()
    }

    /// A measurement report waits for its screenshot.
    pub fn report_pending(&self) -> bool {
        self.report.is_some()
    }

    /// A "Render image…" job runs.
    pub fn rendering_image(&self) -> bool {
        self.render_image_job.is_some()
    }

    pub fn side_panel_shown(&self) -> bool {
        self.show_controls
    }

    /// The Materials panel's filter text.
    pub fn part_filter(&self) -> &str {
        &self.panels.part_filter
    }

    /// The film size of the viewport, pixels.
    pub fn viewport_px(&self) -> [u32; 2] {
        self.viewport_px
    }

    /// What the current orbit turns about, while dragging.
    pub fn orbit_pivot(&self) -> Option<glam::Vec3> {
        self.orbit_pivot
    }

    /// The luminance meter's rectangle.
    pub fn meter(&self) -> Option<crate::luminance_meter::Meter> {
        self.meter
    }

    /// The read-out under the pointer.
    pub fn hover(&self) -> Option<&HoverInfo> {
        self.hover.as_ref()
    }

    /// The size (pixels) of the Environment section's thumbnail of the current map, once made.
    pub fn map_thumbnail_size(&self) -> Option<[usize; 2]> {
        match self.doc.setup.environment.as_ref().map(|e| &e.source) {
            Some(tracer_core::light::EnvironmentSource::Map(map)) => {
                self.map_thumbnails.get(map).map(egui::TextureHandle::size)
            }
            _ => None,
        }
    }
}

/// Inputs a test gives where a user would use a widget or the system.
impl RaygineApp {
    /// The setup, edited in place as the panels' widgets edit it; the next frame restarts the
    /// render and makes the change an undo step.
    pub fn setup_mut(&mut self) -> &mut Setup {
        &mut self.doc.setup
    }

    /// The render settings, as the Render panel edits them.
    pub fn render_prefs_mut(&mut self) -> &mut RenderPrefs {
        &mut self.render
    }

    /// The display settings, as the Display panel edits them.
    pub fn display_mut(&mut self) -> &mut DisplaySettings {
        &mut self.display
    }

    /// Turn the false-colour view on or off, as its checkbox does.
    pub fn set_false_colour(&mut self, on: bool) {
        self.false_colour.enabled = on;
    }

    /// The luminaire path field of the Lights panel, as typed.
    pub fn set_luminaire_path(&mut self, path: &str) {
        path.clone_into(&mut self.panels.luminaire_path);
    }

    /// Fill the "Render image…" form, as its fields do.
    pub fn fill_render_image_form(&mut self, form: RenderImageForm) {
        self.render_image_form = Some(form);
    }

    /// Open the keyboard-shortcut help window.
    pub fn show_help(&mut self) {
        self.show_help = true;
    }

    /// Where the scene is saved (a scratch folder in tests), without reading it.
    pub fn set_document_path(&mut self, path: PathBuf) {
        self.doc.path = Some(path);
    }

    /// The native dialog for `purpose` came back with `picked` (what rfd reports; a test cannot
    /// open a real dialog).
    pub fn finish_dialog(&mut self, purpose: DialogPurpose, picked: Option<PathBuf>) {
        self.dialog = Some(PendingDialog::finished(purpose, picked));
    }

    /// As a machine without (or with) the denoiser library would have it.
    pub fn set_denoiser_availability(&mut self, availability: Availability) {
        self.denoise.availability = availability;
    }

    /// How long a notice stays on screen.
    pub fn set_notice_duration(&mut self, ttl: Duration) {
        self.banners.notice_ttl = ttl;
    }
}
