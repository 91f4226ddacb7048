//! Issue 34's item "Jamming": where the campaign's packings jam and how they scale above it,
//! against O'Hern, Silbert, Liu & Nagel, Phys. Rev. E 68, 011306 (2003). Each packing's own φ_J
//! (where its pressure vanishes as it is decompressed), their mean per seed and the seeds' mean
//! and standard error per N (the seeds' scatter at the campaign's quench fractions alone, told
//! beside how the own φ_J moves between them); z at jamming from each seed's packing nearest its
//! own φ_J (the extrapolation z = z_J + c √Δφ told beside it, not judged); log–log fits of p,
//! z − 4, K and G against each packing's Δφ = φ − φ_J per contact law and N; and the packings
//! unstable to shear, their fall with Δφ N² tested one sample per seed.

use std::collections::BTreeMap;

use super::finding::{Answer, Evidence, Table, Verdict, exponents, plus_minus, sig, signed};
use crate::measure::mean_spread;
use crate::measure::{line_fit, sorted_distinct};
use crate::report::figure::{FigureKind, FigureRef};
use crate::report::jamming::{Quench, fisher_exact, quenches, student_t};
use crate::report::words::{self, number};
use crate::runner::RunRecord;
use crate::sim::{RelaxMethod, RunStatus};
use crate::study::packing::{ONSET_PRECISION, ROUND_OFF_MARGIN, STRAIN, STRAINED_RESIDUAL};
use crate::summary::jamming::{
    EXPONENT_TOLERANCE, FIT_FLOOR, ISOSTATIC, JACKKNIFE_SEEDS, Onset, Scaling, excess, fitted, jammed, key, onsets_of,
    ratio_against_contacts, scalings, scalings_over, seed, seed_jackknife_of,
};

/// The reference of every number here.
const CITATION: &str = "O'Hern, Silbert, Liu & Nagel, Phys. Rev. E 68, 011306 (2003)";
/// Their φ_J of 50:50 discs of diameter ratio 1.4, N → ∞.
const PHI_J: f64 = 0.842;
/// The allowance beside 2 standard errors for what the seeds' scatter leaves out: finite size
/// (small periodic packings jam below φ* on average, O'Hern et al.'s φ_J rising towards it with
/// N: −0.0036 at N = 64 in `campaigns/jamming.yaml`) and the preparation (the own φ_J of one
/// random start rises with the fraction it is quenched at, there by +0.0100 ± 0.0023 from
/// φ = 0.84 to 0.92 at N = 64 and +0.0037 ± 0.0003 from 0.845 to 0.92 at N = 1024, so a mean
/// over other quench fractions moves by up to that), of either sign.
const UNSAMPLED: f64 = 0.01;
/// The tolerance of z at jamming against 4, judged on each seed's packing nearest its own φ_J
/// where their mean Δφ is at most [`NEAR_JAMMING`]: z − 4 grows as c √Δφ above φ_J, c = 3.1 …
/// 3.3 over the 9 linear packings of N = 1024 at Δφ ≤ 0.005 in `campaigns/jamming.yaml`, so
/// z − 4 ≲ 3.5 √0.005 ≈ 0.25 there.
const Z_TOLERANCE: f64 = 0.25;
/// The largest mean Δφ of the packings nearest jamming whose z is judged against 4 (one step
/// of a quench grid 0.005 apart in φ): farther above φ_J, z − 4 exceeds [`Z_TOLERANCE`] by the
/// √Δφ growth alone, and says nothing of z at jamming.
const NEAR_JAMMING: f64 = 0.005;

/// Packings quenched in a fixed box that are unstable to shear (G < 0) though jammed.
const SHEAR_UNSTABLE: &str = "Dagois-Bohy, Tighe, Simon, Henkes & van Hecke, Phys. Rev. Lett. 109, 095703 (2012)";

/// How far a modulus by strain may be from the stiffness matrix's and agree with it (relative).
const STRAINED_AGREEMENT: f64 = 0.01;

/// A modulus of a packing, both ways.
struct Twin {
    /// K or G.
    name: &'static str,
    /// From the stiffness matrix (N/m).
    matrix: fn(&RunRecord) -> Option<f64>,
    /// By strain and relaxation (N/m).
    strained: fn(&RunRecord) -> Option<f64>,
    /// The pairs of discs its strains made or broke.
    changes: fn(&RunRecord) -> Option<u64>,
}

/// K and G, each from the stiffness matrix and by strain and relaxation.
const TWINS: [Twin; 2] = [
    Twin {
        name: "K",
        matrix: |r| r.metrics.packing.bulk_modulus_2d,
        strained: |r| r.metrics.packing.bulk_modulus_2d_strained,
        changes: |r| r.metrics.packing.bulk_strain_contact_changes,
    },
    Twin {
        name: "G",
        matrix: |r| r.metrics.packing.shear_modulus_2d,
        strained: |r| r.metrics.packing.shear_modulus_2d_strained,
        changes: |r| r.metrics.packing.shear_strain_contact_changes,
    },
];

/// A modulus by strain beside the stiffness matrix's: whether it parts from it (by more than
/// [`STRAINED_AGREEMENT`]) and whether a contact was made or broken within its strain (`None`
/// in a record from before that was counted).
struct Compared {
    parted: bool,
    changed: Option<bool>,
}

/// The moduli by strain (the "by MD under a small strain beside them") against the
/// stiffness matrix's, per contact law: in how many jammed packings they agree within
/// [`STRAINED_AGREEMENT`], and where they part, why ([`parted_words`]).
fn strained_sentence(runs: &[&RunRecord]) -> Option<String> {
    let jammed: Vec<&RunRecord> = runs.iter().copied().filter(|r| jammed(r)).collect();
    let betas = exponents(jammed.iter().copied());
    let (mut laws, mut compared) = (Vec::new(), Vec::new());
    for beta in betas {
        let mut counts = Vec::new();
        for twin in &TWINS {
            let of_law: Vec<Compared> = jammed
                .iter()
                .filter(|r| r.spec.law.beta() == beta)
                .filter_map(|r| {
                    let matrix = (twin.matrix)(r).filter(|m| *m > 0.0)?;
                    let changed = (twin.changes)(r).map(|c| c > 0);
                    Some(Compared { parted: !agrees((twin.strained)(r)?, matrix), changed })
                })
                .collect();
            let agree = of_law.iter().filter(|c| !c.parted).count();
            counts.push(format!("{} {agree} of {}", twin.name, of_law.len()));
            compared.extend(of_law);
        }
        laws.push(format!("{} contacts, {}", law_words(beta), counts.join(" and ")));
    }
    if compared.is_empty() {
        return None;
    }
    Some(format!(
        "The same moduli by strain, beside the stiffness matrix's (each packing relaxed again to forces below \
         {STRAINED_RESIDUAL:e} k d^β, or {ROUND_OFF_MARGIN} times their round-off where that is larger, strained by \
         ±{STRAIN:e}, relaxed again, and K and G from its relaxed energies), agree with them within {} % in: {} \
         (jammed packings with both, the matrix's positive){}",
        number(100.0 * STRAINED_AGREEMENT),
        laws.join("; "),
        parted_words(&compared)
    ))
}

/// Where the moduli by strain part from the stiffness matrix's, from the records: how many
/// of them, and of those that agree, have a contact made or broken within their strain, and
/// where any has, why that parts them (U is not smooth there: its second difference is no
/// stiffness, unless the contact carries next to nothing). Only the full stop when none parts.
fn parted_words(compared: &[Compared]) -> String {
    let count = |keep: &dyn Fn(&Compared) -> bool| compared.iter().filter(|c| keep(c)).count();
    let (apart, agree) = (count(&|c| c.parted), count(&|c| !c.parted));
    if apart == 0 {
        return ".".into();
    }
    let changed = count(&|c| c.parted && c.changed == Some(true));
    let against = match agree {
        0 => String::new(),
        _ => format!(
            ", against those of {} of the {agree} that agree{}",
            count(&|c| !c.parted && c.changed == Some(true)),
            if agree == 1 { "s" } else { "" }
        ),
    };
    let why = match changed {
        0 => "",
        _ => {
            ": U is not smooth across such a contact, and its second difference is no stiffness unless the contact \
             carries next to nothing"
        }
    };
    let uncounted = match count(&|c| c.changed.is_none()) {
        0 => String::new(),
        k => format!(" ({k} in records of a build that did not count them)"),
    };
    format!(
        ". Of the {apart} that part{}, the strains of {changed} make or break a contact (columns \
         bulk_strain_contact_changes and shear_strain_contact_changes){against}{uncounted}{why}. The fits and figures \
         use the stiffness matrix's moduli.",
        if apart == 1 { "s" } else { "" }
    )
}

