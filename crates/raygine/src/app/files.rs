//! The app's file work: loads, the path window and the native dialog, exports, the sidecar, the
//! "Render image..." job, and the polls that take their results (each a background job of
//! [`crate::file_ops`]; a failure is shown as the error, never dropped).

use super::RaygineApp;
use crate::command::Edit;
use crate::file_ops::{DialogPurpose, PendingDialog, PendingLoad, start_write};
use crate::panels::PathPrompt;
use crate::render_image::RenderImageJob;
use crate::render_worker::{exposure_stops, map_rect};
use crate::unsaved::Switch;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use tracer_core::light::{Environment, EnvironmentSource};
use tracer_core::render::Snapshot;
use tracer_core::scene::{LengthUnit, Sidecar, sidecar_path};

impl RaygineApp {
    /// Starts loading a scene in the background; the current scene stays until it succeeds.
    pub fn open_path(&mut self, path: &Path) {
        self.open_path_in_unit(path, None);
    }

    /// [`RaygineApp::open_path`] with the scene's length unit given.
    pub fn open_path_in_unit(&mut self, path: &Path, unit: Option<LengthUnit>) {
        self.loading = Some(PendingLoad::start(path, unit, &self.ctx));
    }

    /// Waits for a pending load (tests and scripts only; the UI never calls this).
    pub fn finish_loading_blocking(&mut self, timeout: Duration) {
        let deadline = Instant::now() + timeout;
        while self.loading.is_some() && Instant::now() < deadline {
            self.poll_background();
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// Checks background work: loads, dialogs, writes, the render-image job.
    pub fn poll_background(&mut self) {
        if let Some(result) = self.loading.as_ref().and_then(PendingLoad::poll) {
            self.loading = None;
            match result {
                Ok((loaded, path)) => {
                    let doc = crate::document::Document::from_loaded(loaded, path);
                    self.install_document(doc);
                }
                Err(e) => self.error = Some(e),
            }
        }
        self.poll_dialog();
        self.poll_luminaire();
        self.poll_environment_map();
        if let Some(e) = self
            .map_thumbnails
            .update(&self.ctx, self.doc.setup.environment.as_ref())
        {
            self.error = Some(e);
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

    /// The native dialog's answer goes into the path window (Open runs at once).
    fn poll_dialog(&mut self) {
        let Some(result) = self.dialog.as_ref().and_then(PendingDialog::poll) else {
            return;
        };
        let quick = self
            .dialog
            .as_ref()
            .is_some_and(|d| d.started.elapsed().as_secs_f32() < crate::file_ops::NO_DIALOG_SECS);
        let purpose = self.dialog.take().map(|d| d.purpose);
        // A dialog that could not run is an error, not "cancelled".
        let picked = match result {
            Ok(picked) => picked,
            Err(e) => {
                self.error = Some(e);
                return;
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
                _ => self.prompt = Some(PathPrompt::new(purpose, path.display().to_string())),
            }
            // A file to read is read at once; a file to write waits for the window's Save.
            if !purpose.writes() {
                self.prompt = None;
                self.run_path_action(purpose, path);
            }
        }
    }

    /// Writes the "Render image..." PNG once its render has finished.
    fn poll_render_image(&mut self) {
        if !self
            .render_image_job
            .as_ref()
            .is_some_and(RenderImageJob::finished)
        {
            return;
        }
        let Some(job) = self.render_image_job.take() else {
            return;
        };
        match job.write(&self.ctx) {
            Ok(write) => self.writes.push(write),
            Err(e) => self.error = Some(e),
        }
    }

    /// The measurement report's result, once its screenshot has been written.
    pub(super) fn poll_report(&mut self) {
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
            DialogPurpose::SaveReport => base.with_extension("pdf"),
            DialogPurpose::SaveSidecar => sidecar_path(&base),
            // The map shown, else the scene's folder.
            DialogPurpose::EnvironmentMap => match &self.doc.setup.environment {
                Some(Environment {
                    source: EnvironmentSource::Map(map),
                    ..
                }) => map.file.clone(),
                _ => match self.doc.path.as_deref().and_then(Path::parent) {
                    Some(dir) if !dir.as_os_str().is_empty() => dir.join(""),
                    _ => PathBuf::new(),
                },
            },
        }
    }

    /// Opens the path window for `purpose` (typed path; Browse... runs the native dialog).
    pub fn prompt_path(&mut self, purpose: DialogPurpose) {
        let text = match purpose {
            DialogPurpose::Open => String::new(),
            p => self.suggested_path(p).display().to_string(),
        };
        self.prompt = Some(PathPrompt::new(purpose, text));
    }

    /// Runs the action of a path window once the user confirmed a path.
    pub fn run_path_action(&mut self, purpose: DialogPurpose, path: PathBuf) {
        let ctx = self.ctx.clone();
        match purpose {
            DialogPurpose::Open => self.request(Switch::Open(path)),
            DialogPurpose::ExportPng => self.export_png(&ctx, path),
            DialogPurpose::ExportExr => self.export_exr(&ctx, path),
            DialogPurpose::SaveSidecar => self.save_sidecar(&ctx, path),
            DialogPurpose::RenderImage => self.start_render_image(path),
            DialogPurpose::EnvironmentMap => self.edit(Edit::LoadEnvironmentMap(path)),
            DialogPurpose::SaveReport => self.save_pdf_report(&ctx, path),
        }
    }

    /// Writes the lighting report (PDF) in the background: the grids' readings as the Measure
    /// section has them (else measured anew with the viewer's light transport, 64 samples a
    /// point in the global-illumination modes, 16 in direct), the current camera's view, the
    /// schedule and the requirements check. The UI goes on; the banner says where it went, or
    /// why not.
    pub fn save_pdf_report(&mut self, ctx: &egui::Context, path: PathBuf) {
        let scene = std::sync::Arc::clone(&self.doc.scene);
        let setup = self.doc.setup.clone();
        let integrator = self.render.integrator;
        let samples = if integrator == tracer_core::integrator::IntegratorKind::Direct {
            16
        } else {
            64
        };
        let scene_file = self
            .doc
            .path
            .as_ref()
            .map_or("the built-in Cornell box".to_owned(), |p| {
                p.display().to_string()
            });
        // Illuminance readings (not daylight factors) of this setup's grids, if measured.
        let measured = self
            .measure
            .readings()
            .filter(|r| !r.daylight_factor && r.error.is_none())
            .map(|r| r.results);
        self.notice = Some(format!("writing the report {} …", path.display()));
        self.writes.push(start_write(ctx, move || {
            let mut options =
                crate::report_cmd::ReportOptions::new(scene_file, integrator, samples)
                    .map_err(|e| format!("{e:#}"))?;
            options.measured = measured;
            crate::report_cmd::build_and_write(&scene, &setup, &options, &path)
                .map_err(|e| format!("{e:#}"))
        }));
    }

    /// Writes the image as displayed (display mapping applied) to `path`.
    pub fn export_png(&mut self, ctx: &egui::Context, path: PathBuf) {
        let display = self.effective_display();
        // What is shown: the denoised picture when the viewport shows one.
        let denoised = self.worker.denoised_shown().cloned();
        let colours = denoised.as_ref().map(|p| p.rgb.as_slice());
        let image = self.worker.with_film(|f| {
            f.map(|f| {
                let img = map_rect(f, &display, exposure_stops(&display, f), None, colours);
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
        // The raw means as R, G, B; with denoise on, the denoised picture beside them.
        let denoised = self
            .worker
            .denoised_shown()
            .filter(|p| p.rgb.len() == film.len())
            .cloned();
        self.writes.push(start_write(ctx, move || {
            let layers = denoised.as_ref().map(|p| p.rgb.as_slice());
            tracer_core::export::write_exr_with_denoised(&path, &film, layers)
                .map(|()| {
                    let extra = if layers.is_some() {
                        " with denoised.R/G/B"
                    } else {
                        ""
                    };
                    format!("exported linear EXR (cd/m²){extra} to {}", path.display())
                })
                .map_err(|e| e.to_string())
        }));
    }

    /// Saves materials, lights and camera as the scene's sidecar.
    pub fn save_sidecar(&mut self, ctx: &egui::Context, path: PathBuf) {
        let mut sidecar = Sidecar::from_setup(&self.doc.scene, &self.doc.setup);
        if let Some(dir) = path.parent() {
            // An empty parent is the current folder.
            let dir = if dir.as_os_str().is_empty() {
                Path::new(".")
            } else {
                dir
            };
            sidecar = sidecar.relative_to(dir);
        }
        let text = sidecar.to_toml();
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
        let snapshot = Snapshot {
            scene: std::sync::Arc::clone(&self.doc.scene),
            setup: self.doc.setup.clone(),
            settings: self.render_settings(),
            time_limit: None,
            // "Render image" gives every pixel the samples asked for.
            adaptive: false,
        };
        let job = RenderImageJob::start(
            snapshot,
            [form.width, form.height],
            form.samples,
            self.render.threads,
            path,
            self.effective_display(),
        );
        match job {
            Ok(job) => {
                self.render_image_job = Some(job);
                self.render_image_form = None;
            }
            Err(e) => self.error = Some(e),
        }
    }
}
