//! `Bvh::validate`: the structural invariants traversal relies on.

use super::build::MAX_LEAF;
use super::triangle::PACK;
use super::wide::{Child, MAX_LEAF_START, WIDTH, decode, tree_depth};
use super::{Bvh, PADDING};
use crate::geometry::Aabb;

/// Slack for box tightness (a few ulps of the box's largest coordinate).
fn tolerance(b: &Aabb) -> f32 {
    let scale = b.min.abs().max(b.max.abs()).max_element();
    scale * 4.0 * f32::EPSILON + f32::MIN_POSITIVE
}

/// `outer` contains `inner` and is larger by at most `tol` on every side.
fn tight(outer: &Aabb, inner: &Aabb, tol: f32) -> bool {
    outer.min.cmple(inner.min + tol).all()
        && outer.max.cmpge(inner.max - tol).all()
        && (inner.min - outer.min).max_element() <= tol
        && (outer.max - inner.max).max_element() <= tol
}

impl Bvh {
    /// Checks that nodes form a tree rooted at 0 with children after their parent, every node
    /// has at least one child, unused lanes hold the empty box, indices are in range, every
    /// triangle is in exactly one pack lane of one leaf (leaves of `MAX_LEAF / 4` packs at most,
    /// unused lanes degenerate), each lane's box contains and tightly fits its child node's
    /// boxes or its triangles, the packs' ids are a permutation, and the recorded depth is right.
    pub fn validate(&self) -> Result<(), String> {
        let (nodes, n_tris) = (&self.nodes, self.triangle_count);
        let slots = self.triangles.len() * PACK;
        if nodes.is_empty() != (n_tris == 0) {
            return Err(format!("{} nodes for {n_tris} triangles", nodes.len()));
        }
        let mut seen_prim = vec![false; n_tris];
        let ids = self.triangles.iter().flat_map(|pack| pack.ids);
        for (i, p) in ids.enumerate() {
            if p == PADDING {
                if !self.triangles[i / PACK].is_degenerate(i % PACK) {
                    return Err(format!("padding lane {i} holds a triangle"));
                }
                continue;
            }
            match seen_prim.get_mut(p as usize) {
                Some(seen) if !*seen => *seen = true,
                _ => return Err(format!("prim id {p} at {i} out of range or repeated")),
            }
        }
        if let Some(p) = seen_prim.iter().position(|s| !s) {
            return Err(format!("triangle {p} is in no pack"));
        }
        let mut slot_refs = vec![0u32; slots];
        let mut visited = vec![false; nodes.len()];
        let mut todo = if nodes.is_empty() { vec![] } else { vec![0] };
        while let Some(i) = todo.pop() {
            if std::mem::replace(&mut visited[i], true) {
                return Err(format!("node {i} reached twice"));
            }
            let node = &nodes[i];
            let mut used = 0;
            for lane in 0..WIDTH {
                let b = node.lane_bounds(lane);
                let child = decode(node.children[lane]);
                if child == Child::Empty {
                    if b != Aabb::EMPTY {
                        return Err(format!("node {i}: empty lane {lane} has box {b:?}"));
                    }
                    continue;
                }
                used += 1;
                if b.is_empty() {
                    return Err(format!("node {i} lane {lane}: empty box {b:?}"));
                }
                let tol = tolerance(&b);
                match child {
                    Child::Node(c) => {
                        if c <= i || c >= nodes.len() {
                            return Err(format!("node {i} lane {lane}: child {c} invalid"));
                        }
                        let fit = nodes[c].bounds();
                        if !b.contains(&fit) || !tight(&b, &fit, tol) {
                            return Err(format!(
                                "node {i} lane {lane}: box {b:?} does not fit child {fit:?}"
                            ));
                        }
                        todo.push(c);
                    }
                    Child::Leaf { first, count } => {
                        self.validate_leaf(i, lane, (first, count), &b, &mut slot_refs, tol)?;
                    }
                    Child::Empty => {}
                }
            }
            if used == 0 {
                return Err(format!("node {i} has no children"));
            }
        }
        if let Some(i) = visited.iter().position(|v| !v) {
            return Err(format!("node {i} unreachable"));
        }
        if let Some(i) = slot_refs.iter().position(|&c| c != 1) {
            return Err(format!("pack lane {i} referenced {} times", slot_refs[i]));
        }
        let depth = tree_depth(nodes);
        if depth != self.depth {
            return Err(format!("depth {depth}, recorded {}", self.depth));
        }
        Ok(())
    }

