//! The `sphere N` workload mesh of `BENCHMARK.md`.

use glam::{DVec3, Vec3};

/// A UV sphere of radius 1 at the origin: `segments` around, `segments / 2` rings, the quads
/// between rings split in two, the triangles that degenerate at the poles left out
/// (`sphere 1000` has 998,000 triangles).
///
/// Ring `r` has polar angle `pi * r / rings`, segment `s` azimuth `2 pi s / segments`, vertex
/// `(sin th cos ph, cos th, sin th sin ph)`. Vertices are computed in f64; the seam (`s = N`)
/// and the poles reuse identical vertices so that the mesh is closed exactly.
pub fn uv_sphere(segments: u32) -> Vec<[Vec3; 3]> {
    let rings = segments / 2;
    if segments < 3 || rings < 2 {
        return Vec::new();
    }
    let vertex = |r: u32, s: u32| -> Vec3 {
        if r == 0 {
            return Vec3::Y;
        }
        if r == rings {
            return Vec3::NEG_Y;
        }
        let theta = std::f64::consts::PI * f64::from(r) / f64::from(rings);
        let phi = std::f64::consts::TAU * f64::from(s % segments) / f64::from(segments);
        let (sin_t, cos_t) = theta.sin_cos();
        let (sin_p, cos_p) = phi.sin_cos();
        DVec3::new(sin_t * cos_p, cos_t, sin_t * sin_p).as_vec3()
    };
    let mut triangles = Vec::with_capacity((segments * (2 * rings - 2)) as usize);
    for r in 0..rings {
        for s in 0..segments {
            let a = vertex(r, s);
            let b = vertex(r, s + 1);
            let c = vertex(r + 1, s);
            let d = vertex(r + 1, s + 1);
            if r + 1 < rings {
                triangles.push([a, c, d]);
            }
            if r > 0 {
                triangles.push([a, d, b]);
            }
        }
    }
    triangles
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_match_benchmark_definition() {
        assert_eq!(uv_sphere(1000).len(), 998_000);
        assert_eq!(uv_sphere(64).len(), 64 * 64 - 2 * 64);
        assert!(uv_sphere(2).is_empty());
    }

    #[test]
    fn vertices_on_unit_sphere_and_no_degenerate_triangles() {
        for t in uv_sphere(32) {
            for v in t {
                assert!((v.length() - 1.0).abs() < 1e-6);
            }
            assert!((t[1] - t[0]).cross(t[2] - t[0]).length() > 1e-6);
        }
    }
}
