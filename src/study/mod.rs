//! One home per scene kind: `pair`, `chain` and `lattice` each build their scene from a
//! [`RunSpec`], hold their analytical and static references and measure their runs; this file
//! dispatches down to them and measures what several kinds have (the energy balance, waves,
//! relaxation, the tangent step, the reference run and the error a run is judged by), from
//! the facts each kind gives. What the kinds build from is in `common`. Pure: no I/O.

pub mod chain;
mod columns;
mod common;
pub mod lattice;
pub mod packing;
pub mod pair;

pub use self::columns::{Slot, Values};
pub use self::common::Stopped;

use std::time::Instant;

use serde::{Deserialize, Serialize};

use self::columns::{Block, Row};
use self::common::relaxation_checks;
use crate::fem::Shared;
use crate::measure::{ARRIVAL_CRITERIA, arrival_time, energy_error};
use crate::model::{Axes, Particles};
use crate::sim::{Outcome, RelaxMethod, RunStatus, Scene, Trace};
use crate::spec::{KindSpec, RunSpec, SceneKind};

/// Measured quantities with their analytical twins; `None` where the scene has no such
/// quantity or no exact answer exists. What every kind may have is here, each kind's own
/// group in its file; the groups are flattened in the record, so its keys (and the results
/// table's column names) are the fields' names.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// max |E(t) − E(0)| / E(0) with E = kinetic + potential + dissipated.
    pub energy_error: Option<f64>,
    /// The run's error against the most exact reference it has (see `error_measure`), ≥ 0.
    pub error: Option<f64>,
    /// What `error` measures: `contact_duration`, `restitution`, `normal_modes`,
    /// `reference_dt/R` (a run at dt/R) or `energy`.
    pub error_measure: Option<String>,
    /// Chain wave: arrival time (s) at the receiver by each criterion.
    #[serde(default)]
    pub arrival_times: std::collections::BTreeMap<String, f64>,
    /// Chain wave: the recommended criterion.
    pub arrival_criterion: Option<String>,
    /// Chain wave: distance from the excited particle to the receiver (m).
    pub wave_distance: Option<f64>,
    /// Chain wave: the coursework's estimate t_s = N_s t_c (N_s springs between them) (s).
    pub arrival_time_tc_estimate: Option<f64>,
    /// Chain wave: the long-wavelength (and front) speed a√(k/m) of a linear chain (m/s).
    pub sound_speed_theory: Option<f64>,
    /// Angular frequency of the fastest mode (rad/s), estimated before the run.
    pub omega_max: Option<f64>,
    /// dt · ω_max.
    pub dt_omega_max: Option<f64>,
    /// Damping ratio of the fastest mode.
    pub mode_damping_ratio: Option<f64>,
    /// Largest dt · ω_max the integrator survives at that damping ratio.
    pub stability_limit: Option<f64>,
    /// Loaded lattice: wall time (s) of its static answer (the solve, or the wait for the run
    /// of the campaign that solves it, and for a relaxing run k_min and the sensitivity its
    /// bound needs), part of the run's `wall_s`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solve_s: Option<f64>,
    /// Lattice: time (s) from which the relaxation criterion held.
    pub dissipation_time: Option<f64>,
    /// Lattice: the relaxation criterion, in words.
    pub dissipation_criterion: Option<String>,
    /// The pair's contact.
    #[serde(flatten)]
    pub pair: pair::PairMetrics,
    /// The chain's normal modes and equilibrium.
    #[serde(flatten)]
    pub chain: chain::ChainMetrics,
    /// The lattice's moduli and static answer.
    #[serde(flatten)]
    pub lattice: lattice::LatticeMetrics,
    /// The packing at rest: pressure, contacts, moduli.
    #[serde(flatten)]
    pub packing: packing::PackingMetrics,
}

impl Metrics {
    /// Arrival time (s) by the recommended criterion.
    pub fn arrival_time(&self) -> Option<f64> {
        self.arrival_criterion.as_ref().and_then(|c| self.arrival_times.get(c).copied())
    }

    /// Sound speed L / t_s (m/s) from the arrival time by `criterion`.
    pub fn sound_speed(&self, criterion: &str) -> Option<f64> {
        self.wave_distance.zip(self.arrival_times.get(criterion)).map(|(l, t)| l / t)
    }

