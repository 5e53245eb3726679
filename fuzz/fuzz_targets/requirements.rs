//! A report's requirements table (TOML) through `Requirements::parse`; when it parses, every
//! activity is looked up and checked against a small grid of readings.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tracer_core::measure::requirements::{Requirements, check};
use tracer_core::measure::{GridResult, PointResult};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(table) = Requirements::parse(text, "fuzz.toml") else {
        return;
    };
    let grid = GridResult {
        name: "g".into(),
        normal: glam::Vec3::Y,
        points: [120.0, 480.0, 0.0]
            .iter()
            .map(|&e| PointResult {
                i: 0,
                j: 0,
                position: glam::Vec3::ZERO,
                illuminance_lx: e,
                std_error_lx: 3.0,
                buried: false,
            })
            .collect(),
        samples: 4,
        rays: 0,
    };
    for a in &table.activities {
        let found = table.activity(&a.key);
        assert!(found.is_ok());
        let c = check(&grid, a, Some(80.0), &[("o".into(), Ok(Some((18.0, 0.2))))]);
        let _ = c.passes();
    }
    let _ = table.activity("no such key");
});
