//! Integra `.cam` cameras through `formats::integra::parse_cam`; a camera that parses is turned
//! into position, look-at, up and field of view, and a camera basis with one ray.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use tracer_core::scene::{Camera, Handedness};

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.cam");
    let Ok(Some(cam)) = tracer_core::formats::integra::parse_cam(data, path) else {
        return;
    };
    if let Ok(c) = cam.to_camera(path) {
        let camera = Camera {
            position: c.position,
            look_at: c.look_at,
            up: c.up,
            fov_deg: c.fov_deg,
        };
        let [w, h] = c.resolution.unwrap_or([16, 9]);
        let basis = camera.basis(Handedness::Left, w, h);
        let _ = basis.ray(0.5 * w as f32, 0.5 * h as f32);
    }
});