/// The jammed packings whose G from the stiffness matrix is negative, per N (both laws): a
/// minimum of U for their backbone's discs in their box (the matrix has a Cholesky factor),
/// yet U curves down along a shear of the box; how many of them the route by strain finds
/// the same G < 0 for ([`agrees`]). `None` without a jammed packing with a G.
fn unstable_sentence(runs: &[&RunRecord]) -> Option<String> {
    let shear = |r: &RunRecord| r.metrics.packing.shear_modulus_2d;
    let with_g: Vec<&RunRecord> = runs.iter().copied().filter(|r| jammed(r) && shear(r).is_some()).collect();
    if with_g.is_empty() {
        return None;
    }
    let unstable: Vec<&RunRecord> = with_g.iter().copied().filter(|r| shear(r).is_some_and(|g| g < 0.0)).collect();
    let first = format!(
        "Unstable to shear: {} of the {} jammed packings with a G from the stiffness matrix {} G < 0 ({})",
        unstable.len(),
        with_g.len(),
        if unstable.len() == 1 { "has" } else { "have" },
        per_size(&unstable, &with_g)
    );
    if unstable.is_empty() {
        return Some(format!("{first}."));
    }
    let by_strain = |r: &&RunRecord| r.metrics.packing.shear_modulus_2d_strained.zip(shear(r));
    let confirmed = unstable.iter().filter(|r| by_strain(r).is_some_and(|(s, g)| agrees(s, g))).count();
    Some(format!(
        "{first}. For {} the stiffness matrix over the backbone's discs (one held) has a Cholesky factor, so no motion \
         of theirs lowers U at second order (to 1e-12 of its largest entry), yet U curves down along a shear of the \
         box (d²U/dγ² < 0, the discs relaxed); the route by strain, independent of the matrix, finds G < 0 within {} \
         % of it in {confirmed} of the {}. {SHEAR_UNSTABLE} found packings unstable to shear among those made in a \
         fixed box, fewer the larger p N². {} The log–log fits of G leave them out; those of p, z − 4 and K keep \
         them.",
        if unstable.len() == 1 { "it".to_string() } else { format!("each of the {}", unstable.len()) },
        number(100.0 * STRAINED_AGREEMENT),
        unstable.len(),
        finite_size_words(&unstable, &with_g)
    ))
}

/// Where the finite-size crossover is counted from: Δφ N² in decades from 10² to 10³.
const CROSSOVER: [f64; 2] = [1e2, 1e3];

/// The ranges of Δφ N² that [`CROSSOVER`] parts, in words.
const RANGES: [&str; 3] = ["at Δφ N² < 10²", "at 10² ≤ Δφ N² < 10³", "at Δφ N² ≥ 10³"];

/// The p-value below which Fisher's exact test calls two shares different: a difference that
/// chance alone makes less often than once in 20 such campaigns.
const SIGNIFICANCE: f64 = 0.05;

/// A packing's range of Δφ N² among [`CROSSOVER`]'s (0 below the first edge).
fn crossover_range(r: &RunRecord) -> usize {
    let scaled = excess(r).map_or(0.0, |d| d * key(r).map_or(0.0, |(n, _)| (n * n) as f64));
    CROSSOVER.iter().filter(|&&edge| scaled >= edge).count()
}

/// How the share of packings with G < 0 (`unstable` of `with_g`) goes with Δφ N², the
/// finite-size scaling variable of jamming for either contact law: z − 4 ∝ Δφ^½ for both, so a
/// packing is one contact from isostatic where (z − 4) N ~ 1, i.e. Δφ N² ~ 1 (Goodrich, Liu &
/// Nagel, Phys. Rev. Lett. 109, 095704 (2012)); it is ∝ p N², Dagois-Bohy et al.'s variable, for
/// linear contacts alone (Hertz p ∝ Δφ^(3/2)), which the sentence says where laws are pooled.
/// The counts in each range of [`CROSSOVER`] that has packings (an empty one has no share),
/// whether the share falls from each to the next, and whether the lowest and the highest
/// differ by more than chance ([`fall_verdict`]).
fn finite_size_words(unstable: &[&RunRecord], with_g: &[&RunRecord]) -> String {
    let count = |packings: &[&RunRecord], i: usize| packings.iter().filter(|r| crossover_range(r) == i).count();
    let populated: Vec<(usize, usize, usize)> =
        (0..RANGES.len()).map(|i| (i, count(unstable, i), count(with_g, i))).filter(|&(_, _, all)| all > 0).collect();
    let shares: Vec<f64> = populated.iter().map(|&(_, a, b)| a as f64 / b as f64).collect();
    let falls = shares.len() > 1 && shares.windows(2).all(|w| w[1] < w[0]);
    let counts: Vec<String> = populated.iter().map(|&(i, a, b)| format!("{a} of {b} {}", RANGES[i])).collect();
    let verdict = match (populated.first(), populated.last()) {
        (Some(&low), Some(&high)) if falls => fall_verdict(unstable, with_g, low, high),
        _ => String::new(),
    };
    let laws: Vec<String> = exponents(with_g.iter().copied()).into_iter().map(law_words).collect();
    let pooled = match laws.len() {
        0 | 1 => String::new(),
        _ => format!(", and the {} packings are pooled here", words::listed(&laws, "and")),
    };
    format!(
        "Here the share {} as Δφ N² grows (the finite-size scaling variable of jamming for either contact law: z − 4 \
         ∝ Δφ^½ for both, so a packing is one contact from isostatic where (z − 4) N ~ 1, i.e. Δφ N² ~ 1, Goodrich, \
         Liu & Nagel, Phys. Rev. Lett. 109, 095704 (2012); ∝ p N² for linear contacts alone, as Hertz p ∝ \
         Δφ^(3/2){pooled}): of the jammed packings with a G, {}{verdict}.",
        match (falls, populated.len() > 1) {
            (true, _) => "falls",
            (false, true) => "does not fall steadily",
            (false, false) => "cannot be followed (one range has all the packings)",
        },
        counts.join(", ")
    )
}

/// Whether the share of G < 0 falls from the `low`est range of Δφ N² to the `high`est (range,
/// unstable, all) by more than chance. Fisher's exact test over the packings takes each for an
/// independent sample; a seed's packings at every fraction, N and contact law are not (disc k
/// of seed s starts at one place in units of the box whatever the fraction and N), so where it
/// finds a fall the verdict is the seeds' ([`seed_shares`]): only a fall that chance rarely
/// makes, seed by seed, is called a finite-size effect.
fn fall_verdict(
    unstable: &[&RunRecord],
    with_g: &[&RunRecord],
    (i, a, m): (usize, usize, usize),
    (j, b, n): (usize, usize, usize),
) -> String {
    let p = fisher_exact((a, m), (b, n));
    let pooled = format!("Fisher's exact test of the lowest range against the highest: p = {}", sig(p));
    if p >= SIGNIFICANCE {
        return format!(
            "; but {pooled}, not below {SIGNIFICANCE} even with each packing taken for an independent sample: chance \
             alone makes such a fall more often than once in 20, and these counts cannot tell a finite-size effect"
        );
    }
    let s = seed_shares(unstable, with_g, (i, j));
    let seeds = format!(
        "{pooled}, but it takes the {} packings of those two ranges for independent samples, and those of one seed \
         share its random start, disc k placed alike in units of the box at every fraction, N and contact law, so it \
         overstates; one sample per seed, the seed's own share falls from the lowest range to the highest in {} of the {} seeds with packings \
         in both, rises in {} and stays in {}: the sign test gives p = {}",
        m + n,
        s.falls,
        s.falls + s.rises + s.stays,
        s.rises,
        s.stays,
        sig(s.p)
    );
    if s.p < SIGNIFICANCE {
        format!(" ({seeds} < {SIGNIFICANCE}): a finite-size effect, of that kind")
    } else {
        format!(" ({seeds}, not below {SIGNIFICANCE}): these seeds cannot tell a finite-size effect")
    }
}

/// The seeds whose own share of G < 0 falls, rises or stays from range `low` of Δφ N² to range
/// `high` (those with packings in both), and the two-sided sign test of the falls against the
/// rises ([`sign_test`]): one independent sample per seed.
struct SeedShares {
    falls: usize,
    rises: usize,
    stays: usize,
    p: f64,
}

/// Each seed's share of `unstable` among its `with_g` in range `low` against range `high`.
fn seed_shares(unstable: &[&RunRecord], with_g: &[&RunRecord], (low, high): (usize, usize)) -> SeedShares {
    let seeds: Vec<u64> = sorted_distinct(with_g.iter().map(|r| seed(r)));
    let share = |s: u64, i: usize| {
        let count =
            |packings: &[&RunRecord]| packings.iter().filter(|r| seed(r) == s && crossover_range(r) == i).count();
        let all = count(with_g);
        (all > 0).then(|| count(unstable) as f64 / all as f64)
    };
    let changes: Vec<f64> = seeds.iter().filter_map(|&s| Some(share(s, high)? - share(s, low)?)).collect();
    let falls = changes.iter().filter(|c| **c < 0.0).count();
    let rises = changes.iter().filter(|c| **c > 0.0).count();
    SeedShares { falls, rises, stays: changes.len() - falls - rises, p: sign_test(falls, rises) }
}

/// The two-sided sign test of `a` against `b`: the chance that a fair coin tossed n = a + b
/// times parts at least as unevenly, 2 Σ_{k ≥ max(a, b)} C(n, k) / 2^n, at most 1 (1 at n = 0).
fn sign_test(a: usize, b: usize) -> f64 {
    let n = a + b;
    // C(n, k)/2^n from k = 0 up: 2^−n, then each × (n − k)/(k + 1).
    let terms = (0..=n).scan(0.5f64.powi(n as i32), |term, k| {
        let this = *term;
        *term *= (n - k) as f64 / (k + 1) as f64;
        Some(this)
    });
    (2.0 * terms.skip(a.max(b)).sum::<f64>()).min(1.0)
}

/// "a of b at N = n" for each N of `whole`: how many of its packings are in `part`.
fn per_size(part: &[&RunRecord], whole: &[&RunRecord]) -> String {
    let size = |r: &&RunRecord| key(r).map(|(n, _)| n);
    let sizes: Vec<usize> = sorted_distinct(whole.iter().filter_map(size));
    let of_size = |packings: &[&RunRecord], n: usize| packings.iter().filter(|r| size(r) == Some(n)).count();
    let counts: Vec<String> =
        sizes.iter().map(|&n| format!("{} of {} at N = {n}", of_size(part, n), of_size(whole, n))).collect();
    counts.join(", ")
}

