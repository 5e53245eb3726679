//! IES LM-63 text through `formats::parse_photometry` (read as `.ies`); a table that parses is
//! sampled at a few angles.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    if let Ok(p) = tracer_core::formats::parse_photometry(data, Path::new("fuzz.ies")) {
        for (c, g) in [(0.0, 0.0), (45.0, 30.0), (359.9, 179.9), (-10.0, 90.0)] {
            let _ = p.intensity(c, g);
        }
    }
});
