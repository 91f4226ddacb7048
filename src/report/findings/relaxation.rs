//! Time to a modulus: loaded lattices brought to rest until the displacement bound
//! (`relax.tolerance`) certifies their modulus, by damped MD, critical background damping,
//! FIRE and CG, each against the critically damped bound in steps and the static answer of the
//! same network.

use super::finding::{Answer, Evidence, Table, Verdict, cell, extremes, relative, sig};
use crate::runner::RunRecord;
use crate::sim::{RelaxMethod, RunStatus};
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
    let mut rows = Vec::new();
    let mut bound_held = Vec::new();
    let mut worst: Option<(f64, f64, &RunRecord)> = None;
    for r in &runs {
        let m = &r.metrics.lattice;
        let error = true_error(r).filter(|_| r.status == RunStatus::Ok);
        if let (Some(error), Some(bound)) = (error, m.relax_error_bound) {
            bound_held.push(error <= bound);
            if worst.is_none_or(|(w, _, _)| error / bound > w) {
                worst = Some((error / bound, error, r));
            }
        }
        rows.push(vec![
            r.spec.scene.clone(),
            block(r),
            method(r),
            cell(r.spec.relax().and_then(|relax| relax.tolerance)),
            r.status.as_str().into(),
            r.steps.to_string(),
            cell(over_bound(r)),
            format!("{:.3}", r.wall_s),
            cell(error),
            cell(m.relax_error_bound),
        ]);
    }
    let mut sentences = Vec::new();
    if let Some((_, error, r)) = worst {
        sentences.push(format!(
            "Every relaxed run's modulus lies within its recorded bound of the static answer of the same network \
             ({} of {}): the closest, scene {} ({}, {}), is {} off against its bound {}; the bound \
             |δΔL| ≤ ‖K⁻¹g‖₂‖r‖₂ holds at any instant, whatever the velocities.",
            bound_held.iter().filter(|ok| **ok).count(),
            bound_held.len(),
            r.spec.scene,
            method(r),
            block(r),
            sig(error),
            cell(r.metrics.lattice.relax_error_bound),
        ));
    }
    let critical = e.ok(|r| bounded(r) && r.spec.relax().is_some_and(|relax| relax.critical_background));
    let critical_ratios: Vec<f64> = critical.iter().filter_map(|r| over_bound(r)).collect();
    if !critical_ratios.is_empty() {
        let (low, high) = extremes(&critical_ratios);
        sentences.push(format!(
            "Critical background damping (γ_g = 2√(k_min m)) certifies the tolerance in {}–{} × the critically \
             damped bound 11.75/(ω_min dt) over N = {} (goal: within {CRITICAL_STEPS_ALLOWED}×): the slowest \
             mode, critically damped, falls to 1e-4 at ω_min t = 11.75, and every faster mode is underdamped \
             by the same γ_g and decays at least as fast.",
            sig(low),
            sig(high),
            sizes(&critical),
        ));
    }
    let fixed = e.ok(|r| {
        bounded(r)
            && r.spec.relax().is_some_and(|relax| relax.method == RelaxMethod::Damped && !relax.critical_background)
    });
    if let (Some(first), Some(last)) = (fixed.first(), fixed.last())
        && first.run_id != last.run_id
    {
        sentences.push(format!(
            "A fixed damping ({}) takes {} × the bound at N = {} and {} × at N = {}: the slowest mode's critical \
             damping 2√(k_min m) falls as 1/N, so a fixed γ_g overdamps it ever more.",
            method(first),
            cell(over_bound(first)),
            first.spec.lattice()?.nx,
            cell(over_bound(last)),
            last.spec.lattice()?.nx,
        ));
    }
    for minimiser in [RelaxMethod::Fire, RelaxMethod::Cg] {
        let mine = e.ok(|r| bounded(r) && r.spec.relax().is_some_and(|relax| relax.method == minimiser));
        let ratios: Vec<f64> = mine.iter().filter_map(|r| over_bound(r)).collect();
        if ratios.is_empty() {
            continue;
        }
        let (low, high) = extremes(&ratios);
        sentences.push(format!(
            "{} needs {}–{} of the bound's steps in force evaluations over N = {}.",
            minimiser.name().to_uppercase(),
            sig(low),
            sig(high),
            sizes(&mine),
        ));
    }
    // The runs that did not relax, grouped by how they ended (one message, many runs).
    let mut stalled: Vec<(String, Vec<String>)> = Vec::new();
    for r in runs.iter().filter(|r| r.status != RunStatus::Ok) {
        let how = format!("{}: {}", r.status.as_str(), r.message);
        let which = format!("{} {} ({})", r.spec.scene, block(r), method(r));
        match stalled.iter_mut().find(|(said, _)| *said == how) {
            Some((_, runs)) => runs.push(which),
            None => stalled.push((how, vec![which])),
        }
    }
    if !stalled.is_empty() {
        let said: Vec<String> = stalled.iter().map(|(how, runs)| format!("{} ended {how}", runs.join(", "))).collect();
        sentences.push(format!("Where a method stalls: {}.", said.join("; ")));
    }
    let verdict = Verdict::of(
        bound_held.iter().copied().chain(critical_ratios.iter().map(|ratio| *ratio <= CRITICAL_STEPS_ALLOWED)),
    );
    Some(Answer {
        title: "Relaxation: time to a modulus",
        question: "How soon is a loaded lattice at rest, provably, and which method gets there first?",
        short: match worst {
            Some((_, error, _)) => format!(
                "{} of {} within their bound (closest {}); critical damping {} × the bound",
                bound_held.iter().filter(|ok| **ok).count(),
                bound_held.len(),
                sig(error),
                critical_ratios.iter().copied().reduce(f64::max).map(sig).unwrap_or_else(|| "–".into()),
            ),
            None => "no run relaxed".into(),
        },
        sentences,
        reference: format!(
            "The static answer of the same network (Newton to ‖R‖ ≤ {:e} ‖f‖): each relaxed run's |E − E_fem| \
             must lie below its recorded bound; critical damping within {CRITICAL_STEPS_ALLOWED} × the critically \
             damped bound in steps.",
            crate::fem::NEWTON_TOLERANCE
        ),
        verdict,
        figures: Vec::new(),
        table: Some(Table {
            header: [
                "scene",
                "block",
                "method",
                "tolerance",
                "status",
                "steps",
                "× bound",
                "wall (s)",
                "|E − E_fem|",
                "bound",
            ]
            .map(String::from)
            .to_vec(),
            rows,
        }),
    })
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
    let mut sizes: Vec<usize> = runs.iter().filter_map(|r| r.spec.lattice()).map(|l| l.nx).collect();
    sizes.sort_unstable();
    sizes.dedup();
    sizes.iter().map(usize::to_string).collect::<Vec<_>>().join(", ")
}
