//! Unit tests of `src/report/kinds.rs`, moved out of the library (one test binary).

use mdsolids::model::LawSpec;
use mdsolids::report::kinds::law_name;

/// Only the power law of β = 3/2 is Hertz's; another exponent is named by its β.
#[test]
fn a_power_law_is_named_hertz_only_at_three_halves() {
    assert_eq!(law_name(LawSpec::Linear), "Linear");
    assert_eq!(law_name(LawSpec::Power { beta: 1.5 }), "Hertz");
    assert_eq!(law_name(LawSpec::Power { beta: 2.0 }), "Power-law (β = 2)");
}
