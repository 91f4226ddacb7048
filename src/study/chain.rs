//! The chain: n particles between two walls, hit (a wave, normal modes) or relaxing after a
//! wall is moved. Its scene, its normal-mode solution, equilibrium and sound speed, and its
//! measurement.

use serde::{Deserialize, Serialize};

use super::columns::{Block, Column, Slot};
use super::common::{relaxation, scene, sound_speed};
use crate::measure::{ARRIVAL_CRITERIA, arrival_time, decay_rate, normal_mode_error};
use crate::model::{Axes, Particles, SquareLattice};
use crate::sim::{Network, Outcome, Scene, WaveRecord};
use crate::spec::{ChainRun, RunSpec, WaveSpec};
use crate::theory::ChainModes;

/// What a chain measures, with its analytical twins.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ChainMetrics {
    /// Chain: largest phase-space deviation from the normal-mode solution, relative (see
    /// `measure::normal_mode_error`).
    pub chain_mode_error: Option<f64>,
    /// Timed chain with normal modes: the exact discrete chain's front speed L / t_exact (m/s),
    /// t_exact its arrival by the run's own criterion and threshold (see `exact_front_speed`).
    #[serde(default)]
    pub sound_speed_exact: Option<f64>,
    /// Relaxing chain: mean gap (m) of all springs but the last (which starts with the whole
    /// wall displacement).
    #[serde(default)]
    pub equilibrium_spacing: Option<f64>,
    /// Relaxing chain: equilibrium gap W/(n + 1) (m).
    #[serde(default)]
    pub equilibrium_spacing_theory: Option<f64>,
    /// Relaxing chain: largest minus smallest gap (m); 0 at equilibrium.
    #[serde(default)]
    pub spacing_spread: Option<f64>,
    /// Relaxing chain: tension (N) of the spring at the left wall, s(δ₁); negative in
    /// compression.
    #[serde(default)]
    pub wall_force: Option<f64>,
    /// Relaxing chain: s(ΔW/(n + 1)) (N).
    #[serde(default)]
    pub wall_force_theory: Option<f64>,
    /// Relaxing chain: secant stiffness of the whole chain, wall force / ΔW (N/m).
    #[serde(default)]
    pub secant_stiffness: Option<f64>,
    /// Relaxing chain: s(δ)/ΔW (N/m).
    #[serde(default)]
    pub secant_stiffness_theory: Option<f64>,
    /// Relaxing chain with a tangent step: ΔF/ΔW (N/m) from the MD increments.
    #[serde(default)]
    pub tangent_stiffness: Option<f64>,
    /// Relaxing chain: s′(δ)/(n + 1) (N/m).
    #[serde(default)]
    pub tangent_stiffness_theory: Option<f64>,
    /// Damped hit chain: time (s) from which its energy E_kin + E_pot stays below
    /// [`DISSIPATED`] of its energy at t = 0, the kick's ½ m v0²; none if it never does.
    #[serde(default)]
    pub energy_dissipation_time: Option<f64>,
    /// Damped hit chain: the e-folding time (s) of its energy, 1/rate with the rate fitted
    /// over the second half of the decay (`measure::decay_rate`), where the slowest mode remains.
    #[serde(default)]
    pub energy_decay_time: Option<f64>,
    /// Damped linear bonded hit chain: the slowest excited mode's e-folding time (s) of the
    /// energy ([`excited_mode_rates`]).
    #[serde(default)]
    pub energy_decay_time_theory: Option<f64>,
}

/// The fraction of the kick's energy below which a damped hit chain counts as dissipated:
/// 1e-4, an amplitude of 1 % of the kick's (the energy goes as the amplitude squared).
pub const DISSIPATED: f64 = 1e-4;

/// n particles between two fixed walls `wall_distance` apart, bonded as an (n+2) × 1
/// lattice (the walls are particles 0 and n+1); particle `node` starts at v0. They start
/// evenly spaced (at equilibrium), or, in a relaxing chain, at rest spacing from the left
/// wall, so the last spring takes the whole wall displacement and the chain must relax.
pub(super) fn build(spec: &RunSpec, chain: &ChainRun) -> Scene {
    let (n, walls) = (chain.n, chain.wall_distance);
    let gap = if chain.relax.is_some() { spec.spacing } else { walls / (n + 1) as f64 };
    let mut particles = Particles::default();
    for p in 0..n + 2 {
        let fixed = if p == 0 || p == n + 1 { Axes::FIXED } else { Axes::ONLY_X_MOVES };
        let x = if p == n + 1 { walls } else { p as f64 * gap };
        particles.push(x, 0.0, spec.mass, fixed);
    }
    particles.vx[chain.node] = spec.v0;
    let network = Network::Lattice(SquareLattice::chain(n + 2, spec.spacing, spec.k));
    let mut scene = scene(spec, particles, network, None);
    // The residual force is relative to the equilibrium spring force s(ΔW/(n + 1)).
    scene.sampling.relaxation = relaxation(spec, Some(equilibrium(spec, chain).1.abs()), relaxing(chain).0);
    scene
}

