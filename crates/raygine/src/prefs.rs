//! The app's own persisted settings: display preferences, render preferences, recent files and
//! the last scene. Scene content (materials, lights, camera) lives in the scene's sidecar.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use tracer_core::integrator::IntegratorKind;

/// Storage key of the preferences.
pub const PREFS_KEY: &str = "raygine-prefs";
const MAX_RECENT: usize = 8;

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Prefs {
    pub recent: Vec<PathBuf>,
    pub last_scene: Option<PathBuf>,
    /// No longer read: exposure is kept per scene (`exposures`); stays so older files load.
    pub exposure_stops: f32,
    /// Each scene's exposure, by [`crate::scene_exposure::scene_key`].
    pub exposures: std::collections::BTreeMap<String, crate::scene_exposure::SceneExposure>,
    pub auto_exposure: bool,
    pub tone_map: String,
    /// "path" (global illumination) or "direct".
    pub integrator: String,
    pub max_depth: u32,
    pub target_spp: u32,
    pub resolution_scale: f32,
    pub adaptive: bool,
}

impl Default for Prefs {
    fn default() -> Self {
        Self {
            recent: Vec::new(),
            last_scene: None,
            exposure_stops: 0.0,
            exposures: std::collections::BTreeMap::new(),
            auto_exposure: false,
            tone_map: "filmic".to_owned(),
            integrator: default_integrator().name().to_owned(),
            max_depth: tracer_core::render::DEFAULT_MAX_DEPTH,
            target_spp: 64,
            resolution_scale: 1.0,
            adaptive: true,
        }
    }
}

/// The light transport a new user starts with: global illumination, bidirectional (lamps close
/// to surfaces converge in seconds, as in the built-in Cornell box).
pub fn default_integrator() -> IntegratorKind {
    IntegratorKind::DEFAULT_GI
}

impl Prefs {
    /// Puts `path` first in the recent list (once).
    pub fn add_recent(&mut self, path: &Path) {
        self.recent.retain(|p| p != path);
        self.recent.insert(0, path.to_path_buf());
        self.recent.truncate(MAX_RECENT);
    }
}
