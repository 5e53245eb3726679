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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trace::{count_hits, pool, workloads_for};

    /// Every library compiled in finds the same hits as raygine on the same rays (up to rays
    /// grazing shared edges, which different triangle tests may decide differently).
    fn agrees_with_raygine<A: Accel>() {
        let triangles = tracer_core::bvh::uv_sphere(48);
        let w = workloads_for(&triangles).unwrap();
        let pool = pool(2).unwrap();
        let own = raygine::Raygine::build(&triangles, 2).unwrap();
        let peer = pool.install(|| A::build(&triangles, 2)).unwrap();
        for (rays, any_hit) in [(&w.w1, false), (&w.w2, true), (&w.w3, false)] {
            let a = count_hits(&pool, &own, rays, any_hit);
            let b = count_hits(&pool, &peer, rays, any_hit);
            assert!(
                a.abs_diff(b) <= rays.len() / 1000,
                "{}: {a} vs {b}",
                A::NAME
            );
        }
        assert!(!w.w2.is_empty() && w.w2.len() == w.w3.len());
    }

    #[test]
    fn raygine_agrees_with_itself() {
        agrees_with_raygine::<raygine::Raygine>();
    }

    #[cfg(feature = "obvhs")]
    #[test]
    fn obvhs_agrees_with_raygine() {
        agrees_with_raygine::<obvhs::Obvhs>();
    }

    #[cfg(feature = "embree")]
    #[test]
    fn embree_agrees_with_raygine() {
        agrees_with_raygine::<embree::Embree>();
    }
}
