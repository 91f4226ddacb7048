//! The time loop: start, step, probe every step, sample every few steps, stop on blow-up.

use super::field::ForceField;
use super::integrate::{Integrator, static_forces, take_step};
use super::probe::StepProbe;
use super::state::State;

/// How a run ended: the time loop sets the first four, the runner the last two. Serialised
/// (records, the `status` column) as the snake-case word [`RunStatus::as_str`] gives.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunStatus {
    /// Ran to its end time.
    #[default]
    Ok,
    /// Stopped because it blew up: non-finite or runaway energy, or a collapsed bond.
    Unstable,
    /// A relaxation that did not reach its criterion within its time.
    NoEquilibrium,
    /// Stopped at its wall-clock deadline (the campaign's time budget per run), or refused
    /// for its estimated memory.
    Budget,
    /// The load drives a zero-stiffness motion of the network: nothing was simulated.
    Mechanism,
    /// The run panicked; the message says where.
    Panicked,
}

impl RunStatus {
    /// The word written in records and the `status` column.
    pub fn as_str(self) -> &'static str {
        match self {
            RunStatus::Ok => "ok",
            RunStatus::Unstable => "unstable",
            RunStatus::NoEquilibrium => "no_equilibrium",
            RunStatus::Budget => "budget",
            RunStatus::Mechanism => "mechanism",
            RunStatus::Panicked => "panicked",
        }
    }
}

impl std::fmt::Display for RunStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// What to record, and how often.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampling {
    /// Time step (s).
    pub dt: f64,
    /// Steps to take.
    pub steps: u64,
    /// Record a sample every this many steps (and at the start and the end).
    pub every: u64,
    /// Record the displacements and velocities of every particle at each sample.
    pub displacements: bool,
    /// Stop early once relaxed.
    pub relaxation: Option<Relaxation>,
    /// Stop with [`RunStatus::Budget`] once the wall clock passes this instant.
    pub deadline: Option<std::time::Instant>,
}

impl Sampling {
    /// `steps` steps of `dt` (s), sampled at the start and the end only, without displacements,
    /// relaxation or deadline.
    pub fn new(dt: f64, steps: u64) -> Sampling {
        Sampling { dt, steps, every: steps.max(1), displacements: false, relaxation: None, deadline: None }
    }
}

/// Steps between looks at the clock for the deadline: ~25 ns per look, so at most a few
/// per cent of the cheapest step (a pair, ~100 ns) and at most a few ms late on a 10⁶-particle
/// lattice (~3 ms per step).
const DEADLINE_CHECK_STEPS: u64 = 64;

/// When a relaxation counts as finished: E_kin/E_pot below `kinetic_ratio` at `confirmations`
/// consecutive checks `check_every` steps apart. One low value is not enough: the kinetic
/// energy of a ringing structure passes near zero at every turning point of its main mode, so
/// the checks must span more than that mode's period.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Relaxation {
    /// Tolerance on E_kin/E_pot.
    pub kinetic_ratio: f64,
    /// Tolerance (N) on the largest static force (springs and loads) on any free axis; when
    /// given, this criterion replaces the kinetic-energy ratio.
    pub residual_force: Option<f64>,
    /// The displacement bound: relaxed once the static force's norm ‖r‖₂ (N, over every free
    /// axis) is at most this, at a single check (the bound |δΔL| ≤ ‖K_t⁻¹ g‖₂ ‖r‖₂ on the
    /// measured extension holds at any instant, whatever the velocities); when given, it
    /// replaces both criteria above.
    pub residual_norm: Option<f64>,
    /// Steps between checks.
    pub check_every: u64,
    /// Consecutive checks that must pass.
    pub confirmations: u32,
}

