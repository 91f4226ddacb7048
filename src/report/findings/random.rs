//! The coursework's random networks: bonds cut at random (rigidity against effective-medium
//! theory) or their stiffnesses spread (E against its Voigt and Reuss bounds), each network
//! measured in both directions.

use crate::measure::mean_spread;
use crate::report::figure::FigureKind;
use std::collections::{BTreeMap, BTreeSet};

use super::finding::{
    Answer, Evidence, SeeAlso, Table, Verdict, cell, extremes, modulus_name, percent, shear_name, sig,
};
use crate::measure::{median, sorted_distinct};
use crate::report::words::number;
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::spec::LoadCase;

/// Random networks: cut ones' E and G against the fraction of bonds kept, over seeds, and where
/// they lost rigidity; spread ones' E against its bounds; both in each direction.
pub(super) fn random(e: &Evidence) -> Option<Answer> {
    // Square lattices: the other types' dilution is `types::percolation`.
    // Loaded networks only: a kicked one carries no load to lose and is not relaxed (its front
    // speed is the waves' item's).
    fn loaded(r: &RunRecord) -> Option<&crate::spec::LatticeSpec> {
        r.spec.lattice().filter(|l| l.impulse.is_none())
    }
    let runs = e.all(|r| loaded(r).is_some_and(|l| l.cut_fraction > 0.0 && l.lattice_type.is_square()));
    let spread = e.all(|r| loaded(r).is_some_and(|l| l.cut_fraction == 0.0 && l.stiffness_spread > 0.0));
    let ordered = ordered_ratios(&e.all(|r| loaded(r).is_some_and(|l| !l.is_random())));
    let kicked = e.all(|r| {
        r.spec.lattice().is_some_and(|l| l.impulse.is_some() && l.lattice_type.is_square())
            && r.metrics.recommended_sound_speed().is_some()
    });
    let fronts = kicked_sentences(&kicked);
    let bounded = bounded_runs(&spread);
    let within = within_bounds(&bounded);
    let scene = match runs.first().or(spread.first()) {
        Some(r) => r.spec.scene.clone(),
        None => fronts.first()?.0.clone(),
    };
    let mechanisms = runs.iter().filter(|r| r.status == RunStatus::Mechanism).count();
    let cut = format!("{mechanisms} of {} cut runs lost rigidity", runs.len());
    let bounds = format!("E of {within} of {} spread runs within its Voigt and Reuss bounds", bounded.len());
    let sentences = cut_sentences(e, &runs)
        .into_iter()
        .chain(directions_sentence(&runs, "cut", &ordered))
        .chain(spread_sentence(&spread, &bounded))
        .chain(directions_sentence(&spread, "spread", &ordered))
        .chain(fronts.into_iter().map(|(_, sentence)| sentence))
        .collect();
    let rows = random_rows(&runs).unwrap_or_default();
    Some(Answer {
        title: "Random networks",
        question: "(b) Make the system random (cut springs at random, or vary their stiffness): what do you observe?",
        short: match (runs.is_empty(), bounded.is_empty()) {
            (true, true) => "the front of a kicked network, ordered and random".into(),
            (false, true) => cut,
            (true, false) => bounds,
            (false, false) => format!("{cut}; {bounds}"),
        },
        sentences,
        reference: reference(&runs, !bounded.is_empty(), !kicked.is_empty()),
        see_also: Some(jammed_packings()),
        verdict: if bounded.is_empty() { Verdict::Observed } else { Verdict::of([within == bounded.len()]) },
        figures: e.figure(&scene, FigureKind::Dilution).into_iter().collect(),
        table: cut_table(rows),
    })
}