/// A relaxing chain's equilibrium: every spring extended by δ = ΔW/(n + 1), carrying
/// s(δ); returns (δ (m), s (N), secant stiffness of the whole chain s/ΔW (N/m), tangent
/// stiffness s′(δ)/(n + 1) (N/m)). The secant is the tangent for ΔW = 0.
pub fn equilibrium(spec: &RunSpec, chain: &ChainRun) -> (f64, f64, f64, f64) {
    let springs = (chain.n + 1) as f64;
    let delta = spec.chain_wall_extension() / springs;
    let law = spec.law;
    let (force, tangent) = (law.elastic_force(spec.k, delta), law.tangent_stiffness(spec.k, delta));
    let secant = if delta == 0.0 { tangent / springs } else { force / (delta * springs) };
    (delta, force, secant, tangent / springs)
}

/// True when the chain has an exact normal-mode solution: linear bonded springs, no damping,
/// walls at the rest spacing.
pub fn has_normal_modes(spec: &RunSpec, chain: &ChainRun) -> bool {
    is_modal(spec, chain) && !is_damped(spec)
}

/// Linear bonded springs between walls at the rest spacing: the chain's modes are the sines
/// of [`excited_mode_rates`], damped or not.
fn is_modal(spec: &RunSpec, chain: &ChainRun) -> bool {
    spec.law.is_linear() && !spec.contact && at_rest_spacing(spec, chain)
}

/// Walls (n + 1) spacings apart: the chain at rest stores no energy.
fn at_rest_spacing(spec: &RunSpec, chain: &ChainRun) -> bool {
    let walls = chain.wall_distance;
    (walls - (chain.n + 1) as f64 * spec.spacing).abs() <= 1e-12 * walls
}

/// Whether the walls pre-load the chain's springs: pushed in, or pulled apart for bonded springs
/// (a contact spring opens a gap instead). A pre-loaded chain has a linear sound speed
/// a√(s′(δ₀)/m) even with power-law springs, so it carries no Nesterenko solitary wave.
pub fn is_preloaded(spec: &RunSpec, chain: &ChainRun) -> bool {
    let rest = (chain.n + 1) as f64 * spec.spacing;
    !at_rest_spacing(spec, chain) && (chain.wall_distance < rest || !spec.contact)
}

/// A bond dashpot or background damping.
fn is_damped(spec: &RunSpec) -> bool {
    spec.gamma > 0.0 || spec.gamma_background > 0.0
}

/// The energy decay rates (1/s) of the modes a linear bonded chain hit at its node has, slowest
/// first. Mode j of n particles between walls: ω_j² = k_j/m, k_j = 4k sin²(jπ/(2(n + 1))),
/// shape sin(jπ p/(n + 1)). The bond dashpots damp it as k does, c_j = γ_g + 4γ sin²(jπ/(2(n + 1)))
/// (N s/m), so its energy falls at c_j/m − Re √((c_j/m)² − 4k_j/m) (1/s)
/// (`theory::background_decay_rate`): c_j/m while underdamped. The hit excites the modes that
/// do not vanish at the node; the slowest of them sets the late energy's rate.
fn excited_mode_rates(spec: &RunSpec, chain: &ChainRun) -> Vec<f64> {
    let half_angle = |j: usize| j as f64 * std::f64::consts::PI / (2 * (chain.n + 1)) as f64;
    let mut rates: Vec<f64> = (1..=chain.n)
        .filter(|&j| (2.0 * half_angle(j) * chain.node as f64).sin().abs() > 1e-9)
        .map(|j| {
            let s2 = half_angle(j).sin().powi(2);
            let damping = spec.gamma_background + 4.0 * spec.gamma * s2;
            crate::theory::background_decay_rate(damping, spec.mass, 4.0 * spec.k * s2)
        })
        .collect();
    rates.sort_by(f64::total_cmp);
    rates
}

/// Whether a damped linear bonded hit chain's run resolves its slowest mode's decay: the fit
/// (`measure::decay_rate`) reads the second half of the run, where the next slower mode, rate
/// r₂, must have fallen below 1 % of the slowest's, rate r₁: (r₂ − r₁) T/2 ≥ ln 100 over the
/// run's duration T (s). Modes that share the slowest rate (background damping alone, every
/// mode underdamped) do not disturb it.
pub fn decay_resolved(spec: &RunSpec) -> bool {
    let Some(chain) = spec.chain().filter(|c| is_modal(spec, c)) else { return false };
    let rates = excited_mode_rates(spec, chain);
    let Some(&slowest) = rates.first() else { return false };
    let next = rates.iter().find(|r| **r > slowest * (1.0 + 1e-9));
    next.is_none_or(|next| (next - slowest) * 0.5 * spec.duration >= 100f64.ln())
}