/// Whether a modulus by strain agrees with the stiffness matrix's, within
/// [`STRAINED_AGREEMENT`] of it (both of either sign).
fn agrees(strained: f64, matrix: f64) -> bool {
    (strained / matrix - 1.0).abs() <= STRAINED_AGREEMENT
}

/// The packings of every other contact law than the `base` one φ_J is from are quenches of
/// their own: a sentence each with their φ_J at the largest N ([`onsets_of`]) against the base
/// packings', whose difference O'Hern et al. found none of (φ_J does not depend on the potential).
fn own_onset_sentences(runs: &[&RunRecord], linear: &Onset, base: f64) -> Vec<String> {
    let base_words = law_words(base);
    exponents(runs.iter().copied())
        .into_iter()
        .filter(|&beta| beta != base)
        .filter_map(|beta| {
            let other = Onset::per_size(&onsets_of(runs, beta)).into_iter().find(|s| s.n == linear.n)?;
            let gap = other.mean - linear.mean;
            let spread = other.error.hypot(linear.error);
            // With one seed a side there is no standard error, and no difference to judge by it.
            if spread == 0.0 {
                return Some(format!(
                    "The {} packings, quenches of their own from the same random starts, jam at φ_J = {} at N = {} (one \
                     seed): {} from the {base_words} packings', with no standard error to judge it by.",
                    law_words(beta),
                    sig(other.mean),
                    other.n,
                    signed(gap),
                ));
            }
            let errors = gap.abs() / spread;
            Some(format!(
                "The {} packings, quenches of their own from the same random starts, jam at φ_J = {} at N = {} ({}): \
                 {} from the {base_words} packings', {} standard errors of the difference ({}; {CITATION} found φ_J \
                 independent of the potential).",
                law_words(beta),
                plus_minus(other.mean, other.error),
                other.n,
                words::counted(other.seeds, "seed"),
                signed(gap),
                sig(errors),
                if errors <= 2.0 { "the same φ_J within 2" } else { "more than 2: a different φ_J" },
            ))
        })
        .collect()
}

/// The contact law in words, from its exponent β.
fn law_words(beta: f64) -> String {
    match beta {
        1.0 => "linear".into(),
        1.5 => "Hertz".into(),
        _ => format!("power (β = {})", sig(beta)),
    }
}

impl Onset {
    /// Within 2 standard errors and [`UNSAMPLED`] of O'Hern et al.'s φ_J.
    fn within(&self) -> bool {
        (self.mean - PHI_J).abs() <= 2.0 * self.error + UNSAMPLED
    }

    /// Its sentence, with the quench fractions its standard error is the seeds' scatter at and
    /// how the own φ_J moves between them (`protocol`); held against O'Hern et al.'s φ_J where
    /// that is the mixture's (`literature`).
    fn sentence(&self, literature: bool, protocol: &Protocol) -> String {
        let over = match (self.seeds, self.error > 0.0) {
            (1, _) => "one seed".to_string(),
            (seeds, true) => {
                format!("mean ± standard error over {seeds} seeds: their scatter {} alone", protocol.span_words())
            }
            (seeds, false) => format!("mean of {seeds} seeds that relaxed to one state: no standard error"),
        };
        let judged = if literature {
            format!(
                ", {} from {CITATION}'s {PHI_J}{}: {} (tolerance: 2 standard errors + {UNSAMPLED}, the latter for finite \
                 size and preparation, which the seeds' scatter leaves out)",
                signed(self.mean - PHI_J),
                self.in_errors(),
                if self.within() { "within" } else { "outside" },
            )
        } else {
            String::new()
        };
        format!(
            "N = {}: φ_J = {} ({over}; {}){judged}.",
            self.n,
            plus_minus(self.mean, self.error),
            protocol.dependence()
        )
    }

    /// The gap to the literature's φ_J in standard errors, where that is more than two: a gap
    /// that only [`UNSAMPLED`] covers says so, and by which of its parts. Small periodic
    /// packings jam below φ* on average, O'Hern et al.'s φ_J rising towards it with N, so finite
    /// size explains no φ_J above 0.842: there only the preparation can.
    fn in_errors(&self) -> String {
        let errors = (self.mean - PHI_J).abs() / self.error;
        let parts = match self.mean > PHI_J {
            true => "the preparation, not finite size: small periodic packings jam below 0.842 on average, not above",
            false => "finite size and preparation",
        };
        match (self.error > 0.0 && errors > 2.0, self.within()) {
            (false, _) => String::new(),
            (true, true) => format!(" ({} standard errors: within only by the allowance, for {parts})", sig(errors)),
            (true, false) => format!(" ({} standard errors)", sig(errors)),
        }
    }
}

/// How the mean φ_J moves from the smallest N to the largest, if the campaign has two sizes.
fn trend_sentence(sizes: &[Onset]) -> Option<String> {
    let (first, last) = (sizes.first()?, sizes.last()?);
    (sizes.len() > 1).then(|| {
        let toward = (last.mean - PHI_J).abs() < (first.mean - PHI_J).abs();
        let across = (last.mean - PHI_J).signum() != (first.mean - PHI_J).signum();
        format!(
            "From N = {} to N = {} the mean φ_J moves by {}, {} 0.842.",
            first.n,
            last.n,
            signed(last.mean - first.mean),
            match (across, toward) {
                (true, _) => "across",
                (false, true) => "towards",
                (false, false) => "away from",
            }
        )
    })
}

/// The `base` law's packings of `n` discs by quench fraction, those fractions where some jammed.
fn jammed_quenches(system: &[&RunRecord], n: usize, base: f64) -> Vec<Quench> {
    quenches(system, n, base).into_iter().filter(|q| !q.onsets.is_empty()).collect()
}

/// How a state's own φ_J depends on the fraction it was quenched at, at the largest N: the
/// `base` law's packings at the lowest and the highest fraction where every packing jammed
/// ([`Quench::complete`]: elsewhere those that jammed are the ones whose own φ_J lies below the
/// fraction, a selection that alone makes the own φ_J rise with it), their difference per seed
/// against its standard error. `None` where fewer than two fractions have jammed packings.
fn preparation_sentence(system: &[&RunRecord], n: usize, base: f64) -> Option<String> {
    let quenches = jammed_quenches(system, n, base);
    if quenches.len() < 2 {
        return None;
    }
    let cut: Vec<&Quench> = quenches.iter().filter(|q| !q.complete()).collect();
    let complete: Vec<&Quench> = quenches.iter().filter(|q| q.complete()).collect();
    let selection = match cut.is_empty() {
        true => String::new(),
        false => format!(
            " a packing quenched at φ jams only where its own φ_J lies below φ, so where only some jammed ({}) the own \
             φ_J of those that did are cut off from above and are left out;",
            cut_words(&cut)
        ),
    };
    let comparison = match complete.as_slice() {
        [low, .., high] => quench_difference(&Paired::of(low, high)),
        [only] => format!(
            "every packing jammed at φ = {} alone, so the low end of the quench fractions is cut off by that \
             selection and nothing is said of how the own φ_J depends on the preparation",
            number(only.fraction)
        ),
        [] => "at no fraction did every packing jam, so nothing is said of how the own φ_J depends on the preparation"
            .into(),
    };
    Some(format!(
        "A state's own φ_J against the fraction it was quenched at ({} packings, N = {n}):{selection} {comparison}.",
        law_words(base)
    ))
}

/// Quench fractions where only some packings jammed, in words: "φ = 0.84: 3 of 8 jammed".
fn cut_words(cut: &[&Quench]) -> String {
    let each: Vec<String> = cut
        .iter()
        .map(|q| format!("φ = {}: {} of {} jammed", number(q.fraction), q.onsets.len(), q.packings))
        .collect();
    each.join("; ")
}

/// The own φ_J of one N's packings quenched at a low and a high fraction where every one
/// jammed: their means, and their difference per seed (whose random start both quenches
/// share) with its standard error over the seeds.
struct Paired {
    fractions: (f64, f64),
    means: (f64, f64),
    /// The mean of high − low over the seeds quenched at both (`None` without one).
    difference: Option<f64>,
    /// Its standard error (`None` with one seed, or where every seed moved alike).
    error: Option<f64>,
    seeds: usize,
}

impl Paired {
    fn of(low: &Quench, high: &Quench) -> Self {
        let mean = |q: &Quench| q.onsets.iter().map(|o| o.1).sum::<f64>() / q.onsets.len() as f64;
        let differences: Vec<Option<f64>> = high
            .onsets
            .iter()
            .filter_map(|&(s, phi)| low.onsets.iter().find(|o| o.0 == s).map(|o| Some(phi - o.1)))
            .collect();
        let seeds = differences.len();
        let (difference, spread) = mean_spread(differences.into_iter());
        let error = spread.map(|s| s / (seeds as f64).sqrt()).filter(|e| *e > 0.0);
        Paired { fractions: (low.fraction, high.fraction), means: (mean(low), mean(high)), difference, error, seeds }
    }

    /// The difference in its standard errors, and Student's t that chance exceeds once in 20 at
    /// the seeds' degrees of freedom ([`student_t`]: a paired t-test); `None` without an error.
    fn errors(&self) -> Option<(f64, f64)> {
        Some((self.difference?.abs() / self.error?, student_t(self.seeds - 1)))
    }

