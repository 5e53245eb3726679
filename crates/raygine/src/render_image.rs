//! "Render image...": a render of its own (size and samples from the form) on its own session,
//! mapped and written as a PNG in the background when it finishes.

use crate::file_ops::{PendingWrite, start_write};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;
use tracer_core::display::DisplaySettings;
use tracer_core::render::{RenderSession, RenderSettings, Snapshot};

/// A running "Render image..." job.
#[derive(Debug)]
pub struct RenderImageJob {
    pub worker: RenderSession,
    pub path: PathBuf,
    pub display: DisplaySettings,
    pub started: Instant,
}

impl RenderImageJob {
    /// Starts rendering `snapshot` at `size` pixels and `samples` per pixel (the rest of its
    /// settings as in the viewport) on `threads` threads, to be written to `path` through
    /// `display`.
    pub fn start(
        mut snapshot: Snapshot,
        size: [u32; 2],
        samples: u32,
        threads: usize,
        path: PathBuf,
        display: DisplaySettings,
    ) -> Result<Self, String> {
        let worker = RenderSession::new(threads, Arc::new(|| {}))
            .map_err(|e| format!("cannot start the render: {e}"))?;
        snapshot.settings = RenderSettings {
            width: size[0].clamp(1, 16_384),
            height: size[1].clamp(1, 16_384),
            samples_per_pixel: samples.clamp(1, 65_536),
            ..snapshot.settings
        };
        worker.start(snapshot);
        Ok(Self {
            worker,
            path,
            display,
            started: Instant::now(),
        })
    }

    /// Whether the render has finished.
    pub fn finished(&self) -> bool {
        let stats = self.worker.stats();
        stats.finished && stats.generation == self.worker.generation()
    }

    /// Writes the finished render in the background; says what it wrote.
    pub fn write(self, ctx: &egui::Context) -> Result<PendingWrite, String> {
        let film = self.worker.with_film(|f| f.map(|f| f.accum.clone()));
        let film = film.ok_or_else(|| "the render produced no image".to_owned())?;
        let display = self.display;
        let path = self.path;
        let secs = self.started.elapsed().as_secs_f64();
        Ok(start_write(ctx, move || {
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
        }))
    }
}
