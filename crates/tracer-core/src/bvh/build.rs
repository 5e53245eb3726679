//! Binned SAH build: 16 bins on centroid bounds, subtrees above a few thousand triangles built
//! in parallel with `rayon::join` and stitched into one flat binary node array, which
//! [`wide::collapse`] then turns into 8-wide nodes.

use glam::Vec3;
use rayon::prelude::*;

use super::binary::Node;
use super::triangle::{PACK, Tri4};
use super::wide;
use super::{Bvh, Kernel};
use crate::geometry::Aabb;

const BINS: usize = 16;
/// Largest leaf; bigger ranges are always split.
pub(crate) const MAX_LEAF: usize = 4;
/// Cost of one more box relative to one triangle, for packets (see `decide`). Measured: at 2.0
/// a third of the bunny's leaves split, for no gain in its packets; at 2.5 meshes keep their
/// leaves (+0.7 % leaves for the bunny, +2 % for the ogre) while a room's walls part.
const PACKET_BOX_COST: f32 = 2.5;
/// Ranges larger than this are split with `rayon::join`.
const PARALLEL_SUBTREE: usize = 4096;
/// Ranges larger than this scan (bounds, binning) in parallel chunks.
const PARALLEL_SCAN: usize = 1 << 16;
const SCAN_CHUNK: usize = 1 << 14;

/// A triangle's bounds during the build; `index` is its position in the caller's slice.
#[derive(Clone, Copy)]
struct PrimRef {
    min: Vec3,
    max: Vec3,
    index: u32,
}

impl PrimRef {
    /// Twice the centroid (saves a multiply; used consistently for binning and partition).
    fn centroid2(&self) -> Vec3 {
        self.min + self.max
    }
}

/// Bounds of a range of primitives and of their (doubled) centroids.
#[derive(Clone, Copy)]
struct RangeBounds {
    bounds: Aabb,
    centroids: Aabb,
}

impl RangeBounds {
    const EMPTY: Self = Self {
        bounds: Aabb::EMPTY,
        centroids: Aabb::EMPTY,
    };

    fn grow(self, p: &PrimRef) -> Self {
        Self {
            bounds: Aabb {
                min: self.bounds.min.min(p.min),
                max: self.bounds.max.max(p.max),
            },
            centroids: self.centroids.grow(p.centroid2()),
        }
    }

    fn union(self, o: Self) -> Self {
        Self {
            bounds: self.bounds.union(o.bounds),
            centroids: self.centroids.union(o.centroids),
        }
    }

    fn of(prims: &[PrimRef]) -> Self {
        if prims.len() >= PARALLEL_SCAN {
            prims
                .par_chunks(SCAN_CHUNK)
                .map(Self::of)
                .reduce(|| Self::EMPTY, Self::union)
        } else {
            prims.iter().fold(Self::EMPTY, Self::grow)
        }
    }
}

#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: u32,
}

const EMPTY_BIN: Bin = Bin {
    bounds: Aabb::EMPTY,
    count: 0,
};

type Bins = [[Bin; BINS]; 3];

/// Maps a doubled centroid to a bin on each axis; shared by binning and partition.
#[derive(Clone, Copy)]
struct Binning {
    min: Vec3,
    /// Bins per unit length; 0 on an axis with no centroid extent.
    scale: Vec3,
}

impl Binning {
    fn new(centroids: &Aabb) -> Self {
        let extent = centroids.max - centroids.min;
        let scale = Vec3::select(
            extent.cmpgt(Vec3::ZERO),
            Vec3::splat(BINS as f32) / extent,
            Vec3::ZERO,
        );
        Self {
            min: centroids.min,
            scale,
        }
    }

    #[inline(always)]
    fn bin(&self, c: Vec3, axis: usize) -> usize {
        // `as usize` saturates (NaN -> 0), the `min` keeps the maximum in the last bin.
        (((c[axis] - self.min[axis]) * self.scale[axis]) as usize).min(BINS - 1)
    }

    fn fill(&self, prims: &[PrimRef]) -> Bins {
        if prims.len() >= PARALLEL_SCAN {
            return prims
                .par_chunks(SCAN_CHUNK)
                .map(|c| self.fill(c))
                .reduce(|| [[EMPTY_BIN; BINS]; 3], merge_bins);
        }
        let mut bins = [[EMPTY_BIN; BINS]; 3];
        for p in prims {
            let c = p.centroid2();
            for (axis, axis_bins) in bins.iter_mut().enumerate() {
                let b = &mut axis_bins[self.bin(c, axis)];
                b.bounds.min = b.bounds.min.min(p.min);
                b.bounds.max = b.bounds.max.max(p.max);
                b.count += 1;
            }
        }
        bins
    }
}

