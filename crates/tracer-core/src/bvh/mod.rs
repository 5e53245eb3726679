//! Bounding volume hierarchy over triangles: binned SAH build, flat nodes, closest-hit and any-hit
//! traversal, and `validate()` for its invariants.
//!
//! Interface (implementation to follow in `build.rs`, `traverse.rs`, `validate.rs`):
//!
//! ```ignore
//! let bvh = Bvh::build(&triangles);           // triangles: &[[Vec3; 3]]
//! let hit: Option<Hit> = bvh.intersect(&ray); // closest hit in [ray.t_min, ray.t_max]
//! let blocked: bool = bvh.occluded(&ray);     // any hit in [ray.t_min, ray.t_max]
//! bvh.validate()?;
//! ```
