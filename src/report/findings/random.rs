//! The coursework's random networks: bonds cut at random (rigidity against effective-medium
//! theory) or their stiffnesses spread (E against its Voigt and Reuss bounds), each network
//! measured in both directions.

use crate::report::figure::FigureKind;
use crate::report::solids::mean_spread;
use std::collections::{BTreeMap, BTreeSet};

use super::finding::{
    Answer, Evidence, SeeAlso, Table, Verdict, cell, extremes, modulus_name, percent, shear_name, sig,
};
use crate::measure::median;
use crate::report::words::number;
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::spec::LoadCase;

/// Random networks: cut ones' E and G against the fraction of bonds kept, over seeds, and where
/// they lost rigidity; spread ones' E against its bounds; both in each direction.
pub(super) fn random(e: &Evidence) -> Option<Answer> {
    // Square lattices: the other types' dilution is `types::percolation`.
    let runs = e.all(|r| r.spec.lattice().is_some_and(|l| l.cut_fraction > 0.0 && l.lattice_type.is_square()));
    let spread = e.all(|r| r.spec.lattice().is_some_and(|l| l.cut_fraction == 0.0 && l.stiffness_spread > 0.0));
    let bounded = bounded_runs(&spread);
    let within = within_bounds(&bounded);
    let scene = runs.first().or(spread.first())?.spec.scene.clone();
    let mechanisms = runs.iter().filter(|r| r.status == RunStatus::Mechanism).count();
    let cut = format!("{mechanisms} of {} cut runs lost rigidity", runs.len());
    let bounds = format!("E of {within} of {} spread runs within its Voigt and Reuss bounds", bounded.len());
    let sentences = cut_sentences(e, &runs)
        .into_iter()
        .chain(directions_sentence(&runs, "cut"))
        .chain(spread_sentence(&spread, &bounded))
        .chain(directions_sentence(&spread, "spread"))
        .collect();
    let rows = random_rows(&runs)?;
    Some(Answer {
        title: "Random networks",
        question: "(b) Make the system random (cut springs at random, or vary their stiffness): what do you observe?",
        short: match (runs.is_empty(), bounded.is_empty()) {
            (_, true) => cut,
            (true, false) => bounds,
            (false, false) => format!("{cut}; {bounds}"),
        },
        sentences,
        reference: reference(!runs.is_empty(), !bounded.is_empty()),
        see_also: Some(jammed_packings()),
        verdict: if bounded.is_empty() { Verdict::Observed } else { Verdict::of([within == bounded.len()]) },
        figures: e.figure(&scene, FigureKind::Dilution).into_iter().collect(),
        table: cut_table(rows),
    })
}

/// How many cut networks lost rigidity or did not settle, and where rigidity held against
/// effective-medium theory; nothing without cut networks.
fn cut_sentences(e: &Evidence, runs: &[&RunRecord]) -> Vec<String> {
    if runs.is_empty() {
        return Vec::new();
    }
    let mechanisms = runs.iter().filter(|r| r.status == RunStatus::Mechanism).count();
    let unsettled = runs.iter().filter(|r| !matches!(r.status, RunStatus::Mechanism | RunStatus::Ok)).count();
    let carried: Vec<&&RunRecord> = runs.iter().filter(|r| r.status == RunStatus::Ok).collect();
    let floppy = carried.iter().filter(|r| r.metrics.lattice.stiffness_min == Some(0.0)).count();
    vec![
        format!(
            "Cutting bonds at random softens the network and spreads its moduli over seeds; {} of the {} random runs \
             lost their rigidity: their load drives a mechanism (status mechanism, found by the static solver before \
             MD){}. Rigid here means carrying the load: {floppy} of the {} relaxed runs still have floppy modes that \
             their load leaves alone (k_min = 0).",
            mechanisms,
            runs.len(),
            match unsettled {
                0 => String::new(),
                n => format!(
                    ", and {n} more carry it statically but did not end as relaxed (their status in the appendix), so \
                     they give no modulus"
                ),
            },
            carried.len()
        ),
        rigidity_sentence(runs),
    ]
    .into_iter()
    .chain(buckling_sentence(&carried))
    .chain(relaxation_sentence(e, runs))
    .collect()
}

