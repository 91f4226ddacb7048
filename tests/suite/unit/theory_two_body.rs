//! Unit tests of `src/theory/two_body.rs`, moved out of the library (one test binary).

use mdsolids::theory::special::beta;
use mdsolids::theory::{gamma_for_restitution, linear_restitution, pair_omega};

#[test]
fn restitution_round_trip() {
    // γ from r and back: only round-off (1e-12) separates them.
    for r in [0.1, 0.5, 0.9, 1.0] {
        let g = gamma_for_restitution(r, 2.0, 3.0);
        assert!((linear_restitution(2.0, 3.0, g).unwrap() - r).abs() < 1e-12);
    }
}

#[test]
fn no_damping_is_plus_zero() {
    // r = 1: −ln r was −0, printed as "-0.0" in the gamma column.
    assert!(gamma_for_restitution(1.0, 2.0, 3.0).is_sign_positive());
}

#[test]
fn overdamped_is_an_error() {
    assert!(pair_omega(1.0, 1.0, 2f64.sqrt()).is_err());
}

#[test]
fn hertz_integral() {
    // ∫₀¹ (1 − x^{5/2})^{-1/2} dx = B(2/5, 1/2)/(5/2) = 1.4716375921623523 (Python's
    // math.gamma, an independent implementation; the classic Hertz factor 2.9432 is twice
    // it). 1e-13 covers both implementations' round-off.
    let p: f64 = 2.5;
    assert!((beta(1.0 / p, 0.5) / p - 1.471_637_592_162_352_3).abs() < 1e-13);
}
