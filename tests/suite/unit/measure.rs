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

#[test]
fn the_decay_rate_follows_the_crests_late() {
    // A ringing decay e^(−3t)(1 + 0.9 cos 20t): its crests fall at 3/s to within the crests'
    // spacing in phase (2 %). A sum of two decays e^(−2t) + e^(−10t): over the second half
    // (t ≥ 2.5 s) the slow one alone remains, 2/s to 1e-6.
    let ringing: Vec<(f64, f64)> =
        (0..2000).map(|i| i as f64 * 0.0025).map(|t| (t, (-3.0 * t).exp() * (1.0 + 0.9 * (20.0 * t).cos()))).collect();
    let rate = mdsolids::measure::decay_rate(&ringing).unwrap();
    assert!((rate / 3.0 - 1.0).abs() < 0.02, "{rate}");
    let two: Vec<(f64, f64)> =
        (0..=100).map(|i| i as f64 * 0.05).map(|t| (t, (-2.0 * t).exp() + (-10.0 * t).exp())).collect();
    let rate = mdsolids::measure::decay_rate(&two).unwrap();
    assert!((rate - 2.0).abs() < 1e-6, "{rate}");
    assert_eq!(mdsolids::measure::decay_rate(&[(0.0, 1.0)]), None);
}
