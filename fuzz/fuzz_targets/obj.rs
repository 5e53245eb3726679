//! OBJ text through `formats::obj::parse`, with every `mtllib` answered by the same bytes (so
//! one input exercises the OBJ check, the MTL check and both tobj parsers); on `Ok` the scene is
//! built (smooth normals, BVH).
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::{Path, PathBuf};
use tracer_core::formats::{ReadOptions, obj};

fuzz_target!(|data: &[u8]| {
    let libraries = |_: &str| Some((PathBuf::from("fuzz.mtl"), data.to_vec()));
    if let Ok(desc) = obj::parse(data, Path::new("fuzz.obj"), &libraries, &ReadOptions::default()) {
        let _ = tracer_core::scene::Scene::build(&desc, "fuzz");
    }
});
