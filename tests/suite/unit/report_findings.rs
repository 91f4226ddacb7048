//! Unit tests of `src/report/findings/mod.rs`, moved out of the library (one test binary).

use mdsolids::report::findings::rel;

#[test]
fn relative_errors_read_with_their_sign() {
    // A minus sign (U+2212) as print has it, the exponent's sign a hyphen as code reads it.
    assert_eq!(rel(-1.6464e-4), "−1.6e-4");
    assert_eq!(rel(1.6464e-4), "+1.6e-4");
}
