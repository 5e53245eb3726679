//! The sidecar's `[environment]` table: light from every direction at infinity.
//!
//! ```toml
//! [environment]
//! file = "sky.hdr"        # latitude-longitude .hdr or .exr, 2:1 (relative to the sidecar)
//! scale = 1.0             # cd/m² per unit of the map's luminance (Radiance maps: 179)
//! rotation_deg = 0.0      # about the scene's up axis
//! background = true       # false keeps the viewer's backdrop behind the scene
//! ```
//!
//! or, instead of `file`, a uniform sky: `luminance_cd_m2 = 1000.0` and `color = [1, 1, 1]`.

use crate::light::{Environment, EnvironmentMap, EnvironmentSource};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentSpec {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub luminance_cd_m2: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation_deg: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub background: Option<bool>,
}

impl EnvironmentSpec {
    /// The environment it describes, its map read (relative to `base_dir`), with notes on
    /// what was read but is suspect (invalid texels).
    pub fn to_model(&self, base_dir: Option<&Path>) -> Result<(Environment, Vec<String>), String> {
        let mut notes = Vec::new();
        let source = match (&self.file, self.luminance_cd_m2) {
            (Some(_), Some(_)) => {
                return Err("environment: give `file` or `luminance_cd_m2`, not both".to_string());
            }
            (None, None) => {
                return Err(
                    "environment: give `file` (an .hdr or .exr map) or `luminance_cd_m2`"
                        .to_string(),
                );
            }
            (Some(file), None) => {
                if self.color.is_some() {
                    return Err(
                        "environment: `color` applies to `luminance_cd_m2`, not to a map"
                            .to_string(),
                    );
                }
                let path = match base_dir {
                    Some(dir) => dir.join(file),
                    None => file.into(),
                };
                let (map, map_notes) =
                    EnvironmentMap::load(&path).map_err(|e| format!("environment: {e}"))?;
                notes.extend(map_notes.into_iter().map(|n| format!("environment: {n}")));
                EnvironmentSource::Map(Arc::new(map))
            }
            (None, Some(luminance_cd_m2)) => EnvironmentSource::Uniform {
                luminance_cd_m2,
                color: self.color.unwrap_or([1.0; 3]),
            },
        };
        let env = Environment {
            source,
            scale: self.scale.unwrap_or(1.0),
            rotation_deg: self.rotation_deg.unwrap_or(0.0),
            background: self.background.unwrap_or(true),
        };
        if !env.is_valid() {
            return Err(
                "environment: luminance_cd_m2, color and scale must be finite and >= 0, \
                 rotation_deg finite"
                    .to_string(),
            );
        }
        Ok((env, notes))
    }

    /// The table that gives `env` again (a map by the path it was read from).
    pub fn from_model(env: &Environment) -> Self {
        let mut spec = EnvironmentSpec {
            scale: (env.scale != 1.0).then_some(env.scale),
            rotation_deg: (env.rotation_deg != 0.0).then_some(env.rotation_deg),
            background: (!env.background).then_some(false),
            ..EnvironmentSpec::default()
        };
        match &env.source {
            EnvironmentSource::Uniform {
                luminance_cd_m2,
                color,
            } => {
                spec.luminance_cd_m2 = Some(*luminance_cd_m2);
                spec.color = (*color != [1.0; 3]).then_some(*color);
            }
            EnvironmentSource::Map(map) => spec.file = Some(map.file.display().to_string()),
        }
        spec
    }
}