/// A relaxed run whose load buckles its network: the static answer left an unstable
/// equilibrium (`static_descent_steps` > 0) for a stable one.
struct Buckled {
    /// Its run id, cut fraction, seed and load case.
    label: String,
    /// The static answer's modulus over that of the answer of small displacements, less 1
    /// (mostly softer: a negative number).
    change: f64,
    /// MD's modulus over the static answer's, less 1.
    departure: f64,
    /// Whether MD's modulus lies within its relaxation's error bound of the static answer's;
    /// `None` where the run has no bound (k_min = 0, or velocity control).
    within_bound: Option<bool>,
}

/// The relaxed runs among `carried` whose static solve descended from an unstable state, with
/// the modulus each measures (E pulled, G sheared).
fn buckled_runs(carried: &[&&RunRecord]) -> Vec<Buckled> {
    carried
        .iter()
        .filter(|r| r.metrics.lattice.buckled())
        .filter_map(|r| {
            let m = &r.metrics.lattice;
            let (md, fem, linear) = match (m.youngs_modulus_fem, m.shear_modulus_fem) {
                (Some(fem), _) => (m.youngs_modulus?, fem, m.youngs_modulus_linear?),
                (None, Some(fem)) => (m.shear_modulus?, fem, m.shear_modulus_linear?),
                (None, None) => return None,
            };
            let departure = md / fem - 1.0;
            let within_bound = m.relax_error_bound.map(|bound| departure.abs() <= bound);
            let l = r.spec.lattice()?;
            let label = format!("{} (cut {:.2}, seed {}, {})", r.run_id, l.cut_fraction, l.seed, l.load_name());
            Some(Buckled { label, change: fem / linear - 1.0, departure, within_bound })
        })
        .collect()
}

/// Which relaxed cut networks their load buckles: the answer of small displacements is then an
/// unstable equilibrium (a floppy mode under compression), and the static solver and MD each
/// leave it; how far the static answer's modulus moved, and how near MD ended to it. Says so
/// when no network buckles, and how many have no non-linear static answer at all; nothing
/// without relaxed runs.
fn buckling_sentence(carried: &[&&RunRecord]) -> Option<String> {
    let relaxed = match carried.len() {
        0 => return None,
        1 => "the one relaxed run".to_string(),
        n => format!("the {n} relaxed runs"),
    };
    let newton = carried.iter().filter(|r| r.metrics.lattice.static_descent_steps == Some(0)).count();
    let unanswered = match carried.iter().filter(|r| r.metrics.lattice.static_descent_steps.is_none()).count() {
        0 => String::new(),
        n => {
            let (runs, have, its) = if n == 1 {
                ("run", "has", "its linear one stands")
            } else {
                ("runs", "have", "their linear ones stand")
            };
            format!(
                "; {n} relaxed {runs} {have} no non-linear static answer (Newton–Raphson did not converge, even by \
                 descent), and {its}"
            )
        }
    };
    let buckled = buckled_runs(carried);
    if buckled.is_empty() {
        let how = match (newton, carried.len()) {
            (1, 1) => "its static answer came".to_string(),
            (n, all) if n == all => "every static answer came".to_string(),
            (n, _) => format!("{n} of the static answers came"),
        };
        return Some(format!(
            "None of {relaxed} buckles under its load: {how} from the answer of small displacements by \
             Newton–Raphson alone{unanswered}."
        ));
    }
    let names: Vec<&str> = buckled.iter().map(|b| b.label.as_str()).collect();
    let (most, least) = extremes(buckled.iter().map(|b| b.change));
    let change = if buckled.len() == 1 { percent(most) } else { format!("{} to {}", percent(most), percent(least)) };
    Some(format!(
        "{} of {relaxed} {} under {} load ({}): the answer of small displacements is an unstable equilibrium, a \
         floppy mode under compression (the tangent stiffness there is not positive definite), so the static solver \
         descends the potential energy from it to a stable state whose modulus is {change} against it; {}{unanswered}.",
        buckled.len(),
        if buckled.len() == 1 { "buckles" } else { "buckle" },
        if buckled.len() == 1 { "its" } else { "their" },
        names.join("; "),
        md_clause(&buckled),
    ))
}

