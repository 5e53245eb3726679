//! Small scenes built in code for the crate's unit tests.

use crate::formats::{MeshDescription, PartDescription, SceneDescription};

/// A UV sphere of radius 1 about the origin without vertex normals: `rings` × `segments`.
pub(crate) fn sphere(rings: u32, segments: u32) -> SceneDescription {
    let mut positions = Vec::new();
    for i in 0..=rings {
        let theta = std::f64::consts::PI * f64::from(i) / f64::from(rings);
        for j in 0..segments {
            let phi = 2.0 * std::f64::consts::PI * f64::from(j) / f64::from(segments);
            positions.push([
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ]);
        }
    }
    let at = |i: u32, j: u32| i * segments + j % segments;
    let mut triangles = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j), at(i + 1, j + 1));
            if i > 0 {
                triangles.push([a, b, c]);
            }
            if i + 1 < rings {
                triangles.push([b, d, c]);
            }
        }
    }
    SceneDescription {
        meshes: vec![MeshDescription {
            name: "sphere".into(),
            positions,
            triangles,
            parts: vec![PartDescription::default()],
            ..MeshDescription::default()
        }],
        ..SceneDescription::default()
    }
}