fn merge_bins(mut a: Bins, b: Bins) -> Bins {
    for (x, y) in a.iter_mut().flatten().zip(b.iter().flatten()) {
        x.bounds = x.bounds.union(y.bounds);
        x.count += y.count;
    }
    a
}

/// Triangle packs needed for `count` triangles: leaves test four triangles at once, so the SAH
/// counts packs, not triangles (Embree's builders count blocks the same way).
fn packs(count: u32) -> f32 {
    count.div_ceil(PACK as u32) as f32
}

/// The best SAH split: primitives in bins `< split` of `axis` go left.
struct Split {
    axis: usize,
    split: usize,
    /// Sum of area times count over both sides.
    cost: f32,
    left: Aabb,
    right: Aabb,
    /// Triangles on each side.
    counts: (u32, u32),
}

fn find_split(prims: &[PrimRef], binning: &Binning) -> Option<Split> {
    let bins = binning.fill(prims);
    let mut best: Option<Split> = None;
    for (axis, bins) in bins.iter().enumerate() {
        if binning.scale[axis] == 0.0 {
            continue;
        }
        // right[i]: bounds and count of bins i.. (suffix sums).
        let mut right = [(Aabb::EMPTY, 0u32); BINS];
        let mut acc = (Aabb::EMPTY, 0u32);
        for i in (1..BINS).rev() {
            acc = (acc.0.union(bins[i].bounds), acc.1 + bins[i].count);
            right[i] = acc;
        }
        let mut left = (Aabb::EMPTY, 0u32);
        for split in 1..BINS {
            left = (
                left.0.union(bins[split - 1].bounds),
                left.1 + bins[split - 1].count,
            );
            let (rb, rc) = right[split];
            if left.1 == 0 || rc == 0 {
                continue;
            }
            let cost = left.0.area() * packs(left.1) + rb.area() * packs(rc);
            if best.as_ref().is_none_or(|b| cost < b.cost) {
                best = Some(Split {
                    axis,
                    split,
                    cost,
                    left: left.0,
                    right: rb,
                    counts: (left.1, rc),
                });
            }
        }
    }
    best
}

/// Moves the primitives going left to the front; returns their count and both sides' bounds.
fn partition(
    prims: &mut [PrimRef],
    split: &Split,
    binning: &Binning,
) -> (usize, RangeBounds, RangeBounds) {
    let mut left = RangeBounds::EMPTY;
    let mut right = RangeBounds::EMPTY;
    let (mut i, mut j) = (0, prims.len());
    while i < j {
        let p = prims[i];
        if binning.bin(p.centroid2(), split.axis) < split.split {
            left.centroids = left.centroids.grow(p.centroid2());
            i += 1;
        } else {
            right.centroids = right.centroids.grow(p.centroid2());
            j -= 1;
            prims.swap(i, j);
        }
    }
    left.bounds = split.left;
    right.bounds = split.right;
    (i, left, right)
}

enum Decision {
    Leaf,
    Split {
        mid: usize,
        left: RangeBounds,
        right: RangeBounds,
    },
}

/// Leaf or split for one range (reorders `prims` when splitting).
fn decide(prims: &mut [PrimRef], range: &RangeBounds) -> Decision {
    let n = prims.len();
    // Up to PACKET_BOX_COST triangles no split can pass the test below.
    if n <= 1 || (n <= MAX_LEAF && n as f32 <= PACKET_BOX_COST) {
        return Decision::Leaf;
    }
    let binning = Binning::new(&range.centroids);
    let split = find_split(prims, &binning);
    if n <= MAX_LEAF {
        // One pack of four costs a single ray the same as one triangle, so by the SAH above a
        // small range is always a leaf. Packets, though, test a leaf's triangles one at a
        // time: a leaf holding triangles far apart (two walls of a room) makes every packet
        // entering its wide box test them all. Such ranges are split when the triangles
        // tested, weighed by the boxes' areas, outweigh one more box.
        let area = range.bounds.area();
        let worth_it = split.as_ref().is_some_and(|s| {
            let (l, r) = (s.counts.0 as f32, s.counts.1 as f32);
            let tested = (s.left.area() * l + s.right.area() * r) / area;
            area > 0.0 && PACKET_BOX_COST + tested < n as f32
        });
        if !worth_it {
            return Decision::Leaf;
        }
    }
    match split {
        Some(split) => {
            let (mid, left, right) = partition(prims, &split, &binning);
            Decision::Split { mid, left, right }
        }
        // All centroids identical: any halving is as good as another.
        None => {
            let mid = n / 2;
            Decision::Split {
                mid,
                left: RangeBounds::of(&prims[..mid]),
                right: RangeBounds::of(&prims[mid..]),
            }
        }
    }
}

