//! Work with files off the UI thread: loading scenes, native dialogs, exports, and the
//! "Render image..." job. Each task reports back through a channel and wakes the UI.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::time::Instant;
use tracer_core::scene::{LoadOptions, LoadedScene};

/// A scene being read on a background thread.
#[derive(Debug)]
pub struct PendingLoad {
    pub path: PathBuf,
    pub started: Instant,
    rx: Receiver<Result<LoadedScene, String>>,
}

impl PendingLoad {
    /// Starts reading `path` (parse, BVH build, sidecar) on a named thread.
    pub fn start(path: &Path, ctx: &egui::Context) -> Self {
        Self::start_in_unit(path, None, ctx)
    }

    /// [`PendingLoad::start`] with the scene's length unit given (it wins over the sidecar's).
    pub fn start_in_unit(
        path: &Path,
        unit: Option<tracer_core::scene::LengthUnit>,
        ctx: &egui::Context,
    ) -> Self {
        let (tx, rx) = channel();
        let p = path.to_path_buf();
        let repaint = ctx.clone();
        let spawned = std::thread::Builder::new()
            .name("raygine-load".to_owned())
            .spawn(move || {
                let options = LoadOptions {
                    unit,
                    ..LoadOptions::default()
                };
                let result = tracer_core::scene::load(&p, &options).map_err(|e| e.to_string());
                let _ = tx.send(result);
                repaint.request_repaint();
            });
        let (tx_err, rx_err) = channel();
        let rx = match spawned {
            Ok(_) => rx,
            Err(e) => {
                let _ = tx_err.send(Err(format!("cannot start loading: {e}")));
                rx_err
            }
        };
        Self {
            path: path.to_path_buf(),
            started: Instant::now(),
            rx,
        }
    }

    /// The result once the load has finished.
    pub fn poll(&self) -> Option<Result<LoadedScene, String>> {
        match self.rx.try_recv() {
            Ok(r) => Some(r),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => {
                Some(Err("the loader stopped unexpectedly".to_owned()))
            }
        }
    }
}

/// What a native dialog was asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DialogPurpose {
    Open,
    ExportPng,
    ExportExr,
    SaveSidecar,
    RenderImage,
}

/// A native file dialog running on its own thread (rfd); `None` means cancelled or unavailable.
#[derive(Debug)]
pub struct PendingDialog {
    pub purpose: DialogPurpose,
    pub started: Instant,
    rx: Receiver<Option<PathBuf>>,
}

/// A dialog that closes with nothing sooner than this never showed: without a desktop portal
/// rfd returns at once.
pub const NO_DIALOG_SECS: f32 = 0.4;

impl PendingDialog {
    pub fn start(purpose: DialogPurpose, suggested: Option<&Path>, ctx: &egui::Context) -> Self {
        let (tx, rx) = channel();
        let repaint = ctx.clone();
        let suggested = suggested.map(Path::to_path_buf);
        let _ = std::thread::Builder::new()
            .name("raygine-dialog".to_owned())
            .spawn(move || {
                let mut dialog = rfd::FileDialog::new();
                if let Some(dir) = suggested.as_deref().and_then(Path::parent)
                    && !dir.as_os_str().is_empty()
                {
                    dialog = dialog.set_directory(dir);
                }
                if let Some(name) = suggested.as_deref().and_then(Path::file_name) {
                    dialog = dialog.set_file_name(name.to_string_lossy());
                }
                let picked = match purpose {
                    DialogPurpose::Open => {
                        dialog.add_filter("Lumicept scene", &["shp"]).pick_file()
                    }
                    DialogPurpose::ExportPng | DialogPurpose::RenderImage => {
                        dialog.add_filter("PNG image", &["png"]).save_file()
                    }
                    DialogPurpose::ExportExr => {
                        dialog.add_filter("OpenEXR image", &["exr"]).save_file()
                    }
                    DialogPurpose::SaveSidecar => {
                        dialog.add_filter("raygine sidecar", &["toml"]).save_file()
                    }
                };
                let _ = tx.send(picked);
                repaint.request_repaint();
            });
        Self {
            purpose,
            started: Instant::now(),
            rx,
        }
    }

    /// A dialog that has already closed with `picked` (tests; platforms without dialogs).
    pub fn finished(purpose: DialogPurpose, picked: Option<PathBuf>) -> Self {
        let (tx, rx) = channel();
        let _ = tx.send(picked);
        Self {
            purpose,
            started: Instant::now(),
            rx,
        }
    }

    /// `Some(result)` once the dialog closed.
    pub fn poll(&self) -> Option<Option<PathBuf>> {
        match self.rx.try_recv() {
            Ok(r) => Some(r),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => Some(None),
        }
    }
}

/// A write running in the background (export or sidecar save); reports a line for the user.
#[derive(Debug)]
pub struct PendingWrite {
    rx: Receiver<Result<String, String>>,
}

impl PendingWrite {
    pub fn start(
        ctx: &egui::Context,
        work: impl FnOnce() -> Result<String, String> + Send + 'static,
    ) -> Self {
        let (tx, rx) = channel();
        let repaint = ctx.clone();
        let spawned = std::thread::Builder::new()
            .name("raygine-write".to_owned())
            .spawn(move || {
                let _ = tx.send(work());
                repaint.request_repaint();
            });
        if let Err(e) = spawned {
            let (tx2, rx2) = channel();
            let _ = tx2.send(Err(format!("cannot start writing: {e}")));
            return Self { rx: rx2 };
        }
        Self { rx }
    }

    pub fn poll(&self) -> Option<Result<String, String>> {
        match self.rx.try_recv() {
            Ok(r) => Some(r),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => {
                Some(Err("the writer stopped unexpectedly".to_owned()))
            }
        }
    }
}
