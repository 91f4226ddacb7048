//! The packings' jamming (issue 34), computed once from the records for `summary.csv` and the
//! report: φ_J of each (N, seed), the mean of its packings' own (per law), its mean and standard
//! error per N, Δφ = φ − φ_J of every packing from its own φ_J, and the scalings of p, z − 4, K
//! and G against Δφ (and G/K against z − 4) fitted on log–log axes. The report draws them
//! (`report::jamming`) and states them against the literature (`report::findings::jamming`).

use std::collections::BTreeMap;

use super::ScalingFit;
use crate::measure::{PowerLawFit, mean_spread, power_law_fit, sorted_distinct};
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::study::packing::ONSET_PRECISION;

/// z at jamming in 2D: isostatic, 2d contacts per disc.
pub(crate) const ISOSTATIC: f64 = 4.0;

/// The scalings are fitted from Δφ ≥ this many times the precision of a packing's own φ_J.
pub(crate) const FIT_FLOOR: f64 = 5.0;

/// The tolerance of a fitted exponent against the theory's (judged on the largest N only):
/// Δφ of the smallest fitted point is uncertain by up to 1/`FIT_FLOOR` of itself (ln 1.2 ≈
/// 0.18), which over a fitted range of ln(0.08/0.004) ≈ 3 moves a slope by up to ≈ 0.06; the
/// tolerance allows as much again for the corrections to scaling away from Δφ → 0, which the
/// theory's exponents leave out.
pub const EXPONENT_TOLERANCE: f64 = 0.15;

/// Whether a `summary.csv` fit against `against` is a packing's scaling near jamming.
pub fn is_fitted_against(against: &str) -> bool {
    against == AGAINST_FRACTION || against == AGAINST_CONTACTS
}

/// A packing's value, if measured.
type Pick = fn(&RunRecord) -> Option<f64>;

/// A scaling near jamming: its symbol in the report, its name in `summary.csv`, the packing's
/// value and the theory's exponent as a function of the contact law's β.
struct Quantity {
    symbol: &'static str,
    column: &'static str,
    pick: Pick,
    theory: fn(f64) -> f64,
}

/// What the packings' scalings are fitted against in `summary.csv`: Δφ = φ − φ_J, each packing's
/// own φ_J.
pub const AGAINST_FRACTION: &str = "fraction_excess";

/// What G/K is fitted against in `summary.csv`: Δz = z − 4 (rattlers removed).
pub const AGAINST_CONTACTS: &str = "coordination_excess";

/// G/K's name in `summary.csv`.
const RATIO: &str = "shear_over_bulk";

/// The scalings near jamming for contact forces ∝ δ^β (δ ∝ Δφ), each with the theory's exponent
/// as a function of β: p ∝ δ^β, z − 4 ∝ Δφ^½ (geometry), K ∝ k_t ∝ δ^(β−1) and
/// G ∝ K Δz ∝ Δφ^(β−½); linear (β = 1): 1, ½, 0, ½; Hertz (β = 3/2): 3/2, ½, ½, 1.
const QUANTITIES: [Quantity; 4] = [
    Quantity { symbol: "p", column: "pressure", pick: |r| r.metrics.packing.pressure, theory: |beta| beta },
    Quantity {
        symbol: "z − 4",
        column: AGAINST_CONTACTS,
        pick: |r| r.metrics.packing.coordination.map(|z| z - ISOSTATIC),
        theory: |_| 0.5,
    },
    Quantity {
        symbol: "K",
        column: "bulk_modulus_2d",
        pick: |r| r.metrics.packing.bulk_modulus_2d,
        theory: |beta| beta - 1.0,
    },
    Quantity {
        symbol: "G",
        column: "shear_modulus_2d",
        pick: |r| r.metrics.packing.shear_modulus_2d,
        theory: |beta| beta - 0.5,
    },
];

/// The exponent the theory predicts for a packing's `quantity` (its `summary.csv` name) fitted
/// against `against` with contact forces ∝ δ^β, and the formula in β: [`QUANTITIES`] against
/// Δφ, and G/K ∝ Δz¹ for every law.
pub fn predicted(quantity: &str, against: &str, beta: f64) -> Option<(f64, &'static str)> {
    const FORMULAS: [&str; 4] = ["β", "½", "β−1", "β−½"];
    match against {
        AGAINST_FRACTION => QUANTITIES
            .iter()
            .zip(FORMULAS)
            .find(|(q, _)| q.column == quantity)
            .map(|(q, formula)| ((q.theory)(beta), formula)),
        AGAINST_CONTACTS if quantity == RATIO => Some((1.0, "1")),
        _ => None,
    }
}

