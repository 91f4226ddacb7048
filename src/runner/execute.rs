//! One run: build the scene, solve the static problem of a lattice, integrate, measure; a
//! panic becomes a `panicked` record, a load that drives a mechanism a `mechanism` record.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

use super::record::{BUILD, Metrics, RunRecord};
use crate::draw::Movie;
use crate::fem::{StaticSolution, Truss};
use crate::measure::{
    ARRIVAL_CRITERIA, LatticeShape, anisotropic_moduli, arrival_time, constrained_modulus_y, contact_timing,
    energy_error, homogeneity, lattice_constants, normal_mode_error, shear_modulus, tensile_moduli,
};
use crate::model::{ForceLaw, LawVisitor};
use crate::plan::Estimates;
use crate::scenes::{
    build_scene, chain_equilibrium, chain_has_normal_modes, drive_travel, lattice_bonds, lattice_springs,
    pair_references, relaxation_checks, top_row,
};
use crate::sim::{Outcome, ProbeTrace, RunStatus, Scene, Trace, stored_samples};
use crate::spec::{Budget, Control, LatticeSpec, LoadCase, ProbeLine, RunSpec, SceneKind, reference_extension};

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
        Some(_) => Ok(Finished::OverBudget),
        None => catch_unwind(AssertUnwindSafe(|| run_and_measure(spec, deadline, estimates))),
    };
    let mut record = RunRecord {
        run_id: spec.run_id(),
        build: BUILD.into(),
        spec: spec.clone(),
        status: RunStatus::Ok,
        message: String::new(),
        wall_s: 0.0,
        steps: 0,
        metrics: Metrics::default(),
        trace: Trace::default(),
        movie: None,
    };
    let mut reference_s = 0.0;
    match result {
        Ok(Finished::Simulated(done)) => {
            let (mut outcome, metrics, reference_wall_s, movie) = *done;
            reference_s = reference_wall_s;
            record.movie = movie;
            if let Some(lattice) = &spec.lattice {
                // Recorded to compare with a reference run or to follow a wave: too bulky to
                // store whole. The probed lines are kept: an impulse lattice's kicked column
                // (the wave's straight path down, for the space–time picture) and the user's.
                let t = &mut outcome.trace;
                let kicked = lattice.impulse.map(|impulse| ProbeLine::Column(impulse.node % lattice.nx));
                let mut lines: Vec<ProbeLine> = kicked.into_iter().collect();
                lines.extend(lattice.probes.iter().filter(|&&line| Some(line) != kicked));
                if !t.displacement_x.is_empty() {
                    t.probes = lines
                        .into_iter()
                        .map(|line| ProbeTrace::from_trace(line.name(), line.nodes(lattice.nx, lattice.ny), t))
                        .collect();
                }
                (t.displacement_x, t.displacement_y, t.velocity_x, t.velocity_y) = Default::default();
            }
            record.status = outcome.trace.status;
            record.message = outcome.trace.message.clone();
            record.steps = outcome.trace.steps;
            if spec.kind == SceneKind::Pair && metrics.contact_duration.is_none() && record.message.is_empty() {
                record.message = "the contact did not close and open again within the run".into();
            }
            record.metrics = metrics;
            record.trace = outcome.trace;
            // Measured from every sample above; stored thinned, within a bounded size.
            record.trace.thin(stored_samples(record.trace.numbers_per_sample()));
        }
        Ok(Finished::Mechanism { residual }) => {
            record.status = RunStatus::Mechanism;
            record.message = format!(
                "the load drives a zero-stiffness motion: the static equations K u = f have no solution \
                 (relative residual {residual:.1e}); nothing to relax towards"
            );
        }
        Ok(Finished::OverBudget) => {
            record.status = RunStatus::Budget;
            record.message = refused.clone().unwrap_or_default();
        }
        Ok(Finished::PastDeadline { stage }) => {
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

/// How a run ended when it did not panic.
enum Finished {
    /// Integrated and measured, with the wall time (s) of the reference run, if any, and the
    /// movie, if asked for.
    Simulated(Box<(Outcome, Metrics, f64, Option<Movie>)>),
    /// The static problem is singular for this load: no MD run.
    Mechanism { residual: f64 },
    /// Not started: beyond the memory budget.
    OverBudget,
    /// Stopped before its time loop: the deadline passed in this stage.
    PastDeadline { stage: &'static str },
}

/// The scene of `spec`, its time loops stopped at `deadline`.
fn build_scene_until(spec: &RunSpec, deadline: Instant) -> Scene {
    let mut scene = build_scene(spec);
    scene.sampling.deadline = Some(deadline);
    scene
}

fn run_and_measure(spec: &RunSpec, deadline: Instant, estimates: &Estimates) -> Finished {
    assert!(spec.is_planned(), "a run reached the runner without its time step: plan the campaign (crate::plan)");
    let mut scene = build_scene_until(spec, deadline);
    let stability = estimates.stability(spec);
    let mut metrics = Metrics {
        omega_max: Some(stability.omega_max),
        dt_omega_max: Some(stability.dt_omega_max),
        mode_damping_ratio: Some(stability.damping_ratio),
        stability_limit: Some(stability.limit),
        ..Metrics::default()
    };
    if let Some(lattice) = spec.lattice.as_ref().filter(|l| l.impulse.is_none()) {
        let bonds = lattice_bonds(spec, lattice);
        if lattice.is_random() {
            let full = lattice_springs(spec, lattice).bond_count();
            metrics.bond_fraction_kept = Some(bonds.len() as f64 / full.max(1) as f64);
        }
        let (held_x, held_y, prescribed) = static_supports(spec, lattice, &scene);
        let p = &scene.particles;
        let truss = Truss {
            x: &p.x,
            y: &p.y,
            bonds: &bonds,
            held_x: &held_x,
            held_y: &held_y,
            loads: &scene.loads,
            prescribed: &prescribed,
        };
        let answer = scene.law.dispatch(StaticAnswer { spec, lattice, truss: &truss, deadline, metrics: &mut metrics });
        let top_row_force = match answer {
            Ok(force) => force,
            Err(stopped) => return stopped,
        };
        // Under velocity control the residual force is judged against the force the drive
        // holds at equilibrium (per top-row node), not the unused load_per_node.
        let fraction = spec.relax.and_then(|r| r.residual_force);
        if let (Control::Velocity, Some(fraction), Some(relaxation)) =
            (lattice.control, fraction, scene.sampling.relaxation.as_mut())
        {
            relaxation.residual_force = Some(fraction * (top_row_force / lattice.nx as f64).abs());
        }
    }
    let start = (scene.particles.x.clone(), scene.particles.y.clone());
    let mut bonds = Vec::new();
    if spec.movie.is_some() {
        scene.network.for_each_bond(|i, j, rest, _, shift| {
            if shift == 0.0 {
                bonds.push((i, j, rest));
            }
        });
    }
    let sample_every = scene.sampling.every;
    let mut outcome = scene.run();
    let movie = spec.movie.map(|movie| Movie {
        frames: std::mem::take(&mut outcome.frames),
        bonds,
        spec: movie,
        title: format!("{} {}", spec.scene, spec.varied_label(|_| true)),
        deadline: Some(deadline),
    });
    measure(spec, &outcome, &start, &mut metrics);
    if let Some(step) = spec.relax.and_then(|r| r.tangent_step).filter(|_| outcome.trace.relaxed_at.is_some()) {
        tangent_step(spec, &outcome, step, deadline, &mut metrics);
    }
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
        None => exact_error(spec, &metrics),
    };
    Finished::Simulated(Box::new((outcome, metrics, reference_s, movie)))
}

/// [`static_answer`] with the run's concrete law, from [`crate::model::LawSpec::dispatch`].
struct StaticAnswer<'a> {
    spec: &'a RunSpec,
    lattice: &'a LatticeSpec,
    truss: &'a Truss<'a>,
    deadline: Instant,
    metrics: &'a mut Metrics,
}

impl LawVisitor for StaticAnswer<'_> {
    type Output = Result<f64, Finished>;
    fn visit<L: ForceLaw>(self, law: L) -> Self::Output {
        static_answer(self.spec, self.lattice, self.truss, &law, self.deadline, self.metrics)
    }
}

