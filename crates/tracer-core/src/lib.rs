//! # tracer-core: the raygine renderer as a library
//!
//! ```text
//!  .shp / .brs (+ Integra bundle) ──formats::read_scene──▶ SceneDescription (neutral, plain data)
//!                                        │ scene::Scene::build (+ sidecar: materials, lights, camera)
//!                                        ▼
//!                                      Scene ──bvh::Bvh::build──▶ BVH over world triangles
//!                                        │
//!                                        │ lit_scene::LitScene (+ setup: lights, material constants, emitters)
//!                                        ▼
//!                     integrator (direct, path, bidirectional, light tracing; shading's BSDFs)
//!                                        │
//!                     render (tiles, passes, samples seeded by pixel and sample index)
//!                                        ▼
//!                                Film (linear HDR cd/m², per-pixel illuminance lx)
//!                                        │ display (exposure, tone map, sRGB, false colour)
//!                                        ▼
//!                                    PNG / EXR
//! ```
//!
//! Across machines: [`shard`] splits the sample range into M contiguous shards whose films (or
//! grid sums) are written as part files and added exactly, bit-identical to one machine's.
//!
//! Units: lengths in the scene unit (mm, cm or m, see [`scene::LengthUnit`]); light is photometric
//! SI: intensity in candela, illuminance in lux, luminance in cd/m². Angles are radians inside.
//! This crate knows nothing of egui, dialogs or UI threads.

pub mod bvh;
pub mod denoise;
pub mod display;
pub mod export;
pub mod formats;
pub mod geometry;
pub mod glare;
pub mod integrator;
mod lanes8;
pub mod light;
pub mod lit_scene;
pub mod measure;
mod pages;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod shading;
pub mod shard;
#[cfg(test)]
mod test_scenes;
pub mod texture;

/// The `.shp` reader, kept at its old path (it lives in [`formats::shp`]).
pub use formats::shp;

pub use geometry::{Aabb, Ray};
