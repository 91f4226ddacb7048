//! The packings' jamming (issue 34): φ_J of each (N, seed), the mean of its packings' own (per
//! law), its mean and standard error per N, Δφ = φ − φ_J of every packing from its own φ_J, and
//! the scalings of p, z − 4, K
//! and G against Δφ fitted on log–log axes and drawn, one figure per packing scene. The report's
//! item "Jamming" (`findings/jamming.rs`) states them against the literature.

use std::collections::BTreeMap;

use super::figure::{Figure, FigureKind, Part};
use crate::draw::chart::{Chart, Mark, Scale, Series, line_chart};
use crate::measure::{PowerLawFit, power_law_fit};
use crate::report::solids::mean_spread;
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::study::packing::ONSET_PRECISION;

/// z at jamming in 2D: isostatic, 2d contacts per disc.
pub(super) const ISOSTATIC: f64 = 4.0;

/// The scalings are fitted from Δφ ≥ this many times the precision of a packing's own φ_J.
pub(super) const FIT_FLOOR: f64 = 5.0;

/// A packing's value, if measured.
type Pick = fn(&RunRecord) -> Option<f64>;

/// A theory's exponent as a function of the contact law's β.
type Exponent = fn(f64) -> f64;

/// The scalings near jamming for contact forces ∝ δ^β (δ ∝ Δφ): name, value and the theory's
/// exponent as a function of β: p ∝ δ^β, z − 4 ∝ Δφ^½ (geometry), K ∝ k_t ∝ δ^(β−1) and
/// G ∝ K Δz ∝ Δφ^(β−½); linear (β = 1): 1, ½, 0, ½; Hertz (β = 3/2): 3/2, ½, ½, 1.
const SCALINGS: [(&str, Pick, Exponent); 4] = [
    ("p", |r| r.metrics.packing.pressure, |beta| beta),
    ("z − 4", |r| r.metrics.packing.coordination.map(|z| z - ISOSTATIC), |_| 0.5),
    ("K", |r| r.metrics.packing.bulk_modulus_2d, |beta| beta - 1.0),
    ("G", |r| r.metrics.packing.shear_modulus_2d, |beta| beta - 0.5),
];

/// The packing's (N, seed): its φ_J's key.
pub(super) fn key(r: &RunRecord) -> Option<(usize, u64)> {
    r.spec.packing().map(|p| (p.n, p.seed))
}

/// The packing's seed (0 for a run that is not a packing).
pub(super) fn seed(r: &RunRecord) -> u64 {
    key(r).map_or(0, |k| k.1)
}

/// Whether the packing jammed (relaxed, p above its floor, carried by a rigid backbone).
pub(super) fn jammed(r: &RunRecord) -> bool {
    r.metrics.packing.packing_state.as_deref() == Some("jammed")
}

/// A packing the fits are made over: one quenched from random positions at its fraction (O'Hern
/// et al.'s protocol; a slowly compressed one followed another path to its state), relaxed for
/// its own sake (a movie's run is made for its picture and may repeat one of the grid's).
pub(crate) fn fitted(r: &RunRecord) -> bool {
    let quenched = r.spec.packing().is_some_and(|p| p.compression.is_none());
    r.status == RunStatus::Ok && quenched && r.spec.movie.is_none()
}

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

/// φ_J of every (N, seed) from its jammed packings of contact law β (forces ∝ δ^β): the mean of
/// their own φ_J, each where its pressure vanishes as it is decompressed (`own_jamming_fraction`,
/// O'Hern et al.'s jamming point of one state). The packings of a seed are quenches from one
/// random start at different φ, each jamming at its own φ_J; their mean is the seed's, and the
/// seed the independent sample of [`Onset::per_size`].
pub(super) fn onsets_of(runs: &[&RunRecord], beta: f64) -> BTreeMap<(usize, u64), f64> {
    let mut own: BTreeMap<(usize, u64), Vec<f64>> = BTreeMap::new();
    for r in runs.iter().filter(|r| r.spec.law.beta() == beta && jammed(r)) {
        if let (Some(k), Some(phi_j)) = (key(r), r.metrics.packing.own_jamming_fraction) {
            own.entry(k).or_default().push(phi_j);
        }
    }
    own.into_iter().map(|(k, phis)| (k, phis.iter().sum::<f64>() / phis.len() as f64)).collect()
}

/// Δφ = φ − φ_J of a packing from its own φ_J, when positive.
pub(super) fn excess(r: &RunRecord) -> Option<f64> {
    let m = &r.metrics.packing;
    Some(m.packing_fraction? - m.own_jamming_fraction?).filter(|d| *d > 0.0)
}

