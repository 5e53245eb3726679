//! Bare `.brs` brep bytes through the reader.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use tracer_core::shp::parse_brs;

fuzz_target!(|data: &[u8]| {
    let _ = parse_brs(data, Path::new("fuzz.brs"), "fuzz");
});
