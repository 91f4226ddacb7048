//! One run: build the scene, integrate it, measure it; a panic becomes a `panicked` record.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

use super::record::{Metrics, RunRecord};
use crate::measure::{contact_timing, energy_error, normal_mode_error};
use crate::scenes::{build_scene, chain_has_normal_modes, pair_references};
use crate::sim::{Outcome, Trace};
use crate::spec::{RunSpec, SceneKind};

/// Runs `spec` and returns its record; never panics.
pub fn execute(spec: &RunSpec) -> RunRecord {
    let started = Instant::now();
    let outcome = catch_unwind(AssertUnwindSafe(|| build_scene(spec).run()));
    let wall_s = started.elapsed().as_secs_f64();
    let mut record = RunRecord {
        run_id: spec.run_id(),
        spec: spec.clone(),
        status: "ok".into(),
        message: String::new(),
        wall_s,
        steps: 0,
        metrics: Metrics::default(),
        trace: Trace::default(),
    };
    match outcome {
        Ok(outcome) => {
            record.metrics = measure(spec, &outcome);
            record.status = outcome.trace.status.word().into();
            record.message = outcome.trace.message.clone();
            record.steps = outcome.trace.steps;
            if spec.kind == SceneKind::Pair && record.metrics.contact_duration.is_none() && record.message.is_empty() {
                record.message = "the contact did not close and open again within the run".into();
            }
            record.trace = outcome.trace;
        }
        Err(panic) => {
            record.status = "panicked".into();
            record.message = panic_message(panic.as_ref());
        }
    }
    record
}

fn measure(spec: &RunSpec, outcome: &Outcome) -> Metrics {
    let timing = contact_timing(&outcome.crossings);
    let (contact_duration_theory, restitution_theory) = pair_references(spec);
    let chain_mode_error = chain_has_normal_modes(spec)
        .then(|| {
            let n = spec.n.unwrap_or(0);
            let movable: Vec<usize> = (1..=n).collect();
            let v0: Vec<f64> = movable.iter().map(|&p| if Some(p) == spec.node { spec.v0 } else { 0.0 }).collect();
            normal_mode_error(&outcome.trace, &movable, &v0, spec.k, spec.mass)
        })
        .flatten();
    Metrics {
        contact_duration: timing.map(|t| t.duration),
        contact_duration_theory,
        restitution: timing.map(|t| t.restitution),
        restitution_theory,
        energy_error: energy_error(&outcome.trace),
        chain_mode_error,
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