    /// Whether the seeds resolve a dependence on the preparation: the difference beyond t.
    fn resolved(&self) -> bool {
        self.errors().is_some_and(|(errors, t)| errors > t)
    }
}

/// The own φ_J of the packings quenched at the `paired` fractions (every one jammed at both)
/// and their difference per seed against its standard error over the seeds: told as a
/// dependence on the preparation only where the seeds resolve it ([`Paired::resolved`]).
fn quench_difference(paired: &Paired) -> String {
    let both = format!(
        "where every one jammed, those quenched at φ = {} jam at {} and those at φ = {} at {}",
        number(paired.fractions.0),
        sig(paired.means.0),
        number(paired.fractions.1),
        sig(paired.means.1)
    );
    let (Some(difference), Some(error), Some((errors, t))) = (paired.difference, paired.error, paired.errors()) else {
        return format!(
            "{both}; with {} quenched at both there is no standard error to judge the difference by, and nothing is \
             said of how the own φ_J depends on the preparation",
            words::counted(paired.seeds, "seed")
        );
    };
    let verdict = if paired.resolved() {
        format!(
            "the own φ_J {} with the quench fraction (Chaudhuri, Berthier & Sastry, Phys. Rev. Lett. 104, 165701 \
             (2010) found jamming spread over a range of φ with the preparation)",
            direction(difference)
        )
    } else {
        "these seeds cannot tell whether the own φ_J depends on the preparation".into()
    };
    format!(
        "{both}, {} per seed over {} quenched at both from one random start, {} standard errors, {} {} (Student's t \
         that chance exceeds once in 20 at {} of freedom): {verdict}",
        plus_minus_signed(difference, error),
        words::counted(paired.seeds, "seed"),
        sig(errors),
        if paired.resolved() { "more than" } else { "not more than" },
        sig(t),
        words::counted(paired.seeds - 1, "degree")
    )
}

/// The quench fractions one N's φ_J is measured at, and how its packings' own φ_J moves
/// between them. The seeds' standard error of φ_J is their scatter at these fractions alone:
/// the own φ_J of one random start rises with the fraction it is quenched at (jamming.yaml,
/// N = 1024: +0.00374 ± 0.00030 from φ = 0.845 to 0.92), so the same seeds quenched elsewhere
/// give another φ_J beyond that error (N = 256, seeds 1 … 8: 0.84051 ± 0.00064 quenched at φ =
/// 0.845 and 0.85, 0.84364 ± 0.00038 at 0.90 … 0.94, 5.6 standard errors of the paired
/// difference apart).
struct Protocol {
    /// The lowest and the highest fraction with a jammed packing.
    span: (f64, f64),
    /// The lowest and the highest fraction where every packing jammed, compared per seed; `None`
    /// without two such.
    paired: Option<Paired>,
}

impl Protocol {
    /// The protocol of the `base` law's packings of `n` discs among `system`.
    fn of(system: &[&RunRecord], n: usize, base: f64) -> Self {
        let quenches = jammed_quenches(system, n, base);
        let complete: Vec<&Quench> = quenches.iter().filter(|q| q.complete()).collect();
        let paired = match complete.as_slice() {
            [low, .., high] => Some(Paired::of(low, high)),
            _ => None,
        };
        Protocol { span: crate::measure::extremes(quenches.iter().map(|q| q.fraction)), paired }
    }

    /// "at φ = 0.82 … 0.92", or "at φ = 0.86" for one fraction.
    fn span_words(&self) -> String {
        match self.span.0 < self.span.1 {
            true => format!("at φ = {} … {}", number(self.span.0), number(self.span.1)),
            false => format!("at φ = {}", number(self.span.0)),
        }
    }

    /// How the own φ_J moves from the lowest fraction where every packing jammed to the
    /// highest, per seed, and what that is to the seeds' standard error.
    fn dependence(&self) -> String {
        let between = |p: &Paired| format!("from φ = {} to {}", number(p.fractions.0), number(p.fractions.1));
        match &self.paired {
            Some(p @ Paired { difference: Some(d), error: Some(e), .. }) if p.resolved() => format!(
                "the own φ_J {} by {} {} per seed, a dependence on the preparation that this standard error leaves out",
                direction(*d),
                plus_minus_signed(*d, *e),
                between(p)
            ),
            Some(p @ Paired { difference: Some(d), error: Some(e), .. }) => format!(
                "the own φ_J moves by {} {} per seed, a dependence on the preparation these seeds do not resolve",
                plus_minus_signed(*d, *e),
                between(p)
            ),
            Some(p @ Paired { difference: Some(d), .. }) => {
                format!("the own φ_J moves by {} {}, with no standard error to judge it by", signed(*d), between(p))
            }
            _ => "how it moves with the quench fraction is not measured here: that needs two fractions where every \
                  packing jammed, with seeds quenched at both"
                .into(),
        }
    }

    /// The headline's and the table's words for `onset`: the fractions its seeds' scatter is
    /// from, and the dependence on the preparation where the seeds resolve it.
    fn headline(&self, onset: &Onset) -> String {
        let moves = match &self.paired {
            Some(p @ Paired { difference: Some(d), error: Some(e), .. }) if p.resolved() => format!(
                "; it depends on the preparation: the own φ_J {} by {} per seed from φ = {} to {}",
                direction(*d),
                plus_minus_signed(*d, *e),
                number(p.fractions.0),
                number(p.fractions.1)
            ),
            _ => String::new(),
        };
        let scatter = if onset.error > 0.0 { "± the seeds' scatter " } else { "" };
        format!("{scatter}quenched {}{}{moves}", self.span_words(), if scatter.is_empty() { "" } else { " alone" })
    }
}

/// How the own φ_J goes with the quench fraction, from their difference per seed.
fn direction(difference: f64) -> &'static str {
    if difference > 0.0 { "rises" } else { "falls" }
}

/// A difference ± its standard error, with its sign.
fn plus_minus_signed(x: f64, error: f64) -> String {
    let words = plus_minus(x, error);
    if x > 0.0 { format!("+{words}") } else { words }
}

/// The seeds' φ_J of every N where some quench fraction has only some packings jammed: each
/// seed's φ_J averages its jammed packings at every fraction, those cut off from above at their
/// fraction ([`Quench::complete`]) among them, so the mean is said again from the fractions
/// where every packing jammed alone. `None` where no fraction is cut.
fn selection_sentence(system: &[&RunRecord], runs: &[&RunRecord], base: f64, sizes: &[Onset]) -> Option<String> {
    let mut parts = Vec::new();
    for size in sizes {
        let quenches = quenches(system, size.n, base);
        let cut: Vec<&Quench> = quenches.iter().filter(|q| !q.complete() && !q.onsets.is_empty()).collect();
        if cut.is_empty() {
            continue;
        }
        let whole = |r: &&&RunRecord| {
            let at = |q: &&Quench| r.spec.packing().is_some_and(|p| p.fraction == q.fraction);
            r.spec.law.beta() != base
                || key(r).is_none_or(|k| k.0 != size.n)
                || quenches.iter().find(at).is_some_and(Quench::complete)
        };
        let kept: Vec<&RunRecord> = runs.iter().filter(whole).copied().collect();
        let without = Onset::per_size(&onsets_of(&kept, base)).into_iter().find(|s| s.n == size.n);
        let pull = |w: Onset| {
            let by = w.mean - size.mean;
            format!(
                "φ_J = {} from the fractions where every packing jammed alone, so those {}",
                plus_minus(w.mean, w.error),
                match by > 0.0 {
                    true => format!("pull it down by {}", sig(by)),
                    false => format!("do not pull it down here (without them it is {} lower)", sig(-by)),
                }
            )
        };
        let without = without.map_or("no fraction has every packing jammed".into(), pull);
        parts.push(format!("at N = {} ({}), {without}", size.n, cut_words(&cut)));
    }
    (!parts.is_empty()).then(|| {
        format!(
            "Each seed's φ_J above averages its jammed packings at every quench fraction, also where only some \
             packings jammed, whose own φ_J are cut off from above at that fraction: {}.",
            parts.join("; ")
        )
    })
}

/// A jammed packing as z at jamming is told from it: Δφ from its own φ_J, z (contacts per disc,
/// rattlers removed), N′ (its discs that are not rattlers) and its seed.
struct Contacted {
    excess: f64,
    z: f64,
    backbone: f64,
    seed: u64,
}

/// The jammed packings of `n` discs of contact law `base` with a Δφ > 0 and a z.
fn contacted(runs: &[&RunRecord], n: usize, base: f64) -> Vec<Contacted> {
    let of_size = |r: &&&RunRecord| r.spec.law.beta() == base && jammed(r) && key(r).is_some_and(|k| k.0 == n);
    runs.iter()
        .filter(of_size)
        .filter_map(|r| {
            let m = &r.metrics.packing;
            let backbone = (n as f64 * (1.0 - m.rattler_fraction?)).round();
            Some(Contacted { excess: excess(r)?, z: m.coordination?, backbone, seed: seed(r) })
        })
        .collect()
}

/// Whether a packing has fewer contacts than the isostatic count 2N′ − 1 of its N′ discs that
/// are not rattlers (2N′ − 2 degrees of freedom in a periodic box, less its two translations,
/// and one more to carry a pressure: Goodrich, Liu & Nagel, Phys. Rev. Lett. 109, 095704
/// (2012)), i.e. z = 2C/N′ < 4 − 2/N′, which no jammed packing can have. Counted in contacts
/// C = z N′/2, half a contact allowed for the round-off of z.
fn hypostatic(p: &Contacted) -> bool {
    p.z * p.backbone / 2.0 < 2.0 * p.backbone - 1.5
}