/// Kicked networks, per scene with random ones (cut or spread): the front's speed (m/s, by the
/// scene's timing criterion) at each level of randomness over its seeds, from the ordered
/// network's (level 0) up, against c_L; and which way it went. (scene, sentence) each.
fn kicked_sentences(kicked: &[&RunRecord]) -> Vec<(String, String)> {
    let mut scenes: BTreeMap<&str, BTreeMap<u64, Vec<f64>>> = BTreeMap::new();
    let mut cut = BTreeSet::new();
    for r in kicked {
        let Some(l) = r.spec.lattice() else { continue };
        let level = if l.cut_fraction > 0.0 { l.cut_fraction } else { l.stiffness_spread };
        if l.cut_fraction > 0.0 {
            cut.insert(r.spec.scene.as_str());
        }
        let speeds = scenes.entry(&r.spec.scene).or_default().entry(level.to_bits()).or_default();
        speeds.extend(r.metrics.recommended_sound_speed());
    }
    scenes
        .into_iter()
        .filter(|(_, levels)| levels.keys().any(|&level| level != 0))
        .map(|(scene, levels)| {
            let kind = if cut.contains(scene) { "cut" } else { "spread" };
            let theory = kicked.iter().find(|r| r.spec.scene == scene).and_then(|r| r.metrics.sound_speed_theory);
            (scene.to_string(), front_words(scene, kind, &levels, theory))
        })
        .collect()
}

/// "… 1.291 m/s ordered, 0.8263 to 1.023 m/s at cut 0.20 …: slower as more is cut".
fn front_words(scene: &str, kind: &str, levels: &BTreeMap<u64, Vec<f64>>, theory: Option<f64>) -> String {
    let words: Vec<String> = levels
        .iter()
        .map(|(&level, speeds)| match f64::from_bits(level) {
            0.0 => format!("{} m/s ordered", listed_range(speeds)),
            level => range_at(level, speeds, kind).replacen(" at", " m/s at", 1),
        })
        .collect();
    let median_at = |speeds: Option<&Vec<f64>>| speeds.and_then(|s| median(s.clone()));
    let (first, last) = (median_at(levels.values().next()), median_at(levels.values().last()));
    let trend = match (first, last) {
        (Some(a), Some(b)) if b < 0.95 * a => {
            format!(": the front slows as more is {kind}, its median {} of the {}'s", sig(b / a), least(kind, levels))
        }
        (Some(a), Some(b)) if b > 1.05 * a => format!(
            ": the front speeds up as more is {kind}, its median {} times the least {kind} network's",
            sig(b / a)
        ),
        (Some(_), Some(_)) => {
            format!(": the {kind} networks carry the front as fast as the {}, within 5 %", least(kind, levels))
        }
        _ => String::new(),
    };
    let c_l = theory.map_or(String::new(), |c| format!(" (the continuum's c_L = {} m/s)", sig(c)));
    format!(
        "Given an impulse instead of a load, the {kind} networks of scene {scene} carry the front to the bottom row at \
         {}{c_l}{trend}.",
        crate::report::words::listed(&words, "and")
    )
}

/// The network the others are measured against: the ordered one, or the least random.
fn least(kind: &str, levels: &BTreeMap<u64, Vec<f64>>) -> String {
    if levels.contains_key(&0.0_f64.to_bits()) { "ordered network".into() } else { format!("least {kind} network") }
}

