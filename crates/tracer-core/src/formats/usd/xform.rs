//! UsdGeomXformable's op stacks: `xformOpOrder` lists ops (`xformOp:translate`,
//! `xformOp:rotateXYZ`, `xformOp:orient`, `xformOp:scale`, `xformOp:transform`, with optional
//! `:suffix`es and `!invert!` prefixes); the first listed is the outermost. `!resetXformStack!`
//! first in the list drops the parent's transform.
//!
//! Matrices here are glam's (column vectors): a point p goes to M p. USD writes row vectors
//! (p M), so its `matrix4d` values are read transposed.

use super::values::{self, Time};
use glam::{DMat4, DQuat, DVec3};
use openusd::sdf::Value;
use openusd::usd::Prim;

const RESET: &str = "!resetXformStack!";
const INVERT: &str = "!invert!";

/// A prim's local-to-parent transform, and whether it resets the parent's.
pub(super) fn local(prim: &Prim, time: Time) -> Result<(DMat4, bool), String> {
    let order = match values::value(prim, "xformOpOrder", Time::Default)? {
        Some(Value::TokenVec(t)) => t.iter().map(|t| t.as_str().to_owned()).collect(),
        Some(Value::StringVec(s)) => s,
        Some(other) => return Err(format!("xformOpOrder: not a token array ({other:?})")),
        None => Vec::new(),
    };
    let mut m = DMat4::IDENTITY;
    let mut reset = false;
    for (i, op) in order.iter().enumerate() {
        if op == RESET {
            if i == 0 {
                reset = true;
                continue;
            }
            return Err(format!(
                "xformOpOrder: {RESET} is only allowed first (found at {i})"
            ));
        }
        m *= op_matrix(prim, op, time)?;
    }
    if !m.is_finite() {
        return Err("its transform (xformOpOrder) is not finite".into());
    }
    Ok((m, reset))
}

/// One op's matrix.
fn op_matrix(prim: &Prim, op: &str, time: Time) -> Result<DMat4, String> {
    let (inverted, name) = match op.strip_prefix(INVERT) {
        Some(rest) => (true, rest),
        None => (false, op),
    };
    let kind = name
        .strip_prefix("xformOp:")
        .ok_or_else(|| format!("xformOpOrder: {op} is not an xformOp"))?
        .split(':')
        .next()
        .unwrap_or_default();
    let Some(v) = values::value(prim, name, time)? else {
        return Err(format!("xformOpOrder lists {name}, which has no value"));
    };
    let bad = || format!("{name}: a {kind} op cannot hold {v:?}");
    let s = || values::scalar(&v).ok_or_else(bad);
    let v3 = || values::vec3(&v).map(DVec3::from).ok_or_else(bad);
    let m = match kind {
        "translate" => DMat4::from_translation(v3()?),
        "translateX" => DMat4::from_translation(DVec3::X * s()?),
        "translateY" => DMat4::from_translation(DVec3::Y * s()?),
        "translateZ" => DMat4::from_translation(DVec3::Z * s()?),
        "scale" => DMat4::from_scale(v3()?),
        "scaleX" => DMat4::from_scale(DVec3::new(s()?, 1.0, 1.0)),
        "scaleY" => DMat4::from_scale(DVec3::new(1.0, s()?, 1.0)),
        "scaleZ" => DMat4::from_scale(DVec3::new(1.0, 1.0, s()?)),
        "rotateX" => DMat4::from_rotation_x(s()?.to_radians()),
        "rotateY" => DMat4::from_rotation_y(s()?.to_radians()),
        "rotateZ" => DMat4::from_rotation_z(s()?.to_radians()),
        "rotateXYZ" | "rotateXZY" | "rotateYXZ" | "rotateYZX" | "rotateZXY" | "rotateZYX" => {
            let angles = v3()?;
            // The first named axis turns the point first: it is the rightmost factor.
            kind[6..].chars().fold(DMat4::IDENTITY, |m, axis| {
                let r = match axis {
                    'X' => DMat4::from_rotation_x(angles.x.to_radians()),
                    'Y' => DMat4::from_rotation_y(angles.y.to_radians()),
                    _ => DMat4::from_rotation_z(angles.z.to_radians()),
                };
                r * m
            })
        }
        "orient" => {
            let q = match &v {
                Value::Quatf(q) => DQuat::from_xyzw(q.x.into(), q.y.into(), q.z.into(), q.w.into()),
                Value::Quatd(q) => DQuat::from_xyzw(q.x, q.y, q.z, q.w),
                Value::Quath(q) => DQuat::from_xyzw(
                    q.x.to_f32().into(),
                    q.y.to_f32().into(),
                    q.z.to_f32().into(),
                    q.w.to_f32().into(),
                ),
                _ => return Err(bad()),
            };
            if q.length().is_nan() || q.length() <= 0.0 {
                return Err(format!("{name}: a zero quaternion"));
            }
            DMat4::from_quat(q.normalize())
        }
        "transform" => match &v {
            Value::Matrix4d(m) => DMat4::from_cols_array(&m.0),
            _ => return Err(bad()),
        },
        _ => return Err(format!("{name}: unknown op kind {kind}")),
    };
    if inverted {
        if m.determinant().abs() < 1e-300 || !m.is_finite() {
            return Err(format!("{op}: the op is singular and cannot be inverted"));
        }
        Ok(m.inverse())
    } else {
        Ok(m)
    }
}

/// The turn from a stage's up axis to raygine's +Y: none for "Y", −90° about X for "Z"
/// (+Z up becomes +Y up, +Y becomes −Z).
pub(super) fn up_axis(axis: &str) -> Option<DMat4> {
    match axis {
        "Y" => Some(DMat4::IDENTITY),
        "Z" => Some(DMat4::from_cols_array(&[
            1.0, 0.0, 0.0, 0.0, //
            0.0, 0.0, -1.0, 0.0, //
            0.0, 1.0, 0.0, 0.0, //
            0.0, 0.0, 0.0, 1.0,
        ])),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn z_up_turns_z_to_y_and_y_to_minus_z() {
        let m = up_axis("Z").unwrap_or_default();
        assert_eq!(m.transform_vector3(DVec3::Z), DVec3::Y);
        assert_eq!(m.transform_vector3(DVec3::Y), -DVec3::Z);
        assert_eq!(m.transform_vector3(DVec3::X), DVec3::X);
        assert!((m.determinant() - 1.0).abs() < 1e-15);
    }
}
