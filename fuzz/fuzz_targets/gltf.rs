//! glTF JSON or GLB bytes through `formats::gltf::parse` (buffer files are refused; `data:`
//! URIs and the GLB chunk are read); on `Ok` the scene is built (smooth normals, BVH).
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use tracer_core::formats::{ReadOptions, gltf};

fuzz_target!(|data: &[u8]| {
    let external = |_: &Path| Err("no files while fuzzing".to_owned());
    if let Ok(desc) = gltf::parse(data, Path::new("fuzz.gltf"), &external, &ReadOptions::default()) {
        let _ = tracer_core::scene::Scene::build(&desc, "fuzz");
    }
});