    fn validate_leaf(
        &self,
        i: usize,
        lane: usize,
        (first, count): (usize, usize),
        b: &Aabb,
        refs: &mut [u32],
        tol: f32,
    ) -> Result<(), String> {
        if !(1..=MAX_LEAF.div_ceil(PACK)).contains(&count)
            || first >= MAX_LEAF_START
            || first + count > self.triangles.len()
        {
            return Err(format!(
                "node {i} lane {lane}: packs {first}..+{count} invalid"
            ));
        }
        let mut fit = Aabb::EMPTY;
        for (pack, r) in (first * PACK..(first + count) * PACK).zip(&mut refs[first * PACK..]) {
            *r += 1;
            let tri = &self.triangles[pack / PACK];
            fit = (0..3).fold(fit, |b, v| b.grow(tri.vertex(pack % PACK, v)));
        }
        if !b.contains(&fit) || !tight(b, &fit, tol) {
            return Err(format!(
                "node {i} lane {lane}: box {b:?} does not fit {fit:?}"
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::uv_sphere;
    use crate::bvh::wide::leaf_ref;

    fn sphere_bvh() -> Bvh {
        let bvh = Bvh::build(&uv_sphere(24));
        assert_eq!(bvh.validate(), Ok(()));
        bvh
    }

    /// (node, lane) of the first leaf reference and of the first interior reference below
    /// the root.
    fn lanes(bvh: &Bvh, leaf: bool) -> Vec<(usize, usize)> {
        let mut out = vec![];
        for (i, n) in bvh.nodes.iter().enumerate() {
            for (lane, &r) in n.children.iter().enumerate() {
                let is = match decode(r) {
                    Child::Leaf { .. } => leaf,
                    Child::Node(_) => !leaf && i > 0,
                    Child::Empty => false,
                };
                if is {
                    out.push((i, lane));
                }
            }
        }
        out
    }

    #[test]
    fn catches_shrunken_leaf_box() {
        let mut bvh = sphere_bvh();
        let (i, lane) = lanes(&bvh, true)[0];
        *bvh.nodes[i].bound_mut(3, lane) = *bvh.nodes[i].bound_mut(0, lane);
        assert!(bvh.validate().is_err());
    }

    #[test]
    fn catches_loose_box() {
        let mut bvh = sphere_bvh();
        let (i, lane) = lanes(&bvh, true)[0];
        *bvh.nodes[i].bound_mut(1, lane) -= 0.5;
        assert!(bvh.validate().is_err());
    }

    #[test]
    fn catches_triangle_referenced_twice() {
        let mut bvh = sphere_bvh();
        let leaves = lanes(&bvh, true);
        let ((i, a), (j, b)) = (leaves[0], leaves[leaves.len() - 1]);
        bvh.nodes[j].children[b] = bvh.nodes[i].children[a];
        assert!(bvh.validate().is_err());
    }

    #[test]
    fn catches_bad_child_index_and_cycle() {
        let mut bvh = sphere_bvh();
        let (i, lane) = lanes(&bvh, false)[0];
        bvh.nodes[i].children[lane] = bvh.nodes.len() as u32;
        assert!(bvh.validate().is_err());
        let mut bvh = sphere_bvh();
        bvh.nodes[i].children[lane] = 0;
        assert!(bvh.validate().is_err());
    }

    #[test]
    fn catches_oversized_leaf_filled_empty_lane_and_bad_prim_ids() {
        let mut bvh = sphere_bvh();
        let (i, lane) = lanes(&bvh, true)[0];
        bvh.nodes[i].children[lane] = leaf_ref(0, MAX_LEAF.div_ceil(PACK) + 1);
        assert!(bvh.validate().is_err());
        let mut bvh = sphere_bvh();
        *bvh.nodes[0].bound_mut(0, 0) = f32::INFINITY;
        *bvh.nodes[0].bound_mut(3, 0) = f32::NEG_INFINITY;
        assert!(bvh.validate().is_err());
        let mut bvh = sphere_bvh();
        bvh.triangles[0].ids[0] = bvh.triangles[0].ids[1];
        assert!(bvh.validate().is_err());
    }

    #[test]
    fn catches_wrong_depth() {
        let mut bvh = sphere_bvh();
        bvh.depth += 1;
        assert!(bvh.validate().is_err());
    }
}
