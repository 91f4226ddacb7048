//! One metric of one scene in numbers, over the joined rows `ok` on both sides: the medians of
//! A, of B and of their ratios, and whether the two sides differ beyond the metric's noise.

use super::join::SceneRows;
use super::quantity::{Class, NOISE, class};
use crate::measure::median;

/// One metric of one scene in numbers, over the rows `ok` on both sides.
pub(super) struct Stats {
    pub(super) metric: String,
    pub(super) class: Class,
    /// The medians of A and of B (each run once) and of the rows' ratios B/A.
    pub(super) a: Option<f64>,
    pub(super) b: Option<f64>,
    pub(super) ratio: Option<f64>,
    /// The smallest and the largest ratio, where there are several.
    pub(super) range: Option<(f64, f64)>,
    pub(super) ratios: usize,
    /// Some row's two values differ beyond that row's noise ([`row_noise`]).
    pub(super) differs: bool,
    /// The largest noise of the rows: relative, absolute for a [`Class::Deviation`].
    pub(super) noise: f64,
    /// One side's values take both signs (a wall force through ΔW = 0): their medians say little.
    pub(super) signed: bool,
}

/// The medians of metric `name` on each side and of their ratio over the rows `both` ended
/// `ok` on, and whether the sides differ; `None` when neither side has a value there.
pub(super) fn stats(rows: &SceneRows, both: &[usize], name: &str) -> Option<Stats> {
    let with_ratio: Vec<usize> =
        both.iter().copied().filter(|&r| rows.metric(name, "ratio").number(r).is_some()).collect();
    // A and B over the rows behind the ratios, so that the three agree; where there is no
    // ratio (a value of zero or missing on one side), over every row ok on both sides.
    let basis = if with_ratio.is_empty() { both } else { &with_ratio };
    let values = |side: &str| -> Vec<f64> {
        rows.once(side, basis).into_iter().filter_map(|r| rows.metric(name, side).number(r)).collect()
    };
    let (va, vb) = (values("a"), values("b"));
    if va.is_empty() && vb.is_empty() {
        return None;
    }
    let ratios: Vec<f64> = with_ratio.iter().filter_map(|&r| rows.metric(name, "ratio").number(r)).collect();
    let (lo, hi) = crate::measure::extremes(&ratios);
    let class = class(name);
    let signed = [&va, &vb].iter().any(|v| v.iter().any(|&x| x < 0.0) && v.iter().any(|&x| x > 0.0));
    let pair = |r: usize| (rows.metric(name, "a").number(r), rows.metric(name, "b").number(r));
    let noise = both.iter().map(|&r| row_noise(rows, name, r)).fold(NOISE, f64::max);
    Some(Stats {
        metric: name.to_string(),
        class,
        a: median(va),
        b: median(vb),
        range: (ratios.len() > 1).then_some((lo, hi)),
        ratios: ratios.len(),
        ratio: median(ratios),
        differs: both.iter().any(|&r| {
            let ratio = rows.metric(name, "ratio").number(r);
            differs(class, pair(r), ratio, row_noise(rows, name, r))
        }),
        noise,
        signed,
    })
}

/// The noise of metric `name` in row `r`, relative: [`NOISE`], or more where a run measures its
/// own error: the relative error against the analytical value (`<name>_error`) and the
/// difference of MD from the static answer of the same network (`<name>_fem`), on either side.
fn row_noise(rows: &SceneRows, name: &str, r: usize) -> f64 {
    let own = |side: &str| {
        let number = |column: String| rows.column(&column).and_then(|c| c.number(r));
        let error = number(format!("{name}_error_{side}")).map(f64::abs);
        let fem = number(format!("{name}_fem_{side}")).filter(|&f| f != 0.0);
        let md = rows.metric(name, side).number(r);
        [error, md.zip(fem).map(|(md, fem)| (md / fem - 1.0).abs())]
    };
    own("a").into_iter().chain(own("b")).flatten().fold(NOISE, f64::max)
}

/// The values `(a, b)` of one row differ: inputs and costs when they are not the same number,
/// a deviation by more than [`NOISE`], a result by a ratio further from 1 than `noise` (or, with
/// no ratio, when A is 0 and B is not).
fn differs(class: Class, (a, b): (Option<f64>, Option<f64>), ratio: Option<f64>, noise: f64) -> bool {
    let (Some(a), Some(b)) = (a, b) else { return false };
    match class {
        Class::Cost | Class::Setup => a != b,
        Class::Deviation => (b - a).abs() > NOISE,
        Class::Result => ratio.map_or(a != b, |ratio| (ratio - 1.0).abs() > noise),
    }
}