/// Builds the subtree of `prims` (at `offset` in BVH order) into its own node array, root first.
fn build_sequential(prims: &mut [PrimRef], offset: usize, range: RangeBounds) -> Vec<Node> {
    let mut nodes = Vec::with_capacity(2 * prims.len());
    nodes.push(Node::new(range.bounds, 0, 0));
    let mut todo = vec![(0usize, 0usize, prims.len(), range)];
    while let Some((node, start, end, range)) = todo.pop() {
        match decide(&mut prims[start..end], &range) {
            Decision::Leaf => {
                nodes[node] =
                    Node::new(range.bounds, (offset + start) as u32, (end - start) as u32);
            }
            Decision::Split { mid, left, right } => {
                let l = nodes.len();
                nodes[node] = Node::new(range.bounds, l as u32, 0);
                nodes.push(Node::new(left.bounds, 0, 0));
                nodes.push(Node::new(right.bounds, 0, 0));
                todo.push((l + 1, start + mid, end, right));
                todo.push((l, start, start + mid, left));
            }
        }
    }
    nodes
}

/// The top of the tree as built in parallel: sequential chunks joined by split nodes.
enum Subtree {
    Chunk(Vec<Node>),
    Split {
        bounds: Aabb,
        children: Box<(Subtree, Subtree)>,
    },
}

fn build_parallel(prims: &mut [PrimRef], offset: usize, range: RangeBounds) -> Subtree {
    if prims.len() <= PARALLEL_SUBTREE {
        return Subtree::Chunk(build_sequential(prims, offset, range));
    }
    match decide(prims, &range) {
        Decision::Leaf => Subtree::Chunk(build_sequential(prims, offset, range)),
        Decision::Split { mid, left, right } => {
            let (lp, rp) = prims.split_at_mut(mid);
            let children = rayon::join(
                || build_parallel(lp, offset, left),
                || build_parallel(rp, offset + mid, right),
            );
            Subtree::Split {
                bounds: range.bounds,
                children: Box::new(children),
            }
        }
    }
}

/// Writes `tree` into `nodes`, its root at `slot`, keeping children adjacent and after parents.
fn flatten(tree: Subtree, slot: usize, nodes: &mut Vec<Node>) {
    match tree {
        Subtree::Chunk(chunk) => {
            // Chunk indices 1.. move to base..; the chunk root goes to `slot`.
            let base = nodes.len();
            let relocate = |mut n: Node| {
                if !n.is_leaf() {
                    n.index = (n.index as usize - 1 + base) as u32;
                }
                n
            };
            nodes[slot] = relocate(chunk[0]);
            nodes.extend(chunk[1..].iter().map(|&n| relocate(n)));
        }
        Subtree::Split { bounds, children } => {
            let l = nodes.len();
            nodes[slot] = Node::new(bounds, l as u32, 0);
            nodes.push(Node::new(Aabb::EMPTY, 0, 0));
            nodes.push(Node::new(Aabb::EMPTY, 0, 0));
            let (left, right) = *children;
            flatten(left, l, nodes);
            flatten(right, l + 1, nodes);
        }
    }
}

/// Copies each leaf's triangles (BVH order in `prims`) into packs of four, in the order the
/// nodes reference them, and points the leaf references at their packs.
fn pack_leaves(
    nodes: &mut [wide::WideNode],
    prims: &[PrimRef],
    triangles: &[[Vec3; 3]],
) -> Vec<Tri4> {
    let mut packs = crate::pages::vec_on_huge_pages(prims.len() / 2 + 1);
    let mut scratch = Vec::with_capacity(PACK);
    let mut ids = Vec::with_capacity(PACK);
    for node in nodes {
        for r in &mut node.children {
            let wide::Child::Leaf { first, count } = wide::decode(*r) else {
                continue;
            };
            let start = packs.len();
            for chunk in prims[first..first + count].chunks(PACK) {
                scratch.clear();
                scratch.extend(chunk.iter().map(|p| triangles[p.index as usize]));
                ids.clear();
                ids.extend(chunk.iter().map(|p| p.index));
                packs.push(Tri4::new(&scratch, &ids));
            }
            *r = wide::leaf_ref(start, packs.len() - start);
        }
    }
    packs
}

