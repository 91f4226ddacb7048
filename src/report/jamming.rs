//! The packings' jamming drawn (issue 34): one figure per packing scene of p, z − 4, K and G
//! against Δφ, and of G/K against z − 4, from the fits of `summary::jamming`; and the statistics
//! the item "Jamming" (`findings/jamming.rs`) judges its shares and shifts by.

use std::collections::BTreeMap;

use super::figure::{Figure, FigureKind, Part};
use crate::draw::chart::{Chart, Mark, Scale, Series, line_chart};
use crate::runner::RunRecord;
use crate::summary::jamming::{Onset, fitted, jammed, key, onsets_of, ratio_against_contacts, scalings, seed};

/// The packings of one N and contact law quenched at one area fraction.
pub(super) struct Quench {
    pub(super) fraction: f64,
    /// How many were quenched there, relaxed or not.
    pub(super) packings: usize,
    /// (seed, own φ_J) of those that relaxed and jammed.
    pub(super) onsets: Vec<(u64, f64)>,
}

impl Quench {
    /// Whether every packing quenched here jammed. A packing quenched at φ jams only where its
    /// own φ_J lies below φ, so where some did not, the own φ_J of those that did are the
    /// lower part of theirs, cut off from above at φ; where every one did, nothing is cut.
    pub(super) fn complete(&self) -> bool {
        self.onsets.len() == self.packings
    }
}

/// The packings of `n` discs with contact exponent `beta` among `system` (every quenched
/// packing, relaxed or not: one that did not relax is not known to jam), by quench fraction.
pub(super) fn quenches(system: &[&RunRecord], n: usize, beta: f64) -> Vec<Quench> {
    let mut by_fraction: BTreeMap<u64, Quench> = BTreeMap::new();
    for r in system.iter().filter(|r| r.spec.law.beta() == beta && key(r).is_some_and(|k| k.0 == n)) {
        let Some(fraction) = r.spec.packing().map(|p| p.fraction) else { continue };
        let quench = by_fraction.entry(fraction.to_bits()).or_insert(Quench { fraction, packings: 0, onsets: vec![] });
        quench.packings += 1;
        if let Some(phi_j) = r.metrics.packing.own_jamming_fraction.filter(|_| fitted(r) && jammed(r)) {
            quench.onsets.push((seed(r), phi_j));
        }
    }
    by_fraction.into_values().collect()
}

/// The two-sided p-value of Fisher's exact test that `a` of `m` and `b` of `n` are shares of
/// one rate: with the margins held, the hypergeometric probability of every split of the
/// a + b that is no more likely than the one observed, summed.
pub(super) fn fisher_exact((a, m): (usize, usize), (b, n): (usize, usize)) -> f64 {
    let ln_factorial = |k: usize| (2..=k).map(|i| (i as f64).ln()).sum::<f64>();
    let ln_choose = |n: usize, k: usize| ln_factorial(n) - ln_factorial(k) - ln_factorial(n - k);
    let hits = a + b;
    let probability = |x: usize| (ln_choose(m, x) + ln_choose(n, hits - x) - ln_choose(m + n, hits)).exp();
    let observed = probability(a);
    // Splits as likely as the observed one within round-off count as no more likely.
    let splits = hits.saturating_sub(n)..=hits.min(m);
    splits.map(probability).filter(|p| *p <= observed * (1.0 + 1e-7)).sum::<f64>().min(1.0)
}

/// Student's t that chance exceeds, of either sign, once in 20 at `dof` degrees of freedom:
/// a mean over few seeds whose standard error is estimated from the same seeds needs more than
/// 2 of it to differ from zero (12.7 from two seeds, 4.3 from three, 2.36 from eight).
pub(super) fn student_t(dof: usize) -> f64 {
    const TABLE: [f64; 30] = [
        12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131,
        2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042,
    ];
    match dof {
        0 => f64::INFINITY,
        1..=30 => TABLE[dof - 1],
        // Within 0.002 of the quantile above 30 (2.021 at 40, 2.000 at 60, 1.980 at 120).
        _ => 1.96 + 2.5 / dof as f64,
    }
}

