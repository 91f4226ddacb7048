//! One metric of one scene in numbers, over the joined rows that compare like with like: the
//! medians of A, of B and of their ratios, and whether the two sides differ beyond the metric's
//! noise: a row's own error, or, where the scene varies the seed on both sides, the spread
//! between the seeds.

use super::join::SceneRows;
use super::quantity::{Class, NOISE, ROUND_OFF, class};
use crate::measure::median;

/// Two sides whose seed means differ by less than this many standard errors of their
/// difference are the same within the seeds' spread: the jamming item judges φ_J at two.
pub(super) const SEED_ERRORS: f64 = 2.0;

/// One metric of one scene in numbers, over the rows that compare like with like.
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
    /// The two sides differ beyond their noise ([`Verdict`]).
    pub(super) differs: bool,
    /// The largest noise of the rows: relative, absolute for a [`Class::Deviation`].
    pub(super) noise: f64,
    /// The noise is the spread between the seeds.
    pub(super) seeded: bool,
    /// Compared in some row, but judged in none: every group of its packings' seeds had some
    /// that did not jam ([`SceneRows::every_seed_comparable`]), so it neither differs nor agrees.
    pub(super) unjudged: bool,
    /// One side's values take both signs (a wall force through ΔW = 0): their medians say little.
    pub(super) signed: bool,
    /// Rows compared: on both sides, measured alike.
    pub(super) compared: usize,
    /// How A and B measured the metric where they measured it differently (those rows are not
    /// compared).
    pub(super) unlike: Option<(String, String)>,
    /// Every value compared is at or below its floor, on both sides: round-off on both.
    pub(super) at_floor: bool,
}

/// The medians of metric `name` on each side and of their ratio over the rows `both` (that
/// compare like with like) where the two sides measured it alike, and whether the sides
/// differ; `None` when neither side has a value there.
pub(super) fn stats(rows: &SceneRows, both: &[usize], name: &str) -> Option<Stats> {
    let alike: Vec<usize> = both.iter().copied().filter(|&r| rows.unlike(name, r).is_none()).collect();
    let unlike = both.iter().find_map(|&r| rows.unlike(name, r));
    let with_ratio: Vec<usize> = alike.iter().copied().filter(|&r| rows.ratio(name, r).is_some()).collect();
    // A and B over the rows behind the ratios, so that the three agree; where there is no
    // ratio (a value of zero or missing on one side), over every row compared, and where the
    // two sides measured it differently everywhere, over those rows, for the record.
    let basis = [&with_ratio[..], &alike, both].into_iter().find(|b| !b.is_empty()).unwrap_or(both);
    let values = |side: &str| -> Vec<f64> {
        rows.once(side, basis).into_iter().filter_map(|r| rows.metric(name, side).number(r)).collect()
    };
    let (va, vb) = (values("a"), values("b"));
    if va.is_empty() && vb.is_empty() {
        return None;
    }
    let ratios: Vec<f64> = with_ratio.iter().filter_map(|&r| rows.ratio(name, r)).collect();
    let (lo, hi) = crate::measure::extremes(&ratios);
    let class = class(name);
    let verdict = Verdict::of(rows, &alike, name, class);
    let on_both = |r: &usize| rows.metric(name, "a").number(*r).zip(rows.metric(name, "b").number(*r)).is_some();
    let compared: Vec<usize> = alike.iter().copied().filter(on_both).collect();
    Some(Stats {
        metric: name.to_string(),
        class,
        signed: [&va, &vb].iter().any(|v| v.iter().any(|&x| x < 0.0) && v.iter().any(|&x| x > 0.0)),
        a: median(va),
        b: median(vb),
        range: (ratios.len() > 1).then_some((lo, hi)),
        ratios: ratios.len(),
        ratio: median(ratios),
        differs: verdict.differs,
        noise: verdict.noise,
        seeded: verdict.seeded,
        unjudged: !verdict.judged,
        at_floor: !compared.is_empty()
            && compared.iter().all(|&r| rows.at_floor(name, "a", r) && rows.at_floor(name, "b", r)),
        compared: compared.len(),
        unlike,
    })
}

