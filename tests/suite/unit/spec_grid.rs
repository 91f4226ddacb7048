//! Unit tests of `src/spec/grid.rs`, moved out of the library (one test binary).

use mdsolids::spec::Grid;
use mdsolids::spec::grid::{canonical, get_path, grid_points, merge, point_count, set_path};
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