/// How near MD ended to the buckled runs' static answers: "settles in the same one" only where
/// every run is within its relaxation's error bound.
fn md_clause(buckled: &[Buckled]) -> String {
    let furthest = sig(buckled.iter().map(|b| b.departure.abs()).fold(0.0, f64::max));
    let within = buckled.iter().filter(|b| b.within_bound == Some(true)).count();
    let unbounded = buckled.iter().filter(|b| b.within_bound.is_none()).count();
    match (within, buckled.len()) {
        (n, all) if n == all => {
            let (ones, moduli, each) =
                if all == 1 { ("one", "its modulus", "") } else { ("ones", "their moduli", "each ") };
            format!(
                "MD leaves the unstable state by itself and settles in the same {ones}, within {furthest} of {moduli}, \
                 {each}within its relaxation's error bound"
            )
        }
        (n, all) => format!(
            "MD ends within {furthest} of their moduli: {n} of {all} within their relaxation's error bound{}",
            if unbounded > 0 {
                format!(", {unbounded} without one (k_min = 0 or velocity control)")
            } else {
                String::new()
            }
        ),
    }
}

/// What "relax the system first" means here, and how long the cut networks' relaxation under
/// load took: the median steps of the relaxed runs per cut fraction, the uncut network's of the
/// same scene first (the soft modes cutting leaves relax slowest).
fn relaxation_sentence(e: &Evidence, runs: &[&RunRecord]) -> Option<String> {
    let scenes: Vec<&str> = runs.iter().map(|r| r.spec.scene.as_str()).collect();
    let uncut = e.all(|r| scenes.contains(&r.spec.scene.as_str()) && r.spec.lattice().is_some_and(|l| !l.is_random()));
    let mut by_cut: BTreeMap<u64, Vec<f64>> = BTreeMap::new();
    for r in uncut.iter().chain(runs).filter(|r| r.status == RunStatus::Ok) {
        let cut = r.spec.lattice()?.cut_fraction;
        by_cut.entry((cut * 1000.0).round() as u64).or_default().push(r.steps as f64);
    }
    let steps: Vec<String> = by_cut
        .into_iter()
        .filter_map(|(cut, steps)| {
            let at = if cut == 0 { "uncut".into() } else { format!("at cut {:.2}", cut as f64 / 1000.0) };
            Some(format!("{:.0} {at}", median(steps)?))
        })
        .collect();
    (steps.len() >= 2).then(|| {
        format!(
            "Cut from a stress-free lattice, a network has no stress to relax before its load (the coursework's \
             \"relax the system first\" matters for a network cut under load or pre-stressed); under its load the \
             soft modes cutting leaves relax slowest: the median relaxed run took {} (steps).",
            steps.join(", ")
        )
    })
}

/// The item's reference: effective-medium theory's threshold for cut networks, an observation,
/// and for spread networks measured in tension their rigorous bounds.
fn reference(cut: bool, bounds: bool) -> String {
    let threshold = "Effective-medium theory's rigidity threshold at half the interior bonds kept (p = 1/2); an \
                     observation.";
    let spread = "Each spread network's own bounds on E (Voigt above, Reuss below), rigorous for linear springs at \
                  small strain; no tolerance: MD's E is within its relaxation's error (~1e-6) of the static answer, the \
                  bounds are percent apart.";
    match (cut, bounds) {
        (true, true) => format!("{threshold} {spread}"),
        (_, true) => spread.into(),
        _ => threshold.into(),
    }
}

