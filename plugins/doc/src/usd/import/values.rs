//! Typed reads of a prim's attributes from `openusd` values, each failure
//! naming the prim and the attribute.

use super::{R, attr_error};
use crate::usd::MAX_ARRAY;
use glam::{DQuat, DVec2, DVec3};
use openusd::{sdf, usd};

/// The attribute's default value (`None` when not authored).
pub(super) fn get_value(prim: &usd::Prim, name: &str) -> R<Option<sdf::Value>> {
    let v = prim
        .attribute(name)
        .get::<sdf::Value>()
        .map_err(|e| attr_error(prim, name, format!("cannot be read: {e:#}")))?;
    if let Some(v) = &v
        && array_len(v) > MAX_ARRAY
    {
        return Err(attr_error(
            prim,
            name,
            format!("more than {MAX_ARRAY} elements; refused"),
        ));
    }
    Ok(v)
}

fn array_len(v: &sdf::Value) -> usize {
    use sdf::Value as V;
    match v {
        V::IntVec(x) => x.len(),
        V::Int64Vec(x) => x.len(),
        V::UintVec(x) => x.len(),
        V::FloatVec(x) => x.len(),
        V::DoubleVec(x) => x.len(),
        V::Vec3fVec(x) => x.len(),
        V::Vec3dVec(x) => x.len(),
        V::Vec2fVec(x) => x.len(),
        V::Vec2dVec(x) => x.len(),
        V::TokenVec(x) => x.len(),
        _ => 0,
    }
}

/// True when the attribute has time samples (animation).
pub(super) fn time_sampled(prim: &usd::Prim, name: &str) -> bool {
    prim.attribute(name).num_time_samples().is_ok_and(|n| n > 0)
}

/// The primvar's `interpolation` metadata.
pub(super) fn interpolation(prim: &usd::Prim, name: &str) -> Option<String> {
    let v = prim
        .attribute(name)
        .get_metadata::<sdf::Value>("interpolation")
        .ok()
        .flatten()?;
    text(&v)
}

fn text(v: &sdf::Value) -> Option<String> {
    match v {
        sdf::Value::Token(t) => Some(t.as_str().to_string()),
        sdf::Value::String(s) => Some(s.clone()),
        _ => None,
    }
}

fn wrong(prim: &usd::Prim, name: &str, what: &str) -> crate::usd::import::UsdError {
    attr_error(prim, name, format!("is not {what}"))
}

pub(super) fn get_bool(prim: &usd::Prim, name: &str) -> R<Option<bool>> {
    match get_value(prim, name)? {
        None => Ok(None),
        Some(sdf::Value::Bool(b)) => Ok(Some(b)),
        Some(v) => scalar(&v)
            .map(|x| Some(x != 0.0))
            .ok_or_else(|| wrong(prim, name, "a bool")),
    }
}

pub(super) fn get_string(prim: &usd::Prim, name: &str) -> R<Option<String>> {
    match get_value(prim, name)? {
        None => Ok(None),
        Some(v) => text(&v)
            .map(Some)
            .ok_or_else(|| wrong(prim, name, "a string")),
    }
}

pub(super) fn get_token(prim: &usd::Prim, name: &str) -> R<Option<String>> {
    get_string(prim, name)
}

pub(super) fn get_tokens(prim: &usd::Prim, name: &str) -> R<Option<Vec<String>>> {
    match get_value(prim, name)? {
        None => Ok(None),
        Some(sdf::Value::TokenVec(t)) => {
            Ok(Some(t.iter().map(|t| t.as_str().to_string()).collect()))
        }
        Some(sdf::Value::StringVec(t)) => Ok(Some(t)),
        Some(_) => Err(wrong(prim, name, "an array of tokens")),
    }
}

pub(super) fn get_ints(prim: &usd::Prim, name: &str) -> R<Option<Vec<i64>>> {
    use sdf::Value as V;
    Ok(match get_value(prim, name)? {
        None => None,
        Some(V::IntVec(x)) => Some(x.into_iter().map(i64::from).collect()),
        Some(V::Int64Vec(x)) => Some(x),
        Some(V::UintVec(x)) => Some(x.into_iter().map(i64::from).collect()),
        Some(_) => return Err(wrong(prim, name, "an array of integers")),
    })
}

pub(super) fn get_floats(prim: &usd::Prim, name: &str) -> R<Option<Vec<f64>>> {
    use sdf::Value as V;
    Ok(match get_value(prim, name)? {
        None => None,
        Some(V::FloatVec(x)) => Some(x.into_iter().map(f64::from).collect()),
        Some(V::DoubleVec(x)) => Some(x),
        Some(V::IntVec(x)) => Some(x.into_iter().map(f64::from).collect()),
        Some(_) => return Err(wrong(prim, name, "an array of numbers")),
    })
    .and_then(|v: Option<Vec<f64>>| match v {
        Some(v) if v.iter().any(|x| !x.is_finite()) => {
            Err(wrong(prim, name, "finite (it holds NaN or infinity)"))
        }
        v => Ok(v),
    })
}