/// z = z_J + c √Δφ fitted over `packings`: z_J and its standard error over the seeds (the
/// jackknife). An extrapolation, biased low where z − 4 grows faster than √Δφ.
fn coordination_at_jamming(packings: &[Contacted]) -> Option<(f64, Option<f64>)> {
    let points: Vec<(f64, f64)> = packings.iter().map(|p| (p.excess.sqrt(), p.z)).collect();
    let seeds: Vec<u64> = packings.iter().map(|p| p.seed).collect();
    let intercept = |kept: &[(f64, f64)]| line_fit(kept).map(|l| l.intercept);
    Some((intercept(&points)?, seed_jackknife_of(&points, &seeds, intercept)))
}

/// Each seed's packing nearest its own φ_J (its smallest Δφ): z there needs no extrapolation.
fn nearest(packings: &[Contacted]) -> Vec<&Contacted> {
    let seeds: Vec<u64> = sorted_distinct(packings.iter().map(|p| p.seed));
    let of_seed = |s: u64| packings.iter().filter(|p| p.seed == s).min_by(|a, b| a.excess.total_cmp(&b.excess));
    seeds.into_iter().filter_map(of_seed).collect()
}

impl Scaling {
    fn within(&self) -> bool {
        (self.fit.exponent - self.theory).abs() <= EXPONENT_TOLERANCE
    }

    /// The fitted exponent, ± its standard error over the seeds where there is one.
    fn exponent_words(&self) -> String {
        match self.error {
            Some(error) if error > 0.0 => plus_minus(self.fit.exponent, error),
            _ => sig(self.fit.exponent),
        }
    }
}

/// The sentence of one law and N's scalings.
fn scalings_sentence(beta: f64, size: &Onset, fitted: &[Scaling], judged: bool) -> String {
    let parts: Vec<String> = fitted
        .iter()
        .map(|s| {
            let verdict = if !judged {
                ""
            } else if s.within() {
                ", within"
            } else {
                ", outside"
            };
            let left_out = match s.not_positive {
                0 => String::new(),
                k => format!(", {k} with {} ≤ 0 left out", s.quantity),
            };
            format!(
                "{} ∝ Δφ^{} (theory {}{verdict}; {} packings{left_out})",
                s.quantity,
                s.exponent_words(),
                sig(s.theory),
                s.points.len()
            )
        })
        .collect();
    let how = if judged {
        format!("judged within {EXPONENT_TOLERANCE} of the theory's exponent")
    } else {
        "a smaller N, not judged".into()
    };
    format!(
        "{} contacts, N = {}, over Δφ ≥ {} ({FIT_FLOOR} times the precision of each packing's own φ_J; {how}): {}.",
        words::capitalised(&law_words(beta)),
        size.n,
        sig(size.fit_floor()),
        parts.join(", ")
    )
}

/// O'Hern et al.'s mixture: 50:50 discs of diameter ratio 1.4, the one [`PHI_J`] is for.
const LITERATURE_RATIO: f64 = 1.4;

/// The packings one φ_J and one set of scalings are measured over, and those left out.
struct System<'a> {
    /// Of one mixture, one minimiser and, per contact law, one spring constant and disc size,
    /// each state once.
    runs: Vec<&'a RunRecord>,
    /// The mixture's diameter ratio: O'Hern et al.'s 1.4 where the campaign has it, else the
    /// first packing's.
    ratio: f64,
    /// The minimiser the kept packings are relaxed by: FIRE (the default) where the mixture's
    /// packings have it, else the first one's.
    method: RelaxMethod,
    /// Why each left-out packing is left out: another ratio, minimiser, spring or disc size, or
    /// a state another scene already has.
    left_out: Vec<(String, &'a RunRecord)>,
}

