//! Unit tests of `src/model/law.rs`, moved out of the library (one test binary).

use mdsolids::model::{ForceLaw, PowerLaw};

/// Distance in units in the last place between two finite doubles of one sign.
fn ulps(a: f64, b: f64) -> u64 {
    a.to_bits().abs_diff(b.to_bits())
}

/// Hertz's exponents go through a square root (|δ|√|δ| for s, δ²√|δ| for e, √|δ| for ds/dδ)
/// instead of `powf`: within 2 ulp of `powf` over 10⁵ extensions spread over 1e-12 … 1e2 m of
/// either sign (|δ|√|δ| rounds twice, `powf` once, each by ≤ ½–1 ulp), the energy within 3 ulp
/// (δ²√|δ| rounds three times), the sign of the force that of δ, zero at δ = 0. Other exponents still use `powf` itself, bit for bit.
#[test]
fn hertz_through_the_square_root_agrees_with_powf_to_the_last_bits() {
    let hertz = PowerLaw { beta: 1.5 };
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    for _ in 0..100_000 {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let exponent = (state >> 11) as f64 / (1u64 << 53) as f64 * 14.0 - 12.0;
        let delta = 10f64.powf(exponent) * if state & 1 == 0 { 1.0 } else { -1.0 };
        let magnitude = delta.abs();
        let force = hertz.elastic_force(1.0, delta);
        assert_eq!(force.signum(), delta.signum(), "δ = {delta:e}");
        assert!(ulps(force.abs(), magnitude.powf(1.5)) <= 2, "s({delta:e}) = {force:e}");
        assert!(
            ulps(hertz.energy(1.0, delta), magnitude.powf(2.5) / 2.5) <= 3,
            "e({delta:e}): {} ulp",
            ulps(hertz.energy(1.0, delta), magnitude.powf(2.5) / 2.5)
        );
        assert!(ulps(hertz.tangent_stiffness(1.0 / 1.5, delta), magnitude.sqrt()) <= 2, "k_t({delta:e})");
        let other = PowerLaw { beta: 1.25 };
        assert_eq!(other.elastic_force(1.0, delta).abs(), magnitude.powf(1.25), "β = 1.25 at {delta:e}");
    }
    assert_eq!(hertz.elastic_force(3.0, 0.0), 0.0);
    assert_eq!(hertz.tangent_stiffness(3.0, 0.0), 0.0);
}