/// The relaxed spread networks pulled in tension: each with its E (Pa) and its bounds
/// (E_Reuss, E_Voigt) (Pa), `study::lattice`'s `spread_bounds`.
fn bounded_runs<'a>(spread: &[&'a RunRecord]) -> Vec<(&'a RunRecord, f64, (f64, f64))> {
    spread
        .iter()
        .filter(|r| r.status == RunStatus::Ok)
        .filter_map(|r| {
            let l = &r.metrics.lattice;
            Some((*r, l.youngs_modulus?, (l.youngs_modulus_reuss?, l.youngs_modulus_voigt?)))
        })
        .collect()
}

/// How many of the `bounded` runs have their E within their bounds.
fn within_bounds(bounded: &[(&RunRecord, f64, (f64, f64))]) -> usize {
    bounded.iter().filter(|(_, e, (low, high))| low <= e && e <= high).count()
}

/// What spreading the springs does, and each network's E against its own bounds: the mean E
/// and G per spread w over the relaxed networks (both directions), E's mean change from the same
/// networks unspread, the count within the bounds and the nearest approach to one of them,
/// relative to E.
fn spread_sentence(spread: &[&RunRecord], bounded: &[(&RunRecord, f64, (f64, f64))]) -> Option<String> {
    let (first, ..) = bounded.first()?;
    let shear = shear_name(spread);
    let moduli: Vec<String> = spread_means(spread)
        .iter()
        .map(|(w, m)| {
            let change =
                m.softening.map_or_else(String::new, |s| format!(" ({} from the uniform network's)", percent(s)));
            format!("E = {} Pa{change} and {shear} = {} Pa at w = {}", cell(m.youngs), cell(m.shear), number(*w))
        })
        .collect();
    let within = within_bounds(bounded);
    let nearest =
        bounded.iter().map(|(_, e, (low, high))| ((e - low) / e).min((high - e) / e)).fold(f64::INFINITY, f64::min);
    Some(format!(
        "Spreading the stiffnesses instead, k (1 + w U) with U uniform in [−1, 1] and every bond kept ({}): {} (means \
         over the relaxed networks). Each network's E has bounds of its own, from the uniform network's answer under \
         the same load: its bond forces balance the load in the spread network too (Reuss: E ≥ E0/⟨1/(1 + w U)⟩) and \
         its deformation fits it (Voigt: E ≤ E0 ⟨1 + w U⟩), ⟨⟩ weighted by the uniform network's bond energies under \
         this load (so the Voigt bound too may lie below E0). \
         {within} of the {} spread runs in tension ({}) lie within their bounds{}, the nearest {} of E inside one.",
        first.spec.scene,
        moduli.join("; "),
        bounded.len(),
        pulled_words(bounded),
        if within == bounded.len() { "" } else { " (outside: the network or its measurement is wrong)" },
        sig(nearest)
    ))
}

/// Which ways the bounded runs pulled their networks: along y, along x (turned), or both.
fn pulled_words(bounded: &[(&RunRecord, f64, (f64, f64))]) -> &'static str {
    let turned = |r: &RunRecord| r.spec.lattice().is_some_and(|l| l.rotated);
    match (bounded.iter().any(|b| !turned(b.0)), bounded.iter().any(|b| turned(b.0))) {
        (true, true) => "each network along y and along x",
        (false, true) => "pulled along x",
        _ => "pulled along y",
    }
}

/// The spread networks' mean moduli at one spread w.
#[derive(Default)]
struct SpreadMeans {
    /// Mean E (Pa) of the relaxed runs in tension.
    youngs: Option<f64>,
    /// Mean G (Pa) of the relaxed runs in shear.
    shear: Option<f64>,
    /// Mean E/E0 − 1 over the runs in tension, E0 each network's uniform twin's.
    softening: Option<f64>,
}