impl<'a> System<'a> {
    /// Chooses the system among quenched `packings`: pooling two mixtures would average two φ_J,
    /// two spring constants would scatter p, K and G by their ratio, two minimisers take one
    /// random start to different states (FIRE and CG 1.1–1.5 diameters apart, with other
    /// pressures, some jammed where the other is not): another protocol, not a repeat; and a
    /// state met twice (the same N, seed, fraction and law in two scenes, both by the kept
    /// minimiser) is one sample, not two. What is kept does not depend on the order of the scenes.
    fn of(packings: &[&'a RunRecord]) -> Self {
        // The relaxed packings first: a state is kept in its relaxed copy, and a mixture or a
        // law's spring is chosen by packings that tell something.
        let (relaxed, failed): (Vec<&RunRecord>, Vec<&RunRecord>) =
            packings.iter().partition(|r| r.status == RunStatus::Ok);
        let packings: Vec<&RunRecord> = relaxed.into_iter().chain(failed).collect();
        let ratio = chosen(&packings, ratio_of, LITERATURE_RATIO);
        let mixture: Vec<&RunRecord> = packings.iter().copied().filter(|r| ratio_of(r) == ratio).collect();
        let method = chosen(&mixture, method_of, RelaxMethod::Fire);
        let mut system = System { runs: Vec::new(), ratio, method, left_out: Vec::new() };
        let mut seen: Vec<(u64, usize, u64, u64)> = Vec::new();
        for &r in &packings {
            let state = (r.spec.law.beta().to_bits(), key(r).map_or(0, |k| k.0), seed(r), fraction_bits(r));
            let repeated = seen.contains(&state).then(|| "repeating another scene's states (counted once)".to_string());
            match system.reason(&mixture, r).or(repeated) {
                Some(reason) => system.left_out.push((reason, r)),
                None => {
                    seen.push(state);
                    system.runs.push(r);
                }
            }
        }
        system
    }

    /// Why `r` is not of the kept mixture, minimiser, or its law's spring and disc size (those
    /// of the first of `mixture` with its law and the kept minimiser); `None` when it is.
    fn reason(&self, mixture: &[&RunRecord], r: &RunRecord) -> Option<String> {
        let first = mixture.iter().find(|o| o.spec.law == r.spec.law && method_of(o) == self.method);
        if ratio_of(r) != self.ratio {
            Some(format!("of diameter ratio {}", number(ratio_of(r))))
        } else if method_of(r) != self.method {
            Some(format!("relaxed by {} (the kept ones' {})", method_of(r).name(), self.method.name()))
        } else if let Some(first) = first.filter(|f| f.spec.k != r.spec.k) {
            Some(format!("with k = {} (the kept ones' {})", number(r.spec.k), number(first.spec.k)))
        } else {
            first.filter(|f| f.spec.spacing != r.spec.spacing).map(|first| {
                format!("of spacing {} m (the kept ones' {} m)", number(r.spec.spacing), number(first.spec.spacing))
            })
        }
    }

    /// Whether O'Hern et al.'s φ_J is this mixture's.
    fn is_literature(&self) -> bool {
        self.ratio == LITERATURE_RATIO
    }

    /// The left-out packings in a sentence, by reason, another mixture with its own φ_J at its
    /// largest N; `None` when none is.
    fn left_out_sentence(&self) -> Option<String> {
        let mut reasons: Vec<&str> = Vec::new();
        for (reason, _) in &self.left_out {
            if !reasons.contains(&reason.as_str()) {
                reasons.push(reason);
            }
        }
        let parts: Vec<String> = reasons
            .iter()
            .map(|&reason| {
                let group: Vec<&RunRecord> =
                    self.left_out.iter().filter(|(w, _)| w == reason).map(|(_, r)| *r).collect();
                format!("{} {reason}{}", words::counted(group.len(), "packing"), own_mixture_words(&group))
            })
            .collect();
        (!parts.is_empty()).then(|| {
            format!(
                "Left out of φ_J and the scalings, which hold one mixture of diameter ratio {} and one spring per law: {}.",
                number(self.ratio),
                words::listed(&parts, "and")
            )
        })
    }
}

/// A packing's diameter ratio (0 for a run that is not a packing).
fn ratio_of(r: &RunRecord) -> f64 {
    r.spec.packing().map_or(0.0, |p| p.radius_ratio)
}

/// The minimiser a packing is relaxed by (FIRE, the packings' default, where none is given).
fn method_of(r: &RunRecord) -> RelaxMethod {
    r.spec.relax().map_or(RelaxMethod::Fire, |relax| relax.method)
}

/// `preferred` where one of `packings` has it, else the first one's value of `of`: a choice
/// the order of the scenes changes only where the preferred value is absent.
fn chosen<T: Copy + PartialEq>(packings: &[&RunRecord], of: fn(&RunRecord) -> T, preferred: T) -> T {
    match packings.iter().any(|r| of(r) == preferred) {
        true => preferred,
        false => packings.first().map_or(preferred, |r| of(r)),
    }
}

/// A packing's area fraction's bits, to tell states apart.
fn fraction_bits(r: &RunRecord) -> u64 {
    r.spec.packing().map_or(0, |p| p.fraction.to_bits())
}

/// Another mixture's own φ_J at its largest N, from its jammed packings of its lowest β.
fn own_mixture_words(group: &[&RunRecord]) -> String {
    let ok: Vec<&RunRecord> = group.iter().copied().filter(|r| r.status == RunStatus::Ok).collect();
    let Some(&beta) = exponents(ok.iter().copied()).first() else { return String::new() };
    Onset::per_size(&onsets_of(&ok, beta)).pop().map_or(String::new(), |size| {
        format!(
            " (their φ_J = {} at N = {}, {} packings, {})",
            plus_minus(size.mean, size.error),
            size.n,
            law_words(beta),
            words::counted(size.seeds, "seed")
        )
    })
}

/// The packings of `system` that did not relax within their budget, in a sentence; `None`
/// when every one did.
fn not_relaxed_sentence(system: &[&RunRecord]) -> Option<String> {
    let failed: Vec<&RunRecord> = system.iter().copied().filter(|r| r.status != RunStatus::Ok).collect();
    let statuses: Vec<&str> = sorted_distinct(failed.iter().map(|r| r.status.as_str()));
    (!failed.is_empty()).then(|| {
        format!(
            "{} of the {} did not relax within {} budget (status {}) and {} left out: where {} would jam is not \
             known (raise `relax.max_tc` or `budget.seconds_per_run`).",
            failed.len(),
            words::counted(system.len(), "packing"),
            if failed.len() == 1 { "its" } else { "their" },
            statuses.join(", "),
            if failed.len() == 1 { "is" } else { "are" },
            if failed.len() == 1 { "it" } else { "they" }
        )
    })
}

/// Where do random packings of discs jam, and how do their pressure, contacts and moduli grow
/// above it? `None` without packings.
pub(super) fn jamming(e: &Evidence) -> Option<Answer> {
    let any = e.all(|r| r.spec.packing().is_some() && r.spec.movie.is_none());
    if any.is_empty() {
        return None;
    }
    let system =
        System::of(&e.all(|r| r.spec.packing().is_some_and(|p| p.compression.is_none()) && r.spec.movie.is_none()));
    let runs: Vec<&RunRecord> = system.runs.iter().copied().filter(|r| fitted(r)).collect();
    // φ_J from the softest law that jammed (linear where it did): O'Hern et al. found it the
    // same for every potential, and z_J and the preparation are counted over the same packings.
    let onset_known = |r: &&&RunRecord| jammed(r) && r.metrics.packing.own_jamming_fraction.is_some();
    let Some(&base) = exponents(runs.iter().filter(onset_known).copied()).first() else {
        return Some(unjammed(&any, &system));
    };
    let onsets = onsets_of(&runs, base);
    let sizes = Onset::per_size(&onsets);
    match sizes.last() {
        Some(largest) => Some(jammed_answer(e, &system, &runs, (base, &onsets), (&sizes, largest))),
        None => Some(unjammed(&any, &system)),
    }
}

/// The opening sentence: how a packing's own φ_J and a seed's are found, over how many seeds.
fn onset_method(base: f64, onsets: &BTreeMap<(usize, u64), f64>) -> String {
    let seeds: Vec<u64> = sorted_distinct(onsets.keys().map(|k| k.1));
    let mut sizes: Vec<usize> = onsets.keys().map(|k| k.0).collect();
    sizes.dedup();
    format!(
        "Each jammed packing (p above the relaxation's floor, carried by a rigid backbone) has its own φ_J, where \
         its pressure vanishes as it is decompressed, box and positions grown together and relaxed after each step \
         (O'Hern et al.'s protocol; the steps are Newton's on p^(1/β) = 0 with dp/dφ = K/φ, to {ONSET_PRECISION:e} of φ); a \
         seed's φ_J is the mean over its jammed {} packings, {} at {}. p is the virial pressure \
         Σ f_c l_c/2A; K = −A dp/dA and G = (1/A) d²U/dγ² come from the stiffness matrix of the backbone's \
         contacts, with the discs' non-affine relaxation and the pre-stress.",
        law_words(base),
        words::counted(seeds.len(), "seed"),
        words::counted(sizes.len(), "size")
    )
}

/// The item where some packings jammed: φ_J per N from the `base` law's `onsets`, z_J, the
/// scalings of every law, the moduli by strain and the packings unstable to shear.
fn jammed_answer(
    e: &Evidence,
    system: &System,
    runs: &[&RunRecord],
    (base, onsets): (f64, &BTreeMap<(usize, u64), f64>),
    (sizes, largest): (&[Onset], &Onset),
) -> Answer {
    let literature = system.is_literature();
    let protocols: Vec<Protocol> = sizes.iter().map(|s| Protocol::of(&system.runs, s.n, base)).collect();
    let mut sentences = vec![onset_method(base, onsets)];
    sentences.extend(sizes.iter().zip(&protocols).map(|(s, p)| s.sentence(literature, p)));
    sentences.extend(selection_sentence(&system.runs, runs, base, sizes));
    sentences.extend(own_onset_sentences(runs, largest, base));
    sentences.extend(trend_sentence(sizes).filter(|_| literature));
    sentences.extend(preparation_sentence(&system.runs, largest.n, base));
    let law = law_words(base);
    let measured = |s: &Onset, p: &Protocol| format!("{} ({})", plus_minus(s.mean, s.error), p.headline(s));
    let mut rows: Vec<Vec<String>> = sizes
        .iter()
        .zip(&protocols)
        .filter(|_| literature)
        .map(|(s, p)| row(&law, s.n, "φ_J", &measured(s, p), PHI_J, s.seeds, Some(s.within())))
        .collect();
    if let Some((sentence, z_row)) = isostatic_words(runs, largest, base) {
        sentences.push(sentence);
        rows.push(z_row);
    }
    let (scaling_sentences, scaling_rows) = all_scalings(runs);
    sentences.extend(scaling_sentences);
    sentences.extend(strained_sentence(runs).into_iter().chain(unstable_sentence(runs)));
    sentences.extend(not_relaxed_sentence(&system.runs).into_iter().chain(system.left_out_sentence()));
    rows.extend(scaling_rows);
    Answer {
        title: "Jamming",
        question: "Where do random packings of discs jam, and how do p, z, K and G grow above it?",
        short: summary_line(largest, protocols.last(), &rows, system.ratio),
        sentences,
        reference: reference(runs, system),
        see_also: None,
        verdict: table_verdict(&rows),
        figures: jamming_figures(e, runs),
        table: Some(Table {
            header: ["law", "N", "quantity", "measured", "theory", "seeds or packings", "verdict"]
                .map(String::from)
                .to_vec(),
            rows,
        }),
    }
}

/// The item's reference, with how the exponents' standard errors are found: the jackknife over
/// the seeds needs [`JACKKNIFE_SEEDS`] of them, and a campaign with fewer has none to give.
fn reference(runs: &[&RunRecord], system: &System) -> String {
    let seeds: Vec<u64> = sorted_distinct(runs.iter().filter(|r| jammed(r)).map(|r| seed(r)));
    let errors = if seeds.len() >= JACKKNIFE_SEEDS {
        format!(
            "each ± its standard error over the seeds (the jackknife: refitted without each seed in turn, given where \
             a fit has {JACKKNIFE_SEEDS} seeds or more)"
        )
    } else {
        format!(
            "without standard errors: the jackknife over the seeds (refitted without each seed in turn) needs \
             {JACKKNIFE_SEEDS}, and the jammed packings here have {}",
            words::counted(seeds.len(), "seed")
        )
    };
    let mixture = match system.is_literature() {
        true => String::new(),
        false => format!(" (not this mixture's, of ratio {}: not held against it)", number(system.ratio)),
    };
    format!(
        "{CITATION}: φ_J ≈ {PHI_J} for 1:1.4 bidisperse discs{mixture}, z_J = 4, and p, z − 4, K, G ∝ Δφ^(1, ½, 0, ½) \
         for linear and ^(3/2, ½, ½, 1) for Hertz contacts; exponents judged on the largest N within \
         {EXPONENT_TOLERANCE}, {errors}."
    )
}

/// z at jamming of the `base` law's packings of the largest N (`size`), in a sentence and a
/// table row: the extrapolated z_J ([`coordination_at_jamming`]) against the least z a jammed
/// packing can have, 4 − 2/N′ ([`hypostatic`]), not judged; and z of each seed's packing
/// nearest its own φ_J ([`nearest`]) against 4, judged ([`nearest_verdict`]). `None` where z_J
/// cannot be fitted.
fn isostatic_words(runs: &[&RunRecord], size: &Onset, base: f64) -> Option<(String, Vec<String>)> {
    let packings = contacted(runs, size.n, base);
    let (z_j, error) = coordination_at_jamming(&packings)?;
    let fewest = packings.iter().map(|p| p.backbone).fold(f64::INFINITY, f64::min);
    // The least z of any of them: the bound of the packing with the fewest discs in its backbone.
    let bound = ISOSTATIC - 2.0 / fewest;
    let extrapolated = match (z_j < bound, error.filter(|e| *e > 0.0)) {
        (false, _) => "at or above".to_string(),
        (true, Some(e)) => format!("{} standard errors below", sig((bound - z_j) / e)),
        (true, None) => "below".into(),
    };
    let zeta = scalings(runs, size.n, base, size.fit_floor()).into_iter().find(|s| s.quantity == "z − 4");
    // z − 4 ∝ Δφ^ζ with ζ > ½ is convex in √Δφ: a straight line through it meets √Δφ = 0 below 4.
    let bends = match zeta.map(|s| s.fit.exponent) {
        Some(zeta) if z_j < bound && zeta > 0.5 => {
            format!(": the √Δφ form bends (z − 4 ∝ Δφ^{}), not judged", sig(zeta))
        }
        _ => "; an extrapolation, not judged".to_string(),
    };
    let near = nearest(&packings);
    let mean = mean_spread(near.iter().map(|p| Some(p.z)));
    let (mean, error_near) = (mean.0?, mean.1.map(|s| s / (near.len() as f64).sqrt()).filter(|e| *e > 0.0));
    let measured = error_near.map_or(sig(mean), |e| plus_minus(mean, e));
    let (low, high) = crate::measure::extremes(near.iter().map(|p| p.excess));
    let span = if low == high { sig(low) } else { format!("{} … {}", sig(low), sig(high)) };
    let (verdict, ok) = nearest_verdict(&packings, &near, mean);
    let sentence = format!(
        "z at jamming (mean contacts per disc, rattlers removed), {} packings of N = {}: z = z_J + c √Δφ over the {} \
         jammed ones extrapolates to z_J = {}, {extrapolated} 4 − 2/N′ = {}, the least z of a jammed packing (2N′ − 1 \
         contacts on its N′ discs that are not rattlers; N′ ≥ {fewest}){bends}. Each seed's packing nearest its \
         own φ_J (Δφ = {span}) has z = {measured} ({}){verdict}.",
        law_words(base),
        size.n,
        packings.len(),
        error.filter(|e| *e > 0.0).map_or(sig(z_j), |e| plus_minus(z_j, e)),
        sig(bound),
        words::counted(near.len(), "seed"),
    );
    Some((sentence, row(&law_words(base), size.n, "z nearest φ_J", &measured, ISOSTATIC, near.len(), ok)))
}

/// The verdict on z at jamming in words and for the table: outside where any of `packings`
/// has fewer than its isostatic count of contacts ([`hypostatic`]); else z of the `near`est
/// (mean `z`) within [`Z_TOLERANCE`] of 4 where their mean Δφ is at most [`NEAR_JAMMING`], and
/// not judged farther above φ_J.
fn nearest_verdict(packings: &[Contacted], near: &[&Contacted], z: f64) -> (String, Option<bool>) {
    let under = packings.iter().filter(|p| hypostatic(p)).count();
    let distance = near.iter().map(|p| p.excess).sum::<f64>() / near.len() as f64;
    if under > 0 {
        let count = format!("{under} of the {}", packings.len());
        return (
            format!(", but {count} have fewer than 2N′ − 1 contacts, which no jammed packing has: outside"),
            Some(false),
        );
    }
    if distance > NEAR_JAMMING {
        let far =
            format!(": at a mean Δφ of {}, above {NEAR_JAMMING}, too far from φ_J to judge z there", sig(distance));
        return (far, None);
    }
    let ok = (z - ISOSTATIC).abs() <= Z_TOLERANCE;
    (
        format!(
            ", and none of the {} has fewer than 2N′ − 1 contacts: {} {Z_TOLERANCE} of the isostatic {ISOSTATIC} (allowing \
             z − 4 ∝ √Δφ at their mean Δφ, {} ≤ {NEAR_JAMMING})",
            packings.len(),
            if ok { "within" } else { "outside" },
            sig(distance)
        ),
        Some(ok),
    )
}

/// The scalings of every contact law at every N, each against the φ_J of its own law's packings
/// ([`onsets_of`]), in sentences and table rows (the largest N of each law judged).
fn all_scalings(runs: &[&RunRecord]) -> (Vec<String>, Vec<Vec<String>>) {
    let (mut sentences, mut rows) = (Vec::new(), Vec::new());
    for beta in exponents(runs.iter().copied()) {
        let onsets = &onsets_of(runs, beta);
        let sizes = Onset::per_size(onsets);
        let fitted: Vec<(&Onset, Vec<Scaling>)> = sizes
            .iter()
            .map(|size| (size, scalings(runs, size.n, beta, size.fit_floor())))
            .filter(|(_, fitted)| !fitted.is_empty())
            .collect();
        for (i, (size, scalings)) in fitted.iter().enumerate() {
            let judged = i + 1 == fitted.len();
            sentences.push(scalings_sentence(beta, size, scalings, judged));
            for s in scalings {
                rows.push(row(
                    &law_words(beta),
                    size.n,
                    s.quantity,
                    &s.exponent_words(),
                    s.theory,
                    s.points.len(),
                    judged.then(|| s.within()),
                ));
            }
        }
        if let Some((size, largest)) = fitted.last() {
            sentences.extend(correction_sentence(runs, beta, size, largest));
        }
        if let Some((size, largest)) = fitted.last()
            && let Some(ratio) = ratio_against_contacts(runs, size.n, beta, size.fit_floor())
        {
            sentences.push(ratio_sentence(beta, size.n, &ratio, implied_ratio_exponent(largest)));
            rows.push(row(
                &law_words(beta),
                size.n,
                ratio.quantity,
                &ratio.exponent_words(),
                1.0,
                ratio.points.len(),
                Some(ratio.within()),
            ));
        }
    }
    (sentences, rows)
}

/// Fewest packings a refit over the lower decades of Δφ is made from.
const LOWER_DECADES_PACKINGS: usize = 6;

/// How a refitted exponent moved from the whole range's, judged by the shift's own standard
/// error over the seeds ([`Scaling::shift_error`]).
#[derive(Clone, Copy, PartialEq)]
enum Shift {
    /// By more than Student's t standard errors ([`student_t`]), nearer the theory's.
    Towards,
    /// By more than Student's t standard errors, to further from the theory's (past it, or
    /// away from it).
    Away,
    /// By no more than Student's t standard errors, or without one: the refit cannot tell.
    Unclear,
}

/// Whether the judged exponents' distance from the theory's is a correction to scaling, which
/// fades as Δφ → 0: refitted over the lower half of the decades of Δφ measured (up to the
/// geometric mean √(Δφ_min Δφ_max) of the whole fit's), such an exponent moves towards the
/// theory's, by more than Student's t ([`student_t`], at 5 % for the seeds' degrees of freedom)
/// standard errors of its shift (a shift inside its error explains nothing). Said with the largest distance in standard errors over the whole
/// range.
fn correction_sentence(runs: &[&RunRecord], beta: f64, size: &Onset, whole: &[Scaling]) -> Option<String> {
    let spans = whole.iter().flat_map(|s| s.points.iter().map(|p| p.0));
    let (low, high) = crate::measure::extremes(spans);
    let ceiling = (low * high).sqrt();
    let lower = scalings_over(runs, size.n, beta, (size.fit_floor(), ceiling));
    let gap = |s: &Scaling| (s.fit.exponent - s.theory).abs();
    let seeds: Vec<u64> = sorted_distinct(whole.iter().flat_map(|w| w.seeds.iter().copied()));
    let t = student_t(seeds.len().saturating_sub(1));
    let moves: Vec<(&Scaling, &Scaling, Shift, Option<f64>)> = lower
        .iter()
        .filter(|s| s.points.len() >= LOWER_DECADES_PACKINGS)
        .filter_map(|l| {
            let w = whole.iter().find(|w| w.quantity == l.quantity)?;
            let error = w.shift_error(ceiling).filter(|e| *e > 0.0);
            let shift = match error {
                Some(e) if (l.fit.exponent - w.fit.exponent).abs() > t * e => {
                    if gap(l) < gap(w) {
                        Shift::Towards
                    } else {
                        Shift::Away
                    }
                }
                _ => Shift::Unclear,
            };
            Some((l, w, shift, error))
        })
        .collect();
    if moves.is_empty() {
        return None;
    }
    let parts: Vec<String> = moves
        .iter()
        .map(|&(l, w, _, error)| {
            let shift = l.fit.exponent - w.fit.exponent;
            let moved = error.map_or_else(|| format!("{} from it", signed(shift)), |e| plus_minus_signed(shift, e));
            format!("{} {} (from {}, {moved})", l.quantity, l.exponent_words(), sig(w.fit.exponent))
        })
        .collect();
    let widest = whole.iter().filter_map(|w| Some(gap(w) / w.error.filter(|e| *e > 0.0)?)).fold(0.0, f64::max);
    Some(format!(
        "{} contacts, N = {}, refitted over the lower half of the decades of Δφ ({} ≤ Δφ ≤ {}), each with its shift \
         ± the shift's standard error over the seeds (the jackknife), a move only beyond {} of them (Student's t \
         that chance exceeds once in 20 at {} of freedom): {}; {}.",
        words::capitalised(&law_words(beta)),
        size.n,
        sig(size.fit_floor()),
        sig(ceiling),
        sig(t),
        words::counted(seeds.len().saturating_sub(1), "degree"),
        parts.join(", "),
        correction_verdict(&moves.iter().map(|m| (m.0.quantity, m.2)).collect::<Vec<_>>(), widest)
    ))
}

/// What the refit's shifts (quantity, how it moved) tell of a correction to scaling; `widest`
/// the largest distance from the theory's over the whole range, in standard errors.
fn correction_verdict(moves: &[(&str, Shift)], widest: f64) -> String {
    let names =
        |kind: Shift| -> Vec<String> { moves.iter().filter(|m| m.1 == kind).map(|m| m.0.to_string()).collect() };
    let (towards, away, unclear) = (names(Shift::Towards), names(Shift::Away), names(Shift::Unclear));
    if towards.len() == moves.len() {
        return format!(
            "every one moves towards the theory's by more than that: the distance over the whole range (up to {widest:.0} standard errors) is a correction to scaling at larger \
             Δφ, which the tolerance {EXPONENT_TOLERANCE} allows for"
        );
    }
    if unclear.len() == moves.len() {
        return "no shift exceeds that: the refit cannot tell whether the distance is a correction to scaling at \
                larger Δφ"
            .into();
    }
    let verb = |names: &[String], one: &str, several: &str| {
        format!("{} {}", words::listed(names, "and"), if names.len() == 1 { one } else { several })
    };
    let mut clauses = Vec::new();
    if !towards.is_empty() {
        clauses.push(format!(
            "{} towards the theory's by more than that: a correction to scaling at larger Δφ explains {} distance",
            verb(&towards, "moves", "move"),
            if towards.len() == 1 { "its" } else { "their" }
        ));
    }
    if !away.is_empty() {
        clauses.push(format!(
            "{} by more than that but {} further from the theory's: the refit does not bring {} nearer it",
            verb(&away, "shifts", "shift"),
            if away.len() == 1 { "ends" } else { "end" },
            if away.len() == 1 { "it" } else { "them" }
        ));
    }
    if !unclear.is_empty() {
        clauses.push(format!("{} by no more than that: the refit cannot tell", verb(&unclear, "shifts", "shift")));
    }
    clauses.join("; ")
}

/// The exponent of G/K against z − 4 that the fits against Δφ imply: (g − k)/ζ for G ∝ Δφ^g,
/// K ∝ Δφ^k and z − 4 ∝ Δφ^ζ.
fn implied_ratio_exponent(fitted: &[Scaling]) -> Option<f64> {
    let exponent = |name: &str| fitted.iter().find(|s| s.quantity == name).map(|s| s.fit.exponent);
    Some((exponent("G")? - exponent("K")?) / exponent("z − 4")?)
}

/// G/K against the excess coordination in words, with its verdict and the exponent the fits
/// against Δφ imply.
fn ratio_sentence(beta: f64, n: usize, ratio: &Scaling, implied: Option<f64>) -> String {
    let implied = implied.map_or(String::new(), |x| {
        let agree = if (x - ratio.fit.exponent).abs() <= EXPONENT_TOLERANCE { "consistent with" } else { "unlike" };
        format!("; the fits of G, K and z − 4 against Δφ above imply (g − k)/ζ = {}, {agree} it", sig(x))
    });
    format!(
        "{} contacts, N = {n}: G/K ∝ (z − 4)^{} over {} packings, against the theory's 1 (G ∝ K Δz: shear costs what \
         the contacts beyond the isostatic 4 give), {} {EXPONENT_TOLERANCE}{implied}.",
        words::capitalised(&law_words(beta)),
        ratio.exponent_words(),
        ratio.points.len(),
        if ratio.within() { "within" } else { "outside" }
    )
}

/// The item's figures: each packing scene's log–log scalings, then the packings' movies.
fn jamming_figures(e: &Evidence, runs: &[&RunRecord]) -> Vec<FigureRef> {
    packing_scenes(runs)
        .into_iter()
        .flat_map(|scene| e.figures(&[(scene, FigureKind::Jamming), (scene, FigureKind::JammingRatio)]))
        .chain(e.movies(|r| r.spec.packing().is_some()))
        .collect()
}

/// The packing scenes of `runs`, in campaign order.
fn packing_scenes<'a>(runs: &[&'a RunRecord]) -> Vec<&'a str> {
    let mut scenes: Vec<&str> = runs.iter().map(|r| r.spec.scene.as_str()).collect();
    scenes.dedup();
    scenes
}

