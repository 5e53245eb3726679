//! The frame: background results, shortcuts, panels, viewport and windows in turn, each drawing
//! what it is given and returning commands, then the undo step and the render sync.

use super::RaygineApp;
use crate::command::{Command, Commands};
use crate::panels::{MeasureView, MenuBar, SidePanel, StatusBar, Windows};
use crate::viewport_ui::Viewport;
use std::time::{Duration, Instant};

/// The narrowest the viewport gets while the side panel is shown, points.
pub const MIN_VIEWPORT_WIDTH: f32 = 320.0;

/// How long the wheel rests before a dolly by wheel is one undo step.
const WHEEL_REST: Duration = Duration::from_millis(400);

impl RaygineApp {
    fn record_frame_time(&mut self) {
        let log_due = self.frame_stats.frame_started(self.worker.busy());
        if self.frame_stats.logging() && !self.first_full_logged {
            let s = self.worker.stats();
            if s.samples_per_pixel >= 1 {
                self.first_full_logged = true;
                eprintln!(
                    "frame-stats first_full_image_s={:.2} (since the app started) generation={} first_preview_s={:.3} first_full_s={:.2} (since the generation started)",
                    self.frame_stats.since_start().as_secs_f64(),
                    s.generation,
                    s.first_preview_secs.unwrap_or(f64::NAN),
                    s.first_full_secs.unwrap_or(f64::NAN),
                );
            }
        }
        if log_due && let Some(p95) = self.p95_frame_ms() {
            let s = self.worker.stats();
            eprintln!(
                "frame-stats p95_ms={p95:.1} app_work_p95_ms={:.1} frames={} spp={} busy={} change_to_pixels_ms={:.1}",
                self.frame_stats.p95_work_ms().unwrap_or(f32::NAN),
                self.frame_stats.frames(),
                s.samples_per_pixel,
                self.worker.busy(),
                self.worker.last_change_to_pixels.unwrap_or(f64::NAN) * 1e3
            );
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

    /// One frame: background results, shortcuts, panels, viewport, windows, then the render
    /// sync. Commands are applied as soon as what returned them has drawn: the shortcuts' before
    /// the panels, the panels' before the viewport (so the picture and a report screenshot show
    /// them this frame), the viewport's and the windows' before the unsaved-edits question.
    /// Sends the next denoise when due and picks the picture the viewport shows: the
    /// denoised one when the toggle is on and one of this render is ready, never in false
    /// colour (its colours are values).
    fn poll_denoise(&mut self, ctx: &egui::Context) {
        let mode = self.render.integrator;
        if let Some(wait) = self.denoise.poll(&self.worker, mode) {
            ctx.request_repaint_after(wait);
        }
        let false_colour = self.effective_display().false_colour.is_some();
        let shown = if false_colour {
            None
        } else {
            self.denoise.shown(self.worker.generation(), mode).cloned()
        };
        self.worker.set_denoised(shown);
    }

    pub fn frame_ui(&mut self, ui: &mut egui::Ui) {
        let started = Instant::now();
        let ctx = ui.ctx().clone();
        if !std::mem::replace(&mut self.focus_asked, true) {
            // Take the keyboard at launch: without a window manager that hands focus over (a
            // bare X server, some tiling setups) the first keys, Ctrl+Q among them, went nowhere.
            ctx.send_viewport_cmd(egui::ViewportCommand::Focus);
        }
        self.record_frame_time();
        self.poll_background();
        self.poll_denoise(&ctx);
        self.measure.update(
            &self.doc.scene,
            &self.doc.setup,
            self.render.integrator,
            self.daylight_factor,
            &ctx,
        );
        self.glare.update(
            &self.doc.scene,
            &self.doc.setup,
            self.render.integrator,
            self.panels.glare,
            &ctx,
        );
        self.poll_report();
        let mut commands = crate::shortcuts::Pressed::read(&ctx).commands();
        commands.extend(dropped_file(&ctx));
        self.apply_all(commands);
        self.update_picture_hint();
        let mut commands = Commands::new();
        self.bars_ui(ui, &mut commands);
        if self.show_controls {
            // The viewport keeps at least MIN_VIEWPORT_WIDTH points; the panel scrolls instead.
            let max_panel = (ui.available_width() - MIN_VIEWPORT_WIDTH).max(120.0);
            egui::Panel::left("controls")
                .resizable(true)
                .default_size(378.0_f32.min(max_panel))
                .size_range(120.0..=max_panel)
                .show(ui, |ui| {
                    // A scene opens with its panel at the top (the Lights first), not where the
                    // last scene, or the last session, left it.
                    let mut area = egui::ScrollArea::both().id_salt("controls-scroll");
                    if std::mem::take(&mut self.panels.scroll_to_top) {
                        area = area
                            .vertical_scroll_offset(0.0)
                            .horizontal_scroll_offset(0.0);
                    }
                    area.show(ui, |ui| self.controls_ui(ui, &mut commands));
                });
        }
        self.apply_all(std::mem::take(&mut commands));
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE.fill(egui::Color32::from_gray(20)))
            .show(ui, |ui| self.viewport_ui(ui, &mut commands));
        crate::panels::windows_ui(
            &ctx,
            Windows {
                prompt: &mut self.prompt,
                render_image_form: &mut self.render_image_form,
                render_image_job: self.render_image_job.as_ref(),
                show_help: &mut self.show_help,
            },
            &mut commands,
        );
        crate::panels::notes_ui(
            &ctx,
            &mut self.panels.show_notes,
            &self.doc.title(),
            &self.doc.warnings,
        );
        self.apply_all(commands);
        // The window's close button: ask first when edits would be lost.
        if ctx.input(|i| i.viewport().close_requested())
            && !self.allow_close
            && self.has_unsaved_edits()
        {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.pending_switch = Some(crate::unsaved::Switch::Quit);
        }
        self.answer_unsaved(&ctx);
        // Commit a finished interaction as one undo step: not while a button is held (a drag),
        // nor while a value is being typed (it applies, and commits, when the field lets go),
        // nor until the wheel has rested for WHEEL_REST (a dolly of many wheel steps).
        if ctx.input(|i| i.smooth_scroll_delta != egui::Vec2::ZERO) {
            self.last_scroll = Some(Instant::now());
        }
        let wheel_resting = match self.last_scroll {
            Some(t) if t.elapsed() < WHEEL_REST => {
                ctx.request_repaint_after(WHEEL_REST);
                false
            }
            _ => true,
        };
        if !ctx.input(|i| i.pointer.any_down()) && !ctx.text_edit_focused() && wheel_resting {
            self.history.commit(&self.doc.setup);
        }
        if let Some(wait) = self
            .banners
            .expire(&mut self.error, &mut self.notice, Instant::now())
        {
            ctx.request_repaint_after(wait);
        }
        self.sync_render();
        self.keep_exposure();
        let busy = self.worker.busy();
        self.frame_stats
            .frame_done(busy, started.elapsed().as_secs_f32());
        if busy {
            // The status figures (time, samples, time left) move at least twice a second, also
            // while a long tile keeps the picture itself unchanged.
            ctx.request_repaint_after(Duration::from_millis(400));
        }
        if self.loading.is_some()
            || self.dialog.is_some()
            || !self.writes.is_empty()
            || self.render_image_job.is_some()
        {
            ctx.request_repaint_after(Duration::from_millis(100));
        }
    }

    /// The menu bar and the status bar.
    fn bars_ui(&mut self, ui: &mut egui::Ui, out: &mut Commands) {
        let menu = MenuBar {
            can_undo: self.history.can_undo_from(&self.doc.setup),
            can_redo: self.history.can_redo(),
            paused: self.paused,
            recent: &self.prefs.recent,
            show_controls: &mut self.show_controls,
            show_help: &mut self.show_help,
            show_notes: &mut self.panels.show_notes,
            notes: self.doc.warnings.len(),
            ground: self.doc.without_ground.is_some(),
        };
        crate::panels::menu_bar(ui, menu, out);
        let status = StatusBar {
            stats: self.worker.stats(),
            paused: self.paused,
            integrator: self.render.integrator,
            doc: &self.doc,
            viewport_px: self.viewport_px,
            loading: self.loading.as_ref(),
            p95_frame_ms: self.p95_frame_ms(),
            denoised: self.worker.denoised_shown().map(|p| (p.samples, p.secs)),
            writing: !self.writes.is_empty(),
        };
        crate::panels::status_bar(ui, status, out);
    }

    /// The side panel's control groups.
    fn controls_ui(&mut self, ui: &mut egui::Ui, out: &mut Commands) {
        let measure = MeasureView {
            readings: self.measure.readings(),
            selected_slot: self.selected_slot,
            integrator: self.render.integrator,
        };
        let thumbnail = match self.doc.setup.environment.as_ref().map(|e| &e.source) {
            Some(tracer_core::light::EnvironmentSource::Map(map)) => self
                .map_thumbnails
                .get(map)
                .map(egui::load::SizedTexture::from_handle),
            _ => None,
        };
        let panel = SidePanel {
            doc: &mut self.doc,
            loading: self.loading.is_some(),
            render: &mut self.render,
            display: &mut self.display,
            false_colour: &mut self.false_colour,
            denoise: &mut self.denoise,
            show_grids: &mut self.show_grids,
            daylight_factor: &mut self.daylight_factor,
            measure,
            glare: self.glare.readings(),
            state: &mut self.panels,
            adding_luminaire: self.adding_luminaire.is_some(),
            loading_environment: self.loading_environment.is_some(),
            environment_thumbnail: thumbnail,
            viewport_aspect: self.viewport_px[0].max(1) as f32 / self.viewport_px[1].max(1) as f32,
        };
        crate::panels::controls_ui(ui, panel, out);
    }

    /// The picture and what is drawn over it.
    fn viewport_ui(&mut self, ui: &mut egui::Ui, out: &mut Commands) {
        let viewport = Viewport {
            display: self.effective_display(),
            worker: &mut self.worker,
            doc: &mut self.doc,
            measure: &self.measure,
            glare: &self.glare,
            resolution_scale: self.render.resolution_scale,
            show_grids: self.show_grids,
            selected_light: self.panels.selected_light,
            loading: self.loading.as_ref(),
            picture_hint: self.picture_hint.as_deref(),
            error: self.error.as_deref(),
            notice: self.notice.as_deref(),
            viewport_px: &mut self.viewport_px,
            viewport_rect: &mut self.viewport_rect,
            picture_drawn: &mut self.picture_drawn,
            hover: &mut self.hover,
            meter: &mut self.meter,
            meter_anchor: &mut self.meter_anchor,
            orbit_pivot: &mut self.orbit_pivot,
        };
        crate::viewport_ui::viewport_ui(ui, viewport, out);
        self.show_illuminance();
    }

    /// The render measures the pixels' illuminance from the first time a readout in lx shows
    /// (the hover) or the false colour shows illuminance on.
    fn show_illuminance(&mut self) {
        let false_colour = self.false_colour.enabled
            && self.false_colour.quantity == tracer_core::display::FalseColourQuantity::Illuminance;
        if self.hover.is_some() || false_colour {
            self.worker.measure_illuminance();
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
                self.pending_switch = None;
                self.apply(Command::SaveSidecar);
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
}

/// A file dropped on the window: a scene (`.shp`, `.brs`, `.obj`, `.gltf`, `.glb`, USD) is opened
/// (asking first about unsaved edits); anything else is an error.
fn dropped_file(ctx: &egui::Context) -> Option<Command> {
    let path = ctx.input(|i| i.raw.dropped_files.first().map(|f| f.path().to_path_buf()))?;
    Some(
        if tracer_core::formats::is_scene_file(&path) || tracer_core::scene::is_sidecar_file(&path)
        {
            Command::Switch(crate::unsaved::Switch::Open(path))
        } else {
            Command::Error(format!(
                "{}: not a scene (raygine opens .{} and NAME.raygine.toml scene settings)",
                path.display(),
                tracer_core::formats::SCENE_EXTENSIONS.join(", .")
            ))
        },
    )
}