/// (w, its means) per spread w, in increasing w.
fn spread_means(spread: &[&RunRecord]) -> Vec<(f64, SpreadMeans)> {
    let mut by_width: BTreeMap<u64, [Vec<f64>; 3]> = BTreeMap::new();
    for r in spread.iter().filter(|r| r.status == RunStatus::Ok) {
        let Some(l) = r.spec.lattice() else { continue };
        let m = &r.metrics.lattice;
        let [youngs, shear, softening] = by_width.entry(l.stiffness_spread.to_bits()).or_default();
        youngs.extend(m.youngs_modulus);
        shear.extend(m.shear_modulus);
        softening.extend(m.youngs_modulus.zip(m.youngs_modulus_uniform).map(|(e, e0)| e / e0 - 1.0));
    }
    let mean = |v: &[f64]| mean_spread(v.iter().map(|x| Some(*x))).0;
    by_width
        .iter()
        .map(|(w, [e, g, s])| (f64::from_bits(*w), SpreadMeans { youngs: mean(e), shear: mean(g), softening: mean(s) }))
        .collect()
}

/// One network loaded along y (`tensile`) and along x (`tensile-x`, the same bonds cut or
/// spread): E_x/E_y per level of randomness (`kind`: cut fraction or spread w), its range over
/// the seeds, and the geometric mean of E_x/E_y against 1 with the standard error over the
/// seeds, each seed's ln(E_x/E_y) averaged over its levels first (a seed's networks at every
/// level share its random numbers, so they are not independent samples): random bonds prefer
/// no direction, so the ensemble should not either.
fn directions_sentence(runs: &[&RunRecord], kind: &str) -> Option<String> {
    let ratios = direction_ratios(runs);
    let mut by_level: BTreeMap<u64, Vec<f64>> = BTreeMap::new();
    let mut by_seed: BTreeMap<u64, Vec<f64>> = BTreeMap::new();
    for (level, seed, ratio) in &ratios {
        by_level.entry(level.to_bits()).or_default().push(*ratio);
        by_seed.entry(*seed).or_default().push(ratio.ln());
    }
    if by_seed.len() < 2 {
        return None;
    }
    let ranges: Vec<String> = by_level.iter().map(|(level, r)| range_at(f64::from_bits(*level), r, kind)).collect();
    let seeds = by_seed.values().map(|logs| mean_spread(logs.iter().map(|x| Some(*x))).0);
    let (mean, spread) = mean_spread(seeds);
    let (mean, error) = (mean?, spread? / (by_seed.len() as f64).sqrt());
    Some(format!(
        "Every {kind} network was pulled along y and along x (tensile-x, the block turned), as the coursework asks of \
         random systems: {}; E_x/E_y is {} ({} pairs relaxed both ways){}. By symmetry ln(E_x/E_y) averages 0 over \
         seeds; here the geometric mean of E_x/E_y is {}, its logarithm {} ± {} (mean ± standard error over {} \
         seeds, each seed's levels averaged first: they share its random numbers), {}.",
        if kind == "cut" {
            "the same interior bonds are cut, but each loading keeps its own loaded and held edges whole, so a seed's \
             two are one network only in the interior and their ratio mixes its anisotropy with their edges' \
             difference"
        } else {
            "the same bonds spread, one network both ways"
        },
        ranges.join(", "),
        ratios.len(),
        poisson_words(runs),
        sig(mean.exp()),
        sig(mean),
        sig(error),
        by_seed.len(),
        if mean.abs() <= 2.0 * error {
            "within 2 standard errors of 0: one network differs by direction, and on average none is preferred"
        } else {
            "more than 2 standard errors from 0: these networks lean one way on average, by chance (one time in 20 \
             for networks that prefer no direction) or by a preferred direction (the edge bands each loading keeps \
             whole)"
        }
    ))
}

