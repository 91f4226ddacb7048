//! Unit tests of `src/compare/exponents.rs`, moved out of the library (one test binary).

use mdsolids::compare::exponents::predicted;

/// Hertz springs (β = 3/2): sound speed ∝ v0^(1/5), moduli ∝ F^(1/3), chain stiffness
/// ∝ |ΔW|^(1/2); linear springs 0 throughout.
#[test]
fn laws_predict_the_hertz_exponents() {
    let p = |against: &str, beta: f64| predicted(against, beta).unwrap().0;
    assert!((p("v0", 1.5) - 0.2).abs() < 1e-15);
    assert!((p("load_per_node", 1.5) - 1.0 / 3.0).abs() < 1e-15);
    assert!((p("wall_displacement", 1.5) - 0.5).abs() < 1e-15);
    for against in ["v0", "load_per_node", "wall_displacement"] {
        assert_eq!(p(against, 1.0), 0.0);
    }
    assert!(predicted("time.dt_per_tc", 1.5).is_none());
}
