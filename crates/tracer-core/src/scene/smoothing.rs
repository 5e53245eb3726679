//! Vertex normals for smooth shading, per triangle corner.
//!
//! A mesh's own vertex normals (OBJ `vn`, glTF `NORMAL`) are used as the file gives them. A mesh
//! without them (`.shp`, `.brs`, OBJ without `vn`) gets normals averaged over the triangles
//! around each vertex whose planes lie within the crease angle of the corner's own triangle,
//! each weighted by its angle at that vertex (so a fan of thin triangles does not outweigh one
//! wide one). Vertices at the same position (to a billionth of the mesh's size) are welded
//! first, since exporters often repeat a vertex per face. Sharper edges stay sharp: the 90° corners of a box are never smoothed.
//!
//! Flat triangles (a part the format marks `shading flat`, degenerate triangles, a crease angle
//! of 0) get no corner normals; shading then uses the geometric normal.

use crate::formats::MeshDescription;
use glam::DVec3;
use std::collections::HashMap;

/// The crease angle used when the sidecar gives none (`smooth_angle_deg`), degrees: smooth
/// across edges whose faces meet at less than this, sharp beyond.
pub const DEFAULT_SMOOTH_ANGLE_DEG: f32 = 45.0;

/// Corner normals of each of `mesh`'s triangles in its local coordinates (unit length), or None
/// for a triangle shaded flat. `crease_deg` ≤ 0 makes every triangle flat, the file's normals
/// included.
pub fn corner_normals(mesh: &MeshDescription, crease_deg: f32) -> Vec<Option<[DVec3; 3]>> {
    let mut out = Vec::with_capacity(mesh.triangles.len());
    for_each_corner_normals(mesh, crease_deg, |_, c| out.push(c));
    out
}