/// Poisson's ratio by direction: ν_yx (pulled along y) and ν_xy (along x) over every relaxed
/// run in tension, as their ranges.
fn poisson_words(runs: &[&RunRecord]) -> String {
    let mut along: [Vec<f64>; 2] = Default::default();
    for r in runs.iter().filter(|r| r.status == RunStatus::Ok) {
        if let (Some(l), Some(nu)) = (r.spec.lattice(), r.metrics.lattice.poisson_ratio) {
            along[usize::from(l.rotated)].push(nu);
        }
    }
    let range = |v: &[f64]| {
        let (low, high) = extremes(v);
        format!("{} to {}", sig(low), sig(high))
    };
    match along {
        [y, x] if !y.is_empty() && !x.is_empty() => {
            format!(", and Poisson's ratio ν_yx {} against ν_xy {}", range(&y), range(&x))
        }
        _ => String::new(),
    }
}

/// "a to b at cut 0.30" (or "a at w = 0.5" for one network) of the ratios `r` at `level`.
fn range_at(level: f64, r: &[f64], kind: &str) -> String {
    let (low, high) = extremes(r);
    let at = if kind == "cut" { format!("cut {level:.2}") } else { format!("w = {}", number(level)) };
    if r.len() == 1 { format!("{} at {at}", sig(low)) } else { format!("{} to {} at {at}", sig(low), sig(high)) }
}

/// One random network: its level of randomness, its seed, and E loaded along y and along x.
type DirectionPair = (f64, u64, [Option<f64>; 2]);

/// (randomness level, seed, E_x/E_y) of each network relaxed in both directions: runs of one
/// scene and the same grid values but the load case, one `tensile` and one `tensile-x`.
fn direction_ratios(runs: &[&RunRecord]) -> Vec<(f64, u64, f64)> {
    // (scene, grid values but the load case) → (level, seed, [E_y, E_x]).
    let mut networks: BTreeMap<(String, String), DirectionPair> = BTreeMap::new();
    for r in runs.iter().filter(|r| r.status == RunStatus::Ok) {
        let Some(l) = r.spec.lattice().filter(|l| l.load_case == LoadCase::Tensile) else { continue };
        let key = (r.spec.scene.clone(), r.spec.varied_in_words(|path| path != "load.case"));
        let level = if l.cut_fraction > 0.0 { l.cut_fraction } else { l.stiffness_spread };
        networks.entry(key).or_insert((level, l.seed, [None; 2])).2[usize::from(l.rotated)] =
            r.metrics.lattice.youngs_modulus;
    }
    networks.values().filter_map(|(level, seed, [y, x])| Some((*level, *seed, x.as_ref()? / y.as_ref()?))).collect()
}

/// Where the random solid goes on: a granular material's random solid is a jammed packing of
/// discs whose contacts come and go, the jamming campaign's subject.
fn jammed_packings() -> SeeAlso {
    SeeAlso {
        text: "In granular matter the random solid is a jammed packing of discs whose contacts come and go, rigid \
               above φ_J ≈ 0.842 with z → 4 contacts each (the cut networks' threshold 2d); the jamming campaign \
               states φ_J, z and the scalings of p, z − 4, K and G against O'Hern et al. (2003)."
            .into(),
        campaign: "campaigns/jamming.yaml",
        page: "../jamming/index.html",
        written: false,
    }
}

/// The cut networks' table of `rows` ([`random_rows`]); its network column only where the rows
/// span more than one network (one network is the scene's own, named above).
fn cut_table(mut rows: Vec<Vec<String>>) -> Option<Table> {
    let first = rows.first()?.clone();
    let mut header: Vec<String> = [
        "load",
        "network",
        "cut fraction",
        "rigid seeds",
        "kept of all bonds (rigid seeds)",
        "modulus mean over relaxed seeds (Pa)",
        "standard deviation (Pa)",
    ]
    .map(String::from)
    .to_vec();
    if rows.iter().all(|row| row[1] == first[1]) {
        header.remove(1);
        for row in &mut rows {
            row.remove(1);
        }
    }
    Some(Table { header, rows })
}

