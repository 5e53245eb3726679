//! The viewer application. It owns the document, its undo history, the view settings and the
//! background work. The frame (`frame.rs`) runs shortcuts, panels, viewport and windows, each
//! drawing what it is given and returning [`crate::command::Command`]s, which
//! [`RaygineApp::apply`] carries out (`apply.rs`); file work is in `files.rs`.

mod apply;
mod edits;
mod files;
mod frame;
mod inspect;

use crate::document::Document;
use crate::file_ops::{PendingDialog, PendingLoad, PendingWrite};
use crate::frame_stats::FrameStats;
use crate::history::History;
use crate::panels::PanelState;
use crate::prefs::{PREFS_KEY, Prefs};
use crate::render_worker::{RenderKey, RenderWorker};
use std::path::PathBuf;
use tracer_core::display::{DisplaySettings, ToneMap};
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::RenderSettings;
use tracer_core::scene::Setup;

pub use frame::MIN_VIEWPORT_WIDTH;

pub use crate::panels::{FalseColourUi, PathPrompt, RenderImageForm, RenderPrefs};
pub use crate::render_image::RenderImageJob;
pub use crate::shortcuts::{
    SHORTCUT_EXPORT, SHORTCUT_OPEN, SHORTCUT_QUIT, SHORTCUT_REDO, SHORTCUT_SAVE, SHORTCUT_UNDO,
};
pub use crate::viewport_ui::HoverInfo;

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

/// The viewer's state. Only [`RaygineApp::apply`] and the background polls change it, apart
/// from the values panels edit in place (see [`crate::command`]); tests and scripts read it and
/// give their inputs through `inspect.rs`.
pub struct RaygineApp {
    /// The frame-statistics log has reported the first full-resolution image.
    pub(crate) first_full_logged: bool,
    /// The egui context, for waking the UI from background threads.
    pub(crate) ctx: egui::Context,
    pub(crate) doc: Document,
    pub(crate) history: History,
    pub(crate) render: RenderPrefs,
    pub(crate) display: DisplaySettings,
    /// The scene's exposure: automatic on its first view, then held, or the user's.
    pub(crate) exposure: crate::scene_exposure::ExposureKeeper,
    pub(crate) false_colour: FalseColourUi,
    pub(crate) worker: RenderWorker,
    /// The denoised display (Open Image Denoise on a background thread).
    pub(crate) denoise: crate::denoise_view::DenoiseView,
    pub(crate) prefs: Prefs,
    pub(crate) selected_slot: Option<u32>,
    pub(crate) error: Option<String>,
    pub(crate) notice: Option<String>,
    /// When the error and the notice appeared; they expire or are dismissed.
    pub(crate) banners: crate::banners::Banners,
    pub(crate) loading: Option<PendingLoad>,
    pub(crate) dialog: Option<PendingDialog>,
    pub(crate) writes: Vec<PendingWrite>,
    pub(crate) prompt: Option<PathPrompt>,
    pub(crate) render_image_form: Option<RenderImageForm>,
    pub(crate) render_image_job: Option<RenderImageJob>,
    pub(crate) hover: Option<HoverInfo>,
    pub(crate) paused: bool,
    pub(crate) show_help: bool,
    /// Whether the side panel is shown (View > Side panel hides it for a small window).
    pub(crate) show_controls: bool,
    /// The panels' own state (text fields kept between frames).
    pub(crate) panels: PanelState,
    /// The setup as loaded or last saved: anything else is an unsaved edit.
    pub(crate) saved_setup: Setup,
    /// A scene switch or quit waiting for the user's answer about unsaved edits.
    pub(crate) pending_switch: Option<crate::unsaved::Switch>,
    /// The user agreed to close: the window's close request goes through.
    allow_close: bool,
    /// The window has asked for the keyboard focus (once, at launch).
    focus_asked: bool,
    /// The luminaire file being read for "Add luminaire".
    adding_luminaire: Option<edits::PendingLuminaire>,
    /// The environment map being read for "Load map…".
    loading_environment: Option<edits::PendingEnvironmentMap>,
    /// The Environment section's pictures of its maps.
    pub(crate) map_thumbnails: crate::map_thumbnail::MapThumbnails,
    /// When the wheel last turned: a dolly by wheel becomes one undo step once it rests.
    last_scroll: Option<std::time::Instant>,
    /// The grids' background measurement (Measure panel, grid overlay).
    pub(crate) measure: crate::measure_worker::MeasureWorker,
    pub(crate) glare: crate::glare_worker::GlareWorker,
    /// Whether grid readings are drawn over the picture.
    pub(crate) show_grids: bool,
    /// The Measure section reads daylight factors instead of illuminance.
    pub(crate) daylight_factor: bool,
    /// The luminance meter's rectangle (Ctrl+drag over the picture), film pixels.
    pub(crate) meter: Option<crate::luminance_meter::Meter>,
    /// Where the current Ctrl+drag started (film position).
    pub(crate) meter_anchor: Option<(f32, f32)>,
    /// What the current orbit turns about (shown while dragging).
    pub(crate) orbit_pivot: Option<glam::Vec3>,
    /// The viewport's screen rectangle in the last frame (points), for reports.
    pub(crate) viewport_rect: Option<egui::Rect>,
    /// A measurement report waiting for its screenshot.
    pub(crate) report: Option<crate::report::ReportStatus>,
    /// Film size of the viewport, pixels.
    pub(crate) viewport_px: [u32; 2],
    /// Whether the last frame drew a picture (only ever one of the scene open).
    pub(crate) picture_drawn: bool,
    /// The film's brightness at the last pass measured (for `picture_hint`).
    pub(crate) film_levels: Option<crate::picture_hints::FilmLevels>,
    /// Why the picture is black, when it is.
    pub(crate) picture_hint: Option<String>,
    /// UI frame times while rendering (the p95 in the status bar).
    pub(crate) frame_stats: FrameStats,
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
        let mut display = DisplaySettings {
            exposure_stops: 0.0,
            auto_exposure: prefs.auto_exposure,
            tone_map: ToneMap::from_name(&prefs.tone_map).unwrap_or_default(),
            false_colour: None,
        };
        let exposure = crate::scene_exposure::ExposureKeeper::for_scene(
            crate::scene_exposure::scene_key(None),
            prefs
                .exposures
                .get(&crate::scene_exposure::scene_key(None))
                .copied(),
            &mut display,
            worker.generation(),
        );
        let mut app = Self {
            ctx: cc.egui_ctx.clone(),
            history: History::new(&doc.setup),
            doc,
            render: RenderPrefs {
                integrator: IntegratorKind::from_name(&prefs.integrator)
                    .unwrap_or_else(Self::default_integrator),
                max_depth: prefs.max_depth.min(64),
                target_spp: prefs.target_spp.clamp(1, 65_536),
                adaptive: prefs.adaptive,
                resolution_scale: prefs.resolution_scale.clamp(0.25, 1.0),
                threads: if threads == 0 { cores } else { threads },
            },
            display,
            exposure,
            false_colour: FalseColourUi::default(),
            worker,
            denoise: crate::denoise_view::DenoiseView::new(
                &cc.egui_ctx,
                if threads == 0 { cores } else { threads },
            ),
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
            panels: PanelState {
                scroll_to_top: true,
                ..PanelState::default()
            },
            saved_setup,
            pending_switch: None,
            allow_close: false,
            last_scroll: None,
            adding_luminaire: None,
            loading_environment: None,
            map_thumbnails: crate::map_thumbnail::MapThumbnails::default(),
            focus_asked: false,
            measure: crate::measure_worker::MeasureWorker::default(),
            glare: crate::glare_worker::GlareWorker::default(),
            show_grids: true,
            daylight_factor: false,
            meter: None,
            meter_anchor: None,
            orbit_pivot: None,
            viewport_rect: None,
            report: None,
            viewport_px: [0, 0],
            picture_drawn: false,
            film_levels: None,
            picture_hint: None,
            frame_stats: FrameStats::new(std::env::var_os("RAYGINE_FRAME_STATS").is_some()),
            first_full_logged: false,
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

    /// The light transport a new user starts with (see [`crate::prefs::default_integrator`]).
    pub fn default_integrator() -> IntegratorKind {
        crate::prefs::default_integrator()
    }

    /// Whether the setup differs from what was loaded or last saved.
    pub fn has_unsaved_edits(&self) -> bool {
        self.doc.setup != self.saved_setup
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
            // Measured once shown (`show_illuminance`), without a restart.
            pixel_illuminance: false,
            guides: self.denoise.guides_wanted(self.render.integrator),
        }
    }

