//! Time to a modulus: loaded lattices brought to rest until the displacement bound
//! (`relax.tolerance`) certifies their modulus, by damped MD, critical background damping,
//! FIRE and CG, each against the critically damped bound in steps and the static answer of the
//! same network.

use super::discussion::Paragraph;
use super::finding::{Answer, Evidence, Table, Verdict, cell, extremes, relative, sig};
use crate::measure::{power_law_fit, sorted_distinct};
use crate::runner::RunRecord;
use crate::sim::{PreconditionerKind, RelaxMethod, RunStatus};
use crate::study::lattice::critical_bound_steps;

/// A critically damped run must end within this many critically damped bounds (issue 17).
const CRITICAL_STEPS_ALLOWED: f64 = 2.0;

/// A loaded lattice run stopped by the displacement bound: a tolerance, and MD or a minimiser
/// (a static-only run has nothing to bound).
fn bounded(r: &RunRecord) -> bool {
    r.spec.lattice().is_some_and(|l| l.impulse.is_none())
        && r.spec.relax().is_some_and(|relax| relax.tolerance.is_some() && relax.method != RelaxMethod::Static)
}

/// How a run came to rest, in words.
fn method(r: &RunRecord) -> String {
    match r.spec.relax() {
        Some(relax) if relax.critical_background => "critical damping".into(),
        Some(relax) if relax.method == RelaxMethod::Damped => {
            let dashpot = if r.spec.gamma > 0.0 { ", dashpots" } else { "" };
            format!("damped MD (γ_g {} N s/m{dashpot})", sig(r.spec.gamma_background))
        }
        Some(relax) if relax.preconditioner != PreconditionerKind::None => {
            format!("{} in the {} metric", relax.method.name().to_uppercase(), relax.preconditioner.name())
        }
        Some(relax) => relax.method.name().to_uppercase(),
        None => String::new(),
    }
}

/// Steps over the critically damped bound 11.75/(ω_min dt), where k_min is known.
fn over_bound(r: &RunRecord) -> Option<f64> {
    let k_min = r.metrics.lattice.stiffness_min.filter(|k| *k > 0.0)?;
    Some(r.steps as f64 / critical_bound_steps(&r.spec, k_min))
}

/// |E − E_fem|/E_fem (tension) or |G − G_fem|/G_fem (shear) of a relaxed run.
fn true_error(r: &RunRecord) -> Option<f64> {
    let l = &r.metrics.lattice;
    relative(l.youngs_modulus, l.youngs_modulus_fem)
        .or_else(|| relative(l.shear_modulus, l.shear_modulus_fem))
        .map(f64::abs)
}

/// The time-to-a-modulus study: steps and wall time of every bounded run against the critically
/// damped bound, its true error against its recorded bound, and where a method stalled.
pub(super) fn time_to_modulus(e: &Evidence) -> Option<Answer> {
    let runs = e.all(bounded);
    if runs.is_empty() {
        return None;
    }
    let bounds = BoundChecks::of(&runs);
    let critical = e.ok(|r| bounded(r) && r.spec.relax().is_some_and(|relax| relax.critical_background));
    let critical_ratios: Vec<f64> = critical.iter().filter_map(|r| over_bound(r)).collect();
    let races = races(&runs);
    let mut sentences: Vec<String> = races.last().map(Race::sentence).into_iter().collect();
    sentences.extend(winners_sentence(&races));
    sentences.extend(bounds.sentence());
    sentences.extend(critical_sentence(&critical, &critical_ratios));
    sentences.extend(fixed_damping_sentence(e));
    sentences.extend(minimiser_sentences(e));
    sentences.extend(stalled_sentence(&runs));
    let verdict = Verdict::of(
        bounds.held.iter().copied().chain(critical_ratios.iter().map(|ratio| *ratio <= CRITICAL_STEPS_ALLOWED)),
    );
    Some(Answer {
        title: "Relaxation: time to a modulus",
        question: "Which method brings a loaded lattice to rest first, provably, and by how much?",
        short: races.last().map_or_else(|| bounds.short(&critical_ratios), Race::short),
        sentences,
        reference: format!(
            "The static answer of the same network (Newton to ‖R‖ ≤ {:e} ‖f‖): each relaxed run's |E − E_fem| \
             must lie below its recorded bound; critical damping within {CRITICAL_STEPS_ALLOWED} × the critically \
             damped bound in steps.",
            crate::fem::NEWTON_TOLERANCE
        ),
        see_also: None,
        verdict,
        figures: Vec::new(),
        table: Some(time_table(&runs)),
    })
}

