//! The viewer application: state, the per-frame loop, shortcuts and file actions. Panels and
//! the viewport draw in their own modules.

use crate::document::Document;
use crate::file_ops::{DialogPurpose, PendingDialog, PendingLoad, PendingWrite, start_write};
use crate::history::History;
use crate::prefs::{PREFS_KEY, Prefs};
use crate::render_worker::{RenderKey, RenderWorker, exposure_stops, map_rect};
use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use tracer_core::display::{
    DisplaySettings, FalseColour, FalseColourQuantity, FalseColourScale, ToneMap,
};
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::RenderSettings;
use tracer_core::scene::{Setup, Sidecar, framing_camera, sidecar_path};

pub use crate::shortcuts::{
    SHORTCUT_EXPORT, SHORTCUT_OPEN, SHORTCUT_QUIT, SHORTCUT_REDO, SHORTCUT_SAVE, SHORTCUT_UNDO,
};

/// The narrowest the viewport gets while the side panel is shown, points.
pub const MIN_VIEWPORT_WIDTH: f32 = 320.0;

/// How the viewer starts.
#[derive(Clone, Debug, Default)]
pub struct AppOptions {
    /// Scene to open; else the last scene (if it still exists), else the built-in Cornell box.
    pub scene: Option<PathBuf>,
    /// Render threads (0: all cores).
    pub threads: usize,
    /// Do not reopen the last scene (tests, smoke runs).
    pub ignore_last_scene: bool,
    /// The length unit of the scene opened at start (`--units`); wins over its sidecar.
    pub unit: Option<tracer_core::scene::LengthUnit>,
}

/// Render preferences that restart the render when changed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderPrefs {
    /// Light transport: global illumination by default in the viewer.
    pub integrator: IntegratorKind,
    pub max_depth: u32,
    pub target_spp: u32,
    /// Film pixels per screen pixel (0.25 ..= 1).
    pub resolution_scale: f32,
    pub threads: usize,
}

/// The false-colour view as edited in the panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FalseColourUi {
    pub enabled: bool,
    pub quantity: FalseColourQuantity,
    pub scale: FalseColourScale,
    pub min: f32,
    pub max: f32,
}

/// A finished or running "Render image..." job.
#[derive(Debug)]
pub struct RenderImageJob {
    pub worker: tracer_core::render::RenderSession,
    pub path: PathBuf,
    pub display: DisplaySettings,
    pub started: Instant,
}

/// Values the "Render image..." window edits.
#[derive(Clone, Debug)]
pub struct RenderImageForm {
    pub width: u32,
    pub height: u32,
    pub samples: u32,
    pub path: String,
}

/// What the path window (typed path, with a Browse... button for the native dialog) is for.
#[derive(Clone, Debug)]
pub struct PathPrompt {
    pub purpose: DialogPurpose,
    pub text: String,
    /// Set when the file exists and the user must confirm overwriting it.
    pub confirm_overwrite: bool,
    /// The path field takes keyboard focus on the next frame (set when the window opens).
    pub focus_field: bool,
    /// Why Browse… did not help (no desktop file dialog), shown in the window.
    pub note: Option<String>,
}

/// What the mouse points at in the viewport.
#[derive(Clone, Debug, Default)]
pub struct HoverInfo {
    pub luminance: f32,
    pub illuminance: f32,
    pub surface: Option<String>,
    pub pixel: [u32; 2],
}