/// The static answer of a loaded lattice beside MD: its moduli (`*_fem`), solved non-linearly
/// like MD; for linear springs how far that is from the linear answer; with a tangent step
/// the tangent moduli from the tangent stiffness at the equilibrium. Returns the total force
/// on the top row at the static equilibrium (N): the load, or what the drive must hold
/// (non-linear answer where it exists, else linear). `Err` when the load drives a mechanism,
/// or when `deadline` passes (checked between factorisations).
fn static_answer<L: ForceLaw>(
    spec: &RunSpec,
    lattice: &LatticeSpec,
    truss: &Truss,
    law: &L,
    deadline: Instant,
    metrics: &mut Metrics,
) -> Result<f64, Finished> {
    let past_deadline = || Finished::PastDeadline { stage: "static solve" };
    // The force on the top row: the load, or what the supports must apply to hold the
    // driven row where it is.
    let force = |ux: &[f64], uy: &[f64]| match lattice.control {
        Control::Force => lattice.total_load(),
        Control::Velocity => {
            let (fx, fy) = truss.reaction(law, ux, uy, &top_row(lattice));
            if lattice.load_case == LoadCase::Tensile { fy } else { fx }
        }
    };
    // The linear problem decides whether the network carries the load at all (a power law's
    // linear answer means nothing else).
    if Instant::now() > deadline {
        return Err(past_deadline());
    }
    let (linear, linear_force) = match truss.solve_linear() {
        StaticSolution::Mechanism { residual } => return Err(Finished::Mechanism { residual }),
        StaticSolution::PastDeadline => return Err(past_deadline()),
        StaticSolution::Displacements { ux, uy } => {
            let top = force(&ux, &uy);
            (lattice_moduli(spec, lattice, top, &ux, &uy), top)
        }
    };
    let (ux, uy) = match truss.solve_nonlinear(law, reference_extension(spec), Some(deadline)) {
        Some(StaticSolution::Displacements { ux, uy }) => (ux, uy),
        Some(StaticSolution::PastDeadline) => return Err(past_deadline()),
        _ => return Ok(linear_force),
    };
    let top_row_force = force(&ux, &uy);
    let fem = lattice_moduli(spec, lattice, top_row_force, &ux, &uy);
    if spec.law.is_linear() {
        // Relative for E and G; absolute for ν, which can be 0 (no diagonals).
        let relative = |a: Option<f64>, b: Option<f64>| crate::measure::relative_error(a, b).map(f64::abs);
        let absolute = fem.poisson_ratio.zip(linear.poisson_ratio).map(|(a, b)| (a - b).abs());
        metrics.static_nonlinearity = [
            relative(fem.youngs_modulus, linear.youngs_modulus),
            relative(fem.shear_modulus, linear.shear_modulus),
            absolute,
        ]
        .into_iter()
        .flatten()
        .reduce(f64::max);
    }
    metrics.youngs_modulus_fem = fem.youngs_modulus;
    metrics.poisson_ratio_fem = fem.poisson_ratio;
    metrics.shear_modulus_fem = fem.shear_modulus;
    if spec.relax.is_some_and(|r| r.tangent_step.is_some()) {
        // Δu per unit load factor: the increment of the whole load.
        if Instant::now() > deadline {
            return Err(past_deadline());
        }
        if let Some((dx, dy)) = truss.tangent_response(law, &ux, &uy) {
            let tangent = lattice_moduli(spec, lattice, lattice.total_load(), &dx, &dy);
            metrics.youngs_modulus_tangent_fem = tangent.youngs_modulus;
            metrics.poisson_ratio_tangent_fem = tangent.poisson_ratio;
            metrics.shear_modulus_tangent_fem = tangent.shear_modulus;
        }
    }
    Ok(top_row_force)
}

