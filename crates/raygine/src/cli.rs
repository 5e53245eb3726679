//! Command-line interface. `raygine render` keeps the coursework renderer's interface:
//! `raygine render -S scene.shp -W 1280 -H 720 -I 100 -A -R out.png lx ly lz cx cy cz cf`.

use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;
use tracer_core::scene::LengthUnit;

pub use crate::cli_args::{
    DisplayArgs, PATH_DEFAULT_SAMPLES, SceneArgs, parse_tone_map, parse_vec3,
};

#[derive(Debug, Parser)]
#[command(
    name = "raygine",
    version,
    about = "Interactive progressive ray tracer for lighting design"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Scene to open (Lumicept .shp or .brs, an Integra bundle's .shp, OBJ, glTF, .glb or USD:
    /// .usda, .usdc, .usdz, .usd); without one, the last scene or the built-in Cornell box.
    pub scene: Option<PathBuf>,
    /// Render threads of the viewer (default: all cores).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: Option<u32>,
    /// Start with the built-in Cornell box instead of reopening the last scene.
    #[arg(long)]
    pub no_restore: bool,
    /// Length unit of the scene opened: mm, cm or m (default: the sidecar's, else mm). The
    /// viewer's side panel changes it too.
    #[arg(long, value_name = "UNIT")]
    pub units: Option<LengthUnit>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a scene to a PNG (and optionally an EXR) without a window.
    Render(RenderArgs),
    /// Measure the illuminance on the sidecar's [[grids]] and write it as CSV.
    Measure(MeasureArgs),
    /// Say what a scene holds: unit, bounds, triangles, materials, lights, camera.
    Info(InfoArgs),
    /// Add the part files of sharded renders (or measurements) into the image (or readings).
    Merge(crate::cli_shards::MergeArgs),
    /// Render (and measure) variants of a scene, each a patch of its sidecar.
    Sweep(crate::cli_shards::SweepArgs),
    /// Measure the grids and write a lighting report (PDF): settings, a view, per grid a plan
    /// and its statistics, the luminaire schedule and the requirements check.
    Report(ReportArgs),
    /// Glare at the sidecar's [[observers]]: UGR and DGP with their standard errors, from a
    /// 180° fisheye at each eye (sources from the image and from luminaires' openings).
    /// Samples a pixel: 16 in direct mode, 64 otherwise, at least 2 (--samples).
    Glare(GlareArgs),
}

#[derive(Debug, Args)]
pub struct GlareArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Only this observer (repeat for several; default: every observer).
    #[arg(long, value_name = "NAME")]
    pub observer: Vec<String>,
    /// Side of the square fisheye, pixels (32 to 4096): finer images judge small sources
    /// better (docs/glare.md).
    #[arg(long, value_name = "PX", default_value_t = tracer_core::glare::DEFAULT_IMAGE_SIZE,
          value_parser = clap::value_parser!(u32).range(32..=4096))]
    pub size: u32,
    /// Glare pixels (evalglare's -b): above this factor times the image's mean luminance, or
    /// above this luminance (cd/m²) when it is over 100.
    #[arg(long, value_name = "B", default_value_t = 5.0, value_parser = parse_positive)]
    pub threshold: f64,
    /// evalglare's -r (radians, full angle): glare pixels within half of it of each other
    /// form one source.
    #[arg(long, value_name = "RAD", default_value_t = 0.2, value_parser = parse_positive)]
    pub search_radius: f64,
    /// Apply evalglare's low-light correction of DGP below 1000 lx (-C l+).
    #[arg(long)]
    pub dgp_low_light: bool,
    /// Write every figure and source here (JSON).
    #[arg(long, value_name = "PATH")]
    pub json: Option<std::path::PathBuf>,
    /// Write one row per observer and way of finding sources here (CSV).
    #[arg(long, value_name = "PATH")]
    pub csv: Option<std::path::PathBuf>,
    /// Write each observer's fisheye as DIR/NAME.hdr, a Radiance picture for evalglare.
    #[arg(long, value_name = "DIR")]
    pub hdr: Option<std::path::PathBuf>,
}

fn parse_positive(s: &str) -> Result<f64, String> {
    s.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0)
        .ok_or_else(|| format!("`{s}` is not a positive number"))
}

#[derive(Debug, Args)]
pub struct ReportArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The PDF to write.
    #[arg(short = 'o', long, value_name = "PATH")]
    pub output: PathBuf,
    /// Measure until every point's standard error is at most PCT % of max(E_i, 0.1 × Eavg),
    /// as `measure --target-error` does (--samples caps it).
    #[arg(long, value_name = "PCT", value_parser = parse_percent)]
    pub target_error: Option<f64>,
    /// Paper: a4 (default) or letter.
    #[arg(long, value_name = "a4|letter", default_value = "a4")]
    pub paper: String,
    /// The requirements table (TOML) the grids' `task` keys name (default: raygine's, with
    /// EN 12464-1 rows and their sources).
    #[arg(long, value_name = "FILE")]
    pub requirements: Option<PathBuf>,
    /// Samples per pixel of the scene's view (default 16 direct, 64 otherwise).
    #[arg(long, value_name = "N")]
    pub view_samples: Option<u32>,
}