/// A table row; `ok` `None` for a number not judged.
fn row(
    law: &str,
    n: usize,
    quantity: &str,
    measured: &str,
    theory: f64,
    count: usize,
    ok: Option<bool>,
) -> Vec<String> {
    let verdict = ok.map_or("not judged", |ok| if ok { "within" } else { "outside" });
    vec![law.into(), n.to_string(), quantity.into(), measured.into(), sig(theory), count.to_string(), verdict.into()]
}

/// A table row's verdict: `None` when not judged.
fn judged(row: &[String]) -> Option<bool> {
    match row[6].as_str() {
        "within" => Some(true),
        "outside" => Some(false),
        _ => None,
    }
}

/// The item's verdict from its table: within or outside where some number is held against a
/// reference, observed where none is (another mixture's φ_J, one seed's fit: nothing checked).
fn table_verdict(rows: &[Vec<String>]) -> Verdict {
    let checks: Vec<bool> = rows.iter().filter_map(|r| judged(r)).collect();
    if checks.is_empty() { Verdict::Observed } else { Verdict::of(checks) }
}

/// The summary's line: φ_J of the `largest` N with the fractions its seeds were quenched at
/// and the dependence on them its standard error leaves out ([`Protocol::headline`]), then
/// every judged number of `rows` outside its tolerance (law, N), so that the item's ✗ names
/// what it is for.
fn summary_line(largest: &Onset, protocol: Option<&Protocol>, rows: &[Vec<String>], ratio: f64) -> String {
    let outside: Vec<String> = rows
        .iter()
        .filter(|r| judged(r) == Some(false))
        .map(|r| format!("{} ({}, N = {})", r[2], r[0], r[1]))
        .collect();
    let clause = if outside.is_empty() { String::new() } else { format!("; outside: {}", outside.join(", ")) };
    let against = if ratio == LITERATURE_RATIO {
        format!("against {PHI_J}")
    } else {
        format!("for diameter ratio {}, not 1.4's", number(ratio))
    };
    let quenched = protocol.map_or(String::new(), |p| format!("; {}", p.headline(largest)));
    format!("φ_J = {} (N = {}{quenched}) {against}{clause}", plus_minus(largest.mean, largest.error), largest.n)
}