/// Whether the two sides of a metric differ, and the noise they were judged by.
struct Verdict {
    differs: bool,
    noise: f64,
    seeded: bool,
    /// Some row or group of seeds was judged: not so where every group was left out.
    judged: bool,
}

impl Verdict {
    /// A result of a scene that varies the seed on both sides is judged group by group (rows
    /// that differ only by their seed) on the seeds' means, against their spread
    /// ([`seed_verdict`]), where every seed of the group compares like with like
    /// ([`SceneRows::every_seed_comparable`]); every other row on its own ([`differs`]).
    fn of(rows: &SceneRows, alike: &[usize], name: &str, class: Class) -> Verdict {
        let mut verdict = Verdict { differs: false, noise: NOISE, seeded: false, judged: false };
        let mut single = Vec::new();
        for group in replicates(rows, alike) {
            let seeded = class == Class::Result && rows.seeded();
            if seeded && !rows.every_seed_comparable(group[0]) {
                continue;
            }
            match seeded.then(|| seed_verdict(rows, &group, name)).flatten() {
                Some((differs, noise)) => {
                    verdict.differs |= differs;
                    verdict.noise = verdict.noise.max(noise);
                    (verdict.seeded, verdict.judged) = (true, true);
                }
                None => single.extend(group),
            }
        }
        for r in single {
            verdict.judged = true;
            let noise = row_noise(rows, name, r);
            let pair = (rows.value(name, "a", r), rows.value(name, "b", r));
            verdict.differs |= differs(class, pair, rows.ratio(name, r), noise);
            verdict.noise = verdict.noise.max(noise);
        }
        verdict
    }
}

/// `alike` in groups of rows that share every join key but the seed, in order of appearance.
fn replicates(rows: &SceneRows, alike: &[usize]) -> Vec<Vec<usize>> {
    let mut groups: Vec<(Vec<Option<String>>, Vec<usize>)> = Vec::new();
    for &r in alike {
        let key = rows.replicate_key(r);
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, members)) => members.push(r),
            None => groups.push((key, vec![r])),
        }
    }
    groups.into_iter().map(|(_, members)| members).collect()
}

/// Whether the seeds' means of metric `name` over `group` (rows that differ only by their seed)
/// differ on the two sides by more than [`SEED_ERRORS`] standard errors of their difference,
/// √(s_A²/n_A + s_B²/n_B) over the n runs of each side, or than the rows' own noise; with that
/// noise relative to A's mean. `None` with fewer than two runs on a side: no spread to judge by.
fn seed_verdict(rows: &SceneRows, group: &[usize], name: &str) -> Option<(bool, f64)> {
    let spread = |side: &str| -> Option<(f64, f64)> {
        let values: Vec<f64> = rows.once(side, group).iter().filter_map(|&r| rows.value(name, side, r)).collect();
        let n = values.len() as f64;
        (values.len() >= 2).then(|| {
            let mean = values.iter().sum::<f64>() / n;
            (mean, values.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0) / n)
        })
    };
    let ((mean_a, var_a), (mean_b, var_b)) = (spread("a")?, spread("b")?);
    let own = group.iter().map(|&r| row_noise(rows, name, r)).fold(NOISE, f64::max) * mean_a.abs();
    let threshold = (SEED_ERRORS * (var_a + var_b).sqrt()).max(own);
    let relative = if mean_a == 0.0 { threshold } else { threshold / mean_a.abs() };
    Some(((mean_b - mean_a).abs() > threshold, relative))
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

/// The values `(a, b)` of one row (0 at their floor) differ: inputs and costs beyond round-off
/// ([`ROUND_OFF`]: one input resolved along two paths differs in its last bits), a deviation by
/// more than [`NOISE`], a result by a ratio further from 1 than `noise` (or, with no ratio,
/// when A is 0 and B is not).
fn differs(class: Class, (a, b): (Option<f64>, Option<f64>), ratio: Option<f64>, noise: f64) -> bool {
    let (Some(a), Some(b)) = (a, b) else { return false };
    match class {
        Class::Cost | Class::Setup => (b - a).abs() > ROUND_OFF * a.abs().max(b.abs()),
        Class::Deviation => (b - a).abs() > NOISE,
        Class::Result => ratio.map_or(a != b, |ratio| (ratio - 1.0).abs() > noise),
    }
}
