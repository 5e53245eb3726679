//! tracer-core's integration tests, one module per suite, built as one test binary: one link
//! instead of 24, and the shared helpers compiled once. Run one suite with
//! `cargo test -p tracer-core --test core SUITE::` (e.g. `bdpt_analytic::`).

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod bvh_support;
mod gi_support;

mod adaptive;
mod alpha;
mod area_luminaires;
mod bdpt_analytic;
mod bvh_differential;
mod bvh_speed;
mod cornell_reference;
mod daylight;
mod default_setup;
mod denoise;
mod direct_wavefront;
mod environment;
mod environment_input;
mod film_precision;
mod fuzz_corpus;
mod gi_analytic;
mod glare;
mod glare_evalglare;
mod guth_table_copy;
mod illuminance_on_demand;
mod instancing;
mod integra_bundle;
mod integra_room2;
mod luminaires;
mod many_lights;
mod measure_grids;
mod metal_peers;
mod metal_rough;
mod panes;
mod projections;
mod proptest_shp;
mod radiance_daylight;
mod session;
mod session_adaptive;
mod shading_analytic;
mod shp_errors;
mod shp_format;
mod shp_real_files;
mod shp_robustness;
mod shp_speed;
mod std_error_honesty;
mod stress_limits;
mod stress_session;
mod textures;
mod usd;
