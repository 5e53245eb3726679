//! obvhs (pure Rust): a compressed wide BVH8 (CWBVH) from its PLOC builder, medium preset,
//! parallel on the current rayon pool. Triangles are reordered into BVH order after the build
//! (part of the timed build), as obvhs's own examples do, so leaves read memory in order.

use std::time::Duration;

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::ray::{Ray as ORay, RayHit};
use obvhs::triangle::Triangle;
use tracer_core::Ray;

use super::Accel;

pub struct Obvhs {
    bvh: CwBvh,
    /// Triangles in BVH order: `ordered[i]` is the caller's `bvh.primitive_indices[i]`.
    ordered: Vec<Triangle>,
}

impl std::fmt::Debug for Obvhs {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Obvhs")
            .field("triangles", &self.ordered.len())
            .finish_non_exhaustive()
    }
}

fn to_obvhs(ray: &Ray) -> ORay {
    ORay::new(
        Vec3A::from(ray.origin),
        Vec3A::from(ray.dir),
        ray.t_min,
        ray.t_max,
    )
}

impl Accel for Obvhs {
    const NAME: &'static str = "obvhs";

    fn build(triangles: &[[Vec3; 3]], _threads: usize) -> anyhow::Result<Self> {
        let tris: Vec<Triangle> = triangles
            .iter()
            .map(|[a, b, c]| Triangle {
                v0: (*a).into(),
                v1: (*b).into(),
                v2: (*c).into(),
            })
            .collect();
        let mut core_time = Duration::ZERO;
        let bvh = build_cwbvh_from_tris(&tris, BvhBuildParams::medium_build(), &mut core_time);
        let ordered = bvh
            .primitive_indices
            .iter()
            .map(|&i| tris[i as usize])
            .collect();
        Ok(Self { bvh, ordered })
    }

    fn closest(&self, ray: &Ray) -> Option<(f32, u32)> {
        let mut hit = RayHit::none();
        let found = self.bvh.ray_traverse(to_obvhs(ray), &mut hit, |r, id| {
            self.ordered[id].intersect(r)
        });
        found.then(|| {
            let prim = self.bvh.primitive_indices[hit.primitive_id as usize];
            (hit.t, prim)
        })
    }

    fn occluded(&self, ray: &Ray) -> bool {
        !self
            .bvh
            .ray_traverse_miss(to_obvhs(ray), |r, id| self.ordered[id].intersect(r))
    }
}
