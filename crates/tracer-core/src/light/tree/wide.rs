//! The light tree as the sampler walks it: up to eight children per node, their bounds stored
//! lane by lane, so that one pass over eight lanes (vectorised by the compiler, no branches)
//! gives every child's importance. Collapsed from the binary build: a node opens its most
//! powerful inner child until it has eight children or only leaves.

use super::{Node, Packed};
use crate::lanes8::{Lanes8, Mask8};
use glam::Vec3;

/// Children per node.
pub(super) const LANES: usize = 8;

/// A child reference: a wide node's index, or a light's with the top bit set.
const LEAF: u32 = 1 << 31;

/// One node: its children's bounds, lane by lane (unused lanes have no power).
#[derive(Clone, Debug, Default)]
pub(super) struct Wide {
    pub(super) child: [u32; LANES],
    cx: [f32; LANES],
    cy: [f32; LANES],
    cz: [f32; LANES],
    radius: [f32; LANES],
    radius2: [f32; LANES],
    ax: [f32; LANES],
    ay: [f32; LANES],
    az: [f32; LANES],
    power: [f32; LANES],
    sin_o: [f32; LANES],
    cos_o: [f32; LANES],
    cos_e: [f32; LANES],
    /// 1 where the child emits every way (no cone to test), else 0.
    omni: [f32; LANES],
}

/// What a child reference names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Child {
    Node(u32),
    Light(u32),
}

impl Wide {
    pub(super) fn child(&self, lane: usize) -> Child {
        let c = self.child[lane];
        if c & LEAF != 0 {
            Child::Light(c & !LEAF)
        } else {
            Child::Node(c)
        }
    }

    fn set(&mut self, lane: usize, child: Child, b: &Packed) {
        self.child[lane] = match child {
            Child::Node(i) => i,
            Child::Light(l) => l | LEAF,
        };
        self.cx[lane] = b.centre.x;
        self.cy[lane] = b.centre.y;
        self.cz[lane] = b.centre.z;
        self.radius[lane] = b.radius;
        self.radius2[lane] = b.radius2;
        self.ax[lane] = b.axis.x;
        self.ay[lane] = b.axis.y;
        self.az[lane] = b.axis.z;
        self.power[lane] = b.power;
        self.sin_o[lane] = b.sin_o;
        self.cos_o[lane] = b.cos_o;
        self.cos_e[lane] = b.cos_e;
        self.omni[lane] = if b.omni { 1.0 } else { 0.0 };
    }

    /// Every child's importance at `p` (unit normal `n`, or zero): `Packed::importance` in
    /// eight lanes at once, with selects instead of branches.
    #[inline(always)]
    pub(super) fn importances<L: Lanes8>(&self, p: Vec3, n: Vec3) -> L {
        let lanes = |a: &[f32; LANES]| L::from_array(*a);
        let (zero, one) = (L::splat(0.0), L::splat(1.0));
        let power = lanes(&self.power);
        let dx = L::splat(p.x).sub(lanes(&self.cx));
        let dy = L::splat(p.y).sub(lanes(&self.cy));
        let dz = L::splat(p.z).sub(lanes(&self.cz));
        let dist2 = dx.mul(dx).add(dy.mul(dy)).add(dz.mul(dz));
        let r2 = lanes(&self.radius2);
        // Inside the bounding sphere every direction is possible (θb = π).
        let inside = dist2.le(r2);
        let inv_dist = L::select(inside, zero, one.div(dist2.sqrt()));
        let mut imp = L::select(inside, power.div(r2), power.mul(inv_dist).mul(inv_dist));
        // sin of the half-angle θb the bounding sphere subtends from `p`.
        let sin_b = lanes(&self.radius).mul(inv_dist).min_or(one);
        // The emission cone: the smallest angle between an emission normal and the direction
        // to `p`, less θo and θb.
        let sb = L::select(inside, zero, sin_b);
        let cb = L::select(inside, L::splat(-1.0), sin_of(sin_b));
        let (ax, ay, az) = (lanes(&self.ax), lanes(&self.ay), lanes(&self.az));
        let tx = L::select(inside, ax, dx.mul(inv_dist));
        let ty = L::select(inside, ay, dy.mul(inv_dist));
        let tz = L::select(inside, az, dz.mul(inv_dist));
        let cos_w = ax
            .mul(tx)
            .add(ay.mul(ty))
            .add(az.mul(tz))
            .max_or(L::splat(-1.0))
            .min_or(one);
        let sin_w = sin_of(cos_w);
        let (so, co) = (lanes(&self.sin_o), lanes(&self.cos_o));
        let within = cos_w.ge(co);
        let sin_x = L::select(within, zero, sin_w.mul(co).sub(cos_w.mul(so)));
        let cos_x = L::select(within, one, cos_w.mul(co).add(sin_w.mul(so)));
        let cos_p = L::select(cos_x.ge(cb), one, cos_x.mul(cb).add(sin_x.mul(sb)));
        // Slightly generous, so that rounding never zeroes a light at the edge of its cone.
        let outside_cone = cos_p.lt(lanes(&self.cos_e).sub(L::splat(1e-4)));
        let cone = L::select(outside_cone, zero, cos_p.max_or(L::splat(1e-4)));
        imp = L::select(lanes(&self.omni).gt(zero), imp, imp.mul(cone));
        if n != Vec3::ZERO {
            // The receiver's cosine, two-sided, loosened by θb.
            let dot = L::splat(n.x)
                .mul(dx)
                .add(L::splat(n.y).mul(dy))
                .add(L::splat(n.z).mul(dz));
            let facing = dot
                .abs()
                .mul(inv_dist)
                .add(sin_b)
                .max_or(L::splat(1e-4))
                .min_or(one);
            imp = L::select(inside, imp, imp.mul(facing));
        }
        // `p` at a point light.
        let at_point = inside.and(r2.le(zero));
        imp = L::select(at_point, power.mul(L::splat(1e12)), imp);
        L::select(power.gt(zero), imp, zero)
    }
}

