//! The one place commands are carried out, and the document actions they lead to: switching
//! documents (asking first about unsaved edits), undo and redo, framing, pausing.

use super::RaygineApp;
use crate::command::{Command, Commands};
use crate::document::Document;
use crate::file_ops::{DialogPurpose, PendingDialog, start_write};
use crate::history::History;
use crate::panels::RenderImageForm;
use crate::unsaved::Switch;
use tracer_core::scene::{LengthUnit, framing_camera, sidecar_path};

impl RaygineApp {
    /// Carries out what the user asked for.
    pub fn apply(&mut self, command: Command) {
        match command {
            Command::Switch(switch) => self.request(switch),
            Command::Edit(edit) => self.edit(edit),
            Command::PromptPath(purpose) => self.prompt_path(purpose),
            Command::Browse { purpose, suggested } => {
                self.dialog = Some(PendingDialog::start(purpose, Some(&suggested), &self.ctx));
            }
            Command::RunPathAction(purpose, path) => self.run_path_action(purpose, path),
            Command::SaveSidecar => match self.doc.path.clone() {
                Some(p) => {
                    let ctx = self.ctx.clone();
                    self.save_sidecar(&ctx, sidecar_path(&p));
                }
                None => self.prompt_path(DialogPurpose::SaveSidecar),
            },
            Command::Undo => self.undo(),
            Command::Redo => self.redo(),
            Command::FrameScene => self.frame_scene(),
            Command::ResetCamera => self.doc.setup.camera = self.saved_setup.camera,
            Command::TogglePause => self.set_paused(!self.paused),
            Command::SetGround(on) => self.set_ground(on),
            Command::ToggleDenoise => {
                if self.denoise.available() {
                    self.denoise.toggle(self.render.integrator);
                }
            }
            Command::OpenRenderImageForm => {
                let [w, h] = self.viewport_px;
                self.render_image_form = Some(RenderImageForm {
                    width: w.max(640),
                    height: h.max(360),
                    samples: 64,
                    path: self
                        .suggested_path(DialogPurpose::RenderImage)
                        .display()
                        .to_string(),
                });
            }
            Command::StartRenderImage(path) => self.start_render_image(path),
            Command::CancelRenderImage => {
                self.render_image_job = None;
                self.notice = Some("render cancelled".to_owned());
            }
            Command::CancelLoad => self.loading = None,
            Command::Select(slot) => self.selected_slot = slot,
            Command::WriteText { path, text } => {
                self.writes.push(start_write(&self.ctx, move || {
                    tracer_core::export::write_text(&path, &text)
                        .map(|()| format!("wrote {}", path.display()))
                        .map_err(|e| format!("{}: {e}", path.display()))
                }));
            }
            Command::SaveReport { png, csv, csv_text } => {
                if let Some(rect) = self.viewport_rect {
                    self.show_grids = true;
                    // The report shows the picture and the grids, not this session's banners.
                    self.notice = None;
                    self.error = None;
                    let report = crate::report::save(&self.ctx, rect, png, csv, &csv_text);
                    self.report = Some(report);
                }
            }
            Command::Error(e) => self.error = Some(e),
            Command::Notice(n) => self.notice = Some(n),
            Command::DismissError => self.error = None,
            Command::DismissNotice => self.notice = None,
        }
    }

    /// Applies `commands` in order; the next frame shows what they changed.
    pub(super) fn apply_all(&mut self, commands: Commands) {
        if !commands.is_empty() {
            self.ctx.request_repaint();
        }
        for command in commands {
            self.apply(command);
        }
    }

    /// Switches scenes or quits, asking first when that would drop unsaved edits.
    pub fn request(&mut self, switch: Switch) {
        if self.has_unsaved_edits() {
            self.pending_switch = Some(switch);
        } else {
            self.perform(switch);
        }
    }