/// The packing scene's figure: p, z − 4, K and G of its largest N's jammed packings against
/// Δφ on log–log axes (φ_J from the packings of the whole campaign with the scene's contact
/// law, [`onsets_of`]), each with its fitted power law; none without a φ_J.
pub(super) fn part(records: &[RunRecord], scene: &str) -> anyhow::Result<Part<()>> {
    let runs: Vec<&RunRecord> = records.iter().filter(|r| fitted(r)).collect();
    let mine: Vec<&RunRecord> = runs.iter().copied().filter(|r| r.spec.scene == scene).collect();
    let onsets = onsets_of(&runs, mine.first().map_or(1.0, |r| r.spec.law.beta()));
    let sizes = Onset::per_size(&onsets);
    let (Some(first), Some(size)) =
        (mine.first(), sizes.iter().rev().find(|s| mine.iter().any(|r| key(r).is_some_and(|k| k.0 == s.n))))
    else {
        return Ok(Part { figures: Vec::new(), rows: () });
    };
    let beta = first.spec.law.beta();
    let mut series = Vec::new();
    for s in scalings(&mine, size.n, beta, size.fit_floor()) {
        let mut xs: Vec<f64> = s.points.iter().map(|p| p.0).collect();
        xs.sort_by(f64::total_cmp);
        let line = xs.iter().map(|&x| (x, s.fit.prefactor * x.powf(s.fit.exponent))).collect();
        series.push(Series {
            label: format!("{}: packings, fit Δφ^{:.2} (theory {:.2})", s.quantity, s.fit.exponent, s.theory),
            points: s.points.clone(),
            mark: Mark::Fitted(line),
        });
    }
    let chart = Chart {
        title: format!("{scene}: p, z − 4, K and G against Δφ (N = {})", size.n),
        x_label: "Δφ = φ − φ_J".into(),
        y_label: "p, K, G (N/m); z − 4".into(),
        scale: Scale::LogLog,
    };
    let ratio = ratio_figure(scene, &mine, size.n, beta, size.fit_floor())?;
    let figure = Figure {
        scene: scene.into(),
        kind: FigureKind::Jamming,
        file: format!("plots/{scene}-jamming.svg"),
        caption: format!(
            "{scene}: pressure p, excess coordination z − 4 and moduli K, G of the jammed packings of {} discs \
             against Δφ = φ − φ_J (φ_J each packing's own, where its pressure vanishes as it is decompressed), \
             over Δφ ≥ {}, on log–log axes with fitted power laws.",
            size.n,
            crate::report::words::short(size.fit_floor())
        ),
        image: line_chart(&chart, &series)?,
    };
    Ok(Part { figures: std::iter::once(figure).chain(ratio).collect(), rows: () })
}

/// The scene's G/K against z − 4 for its `n` discs on log–log axes with the fitted power law
/// beside the theory's Δz¹ ([`ratio_against_contacts`]); none without packings to fit.
fn ratio_figure(scene: &str, mine: &[&RunRecord], n: usize, beta: f64, floor: f64) -> anyhow::Result<Option<Figure>> {
    let Some(s) = ratio_against_contacts(mine, n, beta, floor) else { return Ok(None) };
    let (low, high) = s.points.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), p| (lo.min(p.0), hi.max(p.0)));
    let line = |exponent: f64, prefactor: f64| {
        vec![(low, prefactor * low.powf(exponent)), (high, prefactor * high.powf(exponent))]
    };
    // The theory's line through the packings' geometric mean, so only its slope compares.
    let (mean_x, mean_y) = s.points.iter().fold((0.0, 0.0), |(x, y), p| (x + p.0.ln(), y + p.1.ln()));
    let count = s.points.len() as f64;
    let through_mean = (mean_y / count - s.theory * mean_x / count).exp();
    let series = vec![
        Series { label: "packings".into(), points: s.points.clone(), mark: Mark::Markers },
        Series {
            label: format!("fit Δz^{:.2}", s.fit.exponent),
            points: line(s.fit.exponent, s.fit.prefactor),
            mark: Mark::Line,
        },
        Series { label: format!("theory Δz^{:.0}", s.theory), points: line(s.theory, through_mean), mark: Mark::Line },
    ];
    let chart = Chart {
        title: format!("{scene}: G/K against z − 4 (N = {n})"),
        x_label: "Δz = z − 4".into(),
        y_label: "G/K".into(),
        scale: Scale::LogLog,
    };
    Ok(Some(Figure {
        scene: scene.into(),
        kind: FigureKind::JammingRatio,
        file: format!("plots/{scene}-ratio.svg"),
        caption: format!(
            "{scene}: G/K of the jammed packings of {n} discs against their excess coordination Δz = z − 4 \
             (rattlers removed), over Δφ ≥ {}, on log–log axes, with the fitted power law and the theory's \
             G/K ∝ Δz (its line drawn through the packings' geometric mean: only the slopes compare).",
            crate::report::words::short(floor)
        ),
        image: line_chart(&chart, &series)?,
    }))
}