/// The answer when no quenched packing of the system has its own φ_J: when none jammed,
/// whether they relaxed at all (a packing not relaxed within its budget tells nothing of
/// jamming) and whether O'Hern et al.'s φ_J lies above the fractions reached (nothing should
/// have jammed) or among them; with some jammed ([`jammed_elsewhere`]), an observation.
fn unjammed(any: &[&RunRecord], system: &System) -> Answer {
    let highest = highest_relaxed(any);
    // A packing stopped by its budget is no finding about jamming: nothing is judged.
    let (sentence, verdict, short) = if any.iter().all(|r| r.status != RunStatus::Ok) {
        (String::new(), Verdict::Observed, "no packing relaxed within its budget".to_string())
    } else if let Some((sentence, short)) = jammed_elsewhere(any) {
        (sentence, Verdict::Observed, short)
    } else {
        let below = highest < PHI_J;
        let place = if below {
            "above every fraction relaxed here, so none should jam"
        } else {
            "within the fractions relaxed here, so the packings above it should have jammed"
        };
        (
            format!(
                "No jammed state was found: 0 of the {} (relaxed up to φ = {}) jammed. {CITATION}'s φ_J ≈ {PHI_J} lies \
                 {place}.",
                words::counted(any.len(), "packing"),
                sig(highest)
            ),
            Verdict::of([below]),
            format!("no jammed state up to φ = {}", sig(highest)),
        )
    };
    Answer {
        title: "Jamming",
        question: "Where do random packings of discs jam, and how do p, z, K and G grow above it?",
        short,
        sentences: std::iter::once(sentence)
            .filter(|s| !s.is_empty())
            .chain(not_relaxed_sentence(&system.runs))
            .chain(system.left_out_sentence())
            .collect(),
        reference: format!("{CITATION}: φ_J ≈ {PHI_J} for 1:1.4 bidisperse discs."),
        see_also: None,
        verdict,
        figures: Vec::new(),
        table: None,
    }
}

/// The highest area fraction among `packings` that relaxed (0 where none did).
fn highest_relaxed(packings: &[&RunRecord]) -> f64 {
    let relaxed = packings.iter().filter(|r| r.status == RunStatus::Ok);
    relaxed.filter_map(|r| r.spec.packing().map(|p| p.fraction)).fold(0.0, f64::max)
}

/// Where some of `any` jammed though none is a quench held here with its own φ_J: the
/// sentence and the summary's words. Slowly compressed packings followed another path to their
/// state than O'Hern et al.'s quench, which φ_J and the scalings are defined by; jammed quenches
/// are another mixture's, minimiser's or spring's (the sentence of those left out names them).
/// `None` where none jammed.
fn jammed_elsewhere(any: &[&RunRecord]) -> Option<(String, String)> {
    let (quenches, compressed): (Vec<&RunRecord>, Vec<&RunRecord>) =
        any.iter().partition(|r| r.spec.packing().is_some_and(|p| p.compression.is_none()));
    let count = |packings: &[&RunRecord]| packings.iter().filter(|r| jammed(r)).count();
    let not_fitted =
        "slow compression, which this item does not fit (φ_J and the scalings are O'Hern et al.'s quenches)";
    match (count(&quenches), count(&compressed)) {
        (0, 0) => None,
        (0, slow) => {
            let quenched = match quenches.len() {
                0 => String::new(),
                all => format!(
                    "; none of the {} quenched (relaxed up to φ = {}) jammed",
                    words::counted(all, "packing"),
                    sig(highest_relaxed(&quenches))
                ),
            };
            Some((
                format!(
                    "No φ_J could be found: {} jammed, all made by {not_fitted}{quenched}.",
                    words::counted(slow, "packing")
                ),
                "no φ_J: only slowly compressed packings jammed".into(),
            ))
        }
        (fast, slow) => {
            let also = match slow {
                0 => String::new(),
                _ => format!(" ({slow} more made by {not_fitted})"),
            };
            Some((
                format!(
                    "No φ_J could be found: {fast} of the {} quenched jammed, none of them one held here with its own \
                     φ_J{also}.",
                    words::counted(quenches.len(), "packing")
                ),
                "no φ_J: no quench held here jammed".into(),
            ))
        }
    }
}
