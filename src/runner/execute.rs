//! One run's lifecycle: the budget (not started beyond its memory, stopped at its deadline),
//! `catch_unwind` around the run `study::run` builds, integrates and measures, and the record;
//! a panic becomes a `panicked` record, a load that drives a mechanism a `mechanism` record.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

use super::record::{BUILD, Metrics, RunRecord};
use super::series;
use crate::draw::Movie;
use crate::fem::Floppy;
use crate::plan::Estimates;
use crate::sim::{RelaxMethod, RunStatus, Trace};
use crate::spec::{Budget, RunSpec};
use crate::study::{self, Run, Stopped};

/// Runs `spec` (planned: [`crate::plan`]) within the default [`Budget`], estimating its
/// stability afresh, and returns its record; never panics.
pub fn execute(spec: &RunSpec) -> RunRecord {
    execute_within(spec, &Budget::default(), &Estimates::default())
}

/// Runs `spec` (planned: [`crate::plan`]) and returns its record; never panics. Its stability
/// comes from `estimates` (the plan's, where it was estimated already). A run whose estimated
/// memory exceeds `budget` is not started, one that passes its time budget is stopped: both
/// are recorded with `status = budget`.
pub fn execute_within(spec: &RunSpec, budget: &Budget, estimates: &Estimates) -> RunRecord {
    let started = Instant::now();
    let refused = budget.refuses(spec);
    let deadline = started + budget.time_per_run();
    let result = match &refused {
        Some(_) => Ok(Err(None)),
        None => catch_unwind(AssertUnwindSafe(|| run_and_measure(spec, deadline, estimates).map_err(Some))),
    };
    let mut record = blank_record(spec);
    let mut reference_s = 0.0;
    match result {
        Ok(Ok(run)) => {
            reference_s = run.reference_s;
            fill(&mut record, *run, deadline);
        }
        Ok(Err(Some(Stopped::Mechanism(floppy)))) => {
            record.status = RunStatus::Mechanism;
            record.message = mechanism_message(floppy);
        }
        Ok(Err(None)) => {
            record.status = RunStatus::Budget;
            record.message = refused.clone().unwrap_or_default();
        }
        Ok(Err(Some(Stopped::PastDeadline { stage }))) => {
            record.status = RunStatus::Budget;
            record.message = format!("stopped in its {stage}");
        }
        Err(panic) => {
            record.status = RunStatus::Panicked;
            record.message = panic_message(panic.as_ref());
        }
    }
    // The reference run or the tangent step may be what passed the deadline.
    if record.status == RunStatus::Ok && Instant::now() > deadline {
        record.status = RunStatus::Budget;
        record.message = "stopped in its reference run or tangent step".into();
    }
    if record.status == RunStatus::Budget && refused.is_none() {
        record.message = format!(
            "passed its time budget of {} s per run (budget.seconds_per_run) after {:.3} s: {}",
            budget.seconds_per_run,
            started.elapsed().as_secs_f64(),
            record.message
        );
    }
    // The run's own cost: a reference run at a finer dt is not part of it.
    record.wall_s = started.elapsed().as_secs_f64() - reference_s;
    record
}

/// The record of `spec` before its run: `ok`, nothing measured.
fn blank_record(spec: &RunSpec) -> RunRecord {
    RunRecord {
        run_id: spec.run_id(),
        build: BUILD.into(),
        spec: spec.clone(),
        status: RunStatus::Ok,
        message: String::new(),
        wall_s: 0.0,
        steps: 0,
        metrics: Metrics::default(),
        trace: Trace::default(),
        series: None,
        particle_table: None,
        probe_table: None,
        full_series: None,
        movie: None,
        final_state: None,
    }
}

/// The run with the stability estimate's numbers among its metrics; `Err` when it stopped
/// before its time loop.
fn run_and_measure(spec: &RunSpec, deadline: Instant, estimates: &Estimates) -> Result<Box<Run>, Stopped> {
    assert!(spec.is_planned(), "a run reached the runner without its time step: plan the campaign (crate::plan)");
    let stability = estimates.stepped_stability(spec);
    let mut run = study::run(spec, deadline, estimates.shared())?;
    if let Some(stability) = stability {
        run.metrics.omega_max = Some(stability.omega_max);
        run.metrics.dt_omega_max = Some(stability.dt_omega_max);
        run.metrics.mode_damping_ratio = Some(stability.damping_ratio);
        run.metrics.stability_limit = Some(stability.limit);
    }
    Ok(Box::new(run))
}

