//! The binary tree the SAH build makes (`build.rs`) and [`super::wide::collapse`] turns into
//! 8-wide nodes; its own module so that neither of the two uses the other back.

use glam::Vec3;

use crate::geometry::Aabb;

/// A node of the binary tree the build makes before [`wide::collapse`] turns it into 8-wide
/// nodes: children adjacent (`index`, `index + 1`) and after their parent.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Node {
    pub min: [f32; 3],
    /// Interior: index of the left child (the right child is `index + 1`).
    /// Leaf: position of the first triangle in BVH order.
    pub index: u32,
    pub max: [f32; 3],
    /// Number of triangles in a leaf; 0 marks an interior node.
    pub count: u32,
}

impl Node {
    pub fn new(bounds: Aabb, index: u32, count: u32) -> Self {
        Self {
            min: bounds.min.to_array(),
            index,
            max: bounds.max.to_array(),
            count,
        }
    }

    pub fn bounds(&self) -> Aabb {
        Aabb {
            min: Vec3::from_array(self.min),
            max: Vec3::from_array(self.max),
        }
    }

    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }
}
