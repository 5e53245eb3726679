//! The wide (8 children) node the traversal walks, and [`collapse`], which makes such nodes from the binary
//! SAH tree by pulling up grandchildren (largest surface area first) until a node has eight
//! children or only leaves below it.
//!
//! A node stores its children's boxes structure-of-arrays (one lane per child) so one ray is
//! tested against all its boxes with the same few vector instructions, and a child reference
//! per lane:
//!
//! | reference                 | meaning                                                    |
//! |---------------------------|------------------------------------------------------------|
//! | [`EMPTY`]                 | unused lane; its box is empty (`+inf` minima, `-inf` maxima) |
//! | bit 31 clear              | index of an interior node, always after its parent         |
//! | bit 31 set                | leaf: first pack in bits 4..=30, pack count in bits 0..=3  |

//!
//! During [`collapse`] a leaf reference holds a triangle range of the binary tree; `build.rs` then
//! copies the triangles into packs and rewrites the reference to the pack range.

use super::binary;
use crate::geometry::Aabb;

/// Children per node: groups of four lanes, each group one SSE register.
pub(crate) const WIDTH: usize = 8;
pub(crate) const GROUPS: usize = WIDTH / LANES;
/// Lanes of one SIMD group.
pub(crate) const LANES: usize = 4;
/// An unused lane.
pub(crate) const EMPTY: u32 = u32::MAX;
pub(crate) const LEAF_BIT: u32 = 1 << 31;
const COUNT_BITS: u32 = 4;
/// Leaves can start at triangles (and packs) below this: a BVH holds fewer than 2^27 triangles.
pub(crate) const MAX_LEAF_START: usize = 1 << (31 - COUNT_BITS);

/// [`WIDTH`] children's boxes and references (256 bytes, four cache lines, when 8 wide).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub(crate) struct WideNode {
    /// `bounds[axis][group][lane]`: minima; `bounds[3 + axis][group][lane]`: maxima; child
    /// `LANES * group + lane`.
    pub bounds: [[[f32; LANES]; GROUPS]; 6],
    pub children: [u32; WIDTH],
    _pad: [u32; WIDTH],
}

/// A decoded child reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Child {
    Empty,
    Node(usize),
    Leaf { first: usize, count: usize },
}

pub(crate) fn leaf_ref(first: usize, count: usize) -> u32 {
    debug_assert!(first < MAX_LEAF_START && (1..1 << COUNT_BITS).contains(&count));
    LEAF_BIT | (first as u32) << COUNT_BITS | count as u32
}

/// First triangle and count of a leaf reference (bit 31 set, not [`EMPTY`]).
#[inline(always)]
pub(crate) fn leaf_range(r: u32) -> (usize, usize) {
    let first = ((r & !LEAF_BIT) >> COUNT_BITS) as usize;
    (first, (r & ((1 << COUNT_BITS) - 1)) as usize)
}

pub(crate) fn decode(r: u32) -> Child {
    if r == EMPTY {
        Child::Empty
    } else if r & LEAF_BIT != 0 {
        let (first, count) = leaf_range(r);
        Child::Leaf { first, count }
    } else {
        Child::Node(r as usize)
    }
}

impl WideNode {
    pub const EMPTY: Self = Self {
        bounds: [
            [[f32::INFINITY; LANES]; GROUPS],
            [[f32::INFINITY; LANES]; GROUPS],
            [[f32::INFINITY; LANES]; GROUPS],
            [[f32::NEG_INFINITY; LANES]; GROUPS],
            [[f32::NEG_INFINITY; LANES]; GROUPS],
            [[f32::NEG_INFINITY; LANES]; GROUPS],
        ],
        children: [EMPTY; WIDTH],
        _pad: [0; WIDTH],
    };

    /// Row `row` (min x, y, z, max x, y, z) of every child, child `c` in element `c`.
    #[inline(always)]
    pub fn row(&self, row: usize) -> [f32; WIDTH] {
        let mut out = [0.0; WIDTH];
        out.copy_from_slice(self.bounds[row].as_flattened());
        out
    }

    /// Row `row` (min x, y, z, max x, y, z) of child `lane`.
    pub fn bound_mut(&mut self, row: usize, lane: usize) -> &mut f32 {
        &mut self.bounds[row][lane / LANES][lane % LANES]
    }