/// One row per load case, network and cut fraction: how many seeds stayed rigid, their kept
/// fraction and the moduli's mean and sample standard deviation over them only (a floppy seed has
/// no modulus, and one seed no deviation: a dash).
fn random_rows(runs: &[&RunRecord]) -> Option<Vec<Vec<String>>> {
    // Keyed by what the runs measure too: a campaign's shear on two kinds of supports is two rows
    // (the shear modulus is named for its supports), and so is its tension; and by the network,
    // so that seeds of one lattice (not of two) make each mean.
    let mut by_cut: BTreeMap<(String, String, u64), Vec<&RunRecord>> = BTreeMap::new();
    let scenes: BTreeSet<&str> = runs.iter().map(|r| r.spec.scene.as_str()).collect();
    let supports: BTreeSet<&str> = runs.iter().filter_map(|r| r.spec.lattice()).map(|l| l.supports.name()).collect();
    for r in runs {
        let l = r.spec.lattice()?;
        let mut measured = format!("{}: {}", l.load_name(), modulus_name(l));
        if supports.len() > 1 && l.load_case != LoadCase::Shear {
            measured += &format!(" ({} supports)", l.supports.name());
        }
        let network = network_words(r, scenes.len() > 1);
        by_cut.entry((measured, network, (l.cut_fraction * 1000.0).round() as u64)).or_default().push(r);
    }
    let kept = |rs: &[&&RunRecord]| {
        let fractions: Vec<f64> = rs.iter().filter_map(|r| r.metrics.lattice.bond_fraction_kept).collect();
        (!fractions.is_empty()).then(|| fractions.iter().sum::<f64>() / fractions.len() as f64)
    };
    let rows = by_cut
        .iter()
        .map(|((case, network, cut), rs)| {
            // A mechanism stops before its bonds are counted: only rigid seeds know their kept fraction.
            let rigid: Vec<&&RunRecord> = rs.iter().filter(|r| r.status != RunStatus::Mechanism).collect();
            let (mean, spread) = mean_spread(
                rigid
                    .iter()
                    .filter(|r| r.status == RunStatus::Ok)
                    .map(|r| r.metrics.lattice.youngs_modulus.or(r.metrics.lattice.shear_modulus)),
            );
            vec![
                case.clone(),
                network.clone(),
                format!("{:.2}", *cut as f64 / 1000.0),
                format!("{}/{}", rigid.len(), rs.len()),
                kept(&rigid).map_or_else(|| "–".into(), |k| format!("{k:.3}")),
                cell(mean),
                cell(spread),
            ]
        })
        .collect();
    Some(rows)
}

/// The network of a cut run in words: its grid values but the seed, the cut fraction, the load
/// case and the supports, which the load column names ("no diagonals", "k_d/k = 0.5, 16 × 16"),
/// as the dilution figure labels its series; after its scene's name when `with_scene` (the cut
/// runs span several scenes), and the scene's name alone where its grid varies nothing else.
fn network_words(r: &RunRecord, with_scene: bool) -> String {
    let network =
        r.spec.varied_in_words(|path| !matches!(path, "seed" | "lattice.cut_fraction" | "load.case" | "supports"));
    match (with_scene, network.is_empty()) {
        (false, false) => network,
        (true, false) => format!("{}: {network}", r.spec.scene),
        (_, true) => r.spec.scene.clone(),
    }
}