/// The packing's (N, seed): its φ_J's key.
pub(crate) fn key(r: &RunRecord) -> Option<(usize, u64)> {
    r.spec.packing().map(|p| (p.n, p.seed))
}

/// The packing's seed (0 for a run that is not a packing).
pub(crate) fn seed(r: &RunRecord) -> u64 {
    key(r).map_or(0, |k| k.1)
}

/// Whether the packing jammed (relaxed, p above its floor, carried by a rigid backbone).
pub(crate) fn jammed(r: &RunRecord) -> bool {
    r.metrics.packing.packing_state.as_deref() == Some("jammed")
}

/// A packing the fits are made over: one quenched from random positions at its fraction (O'Hern
/// et al.'s protocol; a slowly compressed one followed another path to its state), relaxed for
/// its own sake (a movie's run is made for its picture and may repeat one of the grid's).
pub(crate) fn fitted(r: &RunRecord) -> bool {
    let quenched = r.spec.packing().is_some_and(|p| p.compression.is_none());
    r.status == RunStatus::Ok && quenched && r.spec.movie.is_none()
}

/// φ_J of every (N, seed) from its jammed packings of contact law β (forces ∝ δ^β): the mean of
/// their own φ_J, each where its pressure vanishes as it is decompressed (`own_jamming_fraction`,
/// O'Hern et al.'s jamming point of one state). The packings of a seed are quenches from one
/// random start at different φ, each jamming at its own φ_J; their mean is the seed's, and the
/// seed the independent sample of [`Onset::per_size`].
pub(crate) fn onsets_of(runs: &[&RunRecord], beta: f64) -> BTreeMap<(usize, u64), f64> {
    let mut own: BTreeMap<(usize, u64), Vec<f64>> = BTreeMap::new();
    for r in runs.iter().filter(|r| r.spec.law.beta() == beta && jammed(r)) {
        if let (Some(k), Some(phi_j)) = (key(r), r.metrics.packing.own_jamming_fraction) {
            own.entry(k).or_default().push(phi_j);
        }
    }
    own.into_iter().map(|(k, phis)| (k, phis.iter().sum::<f64>() / phis.len() as f64)).collect()
}

/// Δφ = φ − φ_J of a packing from its own φ_J, when positive.
pub(crate) fn excess(r: &RunRecord) -> Option<f64> {
    let m = &r.metrics.packing;
    Some(m.packing_fraction? - m.own_jamming_fraction?).filter(|d| *d > 0.0)
}

/// The campaign's φ_J of one N: mean and standard error over its seeds, and how it stands.
pub(crate) struct Onset {
    pub(crate) n: usize,
    pub(crate) seeds: usize,
    pub(crate) mean: f64,
    /// The standard error of the mean (0 with one seed).
    pub(crate) error: f64,
}

