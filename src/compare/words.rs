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

/// Numbers in sentences and fitted exponents are written as the campaign report writes them.
pub(super) use crate::report::words::{count, counted, exponent, short};