/// Where the cut networks lost rigidity against effective-medium theory's threshold: a
/// central-force network is rigid while its mean coordination is above 2d = 4, half the 8 bonds
/// per node of the square lattice with both diagonals. Measured, as in the dilution figure, by
/// the kept fraction p = 1 − cut fraction of the interior bonds (the edges' bonds are never cut,
/// so a network's share of all its bonds is larger): the sparsest network still rigid and the
/// densest that lost rigidity say on which side of p = 1/2 this campaign's networks held.
fn rigidity_sentence(runs: &[&RunRecord]) -> String {
    let kept = |r: &&RunRecord| r.spec.lattice().map_or(f64::NAN, |l| 1.0 - l.cut_fraction);
    // Rigid as the static solver finds it (the table's "rigid seeds"), relaxed or not.
    let lowest_rigid = runs.iter().filter(|r| r.status != RunStatus::Mechanism).map(kept).reduce(f64::min);
    let highest_lost = runs.iter().filter(|r| r.status == RunStatus::Mechanism).map(kept).reduce(f64::max);
    let theory = "Effective-medium theory for central-force networks puts the loss of rigidity where the mean \
                  coordination reaches twice the dimension, 4, a kept fraction p = 4/8 = 1/2 of the square lattice with both \
                  diagonals (p counts the interior bonds, which alone are cut, as in the figure; it is the \
                  probability that each is kept, and a network's own share scatters about it).";
    let held = match (lowest_rigid, highest_lost) {
        (Some(p), _) if p < 0.5 => format!(
            " A network kept at p = {p:.2}, below 1/2, still stayed rigid: a finite network whose edges are not cut \
             keeps some rigidity beyond the threshold."
        ),
        (Some(p), Some(lost)) => mixed_words(runs, p, lost),
        (Some(p), None) => format!(
            " Every network here stayed rigid, down to p = {p:.2}: the campaign cuts no network as far as the \
             threshold."
        ),
        (None, _) => " No cut network stayed rigid here.".into(),
    };
    format!("{theory}{held}")
}

/// Where rigidity was lost, as a kept fraction p falls: the sparsest rigid network at p, the
/// densest that lost rigidity at `lost`; where the two levels meet, how many of that level's
/// networks went each way.
fn mixed_words(runs: &[&RunRecord], p: f64, lost: f64) -> String {
    let at_threshold = |x: f64| if (x - 0.5).abs() < 0.01 { " (the threshold itself)" } else { "" };
    if lost < p - 1e-9 {
        return format!(
            " Here rigidity held down to p = {p:.2} and was first lost at p = {lost:.2}{}.",
            at_threshold(lost)
        );
    }
    let at_p = |r: &&&RunRecord| r.spec.lattice().is_some_and(|l| (1.0 - l.cut_fraction - p).abs() < 1e-9);
    let level: Vec<&RunRecord> = runs.iter().filter(at_p).copied().collect();
    let denser = if lost > p + 1e-9 {
        let also = if level.iter().any(|r| r.status == RunStatus::Mechanism) { " too" } else { "" };
        format!("; denser networks lost it{also}, up to p = {lost:.2}")
    } else {
        "; every denser network stayed rigid".into()
    };
    format!(" At p = {p:.2}{}, {}{denser}.", at_threshold(p), rigid_counts(&level))
}

/// "the networks stayed rigid in 2 of 4 pulled along y, 1 of 4 pulled along x": one count per
/// load case, since each network is loaded in every case of the campaign and may hold in one only.
fn rigid_counts(level: &[&RunRecord]) -> String {
    let mut by_case: BTreeMap<&str, (usize, usize)> = BTreeMap::new();
    for r in level {
        let case = r.spec.lattice().map_or("", |l| l.load_name());
        let (rigid, all) = by_case.entry(case).or_default();
        *rigid += usize::from(r.status != RunStatus::Mechanism);
        *all += 1;
    }
    let loaded = |case: &str| match case {
        "tensile" => "pulled along y",
        "tensile-x" => "pulled along x",
        _ => "sheared",
    };
    let counts: Vec<String> =
        by_case.iter().map(|(case, (rigid, all))| format!("{rigid} of {all} {}", loaded(case))).collect();
    let single = by_case.len() == 1;
    match by_case.values().next() {
        Some(&(rigid, all)) if single => {
            format!("{rigid} of {all} networks stayed rigid and {} lost rigidity", all - rigid)
        }
        _ => format!("the networks stayed rigid in {}", counts.join(", ")),
    }
}
