//! UsdGeomPointInstancer: each point draws one of the `prototypes` (`protoIndices`) placed by
//! `positions`, `orientations` (or `orientationsf`) and `scales` (scaled, then turned, then
//! moved, in the instancer's frame), skipping `invisibleIds`. A prototype's own transform is
//! included (USD's default). Each prototype's meshes are read once and every point places an
//! instance of them; the prims below the instancer are drawn only through it. Instances are
//! named `/Instancer[i]/Proto/...` for point i.

use super::Reader;
use super::values;
use crate::formats::FormatError;
use glam::{DMat4, DQuat, DVec3};
use openusd::sdf::Value;
use openusd::usd::Prim;

/// Most points read from one instancer (a count beyond is refused, naming the prim).
const MAX_POINTS: usize = 50_000_000;

impl Reader<'_> {
    pub(super) fn point_instancer(
        &mut self,
        prim: &Prim,
        world: DMat4,
        depth: usize,
    ) -> Result<(), FormatError> {
        let time = self.time;
        let err = |e: String| self.error_at(prim, e);
        let targets = prim
            .path()
            .append_property("prototypes")
            .ok()
            .and_then(|rel| self.stage.relationship(rel).targets().ok())
            .unwrap_or_default();
        let read = |name: &str| values::value(prim, name, time);
        let indices = read("protoIndices")
            .map_err(err)?
            .as_ref()
            .and_then(values::int_array)
            .unwrap_or_default();
        let positions = read("positions")
            .map_err(err)?
            .as_ref()
            .and_then(values::vec3_array)
            .unwrap_or_default();
        if indices.len() > MAX_POINTS {
            return Err(err(format!(
                "{} points: more than raygine places from one instancer ({MAX_POINTS})",
                indices.len()
            )));
        }
        if positions.len() < indices.len() {
            return Err(err(format!(
                "protoIndices has {} points but positions {}",
                indices.len(),
                positions.len()
            )));
        }
        let orientations: Vec<DQuat> = match read("orientationsf")
            .map_err(err)?
            .or(read("orientations").map_err(err)?)
        {
            Some(Value::QuathVec(q)) => q
                .iter()
                .map(|q| {
                    DQuat::from_xyzw(
                        q.x.to_f32().into(),
                        q.y.to_f32().into(),
                        q.z.to_f32().into(),
                        q.w.to_f32().into(),
                    )
                })
                .collect(),
            Some(Value::QuatfVec(q)) => q
                .iter()
                .map(|q| DQuat::from_xyzw(q.x.into(), q.y.into(), q.z.into(), q.w.into()))
                .collect(),
            _ => Vec::new(),
        };
        let scales = read("scales")
            .map_err(err)?
            .as_ref()
            .and_then(values::vec3_array)
            .unwrap_or_default();
        let ids = read("ids")
            .map_err(err)?
            .as_ref()
            .and_then(values::int_array);
        let invisible: std::collections::HashSet<i64> = read("invisibleIds")
            .map_err(err)?
            .as_ref()
            .and_then(values::int_array)
            .unwrap_or_default()
            .into_iter()
            .collect();
        // Each prototype read once (recorded as a scene-graph prototype is).
        let mut prototypes = Vec::with_capacity(targets.len());
        for target in &targets {
            let key = format!("PointInstancer {}", target.as_str());
            let root = target
                .parent()
                .map(|p| p.as_str().trim_end_matches('/').to_owned())
                .unwrap_or_default();
            let proto_prim = self.stage.prim(target.clone());
            let proto = self.prototype(&key, &root, prim, |reader| {
                reader.prim(&proto_prim, DMat4::IDENTITY, depth + 1)
            })?;
            prototypes.push(proto);
        }
        let base = prim.path().as_str().to_owned();
        let mut skipped = 0usize;
        for (i, &proto_index) in indices.iter().enumerate() {
            let id = ids
                .as_ref()
                .and_then(|ids| ids.get(i).copied())
                .unwrap_or(i as i64);
            if invisible.contains(&id) {
                continue;
            }
            let Some(proto) = usize::try_from(proto_index)
                .ok()
                .and_then(|k| prototypes.get(k))
            else {
                skipped += 1;
                continue;
            };
            let q = orientations.get(i).copied().unwrap_or(DQuat::IDENTITY);
            let q = if q.length() > 0.0 {
                q.normalize()
            } else {
                DQuat::IDENTITY
            };
            let s = scales.get(i).map_or(DVec3::ONE, |s| DVec3::from(*s));
            let m = world * DMat4::from_scale_rotation_translation(s, q, DVec3::from(positions[i]));
            let proto = std::rc::Rc::clone(proto);
            self.place(&proto, m, &format!("{base}[{i}]"));
        }
        if skipped > 0 {
            self.desc.notes.push(format!(
                "{}: {skipped} points name no prototype (protoIndices outside the {} \
                 prototypes); skipped",
                self.at(prim),
                prototypes.len()
            ));
        }
        Ok(())
    }
}