/// The small extra step after a relaxation: from the relaxed state (at rest), the load
/// (a chain's wall displacement) raised by the fraction `step`, relaxed again; tangent moduli
/// (a chain's tangent stiffness) are the increments' ratios. Nothing is set when the second
/// relaxation does not finish.
fn tangent_step(spec: &RunSpec, relaxed: &Outcome, step: f64, deadline: Instant, metrics: &mut Metrics) {
    let mut scene = build_scene_until(spec, deadline);
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
    if spec.kind == SceneKind::Chain {
        let wall = scene.particles.len() - 1;
        scene.particles.x[wall] += wall_step;
    }
    let next = scene.run();
    if next.trace.relaxed_at.is_none() {
        return;
    }
    let end = &next.state.particles;
    match &spec.lattice {
        Some(lattice) => {
            let dx: Vec<f64> = end.x.iter().zip(&start.x).map(|(b, a)| b - a).collect();
            let dy: Vec<f64> = end.y.iter().zip(&start.y).map(|(b, a)| b - a).collect();
            let tangent = lattice_moduli(spec, lattice, step * lattice.total_load(), &dx, &dy);
            metrics.youngs_modulus_tangent = tangent.youngs_modulus;
            metrics.poisson_ratio_tangent = tangent.poisson_ratio;
            metrics.shear_modulus_tangent = tangent.shear_modulus;
        }
        None if wall_step != 0.0 => {
            let before = wall_force(spec, &start.x);
            metrics.tangent_stiffness = Some((wall_force(spec, &end.x) - before) / wall_step);
        }
        None => {}
    }
}

