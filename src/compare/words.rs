//! How the comparison writes numbers: values in tables in one scientific form so A and B line
//! up digit by digit, ratios and exponents with fixed decimals, numbers in sentences with four
//! significant digits.

/// A value in the comparison tables: the same form at every magnitude, so that A and B line
/// up digit by digit.
pub(super) fn value(x: Option<f64>) -> String {
    x.map_or_else(|| "–".into(), |x| format!("{x:.4e}"))
}

/// A ratio, an exponent or an R²: fixed decimals for the values of order one they mostly are.
pub(super) fn fixed(x: Option<f64>) -> String {
    match x {
        Some(x) if x == 0.0 || (1e-3..1e4).contains(&x.abs()) => format!("{x:.4}"),
        Some(x) => format!("{x:.3e}"),
        None => "–".into(),
    }
}

/// A number in a sentence: 4 significant digits, plain from 1e-3 to 1e5, scientific otherwise.
pub(super) fn short(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    // The exponent after rounding to 4 digits (0.099999 is 1.000e-1), so the digits stay 4.
    let scientific = format!("{x:.3e}");
    let magnitude: i32 = scientific.split_once('e').and_then(|(_, e)| e.parse().ok()).unwrap_or(0);
    if (-3..5).contains(&magnitude) {
        let decimals = (3 - magnitude).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        scientific
    }
}

/// A fitted exponent: 4 decimals, with a fit's round-off (below 5e-5, which would print as
/// ±0.0000) written 0.0000.
pub(super) fn exponent(x: f64) -> String {
    if x.abs() < 5e-5 { "0.0000".into() } else { format!("{x:.4}") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_digits_in_sentences() {
        assert_eq!(short(2.2482), "2.248");
        assert_eq!(short(0.099999999), "0.1000");
        assert_eq!(short(0.004973), "0.004973");
        assert_eq!(short(12345.6), "12346");
        assert_eq!(short(1.4584e9), "1.458e9");
        assert_eq!(exponent(-1.83e-14), "0.0000");
        assert_eq!(exponent(0.19976), "0.1998");
    }
}