/// The true error of a run that relaxed (none for a run that stalled).
fn relaxed_error(r: &RunRecord) -> Option<f64> {
    true_error(r).filter(|_| r.status == RunStatus::Ok)
}

/// Each relaxed run's true error held against its recorded bound.
struct BoundChecks<'a> {
    /// Per run with both, whether the error lies within the bound.
    held: Vec<bool>,
    /// The run closest to its bound: error over bound, the error, the run.
    worst: Option<(f64, f64, &'a RunRecord)>,
}

impl<'a> BoundChecks<'a> {
    fn of(runs: &[&'a RunRecord]) -> Self {
        let mut checks = BoundChecks { held: Vec::new(), worst: None };
        for r in runs {
            if let (Some(error), Some(bound)) = (relaxed_error(r), r.metrics.lattice.relax_error_bound) {
                checks.held.push(error <= bound);
                if checks.worst.is_none_or(|(w, _, _)| error / bound > w) {
                    checks.worst = Some((error / bound, error, r));
                }
            }
        }
        checks
    }

    fn within(&self) -> usize {
        self.held.iter().filter(|ok| **ok).count()
    }

    fn sentence(&self) -> Option<String> {
        let (_, error, r) = self.worst?;
        Some(format!(
            "Every relaxed run's modulus lies within its recorded bound of the static answer of the same network \
             ({} of {}): the closest, scene {} ({}, {}), is {} off against its bound {}; the bound \
             |δΔL| ≤ ‖K⁻¹g‖₂‖r‖₂ holds at any instant, whatever the velocities.",
            self.within(),
            self.held.len(),
            r.spec.scene,
            method(r),
            block(r),
            sig(error),
            cell(r.metrics.lattice.relax_error_bound),
        ))
    }

    /// The summary's answer, with the critically damped runs' largest steps over the bound.
    fn short(&self, critical_ratios: &[f64]) -> String {
        match self.worst {
            Some((_, error, _)) => format!(
                "{} of {} within their bound (closest {}); critical damping {} × the bound",
                self.within(),
                self.held.len(),
                sig(error),
                critical_ratios.iter().copied().reduce(f64::max).map(sig).unwrap_or_else(|| "–".into()),
            ),
            None => "no run relaxed".into(),
        }
    }
}

/// How many bounds critical background damping needs, over the sizes of its runs.
fn critical_sentence(critical: &[&RunRecord], ratios: &[f64]) -> Option<String> {
    if ratios.is_empty() {
        return None;
    }
    let (low, high) = extremes(ratios);
    Some(format!(
        "Critical background damping (γ_g = 2√(k_min m)) certifies the tolerance in {}–{} × the critically \
         damped bound 11.75/(ω_min dt) over N = {} (goal: within {CRITICAL_STEPS_ALLOWED}×): the slowest \
         mode, critically damped, falls to 1e-4 at ω_min t = 11.75, and every faster mode is underdamped \
         by the same γ_g and decays at least as fast.",
        sig(low),
        sig(high),
        sizes(critical),
    ))
}

/// How a fixed background damping falls behind the bound as the block grows.
fn fixed_damping_sentence(e: &Evidence) -> Option<String> {
    let fixed = e.ok(|r| {
        bounded(r)
            && r.spec.relax().is_some_and(|relax| relax.method == RelaxMethod::Damped && !relax.critical_background)
    });
    let (first, last) = (fixed.first()?, fixed.last()?);
    if first.run_id == last.run_id {
        return None;
    }
    Some(format!(
        "A fixed damping ({}) takes {} × the bound at N = {} and {} × at N = {}: the slowest mode's critical \
         damping 2√(k_min m) falls as 1/N, so a fixed γ_g overdamps it ever more.",
        method(first),
        cell(over_bound(first)),
        first.spec.lattice()?.nx,
        cell(over_bound(last)),
        last.spec.lattice()?.nx,
    ))
}

/// Per minimiser (FIRE in a stiffness's metric apart from FIRE by the masses), its force
/// evaluations over the bound's steps.
fn minimiser_sentences(e: &Evidence) -> Vec<String> {
    let by_minimiser = |r: &RunRecord| bounded(r) && r.spec.relax().is_some_and(|relax| relax.method.is_minimiser());
    // Every minimiser `sim::relax` knows, and every metric, so a new one is timed without
    // touching this item; in campaign order.
    let mut names: Vec<String> = Vec::new();
    for r in e.ok(by_minimiser) {
        if !names.contains(&method(r)) {
            names.push(method(r));
        }
    }
    let mut sentences = Vec::new();
    for name in names {
        let mine = e.ok(|r| by_minimiser(r) && method(r) == name);
        let ratios: Vec<f64> = mine.iter().filter_map(|r| over_bound(r)).collect();
        if ratios.is_empty() {
            continue;
        }
        let (low, high) = extremes(&ratios);
        sentences.push(format!(
            "{name} needs {}–{} of the bound's steps in force evaluations over N = {}.",
            sig(low),
            sig(high),
            sizes(&mine),
        ));
    }
    sentences
}

/// The runs that did not relax, grouped by how they ended (one message, many runs); a mechanism
/// ran no method at all (the load drives a zero-stiffness motion), so it is counted apart.
fn stalled_sentence(runs: &[&RunRecord]) -> Option<String> {
    let mechanisms = runs.iter().filter(|r| r.status == RunStatus::Mechanism).count();
    let mechanism_words = match mechanisms {
        0 => String::new(),
        n => format!(
            " {n} run{} {} a mechanism: the load or drive meets a zero-stiffness motion, and no method ran.",
            if n == 1 { "" } else { "s" },
            if n == 1 { "is" } else { "are" }
        ),
    };
    let mut stalled: Vec<(String, Vec<String>)> = Vec::new();
    for r in runs.iter().filter(|r| !matches!(r.status, RunStatus::Ok | RunStatus::Mechanism)) {
        let how = format!("{}: {}", r.status.as_str(), r.message);
        let which = format!("{} {} ({})", r.spec.scene, block(r), method(r));
        match stalled.iter_mut().find(|(said, _)| *said == how) {
            Some((_, runs)) => runs.push(which),
            None => stalled.push((how, vec![which])),
        }
    }
    if stalled.is_empty() {
        return (mechanisms > 0).then(|| mechanism_words.trim_start().to_string());
    }
    let said: Vec<String> = stalled.iter().map(|(how, runs)| format!("{} ended {how}", runs.join(", "))).collect();
    Some(format!("Where a method stalls: {}.{mechanism_words}", said.join("; ")))
}

/// One row per bounded run: how it came to rest, its cost and its error against its bound.
fn time_table(runs: &[&RunRecord]) -> Table {
    let rows = runs
        .iter()
        .map(|r| {
            vec![
                r.spec.scene.clone(),
                block(r),
                method(r),
                cell(r.spec.relax().and_then(|relax| relax.tolerance)),
                r.status.as_str().into(),
                r.steps.to_string(),
                cell(over_bound(r)),
                format!("{:.3}", r.wall_s),
                cell(relaxed_error(r)),
                cell(r.metrics.lattice.relax_error_bound),
            ]
        })
        .collect();
    let header =
        ["scene", "block", "method", "tolerance", "status", "steps", "× bound", "wall (s)", "|E − E_fem|", "bound"];
    Table { header: header.map(String::from).to_vec(), rows }
}

/// The block in words: "40 × 40", with its cut fraction where bonds were cut.
fn block(r: &RunRecord) -> String {
    match r.spec.lattice() {
        Some(l) if l.cut_fraction > 0.0 => format!("{} × {}, cut {}", l.nx, l.ny, l.cut_fraction),
        Some(l) => format!("{} × {}", l.nx, l.ny),
        None => String::new(),
    }
}

/// The block sizes N of `runs`, in order, without repeats: "20, 40, 80".
fn sizes(runs: &[&RunRecord]) -> String {
    let sizes: Vec<usize> = sorted_distinct(runs.iter().filter_map(|r| r.spec.lattice()).map(|l| l.nx));
    sizes.iter().map(usize::to_string).collect::<Vec<_>>().join(", ")
}

/// The runs of one block that more than one method brought to rest: the same scene settings but
/// the method (block, material, load and tolerance), the cheapest first.
struct Race<'a> {
    /// Ended `ok`, by force evaluations (an MD step is one), fewest first.
    runs: Vec<&'a RunRecord>,
}