    /// The display mapping in force: the display settings plus the false-colour view.
    pub fn effective_display(&self) -> DisplaySettings {
        self.false_colour.over(&self.display)
    }

    /// Starts a new render generation when anything that affects the picture changed.
    pub fn sync_render(&mut self) {
        if self.viewport_px[0] == 0 || self.viewport_px[1] == 0 {
            return;
        }
        // A scene opened with an orthographic camera while the light tracer was chosen (the
        // menus keep the two apart otherwise): bidirectional renders it, and the user is told.
        if let Err(why) = self
            .render
            .integrator
            .check_projection(self.doc.setup.camera.projection)
        {
            self.render.integrator = IntegratorKind::Bidirectional;
            self.notice = Some(format!("{why}. Switched to bidirectional."));
        }
        let key = RenderKey {
            scene: std::sync::Arc::clone(&self.doc.scene),
            setup: self.doc.setup.clone(),
            settings: self.render_settings(),
            threads: self.render.threads,
            adaptive: self.render.adaptive,
        };
        self.worker.sync(key);
    }

    /// The 95th percentile of recent UI frame intervals while rendering, milliseconds.
    pub fn p95_frame_ms(&self) -> Option<f32> {
        self.frame_stats.p95_ms()
    }
}

impl eframe::App for RaygineApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.frame_ui(ui);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        self.prefs.auto_exposure = self.display.auto_exposure;
        self.prefs.tone_map = self.display.tone_map.name().to_owned();
        self.prefs.max_depth = self.render.max_depth;
        self.prefs.target_spp = self.render.target_spp;
        self.prefs.integrator = self.render.integrator.name().to_owned();
        self.prefs.resolution_scale = self.render.resolution_scale;
        self.prefs.adaptive = self.render.adaptive;
        eframe::set_value(storage, PREFS_KEY, &self.prefs);
    }
}