    pub(super) fn perform(&mut self, switch: Switch) {
        match switch {
            Switch::Open(path) => self.open_path(&path),
            Switch::Builtin => match Document::builtin() {
                Ok(doc) => self.install_document(doc),
                Err(e) => self.error = Some(format!("cannot build the Cornell box: {e:#}")),
            },
            Switch::Unit(unit) => self.set_unit(unit),
            Switch::Quit => {
                self.allow_close = true;
                self.ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
    }

    /// Reads the scene again in another length unit: distances, the default light and camera
    /// follow it (edits not saved in the sidecar are dropped, as on reopening).
    pub fn set_unit(&mut self, unit: LengthUnit) {
        match self.doc.path.clone() {
            Some(path) => self.open_path_in_unit(&path, Some(unit)),
            None => match tracer_core::scene::builtin_cornell_box(Some(unit)) {
                Ok(loaded) => self.install_document(Document::from_loaded(loaded, None)),
                Err(e) => self.error = Some(format!("cannot build the Cornell box: {e}")),
            },
        }
    }

    /// Shows another document: fresh history, no selection or meter, the last error gone, its
    /// load warnings as the notice, its file first in the recent list, and rendering resumed,
    /// so the new scene gets a picture (the old scene's picture is never shown for it).
    pub(super) fn install_document(&mut self, doc: Document) {
        // The same scene read again (another unit) keeps its ground plane.
        let keep_ground = self.doc.without_ground.is_some() && self.doc.path == doc.path;
        // The viewer has its own unit control.
        self.notice = load_notice(&doc.warnings).map(|n| {
            n.replace(
                "pass --units",
                "choose the unit at the top of the side panel:",
            )
        });
        self.error = None;
        if let Some(p) = &doc.path {
            self.prefs.add_recent(p);
            self.prefs.last_scene = Some(p.clone());
        }
        self.history = History::new(&doc.setup);
        self.saved_setup = doc.setup.clone();
        let key = crate::scene_exposure::scene_key(doc.path.as_deref());
        self.exposure = crate::scene_exposure::ExposureKeeper::for_scene(
            key.clone(),
            self.prefs.exposures.get(&key).copied(),
            &mut self.display,
            self.worker.generation(),
        );
        self.doc = doc;
        self.panels.scroll_to_top = true;
        self.selected_slot = None;
        self.meter = None;
        if self.paused {
            self.set_paused(false);
        }
        if keep_ground {
            self.set_ground(true);
        }
    }

    /// Sets the scene's exposure on its first view and keeps what the user set; remembers it
    /// per scene. Called every frame.
    pub(super) fn keep_exposure(&mut self) {
        let stats = self.worker.stats();
        let worker = &self.worker;
        let remember = self.exposure.update(&mut self.display, &stats, || {
            let basis = worker.basis();
            worker.with_film(|f| {
                let f = f.filter(|f| f.generation == stats.generation)?;
                // A fisheye's black corners are not the scene.
                let outside = |i: usize| {
                    basis.as_ref().is_some_and(|b| {
                        let w = f.width() as usize;
                        b.width == f.width() && b.pixel_outside((i % w) as u32, (i / w) as u32)
                    })
                };
                crate::scene_exposure::median_exposure_stops(f, outside)
            })
        });
        if let Some(e) = remember {
            self.prefs
                .exposures
                .insert(self.exposure.key().to_owned(), e);
        }
    }

    fn set_paused(&mut self, paused: bool) {
        self.paused = paused;
        self.worker.set_paused(paused);
    }

    pub fn undo(&mut self) {
        if let Some(s) = self.history.undo(&self.doc.setup) {
            self.doc.setup = s;
        }
    }

    pub fn redo(&mut self) {
        if let Some(s) = self.history.redo(&self.doc.setup) {
            self.doc.setup = s;
        }
    }

    /// Adds the ground plane under the scene (its material the last slot, in every undo step
    /// and in the saved state, so it is no unsaved edit), or takes it away again.
    pub fn set_ground(&mut self, on: bool) {
        use std::sync::Arc;
        if on == self.doc.without_ground.is_some() {
            return;
        }
        let change: fn(&mut tracer_core::scene::Setup) = if on {
            |s| {
                s.materials.push(tracer_core::scene::ground_material());
                s.hidden.push(false);
            }
        } else {
            |s| {
                s.materials.pop();
                s.hidden.pop();
            }
        };
        if on {
            let plain = Arc::clone(&self.doc.scene);
            self.doc.scene = Arc::new(plain.with_ground());
            self.doc.without_ground = Some(plain);
        } else if let Some(plain) = self.doc.without_ground.take() {
            self.doc.scene = plain;
        }
        change(&mut self.doc.setup);
        change(&mut self.saved_setup);
        self.history.map(change);
        if self
            .selected_slot
            .is_some_and(|s| s as usize >= self.doc.setup.materials.len())
        {
            self.selected_slot = None;
        }
    }

    /// Resets the camera to frame the scene (keeps the field of view).
    pub fn frame_scene(&mut self) {
        let fov = self.doc.setup.camera.fov_deg;
        self.doc.setup.camera = framing_camera(&self.doc.scene, fov);
    }
}

/// The viewport's one-line notice after a load: the warnings themselves when they are few and
/// short; else the first and a count, with where to read them all (View > Notes; stderr too).
fn load_notice(warnings: &[String]) -> Option<String> {
    for w in warnings {
        eprintln!("warning: {w}");
    }
    let joined = warnings.join("; ");
    match warnings {
        [] => None,
        _ if joined.chars().count() <= 200 => Some(joined),
        [first, rest @ ..] => Some(format!(
            "{} … and {} more notes on this scene (View > Notes lists them all)",
            first.chars().take(160).collect::<String>(),
            rest.len()
        )),
    }
}