/// `name` as floats, or `hedra:<name>` (the exact doubles Hedra wrote)
/// when that rounds to the same floats.
pub(super) fn exact_floats(prim: &usd::Prim, name: &str) -> R<Vec<f64>> {
    let plain = get_floats(prim, name)?.unwrap_or_default();
    let exact = get_floats(prim, &format!("{}{name}", crate::usd::HEDRA))?;
    Ok(match exact {
        Some(e)
            if e.len() == plain.len()
                && e.iter().zip(&plain).all(|(a, b)| (*a as f32) as f64 == *b) =>
        {
            e
        }
        _ => plain,
    })
}

/// `points`, or `hedra:points` when that rounds to the same floats.
pub(super) fn exact_points(prim: &usd::Prim) -> R<Vec<DVec3>> {
    let plain = match get_value(prim, "points")? {
        None => Vec::new(),
        Some(v) => vec3s(&v).ok_or_else(|| wrong(prim, "points", "an array of points"))?,
    };
    if plain.iter().any(|p| !p.is_finite()) {
        return Err(wrong(prim, "points", "finite (it holds NaN or infinity)"));
    }
    let exact = match get_value(prim, "hedra:points")? {
        Some(v) => vec3s(&v),
        None => None,
    };
    let f = |p: &DVec3| p.as_vec3().as_dvec3();
    Ok(match exact {
        Some(e)
            if e.len() == plain.len()
                && e.iter().all(|p| p.is_finite())
                && e.iter().zip(&plain).all(|(a, b)| f(a) == *b) =>
        {
            e
        }
        _ => plain,
    })
}

pub(super) fn scalar(v: &sdf::Value) -> Option<f64> {
    use sdf::Value as V;
    match v {
        V::Int(x) => Some(f64::from(*x)),
        V::Int64(x) => Some(*x as f64),
        V::Uint(x) => Some(f64::from(*x)),
        V::Float(x) => Some(f64::from(*x)),
        V::Double(x) => Some(*x),
        _ => None,
    }
    .filter(|x| x.is_finite())
}

pub(super) fn vec2(v: &sdf::Value) -> Option<DVec2> {
    match v {
        sdf::Value::Vec2d(p) => Some(DVec2::new(p.x, p.y)),
        sdf::Value::Vec2f(p) => Some(DVec2::new(f64::from(p.x), f64::from(p.y))),
        _ => None,
    }
    .filter(|p| p.is_finite())
}

pub(super) fn vec3(v: &sdf::Value) -> Option<DVec3> {
    match v {
        sdf::Value::Vec3d(p) => Some(DVec3::new(p.x, p.y, p.z)),
        sdf::Value::Vec3f(p) => Some(DVec3::new(f64::from(p.x), f64::from(p.y), f64::from(p.z))),
        _ => None,
    }
    .filter(|p| p.is_finite())
}

pub(super) fn quat(v: &sdf::Value) -> Option<DQuat> {
    match v {
        sdf::Value::Quatd(q) => Some(DQuat::from_xyzw(q.x, q.y, q.z, q.w)),
        sdf::Value::Quatf(q) => Some(DQuat::from_xyzw(
            f64::from(q.x),
            f64::from(q.y),
            f64::from(q.z),
            f64::from(q.w),
        )),
        _ => None,
    }
    .filter(|q| q.is_finite() && q.length() > 1e-12)
}

pub(super) fn vec2s(v: &sdf::Value) -> Option<Vec<DVec2>> {
    match v {
        sdf::Value::Vec2fVec(x) => Some(
            x.iter()
                .map(|p| DVec2::new(f64::from(p.x), f64::from(p.y)))
                .collect(),
        ),
        sdf::Value::Vec2dVec(x) => Some(x.iter().map(|p| DVec2::new(p.x, p.y)).collect()),
        _ => None,
    }
}

pub(super) fn vec3s(v: &sdf::Value) -> Option<Vec<DVec3>> {
    match v {
        sdf::Value::Vec3fVec(x) => Some(
            x.iter()
                .map(|p| DVec3::new(f64::from(p.x), f64::from(p.y), f64::from(p.z)))
                .collect(),
        ),
        sdf::Value::Vec3dVec(x) => Some(x.iter().map(|p| DVec3::new(p.x, p.y, p.z)).collect()),
        _ => None,
    }
}
