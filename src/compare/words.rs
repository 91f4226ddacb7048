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
    let magnitude = x.abs().log10().floor();
    if (-3.0..5.0).contains(&magnitude) {
        let decimals = (3.0 - magnitude).max(0.0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.3e}")
    }
}

/// A fitted exponent: 4 decimals, with a fit's round-off (below 5e-5, which would print as
/// ±0.0000) written 0.0000.
pub(super) fn exponent(x: f64) -> String {
    if x.abs() < 5e-5 { "0.0000".into() } else { format!("{x:.4}") }
}
