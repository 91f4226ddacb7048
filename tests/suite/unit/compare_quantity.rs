//! Unit tests of `src/compare/quantity.rs`, moved out of the library (one test binary).

use mdsolids::compare::quantity::{Class, class, unit};

#[test]
fn classes_and_units() {
    assert_eq!(class("wall_s"), Class::Cost);
    assert_eq!(class("mass"), Class::Setup);
    assert_eq!(class("contact_duration_theory"), Class::Setup);
    assert_eq!(class("contact_duration_error"), Class::Deviation);
    assert_eq!(class("homogeneity"), Class::Deviation);
    assert_eq!(class("sound_speed_first_maximum"), Class::Result);
    assert_eq!(unit("contact_duration_error"), "1");
    assert_eq!(unit("sound_speed_first_maximum"), "m/s");
    assert_eq!(unit("youngs_modulus_tangent_fem"), "Pa");
    assert_eq!(unit("spacing_spread"), "m");
    assert_eq!(unit("dt_per_tc"), "1");
    assert_eq!(unit("k_diag"), "N/m^β");
    assert_eq!(unit("poisson_ratio"), "1");
}