/// Every [`Race`] among the bounded `runs`, the one that matters most last: the largest block
/// (by node count), then the most methods (of equal ones, in campaign order).
fn races<'a>(runs: &[&'a RunRecord]) -> Vec<Race<'a>> {
    // Everything but the method: the network (type, diagonals, stiffnesses, law, cut seed), its
    // supports and load, the material and the tolerance.
    let setup = |r: &RunRecord| {
        let l = r.spec.lattice().expect("a bounded run is a lattice's");
        let tolerance = r.spec.relax().and_then(|relax| relax.tolerance);
        let network = (l.lattice_type, l.diagonals, l.k_x, l.k_y, l.k_diag, r.spec.law.beta(), l.seed);
        format!(
            "{} {network:?} {:?} {:?} {} {} {} {} {:?}",
            block(r),
            l.supports,
            l.load_case,
            l.load_per_node,
            r.spec.k,
            r.spec.mass,
            r.spec.spacing,
            tolerance
        )
    };
    let mut groups: Vec<(String, Vec<&RunRecord>)> = Vec::new();
    for r in runs.iter().copied().filter(|r| r.status == RunStatus::Ok) {
        let key = setup(r);
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, mine)) => mine.push(r),
            None => groups.push((key, vec![r])),
        }
    }
    let mut races: Vec<Race> = groups
        .into_iter()
        .map(|(_, mut runs)| {
            runs.sort_by_key(|r| r.steps);
            Race { runs }
        })
        .filter(|race| race.methods() > 1)
        .collect();
    races.sort_by_key(|race| (race.nodes(), race.methods()));
    races
}

