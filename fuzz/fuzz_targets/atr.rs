//! Integra `.atr` attributes through `formats::integra::parse_atr`; each attribute read is
//! mapped to a material and on to the model (tint, clamps, transmission and emission notes).
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use tracer_core::formats::integra;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.atr");
    if let Ok(attrs) = integra::parse_atr(data, path) {
        let mut notes = Vec::new();
        for attr in &attrs {
            let m = integra::material_from_attr(attr, path, &mut notes);
            let _ = tracer_core::scene::material_from_description(&m, &mut notes);
        }
    }
});
