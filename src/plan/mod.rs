//! The plan stage, between the campaign file and the first run: the campaign loaded and
//! expanded ([`crate::spec`]), every run's time step and step count decided (once, here),
//! its stability checked against its integrator's limit and its collisions against particles
//! passing through each other ([`overlap`]), and the estimates kept for the runs'
//! records. Every command that reads a campaign file starts from [`load`]; the runner takes
//! the [`Plan`] it returns. The cost estimate is [`RunSpec::estimated_seconds`] of a planned run.

mod lanczos;
mod overlap;
pub mod stability;

pub use self::overlap::collision_warning;
pub use self::stability::{Estimates, RUN_GROWTH, Stability, estimate};

use rayon::prelude::*;
use std::path::Path;

use crate::spec::{
    Campaign, DEFAULT_DT_PER_TC, Num, RESIDUAL_OVER_ROUND_OFF, RunSpec, SpecError, force_resolution, round_off_words,
};

/// A campaign ready to run: every run's dt and steps final, each within its integrator's
/// stability limit unless it says `time.allow_unstable: true`.
#[derive(Debug)]
pub struct Plan {
    /// The campaign, its runs planned.
    pub campaign: Campaign,
    /// The estimates the check made (modes per network, limits per integrator), which the
    /// runs read again for their records instead of computing them once more.
    pub estimates: Estimates,
}

/// Reads, validates and expands the campaign file at `path` ([`crate::spec::load`]), then
/// plans every run ([`plan`]): what every command starts from.
pub fn load(path: &Path) -> Result<Plan, SpecError> {
    plan(&path.display().to_string(), crate::spec::load(path)?)
}

/// [`load`] for campaign text; `file` names it in errors.
pub fn parse(file: &str, text: &str) -> Result<Plan, SpecError> {
    plan(file, crate::spec::parse(file, text)?)
}

/// Plans every run of `campaign` ([`plan_run`]), refusing the campaign at the first run that
/// cannot run. Errors name the file, the scene, the grid values and the field.
pub fn plan(file: &str, campaign: Campaign) -> Result<Plan, SpecError> {
    let estimates = Estimates::default();
    let campaign = plan_sharing(file, campaign, &estimates)?;
    Ok(Plan { campaign, estimates })
}

/// [`plan`] with `estimates` that other plans share: many one-run campaigns of the same
/// integrators (a test's product of axes) measure each stability limit once, as a campaign's
/// runs do. The runs read the same `estimates` again ([`crate::runner::execute_within`]).
pub fn plan_sharing(file: &str, mut campaign: Campaign, estimates: &Estimates) -> Result<Campaign, SpecError> {
    let (scenes, budget) = (&campaign.scenes, campaign.budget);
    campaign.runs.par_iter_mut().try_for_each(|spec| {
        let refused = budget.refuses(spec).is_some();
        plan_run(spec, refused, estimates).map_err(|detail| {
            let index = scenes.iter().position(|(name, _)| *name == spec.scene).unwrap_or(0);
            let place = match spec.varied_label(|_| true) {
                label if label.is_empty() => format!("scenes[{index}] ({})", spec.scene),
                label => format!("scenes[{index}] ({}, run {label})", spec.scene),
            };
            SpecError::Invalid { file: file.to_string(), detail: format!("{place}.{detail}") }
        })
    })?;
    Ok(campaign)
}

/// Plans `spec` ([`plan_step`]) and refuses, before anything runs, a collision whose
/// particles may pass through each other at that step ([`overlap::check`]) unless it says
/// `time.allow_unstable: true`. A run its memory budget `refused` is not started anyway. The
/// error is the field and why.
fn plan_run(spec: &mut RunSpec, refused: bool, estimates: &Estimates) -> Result<(), String> {
    check_round_off(spec)?;
    plan_step(spec, refused, estimates)?;
    if refused { Ok(()) } else { overlap::check(spec, dt_field(spec)) }
}

/// The campaign field that set the time step of `spec`, as its errors name it.
fn dt_field(spec: &RunSpec) -> &'static str {
    if spec.dt_omega_max.is_some() { "time.dt_omega_max" } else { "time.dt_per_tc (or time.dt)" }
}