/// What a race holds fixed besides its block and method, in words, (what, value): the supports,
/// the load, the springs, the masses, the spacing and the tolerance ([`races`] groups by them
/// exactly, and by the network, which the scene's name tells).
fn setting(r: &RunRecord) -> [(&'static str, String); 6] {
    let l = r.spec.lattice().expect("a bounded run is a lattice's");
    let tolerance = r.spec.relax().and_then(|relax| relax.tolerance).map_or_else(|| "none".to_string(), sig);
    let case = format!("{:?}", l.load_case).to_lowercase();
    [
        ("supports", l.supports.name().to_string()),
        ("load", format!("{case}, {} N per node", sig(l.load_per_node))),
        ("k", format!("{} N/m", sig(r.spec.k))),
        ("m", format!("{} kg", sig(r.spec.mass))),
        ("a", format!("{} m", sig(r.spec.spacing))),
        ("tolerance", tolerance),
    ]
}

impl Race<'_> {
    fn methods(&self) -> usize {
        let mut names: Vec<String> = self.runs.iter().map(|r| method(r)).collect();
        names.dedup();
        names.len()
    }

    fn nodes(&self) -> usize {
        self.runs[0].spec.lattice().map_or(0, |l| l.nx * l.ny)
    }

    fn winner(&self) -> &RunRecord {
        self.runs[0]
    }

    /// How many times the winner's force evaluations `other` takes.
    fn times(&self, other: &RunRecord) -> f64 {
        other.steps as f64 / self.winner().steps.max(1) as f64
    }

    /// Who wins at this block and by how much, in force evaluations and in loop time.
    fn sentence(&self) -> String {
        let w = self.winner();
        let others: Vec<String> = self.runs[1..]
            .iter()
            .map(|r| {
                format!(
                    "{} × fewer than {} ({} steps, {} × the loop time)",
                    sig(self.times(r)),
                    method(r),
                    r.steps,
                    sig(r.trace.loop_s / w.trace.loop_s.max(f64::MIN_POSITIVE))
                )
            })
            .collect();
        format!(
            "On the largest block that several methods brought to rest ({}), the fastest to a certified \
             modulus is {}: {} force evaluations in {} s of time loop ({} s of wall time), {}. A force \
             evaluation is one MD step or one minimiser iteration; the loop times were measured beside the \
             campaign's other runs, and each wall time adds its run's setup (the static twin and the bound's \
             ‖K⁻¹g‖₂).",
            block(w),
            method(w),
            w.steps,
            sig(w.trace.loop_s),
            sig(w.wall_s),
            others.join(", ")
        )
    }

    fn short(&self) -> String {
        let w = self.winner();
        let last = self.runs[self.runs.len() - 1];
        format!(
            "{} first at {}: {} × fewer force evaluations than {}",
            method(w),
            block(w),
            sig(self.times(last)),
            method(last)
        )
    }
}

