//! Normal and bump maps: the shading normal a map bends a surface's normal to.
//!
//! - A tangent-space normal map reads (x, y, z) = 2 · RGB − 1 (x and y times the map's scale)
//!   in the frame (T, B, N): T the tangent (increasing u), B = w · N × T (up the image, the
//!   OpenGL convention glTF uses), N the interpolated vertex normal.
//! - A height map h (scene units) moves the surface along N: the bent normal is
//!   (∂P/∂u + ∂h/∂u N) × (∂P/∂v + ∂h/∂v N) turned to N's side, the derivatives of h by central
//!   differences one texel apart (Blinn 1978, as pbrt's bump mapping).
//! - Either way the bent normal stays at least [`MIN_COS`] above the geometric surface: a
//!   shading normal below it would light the back of the surface (the terminator problem).

use super::{Encoding, Texture, TextureSet};
use glam::{Vec2, Vec3, Vec4};

/// The smallest cosine between a bent normal and the geometric normal.
pub const MIN_COS: f32 = 0.05;

/// `ns` lifted, if needed, to at least [`MIN_COS`] above the surface of unit normal `ng` (both
/// on the same side).
pub fn above_surface(ns: Vec3, ng: Vec3) -> Vec3 {
    let c = ns.dot(ng);
    if c >= MIN_COS {
        return ns;
    }
    // Keep the tangential direction, set the normal component so the cosine is MIN_COS.
    let tangential = (ns - ng * c).normalize_or_zero();
    let sin = (1.0 - MIN_COS * MIN_COS).sqrt();
    (tangential * sin + ng * MIN_COS).normalize_or(ng)
}

/// The surface's derivatives at a hit: ∂P/∂u and ∂P/∂v, and the tangent (xyz, handedness w)
/// when the mesh has tangents.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceDerivatives {
    pub dp_du: Vec3,
    pub dp_dv: Vec3,
    pub tangent: Option<Vec4>,
}

impl SurfaceDerivatives {
    /// ∂P/∂u and ∂P/∂v of the triangle `p` with texture coordinates `uv` (None when the UVs
    /// are degenerate).
    pub fn of_triangle(p: [Vec3; 3], uv: [Vec2; 3]) -> Option<(Vec3, Vec3)> {
        let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
        let (d1, d2) = (uv[1] - uv[0], uv[2] - uv[0]);
        let det = d1.x * d2.y - d2.x * d1.y;
        if det.abs() < 1e-20 || !det.is_finite() {
            return None;
        }
        let dp_du = (e1 * d2.y - e2 * d1.y) / det;
        let dp_dv = (e2 * d1.x - e1 * d2.x) / det;
        (dp_du.is_finite() && dp_dv.is_finite()).then_some((dp_du, dp_dv))
    }
}

impl TextureSet {
    /// The normal `n` (unit, on the side the mesh's normals face) bent by the normal map and
    /// the height map at UV sets `uv`.
    pub fn bend(
        &self,
        textures: &[Texture],
        uv: [Vec2; 2],
        n: Vec3,
        d: &SurfaceDerivatives,
    ) -> Vec3 {
        let mut out = n;
        if let Some(map) = &self.normal {
            let rgb = map.read(textures, uv, Encoding::Linear).truncate() * 2.0 - Vec3::ONE;
            let ts = Vec3::new(rgb.x * self.normal_scale, rgb.y * self.normal_scale, rgb.z);
            // The tangent from the mesh, else ∂P/∂u; orthogonal to n (Gram-Schmidt).
            let (t, w) = match d.tangent {
                Some(t) => (t.truncate(), if t.w < 0.0 { -1.0 } else { 1.0 }),
                None => {
                    // B up the image is −∂P/∂v (v runs down the image); w makes N × T point there.
                    let t = d.dp_du;
                    let w = if n.cross(t).dot(-d.dp_dv) < 0.0 {
                        -1.0
                    } else {
                        1.0
                    };
                    (t, w)
                }
            };
            let t = (t - n * n.dot(t)).normalize_or_zero();
            if t != Vec3::ZERO {
                let b = n.cross(t) * w;
                out = (t * ts.x + b * ts.y + n * ts.z).normalize_or(n);
            }
        }
        if let Some(map) = &self.bump {
            let texture = textures.get(map.texture as usize);
            if let Some(texture) = texture {
                let step = Vec2::new(1.0 / texture.width as f32, 1.0 / texture.height as f32);
                let set = usize::from(map.set.min(1));
                let height = |offset: Vec2| {
                    let mut at = uv;
                    at[set] += offset;
                    map.read(textures, at, Encoding::Linear).x * self.bump_scale
                };
                let hu = (height(Vec2::new(step.x, 0.0)) - height(Vec2::new(-step.x, 0.0)))
                    / (2.0 * step.x);
                let hv = (height(Vec2::new(0.0, step.y)) - height(Vec2::new(0.0, -step.y)))
                    / (2.0 * step.y);
                let du = d.dp_du + out * hu;
                let dv = d.dp_dv + out * hv;
                let bumped = du.cross(dv);
                let bumped = if bumped.dot(out) < 0.0 {
                    -bumped
                } else {
                    bumped
                };
                out = bumped.normalize_or(out);
            }
        }
        out
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_of_a_unit_quad_triangle() {
        let p = [
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 3.0),
        ];
        let uv = [Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(1.0, 1.0)];
        let (du, dv) = SurfaceDerivatives::of_triangle(p, uv).unwrap();
        assert!((du - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-6, "{du}");
        assert!((dv - Vec3::new(0.0, 0.0, 3.0)).length() < 1e-6, "{dv}");
        assert!(SurfaceDerivatives::of_triangle(p, [Vec2::ZERO; 3]).is_none());
    }

    #[test]
    fn a_normal_below_the_surface_is_lifted_to_the_minimum_cosine() {
        let ng = Vec3::Y;
        let below = Vec3::new(1.0, -0.2, 0.0).normalize();
        let lifted = above_surface(below, ng);
        assert!((lifted.dot(ng) - MIN_COS).abs() < 1e-5);
        assert!(lifted.x > 0.99 && (lifted.length() - 1.0).abs() < 1e-5);
        let fine = Vec3::new(0.3, 0.9, 0.1).normalize();
        assert_eq!(above_surface(fine, ng), fine);
    }
}
