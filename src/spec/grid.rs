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

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn product_order_is_fixed() {
        let grid: Grid = [("b".to_string(), vec![json!(1), json!(2)]), ("a".to_string(), vec![json!("x"), json!("y")])]
            .into_iter()
            .collect();
        let points = grid_points(&grid);
        let labels: Vec<String> = points.iter().map(|p| format!("{}{}", p[0].1, p[1].1)).collect();
        assert_eq!(labels, ["\"x\"1", "\"x\"2", "\"y\"1", "\"y\"2"]);
        assert_eq!(point_count(&grid), Some(4));
    }

    #[test]
    fn point_count_saturates_to_none() {
        let axis = vec![json!(0); 1000];
        let grid: Grid = (0..7).map(|i| (format!("a{i}"), axis.clone())).collect();
        assert_eq!(point_count(&grid), None); // 1000^7 > 2^64
        assert_eq!(point_count(&Grid::new()), Some(1));
    }

    #[test]
    fn canonical_numbers_are_equal_when_their_values_are() {
        assert_eq!(canonical(&json!(50.0)), json!(50));
        assert_eq!(canonical(&json!(-0.0)), json!(0));
        assert_eq!(canonical(&json!(0.0)).to_string(), canonical(&json!(-0.0)).to_string());
        assert_eq!(canonical(&json!({"a": [2.0, 0.5], "b": -3.0})), json!({"a": [2, 0.5], "b": -3}));
        assert_eq!(canonical(&json!(0.5)), json!(0.5));
        assert_eq!(canonical(&json!(1e300)), json!(1e300)); // beyond i64: left a float
        assert_eq!(canonical(&json!(u64::MAX)), json!(u64::MAX));
    }

    #[test]
    fn merge_keeps_base_under_null_and_nests() {
        let mut base = json!({"time": {"dt_per_tc": 50, "samples": 10}, "v0": 1.0});
        merge(&mut base, &json!({"time": {"dt_per_tc": 20, "samples": null}, "v0": null}));
        assert_eq!(base, json!({"time": {"dt_per_tc": 20, "samples": 10}, "v0": 1.0}));
        set_path(&mut base, "damping.restitution", json!(0.5));
        assert_eq!(get_path(&base, "damping.restitution"), Some(&json!(0.5)));
    }
}
