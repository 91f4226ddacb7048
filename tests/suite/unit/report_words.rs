//! Unit tests of `src/report/words.rs`, moved out of the library (one test binary).

use mdsolids::report::words::{exponent, short, times};

/// Numbers in sentences keep 4 significant digits after rounding; an exponent's round-off is 0.
#[test]
fn four_digits_in_sentences() {
    assert_eq!(short(2.2482), "2.248");
    assert_eq!(short(2.221441469), "2.221");
    assert_eq!(short(0.0444288), "0.04443");
    assert_eq!(short(0.099999999), "0.1000");
    assert_eq!(short(0.004973), "0.004973");
    assert_eq!(short(12345.6), "12346");
    assert_eq!(short(1.4584e9), "1.458e9");
    assert_eq!(short(2.0e11), "2.000e11");
    assert_eq!(exponent(-1.83e-14, 4), "0.0000");
    assert_eq!(exponent(-2e-4, 3), "0.000");
    assert_eq!(exponent(0.19976, 4), "0.1998");
}

#[test]
fn times_says_which_way_and_keeps_a_decimal_below_ten() {
    assert_eq!(times(1.16, "longer", "shorter"), "1.2× longer");
    assert_eq!(times(0.5, "faster", "slower"), "2.0× slower");
    assert_eq!(times(12.4, "faster", "slower"), "12× faster");
}