/// sin of an angle from its cosine, per lane.
#[inline(always)]
fn sin_of<L: Lanes8>(cos: L) -> L {
    L::splat(1.0).sub(cos.mul(cos)).max_or(L::splat(0.0)).sqrt()
}

/// The wide nodes of a binary tree (`nodes` with their `packed` bounds, root 0), with each
/// wide node's parent (node, lane) and each light's (node, lane).
pub(super) struct Collapsed {
    pub(super) wide: Vec<Wide>,
    pub(super) parent: Vec<(u32, u8)>,
    pub(super) leaf_of: Vec<Option<(u32, u8)>>,
}

pub(super) fn collapse(nodes: &[Node], packed: &[Packed], light_count: usize) -> Collapsed {
    let mut c = Collapsed {
        wide: Vec::new(),
        parent: Vec::new(),
        leaf_of: vec![None; light_count],
    };
    if !nodes.is_empty() {
        collapse_at(nodes, packed, 0, (u32::MAX, 0), &mut c);
    }
    c
}

/// The binary children of binary node `i` (none for a leaf).
fn children(nodes: &[Node], i: usize) -> Option<[usize; 2]> {
    match nodes[i] {
        Node::Leaf(_) => None,
        Node::Inner(second) => Some([i + 1, second as usize]),
    }
}

fn collapse_at(
    nodes: &[Node],
    packed: &[Packed],
    root: usize,
    parent: (u32, u8),
    c: &mut Collapsed,
) -> u32 {
    // Open the most powerful inner node until there are eight or only leaves.
    let mut open: Vec<usize> = children(nodes, root).map_or(vec![root], |ch| ch.to_vec());
    while open.len() < LANES {
        let Some((at, _)) = open
            .iter()
            .enumerate()
            .filter(|(_, i)| children(nodes, **i).is_some())
            .max_by(|a, b| packed[*a.1].power.total_cmp(&packed[*b.1].power))
        else {
            break;
        };
        let i = open.swap_remove(at);
        if let Some(ch) = children(nodes, i) {
            open.extend(ch);
        }
    }
    let here = c.wide.len() as u32;
    c.wide.push(Wide::default());
    c.parent.push(parent);
    for (lane, &i) in open.iter().enumerate() {
        let child = match nodes[i] {
            Node::Leaf(light) => {
                if let Some(slot) = c.leaf_of.get_mut(light as usize) {
                    *slot = Some((here, lane as u8));
                }
                Child::Light(light)
            }
            Node::Inner(_) => Child::Node(collapse_at(nodes, packed, i, (here, lane as u8), c)),
        };
        c.wide[here as usize].set(lane, child, &packed[i]);
    }
    here
}
