//! Work with files off the UI thread: loading scenes, native dialogs and writes (exports, the
//! sidecar, the "Render image..." PNG). Each is a [`Job`]: a named thread whose result the UI
//! polls, which wakes the UI when it is done. A job that cannot start, or whose thread dies,
//! reports an error like any other failure; nothing is dropped.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::time::Instant;
use tracer_core::scene::{LoadOptions, LoadedScene};

/// Starts `work` on a thread named `name` (std's threads; tests pass one that fails).
pub type Spawn = fn(name: String, work: Box<dyn FnOnce() + Send>) -> std::io::Result<()>;

/// [`Spawn`] on a named std thread.
pub fn spawn_thread(name: String, work: Box<dyn FnOnce() + Send>) -> std::io::Result<()> {
    std::thread::Builder::new()
        .name(name)
        .spawn(work)
        .map(|_| ())
}

/// Work running on its own thread; `poll` gives its result once, when it is done.
pub struct Job<T> {
    /// What the job does, for messages ("loading the scene").
    task: &'static str,
    rx: Receiver<Result<T, String>>,
}

impl<T> std::fmt::Debug for Job<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Job")
            .field("task", &self.task)
            .finish_non_exhaustive()
    }
}

impl<T: Send + 'static> Job<T> {
    /// Runs `work` on a thread named `name`; the UI is woken when it finishes.
    pub fn start(
        name: &str,
        task: &'static str,
        ctx: &egui::Context,
        work: impl FnOnce() -> Result<T, String> + Send + 'static,
    ) -> Self {
        Self::start_on(spawn_thread, name, task, ctx, work)
    }

    /// [`Job::start`] on the threads `spawn` makes.
    pub fn start_on(
        spawn: Spawn,
        name: &str,
        task: &'static str,
        ctx: &egui::Context,
        work: impl FnOnce() -> Result<T, String> + Send + 'static,
    ) -> Self {
        let (tx, rx) = channel();
        let repaint = ctx.clone();
        let started = spawn(
            name.to_owned(),
            Box::new(move || {
                let _ = tx.send(work());
                repaint.request_repaint();
            }),
        );
        match started {
            Ok(()) => Self { task, rx },
            Err(e) => Self::finished(task, Err(format!("cannot start {task}: {e}"))),
        }
    }

    /// A job that has already finished with `result`.
    pub fn finished(task: &'static str, result: Result<T, String>) -> Self {
        let (tx, rx) = channel();
        let _ = tx.send(result);
        Self { task, rx }
    }

    /// The result once the job has finished (a job whose thread died reports that).
    pub fn poll(&self) -> Option<Result<T, String>> {
        match self.rx.try_recv() {
            Ok(r) => Some(r),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => {
                Some(Err(format!("{} stopped unexpectedly", self.task)))
            }
        }
    }
}

/// A scene being read on a background thread.
#[derive(Debug)]
pub struct PendingLoad {
    pub path: PathBuf,
    pub started: Instant,
    /// The scene loaded and the file it came from (None: the built-in box).
    job: Job<(LoadedScene, Option<PathBuf>)>,
}

impl PendingLoad {
    /// Starts reading `path` (parse, BVH build, sidecar) with the scene's length unit given (it
    /// wins over the sidecar's) or not. A sidecar opens the scene beside it with it, or the
    /// built-in box with it.
    pub fn start(
        path: &Path,
        unit: Option<tracer_core::scene::LengthUnit>,
        ctx: &egui::Context,
    ) -> Self {
        let p = path.to_path_buf();
        let job = Job::start("raygine-load", "loading the scene", ctx, move || {
            let options = LoadOptions {
                unit,
                ..LoadOptions::default()
            };
            if tracer_core::scene::is_sidecar_file(&p) {
                return tracer_core::scene::load_sidecar(&p, unit).map_err(|e| e.to_string());
            }
            tracer_core::scene::load(&p, &options)
                .map(|loaded| (loaded, Some(p.clone())))
                .map_err(|e| e.to_string())
        });
        Self {
            path: path.to_path_buf(),
            started: Instant::now(),
            job,
        }
    }

    /// The result once the load has finished.
    pub fn poll(&self) -> Option<Result<(LoadedScene, Option<PathBuf>), String>> {
        self.job.poll()
    }
}

/// What a path window or native dialog is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DialogPurpose {
    Open,
    ExportPng,
    ExportExr,
    SaveSidecar,
    RenderImage,
    /// Read a latitude-longitude `.hdr` or `.exr` map as the environment.
    EnvironmentMap,
    /// Write the lighting report (PDF).
    SaveReport,
}

impl DialogPurpose {
    /// Whether the path is written (the window asks before replacing a file); else it is read.
    pub fn writes(self) -> bool {
        !matches!(self, DialogPurpose::Open | DialogPurpose::EnvironmentMap)
    }
}

/// A native file dialog running on its own thread (rfd). It ends with a path, or `None` when
/// cancelled or when the desktop has no dialog service; or with an error when it could not run.
#[derive(Debug)]
pub struct PendingDialog {
    pub purpose: DialogPurpose,
    pub started: Instant,
    job: Job<Option<PathBuf>>,
}

/// A dialog that closes with nothing sooner than this never showed: without a desktop portal
/// rfd returns at once.
pub const NO_DIALOG_SECS: f32 = 0.4;

impl PendingDialog {
    pub fn start(purpose: DialogPurpose, suggested: Option<&Path>, ctx: &egui::Context) -> Self {
        Self::start_on(spawn_thread, purpose, suggested, ctx)
    }