/// Sampled time series of a run and how it ended.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Trace {
    /// Sample times (s).
    pub time: Vec<f64>,
    /// Kinetic energy (J).
    pub kinetic: Vec<f64>,
    /// Potential energy (J).
    pub potential: Vec<f64>,
    /// Energy dissipated so far (J).
    pub dissipated: Vec<f64>,
    /// Work done by the loads so far (J).
    pub work: Vec<f64>,
    /// x displacement of every particle from its start position (m), one row per sample;
    /// empty unless asked for.
    pub displacement_x: Vec<Vec<f64>>,
    /// y displacement of every particle (m), recorded with the x displacements.
    #[serde(default)]
    pub displacement_y: Vec<Vec<f64>>,
    /// x velocity of every particle (m/s) at each sample, recorded with the displacements.
    #[serde(default)]
    pub velocity_x: Vec<Vec<f64>>,
    /// y velocity of every particle (m/s) at each sample, recorded with the displacements.
    #[serde(default)]
    pub velocity_y: Vec<Vec<f64>>,
    /// Lattice: the probed lines of nodes (an impulse lattice's kicked column first), kept
    /// from the per-particle series, which are too bulky to store whole.
    #[serde(default)]
    pub probes: Vec<ProbeTrace>,
    /// Steps actually taken.
    pub steps: u64,
    /// Wall time of the time loop (s), set-up excluded.
    pub loop_s: f64,
    /// Why the run ended.
    pub status: RunStatus,
    /// Explanation when the status is not `ok`.
    pub message: String,
    /// Relaxation: the time (s) from which the stopping criterion held.
    pub relaxed_at: Option<f64>,
    /// Relaxation: the criterion that stopped the run, `kinetic_ratio`, `residual_force` or
    /// `displacement_bound`; `static_solution` for a run set to its static answer.
    pub relaxed_by: Option<String>,
    /// Relaxation: the norm ‖r‖₂ (N) of the static force (springs and loads) at the end.
    #[serde(default)]
    pub residual_norm: Option<f64>,
}

/// The motion of one line of nodes (a lattice row or column), one row per sample and one
/// entry per node along the line.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ProbeTrace {
    /// `row 0`, `column 9`.
    pub name: String,
    /// The nodes, in order along the line.
    pub nodes: Vec<usize>,
    /// x displacement from the start (m).
    pub displacement_x: Vec<Vec<f64>>,
    /// y displacement from the start (m).
    pub displacement_y: Vec<Vec<f64>>,
    /// x velocity (m/s).
    pub velocity_x: Vec<Vec<f64>>,
    /// y velocity (m/s).
    pub velocity_y: Vec<Vec<f64>>,
}

/// A stored trace (a run's record) holds at most this many numbers, 4 or 8 bytes each before
/// compression in its series file (`runner::record`), ...
pub const STORED_NUMBERS: usize = 2_000_000;
/// ... and at most this many samples: more than a figure shows (its lines are thinned to
/// `draw::chart::LINE_POINTS`) while keeping the shape of every series.
pub const STORED_SAMPLES: usize = 10_000;

/// Samples a stored trace keeps when each sample holds `numbers` numbers: within both bounds,
/// at least the first and the last.
pub fn stored_samples(numbers: usize) -> usize {
    (STORED_NUMBERS / numbers.max(1)).clamp(2, STORED_SAMPLES)
}

impl Trace {
    /// Numbers one sample holds: time, four energies, and four per particle or probed node.
    pub fn numbers_per_sample(&self) -> usize {
        let particles = self.displacement_x.first().map_or(0, Vec::len);
        5 + 4 * (particles + self.probes.iter().map(|p| p.nodes.len()).sum::<usize>())
    }

    /// Keeps at most `most` (≥ 2) samples, evenly spread, the first and the last among them:
    /// what a record stores of a long run (its measurements were taken from every sample).
    pub fn thin(&mut self, most: usize) {
        let len = self.time.len();
        if len <= most.max(2) {
            return;
        }
        // Samples 0, s, 2s, ... and the last: at most `most`.
        let stride = (len - 1).div_ceil(most.max(2) - 1);
        let keep = |index: usize| index.is_multiple_of(stride) || index == len - 1;
        fn retain<T>(series: &mut Vec<T>, keep: &impl Fn(usize) -> bool) {
            let mut index = 0;
            series.retain(|_| {
                index += 1;
                keep(index - 1)
            });
            series.shrink_to_fit();
        }
        for series in [&mut self.time, &mut self.kinetic, &mut self.potential, &mut self.dissipated, &mut self.work] {
            retain(series, &keep);
        }
        let per_particle =
            [&mut self.displacement_x, &mut self.displacement_y, &mut self.velocity_x, &mut self.velocity_y];
        for series in per_particle {
            retain(series, &keep);
        }
        for probe in &mut self.probes {
            for series in
                [&mut probe.displacement_x, &mut probe.displacement_y, &mut probe.velocity_x, &mut probe.velocity_y]
            {
                retain(series, &keep);
            }
        }
    }
}