    /// Sound speed L / t_s (m/s) by the recommended criterion ([`Metrics::arrival_time`]'s).
    pub fn recommended_sound_speed(&self) -> Option<f64> {
        self.arrival_criterion.as_deref().and_then(|c| self.sound_speed(c))
    }
}

/// A simulated and measured run.
#[derive(Debug)]
pub struct Run {
    /// What the time loop produced (the trace of a lattice already cut to its probed lines).
    pub outcome: Outcome,
    /// Its measurements.
    pub metrics: Metrics,
    /// Wall time (s) of the reference run at a finer dt, if any: not part of the run's cost.
    pub reference_s: f64,
    /// Bonds a movie draws (i, j, rest length in m), collected when the run asks for a movie;
    /// bonds across a periodic side are left out.
    pub bonds: Vec<(usize, usize, f64)>,
    /// Particles a movie draws as supports (walls, clamped or rolling nodes) with the axes they
    /// are held along, collected when the run asks for a movie. A hold along y that every
    /// particle has is the line a 1D scene moves on, not a support, and is left out.
    pub supports: Vec<(usize, Axes)>,
    /// A packing's movie frames as discs to scale with their contact forces, when it asks for
    /// a movie.
    pub discs: Option<crate::measure::Discs>,
}

/// Builds the scene of `spec`.
pub fn build_scene(spec: &RunSpec) -> Scene {
    match &spec.scene_kind {
        KindSpec::Pair(pair) => pair::build(spec, pair),
        KindSpec::Chain(chain) => chain::build(spec, chain),
        KindSpec::Lattice(run) => lattice::build(spec, &run.lattice),
        KindSpec::Packing(run) => packing::build(spec, run),
    }
}

/// The scene of `spec`, its time loops stopped at `deadline`.
fn build_scene_until(spec: &RunSpec, deadline: Instant) -> Scene {
    let mut scene = build_scene(spec);
    scene.sampling.deadline = Some(deadline);
    scene
}

/// Builds and integrates `spec` (a loaded lattice after its static answer), its time loops
/// stopped at `deadline`, and measures it: the kind's measurements, the tangent step of a
/// relaxed run, the error against a reference run at a finer dt or the exact answer.
pub fn run(spec: &RunSpec, deadline: Instant, shared: &Shared) -> Result<Run, Stopped> {
    let mut scene = build_scene_until(spec, deadline);
    let mut metrics = Metrics::default();
    let mut no_criterion = None;
    if let Some(l) = spec.lattice().filter(|l| l.impulse.is_none()) {
        let started = Instant::now();
        no_criterion = lattice::static_answer(spec, l, &mut scene, (deadline, shared), &mut metrics.lattice)?;
        metrics.solve_s = Some(started.elapsed().as_secs_f64());
    }
    if no_criterion.is_some() {
        // Nothing could say when it is relaxed: not run, its static answer kept.
        scene.sampling.steps = 0;
    }
    let start = (scene.particles.x.clone(), scene.particles.y.clone());
    let (bonds, supports) =
        if spec.movie.is_some() { (movie_bonds(&scene), supports(&scene.particles)) } else { Default::default() };
    let sample_every = scene.sampling.every;
    // The tangent step relaxes the same scene again, its static set-up (critical γ_g, the
    // displacement bound) included; a static-only run has no MD tangent to measure (its
    // tangent moduli are the static answer's, `*_tangent_fem`).
    let tangent =
        spec.relax().and_then(|r| r.tangent_step).filter(|_| !spec.static_only()).map(|step| (step, scene.clone()));
    // A packing is measured again under strain from its relaxed state, by the scene of its last
    // stage (a compressed packing's box).
    let (packing_scene, mut outcome) = match spec.packing() {
        Some(_) => {
            let (last, outcome) = packing::relax(spec, scene);
            (Some(last), outcome)
        }
        None => (None, scene.run()),
    };
    if let Some(reason) = no_criterion {
        (outcome.trace.status, outcome.trace.message) = (RunStatus::NoEquilibrium, reason);
        (outcome.trace.relaxed_at, outcome.trace.relaxed_by) = (None, None);
    }
    measure(spec, &outcome, &start, &mut metrics);
    if let Some(scene) = &packing_scene {
        packing::measure(spec, scene, &outcome, &mut metrics.packing);
    }
    let discs =
        packing_scene.as_ref().filter(|_| spec.movie.is_some()).and_then(|s| packing::movie_discs(spec, s, &outcome));
    if let Some((step, again)) = tangent.filter(|_| outcome.trace.relaxed_at.is_some()) {
        tangent_step(spec, again, &outcome, step, &mut metrics);
    }
    let reference_s = measure_error(spec, &outcome, sample_every, deadline, &mut metrics);
    if let Some(l) = spec.lattice() {
        lattice::keep_probes(l, &mut outcome.trace);
    }
    Ok(Run { outcome, metrics, reference_s, bonds, supports, discs })
}