    /// [`PendingDialog::start`] on the threads `spawn` makes.
    pub fn start_on(
        spawn: Spawn,
        purpose: DialogPurpose,
        suggested: Option<&Path>,
        ctx: &egui::Context,
    ) -> Self {
        let suggested = suggested.map(Path::to_path_buf);
        let job = Job::start_on(spawn, "raygine-dialog", "the file dialog", ctx, move || {
            Ok(run_dialog(purpose, suggested.as_deref()))
        });
        Self {
            purpose,
            started: Instant::now(),
            job,
        }
    }

    /// A dialog that has already closed with `picked` (tests; platforms without dialogs).
    pub fn finished(purpose: DialogPurpose, picked: Option<PathBuf>) -> Self {
        Self {
            purpose,
            started: Instant::now(),
            job: Job::finished("the file dialog", Ok(picked)),
        }
    }

    /// `Some(result)` once the dialog closed: the path picked (None: cancelled or no dialog),
    /// or why the dialog could not run.
    pub fn poll(&self) -> Option<Result<Option<PathBuf>, String>> {
        self.job.poll()
    }
}

/// The native dialog for `purpose` (blocks until the user closes it).
fn run_dialog(purpose: DialogPurpose, suggested: Option<&Path>) -> Option<PathBuf> {
    let mut dialog = rfd::FileDialog::new();
    // A folder suggested (where a file to read may be) opens in it.
    if let Some(dir) = suggested.filter(|p| p.is_dir()) {
        dialog = dialog.set_directory(dir);
    } else {
        if let Some(dir) = suggested.and_then(Path::parent)
            && !dir.as_os_str().is_empty()
        {
            dialog = dialog.set_directory(dir);
        }
        if let Some(name) = suggested.and_then(Path::file_name) {
            dialog = dialog.set_file_name(name.to_string_lossy());
        }
    }
    match purpose {
        DialogPurpose::Open => dialog
            .add_filter("Scenes", &tracer_core::formats::SCENE_EXTENSIONS)
            .add_filter("Scene settings (NAME.raygine.toml)", &["toml"])
            .add_filter("Lumicept scene", &["shp", "brs"])
            .add_filter("Wavefront OBJ", &["obj"])
            .add_filter("glTF 2.0", &["gltf", "glb"])
            .add_filter("USD", &["usda", "usdc", "usdz", "usd"])
            .pick_file(),
        DialogPurpose::ExportPng | DialogPurpose::RenderImage => {
            dialog.add_filter("PNG image", &["png"]).save_file()
        }
        DialogPurpose::ExportExr => dialog.add_filter("OpenEXR image", &["exr"]).save_file(),
        DialogPurpose::SaveSidecar => dialog.add_filter("raygine sidecar", &["toml"]).save_file(),
        DialogPurpose::SaveReport => dialog.add_filter("PDF report", &["pdf"]).save_file(),
        DialogPurpose::EnvironmentMap => dialog
            .add_filter("Environment map (latitude-longitude)", &["hdr", "exr"])
            .pick_file(),
    }
}

/// A write running in the background (an export, the sidecar); it reports a line for the user.
pub type PendingWrite = Job<String>;

/// Starts a background write; `work` says what it wrote, or why it could not.
pub fn start_write(
    ctx: &egui::Context,
    work: impl FnOnce() -> Result<String, String> + Send + 'static,
) -> PendingWrite {
    Job::start("raygine-write", "writing", ctx, work)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::expect_used)]
    use super::*;

    fn no_threads(_: String, _: Box<dyn FnOnce() + Send>) -> std::io::Result<()> {
        Err(std::io::Error::other("no threads left"))
    }

    /// Polls until the job is done (a real thread needs a moment).
    fn wait<T: Send + 'static>(job: &Job<T>) -> Result<T, String> {
        let deadline = Instant::now() + std::time::Duration::from_secs(10);
        loop {
            if let Some(r) = job.poll() {
                return r;
            }
            assert!(Instant::now() < deadline, "the job never finished");
            std::thread::sleep(std::time::Duration::from_millis(2));
        }
    }

    #[test]
    fn a_job_reports_its_result_once() {
        let ctx = egui::Context::default();
        let job = Job::start("test-job", "adding", &ctx, || Ok(2 + 2));
        assert_eq!(wait(&job), Ok(4));
    }

    #[test]
    fn a_job_that_cannot_start_reports_an_error() {
        let ctx = egui::Context::default();
        let job: Job<u32> = Job::start_on(no_threads, "test-job", "adding", &ctx, || Ok(4));
        assert_eq!(
            job.poll(),
            Some(Err("cannot start adding: no threads left".to_owned()))
        );
    }

    #[test]
    fn a_job_whose_thread_dies_reports_an_error() {
        let ctx = egui::Context::default();
        // The work is dropped unrun, as when its thread panics before sending.
        fn drop_work(_: String, work: Box<dyn FnOnce() + Send>) -> std::io::Result<()> {
            drop(work);
            Ok(())
        }
        let job: Job<u32> = Job::start_on(drop_work, "test-job", "adding", &ctx, || Ok(4));
        assert_eq!(
            job.poll(),
            Some(Err("adding stopped unexpectedly".to_owned()))
        );
    }

    #[test]
    fn a_dialog_that_cannot_start_is_an_error_not_a_cancel() {
        let ctx = egui::Context::default();
        let dialog = PendingDialog::start_on(no_threads, DialogPurpose::Open, None, &ctx);
        let result = dialog.poll().expect("the failure is reported at once");
        let error = result.expect_err("a failed dialog is not 'cancelled'");
        assert!(error.contains("cannot start the file dialog"), "{error}");
    }
}