/// The campaign's φ_J of one N: mean and standard error over its seeds, and how it stands.
pub(super) struct Onset {
    pub(super) n: usize,
    pub(super) seeds: usize,
    pub(super) mean: f64,
    /// The standard error of the mean (0 with one seed).
    pub(super) error: f64,
}

impl Onset {
    /// φ_J of every N, by rising N.
    pub(super) fn per_size(onsets: &BTreeMap<(usize, u64), f64>) -> Vec<Onset> {
        let mut sizes: BTreeMap<usize, Vec<f64>> = BTreeMap::new();
        for (&(n, _), &phi) in onsets {
            sizes.entry(n).or_default().push(phi);
        }
        sizes
            .into_iter()
            .map(|(n, phis)| {
                let (mean, spread) = mean_spread(phis.iter().map(|p| Some(*p)));
                // Seeds that relaxed to one state (two discs in a box find the same) differ by
                // round-off only: no spread to speak of.
                let spread = spread.filter(|s| *s > ROUND_OFF_SPREAD * mean.unwrap_or(0.0).abs());
                let error = spread.unwrap_or(0.0) / (phis.len() as f64).sqrt();
                Onset { n, seeds: phis.len(), mean: mean.unwrap_or(f64::NAN), error }
            })
            .collect()
    }

    /// The smallest Δφ the scalings are fitted from: each packing's own φ_J is known to
    /// [`ONSET_PRECISION`] of φ, so Δφ ≥ `FIT_FLOOR` times that keeps its error of ln Δφ below
    /// ln(1 + 1/`FIT_FLOOR`) ≈ 0.18.
    pub(super) fn fit_floor(&self) -> f64 {
        FIT_FLOOR * ONSET_PRECISION * self.mean
    }
}

/// A spread of the seeds' φ_J below this fraction of their mean is round-off: the seeds relaxed
/// to one state (relaxed positions are known to ~1e-9 of a disc; φ_J to 5e-5).
const ROUND_OFF_SPREAD: f64 = 1e-9;

/// One fitted scaling: quantity, its fit against Δφ, the theory's exponent and the points
/// (Δφ, value) fitted.
pub(super) struct Scaling {
    pub(super) quantity: &'static str,
    pub(super) fit: PowerLawFit,
    pub(super) theory: f64,
    pub(super) points: Vec<(f64, f64)>,
    /// Packings left out of the log–log fit because their value is not positive (a jammed
    /// packing near φ_J may have G ≤ 0: unstable to shear in its fixed box).
    pub(super) not_positive: usize,
    /// The exponent's standard error over the seeds ([`seed_jackknife`]); `None` with fewer
    /// than three seeds.
    pub(super) error: Option<f64>,
    /// The seed of each point's packing, for a jackknife of another estimate over the same points.
    pub(super) seeds: Vec<u64>,
}

impl Scaling {
    /// The standard error over the seeds of how far the exponent moves when refitted over the
    /// points with Δφ ≤ `ceiling` alone. Both fits hold the points below the ceiling, so their
    /// errors are not independent and the shift's is not theirs added: the shift itself is
    /// jackknifed ([`seed_jackknife_of`]). `None` with fewer than [`JACKKNIFE_SEEDS`] seeds.
    pub(super) fn shift_error(&self, ceiling: f64) -> Option<f64> {
        seed_jackknife_of(&self.points, &self.seeds, |kept| {
            let lower: Vec<(f64, f64)> = kept.iter().copied().filter(|p| p.0 <= ceiling).collect();
            Some(power_law_fit(&lower)?.exponent - power_law_fit(kept)?.exponent)
        })
    }
}

/// Fewest seeds a jackknife error is given for: with two, each leave-one-out fit is one seed's.
pub(super) const JACKKNIFE_SEEDS: usize = 3;

/// The standard error of the exponent fitted over `points` whose packings came from `seeds`
/// (one per point), by the jackknife over seeds ([`seed_jackknife_of`]).
fn seed_jackknife(points: &[(f64, f64)], seeds: &[u64]) -> Option<f64> {
    seed_jackknife_of(points, seeds, |kept| power_law_fit(kept).map(|fit| fit.exponent))
}