/// Fills `record` from a finished run: its status, message, steps, metrics, kept trace
/// and movie (written by the runner beside the record, its encoding bounded by `deadline`).
fn fill(record: &mut RunRecord, mut run: Run, deadline: Instant) {
    let spec = &record.spec;
    let captions = untimed_captions(spec, &run.outcome.trace, run.outcome.frames.len());
    record.movie = spec.movie.map(|movie| Movie {
        frames: std::mem::take(&mut run.outcome.frames),
        captions,
        bonds: run.bonds,
        supports: run.supports,
        discs: run.discs.take(),
        spec: movie,
        title: format!("{} {}", spec.scene, spec.varied_in_words(|_| true)),
        t_c: spec.t_c,
        deadline: Some(deadline),
    });
    // Made here, where the final state is at hand; a table that cannot be made is left out.
    record.final_state = series::packing_table(spec, &run.outcome.state.particles).ok().flatten();
    let trace = run.outcome.trace;
    record.status = trace.status;
    record.message = trace.message.clone();
    if record.status == RunStatus::NoEquilibrium && ran_out_of_damped_time(spec, trace.steps) {
        record.message = longer_relaxation(spec, &record.message);
    }
    record.steps = trace.steps;
    if let Some(caveat) = study::caveat(spec, &run.metrics).filter(|_| record.message.is_empty()) {
        record.message = caveat.into();
    }
    record.metrics = run.metrics;
    // Measured from every sample above; kept as `output.series` says: by default thinned,
    // within a bounded size, and only what the report draws.
    (record.trace, record.full_series) = series::kept(trace, &record.spec);
}

/// What the `frames` frames of a run with no time show (a minimiser's or the static solve's
/// two frames, `relax.method: fire | cg | static`): the start, then the state it ended in, with
/// the method and its force evaluations; a compressed packing's, the start and each stage it
/// relaxed at, with its area fraction; none for a run in time, whose frames show their time.
fn untimed_captions(spec: &RunSpec, trace: &Trace, frames: usize) -> Vec<String> {
    let Some(method) = spec.relax().map(|r| r.method).filter(|m| *m != RelaxMethod::Damped) else {
        return Vec::new();
    };
    let (name, evaluations) = (method.name(), trace.steps);
    let end = match (method, trace.status) {
        (RelaxMethod::Static, RunStatus::Ok) => "static answer (relax.method: static)".to_string(),
        (_, RunStatus::Ok) => format!("relaxed ({name}, {evaluations} force evaluations)"),
        (_, status) => format!("stopped ({name}, {evaluations} force evaluations): {status}"),
    };
    match spec.packing().filter(|p| p.compression.is_some()) {
        Some(packing) => compression_captions(&packing.stage_fractions(), frames, &end),
        None => vec!["start".into(), end],
    }
}

/// The captions of a compressed packing's `frames` frames: its random start at the first of
/// the stages' area fractions `stages`, each stage relaxed, and the last with `end`.
fn compression_captions(stages: &[f64], frames: usize, end: &str) -> Vec<String> {
    let mut captions = vec![format!("start: random positions, φ = {:.4}", stages[0])];
    captions.extend(stages.iter().take(frames.saturating_sub(1)).map(|phi| format!("φ = {phi:.4}, relaxed")));
    if let Some(last) = stages.get(frames.saturating_sub(2)).filter(|_| frames >= 2) {
        let end = end.replace(" force evaluations", " force evaluations in all");
        captions[frames - 1] = format!("φ = {last:.4}, {end}");
    }
    captions
}

/// Whether a run that did not relax was damped MD that stepped through its whole budget
/// (`steps` of them): not a minimiser (whose message names its own budget, and which takes no
/// damping), and not a run stopped before its first step (a tolerance below round-off, a floppy
/// network), which no longer budget helps.
fn ran_out_of_damped_time(spec: &RunSpec, steps: u64) -> bool {
    spec.relax().is_some_and(|r| r.method == RelaxMethod::Damped) && steps > 0
}

/// A damped relaxation that did not relax: its `message` with the field that lengthens it. Its
/// length is its budget `relax.max_tc` (t_c), which a lightly damped or soft network outlasts:
/// the slowest mode decays over ~1/(ζ ω_min), many t_c where the bond dashpot's ζ is small.
fn longer_relaxation(spec: &RunSpec, message: &str) -> String {
    // duration = max_tc t_c: the quotient has round-off in its last digits, which 6
    // significant digits drop (0.4 stays 0.4, 5000 stays 5000).
    let max_tc = spec.duration / spec.t_c;
    let max_tc: f64 = format!("{max_tc:.5e}").parse().unwrap_or(max_tc);
    format!("{message} (relax.max_tc = {max_tc} t_c: raise it, or the damping, for a network that relaxes more slowly)")
}

/// Why a mechanism has no MD run, in words: the load's equations that have no solution, or the
/// velocity drive that a zero-energy motion takes ([`Floppy`]).
fn mechanism_message(floppy: Floppy) -> String {
    match floppy {
        Floppy::Load { residual } => format!(
            "the load drives a zero-stiffness motion: the static equations K u = f have no solution \
             (relative residual {residual:.1e}); nothing to relax towards"
        ),
        Floppy::Drive { stiffness, resolution } => format!(
            "the velocity drive is taken by a zero-stiffness motion: held where it stops, the driven row \
             meets {stiffness:.1e} N/m at first order, within the static factor's resolution {resolution:.1e} N/m, \
             and the network carries no stress; no modulus to measure"
        ),
    }
}

fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    let text = panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into());
    format!("the run panicked: {text}")
}