/// Which method won at each block size; a block that several races share (another load,
/// material or tolerance on the same size) names what sets each apart.
fn winners_sentence(races: &[Race]) -> Option<String> {
    let winners: Vec<String> = races
        .iter()
        .map(|race| {
            let at = format!("{} at {}", method(race.winner()), block(race.winner()));
            let same_block: Vec<&Race> = races.iter().filter(|o| block(o.winner()) == block(race.winner())).collect();
            match same_block.len() {
                1 => at,
                _ => format!("{at} ({})", apart(race, &same_block)),
            }
        })
        .collect();
    (winners.len() > 1).then(|| format!("The cheapest method block by block: {}.", winners.join("; ")))
}

/// What sets `race` apart from the other races on its block, as "what value": the parts of its
/// [`setting`] in order, each kept if it tells it from a race no part kept before did (a load
/// alone against another material; the load and the tolerance against the same load at
/// another tolerance).
fn apart(race: &Race, same_block: &[&Race]) -> String {
    let mine = setting(race.winner());
    let others: Vec<_> =
        same_block.iter().filter(|other| !std::ptr::eq(**other, race)).map(|other| setting(other.winner())).collect();
    let mut alike: Vec<usize> = (0..others.len()).collect();
    let mut parts = Vec::new();
    for part in 0..mine.len() {
        let told = |other: &usize| others[*other][part].1 != mine[part].1;
        if alike.iter().any(told) {
            parts.push(part);
            alike.retain(|other| !told(other));
        }
    }
    // Races the words cannot tell apart (settings that differ past four digits) show them all.
    if !alike.is_empty() {
        parts = (0..mine.len()).collect();
    }
    parts.iter().map(|&part| format!("{} {}", mine[part].0, mine[part].1)).collect::<Vec<_>>().join(", ")
}

/// The discussion of a relaxation campaign: which method to use, and how each one's cost grows
/// with the block (least-squares exponent of force evaluations against N over its relaxed runs).
pub(super) fn which_method(e: &Evidence) -> Option<Paragraph> {
    let runs = e.all(bounded);
    let races = races(&runs);
    let race = races.last()?;
    let mut growth = Vec::new();
    let mut names: Vec<String> = e.ok(|r| bounded(r) && !block(r).contains("cut")).iter().map(|r| method(r)).collect();
    names.sort();
    names.dedup();
    for name in names {
        let mine = e.ok(|r| bounded(r) && !block(r).contains("cut") && method(r) == name);
        let points: Vec<(f64, f64)> =
            mine.iter().filter_map(|r| Some((r.spec.lattice()?.nx as f64, r.steps as f64))).collect();
        if let Some(fit) = power_law_fit(&points).filter(|_| points.len() > 2) {
            growth.push(format!("{name} as N^{:.2} (N = {})", fit.exponent, sizes(&mine)));
        }
    }
    let w = race.winner();
    let last = race.runs[race.runs.len() - 1];
    let minimiser = w.spec.relax().is_some_and(|relax| relax.method.is_minimiser());
    Some(Paragraph {
        title: "Which method to use",
        text: format!(
            "{} wins on the largest block several methods relaxed ({}), by {} × in force evaluations over {}. \
             The steps each method needs grow with the block's side N: {}. Damped MD is held back by the \
             slowest mode (ω_min ∝ 1/N) at a time step the fastest mode sets, so its steps grow with N however \
             it is damped; a minimiser's steps are bound to no mode. {}",
            method(w),
            block(w),
            sig(race.times(last)),
            method(last),
            if growth.is_empty() { "not measured (one size per method)".to_string() } else { growth.join("; ") },
            if minimiser {
                "For a modulus alone, the minimiser; MD remains the tool for the motion itself."
            } else {
                "Here damped MD is the cheapest way to the modulus as well as the tool for the motion."
            }
        ),
    })
}