/// The run's error (`metrics.error`, `error_measure`): against its reference run at dt/R
/// when it has one and ran to the end or to a stop without equilibrium, else against the
/// exact answer. Returns the reference run's wall time (s), 0 without one.
fn measure_error(
    spec: &RunSpec,
    outcome: &Outcome,
    sample_every: u64,
    deadline: Instant,
    metrics: &mut Metrics,
) -> f64 {
    let started = Instant::now();
    let reference = spec
        .reference_refinement
        .filter(|_| outcome.trace.status == RunStatus::Ok || outcome.trace.status == RunStatus::NoEquilibrium)
        .and_then(|refinement| {
            reference_error(spec, &outcome.trace, sample_every, refinement, deadline).map(|e| (refinement, e))
        });
    let reference_s = if spec.reference_refinement.is_some() { started.elapsed().as_secs_f64() } else { 0.0 };
    (metrics.error, metrics.error_measure) = match reference {
        Some((refinement, error)) => (Some(error), Some(format!("reference_dt/{refinement}"))),
        None => exact_error(spec, metrics),
    };
    reference_s
}

/// The bonds a movie draws (i, j, rest length in m): every bond of `scene` but those across a
/// periodic side.
fn movie_bonds(scene: &Scene) -> Vec<(usize, usize, f64)> {
    let mut bonds = Vec::new();
    scene.network.for_each_bond(&scene.particles.x, &scene.particles.y, |i, j, rest, _, shift| {
        if shift == 0.0 {
            bonds.push((i, j, rest));
        }
    });
    bonds
}

/// The held particles of `particles` with the axes they are held along; a hold along y on
/// every particle (a 1D scene's line of motion) does not count.
fn supports(particles: &Particles) -> Vec<(usize, Axes)> {
    let one_dimensional = particles.held_y.len() == particles.len();
    (0..particles.len())
        .map(|i| {
            let x = particles.held_x.binary_search(&i).is_ok();
            let y = !one_dimensional && particles.held_y.binary_search(&i).is_ok();
            (i, Axes { x, y })
        })
        .filter(|(_, held)| held.x || held.y)
        .collect()
}

/// The caveat a successful run's record carries, if any.
pub fn caveat(spec: &RunSpec, metrics: &Metrics) -> Option<&'static str> {
    (spec.kind() == SceneKind::Pair).then(|| pair::caveat(&metrics.pair)).flatten()
}

/// Measures a finished run: the energy balance, what its kind measures, then its wave and
/// relaxation from the kind's facts (its linear sound speed, what its relaxation is judged
/// by). `start` holds the positions (x, y) at t = 0.
fn measure(spec: &RunSpec, outcome: &Outcome, start: &(Vec<f64>, Vec<f64>), metrics: &mut Metrics) {
    // A minimiser's steps (FIRE, CG) and the static solve follow no trajectory in time: they
    // remove energy by design, so they have no energy balance to hold (a 0 would be invented).
    let follows_time = spec.relax().is_none_or(|r| r.method == crate::sim::RelaxMethod::Damped);
    metrics.energy_error = if follows_time { energy_error(&outcome.trace) } else { None };
    let (wave_speed, relaxing) = match &spec.scene_kind {
        KindSpec::Pair(_) => {
            pair::measure(spec, outcome, &mut metrics.pair);
            (None, None)
        }
        KindSpec::Chain(chain) => {
            chain::measure(spec, chain, outcome, &mut metrics.chain);
            (chain::wave_speed(spec), Some(chain::relaxing(chain)))
        }
        KindSpec::Lattice(run) => {
            lattice::measure(spec, &run.lattice, outcome, start, &mut metrics.lattice);
            (lattice::wave_speed(spec, &run.lattice), Some(lattice::relaxing(&run.lattice)))
        }
        // Measured with its scene by `run`; relaxed by its largest static force.
        KindSpec::Packing(run) => (None, Some((run.packing.n, "k d^β (a contact overlapped by one small diameter)"))),
    };
    measure_wave(spec, outcome, wave_speed, metrics);
    if let Some((side, scale)) = relaxing {
        measure_relaxation(spec, outcome, side, scale, metrics);
    }
}

