//! `.shp` bytes through the reader and, when they parse, through `Scene::build` (placements,
//! world transform, BVH). Any panic, hang or runaway allocation is a bug.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use tracer_core::scene::Scene;
use tracer_core::shp::parse_shp;

fuzz_target!(|data: &[u8]| {
    if let Ok(desc) = parse_shp(data, Path::new("fuzz.shp")) {
        let _ = Scene::build(&desc, "fuzz");
    }
});
