//! UsdGeomMesh to a mesh description: polygons (`faceVertexCounts`, `faceVertexIndices`,
//! minus `holeIndices`) fanned into triangles from each face's first corner; `normals` or
//! `primvars:normals`, `primvars:st` (V flipped: raygine's V runs down the image) and
//! `primvars:displayColor`, with any interpolation (`constant`, `uniform`, `vertex`,
//! `varying`, `faceVarying`) and indexed primvars; `GeomSubset`s of the `materialBind` family
//! as parts, each with its own bound material. `orientation = "leftHanded"` reverses the
//! winding so that the front stays the side USD calls front. Subdivision surfaces draw their
//! control mesh (the reader counts them for a note).

use super::Reader;
use super::values;
use crate::formats::error::check_memory;
use crate::formats::{FormatError, MeshDescription, PartDescription};
use glam::{DMat3, DMat4, DVec3};
use openusd::sdf::Value;
use openusd::usd::Prim;

/// A primvar as read: its values, indices into them when indexed, and its interpolation.
struct Primvar<T> {
    values: Vec<T>,
    indices: Option<Vec<i64>>,
    interpolation: String,
}

impl<T: Copy> Primvar<T> {
    /// The value at face `face`, its point `point` and its corner number `corner` (over all
    /// faces); None where the primvar has no entry (a short array).
    fn at(&self, face: usize, point: usize, corner: usize) -> Option<T> {
        let element = match self.interpolation.as_str() {
            "constant" => 0,
            "uniform" => face,
            "faceVarying" => corner,
            _ => point,
        };
        let i = match &self.indices {
            Some(ix) => usize::try_from(*ix.get(element)?).ok()?,
            None => element,
        };
        self.values.get(i).copied()
    }

    /// Whether values differ between the corners of one point (so points must be split).
    fn per_corner(&self) -> bool {
        matches!(self.interpolation.as_str(), "uniform" | "faceVarying")
    }
}