pub struct RaygineApp {
    /// The egui context, for waking the UI from background threads.
    pub ctx: egui::Context,
    pub doc: Document,
    pub history: History,
    pub render: RenderPrefs,
    pub display: DisplaySettings,
    pub false_colour: FalseColourUi,
    pub worker: RenderWorker,
    pub prefs: Prefs,
    pub selected_slot: Option<u32>,
    pub error: Option<String>,
    pub notice: Option<String>,
    /// When the error and the notice appeared; they expire or are dismissed.
    pub banners: crate::banners::Banners,
    pub loading: Option<PendingLoad>,
    pub dialog: Option<PendingDialog>,
    pub writes: Vec<PendingWrite>,
    pub prompt: Option<PathPrompt>,
    pub render_image_form: Option<RenderImageForm>,
    pub render_image_job: Option<RenderImageJob>,
    pub hover: Option<HoverInfo>,
    pub paused: bool,
    pub show_help: bool,
    /// Whether the side panel is shown (View > Side panel hides it for a small window).
    pub show_controls: bool,
    /// The setup as loaded or last saved: anything else is an unsaved edit.
    pub saved_setup: Setup,
    /// A scene switch or quit waiting for the user's answer about unsaved edits.
    pub pending_switch: Option<crate::unsaved::Switch>,
    /// The user agreed to close: the window's close request goes through.
    allow_close: bool,
    /// The grids' background measurement (Measure panel, grid overlay).
    pub measure: crate::measure_worker::MeasureWorker,
    /// Whether grid readings are drawn over the picture.
    pub show_grids: bool,
    /// The luminance meter's rectangle (Ctrl+drag over the picture), film pixels.
    pub meter: Option<crate::luminance_meter::Meter>,
    /// Where the current Ctrl+drag started (film position).
    pub meter_anchor: Option<(f32, f32)>,
    /// The viewport's screen rectangle in the last frame (points), for reports.
    pub viewport_rect: Option<egui::Rect>,
    /// A measurement report waiting for its screenshot.
    pub report: Option<crate::report::ReportStatus>,
    /// Film size of the viewport, pixels.
    pub viewport_px: [u32; 2],
    /// Whether the last frame drew a picture (only ever one of the scene open).
    pub picture_drawn: bool,
    /// The film's brightness at the last pass measured (for `picture_hint`).
    pub film_levels: Option<crate::picture_hints::FilmLevels>,
    /// Why the picture is black, when it is.
    pub picture_hint: Option<String>,
    /// Recent UI frame intervals while rendering (for the p95 in the status bar).
    pub frame_times: VecDeque<f32>,
    /// Time the app itself spent in recent frames while rendering (the rest is egui's
    /// tessellation, OpenGL and waiting for the next frame).
    pub frame_work: VecDeque<f32>,
    last_frame: Option<Instant>,
    frame_log: Option<Instant>,
}

impl std::fmt::Debug for RaygineApp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RaygineApp")
            .field("scene", &self.doc.title())
            .finish_non_exhaustive()
    }
}

impl RaygineApp {
    /// Builds the app; reads persisted preferences when the integration has storage.
    pub fn new(cc: &eframe::CreationContext<'_>, options: AppOptions) -> anyhow::Result<Self> {
        let prefs: Prefs = cc
            .storage
            .and_then(|s| eframe::get_value(s, PREFS_KEY))
            .unwrap_or_default();
        let doc = Document::builtin()?;
        let saved_setup = doc.setup.clone();
        let threads = options.threads;
        let worker = RenderWorker::new(&cc.egui_ctx, threads)?;
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let mut app = Self {
            ctx: cc.egui_ctx.clone(),
            history: History::new(&doc.setup),
            doc,
            render: RenderPrefs {
                integrator: IntegratorKind::from_name(&prefs.integrator)
                    .unwrap_or_else(Self::default_integrator),
                max_depth: prefs.max_depth.min(64),
                target_spp: prefs.target_spp.clamp(1, 65_536),
                resolution_scale: prefs.resolution_scale.clamp(0.25, 1.0),
                threads: if threads == 0 { cores } else { threads },
            },
            display: DisplaySettings {
                exposure_stops: if prefs.exposure_stops.is_finite() {
                    prefs.exposure_stops
                } else {
                    0.0
                },
                auto_exposure: prefs.auto_exposure,
                tone_map: ToneMap::from_name(&prefs.tone_map).unwrap_or_default(),
                false_colour: None,
            },
            false_colour: FalseColourUi {
                enabled: false,
                quantity: FalseColourQuantity::Illuminance,
                scale: FalseColourScale::Log,
                min: 1.0,
                max: 10_000.0,
            },
            worker,
            prefs,
            selected_slot: None,
            error: None,
            notice: None,
            banners: crate::banners::Banners::default(),
            loading: None,
            dialog: None,
            writes: Vec::new(),
            prompt: None,
            render_image_form: None,
            render_image_job: None,
            hover: None,
            paused: false,
            show_help: false,
            show_controls: true,
            saved_setup,
            pending_switch: None,
            allow_close: false,
            measure: crate::measure_worker::MeasureWorker::default(),
            show_grids: true,
            meter: None,
            meter_anchor: None,
            viewport_rect: None,
            report: None,
            viewport_px: [0, 0],
            picture_drawn: false,
            film_levels: None,
            picture_hint: None,
            frame_times: VecDeque::new(),
            frame_work: VecDeque::new(),
            last_frame: None,
            frame_log: std::env::var_os("RAYGINE_FRAME_STATS").map(|_| Instant::now()),
        };
        let start_scene = options.scene.or_else(|| {
            if options.ignore_last_scene {
                None
            } else {
                app.prefs.last_scene.clone().filter(|p| p.is_file())
            }
        });
        match (start_scene, options.unit) {
            (Some(path), unit) => app.open_path_in_unit(&path, unit),
            (None, Some(unit)) => app.set_unit(unit),
            (None, None) => {}
        }
        Ok(app)
    }

