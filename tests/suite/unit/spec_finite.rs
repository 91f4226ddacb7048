//! Unit tests of `src/spec/finite.rs`, moved out of the library (one test binary).

use mdsolids::spec::finite::first_non_finite;

#[test]
fn finds_the_path_of_nan_and_infinities() {
    let found = first_non_finite("scenes:\n  - material: {mass: .nan}\n");
    assert!(matches!(found, Some((ref p, v)) if p == "scenes[0].material.mass" && v.is_nan()), "{found:?}");
    let found = first_non_finite("grid:\n  time.dt_per_tc: [1, -.inf]\n");
    assert_eq!(found, Some(("grid.\"time.dt_per_tc\"[1]".into(), f64::NEG_INFINITY)));
    assert_eq!(first_non_finite("a: [1.5, 2, x]\n"), None);
}