impl ProbeTrace {
    /// Picks the line `nodes` called `name` out of the per-particle series of `trace`.
    pub fn from_trace(name: String, nodes: Vec<usize>, trace: &Trace) -> ProbeTrace {
        let pick = |series: &[Vec<f64>]| -> Vec<Vec<f64>> {
            series.iter().map(|row| nodes.iter().map(|&i| row[i]).collect()).collect()
        };
        ProbeTrace {
            displacement_x: pick(&trace.displacement_x),
            displacement_y: pick(&trace.displacement_y),
            velocity_x: pick(&trace.velocity_x),
            velocity_y: pick(&trace.velocity_y),
            name,
            nodes,
        }
    }
}

/// Stored energy may exceed what the start and the loads' work allow by this factor before a
/// run counts as blown up. Generous on purpose: a symplectic scheme just inside its stability
/// limit stores up to 1/(1 − (ω dt/2)²) times the energy in its fastest mode (velocity Verlet
/// at ω dt = 1.9: 10×), while a run beyond the limit grows exponentially and passes any factor.
pub const ENERGY_GROWTH_LIMIT: f64 = 1e3;

/// A bond whose length along its start direction falls below this fraction of its start
/// length has collapsed (or, below zero, inverted): the particles passed through each other.
/// Shared with the plan, which refuses a collision that may reach it (`plan::overlap`).
pub const COLLAPSE_RATIO: f64 = 0.05;

/// Positions at t = 0, for displacements and for the collapse check.
pub(super) struct Start {
    x: Vec<f64>,
    y: Vec<f64>,
}

impl Start {
    /// The positions of `state` now.
    pub(super) fn of(state: &State) -> Start {
        Start { x: state.particles.x.clone(), y: state.particles.y.clone() }
    }
}

impl Trace {
    /// Appends one sample of `state`; refuses, recording nothing, when the state has blown up
    /// (so nothing non-finite reaches a table) and says why.
    pub(super) fn sample<F: ForceField>(
        &mut self,
        state: &State,
        field: &F,
        start: &Start,
        displacements: bool,
    ) -> Result<(), String> {
        let p = &state.particles;
        let kinetic = p.kinetic_energy();
        let potential = field.potential_energy(&p.x, &p.y);
        let work = state.load_work();
        if !(kinetic + potential + state.dissipated + work).is_finite() {
            return Err("the energy became non-finite".into());
        }
        if let (Some(k0), Some(p0)) = (self.kinetic.first(), self.potential.first()) {
            let allowed = k0 + p0 + work.abs();
            if allowed > 0.0 && kinetic + potential > ENERGY_GROWTH_LIMIT * allowed {
                return Err(format!(
                    "the stored energy grew to {:.3e} J, more than {ENERGY_GROWTH_LIMIT:e} × the {allowed:.3e} J that \
                     the start and the loads' work allow",
                    kinetic + potential
                ));
            }
        }
        if let Some((i, j, ratio)) = collapsed_bond(field, &p.x, &p.y, start) {
            return Err(format!(
                "the bond {i}–{j} collapsed: its length along its start direction is {ratio:.3} of its start length \
                 (below {COLLAPSE_RATIO}; negative means the particles passed through each other)"
            ));
        }
        self.time.push(state.time);
        self.kinetic.push(kinetic);
        self.potential.push(potential);
        self.dissipated.push(state.dissipated);
        self.work.push(work);
        if displacements {
            self.displacement_x.push(p.x.iter().zip(&start.x).map(|(x, x0)| x - x0).collect());
            self.displacement_y.push(p.y.iter().zip(&start.y).map(|(y, y0)| y - y0).collect());
            self.velocity_x.push(p.vx.clone());
            self.velocity_y.push(p.vy.clone());
        }
        Ok(())
    }
}