    /// The light transport a new user starts with: global illumination, bidirectional (lamps
    /// close to surfaces converge in seconds, as in the built-in Cornell box).
    pub fn default_integrator() -> IntegratorKind {
        IntegratorKind::Bidirectional
    }

    /// Starts loading a scene in the background; the current scene stays until it succeeds.
    pub fn open_path(&mut self, path: &Path) {
        self.loading = Some(PendingLoad::start(path, None, &self.ctx));
    }

    /// Shows another scene: fresh history, no selection, and rendering resumed, so the new scene
    /// gets a picture (the old scene's picture is never shown for it).
    pub fn replace_document(&mut self, doc: Document) {
        self.history = History::new(&doc.setup);
        self.saved_setup = doc.setup.clone();
        self.doc = doc;
        self.selected_slot = None;
        self.meter = None;
        if self.paused {
            self.paused = false;
            self.worker.set_paused(false);
        }
    }

    /// [`RaygineApp::open_path`] with the scene's length unit given.
    pub fn open_path_in_unit(&mut self, path: &Path, unit: Option<tracer_core::scene::LengthUnit>) {
        self.loading = Some(PendingLoad::start(path, unit, &self.ctx));
    }

    /// Reads the scene again in another length unit: distances, the default light and camera
    /// follow it (edits not saved in the sidecar are dropped, as on reopening).
    pub fn set_unit(&mut self, unit: tracer_core::scene::LengthUnit) {
        match self.doc.path.clone() {
            Some(path) => self.open_path_in_unit(&path, Some(unit)),
            None => match tracer_core::scene::builtin_cornell_box(Some(unit)) {
                Ok(loaded) => {
                    let doc = Document::from_loaded(loaded, None);
                    self.notice = load_notice(&doc.warnings);
                    self.replace_document(doc);
                }
                Err(e) => self.error = Some(format!("cannot build the Cornell box: {e}")),
            },
        }
    }

    /// Whether the setup differs from what was loaded or last saved.
    pub fn has_unsaved_edits(&self) -> bool {
        self.doc.setup != self.saved_setup
    }

    /// Switches scenes or quits, asking first when that would drop unsaved edits.
    pub fn request(&mut self, switch: crate::unsaved::Switch) {
        if self.has_unsaved_edits() {
            self.pending_switch = Some(switch);
        } else {
            self.perform(switch);
        }
    }

