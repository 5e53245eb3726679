//! raygine's own BVH (tracer-core).

use glam::Vec3;
use tracer_core::Ray;
use tracer_core::bvh::Bvh;

use super::Accel;

#[derive(Debug)]
pub struct Raygine(pub Bvh);

impl Accel for Raygine {
    const NAME: &'static str = "raygine";

    fn build(triangles: &[[Vec3; 3]], _threads: usize) -> anyhow::Result<Self> {
        Ok(Self(Bvh::build(triangles)))
    }

    fn closest(&self, ray: &Ray) -> Option<(f32, u32)> {
        self.0.intersect(ray).map(|h| (h.t, h.prim))
    }

    fn occluded(&self, ray: &Ray) -> bool {
        self.0.occluded(ray)
    }

    fn memory_bytes(&self) -> Option<usize> {
        Some(self.0.memory_bytes())
    }
}