/// The bond most compressed along its start direction, when that is below [`COLLAPSE_RATIO`]:
/// `(i, j, ratio)` with ratio = (d · d₀)/|d₀|² for separations d now and d₀ at t = 0.
fn collapsed_bond<F: ForceField>(field: &F, x: &[f64], y: &[f64], start: &Start) -> Option<(usize, usize, f64)> {
    let mut worst: Option<(usize, usize, f64)> = None;
    field.for_each_bond(&mut |i, j, _rest, _k, shift| {
        let (dx, dy) = (x[i] - x[j] + shift, y[i] - y[j]);
        let (dx0, dy0) = (start.x[i] - start.x[j] + shift, start.y[i] - start.y[j]);
        let ratio = (dx * dx0 + dy * dy0) / (dx0 * dx0 + dy0 * dy0);
        if ratio < COLLAPSE_RATIO && worst.is_none_or(|(_, _, r)| ratio < r) {
            worst = Some((i, j, ratio));
        }
    });
    worst
}

/// Runs `sampling.steps` steps of `integrator` on `state` under `field` (split where a damped
/// contact switches), showing every step and every switch to `probe`; stops early with
/// [`RunStatus::Unstable`] when a sample finds the run blown up (non-finite energy, energy
/// grown beyond what loads allow, a collapsed bond).
pub fn simulate<F: ForceField, I: Integrator, P: StepProbe>(
    state: &mut State,
    field: &mut F,
    integrator: &mut I,
    sampling: &Sampling,
    probe: &mut P,
) -> Trace {
    let start = Start::of(state);
    let mut trace = Trace::with_room_for(sampling);
    integrator.start(state, field, sampling.dt);
    probe.observe(state);
    if let Err(reason) = trace.sample(state, &*field, &start, sampling.displacements) {
        trace.status = RunStatus::Unstable;
        trace.message = format!("{reason} at the start");
        return trace;
    }
    let every = sampling.every.max(1);
    let mut watch = sampling.relaxation.map(RelaxationWatch::new);
    let started = std::time::Instant::now();
    for n in 1..=sampling.steps {
        take_step(integrator, state, field, sampling.dt, probe);
        state.advance_drive();
        probe.observe(state);
        let relaxed = watch.as_mut().is_some_and(|w| w.relaxed(n, state, field));
        if (n % every == 0 || n == sampling.steps || relaxed)
            && let Err(reason) = trace.sample(state, &*field, &start, sampling.displacements)
        {
            trace.status = RunStatus::Unstable;
            trace.message = format!("{reason} at t = {:.6e} s (step {n})", state.time);
            break;
        }
        if relaxed || probe.seen_enough() {
            break;
        }
        if let Some(deadline) = sampling.deadline
            && n.is_multiple_of(DEADLINE_CHECK_STEPS)
            && std::time::Instant::now() > deadline
        {
            trace.status = RunStatus::Budget;
            trace.message = format!(
                "stopped at its deadline after {:.3} s of time loop, at t = {:.6e} s (step {n} of {})",
                started.elapsed().as_secs_f64(),
                state.time,
                sampling.steps
            );
            break;
        }
    }
    trace.loop_s = started.elapsed().as_secs_f64();
    if let Some(mut w) = watch {
        trace.residual_norm = Some(w.residual_norm(state, field));
        w.judge(&mut trace, state.time);
    }
    trace.steps = state.steps;
    trace
}

impl Trace {
    /// An empty trace with room for every sample of `sampling` (the start, every `every` steps,
    /// the end, the relaxed state) up front: growing the series by doubling would leave freed
    /// blocks resident, ~2.5 × the series at the peak (untouched room costs no memory).
    fn with_room_for(sampling: &Sampling) -> Trace {
        let mut trace = Trace::default();
        let samples = (sampling.steps / sampling.every.max(1)) as usize + 3;
        for series in
            [&mut trace.time, &mut trace.kinetic, &mut trace.potential, &mut trace.dissipated, &mut trace.work]
        {
            series.reserve_exact(samples);
        }
        if sampling.displacements {
            for series in
                [&mut trace.displacement_x, &mut trace.displacement_y, &mut trace.velocity_x, &mut trace.velocity_y]
            {
                series.reserve_exact(samples);
            }
        }
        trace
    }
}