#[derive(Debug, Args)]
pub struct InfoArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Args)]
pub struct MeasureArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Write every grid point's illuminance here (CSV).
    #[arg(long, value_name = "PATH")]
    pub csv: Option<PathBuf>,
    /// Write the statistics and every point here (JSON).
    #[arg(long, value_name = "PATH")]
    pub json: Option<PathBuf>,
    /// How the CSV and JSON write readings: `rounded` (default) to what each one's standard
    /// error supports, 3 significant figures at most; `full`, every digit, for machines.
    #[arg(long, value_name = "rounded|full", default_value = "rounded", value_parser = parse_precision)]
    pub precision: tracer_core::measure::rounding::Precision,
    /// Stop once every point's standard error is at most PCT % of max(E_i, 0.1 × Eavg of its
    /// grid), after at least 64 samples; --samples caps it (default 65536).
    #[arg(long, value_name = "PCT", value_parser = parse_percent)]
    pub target_error: Option<f64>,
    /// Measure daylight factors: DF = E_in / E_out,h in %, under the CIE overcast sky without
    /// sun, lights or glowing surfaces, whatever the sidecar's sky (E_out,h computed).
    #[arg(long)]
    pub daylight_factor: bool,
    #[command(flatten)]
    pub shard: crate::cli_shards::ShardArgs,
}

fn parse_projection(s: &str) -> Result<tracer_core::scene::Projection, String> {
    tracer_core::scene::Projection::from_name(s).ok_or_else(|| {
        let names: Vec<&str> = tracer_core::scene::Projection::ALL
            .iter()
            .map(|p| p.name())
            .collect();
        format!("unknown projection `{s}`; one of {}", names.join(", "))
    })
}

pub(crate) fn parse_precision(
    s: &str,
) -> Result<tracer_core::measure::rounding::Precision, String> {
    tracer_core::measure::rounding::Precision::from_name(s)
        .ok_or_else(|| format!("`{s}`: the precision is `rounded` or `full`"))
}

fn parse_percent(s: &str) -> Result<f64, String> {
    s.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0 && *v <= 100.0)
        .ok_or_else(|| format!("`{s}` is not a percentage between 0 and 100"))
}

#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Image width in pixels.
    #[arg(short = 'W', long, default_value_t = 1280, value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub width: u32,
    /// Image height in pixels.
    #[arg(short = 'H', long, default_value_t = 720, value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub height: u32,
    /// Intensity of the first point light, candela (cd).
    #[arg(short = 'I', long, value_name = "CD")]
    pub intensity: Option<f32>,
    /// Antialiasing: 16 jittered samples per pixel.
    #[arg(short = 'A', long)]
    pub antialiased: bool,
    /// Output PNG (default: the scene's path with .png; cornell_box.png for the built-in scene).
    #[arg(
        short = 'R',
        long = "render_path",
        visible_alias = "render-path",
        value_name = "PATH"
    )]
    pub render_path: Option<PathBuf>,
    /// Maximum mirror reflection depth (direct mode).
    #[arg(long, default_value_t = tracer_core::render::DEFAULT_MAX_DEPTH, value_parser = clap::value_parser!(u32).range(0..=64))]
    pub depth: u32,
    #[command(flatten)]
    pub display: DisplayArgs,
    /// Point the camera looks at, `x,y,z` (default: the scene's, or -Z from a camera placed by
    /// the positional arguments).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub look_at: Option<[f32; 3]>,
    /// Also write the linear image (cd/m² per channel) as OpenEXR.
    #[arg(long, value_name = "PATH")]
    pub exr: Option<PathBuf>,
    /// Denoise the PNG with Intel Open Image Denoise 2.x (albedo and normal guides); the EXR
    /// keeps the raw R, G, B and adds denoised.R, .G, .B. Printed figures stay the raw image's.
    /// With --time-limit, the limit includes denoising. With --partial, the part keeps the
    /// guides for `merge --denoise`.
    #[arg(long)]
    pub denoise: bool,
    /// Stop once every pixel's standard error is at most PCT % of max(Y, 0.1 × the image's
    /// mean luminance), leaving out the 0.5 % brightest pixels (a lamp's hot spot); samples go
    /// where the error is highest. --samples caps every pixel (default 65536).
    #[arg(long, value_name = "PCT", value_parser = parse_percent)]
    pub target_error: Option<f64>,
    /// With --time-limit or --target-error: give every pixel the same number of samples
    /// instead of sending them where the error is highest.
    #[arg(long, conflicts_with = "target_error")]
    pub no_adaptive: bool,
    /// Camera projection: perspective, fisheye-equidistant (Radiance -vta), fisheye-equisolid,
    /// hemispherical (-vth), equirectangular (360° x 180°) or orthographic (default: the
    /// scene's camera's). Fisheyes take a field of view up to 180°, across the image circle.
    #[arg(long, value_name = "NAME", value_parser = parse_projection)]
    pub projection: Option<tracer_core::scene::Projection>,
    /// Orthographic camera: the image's width in scene units (default: the perspective view's
    /// width at the look-at point).
    #[arg(long, value_name = "UNITS")]
    pub ortho_width: Option<f32>,
    /// Light position, camera position and field of view (degrees; vertical for perspective,
    /// across the image circle for fisheyes): `lx ly lz cx cy cz cf`, or any prefix of them.
    #[arg(value_name = "LX LY LZ CX CY CZ CF", num_args = 0..=7)]
    pub positional: Vec<f32>,
    #[command(flatten)]
    pub shard: crate::cli_shards::ShardArgs,
}
