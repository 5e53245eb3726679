//! The option groups several commands share: the scene and its sampling, and the display
//! mapping of images; with their value parsers.

use clap::Args;
use std::path::PathBuf;
use tracer_core::display::ToneMap;
use tracer_core::integrator::IntegratorKind;
use tracer_core::scene::LengthUnit;

/// Samples per pixel (or per sensor point) in path mode when `--samples` is not given.
pub const PATH_DEFAULT_SAMPLES: u32 = 64;

/// The scene and sampling options every command shares.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// Scene file (Lumicept .shp, an Integra bundle's .shp, .brs, .obj, .gltf, .glb, .usda,
    /// .usdc, .usdz, .usd). Without it, the built-in Cornell box.
    #[arg(
        short = 'S',
        long = "scene_path",
        visible_alias = "scene-path",
        value_name = "PATH"
    )]
    pub scene_path: Option<PathBuf>,
    /// Sidecar with materials, lights, camera and grids (default: NAME.raygine.toml beside the
    /// scene).
    #[arg(long, value_name = "PATH")]
    pub sidecar: Option<PathBuf>,
    /// Scene length unit: mm, cm or m (default: the sidecar's, else mm).
    #[arg(long, value_name = "UNIT")]
    pub units: Option<LengthUnit>,
    /// USD scenes: the time code attributes are read at (default: their default values, or
    /// the earliest time sample of attributes that have only samples).
    #[arg(long, value_name = "TIME", allow_negative_numbers = true)]
    pub usd_time: Option<f64>,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: Option<u32>,
    /// Light transport: direct (the coursework's model: direct light and mirrors), or global
    /// illumination by path tracing (path), bidirectional path tracing (bdpt) or light
    /// tracing (light). Also spelled --gi; `--gi` alone (or `--gi gi`) is the default
    /// global illumination.
    #[arg(long, visible_alias = "gi", value_name = "direct|path|bdpt|light", default_value = "direct", num_args = 0..=1, default_missing_value = "gi", value_parser = parse_integrator)]
    pub integrator: IntegratorKind,
    /// Path mode: at most N diffuse or glossy bounces (1: direct light only; mirrors do not
    /// count). Default: no limit.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100000))]
    pub max_bounces: Option<u32>,
    /// Samples per pixel or per sensor point (default: 1, 16 with -A; 64 in the
    /// global-illumination modes: path, bdpt, light). A cap when --time-limit is given
    /// (render: of every pixel, default 65536).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1048576))]
    pub samples: Option<u32>,
    /// Stop after this many seconds (between passes), with --samples as a cap. `render`
    /// samples adaptively then (after 16 samples in every pixel, where the error is highest).
    #[arg(long, value_name = "SECS", value_parser = parse_seconds)]
    pub time_limit: Option<f64>,
}

/// How the linear image becomes display pixels (PNG): shared by render, merge and sweep.
#[derive(Debug, Args)]
pub struct DisplayArgs {
    /// Exposure in stops (0: 100 cd/m² is display white). Default 0.
    #[arg(
        long,
        value_name = "STOPS",
        allow_hyphen_values = true,
        conflicts_with = "auto_exposure"
    )]
    pub exposure: Option<f32>,
    /// Choose the exposure from the image (log-average luminance to middle grey).
    #[arg(long)]
    pub auto_exposure: bool,
    /// Tone curve: clamp, reinhard or filmic.
    #[arg(long, default_value = "filmic", value_parser = parse_tone_map)]
    pub tone_map: ToneMap,
}

fn parse_integrator(s: &str) -> Result<IntegratorKind, String> {
    IntegratorKind::from_name(s)
        .ok_or_else(|| format!("unknown integrator `{s}` (direct, path, bdpt, light)"))
}

fn parse_seconds(s: &str) -> Result<f64, String> {
    s.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0)
        .ok_or_else(|| format!("`{s}` is not a positive number of seconds"))
}

impl SceneArgs {
    /// Samples per pixel or point: --samples, else `fallback` in direct mode, 64 in the
    /// global-illumination modes.
    pub fn samples_or(&self, fallback: u32) -> u32 {
        self.samples.unwrap_or(match self.integrator {
            IntegratorKind::Direct => fallback,
            IntegratorKind::Path | IntegratorKind::Bidirectional | IntegratorKind::Light => {
                PATH_DEFAULT_SAMPLES
            }
        })
    }
}

pub fn parse_tone_map(s: &str) -> Result<ToneMap, String> {
    ToneMap::from_name(s).ok_or_else(|| format!("unknown tone map `{s}` (clamp, reinhard, filmic)"))
}

/// Parses `x,y,z` (spaces allowed) into three finite numbers.
pub fn parse_vec3(s: &str) -> Result<[f32; 3], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [x, y, z] = parts.as_slice() else {
        return Err(format!("expected x,y,z, got `{s}`"));
    };
    let num = |t: &str| -> Result<f32, String> {
        t.parse::<f32>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| format!("`{t}` is not a finite number"))
    };
    Ok([num(x)?, num(y)?, num(z)?])
}