impl Bvh {
    /// Builds a BVH over `triangles` (binned SAH, parallel for large inputs). Degenerate
    /// triangles are kept (they are never hit); coordinates must not be NaN and there must be
    /// fewer than 2^27 triangles.
    pub fn build(triangles: &[[Vec3; 3]]) -> Bvh {
        if triangles.is_empty() {
            return Bvh::default();
        }
        let mut prims: Vec<PrimRef> = triangles
            .par_iter()
            .with_min_len(SCAN_CHUNK)
            .enumerate()
            .map(|(i, t)| PrimRef {
                min: t[0].min(t[1]).min(t[2]),
                max: t[0].max(t[1]).max(t[2]),
                index: i as u32,
            })
            .collect();
        let range = RangeBounds::of(&prims);
        let tree = build_parallel(&mut prims, 0, range);
        let mut nodes = Vec::with_capacity(2 * prims.len());
        nodes.push(Node::new(range.bounds, 0, 0));
        flatten(tree, 0, &mut nodes);
        let mut wide_nodes = wide::collapse(&nodes);
        // The binary tree (about 32 bytes a triangle) goes before the packs are made: a big
        // scene's load peaks here.
        drop(nodes);
        let tris = pack_leaves(&mut wide_nodes, &prims, triangles);
        drop(prims);
        let nodes = wide_nodes;
        let depth = wide::tree_depth(&nodes);
        let mut bvh = Bvh {
            nodes,
            triangles: tris,
            triangle_count: triangles.len(),
            depth,
            ..Bvh::default()
        };
        bvh.set_kernel(Kernel::Auto);
        bvh
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Once indexed, the packs give back every triangle bit for bit (degenerate ones too), and
    /// the index costs 4 bytes a triangle.
    #[test]
    fn indexed_packs_give_back_every_triangle() {
        let mut triangles: Vec<[Vec3; 3]> = (0..1000)
            .map(|i| {
                let f = i as f32;
                let p = Vec3::new((f * 0.37).sin() * 5.0, (f * 0.11).cos() * 3.0, f * 0.01);
                [
                    p,
                    p + Vec3::new(0.1, f.sqrt() * 1e-3, 0.0),
                    p + Vec3::new(0.0, 0.2, 0.05),
                ]
            })
            .collect();
        triangles[17] = [Vec3::ONE; 3];
        let mut bvh = Bvh::build(&triangles);
        let before = bvh.memory_bytes();
        bvh.index_triangles();
        assert_eq!(bvh.memory_bytes() - before, 4 * triangles.len());
        for (i, t) in triangles.iter().enumerate() {
            let got = bvh.triangle(i);
            assert!(
                got.iter()
                    .zip(t)
                    .all(|(a, b)| a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)),
                "{i}: {got:?} {t:?}"
            );
        }
    }

    /// The triangle ids of each leaf of `triangles`' tree, sorted.
    fn leaves(triangles: &[[Vec3; 3]]) -> Vec<Vec<u32>> {
        let bvh = Bvh::build(triangles);
        let mut out = Vec::new();
        for node in &bvh.nodes {
            for &child in node.children.iter().take_while(|&&c| c != wide::EMPTY) {
                if child & wide::LEAF_BIT != 0 {
                    let (first, count) = wide::leaf_range(child);
                    let mut ids: Vec<u32> = bvh.triangles[first..first + count]
                        .iter()
                        .flat_map(|pack| pack.ids)
                        .filter(|&id| id != super::super::PADDING)
                        .collect();
                    ids.sort_unstable();
                    out.push(ids);
                }
            }
        }
        out.sort();
        out
    }

    /// Two triangles making the square `corner + s·a + t·b`, s, t in [0, 1].
    fn square(corner: Vec3, a: Vec3, b: Vec3) -> [[Vec3; 3]; 2] {
        [
            [corner, corner + a, corner + a + b],
            [corner, corner + a + b, corner + b],
        ]
    }

    #[test]
    fn walls_far_apart_get_leaves_of_their_own() {
        // Floor and back wall of a room: one leaf's box would be the whole room, so every
        // packet entering it would test all four triangles.
        let mut room = Vec::new();
        room.extend(square(Vec3::ZERO, Vec3::X * 5.0, Vec3::Z * 5.0));
        room.extend(square(Vec3::ZERO, Vec3::X * 5.0, Vec3::Y * 5.0));
        assert_eq!(leaves(&room), vec![vec![0, 1], vec![2, 3]]);
    }

    #[test]
    fn small_clusters_stay_one_leaf() {
        // Four neighbouring triangles of a mesh: one pack, as the SAH for single rays wants.
        let mut strip = Vec::new();
        strip.extend(square(Vec3::ZERO, Vec3::X, Vec3::Z));
        strip.extend(square(Vec3::X, Vec3::X, Vec3::Z + Vec3::Y * 0.2));
        assert_eq!(leaves(&strip), vec![vec![0, 1, 2, 3]]);
    }
}
