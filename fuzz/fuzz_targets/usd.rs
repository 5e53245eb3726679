//! USD bytes (`.usda` text, `.usdc` crate binary by its `PXR-USDC` magic, `.usdz` by its zip
//! magic) through `formats::usd::read` (the stage opens from a file, so the bytes are written
//! to one; layers it names are looked up beside it and are absent); on `Ok` the scene is built.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tracer_core::formats::{ReadOptions, usd};

fuzz_target!(|data: &[u8]| {
    // A file openusd loops on is refused after 3 s (libFuzzer's own limit is 10 s).
    let options = ReadOptions {
        usd_trial_secs: Some(3.0),
        ..ReadOptions::default()
    };
    let ext = if data.starts_with(b"PXR-USDC") {
        "usdc"
    } else if data.starts_with(b"PK") {
        "usdz"
    } else {
        "usda"
    };
    let path = std::env::temp_dir().join(format!("raygine-fuzz-{}.{ext}", std::process::id()));
    if std::fs::write(&path, data).is_ok()
        && let Ok(desc) = usd::read(&path, &options)
    {
        let _ = tracer_core::scene::Scene::build(&desc, "fuzz");
    }
});