/// Decides the time step of `spec` where the campaign gave `time.dt_omega_max` (dt = value /
/// ω_max; `time.dt` and `time.dt_per_tc` set it in the spec layer) and refuses a run whose
/// dt · ω_max exceeds its integrator's limit unless it says `time.allow_unstable: true`. A run
/// its memory budget `refused` (its memory does not depend on dt) and a static-only run, which
/// takes no step, are not worth an estimate ([`Estimates::stepped_stability`]).
fn plan_step(spec: &mut RunSpec, refused: bool, estimates: &Estimates) -> Result<(), String> {
    let Some(target) = spec.dt_omega_max else {
        return match (!refused).then(|| estimates.stepped_stability(spec)).flatten() {
            Some(stability) => check_limit(spec, &stability, dt_field(spec)),
            None => Ok(()),
        };
    };
    if refused {
        // Its record says why it never ran; the nominal dt = t_c / 50 gives it its run id.
        spec.set_dt(spec.t_c / DEFAULT_DT_PER_TC);
        return Ok(());
    }
    let omega_max = estimates.omega_max(spec);
    if !(omega_max > 0.0 && omega_max.is_finite()) {
        return Err(format!(
            "time.dt_omega_max = {target}: the scene has no usable fastest mode (ω_max = {omega_max}); give dt or \
             dt_per_tc"
        ));
    }
    spec.set_dt(target / omega_max);
    if !(1..=2_000_000_000).contains(&spec.steps) {
        return Err(format!("time.dt_omega_max = {target}: gives {} steps; from 1 to 2e9", spec.steps));
    }
    // Exactly the value asked for (ω_max · dt may differ in the last digit).
    let stability = Stability { dt_omega_max: target, ..estimates.stability(spec) };
    check_limit(spec, &stability, dt_field(spec))
}

/// A load per node below this many times the round-off of the static force ([`force_resolution`])
/// is refused: MD would resolve the moduli to no better than 1e-3.
const LOAD_OVER_ROUND_OFF: f64 = 1e3;

/// Refuses a loaded lattice under force control whose load, or whose `relax.residual_force`,
/// lies near or below the round-off floor of its positions (a load of 10 N on a 1e30 N/m
/// network; 1e-8 of a load that is 2e-15 N): no relaxation stops there, and the moduli would be
/// round-off. Velocity control's force is known only from the static answer, and the
/// displacement bound's floor needs its sensitivity: both are checked before the run starts
/// (`study::lattice`).
fn check_round_off(spec: &RunSpec) -> Result<(), String> {
    let (Some(floor), Some(force)) = (force_resolution(spec), spec.lattice().and_then(|l| l.force_per_node())) else {
        return Ok(());
    };
    let why = round_off_words(spec, floor);
    if force.abs() < LOAD_OVER_ROUND_OFF * floor {
        return Err(format!(
            "load.per_node = {force:e}: below {LOAD_OVER_ROUND_OFF:e} times the round-off floor: {why}; allowed: \
             load.per_node ≥ {:.2e} N, or relax.method: static (solved in displacements)",
            LOAD_OVER_ROUND_OFF * floor
        ));
    }
    match spec.relax().and_then(|r| r.residual_force) {
        Some(fraction) if fraction * force.abs() < RESIDUAL_OVER_ROUND_OFF * floor => Err(format!(
            "relax.residual_force = {fraction:e}: {:.2e} N, below {RESIDUAL_OVER_ROUND_OFF} times the round-off \
             floor: {why}; allowed: relax.residual_force ≥ {:.2e}",
            fraction * force.abs(),
            RESIDUAL_OVER_ROUND_OFF * floor / force.abs()
        )),
        _ => Ok(()),
    }
}

/// Refuses `spec` when its dt · ω_max passes the limit of its integrator, unless it allows that;
/// `field` is the campaign field that set dt.
fn check_limit(spec: &RunSpec, stability: &Stability, field: &str) -> Result<(), String> {
    let beyond = stability.dt_omega_max > stability.limit;
    if !beyond || spec.allow_unstable {
        return Ok(());
    }
    Err(format!(
        "{field}: dt = {:.4e} s gives dt·ω_max = {:.4} (ω_max = {:.4e} rad/s, damping ratio {:.3}), beyond the \
         stability limit {:.4} of {}; allowed: dt ≤ {:.4e} s (dt_per_tc ≥ {:.3}), or time.allow_unstable: true to \
         run it anyway and watch it blow up",
        spec.dt,
        Num(stability.dt_omega_max),
        stability.omega_max,
        Num(stability.damping_ratio),
        Num(stability.limit),
        spec.integrator.name(),
        stability.limit / stability.omega_max,
        Num(spec.t_c * stability.omega_max / stability.limit),
    ))
}
