//! `Bvh::validate`: the structural invariants traversal relies on.

use super::build::{MAX_LEAF, tree_depth};
use super::{Bvh, Node};
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
    /// Checks that nodes form a tree rooted at 0 with adjacent children after their parent,
    /// indices are in range, every triangle is in exactly one leaf of 1..=8 triangles, each
    /// box contains and tightly fits its children or triangles, `prim_ids` is a permutation,
    /// and the recorded depth is right.
    pub fn validate(&self) -> Result<(), String> {
        let (nodes, n_tris) = (&self.nodes, self.triangles.len());
        if self.prim_ids.len() != n_tris {
            return Err(format!(
                "{} prim ids for {n_tris} triangles",
                self.prim_ids.len()
            ));
        }
        if nodes.is_empty() != (n_tris == 0) {
            return Err(format!("{} nodes for {n_tris} triangles", nodes.len()));
        }
        let mut seen_prim = vec![false; n_tris];
        for (i, &p) in self.prim_ids.iter().enumerate() {
            match seen_prim.get_mut(p as usize) {
                Some(seen) if !*seen => *seen = true,
                _ => return Err(format!("prim id {p} at {i} out of range or repeated")),
            }
        }
        let mut tri_refs = vec![0u32; n_tris];
        let mut visited = vec![false; nodes.len()];
        let mut todo = if nodes.is_empty() { vec![] } else { vec![0] };
        while let Some(i) = todo.pop() {
            if std::mem::replace(&mut visited[i], true) {
                return Err(format!("node {i} reached twice"));
            }
            let node = &nodes[i];
            let b = node.bounds();
            if b.is_empty() {
                return Err(format!("node {i} has an empty box {b:?}"));
            }
            let tol = tolerance(&b);
            if node.is_leaf() {
                self.validate_leaf(i, node, &mut tri_refs, tol)?;
            } else {
                let left = node.index as usize;
                if left <= i || left + 1 >= nodes.len() {
                    return Err(format!("node {i}: children {left}, {} invalid", left + 1));
                }
                let (l, r) = (nodes[left].bounds(), nodes[left + 1].bounds());
                if !b.contains(&l) || !b.contains(&r) || !tight(&b, &l.union(r), tol) {
                    return Err(format!(
                        "node {i}: box {b:?} does not fit children {l:?} {r:?}"
                    ));
                }
                todo.extend([left, left + 1]);
            }
        }
        if let Some(i) = visited.iter().position(|v| !v) {
            return Err(format!("node {i} unreachable"));
        }
        if let Some(i) = tri_refs.iter().position(|&c| c != 1) {
            return Err(format!("triangle {i} referenced {} times", tri_refs[i]));
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
        node: &Node,
        refs: &mut [u32],
        tol: f32,
    ) -> Result<(), String> {
        let (first, count) = (node.index as usize, node.count as usize);
        if !(1..=MAX_LEAF).contains(&count) || first + count > self.triangles.len() {
            return Err(format!("leaf {i}: triangles {first}..+{count} invalid"));
        }
        let mut fit = Aabb::EMPTY;
        for (t, r) in self.triangles[first..first + count]
            .iter()
            .zip(&mut refs[first..])
        {
            *r += 1;
            fit = t.v.iter().fold(fit, |b, &p| b.grow(p));
        }
        if !tight(&node.bounds(), &fit, tol) {
            return Err(format!(
                "leaf {i}: box {:?} does not fit {fit:?}",
                node.bounds()
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::uv_sphere;

    fn sphere_bvh() -> Bvh {
        let bvh = Bvh::build(&uv_sphere(24));
        assert_eq!(bvh.validate(), Ok(()));
        bvh
    }

    fn first_leaf(bvh: &Bvh) -> usize {
        bvh.nodes.iter().position(Node::is_leaf).unwrap_or(0)
    }

    fn first_interior_below_root(bvh: &Bvh) -> usize {
        bvh.nodes
            .iter()
            .skip(1)
            .position(|n| !n.is_leaf())
            .map_or(0, |i| i + 1)
    }

    #[test]
    fn catches_shrunken_leaf_box() {
        let mut bvh = sphere_bvh();
        let i = first_leaf(&bvh);
        bvh.nodes[i].max[0] = bvh.nodes[i].min[0];
        assert!(bvh.validate().is_err());
    }

    #[test]
    fn catches_loose_box() {
        let mut bvh = sphere_bvh();
        let i = first_leaf(&bvh);
        bvh.nodes[i].min[1] -= 0.5;
        assert!(bvh.validate().is_err());
    }

    #[test]
    fn catches_triangle_referenced_twice() {
        let mut bvh = sphere_bvh();
        let i = first_leaf(&bvh);
        let j = bvh.nodes.iter().rposition(Node::is_leaf).unwrap_or(0);
        bvh.nodes[j] = bvh.nodes[i];
        assert!(bvh.validate().is_err());
    }

    #[test]
    fn catches_bad_child_index_and_cycle() {
        let mut bvh = sphere_bvh();
        let i = first_interior_below_root(&bvh);
        bvh.nodes[i].index = bvh.nodes.len() as u32;
        assert!(bvh.validate().is_err());
        let mut bvh = sphere_bvh();
        let i = first_interior_below_root(&bvh);
        bvh.nodes[i].index = 0;
        assert!(bvh.validate().is_err());
    }

    #[test]
    fn catches_oversized_leaf_and_bad_prim_ids() {
        let mut bvh = sphere_bvh();
        let i = first_leaf(&bvh);
        bvh.nodes[i].count = MAX_LEAF as u32 + 1;
        assert!(bvh.validate().is_err());
        let mut bvh = sphere_bvh();
        bvh.prim_ids[0] = bvh.prim_ids[1];
        assert!(bvh.validate().is_err());
    }

    #[test]
    fn catches_wrong_depth() {
        let mut bvh = sphere_bvh();
        bvh.depth += 1;
        assert!(bvh.validate().is_err());
    }
}