impl Onset {
    /// φ_J of every N, by rising N.
    pub(crate) fn per_size(onsets: &BTreeMap<(usize, u64), f64>) -> Vec<Onset> {
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
    pub(crate) fn fit_floor(&self) -> f64 {
        FIT_FLOOR * ONSET_PRECISION * self.mean
    }
}

/// A spread of the seeds' φ_J below this fraction of their mean is round-off: the seeds relaxed
/// to one state (relaxed positions are known to ~1e-9 of a disc; φ_J to 5e-5).
const ROUND_OFF_SPREAD: f64 = 1e-9;

/// One fitted scaling: quantity, its fit against Δφ, the theory's exponent and the points
/// (Δφ, value) fitted.
pub(crate) struct Scaling {
    /// Its symbol in the report (`p`, `G/K against z − 4`).
    pub(crate) quantity: &'static str,
    /// Its name in `summary.csv` and what it is fitted against there.
    column: (&'static str, &'static str),
    pub(crate) fit: PowerLawFit,
    pub(crate) theory: f64,
    pub(crate) points: Vec<(f64, f64)>,
    /// Packings left out of the log–log fit because their value is not positive (a jammed
    /// packing near φ_J may have G ≤ 0: unstable to shear in its fixed box).
    pub(crate) not_positive: usize,
    /// The exponent's standard error over the seeds ([`seed_jackknife`]); `None` with fewer
    /// than three seeds.
    pub(crate) error: Option<f64>,
    /// The seed of each point's packing, for a jackknife of another estimate over the same points.
    pub(crate) seeds: Vec<u64>,
}

impl Scaling {
    /// The standard error over the seeds of how far the exponent moves when refitted over the
    /// points with Δφ ≤ `ceiling` alone. Both fits hold the points below the ceiling, so their
    /// errors are not independent and the shift's is not theirs added: the shift itself is
    /// jackknifed ([`seed_jackknife_of`]). `None` with fewer than [`JACKKNIFE_SEEDS`] seeds.
    pub(crate) fn shift_error(&self, ceiling: f64) -> Option<f64> {
        seed_jackknife_of(&self.points, &self.seeds, |kept| {
            let lower: Vec<(f64, f64)> = kept.iter().copied().filter(|p| p.0 <= ceiling).collect();
            Some(power_law_fit(&lower)?.exponent - power_law_fit(kept)?.exponent)
        })
    }
}

/// Fewest seeds a jackknife error is given for: with two, each leave-one-out fit is one seed's.
pub(crate) const JACKKNIFE_SEEDS: usize = 3;

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
pub(crate) fn seed_jackknife_of(
    points: &[(f64, f64)],
    seeds: &[u64],
    estimate: impl Fn(&[(f64, f64)]) -> Option<f64>,
) -> Option<f64> {
    let distinct = sorted_distinct(seeds.iter().copied());
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
pub(crate) fn scalings(runs: &[&RunRecord], n: usize, beta: f64, floor: f64) -> Vec<Scaling> {
    scalings_over(runs, n, beta, (floor, f64::INFINITY))
}

/// [`scalings`] over the packings whose Δφ lies in `window` (floor and ceiling).
pub(crate) fn scalings_over(runs: &[&RunRecord], n: usize, beta: f64, window: (f64, f64)) -> Vec<Scaling> {
    let mine = fitted_packings(runs, (n, beta), window);
    QUANTITIES
        .iter()
        .filter_map(|q| {
            let (points, seeds): (Vec<(f64, f64)>, Vec<u64>) =
                mine.iter().filter_map(|&(d, r)| Some(((d, (q.pick)(r).filter(|y| *y > 0.0)?), seed(r)))).unzip();
            let not_positive = mine.iter().filter(|(_, r)| (q.pick)(r).is_some_and(|y| y <= 0.0)).count();
            let fit = power_law_fit(&points)?;
            let error = seed_jackknife(&points, &seeds);
            let (quantity, column) = (q.symbol, (q.column, AGAINST_FRACTION));
            Some(Scaling { quantity, column, fit, theory: (q.theory)(beta), points, not_positive, error, seeds })
        })
        .collect()
}

/// G/K of the jammed packings of `n` discs with contact exponent `beta` against their excess
/// coordination Δz = z − 4, fitted on log–log axes over the packings with Δφ ≥ `floor`: the
/// theory's G ∝ K Δz makes it Δz¹ for every contact law (the shear modulus is the bulk
/// modulus thinned by how far the contact network is above isostatic).
pub(crate) fn ratio_against_contacts(runs: &[&RunRecord], n: usize, beta: f64, floor: f64) -> Option<Scaling> {
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
    let (quantity, column) = ("G/K against z − 4", (RATIO, AGAINST_CONTACTS));
    Some(Scaling { quantity, column, fit, theory: 1.0, points, not_positive: 0, error, seeds })
}

/// The packings' scalings for `summary.csv`, per scene and group of its quenched packings (its
/// grid values but the fraction and the seed: one N and contact law each): p, z − 4, K and G
/// against Δφ and G/K against z − 4, fitted as the scene's figures fit them, Δφ from the φ_J of
/// the campaign's packings of that law ([`onsets_of`]) over Δφ ≥ the floor of its N.
pub fn fits(records: &[RunRecord]) -> Vec<ScalingFit> {
    let runs: Vec<&RunRecord> = records.iter().filter(|r| fitted(r)).collect();
    let groups = super::scene_groups(runs.iter().map(|&r| (r, r)), &["packing.fraction", "seed"]);
    groups.iter().flat_map(|(_, label, members)| group_fits(&runs, label, members)).collect()
}

/// The scalings of one group of packings (`members`, of one scene, N and law) as `summary.csv`
/// rows, none where its N has no φ_J.
fn group_fits(runs: &[&RunRecord], group: &str, members: &[&RunRecord]) -> Vec<ScalingFit> {
    let first = members[0];
    let (Some((n, _)), beta) = (key(first), first.spec.law.beta()) else { return Vec::new() };
    let Some(size) = Onset::per_size(&onsets_of(runs, beta)).into_iter().find(|s| s.n == n) else {
        return Vec::new();
    };
    let floor = size.fit_floor();
    let ratio = ratio_against_contacts(members, n, beta, floor);
    scalings(members, n, beta, floor)
        .into_iter()
        .chain(ratio)
        .map(|s| {
            let mut points = s.points;
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            ScalingFit::of(first, group.to_string(), s.column, points, s.fit)
        })
        .collect()
}
