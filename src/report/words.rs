//! How the report writes numbers and specs in words: six significant digits, signed errors, a
//! dash for a missing value, an impulse as a kick or a step force.

use crate::measure::PowerLawFit;
use crate::sim::IntegratorKind;
use crate::spec::ImpulseSpec;

/// `text`, a formatted number, with a minus sign (−, U+2212) where Rust writes a hyphen before
/// it: the sign a reader sees in print. The exponent's sign stays a hyphen (`−1.6e-4`), the
/// form code and spreadsheets read.
pub fn minus_sign(text: String) -> String {
    match text.strip_prefix('-') {
        Some(magnitude) => format!("−{magnitude}"),
        None => text,
    }
}

/// `text` with its first letter upper case.
pub fn capitalised(text: &str) -> String {
    let mut chars = text.chars();
    chars.next().map_or_else(String::new, |c| c.to_uppercase().collect::<String>() + chars.as_str())
}

/// A number with 6 significant digits, plain where that reads well, scientific otherwise.
pub(super) fn number(x: f64) -> String {
    minus_sign(plain_or_scientific(x))
}

/// [`number`] with Rust's hyphen for a minus.
fn plain_or_scientific(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let magnitude = x.abs().log10().floor();
    if (-3.0..5.0).contains(&magnitude) {
        let decimals = (5.0 - magnitude) as usize;
        let text = format!("{x:.decimals$}");
        if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.').to_string() } else { text }
    } else {
        format!("{x:.5e}")
    }
}

/// A number in a sentence: 4 significant digits, plain from 1e-3 to 1e5, scientific otherwise.
pub fn short(x: f64) -> String {
    minus_sign(short_with_hyphen(x))
}

/// [`short`] with Rust's hyphen for a minus.
fn short_with_hyphen(x: f64) -> String {
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

/// A fitted exponent with `decimals` decimals, a fit's round-off (below half the last
/// decimal, which would print as ±0.000) written as 0.
pub fn exponent(x: f64, decimals: usize) -> String {
    if x.abs() < 0.5 * 10f64.powi(-(decimals as i32)) {
        format!("{:.decimals$}", 0.0)
    } else {
        minus_sign(format!("{x:.decimals$}"))
    }
}

/// How well a power law fits, in a sentence: its R² with `decimals` decimals (`R² = 0.9998`),
/// or `through 2 points`, which any line meets (R² = 1 by construction, no measure of the fit).
pub fn fit_quality(fit: &PowerLawFit, decimals: usize) -> String {
    fit.r_squared_measured()
        .map_or_else(|| format!("through {} points", fit.points), |r| format!("R² = {r:.decimals$}"))
}

/// [`fit_quality`] in a table's R² column: the R², or a dash and the point count through two.
pub fn fit_quality_cell(fit: &PowerLawFit, decimals: usize) -> String {
    fit.r_squared_measured().map_or_else(|| format!("– ({} points)", fit.points), |r| format!("{r:.decimals$}"))
}

/// A relative difference in per cent with its sign (`+4.577 %`).
pub fn percent(x: f64) -> String {
    format!("{} %", signed(100.0 * x))
}

/// `x` to 4 significant digits with its sign, + or − (a minus sign, not a hyphen): `+0.0017`.
pub fn signed(x: f64) -> String {
    format!("{}{}", if x < 0.0 { "−" } else { "+" }, short(x.abs()))
}

/// A number as [`number`] writes it, or a dash when there is none.
pub(super) fn optional(x: Option<f64>) -> String {
    x.map(number).unwrap_or_else(|| "–".into())
}

/// A relative error in scientific notation with its sign, or a dash when there is none.
pub(super) fn error(x: Option<f64>) -> String {
    x.map(|e| minus_sign(format!("{e:+.2e}"))).unwrap_or_else(|| "–".into())
}

/// An impulse in words: the kick's velocity or the top row's step force.
pub(super) fn impulse_words(i: &ImpulseSpec) -> String {
    match i.top_row_force {
        Some([fx, fy]) => format!("a step force ({}, {}) N on every top-row node", number(fx), number(fy)),
        None => format!("node {} kicked at ({}, {}) m/s", i.node, number(i.vx), number(i.vy)),
    }
}

/// `items` as a list in a sentence joined by `last` ("and", "or"): "a", "a and b", "a, b and c".
pub fn listed(items: &[String], last: &str) -> String {
    match items {
        [] => String::new(),
        [only] => only.clone(),
        [init @ .., tail] => format!("{} {last} {tail}", init.join(", ")),
    }
}

/// `n` with the words for one or for several: "1 agrees", "6 agree".
pub fn count(n: usize, one: &str, several: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { several })
}

/// `n` and its noun, plural with an s unless `n` is 1: "1 run", "6 runs".
pub fn counted(n: usize, noun: &str) -> String {
    count(n, noun, &format!("{noun}s"))
}

/// How many times more `ratio` is, in words: "12× faster" for 12, "1.2× faster" for 1.2 and,
/// below 1, the other way round: "1.3× slower" for 0.77 (a ratio written to no decimals read
/// "1× longer" for 1.16, and "0× faster" for a slower one).
pub fn times(ratio: f64, more: &str, less: &str) -> String {
    let (factor, word) = if ratio >= 1.0 { (ratio, more) } else { (ratio.recip(), less) };
    if factor >= 10.0 { format!("{factor:.0}× {word}") } else { format!("{factor:.1}× {word}") }
}

/// An integrator's name in prose, mid-sentence ("velocity Verlet", "RK4"); `verlet_as_one`
/// names both Verlet forms "Verlet", where an item counts them as one scheme: the same
/// trajectory in two forms (their errors agree to round-off), so one stands for both.
pub fn scheme(kind: IntegratorKind, verlet_as_one: bool) -> &'static str {
    match kind {
        IntegratorKind::PositionVerlet | IntegratorKind::VelocityVerlet if verlet_as_one => "Verlet",
        IntegratorKind::PositionVerlet => "position Verlet",
        IntegratorKind::VelocityVerlet => "velocity Verlet",
        IntegratorKind::SymplecticEuler => "symplectic Euler",
        IntegratorKind::Rk4 => "RK4",
        IntegratorKind::ForestRuth => "Forest–Ruth",
        IntegratorKind::Gear => "Gear",
    }
}

/// An order as an ordinal word: "second"; "7th" beyond the fifth.
pub fn ordinal(order: u32) -> String {
    match order {
        0..=5 => ["zeroth", "first", "second", "third", "fourth", "fifth"][order as usize].into(),
        n => format!("{n}th"),
    }
}