/// [`corner_normals`] handed to `f` triangle by triangle, in order (triangle index, its corner
/// normals), without the array of them: a big mesh's load peaks while they are made (72 bytes
/// a triangle in f64).
pub fn for_each_corner_normals(
    mesh: &MeshDescription,
    crease_deg: f32,
    mut f: impl FnMut(usize, Option<[DVec3; 3]>),
) {
    let n = mesh.triangles.len();
    if crease_deg.is_nan() || crease_deg <= 0.0 {
        (0..n).for_each(|t| f(t, None));
        return;
    }
    let smooth_part = |t: usize| {
        let part = mesh.triangle_parts.get(t).copied().unwrap_or(0) as usize;
        mesh.parts.get(part).and_then(|p| p.smooth) != Some(false)
    };
    let position = |i: u32| mesh.positions.get(i as usize).map(|&p| DVec3::from(p));
    if !mesh.normals.is_empty() && mesh.normals.len() == mesh.positions.len() {
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let corners = (|| {
                if !smooth_part(t) {
                    return None;
                }
                let mut out = [DVec3::ZERO; 3];
                for (k, &i) in tri.iter().enumerate() {
                    let v = DVec3::from(mesh.normals.get(i as usize)?.map(f64::from));
                    out[k] = v.try_normalize()?;
                }
                Some(out)
            })();
            f(t, corners);
        }
        return;
    }
    // Weld vertices at the same position, to a billionth of the mesh's size (exporters write
    // the same vertex twice with rounding noise: a sphere's pole as sin π = 1e-16).
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(DVec3::from(p)), hi.max(DVec3::from(p)))
        });
    let quantum = ((hi - lo).max_element() * 1e-9).max(f64::MIN_POSITIVE);
    let mut welded: HashMap<[i64; 3], u32> = HashMap::with_capacity(mesh.positions.len());
    let weld: Vec<u32> = mesh
        .positions
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let key = p.map(|c| (c / quantum).round() as i64);
            *welded.entry(key).or_insert(i as u32)
        })
        .collect();
    // The table is no longer needed (about 30 bytes a vertex): freed before the big arrays.
    drop(welded);
    let corner = |t: usize, k: usize| weld.get(mesh.triangles[t][k] as usize).copied();
    // Face normals and corner angles; None for degenerate triangles or bad indices.
    let faces: Vec<Option<(DVec3, [f64; 3])>> = mesh
        .triangles
        .iter()
        .map(|tri| {
            let [a, b, c] = [position(tri[0])?, position(tri[1])?, position(tri[2])?];
            let normal = (b - a).cross(c - a).try_normalize()?;
            let angle = |p: DVec3, q: DVec3, r: DVec3| (q - p).angle_between(r - p);
            Some((normal, [angle(a, b, c), angle(b, c, a), angle(c, a, b)]))
        })
        .collect();
    // Triangles around each welded vertex (compressed rows).
    let mut start = vec![0u32; mesh.positions.len() + 1];
    for t in 0..n {
        for k in 0..3 {
            if let Some(w) = corner(t, k) {
                start[w as usize + 1] += 1;
            }
        }
    }
    for i in 1..start.len() {
        start[i] += start[i - 1];
    }
    let mut fill = start.clone();
    let mut around = vec![(0u32, 0u8); start[start.len() - 1] as usize];
    for t in 0..n {
        for k in 0..3 {
            if let Some(w) = corner(t, k) {
                around[fill[w as usize] as usize] = (t as u32, k as u8);
                fill[w as usize] += 1;
            }
        }
    }
    drop(fill);
    let cos_crease = f64::from(crease_deg.min(180.0)).to_radians().cos();
    let corners_of = |t: usize| {
        if !smooth_part(t) {
            return None;
        }
        let (own, _) = faces[t]?;
        let mut out = [DVec3::ZERO; 3];
        for (k, slot) in out.iter_mut().enumerate() {
            let w = corner(t, k)? as usize;
            let mut sum = DVec3::ZERO;
            for &(other, ok) in &around[start[w] as usize..start[w + 1] as usize] {
                let other = other as usize;
                if !smooth_part(other) {
                    continue;
                }
                if let Some((normal, angles)) = faces[other]
                    && normal.dot(own) >= cos_crease
                {
                    sum += normal * angles[ok as usize];
                }
            }
            *slot = sum.try_normalize().unwrap_or(own);
        }
        Some(out)
    };
    (0..n).for_each(|t| f(t, corners_of(t)));
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;
    use crate::formats::PartDescription;

    fn mesh(positions: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> MeshDescription {
        MeshDescription {
            name: "m".into(),
            positions,
            triangles,
            parts: vec![PartDescription::default()],
            ..MeshDescription::default()
        }
    }

    #[test]
    fn a_shallow_fold_is_smoothed_and_a_right_angle_stays_sharp() {
        // Two triangles sharing the edge (0,0,0)-(1,0,0), folded by 20° and by 90°.
        for (fold_deg, smooth) in [(20.0f64, true), (90.0, false)] {
            let (s, c) = fold_deg.to_radians().sin_cos();
            let m = mesh(
                vec![
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, -c, s],
                ],
                vec![[0, 1, 2], [1, 0, 3]],
            );
            let normals = corner_normals(&m, 45.0);
            let first = normals[0].expect("smooth triangle");
            // At the shared corner the normal turns by half the fold when smoothed.
            let turned = first[0].angle_between(DVec3::Z).to_degrees();
            let expected = if smooth { fold_deg / 2.0 } else { 0.0 };
            assert!((turned - expected).abs() < 1e-6, "{fold_deg}: {turned}");
            // The corner the other triangle does not share keeps the face normal.
            assert!(first[2].angle_between(DVec3::Z) < 1e-9);
        }
    }

    #[test]
    fn flat_parts_and_a_zero_crease_angle_give_no_normals() {
        let mut m = mesh(
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            vec![[0, 1, 2]],
        );
        assert!(corner_normals(&m, 45.0)[0].is_some());
        assert!(corner_normals(&m, 0.0)[0].is_none());
        m.parts[0].smooth = Some(false);
        assert!(corner_normals(&m, 45.0)[0].is_none());
    }

    #[test]
    fn file_normals_are_used_and_bad_ones_fall_back_to_flat() {
        let mut m = mesh(
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            vec![[0, 1, 2]],
        );
        m.normals = vec![[0.0, 0.0, 2.0], [1.0, 0.0, 1.0], [0.0, 0.0, 1.0]];
        let n = corner_normals(&m, 45.0)[0].expect("file normals");
        assert!((n[1] - DVec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-12);
        assert!((n[0] - DVec3::Z).length() < 1e-12);
        m.normals[2] = [0.0; 3];
        assert!(corner_normals(&m, 45.0)[0].is_none());
    }
}
