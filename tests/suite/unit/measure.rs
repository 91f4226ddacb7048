//! Unit tests of `src/measure/mod.rs`, moved out of the library (one test binary).

use mdsolids::measure::{Recommendation, convergence_order, recommended_dt};

#[test]
fn recommendation_of_an_exact_power_law() {
    // e = 3 dt²: the target 3e-4 is met exactly at dt = 0.01, wherever the sweep is.
    let points: Vec<(f64, f64)> = [0.1, 0.05, 0.02, 0.005].iter().map(|&dt| (dt, 3.0 * dt * dt)).collect();
    let order = convergence_order(&points);
    assert!((order.unwrap() - 2.0).abs() < 1e-12);
    let (dt, how) = recommended_dt(&points, 3e-4, order).unwrap();
    assert_eq!(how, Recommendation::Interpolated);
    assert!((dt - 0.01).abs() < 1e-12, "{dt}");
    let (dt, how) = recommended_dt(&points[..2], 3e-4, order).unwrap();
    assert_eq!(how, Recommendation::Extrapolated);
    assert!((dt - 0.01).abs() < 1e-12, "{dt}");
    assert_eq!(recommended_dt(&points, 1.0, order).unwrap(), (0.1, Recommendation::AtLargest));
}
