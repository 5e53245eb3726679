//! End-to-end tests of the `raygine` binary, one module per suite, built as one test binary (one
//! link instead of eight). One suite: `cargo test -p raygine-e2e --test e2e SUITE::`.

mod builtin_scene;
mod course_scene;
mod daylight;
mod denoise;
mod errors;
mod exr_and_units;
mod gi_and_measure;
mod glare;
mod integra;
mod obj_gltf;
mod report;
mod shards;