    fn perform(&mut self, switch: crate::unsaved::Switch) {
        use crate::unsaved::Switch;
        match switch {
            Switch::Open(path) => self.open_path(&path),
            Switch::Builtin => match Document::builtin() {
                Ok(doc) => self.replace_document(doc),
                Err(e) => self.error = Some(format!("cannot build the Cornell box: {e:#}")),
            },
            Switch::Unit(unit) => self.set_unit(unit),
            Switch::Quit => {
                self.allow_close = true;
                self.ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
    }

    /// Applies the answer of the unsaved-edits window.
    fn answer_unsaved(&mut self, ctx: &egui::Context) {
        use crate::unsaved::Choice;
        let Some(switch) = self.pending_switch.clone() else {
            return;
        };
        let can_save = self.doc.path.is_some();
        match crate::unsaved::unsaved_ui(ctx, &switch, can_save) {
            Some(Choice::Save) => {
                if let Some(p) = self.doc.path.clone() {
                    self.save_sidecar(ctx, sidecar_path(&p));
                }
                self.pending_switch = None;
                self.perform(switch);
            }
            Some(Choice::Discard) => {
                self.pending_switch = None;
                self.perform(switch);
            }
            Some(Choice::Cancel) => self.pending_switch = None,
            None => {}
        }
    }

    /// Waits for a pending load (tests and scripts only; the UI never calls this).
    pub fn finish_loading_blocking(&mut self, timeout: Duration) {
        let deadline = Instant::now() + timeout;
        while self.loading.is_some() && Instant::now() < deadline {
            self.poll_background();
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// The render settings of the viewport at its current size.
    pub fn render_settings(&self) -> RenderSettings {
        RenderSettings {
            width: self.viewport_px[0].max(1),
            height: self.viewport_px[1].max(1),
            samples_per_pixel: self.render.target_spp,
            max_depth: self.render.max_depth,
            integrator: self.render.integrator,
            max_bounces: None,
            pixel_illuminance: true,
        }
    }

    /// The display mapping in force: the display settings plus the false-colour view.
    pub fn effective_display(&self) -> DisplaySettings {
        let fc = self.false_colour;
        DisplaySettings {
            false_colour: fc.enabled.then_some(FalseColour {
                quantity: fc.quantity,
                scale: fc.scale,
                min: fc.min,
                max: fc.max,
            }),
            ..self.display
        }
    }

    /// Replaces the setup (undo, redo) and clears a selection that no longer exists.
    fn set_setup(&mut self, setup: Setup) {
        self.doc.setup = setup;
    }

    pub fn undo(&mut self) {
        if let Some(s) = self.history.undo(&self.doc.setup) {
            self.set_setup(s);
        }
    }

    pub fn redo(&mut self) {
        if let Some(s) = self.history.redo(&self.doc.setup) {
            self.set_setup(s);
        }
    }

    /// Resets the camera to frame the scene (keeps the field of view).
    pub fn frame_scene(&mut self) {
        let fov = self.doc.setup.camera.fov_deg;
        self.doc.setup.camera = framing_camera(&self.doc.scene, fov);
    }

    /// Checks background work: loads, dialogs, writes, the render-image job.
    pub fn poll_background(&mut self) {
        if let Some(result) = self.loading.as_ref().and_then(PendingLoad::poll) {
            let path = self.loading.take().map(|l| l.path);
            match result {
                Ok(loaded) => {
                    let doc = Document::from_loaded(loaded, path.clone());
                    // The viewer has its own unit control.
                    self.notice = load_notice(&doc.warnings).map(|n| {
                        n.replace(
                            "pass --units",
                            "choose the unit at the top of the side panel:",
                        )
                    });
                    self.replace_document(doc);
                    self.error = None;
                    if let Some(p) = path {
                        self.prefs.add_recent(&p);
                        self.prefs.last_scene = Some(p);
                    }
                }
                Err(e) => self.error = Some(e),
            }
        }
        if let Some(result) = self.dialog.as_ref().and_then(PendingDialog::poll) {
            let quick = self.dialog.as_ref().is_some_and(|d| {
                d.started.elapsed().as_secs_f32() < crate::file_ops::NO_DIALOG_SECS
            });
            let purpose = self.dialog.take().map(|d| d.purpose);
            // A dialog that could not run is an error, not "cancelled".
            let (picked, quick) = match result {
                Ok(picked) => (picked, quick),
                Err(e) => {
                    self.error = Some(e);
                    (None, false)
                }
            };
            if picked.is_none()
                && quick
                && let Some(p) = &mut self.prompt
            {
                // The typed path stays; say why nothing opened.
                p.note = Some(
                    "No file dialog opened: this desktop has no file-dialog service (an XDG \
                     desktop portal). Type the path above instead."
                        .to_owned(),
                );
            }
            if let (Some(path), Some(purpose)) = (picked, purpose) {
                match &mut self.prompt {
                    Some(p) if p.purpose == purpose => p.text = path.display().to_string(),
                    _ => {
                        self.prompt = Some(PathPrompt {
                            purpose,
                            text: path.display().to_string(),
                            confirm_overwrite: false,
                            focus_field: true,
                            note: None,
                        });
                    }
                }
                if purpose == DialogPurpose::Open {
                    self.prompt = None;
                    self.request(crate::unsaved::Switch::Open(path));
                }
            }
        }
        let mut still = Vec::new();
        for w in self.writes.drain(..) {
            match w.poll() {
                Some(Ok(msg)) => self.notice = Some(msg),
                Some(Err(e)) => self.error = Some(e),
                None => still.push(w),
            }
        }
        self.writes = still;
        self.poll_render_image();
    }

    fn poll_render_image(&mut self) {
        let Some(job) = &self.render_image_job else {
            return;
        };
        let stats = job.worker.stats();
        if !(stats.finished && stats.generation == job.worker.generation()) {
            return;
        }
        let Some(job) = self.render_image_job.take() else {
            return;
        };
        let film = job.worker.with_film(|f| f.map(|f| f.accum.clone()));
        let Some(film) = film else {
            self.error = Some("the render produced no image".to_owned());
            return;
        };
        let display = job.display;
        let path = job.path;
        let secs = job.started.elapsed().as_secs_f64();
        self.writes.push(start_write(&self.ctx, move || {
            let rgba = display.map_film(&film);
            tracer_core::export::write_png(&path, rgba, film.width, film.height)
                .map(|()| {
                    format!(
                        "rendered {}x{} in {secs:.1} s, wrote {}",
                        film.width,
                        film.height,
                        path.display()
                    )
                })
                .map_err(|e| e.to_string())
        }));
    }

    /// Suggested file for an export or save.
    pub fn suggested_path(&self, purpose: DialogPurpose) -> PathBuf {
        let base = self
            .doc
            .path
            .clone()
            .unwrap_or_else(|| PathBuf::from("cornell_box.shp"));
        match purpose {
            DialogPurpose::Open => base,
            DialogPurpose::ExportPng | DialogPurpose::RenderImage => base.with_extension("png"),
            DialogPurpose::ExportExr => base.with_extension("exr"),
            DialogPurpose::SaveSidecar => sidecar_path(&base),
        }
    }

    /// Opens the path window for `purpose` (typed path; Browse... runs the native dialog).
    pub fn prompt_path(&mut self, purpose: DialogPurpose) {
        let text = match purpose {
            DialogPurpose::Open => String::new(),
            p => self.suggested_path(p).display().to_string(),
        };
        self.prompt = Some(PathPrompt {
            purpose,
            text,
            confirm_overwrite: false,
            focus_field: true,
            note: None,
        });
    }

    /// Runs the action of a path window once the user confirmed a path.
    pub fn run_path_action(&mut self, ctx: &egui::Context, purpose: DialogPurpose, path: PathBuf) {
        match purpose {
            DialogPurpose::Open => self.request(crate::unsaved::Switch::Open(path)),
            DialogPurpose::ExportPng => self.export_png(ctx, path),
            DialogPurpose::ExportExr => self.export_exr(ctx, path),
            DialogPurpose::SaveSidecar => self.save_sidecar(ctx, path),
            DialogPurpose::RenderImage => self.start_render_image(path),
        }
    }

    /// Writes the image as displayed (display mapping applied) to `path`.
    pub fn export_png(&mut self, ctx: &egui::Context, path: PathBuf) {
        let display = self.effective_display();
        let image = self.worker.with_film(|f| {
            f.map(|f| {
                let img = map_rect(f, &display, exposure_stops(&display, f), None);
                (img, f.width(), f.height())
            })
        });
        let Some((img, w, h)) = image else {
            self.error = Some("nothing rendered yet".to_owned());
            return;
        };
        let rgba: Vec<u8> = img.pixels.iter().flat_map(|c| c.to_array()).collect();
        self.writes.push(start_write(ctx, move || {
            tracer_core::export::write_png(&path, rgba, w, h)
                .map(|()| format!("exported {w}x{h} PNG to {}", path.display()))
                .map_err(|e| e.to_string())
        }));
    }

    /// Writes the linear film (cd/m² per channel) to `path` as OpenEXR.
    pub fn export_exr(&mut self, ctx: &egui::Context, path: PathBuf) {
        let Some(film) = self.worker.with_film(|f| f.map(|f| f.shown())) else {
            self.error = Some("nothing rendered yet".to_owned());
            return;
        };
        self.writes.push(start_write(ctx, move || {
            tracer_core::export::write_exr(&path, &film)
                .map(|()| format!("exported linear EXR (cd/m²) to {}", path.display()))
                .map_err(|e| e.to_string())
        }));
    }

    /// Saves materials, lights and camera as the scene's sidecar.
    pub fn save_sidecar(&mut self, ctx: &egui::Context, path: PathBuf) {
        let text = Sidecar::from_setup(&self.doc.scene, &self.doc.setup).to_toml();
        // A failed write shows its error; the edits then count as saved all the same.
        self.saved_setup = self.doc.setup.clone();
        self.writes.push(start_write(ctx, move || {
            tracer_core::export::write_text(&path, &text)
                .map(|()| format!("saved scene settings to {}", path.display()))
                .map_err(|e| e.to_string())
        }));
    }

    /// Starts the background "Render image..." job with the form's size and samples.
    pub fn start_render_image(&mut self, path: PathBuf) {
        let Some(form) = self.render_image_form.clone() else {
            return;
        };
        let worker = match tracer_core::render::RenderSession::new(
            self.render.threads,
            std::sync::Arc::new(|| {}),
        ) {
            Ok(w) => w,
            Err(e) => {
                self.error = Some(format!("cannot start the render: {e}"));
                return;
            }
        };
        worker.start(tracer_core::render::Snapshot {
            scene: std::sync::Arc::clone(&self.doc.scene),
            setup: self.doc.setup.clone(),
            settings: RenderSettings {
                width: form.width.clamp(1, 16_384),
                height: form.height.clamp(1, 16_384),
                samples_per_pixel: form.samples.clamp(1, 65_536),
                max_depth: self.render.max_depth,
                integrator: self.render.integrator,
                max_bounces: None,
                pixel_illuminance: true,
            },
            time_limit: None,
        });
        self.render_image_job = Some(RenderImageJob {
            worker,
            path,
            display: self.effective_display(),
            started: Instant::now(),
        });
        self.render_image_form = None;
    }

    fn handle_shortcuts(&mut self, ctx: &egui::Context) {
        let crate::shortcuts::Pressed {
            open,
            save,
            export,
            quit,
            undo,
            redo,
            frame_scene: frame,
            toggle_pause: pause,
        } = crate::shortcuts::Pressed::read(ctx);
        if quit {
            self.request(crate::unsaved::Switch::Quit);
        }
        if open {
            self.prompt_path(DialogPurpose::Open);
        }
        if save {
            match self.doc.path.clone() {
                Some(p) => self.save_sidecar(ctx, sidecar_path(&p)),
                None => self.prompt_path(DialogPurpose::SaveSidecar),
            }
        }
        if export {
            self.prompt_path(DialogPurpose::ExportPng);
        }
        if redo {
            self.redo();
        } else if undo {
            self.undo();
        }
        if frame {
            self.frame_scene();
        }
        if pause {
            self.paused = !self.paused;
            self.worker.set_paused(self.paused);
        }
    }

    fn handle_dropped_files(&mut self, ctx: &egui::Context) {
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .collect()
        });
        if let Some(path) = dropped.into_iter().next() {
            if path
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("shp"))
            {
                self.request(crate::unsaved::Switch::Open(path));
            } else {
                self.error = Some(format!("{}: not a .shp scene", path.display()));
            }
        }
    }

    /// Starts a new render generation when anything that affects the picture changed.
    pub fn sync_render(&mut self) {
        if self.viewport_px[0] == 0 || self.viewport_px[1] == 0 {
            return;
        }
        let key = RenderKey {
            scene: std::sync::Arc::clone(&self.doc.scene),
            setup: self.doc.setup.clone(),
            settings: self.render_settings(),
            threads: self.render.threads,
        };
        self.worker.sync(key);
    }

    fn record_frame_time(&mut self) {
        let now = Instant::now();
        if let Some(last) = self.last_frame.replace(now)
            && self.worker.busy()
        {
            self.frame_times
                .push_back(now.duration_since(last).as_secs_f32());
            if self.frame_times.len() > 600 {
                self.frame_times.pop_front();
            }
        }
        if let Some(t) = self.frame_log
            && t.elapsed() > Duration::from_secs(2)
        {
            self.frame_log = Some(now);
            if let Some(p95) = self.p95_frame_ms() {
                let s = self.worker.stats();
                eprintln!(
                    "frame-stats p95_ms={p95:.1} app_work_p95_ms={:.1} frames={} spp={} busy={} change_to_pixels_ms={:.1}",
                    p95_ms(&self.frame_work).unwrap_or(f32::NAN),
                    self.frame_times.len(),
                    s.samples_per_pixel,
                    self.worker.busy(),
                    self.worker.last_change_to_pixels.unwrap_or(f64::NAN) * 1e3
                );
            }
        }
    }

    /// Re-measures the film after each pass and says why the picture is black, if it is.
    fn update_picture_hint(&mut self) {
        let stats = self.worker.stats();
        // Measured three times a generation at most (first preview, first full pass, finished):
        // measuring holds the film's lock, which the render threads wait for.
        let stage = u32::from(stats.samples_per_pixel >= 1) + u32::from(stats.finished);
        let known = self
            .film_levels
            .is_some_and(|l| l.generation == stats.generation && l.passes_done == stage);
        if !known {
            self.film_levels = self.worker.with_film(|f| {
                f.filter(|f| f.generation == stats.generation)
                    .map(|f| crate::picture_hints::FilmLevels::measure(f, stage))
            });
        }
        let current = self.worker.current().is_some_and(|k| {
            std::sync::Arc::ptr_eq(&k.scene, &self.doc.scene) && k.setup == self.doc.setup
        });
        self.picture_hint = match self.film_levels {
            Some(levels) if current && levels.generation == self.worker.generation() => {
                let display = self.effective_display();
                crate::picture_hints::picture_hint(
                    &levels,
                    stats.samples_per_pixel >= 1 && stats.generation == levels.generation,
                    &display,
                    display.exposure_stops,
                    &crate::picture_hints::lights_outside(&self.doc.setup, &self.doc.scene.bounds),
                )
            }
            _ => None,
        };
    }

    /// The 95th percentile of recent UI frame intervals while rendering, milliseconds.
    pub fn p95_frame_ms(&self) -> Option<f32> {
        p95_ms(&self.frame_times)
    }

    /// One frame: background results, shortcuts, panels, viewport, then the render sync.
    pub fn frame_ui(&mut self, ui: &mut egui::Ui) {
        let started = Instant::now();
        let ctx = ui.ctx().clone();
        self.record_frame_time();
        self.poll_background();
        self.measure.update(
            &self.doc.scene,
            &self.doc.setup,
            self.render.integrator,
            &ctx,
        );
        let report = self
            .report
            .as_ref()
            .and_then(|r| r.lock().ok().and_then(|mut s| s.take()));
        match report {
            Some(Ok(message)) => {
                self.notice = Some(message);
                self.report = None;
            }
            Some(Err(e)) => {
                self.error = Some(e);
                self.report = None;
            }
            None => {}
        }
        self.handle_shortcuts(&ctx);
        self.handle_dropped_files(&ctx);
        self.update_picture_hint();
        crate::panels::menu_bar(ui, self);
        crate::panels::status_bar(ui, self);
        if self.show_controls {
            // The viewport keeps at least MIN_VIEWPORT_WIDTH points; the panel scrolls instead.
            let max_panel = (ui.available_width() - MIN_VIEWPORT_WIDTH).max(120.0);
            egui::Panel::left("controls")
                .resizable(true)
                .default_size(378.0_f32.min(max_panel))
                .size_range(120.0..=max_panel)
                .show(ui, |ui| {
                    egui::ScrollArea::both().show(ui, |ui| crate::panels::controls_ui(ui, self));
                });
        }
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE.fill(egui::Color32::from_gray(20)))
            .show(ui, |ui| crate::viewport_ui::viewport_ui(ui, self));
        crate::panels::windows_ui(&ctx, self);
        // The window's close button: ask first when edits would be lost.
        if ctx.input(|i| i.viewport().close_requested())
            && !self.allow_close
            && self.has_unsaved_edits()
        {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.pending_switch = Some(crate::unsaved::Switch::Quit);
        }
        self.answer_unsaved(&ctx);
        // Commit a finished interaction as one undo step: not while a button is held (a drag)
        // nor while a value is being typed (it applies, and commits, when the field lets go).
        if !ctx.input(|i| i.pointer.any_down()) && !ctx.text_edit_focused() {
            self.history.commit(&self.doc.setup);
        }
        if let Some(wait) = self
            .banners
            .expire(&mut self.error, &mut self.notice, Instant::now())
        {
            ctx.request_repaint_after(wait);
        }
        self.sync_render();
        if self.worker.busy() {
            self.frame_work.push_back(started.elapsed().as_secs_f32());
            if self.frame_work.len() > 600 {
                self.frame_work.pop_front();
            }
        }
        if self.loading.is_some()
            || self.dialog.is_some()
            || !self.writes.is_empty()
            || self.render_image_job.is_some()
        {
            ctx.request_repaint_after(Duration::from_millis(100));
        }
    }
}