/// "1.291" for one speed or equal ones, "0.83 to 1.02" for several.
fn listed_range(speeds: &[f64]) -> String {
    let (low, high) = extremes(speeds);
    if low == high { sig(low) } else { format!("{} to {}", sig(low), sig(high)) }
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
fn reference(cut: &[&RunRecord], bounds: bool, kicked: bool) -> String {
    let zs: Vec<u32> = sorted_distinct(cut.iter().map(|r| coordination_of(r)));
    let threshold = match zs[..] {
        [] => None,
        [8] => Some(
            "Effective-medium theory's rigidity threshold at half the interior bonds kept (p = 1/2); an \
                     observation."
                .to_string(),
        ),
        _ => Some(format!(
            "Effective-medium theory's rigidity threshold at a kept fraction 4/z of the interior bonds ({}); an \
             observation.",
            crate::report::words::listed(
                &zs.iter().rev().map(|&z| format!("{} at z = {z}", threshold_words(z).0)).collect::<Vec<_>>(),
                "and"
            )
        )),
    };
    let spread = "Each spread network's own bounds on E (Voigt above, Reuss below), rigorous for linear springs at \
                  small strain; no tolerance: MD's E is within its relaxation's error (~1e-6) of the static answer, the \
                  bounds are percent apart.";
    let fronts = "The ordered network's front and the continuum's c_L; an observation.";
    let parts =
        [threshold.as_deref(), bounds.then_some(spread), (kicked && threshold.is_none() && !bounds).then_some(fronts)];
    parts.into_iter().flatten().collect::<Vec<_>>().join(" ")
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
/// the seeds, and the geometric mean of E_x/E_y against what the springs make it without
/// randomness, with the standard error over the seeds, each seed's logarithm averaged over its
/// levels first (a seed's networks at every level share its random numbers). Springs alike
/// both ways (k_x = k_y) make it 1 by symmetry; springs that differ make it the ordered
/// network's own ratio (`ordered`), and without that network the sentence tests nothing.
fn directions_sentence(runs: &[&RunRecord], kind: &str, ordered: &BTreeMap<String, f64>) -> Option<String> {
    let ratios = direction_ratios(runs);
    let mut by_level: BTreeMap<u64, Vec<f64>> = BTreeMap::new();
    let mut by_seed: BTreeMap<u64, Vec<f64>> = BTreeMap::new();
    let mut unreferenced = BTreeSet::new();
    for d in &ratios {
        by_level.entry(d.level.to_bits()).or_default().push(d.ratio);
        match d.expected(ordered) {
            Some(expected) => by_seed.entry(d.seed).or_default().push((d.ratio / expected).ln()),
            None => _ = unreferenced.insert(d.network.clone()),
        }
    }
    let ranges: Vec<String> = by_level.iter().map(|(level, r)| range_at(f64::from_bits(*level), r, kind)).collect();
    let opening = format!(
        "Every {kind} network was pulled along y and along x (tensile-x, the block turned), as the coursework asks of \
         random systems: {}; E_x/E_y is {} ({} pairs relaxed both ways){}.",
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
    );
    if !unreferenced.is_empty() {
        return (ratios.len() > 1).then(|| format!("{opening}{}", unreferenced_words(&ratios, ordered)));
    }
    if by_seed.len() < 2 {
        return None;
    }
    Some(format!("{opening} {}", lean_words(&ratios, &by_seed)?))
}

/// The springs' own direction, where no ordered network of the same springs ran to measure it.
fn unreferenced_words(ratios: &[DirectionRatio], ordered: &BTreeMap<String, f64>) -> String {
    let ratio = ratios.iter().find(|d| d.expected(ordered).is_none()).map_or(1.0, |d| d.springs);
    format!(
        " Their springs differ by direction (k_y/k_x = {}), so E_x/E_y ≠ 1 without any randomness; no network of the \
         same springs uncut and unspread ran here to measure that ratio, so whether the randomness makes them lean \
         one way is not tested.",
        number(ratio)
    )
}

/// Whether the networks lean one way on average: the geometric mean of E_x/E_y over the
/// expected ratio, over the seeds (`by_seed`: each seed's logarithms), against 1.
fn lean_words(ratios: &[DirectionRatio], by_seed: &BTreeMap<u64, Vec<f64>>) -> Option<String> {
    let seeds = by_seed.values().map(|logs| mean_spread(logs.iter().map(|x| Some(*x))).0);
    let (mean, spread) = mean_spread(seeds);
    let (mean, error) = (mean?, spread? / (by_seed.len() as f64).sqrt());
    let symmetric = ratios.iter().all(|d| d.springs == 1.0);
    let expected = if symmetric {
        "By symmetry ln(E_x/E_y) averages 0 over seeds; here the geometric mean of E_x/E_y is".to_string()
    } else {
        "Their springs differ by direction, so the reference is the ordered network of the same springs (no bond cut \
         or spread), whose own E_x/E_y the random ones scatter about: ln of the ratio to it averages 0 over seeds; \
         here the geometric mean of E_x/E_y over it is"
            .to_string()
    };
    Some(format!(
        "{expected} {}, its logarithm {} ± {} (mean ± standard error over {} seeds, each seed's levels averaged first: \
         they share its random numbers), {}.",
        sig(mean.exp()),
        sig(mean),
        sig(error),
        by_seed.len(),
        match (mean.abs() <= 2.0 * error, symmetric) {
            (true, true) =>
                "within 2 standard errors of 0: one network differs by direction, and on average none is \
                             preferred",
            (true, false) =>
                "within 2 standard errors of 0: one network differs from the ordered one, and on \
                              average the randomness keeps the springs' own ratio",
            (false, true) =>
                "more than 2 standard errors from 0: these networks lean one way on average, by chance \
                              (one time in 20 for networks that prefer no direction) or by a preferred direction \
                              (the edge bands each loading keeps whole)",
            (false, false) =>
                "more than 2 standard errors from 0: the randomness moves E_x/E_y away from the \
                               springs' own ratio on average, by chance (one time in 20) or because it softens one \
                               direction more (the edge bands each loading keeps whole, or the stiffer springs' \
                               share of the load)",
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

/// One network relaxed both ways: its level of randomness (cut fraction or spread w), its
/// seed, E_x/E_y, the ordered network it is a random copy of ([`ordered_key`]) and its springs'
/// k_y/k_x.
struct DirectionRatio {
    level: f64,
    seed: u64,
    ratio: f64,
    network: String,
    springs: f64,
}

impl DirectionRatio {
    /// The E_x/E_y its springs alone make: 1 where they are alike both ways, else the ordered
    /// network's, if it ran.
    fn expected(&self, ordered: &BTreeMap<String, f64>) -> Option<f64> {
        if self.springs == 1.0 { Some(1.0) } else { ordered.get(&self.network).copied() }
    }
}

/// A network and its E pulled along y and along x (Pa), as they are found.
type Pulled = (DirectionRatio, [Option<f64>; 2]);

/// Each network relaxed in both directions: runs of one scene and the same grid values but the
/// load case, one `tensile` and one `tensile-x`.
fn direction_ratios(runs: &[&RunRecord]) -> Vec<DirectionRatio> {
    // (scene, grid values but the load case) → (the network, [E_y, E_x]).
    let mut networks: BTreeMap<(String, String), Pulled> = BTreeMap::new();
    for r in runs.iter().filter(|r| r.status == RunStatus::Ok) {
        let Some(l) = r.spec.lattice().filter(|l| l.load_case == LoadCase::Tensile) else { continue };
        let key = (r.spec.scene.clone(), r.spec.varied_in_words(|path| path != "load.case"));
        let upright = l.upright();
        let network = DirectionRatio {
            level: if l.cut_fraction > 0.0 { l.cut_fraction } else { l.stiffness_spread },
            seed: l.seed,
            ratio: f64::NAN,
            network: ordered_key(r),
            springs: upright.k_y / upright.k_x,
        };
        networks.entry(key).or_insert((network, [None; 2])).1[usize::from(l.rotated)] =
            r.metrics.lattice.youngs_modulus;
    }
    networks.into_values().filter_map(|(network, [y, x])| Some(DirectionRatio { ratio: x? / y?, ..network })).collect()
}

/// The network of a loaded lattice run without its randomness (cut, spread, seed) or its
/// direction, with its springs' law, stiffness and masses: runs of one key are random copies of
/// one ordered network.
fn ordered_key(r: &RunRecord) -> String {
    let Some(mut l) = r.spec.lattice().map(|l| l.upright()) else { return String::new() };
    (l.cut_fraction, l.stiffness_spread, l.seed) = (0.0, 0.0, 0);
    format!("{l:?} {:?} {} {} {}", r.spec.law, r.spec.k, r.spec.mass, r.spec.spacing)
}

/// E_x/E_y of each ordered network (no bond cut or spread) relaxed both ways, by its key.
fn ordered_ratios(runs: &[&RunRecord]) -> BTreeMap<String, f64> {
    direction_ratios(runs).into_iter().map(|d| (d.network, d.ratio)).collect()
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
/// central-force network is rigid while its mean coordination is above 2d = 4, so a square
/// lattice of z bonds per node uncut (8 with both diagonals, 6 with one family, 4 with none)
/// loses it at a kept fraction p_c = 4/z. Measured, as in the dilution figure, by the kept
/// fraction p = 1 − cut fraction of the interior bonds (the edges' bonds are never cut, so a
/// network's share of all its bonds is larger): per z, the sparsest network still rigid and the
/// densest that lost rigidity say on which side of p_c this campaign's networks held.
fn rigidity_sentence(runs: &[&RunRecord]) -> String {
    let mut by_z: BTreeMap<u32, Vec<&RunRecord>> = BTreeMap::new();
    for r in runs {
        by_z.entry(coordination_of(r)).or_default().push(r);
    }
    let named = by_z.len() > 1;
    let held: String = by_z.iter().rev().map(|(&z, group)| held_words(group, z, named)).collect();
    format!("{}{held}", theory_words(&by_z.keys().copied().collect::<Vec<_>>()))
}

/// The bonds per node of a run's lattice uncut (z, `LatticeSpec::coordination`).
fn coordination_of(r: &RunRecord) -> u32 {
    r.spec.lattice().map_or(4, |l| l.coordination() as u32)
}

/// The threshold p_c = 4/z as a fraction, and the lattice it belongs to.
fn threshold_words(z: u32) -> (&'static str, &'static str) {
    match z {
        8 => ("1/2", "with both diagonals"),
        6 => ("2/3", "with one diagonal family"),
        _ => ("1", "without diagonals"),
    }
}

/// Effective-medium theory's threshold for the lattices of coordinations `zs` (uncut).
fn theory_words(zs: &[u32]) -> String {
    let rule = "Effective-medium theory for central-force networks puts the loss of rigidity where the mean \
                coordination reaches twice the dimension, 4";
    let counted = "(p counts the interior bonds, which alone are cut, as in the figure; it is the probability that \
                   each is kept, and a network's own share scatters about it).";
    if zs == [8] {
        return format!("{rule}, a kept fraction p = 4/8 = 1/2 of the square lattice with both diagonals {counted}");
    }
    let levels: Vec<String> = zs
        .iter()
        .rev()
        .map(|&z| {
            let (p, lattice) = threshold_words(z);
            format!("p = {p} {lattice} (z = {z})")
        })
        .collect();
    format!("{rule}: a kept fraction p = 4/z of a square lattice of z bonds per node, {} {counted}", levels.join(", "))
}

/// Where the networks of one coordination `z` held against its threshold 4/z, after the
/// lattice's name when the campaign cuts lattices of several.
fn held_words(runs: &[&RunRecord], z: u32, named: bool) -> String {
    let threshold = 4.0 / f64::from(z);
    let (words, lattice) = threshold_words(z);
    let kept = |r: &&RunRecord| r.spec.lattice().map_or(f64::NAN, |l| 1.0 - l.cut_fraction);
    // Rigid as the static solver finds it (the table's "rigid seeds"), relaxed or not.
    let lowest_rigid = runs.iter().filter(|r| r.status != RunStatus::Mechanism).map(kept).reduce(f64::min);
    let highest_lost = runs.iter().filter(|r| r.status == RunStatus::Mechanism).map(kept).reduce(f64::max);
    let name = if named { format!(" The lattices {lattice} (z = {z}, threshold p = {words}):") } else { String::new() };
    let held = match (lowest_rigid, highest_lost) {
        (Some(p), _) if p < threshold - 1e-9 => format!(
            " A network kept at p = {p:.2}, below {words}, still stayed rigid: a finite network whose edges are not \
             cut keeps some rigidity beyond the threshold."
        ),
        (Some(p), Some(lost)) => mixed_words(runs, p, lost, threshold),
        (Some(p), None) => format!(
            " Every network here stayed rigid, down to p = {p:.2}: the campaign cuts no network as far as the \
             threshold."
        ),
        (None, _) => " No cut network stayed rigid here.".into(),
    };
    format!("{name}{held}")
}

/// Where rigidity was lost, as a kept fraction p falls: the sparsest rigid network at p, the
/// densest that lost rigidity at `lost`; where the two levels meet, how many of that level's
/// networks went each way. `threshold` is effective-medium theory's p_c.
fn mixed_words(runs: &[&RunRecord], p: f64, lost: f64, threshold: f64) -> String {
    let at_threshold = |x: f64| if (x - threshold).abs() < 0.01 { " (the threshold itself)" } else { "" };
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
