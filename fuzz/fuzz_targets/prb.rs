//! Integra `.prb` part-to-attribute maps through `formats::integra::parse_prb`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let _ = tracer_core::formats::integra::parse_prb(data, Path::new("fuzz.prb"));
});