/// Tension (N) of a chain's first spring, between the left wall and particle 1.
fn wall_force(spec: &RunSpec, x: &[f64]) -> f64 {
    spec.law.elastic_force(spec.k, x[1] - x[0] - spec.spacing)
}

/// The linear sound speed along the wave's path (m/s): a√(k/m) along a chain; in a lattice
/// kicked or stepped mostly along y (the bottom row is below) the longitudinal c_L = a√((k + k_d)/m),
/// kicked mostly along x the transverse c_T = a√(k_d/m). `None` for power-law springs, which
/// have no linear sound speed without pre-load.
fn sound_speed_theory(spec: &RunSpec) -> Option<f64> {
    if !spec.law.is_linear() {
        return None;
    }
    // c = a √(C/m) with C = C22 (longitudinal) or C66 (transverse) per unit depth: the mass
    // per unit area is m/a².
    let speed = |c: f64| (c > 0.0).then(|| spec.spacing * (c / spec.mass).sqrt());
    match spec.lattice.as_ref().and_then(|l| l.impulse.map(|i| (l, i))) {
        None => speed(spec.k),
        Some((l, i)) => {
            let (k_rising, k_falling) = l.diagonal_stiffness();
            let c = lattice_constants(l.k_x, l.k_y, k_rising, k_falling);
            speed(if i.direction()[1].abs() >= i.direction()[0].abs() { c.c22 } else { c.c66 })
        }
    }
}