/// Follows the relaxation criterion in force: it must hold at `confirmations` consecutive checks.
struct RelaxationWatch {
    rule: Relaxation,
    streak: Streak,
    relaxed: Option<(f64, &'static str)>,
    /// Scratch for the static forces (x, y) and zero velocities.
    scratch: (Vec<f64>, Vec<f64>, Vec<f64>),
}

/// A run of consecutive passed checks and the time of its first.
#[derive(Default)]
struct Streak {
    passed: u32,
    since: f64,
}

impl Streak {
    /// Counts one check at `time`; true once `needed` checks in a row have passed.
    fn update(&mut self, pass: bool, time: f64, needed: u32) -> bool {
        if !pass {
            self.passed = 0;
            return false;
        }
        if self.passed == 0 {
            self.since = time;
        }
        self.passed += 1;
        self.passed >= needed
    }
}

impl RelaxationWatch {
    fn new(rule: Relaxation) -> Self {
        RelaxationWatch { rule, streak: Streak::default(), relaxed: None, scratch: Default::default() }
    }

    /// Writes the verdict into `trace` at the end of a run that stopped at `time` (s): when
    /// and by which criterion it relaxed, or `no_equilibrium` if a run otherwise ok never did.
    fn judge(self, trace: &mut Trace, time: f64) {
        trace.relaxed_at = self.relaxed.map(|(at, _)| at);
        trace.relaxed_by = self.relaxed.map(|(_, by)| by.to_string());
        if trace.relaxed_at.is_none() && trace.status == RunStatus::Ok {
            trace.status = RunStatus::NoEquilibrium;
            let criterion = match (self.rule.residual_norm, self.rule.residual_force) {
                (Some(norm), _) => format!("the static force's norm did not fall below {norm:e} N"),
                (None, Some(force)) => format!("the largest static force did not stay below {force:e} N"),
                (None, None) => format!("E_kin/E_pot did not stay below {:e}", self.rule.kinetic_ratio),
            };
            trace.message = format!("{criterion} within {time:.6e} s");
        }
    }

    /// ‖r‖₂ (N): the norm of the static force (springs and loads) at `state`'s positions.
    fn residual_norm<F: ForceField>(&mut self, state: &State, field: &mut F) -> f64 {
        let (fx, fy, zeros) = &mut self.scratch;
        static_forces(state, field, fx, fy, zeros);
        fx.iter().chain(fy.iter()).map(|f| f * f).sum::<f64>().sqrt()
    }

    /// True once a criterion holds; checks only every `check_every` steps.
    fn relaxed<F: ForceField>(&mut self, step: u64, state: &State, field: &mut F) -> bool {
        // Nothing is at rest before the loads are fully on.
        if !step.is_multiple_of(self.rule.check_every.max(1)) || state.time < state.settling_from() {
            return false;
        }
        let p = &state.particles;
        // One criterion is in force: the displacement bound when asked for, else the residual
        // static force when asked for, else E_kin/E_pot.
        if let Some(limit) = self.rule.residual_norm {
            if self.residual_norm(state, field) <= limit {
                self.relaxed = Some((state.time, "displacement_bound"));
            }
            return self.relaxed.is_some();
        }
        let (calm, criterion) = if let Some(tolerance) = self.rule.residual_force {
            // The static imbalance, not the net force: a creeping, overdamped structure has a
            // small net force (drag balances springs) long before it is in equilibrium.
            let (fx, fy, zeros) = &mut self.scratch;
            static_forces(state, field, fx, fy, zeros);
            let largest = fx.iter().chain(fy.iter()).fold(0.0f64, |m, f| m.max(f.abs()));
            (largest < tolerance, "residual_force")
        } else {
            let potential = field.potential_energy(&p.x, &p.y);
            (potential > 0.0 && p.kinetic_energy() < self.rule.kinetic_ratio * potential, "kinetic_ratio")
        };
        if self.streak.update(calm, state.time, self.rule.confirmations) {
            self.relaxed = Some((self.streak.since, criterion));
        }
        self.relaxed.is_some()
    }
}
