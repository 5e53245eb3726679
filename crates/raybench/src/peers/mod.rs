//! The libraries traced side by side: raygine's own BVH and, behind cargo features, the reference
//! libraries. Each builds from the same triangle slice and answers the same two queries.

#[cfg(feature = "embree")]
pub mod embree;
#[cfg(feature = "embree")]
mod embree_ffi;
#[cfg(feature = "obvhs")]
pub mod obvhs;
pub mod raygine;

use glam::Vec3;
use tracer_core::Ray;

/// A built acceleration structure that can be queried from many threads at once.
pub trait Accel: Send + Sync + Sized {
    /// Name printed as `lib=`.
    const NAME: &'static str;

    /// Builds over `triangles`. Rayon-parallel builders run on the current pool; builders with
    /// their own threads use `threads` of them.
    fn build(triangles: &[[Vec3; 3]], threads: usize) -> anyhow::Result<Self>;

    /// Closest hit in `[ray.t_min, ray.t_max]`: `t` and the index of the triangle in the slice
    /// given to [`Accel::build`].
    fn closest(&self, ray: &Ray) -> Option<(f32, u32)>;

    /// Whether anything lies in `[ray.t_min, ray.t_max]`.
    fn occluded(&self, ray: &Ray) -> bool;

    /// Bytes the structure holds (nodes, its copy of the triangles, index arrays), if known.
    fn memory_bytes(&self) -> Option<usize> {
        None
    }
}
