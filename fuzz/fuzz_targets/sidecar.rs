//! Sidecar TOML through `Sidecar::parse`; when it parses, `apply` to a small two-brep scene
//! (one brep with three parts), a tiny render of the resulting setup, and the way back to TOML.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use std::sync::OnceLock;
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::{Scene, Sidecar};
use tracer_core::shp::parse_shp;

/// Brep `a`: a quad of two triangles in parts 0 and 2 (part 1 unused); brep `b`: one triangle.
const SCENE: &str = "\
define breps a
vertices 4
0 0 0
10 0 0
10 10 0
0 10 0
triangles 2
0 1 2
0 2 3
parts 3
0 2
enddef
define breps b
vertices 3
0 0 -5
10 0 -5
0 10 -5
triangles 1
0 1 2
enddef
set breps b
rotation 0 0 45
translation 1 2 3
scale 1 1 1
enddef
";

fn scene() -> Option<&'static Scene> {
    static SCENE_CELL: OnceLock<Option<Scene>> = OnceLock::new();
    SCENE_CELL
        .get_or_init(|| {
            let desc = parse_shp(SCENE.as_bytes(), Path::new("fuzz.shp")).ok()?;
            Scene::build(&desc, "fuzz").ok()
        })
        .as_ref()
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(sidecar) = Sidecar::parse(text, Path::new("fuzz.raygine.toml")) else {
        return;
    };
    let Some(scene) = scene() else {
        return;
    };
    let mut warnings = Vec::new();
    let setup = sidecar.apply(scene, None, &mut warnings);
    let settings = RenderSettings {
        width: 4,
        height: 3,
        samples_per_pixel: 1,
        max_depth: 3,
        ..RenderSettings::default()
    };
    let _ = render(scene, &setup, &settings);
    let _ = Sidecar::from_setup(scene, &setup).to_toml();
});
