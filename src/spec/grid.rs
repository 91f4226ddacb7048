//! Grid expansion: deep merge of defaults and scene, dotted paths, and the cartesian product.

use serde_json::Value;

use super::raw::Grid;

/// Deep-merges `overlay` into `base`: maps merge key by key, a null in `overlay` keeps what
/// `base` has, anything else replaces it.
pub fn merge(base: &mut Value, overlay: &Value) {
    match (base, overlay) {
        (_, Value::Null) => {}
        (Value::Object(base), Value::Object(overlay)) => {
            for (key, value) in overlay {
                merge(base.entry(key.clone()).or_insert(Value::Null), value);
            }
        }
        (base, overlay) => *base = overlay.clone(),
    }
}

/// The value at dotted `path` (`time.dt_per_tc`), if present and not null.
pub fn get_path<'a>(value: &'a Value, path: &str) -> Option<&'a Value> {
    path.split('.').try_fold(value, |v, key| v.get(key)).filter(|v| !v.is_null())
}

/// Sets dotted `path` to `new`, creating maps on the way.
pub fn set_path(value: &mut Value, path: &str, new: Value) {
    let mut slot = value;
    for key in path.split('.') {
        if !slot.is_object() {
            *slot = Value::Object(Default::default());
        }
        slot = slot.as_object_mut().expect("just made an object").entry(key).or_insert(Value::Null);
    }
    *slot = new;
}

/// `value` with every number in one form, so that numbers equal in value are equal as JSON:
/// `-0.0` becomes `0` and an integer-valued float (`50.0`) that integer (`50`). Grid values are
/// stored this way, and run ids hash the spec this way (`RunSpec::run_id`).
pub fn canonical(value: &Value) -> Value {
    match value {
        // Below 2^63 in magnitude an integer-valued f64 is exactly an i64.
        Value::Number(number) if number.is_f64() => match number.as_f64() {
            Some(x) if x.fract() == 0.0 && x.abs() < 2f64.powi(63) => Value::from(x as i64),
            _ => value.clone(),
        },
        Value::Array(items) => Value::Array(items.iter().map(canonical).collect()),
        Value::Object(map) => Value::Object(map.iter().map(|(key, item)| (key.clone(), canonical(item))).collect()),
        _ => value.clone(),
    }
}

/// Number of points of the cartesian product of `grid`, `None` beyond `u64::MAX`: counted
/// before the product is expanded, so an enormous grid is refused without allocating it.
pub fn point_count(grid: &Grid) -> Option<u64> {
    grid.values().try_fold(1u64, |count, values| count.checked_mul(values.len() as u64))
}

/// Cartesian product of `grid`: every combination of values, keys in sorted order with the
/// last key varying fastest. An empty grid has one point (no changes).
pub fn grid_points(grid: &Grid) -> Vec<Vec<(String, Value)>> {
    grid.iter().fold(vec![Vec::new()], |points, (path, values)| {
        points
            .iter()
            .flat_map(|point| {
                values.iter().map(move |value| {
                    let mut next = point.clone();
                    next.push((path.clone(), value.clone()));
                    next
                })
            })
            .collect()
    })
}