impl Reader<'_> {
    /// Reads the Mesh at `prim` with its points carried to scene coordinates by `world`.
    /// `Ok(None)` when it draws nothing (no points or faces).
    pub(super) fn mesh(
        &mut self,
        prim: &Prim,
        world: DMat4,
        name: String,
    ) -> Result<Option<MeshDescription>, FormatError> {
        let at = |why: String| self.error_at(prim, why);
        let time = self.time;
        let read = |n: &str| values::value(prim, n, time).map_err(at);
        let Some(points) = read("points")? else {
            return Ok(None);
        };
        let points = values::vec3_array(&points)
            .ok_or_else(|| at("points: not a point3f[] array".into()))?;
        let counts = read("faceVertexCounts")?
            .as_ref()
            .map(|v| {
                values::int_array(v).ok_or_else(|| at("faceVertexCounts: not an int[]".into()))
            })
            .transpose()?
            .unwrap_or_default();
        let indices = read("faceVertexIndices")?
            .as_ref()
            .map(|v| {
                values::int_array(v).ok_or_else(|| at("faceVertexIndices: not an int[]".into()))
            })
            .transpose()?
            .unwrap_or_default();
        if let Some(bad) = counts.iter().find(|&&n| n < 0) {
            return Err(at(format!("faceVertexCounts: a face of {bad} corners")));
        }
        let corners: i64 = counts.iter().sum();
        if corners != indices.len() as i64 {
            return Err(at(format!(
                "faceVertexCounts add up to {corners} corners but faceVertexIndices has {}",
                indices.len()
            )));
        }
        if let Some(bad) = indices
            .iter()
            .find(|&&i| i < 0 || i as usize >= points.len())
        {
            return Err(at(format!(
                "faceVertexIndices: index {bad} outside the {} points",
                points.len()
            )));
        }
        let triangle_count: u64 = counts.iter().map(|&n| (n.max(2) - 2) as u64).sum();
        check_memory(self.path, 0, triangle_count, points.len() as u64)?;
        if triangle_count == 0 {
            return Ok(None);
        }
        let holes: std::collections::HashSet<i64> = read("holeIndices")?
            .as_ref()
            .and_then(values::int_array)
            .unwrap_or_default()
            .into_iter()
            .collect();
        let left_handed = values::attr_token(prim, "orientation")
            .map_err(at)?
            .as_deref()
            == Some("leftHanded");
        let scheme = values::attr_token(prim, "subdivisionScheme").map_err(at)?;
        if scheme.as_deref() != Some("none") {
            self.subdivided += 1;
        }
        let normals = self.primvar(
            prim,
            &["primvars:normals", "normals"],
            values::vec3_array,
            "vertex",
        )?;
        let st = self.primvar(
            prim,
            &["primvars:st", "primvars:st0", "primvars:UVMap"],
            values::vec2_array,
            "faceVarying",
        )?;
        let split = normals.as_ref().is_some_and(Primvar::per_corner)
            || st.as_ref().is_some_and(Primvar::per_corner);
        let (parts, face_parts) = self.parts(prim, counts.len());

        let normal_matrix = DMat3::from_mat4(world).inverse().transpose();
        let mut out = MeshDescription {
            name,
            source: self.path.to_owned(),
            parts,
            ..MeshDescription::default()
        };
        let mut normals_ok = normals.is_some();
        let mut uvs_ok = st.is_some();
        let mut push_vertex =
            |out: &mut MeshDescription, face: usize, point: usize, corner: usize| {
                out.positions.push(
                    world
                        .transform_point3(DVec3::from(points[point]))
                        .to_array(),
                );
                if let Some(n) = &normals
                    && normals_ok
                {
                    match n.at(face, point, corner) {
                        Some(n) => out.normals.push(
                            (normal_matrix * DVec3::from(n))
                                .normalize_or_zero()
                                .as_vec3()
                                .to_array(),
                        ),
                        None => normals_ok = false,
                    }
                }
                if let Some(st) = &st
                    && uvs_ok
                {
                    match st.at(face, point, corner) {
                        Some([u, v]) => out.uvs[0].push([u as f32, (1.0 - v) as f32]),
                        None => uvs_ok = false,
                    }
                }
            };
        // Vertex of each point (when points are shared): filled as faces first use them.
        let mut vertex_of: Vec<u32> = if split {
            Vec::new()
        } else {
            vec![u32::MAX; points.len()]
        };
        let mut corner = 0usize;
        let mut face_corners: Vec<u32> = Vec::new();
        out.triangles.reserve(triangle_count as usize);
        for (face, &n) in counts.iter().enumerate() {
            let n = n as usize;
            let skip = n < 3 || holes.contains(&(face as i64));
            face_corners.clear();
            for k in 0..n {
                let point = indices[corner + k] as usize;
                if skip {
                    continue;
                }
                let v = if split {
                    push_vertex(&mut out, face, point, corner + k);
                    out.positions.len() as u32 - 1
                } else {
                    if vertex_of[point] == u32::MAX {
                        vertex_of[point] = out.positions.len() as u32;
                        push_vertex(&mut out, face, point, corner + k);
                    }
                    vertex_of[point]
                };
                face_corners.push(v);
            }
            corner += n;
            for k in 1..face_corners.len().saturating_sub(1) {
                let (a, b, c) = (face_corners[0], face_corners[k], face_corners[k + 1]);
                out.triangles
                    .push(if left_handed { [a, c, b] } else { [a, b, c] });
                out.triangle_parts
                    .push(face_parts.get(face).copied().unwrap_or(0));
            }
        }
        if !normals_ok || out.normals.len() != out.positions.len() {
            out.normals.clear();
        }
        if !uvs_ok || out.uvs[0].len() != out.positions.len() {
            out.uvs[0].clear();
        }
        if out.parts.len() <= 1 {
            out.triangle_parts.clear();
        }
        Ok((!out.triangles.is_empty()).then_some(out))
    }

    /// The first of `names` that holds an array `convert` reads, with its indices and
    /// interpolation (`default` when the attribute does not say).
    fn primvar<T>(
        &mut self,
        prim: &Prim,
        names: &[&str],
        convert: fn(&Value) -> Option<Vec<T>>,
        default: &str,
    ) -> Result<Option<Primvar<T>>, FormatError> {
        for name in names {
            let Some(v) =
                values::value(prim, name, self.time).map_err(|e| self.error_at(prim, e))?
            else {
                continue;
            };
            let Some(values) = convert(&v) else {
                self.desc.notes.push(format!(
                    "{}: {name} has an unexpected type; not used",
                    self.at(prim)
                ));
                continue;
            };
            let indices = values::value(prim, &format!("{name}:indices"), self.time)
                .map_err(|e| self.error_at(prim, e))?
                .as_ref()
                .and_then(values::int_array);
            let authored = prim
                .attribute(*name)
                .get_metadata::<Value>("interpolation")
                .ok()
                .flatten();
            let interpolation = authored
                .as_ref()
                .and_then(values::token)
                .unwrap_or(default)
                .to_owned();
            return Ok(Some(Primvar {
                values,
                indices,
                interpolation,
            }));
        }
        Ok(None)
    }

    /// The mesh's parts: its own material for faces no subset claims, then one part per
    /// `GeomSubset` of faces in the `materialBind` family; and each face's part.
    fn parts(&mut self, prim: &Prim, faces: usize) -> (Vec<PartDescription>, Vec<u32>) {
        let own = self.surface_material(prim);
        let mut parts = vec![PartDescription {
            name: None,
            material: own,
            smooth: None,
        }];
        let mut face_parts = vec![0u32; faces];
        let mut claimed = 0usize;
        for child in prim.children().unwrap_or_default() {
            let is_subset = child
                .type_name()
                .ok()
                .flatten()
                .is_some_and(|t| t.as_str() == "GeomSubset");
            if !is_subset {
                continue;
            }
            let family = values::attr_token(&child, "familyName").ok().flatten();
            let element = values::attr_token(&child, "elementType").ok().flatten();
            if family.as_deref() != Some("materialBind")
                || element.as_deref().is_some_and(|e| e != "face")
            {
                continue;
            }
            let faces_of = values::value(&child, "indices", self.time)
                .ok()
                .flatten()
                .as_ref()
                .and_then(values::int_array)
                .unwrap_or_default();
            let part = parts.len() as u32;
            let material = super::material::bound_material(&child).and_then(|m| self.material(&m));
            parts.push(PartDescription {
                name: child.path().name().map(str::to_owned),
                material: material.or(own),
                smooth: None,
            });
            for f in faces_of {
                if let Some(slot) = usize::try_from(f).ok().and_then(|f| face_parts.get_mut(f)) {
                    if *slot == 0 {
                        claimed += 1;
                    }
                    *slot = part;
                }
            }
        }
        if parts.len() > 1 {
            parts[0].name = Some("unbound".into());
            if claimed == faces {
                // Every face is in a subset: part 0 stays, empty (slots keep their numbers).
                parts[0].name = Some("unbound (empty)".into());
            }
        }
        (parts, face_parts)
    }

    /// The material of a prim: its bound UsdPreviewSurface, else its constant
    /// `primvars:displayColor` as a diffuse material, else None (the default material).
    fn surface_material(&mut self, prim: &Prim) -> Option<usize> {
        if let Some(m) = super::material::bound_material(prim).and_then(|m| self.material(&m)) {
            return Some(m);
        }
        let color = values::value(prim, "primvars:displayColor", self.time)
            .ok()
            .flatten()?;
        let rgb = match &color {
            Value::Vec3fVec(a) if !a.is_empty() => {
                let n = a.len() as f32;
                let sum = a
                    .iter()
                    .fold([0.0f32; 3], |s, c| [s[0] + c.x, s[1] + c.y, s[2] + c.z]);
                if a.len() > 1 {
                    self.desc.notes.push(format!(
                        "{}: displayColor varies over the mesh; drawn with its mean",
                        self.at(prim)
                    ));
                }
                sum.map(|c| c / n)
            }
            other => values::vec3(other)?.map(|c| c as f32),
        };
        let key = format!("displayColor {rgb:?}");
        if let Some(&Some(i)) = self.materials.get(&key) {
            return Some(i);
        }
        let name = format!("displayColor({:.3} {:.3} {:.3})", rgb[0], rgb[1], rgb[2]);
        let d = crate::formats::MaterialDescription {
            name,
            source: self.path.to_owned(),
            diffuse: rgb.map(|c| c.clamp(0.0, 1.0)),
            ..Default::default()
        };
        self.desc.materials.push(d);
        let i = self.desc.materials.len() - 1;
        self.materials.insert(key, Some(i));
        Some(i)
    }
}
