//! Unit tests of `src/theory/special.rs`, moved out of the library (one test binary).

use mdsolids::theory::special::{beta, gamma};

#[test]
fn gamma_known_values() {
    // Γ(1/2) = √π, Γ(5) = 24, Γ(0.4) = 2.218159543757688 (tables); 1e-13 leaves room for
    // the approximation's 1e-15 and the powf/exp round-off.
    assert!((gamma(0.5) - std::f64::consts::PI.sqrt()).abs() < 1e-13);
    assert!((gamma(5.0) - 24.0).abs() < 1e-12);
    assert!((gamma(0.4) - 2.218_159_543_757_688).abs() < 1e-13);
    assert!((beta(0.5, 0.5) - std::f64::consts::PI).abs() < 1e-13);
}