/// The arrival of a timed wave by every criterion, with the coursework's estimate and
/// `sound_speed_theory` (m/s), the kind's linear sound speed along the wave's path.
fn measure_wave(spec: &RunSpec, outcome: &Outcome, sound_speed_theory: Option<f64>, metrics: &mut Metrics) {
    if let (Some(wave), Some(record)) = (spec.wave(), &outcome.wave) {
        for criterion in ARRIVAL_CRITERIA {
            if let Some(time) = arrival_time(record, criterion, wave.threshold) {
                metrics.arrival_times.insert(criterion.to_string(), time);
            }
        }
        metrics.arrival_criterion = Some(ARRIVAL_CRITERIA[0].to_string());
        metrics.wave_distance = Some(wave.distance);
        metrics.arrival_time_tc_estimate = Some(wave.springs as f64 * spec.t_c);
        metrics.sound_speed_theory = sound_speed_theory;
    }
}

/// When and by which criterion a relaxing run came to rest, `side` as for the scene's
/// [`common::relaxation`], `scale` naming the force its residual-force criterion is relative to.
fn measure_relaxation(spec: &RunSpec, outcome: &Outcome, side: usize, scale: &str, metrics: &mut Metrics) {
    let Some(relax) = spec.relax() else { return };
    // A minimiser has no physical time: nothing dissipates over time there.
    metrics.dissipation_time = outcome.trace.relaxed_at.filter(|_| relax.method == RelaxMethod::Damped);
    let checks = relaxation_checks(side);
    let by_method =
        if relax.method == RelaxMethod::Damped { String::new() } else { format!(" ({})", relax.method.name()) };
    metrics.dissipation_criterion = outcome.trace.relaxed_by.as_deref().map(|by| match (by, relax.residual_force) {
        ("displacement_bound", _) => format!(
            "moduli within {:e} of rest by the displacement bound ‖K⁻¹g‖₂‖r‖₂{by_method}",
            relax.tolerance.unwrap_or_default()
        ),
        ("static_solution", _) => "none: the static solution of the same network (relax.method: static)".into(),
        ("residual_force", Some(fraction)) if relax.method != RelaxMethod::Damped => {
            format!("largest static force < {fraction:e} of {scale}{by_method}")
        }
        ("residual_force", Some(fraction)) => {
            format!("largest static force < {fraction:e} of {scale} at {checks} checks one t_c apart")
        }
        _ => format!("E_kin/E_pot < {:e} at {checks} checks one t_c apart", relax.kinetic_ratio),
    });
}

/// The small extra step after a relaxation: `scene` (the run's own, as set up before it ran)
/// from the relaxed state (at rest) with the load (a chain's wall displacement) raised by the
/// fraction `step`, relaxed again by the same method and criteria; tangent moduli (a chain's
/// tangent stiffness) are the increments' ratios. Nothing is set when the second relaxation
/// does not finish.
fn tangent_step(spec: &RunSpec, mut scene: Scene, relaxed: &Outcome, step: f64, metrics: &mut Metrics) {
    let start = &relaxed.state.particles;
    scene.particles.x.clone_from(&start.x);
    scene.particles.y.clone_from(&start.y);
    scene.particles.vx.fill(0.0);
    scene.particles.vy.fill(0.0);
    scene.load_ramp = 0.0;
    for load in &mut scene.loads {
        load.fx *= 1.0 + step;
        load.fy *= 1.0 + step;
    }
    let wall_step = step * spec.chain_wall_extension();
    if spec.kind() == SceneKind::Chain {
        let wall = scene.particles.len() - 1;
        scene.particles.x[wall] += wall_step;
    }
    let next = scene.run();
    if next.trace.relaxed_at.is_none() {
        return;
    }
    match &spec.scene_kind {
        KindSpec::Lattice(run) => {
            lattice::tangent_moduli(spec, &run.lattice, step, start, &next.state.particles, &mut metrics.lattice)
        }
        KindSpec::Chain(_) => {
            chain::tangent_stiffness(spec, wall_step, start, &next.state.particles, &mut metrics.chain)
        }
        // A pair never relaxes, and a packing has no tangent step.
        KindSpec::Pair(_) | KindSpec::Packing(_) => {}
    }
}