/// A damped hit chain's energy: when it fell below [`DISSIPATED`] of the kick's for good, and
/// its late e-folding time, measured and (linear bonded springs) from its slowest mode.
fn measure_dissipation(spec: &RunSpec, chain: &ChainRun, outcome: &Outcome, metrics: &mut ChainMetrics) {
    let t = &outcome.trace;
    let energy: Vec<(f64, f64)> = (0..t.time.len()).map(|s| (t.time[s], t.kinetic[s] + t.potential[s])).collect();
    let Some(&(_, kick)) = energy.first().filter(|e| e.1 > 0.0) else { return };
    // The last sample at or above the threshold; the next one starts the dissipated state.
    let last_above = energy.iter().rposition(|e| e.1 >= DISSIPATED * kick);
    metrics.energy_dissipation_time = match last_above {
        None => energy.first().map(|e| e.0),
        Some(s) => energy.get(s + 1).map(|e| e.0),
    };
    metrics.energy_decay_time = decay_rate(&energy).filter(|r| *r > 0.0).map(|r| 1.0 / r);
    metrics.energy_decay_time_theory =
        is_modal(spec, chain).then(|| excited_mode_rates(spec, chain).first().map(|r| 1.0 / r)).flatten();
}

/// Tension (N) of a chain's first spring, between the left wall and particle 1.
fn wall_force(spec: &RunSpec, x: &[f64]) -> f64 {
    spec.law.elastic_force(spec.k, x[1] - x[0] - spec.spacing)
}

/// The normal-mode error, the exact discrete chain's front speed, and a relaxing chain's
/// equilibrium.
pub(super) fn measure(spec: &RunSpec, chain: &ChainRun, outcome: &Outcome, metrics: &mut ChainMetrics) {
    metrics.chain_mode_error = has_normal_modes(spec, chain)
        .then(|| {
            let movable: Vec<usize> = (1..=chain.n).collect();
            normal_mode_error(&outcome.trace, &movable, &initial_velocities(spec, chain), spec.k, spec.mass)
        })
        .flatten();
    metrics.sound_speed_exact = outcome.wave.as_ref().and_then(|record| exact_front_speed(spec, chain, record));
    if chain.relax.is_some() {
        measure_equilibrium(spec, chain, outcome, metrics);
    } else if is_damped(spec) && at_rest_spacing(spec, chain) {
        measure_dissipation(spec, chain, outcome, metrics);
    }
}

/// The chain's initial velocities (m/s), particles 1..n: v0 at the hit node, 0 elsewhere.
fn initial_velocities(spec: &RunSpec, chain: &ChainRun) -> Vec<f64> {
    (1..=chain.n).map(|p| if p == chain.node { spec.v0 } else { 0.0 }).collect()
}

/// The exact discrete chain's front speed L / t_exact (m/s) for a timed chain's `record`:
/// t_exact is the arrival by the recommended criterion and the wave's threshold
/// (`measure::arrival_time`, the measurement's own) on the exact normal-mode motion of the
/// source and receivers sampled at the run's own record times, so the criterion, its linear
/// interpolation between records and the records' spacing are the measurement's and cancel
/// when the two are compared: what remains is the integrator's error. The discrete chain is
/// dispersive, so this threshold arrival is not at x = a√(k/m) t and leads it by an amount
/// that depends on where the receiver sits. `None` where [`ChainModes`] does not describe the
/// chain ([`has_normal_modes`]: a power law or a compression-only contact is not a linear
/// spring, damping takes energy the modes keep, walls off the rest spacing pre-stress it), and
/// where the exact receiver never reaches the threshold within the record.
fn exact_front_speed(spec: &RunSpec, chain: &ChainRun, record: &WaveRecord) -> Option<f64> {
    let wave = chain.wave.as_ref().filter(|_| has_normal_modes(spec, chain))?;
    let exact = exact_wave_record(spec, chain, wave, &record.time);
    let arrival = arrival_time(&exact, ARRIVAL_CRITERIA[0], wave.threshold)?;
    (arrival > 0.0).then(|| wave.distance / arrival)
}