    pub fn lane_bounds(&self, lane: usize) -> Aabb {
        let r = |row: usize| self.bounds[row][lane / LANES][lane % LANES];
        Aabb {
            min: glam::Vec3::new(r(0), r(1), r(2)),
            max: glam::Vec3::new(r(3), r(4), r(5)),
        }
    }

    pub fn set_lane(&mut self, lane: usize, bounds: Aabb, child: u32) {
        for axis in 0..3 {
            *self.bound_mut(axis, lane) = bounds.min[axis];
            *self.bound_mut(3 + axis, lane) = bounds.max[axis];
        }
        self.children[lane] = child;
    }

    /// Union of the lanes' boxes.
    pub fn bounds(&self) -> Aabb {
        (0..WIDTH).fold(Aabb::EMPTY, |b, lane| b.union(self.lane_bounds(lane)))
    }
}

/// Wide nodes from a binary tree (root at 0, children adjacent and after their parent).
/// Children of a node stay in the binary tree's left-to-right order; nodes are laid out depth
/// first, each node's interior children allocated together.
pub(crate) fn collapse(binary: &[binary::Node]) -> Vec<WideNode> {
    if binary.is_empty() {
        return Vec::new();
    }
    let mut nodes = crate::pages::vec_on_huge_pages(binary.len() / 3 + 1);
    nodes.push(WideNode::EMPTY);
    let mut todo = vec![(0usize, 0usize)];
    while let Some((b, slot)) = todo.pop() {
        let mut kids = [0usize; WIDTH];
        let mut n = if binary[b].is_leaf() {
            kids[0] = b;
            1
        } else {
            let l = binary[b].index as usize;
            kids[0] = l;
            kids[1] = l + 1;
            2
        };
        while n < WIDTH {
            let widest = (0..n)
                .filter(|&i| !binary[kids[i]].is_leaf())
                .max_by(|&i, &j| {
                    let (a, c) = (binary[kids[i]].bounds(), binary[kids[j]].bounds());
                    a.area().total_cmp(&c.area())
                });
            let Some(i) = widest else { break };
            let l = binary[kids[i]].index as usize;
            // Keep left-to-right order: the pair replaces its parent in place.
            kids.copy_within(i + 1..n, i + 2);
            kids[i] = l;
            kids[i + 1] = l + 1;
            n += 1;
        }
        let mut node = WideNode::EMPTY;
        let mut interior = Vec::new();
        for (lane, &k) in kids[..n].iter().enumerate() {
            let child = &binary[k];
            let r = if child.is_leaf() {
                leaf_ref(child.index as usize, child.count as usize)
            } else {
                let s = nodes.len();
                nodes.push(WideNode::EMPTY);
                interior.push((k, s));
                s as u32
            };
            node.set_lane(lane, child.bounds(), r);
        }
        nodes[slot] = node;
        todo.extend(interior.into_iter().rev());
    }
    nodes
}

/// Edges on the longest path from the root to a leaf reference; relies on children coming
/// after their parent.
pub(crate) fn tree_depth(nodes: &[WideNode]) -> usize {
    let mut depth = vec![0usize; nodes.len()];
    let mut max = 0;
    for (i, n) in nodes.iter().enumerate() {
        let d = depth[i];
        for &r in &n.children {
            match decode(r) {
                Child::Node(c) => {
                    if let Some(child) = depth.get_mut(c) {
                        *child = d + 1;
                    }
                }
                Child::Leaf { .. } => max = max.max(d + 1),
                Child::Empty => {}
            }
        }
    }
    max
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_is_whole_cache_lines() {
        assert_eq!(size_of::<WideNode>(), 32 * WIDTH);
        assert_eq!(align_of::<WideNode>(), 64);
    }

    #[test]
    fn references_round_trip() {
        assert_eq!(decode(EMPTY), Child::Empty);
        assert_eq!(decode(7), Child::Node(7));
        let r = leaf_ref(MAX_LEAF_START - 1, 8);
        assert_eq!(
            decode(r),
            Child::Leaf {
                first: MAX_LEAF_START - 1,
                count: 8
            }
        );
    }
}
