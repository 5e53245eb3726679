//! The open scene: its immutable geometry (shared with render threads) and its editable setup.

use std::path::PathBuf;
use std::sync::Arc;
use tracer_core::scene::{LoadedScene, Scene, Setup};

#[derive(Debug)]
pub struct Document {
    pub scene: Arc<Scene>,
    pub setup: Setup,
    /// The `.shp` it came from; None for the built-in Cornell box.
    pub path: Option<PathBuf>,
    pub parse_secs: f64,
    /// Non-fatal problems found while loading.
    pub warnings: Vec<String>,
    /// The scene as read, while `scene` is it with a ground plane (View > Ground plane).
    pub without_ground: Option<Arc<Scene>>,
}

impl Document {
    pub fn from_loaded(loaded: LoadedScene, path: Option<PathBuf>) -> Self {
        Self {
            scene: Arc::new(loaded.scene),
            setup: loaded.setup,
            path,
            parse_secs: loaded.parse_secs,
            warnings: loaded.warnings,
            without_ground: None,
        }
    }

    /// The built-in Cornell box.
    pub fn builtin() -> anyhow::Result<Self> {
        Ok(Self::from_loaded(
            tracer_core::scene::builtin_cornell_box(None)?,
            None,
        ))
    }

    pub fn title(&self) -> String {
        match &self.path {
            Some(p) => p.display().to_string(),
            None => self.scene.name.clone(),
        }
    }
}