/// The error of a run against its exact answer: the contact duration (undamped pairs) or the
/// restitution (damped pairs), the normal-mode solution (chains), else the energy balance of
/// an undamped run; `(None, None)` when none applies.
fn exact_error(spec: &RunSpec, m: &Metrics) -> (Option<f64>, Option<String>) {
    let undamped = spec.gamma == 0.0 && spec.gamma_background == 0.0;
    let (error, measure) = match spec.kind() {
        SceneKind::Pair => pair::exact_error(undamped, &m.pair),
        SceneKind::Chain if m.chain.chain_mode_error.is_some() => (m.chain.chain_mode_error, "normal_modes"),
        _ if undamped => (m.energy_error, "energy"),
        _ => (None, ""),
    };
    (error, error.map(|_| measure.to_string()))
}

/// One run as the results table reads it: its spec, its metrics and the steps it took.
pub type RunRow<'a> = (&'a RunSpec, &'a Metrics, u64);

/// The kinds' result columns at `slot`, each named with its values over `runs`: the pair's,
/// the lattice's, then the chain's (the order the table has always had).
pub fn result_columns(slot: Slot, runs: &[RunRow]) -> Vec<(&'static str, Values)> {
    let mut columns = kind_columns(pair::columns(), slot, runs, |m| &m.pair);
    columns.extend(kind_columns(lattice::columns(), slot, runs, |m| &m.lattice));
    columns.extend(kind_columns(chain::columns(), slot, runs, |m| &m.chain));
    columns.extend(kind_columns(packing::columns(), slot, runs, |m| &m.packing));
    columns
}

/// The columns of one kind's `blocks` at `slot` that some run calls for, over `runs`, each
/// run read through its kind's metrics `group`.
fn kind_columns<G>(
    blocks: Vec<Block<G>>,
    slot: Slot,
    runs: &[RunRow],
    group: fn(&Metrics) -> &G,
) -> Vec<(&'static str, Values)> {
    let rows: Vec<Row<G>> = runs
        .iter()
        .map(|&(spec, m, steps)| Row {
            spec,
            group: group(m),
            dissipation_time: m.dissipation_time,
            dissipation_criterion: m.dissipation_criterion.as_deref(),
            steps,
        })
        .collect();
    blocks
        .into_iter()
        .filter(|b| b.slot == slot && b.shown.is_none_or(|shown| runs.iter().any(|(spec, _, _)| shown(spec))))
        .flat_map(|b| b.columns)
        .map(|column| (column.name(), column.values(&rows)))
        .collect()
}

/// Largest displacement difference between the run and the same scene at dt / `refinement`,
/// over the samples both have (the reference is sampled at the run's sample times and runs as
/// long, without stopping early), relative to the reference's largest displacement. The run
/// was sampled every `sample_every` steps.
fn reference_error(spec: &RunSpec, run: &Trace, sample_every: u64, refinement: u32, deadline: Instant) -> Option<f64> {
    let mut fine = spec.clone();
    fine.set_dt(spec.dt / f64::from(refinement));
    let mut scene = build_scene_until(&fine, deadline);
    let r = u64::from(refinement);
    scene.sampling.every = sample_every * r;
    scene.sampling.steps = run.steps * r;
    scene.sampling.relaxation = None;
    let reference = scene.run().trace;
    let (mut largest_difference, mut largest) = (0.0f64, 0.0f64);
    let mut k = 0;
    for (s, t) in run.time.iter().enumerate() {
        while k < reference.time.len() && reference.time[k] < t - 1e-9 * t.abs() {
            k += 1;
        }
        if k == reference.time.len() || (reference.time[k] - t).abs() > 1e-9 * t.abs() {
            continue;
        }
        for (mine, theirs) in [
            (&run.displacement_x[s], &reference.displacement_x[k]),
            (&run.displacement_y[s], &reference.displacement_y[k]),
        ] {
            for (a, b) in mine.iter().zip(theirs) {
                largest_difference = largest_difference.max((a - b).abs());
                largest = largest.max(b.abs());
            }
        }
    }
    (largest > 0.0).then(|| largest_difference / largest)
}
