//! Unit tests of `src/theory/chain.rs`, moved out of the library (one test binary).

use mdsolids::theory::ChainModes;

#[test]
fn initial_velocity_is_reproduced_and_is_the_derivative() {
    let v0 = [0.0, 0.3, -0.1, 0.0, 0.2];
    let (_, at_start) = ChainModes::new(2.0, 0.5, &v0).at(0.0);
    // The mode sum inverts the sine transform exactly: only round-off (1e-15) remains.
    for j in 0..v0.len() {
        assert!((at_start[j] - v0[j]).abs() < 1e-12);
    }
    // u̇ is du/dt: a central difference has error ~ ω³ h² ≈ 1e-12, round-off ~1e-16/h.
    let (h, t) = (1e-6, 0.7);
    let (plus, _) = ChainModes::new(2.0, 0.5, &v0).at(t + h);
    let (minus, _) = ChainModes::new(2.0, 0.5, &v0).at(t - h);
    let (_, velocity) = ChainModes::new(2.0, 0.5, &v0).at(t);
    for j in 0..v0.len() {
        assert!(((plus[j] - minus[j]) / (2.0 * h) - velocity[j]).abs() < 1e-8);
    }
}
