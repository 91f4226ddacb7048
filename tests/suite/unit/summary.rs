//! Unit tests of `src/summary`: the exponents the spring laws predict (moved out of the library:
//! one test binary).

use mdsolids::summary::predicted;

/// Hertz springs (β = 3/2): sound speed ∝ v0^(1/5), moduli ∝ F^(1/3), chain stiffness
/// ∝ |ΔW|^(1/2); linear springs 0 throughout.
#[test]
fn laws_predict_the_hertz_exponents() {
    let p = |against: &str, beta: f64| predicted("", against, beta).unwrap().0;
    assert!((p("v0", 1.5) - 0.2).abs() < 1e-15);
    assert!((p("load_per_node", 1.5) - 1.0 / 3.0).abs() < 1e-15);
    assert!((p("wall_displacement", 1.5) - 0.5).abs() < 1e-15);
    for against in ["v0", "load_per_node", "wall_displacement"] {
        assert_eq!(p(against, 1.0), 0.0);
    }
    assert!(predicted("", "time.dt_per_tc", 1.5).is_none());
}

/// Near jamming (O'Hern, Silbert, Liu & Nagel 2003, their table): linear contacts p ∝ Δφ¹,
/// z − 4 ∝ Δφ^½, K ∝ Δφ⁰, G ∝ Δφ^½; Hertz p ∝ Δφ^(3/2), K ∝ Δφ^½, G ∝ Δφ¹; G/K ∝ Δz¹ for both.
/// A quantity the theory does not scale (the box side) has no prediction.
#[test]
fn packings_near_jamming_predict_o_hern_et_al_s_exponents() {
    let p = |quantity: &str, beta: f64| predicted(quantity, "fraction_excess", beta).unwrap().0;
    let quantities = ["pressure", "coordination_excess", "bulk_modulus_2d", "shear_modulus_2d"];
    assert_eq!(quantities.map(|q| p(q, 1.0)), [1.0, 0.5, 0.0, 0.5]);
    assert_eq!(quantities.map(|q| p(q, 1.5)), [1.5, 0.5, 0.5, 1.0]);
    for beta in [1.0, 1.5] {
        assert_eq!(predicted("shear_over_bulk", "coordination_excess", beta).unwrap().0, 1.0);
    }
    assert!(predicted("box_side", "fraction_excess", 1.0).is_none());
    assert!(predicted("pressure", "coordination_excess", 1.0).is_none());
}
