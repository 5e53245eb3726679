//! Bounding volume hierarchy over triangles: binned SAH build, flat nodes, closest-hit and any-hit
//! traversal, and [`Bvh::validate`] for its invariants.
//!
//! ```ignore
//! let bvh = Bvh::build(&triangles);           // triangles: &[[Vec3; 3]]
//! let hit: Option<Hit> = bvh.intersect(&ray); // closest hit in [ray.t_min, ray.t_max]
//! let blocked: bool = bvh.occluded(&ray);     // any hit in [ray.t_min, ray.t_max]
//! bvh.validate()?;
//! ```
//!
//! Layout: one `Vec` of 256-byte 8-wide nodes (`wide.rs`), root at index 0, children always after
//! their parent; each node holds its eight children's boxes side by side and one reference per
//! child (node index, leaf triangle range, or empty). The build makes a binary SAH tree and
//! collapses it. Leaves hold a range of packs of four triangles (`Tri4`, vertices
//! structure-of-arrays, unused lanes degenerate) tested together, each lane with its index in
//! the caller's slice.
//!
//! Kernels (`traverse.rs`): on x86_64 CPUs with AVX2 and FMA (detected at run time) a node's
//! eight boxes are tested in one AVX register per plane; elsewhere four lanes at a time (SSE2
//! or plain arrays). Both find the same hits; the differential tests run both.
//!
//! Triangle test: watertight (Woop, Benthin, Wald 2013), two-sided, edges and vertices
//! inclusive, so rays through shared edges of closed meshes never leak (see `triangle.rs` for
//! why not Möller–Trumbore). Box tests are conservative (slab exit scaled up by a few ulps, and
//! in the fused AVX2 test the origin moved by a few ulps; see `simd.rs`).

mod binary;
mod boxes;
mod build;
mod frustum;
mod packet;
mod simd;
mod sphere;
mod stack;
mod traverse;
mod triangle;
mod validate;
mod wide;

use crate::geometry::Aabb;
use glam::Vec3;

pub use boxes::BoxTree;
pub use packet::PACKET;
pub use sphere::uv_sphere;
pub use traverse::Kernel;
pub use triangle::{intersect_brute_force, occluded_brute_force};

use triangle::Tri4;
use wide::WideNode;

/// A closest hit: ray parameter `t`, barycentrics `(u, v)` of `v1` and `v2`, and the index of
/// the triangle in the slice given to [`Bvh::build`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub u: f32,
    pub v: f32,
    pub prim: u32,
}

/// Id of an unused lane in a triangle pack.
const PADDING: u32 = u32::MAX;

/// The most triangles a scene can have (ids are `u32`, one value is [`PADDING`]), counting
/// every instance's.
pub const MAX_TRIANGLES: usize = PADDING as usize;

/// A BVH that owns a copy of its triangles in BVH order.
#[derive(Clone, Default)]
pub struct Bvh {
    /// 8-wide nodes, root first, children after their parent. Empty iff there are no triangles.
    nodes: Vec<WideNode>,
    /// Triangles in BVH order, four to a pack with their indices in the caller's slice
    /// (leaves reference a range of packs).
    triangles: Vec<Tri4>,
    /// Triangles given to the build.
    triangle_count: usize,
    /// Where each triangle given to the build sits among the packs (pack · 4 + lane), when
    /// [`Bvh::index_triangles`] made it: the packs then answer [`Bvh::triangle`], and the
    /// caller need not keep its own copy of the vertices (4 bytes a triangle instead of 36).
    locations: Vec<u32>,
    /// Edges on the longest path from the root to a leaf reference (bounds the traversal
    /// stack: at most `WIDTH - 1` entries per level).
    depth: usize,
    /// The node test traversal uses.
    kernel: Kernel,
    /// With [`Kernel::Auto`] on a CPU with AVX2 and FMA, the proof of it: checked once when
    /// the kernel is set, not on every ray.
    #[cfg(target_arch = "x86_64")]
    avx2: Option<simd::Avx2>,
}

impl std::fmt::Debug for Bvh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Bvh")
            .field("triangles", &self.triangle_count)
            .field("packs", &self.triangles.len())
            .field("nodes", &self.nodes.len())
            .field("depth", &self.depth)
            .field("bounds", &self.bounds())
            .finish()
    }
}

impl Bvh {
    /// Bounds of all triangles ([`Aabb::EMPTY`] when there are none).
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, WideNode::bounds)
    }

    pub fn triangle_count(&self) -> usize {
        self.triangle_count
    }

    /// Boxes that together hold every triangle, tighter than [`Bvh::bounds`]: the root's
    /// children's, each inner one replaced by its own children's (up to 64 boxes). Turned and
    /// joined, they bound a transformed copy closely.
    pub fn cover_boxes(&self) -> Vec<Aabb> {
        let Some(root) = self.nodes.first() else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (lane, &child) in root.children.iter().enumerate() {
            if child == wide::EMPTY {
                continue;
            }
            if child & wide::LEAF_BIT != 0 {
                out.push(root.lane_bounds(lane));
                continue;
            }
            let node = &self.nodes[child as usize];
            for (l, &grandchild) in node.children.iter().enumerate() {
                if grandchild != wide::EMPTY {
                    out.push(node.lane_bounds(l));
                }
            }
        }
        out
    }

    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Edges on the longest path from the root node to a leaf (wide nodes).
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// Bytes held: nodes, triangle data and the triangle index.
    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * size_of::<WideNode>()
            + self.triangles.len() * size_of::<Tri4>()
            + self.locations.capacity() * size_of::<u32>()
    }

    /// Indexes where each triangle sits, so that [`Bvh::triangle`] answers.
    pub fn index_triangles(&mut self) {
        let mut locations = vec![u32::MAX; self.triangle_count];
        for (p, pack) in self.triangles.iter().enumerate() {
            for (lane, &id) in pack.ids.iter().enumerate() {
                if let Some(l) = locations.get_mut(id as usize) {
                    *l = (p * triangle::PACK + lane) as u32;
                }
            }
        }
        self.locations = locations;
    }

    /// The vertices of triangle `index` (as given to the build, bit for bit), once
    /// [`Bvh::index_triangles`] has run.
    #[inline]
    pub fn triangle(&self, index: usize) -> [Vec3; 3] {
        let at = self.locations[index] as usize;
        let pack = &self.triangles[at / triangle::PACK];
        let lane = at % triangle::PACK;
        [0, 1, 2].map(|k| pack.vertex(lane, k))
    }
}