/// The standard error of `estimate` over `points` whose packings came from `seeds` (one per
/// point), by the jackknife over seeds: a seed's packings share its random start, so the seed,
/// not the packing, is the independent sample. With x₍ᵢ₎ the estimate without seed i's points
/// and x̄ their mean over the S seeds, SE = √((S − 1)/S · Σ (x₍ᵢ₎ − x̄)²). `None` with fewer
/// than [`JACKKNIFE_SEEDS`] seeds.
pub(super) fn seed_jackknife_of(
    points: &[(f64, f64)],
    seeds: &[u64],
    estimate: impl Fn(&[(f64, f64)]) -> Option<f64>,
) -> Option<f64> {
    let mut distinct = seeds.to_vec();
    distinct.sort_unstable();
    distinct.dedup();
    if distinct.len() < JACKKNIFE_SEEDS {
        return None;
    }
    let without = |left_out: u64| {
        let kept: Vec<(f64, f64)> =
            points.iter().zip(seeds).filter(|(_, s)| **s != left_out).map(|(p, _)| *p).collect();
        estimate(&kept)
    };
    let estimates: Vec<f64> = distinct.iter().map(|&s| without(s)).collect::<Option<_>>()?;
    let count = estimates.len() as f64;
    let mean = estimates.iter().sum::<f64>() / count;
    Some(((count - 1.0) / count * estimates.iter().map(|x| (x - mean).powi(2)).sum::<f64>()).sqrt())
}

/// The jammed packings of `n` discs with contact exponent `beta` whose Δφ = φ − φ_J lies in
/// `window` (floor and ceiling, both included), each with its Δφ: what the scalings are fitted
/// over.
fn fitted_packings<'a>(
    runs: &[&'a RunRecord],
    (n, beta): (usize, f64),
    window: (f64, f64),
) -> Vec<(f64, &'a RunRecord)> {
    runs.iter()
        .filter(|r| jammed(r) && r.spec.law.beta() == beta && key(r).is_some_and(|k| k.0 == n))
        .filter_map(|r| Some((excess(r).filter(|d| (window.0..=window.1).contains(d))?, *r)))
        .collect()
}

/// The scalings of the jammed packings of `n` discs with contact exponent `beta`, each fitted
/// on log–log axes against Δφ over the packings with Δφ ≥ `floor` and a positive value.
pub(super) fn scalings(runs: &[&RunRecord], n: usize, beta: f64, floor: f64) -> Vec<Scaling> {
    scalings_over(runs, n, beta, (floor, f64::INFINITY))
}

/// [`scalings`] over the packings whose Δφ lies in `window` (floor and ceiling).
pub(super) fn scalings_over(runs: &[&RunRecord], n: usize, beta: f64, window: (f64, f64)) -> Vec<Scaling> {
    let mine = fitted_packings(runs, (n, beta), window);
    SCALINGS
        .iter()
        .filter_map(|&(quantity, pick, theory)| {
            let (points, seeds): (Vec<(f64, f64)>, Vec<u64>) =
                mine.iter().filter_map(|&(d, r)| Some(((d, pick(r).filter(|y| *y > 0.0)?), seed(r)))).unzip();
            let not_positive = mine.iter().filter(|(_, r)| pick(r).is_some_and(|y| y <= 0.0)).count();
            let fit = power_law_fit(&points)?;
            let error = seed_jackknife(&points, &seeds);
            Some(Scaling { quantity, fit, theory: theory(beta), points, not_positive, error, seeds })
        })
        .collect()
}

/// G/K of the jammed packings of `n` discs with contact exponent `beta` against their excess
/// coordination Δz = z − 4, fitted on log–log axes over the packings with Δφ ≥ `floor`: the
/// theory's G ∝ K Δz makes it Δz¹ for every contact law (the shear modulus is the bulk
/// modulus thinned by how far the contact network is above isostatic).
pub(super) fn ratio_against_contacts(runs: &[&RunRecord], n: usize, beta: f64, floor: f64) -> Option<Scaling> {
    let (points, seeds): (Vec<(f64, f64)>, Vec<u64>) = fitted_packings(runs, (n, beta), (floor, f64::INFINITY))
        .into_iter()
        .filter_map(|(_, r)| {
            let m = &r.metrics.packing;
            let dz = m.coordination? - ISOSTATIC;
            let ratio = m.shear_modulus_2d? / m.bulk_modulus_2d?;
            (dz > 0.0 && ratio > 0.0).then_some(((dz, ratio), seed(r)))
        })
        .unzip();
    let fit = power_law_fit(&points)?;
    let error = seed_jackknife(&points, &seeds);
    Some(Scaling { quantity: "G/K against z − 4", fit, theory: 1.0, points, not_positive: 0, error, seeds })
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