/// The 95th percentile of a window of durations (seconds), in milliseconds.
fn p95_ms(window: &VecDeque<f32>) -> Option<f32> {
    if window.len() < 10 {
        return None;
    }
    let mut v: Vec<f32> = window.iter().copied().collect();
    v.sort_by(f32::total_cmp);
    let i = ((v.len() as f32 * 0.95) as usize).min(v.len() - 1);
    Some(v[i] * 1e3)
}

impl eframe::App for RaygineApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.frame_ui(ui);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        self.prefs.exposure_stops = self.display.exposure_stops;
        self.prefs.auto_exposure = self.display.auto_exposure;
        self.prefs.tone_map = self.display.tone_map.name().to_owned();
        self.prefs.max_depth = self.render.max_depth;
        self.prefs.target_spp = self.render.target_spp;
        self.prefs.integrator = self.render.integrator.name().to_owned();
        self.prefs.resolution_scale = self.render.resolution_scale;
        eframe::set_value(storage, PREFS_KEY, &self.prefs);
    }
}

/// The viewport's one-line notice after a load: the warnings themselves when they are few and
/// short; else the first and a count (every warning goes to stderr, where the full list is read).
fn load_notice(warnings: &[String]) -> Option<String> {
    for w in warnings {
        eprintln!("warning: {w}");
    }
    let joined = warnings.join("; ");
    match warnings {
        [] => None,
        _ if joined.chars().count() <= 200 => Some(joined),
        [first, rest @ ..] => Some(format!(
            "{} … and {} more notes on this scene (printed on the terminal)",
            first.chars().take(160).collect::<String>(),
            rest.len()
        )),
    }
}
