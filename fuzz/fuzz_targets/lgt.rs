//! Integra `.lgt` luminaires through `formats::integra::parse_lgt`; a file that parses has its
//! fixtures turned into lights (groups, switches, diagrams) and those into model lights, whose
//! flux and intensity at a few angles are asked for.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use tracer_core::formats::integra;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.lgt");
    let Ok(lgt) = integra::parse_lgt(data, path) else {
        return;
    };
    let Ok(lights) = integra::lights_from_lgt(&lgt, path, &mut Vec::new()) else {
        return;
    };
    for l in &lights {
        let light = tracer_core::scene::light_from_description(l);
        let _ = light.flux_lm();
        if let Some(lum) = &light.luminaire {
            for (c, g) in [(0.0, 0.0), (90.0, 45.0), (359.9, 179.9)] {
                let _ = lum.photometry.intensity(c, g);
            }
        }
    }
});