/// The error of a run against its exact answer: the contact duration (undamped pairs) or the
/// restitution (damped pairs), the normal-mode solution (chains), else the energy balance of
/// an undamped run; `(None, None)` when none applies.
fn exact_error(spec: &RunSpec, m: &Metrics) -> (Option<f64>, Option<String>) {
    let relative = |a, b| crate::measure::relative_error(a, b).map(f64::abs);
    let undamped = spec.gamma == 0.0 && spec.gamma_background == 0.0;
    let (error, measure) = match spec.kind {
        SceneKind::Pair if undamped => (relative(m.contact_duration, m.contact_duration_theory), "contact_duration"),
        SceneKind::Pair => (relative(m.restitution, m.restitution_theory), "restitution"),
        SceneKind::Chain if m.chain_mode_error.is_some() => (m.chain_mode_error, "normal_modes"),
        _ if undamped => (m.energy_error, "energy"),
        _ => (None, ""),
    };
    (error, error.map(|_| measure.to_string()))
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

/// Held axes of the static problem and the displacements imposed on them: the scene's
/// supports, plus, under velocity control, the top row held where the drive leaves it.
type StaticSupports = (Vec<usize>, Vec<usize>, Vec<(usize, f64, f64)>);

fn static_supports(spec: &RunSpec, lattice: &LatticeSpec, scene: &Scene) -> StaticSupports {
    let mut supported = scene.particles.clone();
    let mut prescribed = Vec::new();
    if lattice.control == Control::Velocity {
        let travel = drive_travel(spec, lattice);
        let tensile = lattice.load_case == LoadCase::Tensile;
        for node in top_row(lattice) {
            supported.hold(node, tensile);
            prescribed.push(if tensile { (node, 0.0, travel) } else { (node, travel, 0.0) });
        }
    }
    (supported.held_x, supported.held_y, prescribed)
}

/// The moduli a lattice's load case measures; the others stay `None`.
struct LatticeModuli {
    youngs_modulus: Option<f64>,
    poisson_ratio: Option<f64>,
    poisson_ratio_coursework: Option<f64>,
    shear_modulus: Option<f64>,
}

/// The moduli from the total top-row force `force` (N) and the node displacements.
fn lattice_moduli(spec: &RunSpec, lattice: &LatticeSpec, force: f64, ux: &[f64], uy: &[f64]) -> LatticeModuli {
    let shape = lattice_shape(spec, lattice);
    match lattice.load_case {
        LoadCase::Tensile | LoadCase::TensileX => {
            let t = tensile_moduli(&shape, force, ux, uy);
            LatticeModuli {
                youngs_modulus: Some(t.youngs_modulus),
                poisson_ratio: Some(t.poisson_ratio),
                poisson_ratio_coursework: Some(t.poisson_ratio_coursework),
                shear_modulus: None,
            }
        }
        LoadCase::Shear => LatticeModuli {
            youngs_modulus: None,
            poisson_ratio: None,
            poisson_ratio_coursework: None,
            shear_modulus: Some(shear_modulus(&shape, force, ux)),
        },
    }
}

fn measure(spec: &RunSpec, outcome: &Outcome, start: &(Vec<f64>, Vec<f64>), metrics: &mut Metrics) {
    let timing = contact_timing(&outcome.crossings);
    let (contact_duration_theory, restitution_theory) = pair_references(spec);
    metrics.contact_duration = timing.map(|t| t.duration);
    metrics.contact_duration_theory = contact_duration_theory;
    metrics.restitution = timing.map(|t| t.restitution);
    metrics.restitution_theory = restitution_theory;
    metrics.energy_error = energy_error(&outcome.trace);
    metrics.chain_mode_error = chain_has_normal_modes(spec)
        .then(|| {
            let n = spec.n.unwrap_or(0);
            let movable: Vec<usize> = (1..=n).collect();
            let v0: Vec<f64> = movable.iter().map(|&p| if Some(p) == spec.node { spec.v0 } else { 0.0 }).collect();
            normal_mode_error(&outcome.trace, &movable, &v0, spec.k, spec.mass)
        })
        .flatten();
    if let (Some(wave), Some(record)) = (&spec.wave, &outcome.wave) {
        for criterion in ARRIVAL_CRITERIA {
            if let Some(time) = arrival_time(record, criterion, wave.threshold) {
                metrics.arrival_times.insert(criterion.to_string(), time);
            }
        }
        metrics.arrival_criterion = Some(ARRIVAL_CRITERIA[0].to_string());
        metrics.wave_distance = Some(wave.distance);
        metrics.arrival_time_tc_estimate = Some(wave.springs as f64 * spec.t_c);
        metrics.sound_speed_theory = sound_speed_theory(spec);
    }
    if spec.kind == SceneKind::Chain && spec.relax.is_some() {
        let relaxed = outcome.trace.relaxed_at.is_some();
        let keep = |value: Option<f64>| value.filter(|_| relaxed);
        let x = &outcome.state.particles.x;
        let gaps: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let inner = &gaps[..gaps.len() - 1];
        let (shortest, longest) =
            gaps.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), g| (a.min(*g), b.max(*g)));
        let (delta, force, secant, tangent) = chain_equilibrium(spec);
        let extension = spec.chain_wall_extension();
        let measured_force = wall_force(spec, x);
        metrics.equilibrium_spacing = keep(Some(inner.iter().sum::<f64>() / inner.len() as f64));
        metrics.spacing_spread = keep(Some(longest - shortest));
        metrics.equilibrium_spacing_theory = Some(spec.spacing + delta);
        metrics.wall_force = keep(Some(measured_force));
        metrics.wall_force_theory = Some(force);
        metrics.secant_stiffness = keep((extension != 0.0).then(|| measured_force / extension));
        metrics.secant_stiffness_theory = Some(secant);
        metrics.tangent_stiffness_theory = Some(tangent);
    }
    if let Some(lattice) = spec.lattice.as_ref().filter(|l| l.impulse.is_none()) {
        let p = &outcome.state.particles;
        let ux: Vec<f64> = p.x.iter().zip(&start.0).map(|(x, x0)| x - x0).collect();
        let uy: Vec<f64> = p.y.iter().zip(&start.1).map(|(y, y0)| y - y0).collect();
        let relaxed = outcome.trace.relaxed_at.is_some();
        let force = match lattice.control {
            Control::Force => lattice.total_load(),
            Control::Velocity => outcome.state.drive_force,
        };
        let md = lattice_moduli(spec, lattice, force, &ux, &uy);
        // Moduli of a run that never came to rest would be snapshots of an oscillation.
        let keep = |value: Option<f64>| value.filter(|_| relaxed);
        metrics.youngs_modulus = keep(md.youngs_modulus);
        metrics.poisson_ratio = keep(md.poisson_ratio);
        metrics.poisson_ratio_coursework = keep(md.poisson_ratio_coursework);
        metrics.shear_modulus = keep(md.shear_modulus);
        let shape = lattice_shape(spec, lattice);
        metrics.homogeneity = keep(homogeneity(&shape, &ux));
        // The continuum of the regular linear lattice (a random one is compared with it).
        if spec.law.is_linear() {
            let (k_rising, k_falling) = lattice.diagonal_stiffness();
            let continuum = anisotropic_moduli(lattice.k_x, lattice.k_y, k_rising, k_falling, lattice.depth);
            // A periodic strip cannot contract sideways: in tension it measures the
            // constrained modulus (C22 = (k + k_d)/d with both diagonals), with ν = 0.
            if lattice.supports == crate::spec::Supports::PeriodicX {
                let strip = constrained_modulus_y(lattice.k_x, lattice.k_y, k_rising, k_falling, lattice.depth);
                metrics.youngs_modulus_theory = Some(strip);
                metrics.poisson_ratio_theory = Some(0.0);
            } else {
                metrics.youngs_modulus_theory = Some(continuum.youngs_modulus_y);
                metrics.poisson_ratio_theory = Some(continuum.poisson_ratio_yx);
            }
            metrics.shear_modulus_theory = continuum.shear_modulus;
        }
    }
    if let Some(relax) = spec.relax {
        metrics.dissipation_time = outcome.trace.relaxed_at;
        let checks = relaxation_checks(spec);
        let scale = match &spec.lattice {
            Some(l) if l.control == Control::Velocity => "the drive's static force per node",
            Some(_) => "the load per node",
            None => "the wall force",
        };
        metrics.dissipation_criterion =
            outcome.trace.relaxed_by.as_deref().map(|by| match (by, relax.residual_force) {
                ("residual_force", Some(fraction)) => {
                    format!("largest static force < {fraction:e} of {scale} at {checks} checks one t_c apart")
                }
                _ => format!("E_kin/E_pot < {:e} at {checks} checks one t_c apart", relax.kinetic_ratio),
            });
    }
}

fn lattice_shape(spec: &RunSpec, lattice: &LatticeSpec) -> LatticeShape {
    LatticeShape {
        nx: lattice.nx,
        ny: lattice.ny,
        spacing: spec.spacing,
        depth: lattice.depth,
        periodic_x: lattice.supports == crate::spec::Supports::PeriodicX,
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