/// What a `WaveProbe` would record on the exact normal-mode motion of the chain at `times`
/// (s): the source's |u| (m), |v| (m/s) and ½ m v² (J), and over the receivers the largest |u|,
/// the largest |v| and the sum of ½ m v².
fn exact_wave_record(spec: &RunSpec, chain: &ChainRun, wave: &WaveSpec, times: &[f64]) -> WaveRecord {
    let modes = ChainModes::new(spec.k, spec.mass, &initial_velocities(spec, chain));
    let particles: Vec<usize> = std::iter::once(wave.source).chain(wave.receivers.iter().copied()).collect();
    let sample = |&(u, v): &(f64, f64)| (u.abs(), v.abs(), 0.5 * spec.mass * v * v);
    let mut record = WaveRecord::default();
    for &t in times {
        let motion = modes.motion_of(&particles, t);
        record.push(t, sample(&motion[0]), motion[1..].iter().map(sample));
    }
    record
}

/// The continuum speed a√(k/m) of long waves (`sound_speed_theory`); the chain's dispersive
/// threshold front is judged against the exact discrete chain's instead ([`exact_front_speed`]).
pub(super) fn wave_speed(spec: &RunSpec) -> Option<f64> {
    sound_speed(spec, spec.k)
}

/// The side N of the relaxation window (the particles) and the force the residual-force
/// criterion is relative to.
pub(super) fn relaxing(chain: &ChainRun) -> (usize, &'static str) {
    (chain.n, "the wall force")
}

/// A relaxing chain's spacing, wall force and secant stiffness beside its equilibrium; the
/// measured ones only when it came to rest.
fn measure_equilibrium(spec: &RunSpec, chain: &ChainRun, outcome: &Outcome, metrics: &mut ChainMetrics) {
    let relaxed = outcome.trace.relaxed_at.is_some();
    let keep = |value: Option<f64>| value.filter(|_| relaxed);
    let x = &outcome.state.particles.x;
    let gaps: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let inner = &gaps[..gaps.len() - 1];
    let (shortest, longest) = crate::measure::extremes(&gaps);
    let (delta, force, secant, tangent) = equilibrium(spec, chain);
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

/// The tangent stiffness ΔF/ΔW (N/m) of the tangent step: the wall force's increment from the
/// relaxed particles `start` to `end` over the wall's step `wall_step` (m); none for a step of 0.
pub(super) fn tangent_stiffness(
    spec: &RunSpec,
    wall_step: f64,
    start: &Particles,
    end: &Particles,
    metrics: &mut ChainMetrics,
) {
    if wall_step != 0.0 {
        let before = wall_force(spec, &start.x);
        metrics.tangent_stiffness = Some((wall_force(spec, &end.x) - before) / wall_step);
    }
}

/// The chain's result columns: its size, its normal-mode error, a timed chain's exact discrete
/// front speed, a relaxing chain's equilibrium beside the exact one, and a damped hit chain's
/// dissipation.
pub(super) fn columns() -> Vec<Block<ChainMetrics>> {
    use Column::{Count, Number};
    let relaxing: Vec<Column<ChainMetrics>> = vec![
        Number("wall_displacement", |r| r.spec.chain().and_then(|c| c.relax).map(|_| r.spec.chain_wall_extension())),
        Number("equilibrium_spacing", |r| r.group.equilibrium_spacing),
        Number("equilibrium_spacing_theory", |r| r.group.equilibrium_spacing_theory),
        Number("spacing_spread", |r| r.group.spacing_spread),
        Number("wall_force", |r| r.group.wall_force),
        Number("wall_force_theory", |r| r.group.wall_force_theory),
        Number("secant_stiffness", |r| r.group.secant_stiffness),
        Number("secant_stiffness_theory", |r| r.group.secant_stiffness_theory),
        Number("tangent_stiffness", |r| r.group.tangent_stiffness),
        Number("tangent_stiffness_theory", |r| r.group.tangent_stiffness_theory),
    ];
    let dissipating: Vec<Column<ChainMetrics>> = vec![
        Number("energy_dissipation_time", |r| r.group.energy_dissipation_time),
        Number("energy_decay_time", |r| r.group.energy_decay_time),
        Number("energy_decay_time_theory", |r| r.group.energy_decay_time_theory),
    ];
    vec![
        Block { slot: Slot::Size, shown: None, columns: vec![Count("n", |r| r.spec.chain().map(|c| c.n as u64))] },
        Block {
            slot: Slot::Error,
            shown: None,
            columns: vec![Number("chain_mode_error", |r| r.group.chain_mode_error)],
        },
        Block {
            slot: Slot::Tail,
            shown: Some(|spec| spec.chain().is_some_and(|c| c.wave.is_some())),
            columns: vec![Number("sound_speed_exact", |r| r.group.sound_speed_exact)],
        },
        Block {
            slot: Slot::Tail,
            shown: Some(|spec| spec.chain().is_some_and(|c| c.relax.is_some())),
            columns: relaxing,
        },
        Block {
            slot: Slot::Tail,
            shown: Some(|spec| spec.chain().is_some_and(|c| c.relax.is_none()) && is_damped(spec)),
            columns: dissipating,
        },
    ]
}
