//! Reading attribute values off composed prims: at the chosen time, in whatever precision the
//! file wrote them (half, float, double; int or int64), with USD's schema defaults where the
//! file is silent.

use openusd::sdf::Value;
use openusd::usd::{Prim, TimeCode};

/// Which time attribute values are read at.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) enum Time {
    /// The default value; an attribute with time samples only gives its earliest one.
    #[default]
    Default,
    /// The value at this time code (held or interpolated as the stage says).
    At(f64),
}

/// An attribute's value at `time`, `None` when nothing is authored. `Err` names the attribute.
pub(super) fn value(prim: &Prim, name: &str, time: Time) -> Result<Option<Value>, String> {
    let attr = prim.attribute(name);
    let why = |e: anyhow::Error| format!("{name}: {e:#}");
    let got = match time {
        Time::At(t) => attr.get_at::<Value>(TimeCode::new(t)).map_err(why)?,
        Time::Default => match attr.get::<Value>().map_err(why)? {
            Some(v) => Some(v),
            None if attr.num_time_samples().unwrap_or(0) > 0 => {
                attr.get_at::<Value>(TimeCode::EARLIEST).map_err(why)?
            }
            None => None,
        },
    };
    // A blocked value (`None` in the file) reads as unauthored.
    Ok(got.filter(|v| !matches!(v, Value::ValueBlock)))
}

/// The first of `names` that is authored (UsdLux's `inputs:intensity`, then the pre-2021
/// `intensity`).
pub(super) fn first_value(
    prim: &Prim,
    names: &[&str],
    time: Time,
) -> Result<Option<Value>, String> {
    for name in names {
        if let Some(v) = value(prim, name, time)? {
            return Ok(Some(v));
        }
    }
    Ok(None)
}

pub(super) fn scalar(v: &Value) -> Option<f64> {
    match v {
        Value::Double(d) => Some(*d),
        Value::Float(f) => Some(f64::from(*f)),
        Value::Half(h) => Some(f64::from(h.to_f32())),
        Value::Int(i) => Some(f64::from(*i)),
        Value::Int64(i) => Some(*i as f64),
        Value::Uint(i) => Some(f64::from(*i)),
        Value::Bool(b) => Some(f64::from(u8::from(*b))),
        _ => None,
    }
}

pub(super) fn boolean(v: &Value) -> Option<bool> {
    match v {
        Value::Bool(b) => Some(*b),
        other => scalar(other).map(|x| x != 0.0),
    }
}

pub(super) fn vec3(v: &Value) -> Option<[f64; 3]> {
    match v {
        Value::Vec3d(a) => Some([a.x, a.y, a.z]),
        Value::Vec3f(a) => Some([a.x, a.y, a.z].map(f64::from)),
        Value::Vec3h(a) => Some([a.x, a.y, a.z].map(|c| f64::from(c.to_f32()))),
        // A one-element array where a value is meant (constant primvars).
        Value::Vec3fVec(a) if a.len() == 1 => Some([a[0].x, a[0].y, a[0].z].map(f64::from)),
        Value::Vec3dVec(a) if a.len() == 1 => Some([a[0].x, a[0].y, a[0].z]),
        _ => None,
    }
}

pub(super) fn token(v: &Value) -> Option<&str> {
    match v {
        Value::Token(t) => Some(t.as_str()),
        Value::String(s) => Some(s.as_str()),
        _ => None,
    }
}

pub(super) fn vec3_array(v: &Value) -> Option<Vec<[f64; 3]>> {
    Some(match v {
        Value::Vec3fVec(a) => a.iter().map(|p| [p.x, p.y, p.z].map(f64::from)).collect(),
        Value::Vec3dVec(a) => a.iter().map(|p| [p.x, p.y, p.z]).collect(),
        Value::Vec3hVec(a) => a
            .iter()
            .map(|p| [p.x, p.y, p.z].map(|c| f64::from(c.to_f32())))
            .collect(),
        _ => return None,
    })
}

pub(super) fn vec2_array(v: &Value) -> Option<Vec<[f64; 2]>> {
    Some(match v {
        Value::Vec2fVec(a) => a.iter().map(|p| [p.x, p.y].map(f64::from)).collect(),
        Value::Vec2dVec(a) => a.iter().map(|p| [p.x, p.y]).collect(),
        Value::Vec2hVec(a) => a
            .iter()
            .map(|p| [p.x, p.y].map(|c| f64::from(c.to_f32())))
            .collect(),
        _ => return None,
    })
}

/// An integer array (counts, indices); negative entries stay negative for the caller to refuse.
pub(super) fn int_array(v: &Value) -> Option<Vec<i64>> {
    Some(match v {
        Value::IntVec(a) => a.iter().map(|&i| i64::from(i)).collect(),
        Value::Int64Vec(a) => a.clone(),
        Value::UintVec(a) => a.iter().map(|&i| i64::from(i)).collect(),
        Value::Uint64Vec(a) => a
            .iter()
            .map(|&i| i64::try_from(i).unwrap_or(i64::MAX))
            .collect(),
        _ => return None,
    })
}

/// `inputs:NAME` as a number, else `NAME` (UsdLux before 2021), else `fallback`.
pub(super) fn input_scalar(
    prim: &Prim,
    name: &str,
    time: Time,
    fallback: f64,
) -> Result<f64, String> {
    Ok(first_value(prim, &[&format!("inputs:{name}"), name], time)?
        .as_ref()
        .and_then(scalar)
        .filter(|x| x.is_finite())
        .unwrap_or(fallback))
}

/// A scalar attribute (no `inputs:` namespace) or `fallback`.
pub(super) fn attr_scalar(
    prim: &Prim,
    name: &str,
    time: Time,
    fallback: f64,
) -> Result<f64, String> {
    Ok(value(prim, name, time)?
        .as_ref()
        .and_then(scalar)
        .filter(|x| x.is_finite())
        .unwrap_or(fallback))
}

/// A token attribute (uniform: read at the default time).
pub(super) fn attr_token(prim: &Prim, name: &str) -> Result<Option<String>, String> {
    Ok(value(prim, name, Time::Default)?
        .as_ref()
        .and_then(token)
        .map(str::to_owned))
}
