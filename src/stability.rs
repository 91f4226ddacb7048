//! Numerical stability, known before a run starts: the fastest mode ω_max of a scene (power
//! iteration on its dynamical matrix), the largest ω dt its integrator survives (measured on the
//! damped test oscillator with the integrator's own code), and the campaign check that applies
//! `time.dt_omega_max` and refuses runs beyond the limit unless `time.allow_unstable: true`.
//! Pure computation, no I/O.

use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

use crate::model::{Axes, BondDashpot, Linear, NoDashpot, Particles, Spring, SquareLattice};
use crate::scenes::build_scene;
use crate::sim::{IntegratorKind, LatticeNetwork, Sampling, Scene, State, StepProbe, simulate_with};
use crate::spec::{Campaign, LawName, RunSpec, SpecError};
use crate::theory;

/// What is known about a run's stability before it starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stability {
    /// Angular frequency of the fastest mode (rad/s), springs at their reference stiffness.
    pub omega_max: f64,
    /// Damping ratio ζ of that mode (dashpots and background damping).
    pub damping_ratio: f64,
    /// dt · ω_max.
    pub dt_omega_max: f64,
    /// Largest dt · ω the integrator survives at that damping ratio.
    pub limit: f64,
}

/// Estimates the stability of `spec` as it stands.
pub fn estimate(spec: &RunSpec) -> Stability {
    let scene = build_scene(spec);
    let (omega_max, damping_ratio) = fastest_mode(&scene, reference_extension(spec));
    Stability {
        omega_max,
        damping_ratio,
        dt_omega_max: omega_max * spec.dt,
        limit: stability_limit(spec.integrator, damping_ratio),
    }
}

/// The extension (m) at which non-linear springs are linearised: the overlap −δ_max of a
/// two-body collision at the run's v0 (the deformation the run is expected to reach; a
/// power-law spring has no stiffness at δ = 0). Linear springs do not care.
fn reference_extension(spec: &RunSpec) -> f64 {
    match spec.law {
        LawName::Linear => 0.0,
        LawName::Power => -theory::power_law_max_overlap(spec.k, spec.beta, spec.mass, spec.v0),
    }
}

/// Iterations of the power method at most; it stops earlier once the Rayleigh quotient has
/// settled to 1e-10. Eigenvalues within a fraction ε of the top are damped as (1 − ε)^(2n), so
/// the quotient is within a few 1e-3 of λ_max even where the top of the spectrum is dense.
const POWER_ITERATIONS: usize = 4000;

/// ω_max (rad/s) and the damping ratio of that mode: power iteration on the mass-weighted
/// dynamical matrix M^(−½) K M^(−½) over the free axes, K from each bond's tangent stiffness
/// k_t = ds/dδ at `extension` along its direction n̂ (K_bond = k_t n̂ n̂ᵀ; the geometric
/// stiffness of pre-stress is left out), then ζ = uᵀCu / (2 ω uᵀMu) for that mode u, C from
/// the bond dashpots γ n̂ n̂ᵀ and background damping γ_g I.
fn fastest_mode(scene: &Scene, extension: f64) -> (f64, f64) {
    let p = &scene.particles;
    let n = p.len();
    let mut bonds = Vec::new();
    scene.network.for_each_bond(|i, j, _rest, k, shift| {
        let (dx, dy) = (p.x[i] - p.x[j] + shift, p.y[i] - p.y[j]);
        let r = dx.hypot(dy);
        bonds.push((i, j, scene.law.tangent_stiffness(k, extension), dx / r, dy / r));
    });
    let mut free_x = vec![1.0; n];
    let mut free_y = vec![1.0; n];
    for &i in &p.held_x {
        free_x[i] = 0.0;
    }
    for &i in &p.held_y {
        free_y[i] = 0.0;
    }
    let scale: Vec<f64> = p.inv_mass.iter().map(|im| im.sqrt()).collect();
    // y = M^(−½) K M^(−½) w on the free axes.
    let apply = |wx: &[f64], wy: &[f64], yx: &mut [f64], yy: &mut [f64]| {
        yx.fill(0.0);
        yy.fill(0.0);
        for &(i, j, k, nx, ny) in &bonds {
            let (uxi, uyi) = (wx[i] * scale[i] * free_x[i], wy[i] * scale[i] * free_y[i]);
            let (uxj, uyj) = (wx[j] * scale[j] * free_x[j], wy[j] * scale[j] * free_y[j]);
            let s = k * (nx * (uxi - uxj) + ny * (uyi - uyj));
            yx[i] += s * nx;
            yy[i] += s * ny;
            yx[j] -= s * nx;
            yy[j] -= s * ny;
        }
        for i in 0..n {
            yx[i] *= scale[i] * free_x[i];
            yy[i] *= scale[i] * free_y[i];
        }
    };
    // A fixed, irregular start vector (reproducible, not orthogonal to the top mode).
    let start = |i: usize, axis: f64| ((i as f64 + 1.0) * (0.754_877_666 + axis)).fract() - 0.5;
    let mut wx: Vec<f64> = (0..n).map(|i| start(i, 0.0) * free_x[i]).collect();
    let mut wy: Vec<f64> = (0..n).map(|i| start(i, 0.31) * free_y[i]).collect();
    let (mut yx, mut yy) = (vec![0.0; n], vec![0.0; n]);
    let norm = |a: &[f64], b: &[f64]| a.iter().chain(b).map(|v| v * v).sum::<f64>().sqrt();
    let mut lambda = 0.0;
    for iteration in 0..POWER_ITERATIONS {
        let length = norm(&wx, &wy);
        if length == 0.0 {
            return (0.0, 0.0);
        }
        wx.iter_mut().chain(wy.iter_mut()).for_each(|v| *v /= length);
        apply(&wx, &wy, &mut yx, &mut yy);
        let quotient: f64 = wx.iter().zip(&yx).chain(wy.iter().zip(&yy)).map(|(w, y)| w * y).sum();
        let settled = iteration > 50 && (quotient - lambda).abs() <= 1e-10 * quotient.abs();
        lambda = quotient;
        std::mem::swap(&mut wx, &mut yx);
        std::mem::swap(&mut wy, &mut yy);
        if settled {
            break;
        }
    }
    let omega = lambda.max(0.0).sqrt();
    if omega == 0.0 {
        return (0.0, 0.0);
    }
    // The mode u = M^(−½) w with |w| = 1, so uᵀMu = 1.
    let length = norm(&wx, &wy);
    let u = |w: &[f64], free: &[f64], i: usize| w[i] / length * scale[i] * free[i];
    let mut damping = 0.0;
    for &(i, j, _, nx, ny) in &bonds {
        let rate = nx * (u(&wx, &free_x, i) - u(&wx, &free_x, j)) + ny * (u(&wy, &free_y, i) - u(&wy, &free_y, j));
        damping += scene.gamma * rate * rate;
    }
    damping +=
        scene.background_gamma * (0..n).map(|i| u(&wx, &free_x, i).powi(2) + u(&wy, &free_y, i).powi(2)).sum::<f64>();
    (omega, damping / (2.0 * omega))
}

/// The largest ω dt for which `kind` stays bounded on the test oscillator ẍ = −ω²x − 2ζωẋ
/// (ζ = `damping_ratio`), to 1e-6 relative; cached per integrator and ζ (rounded to three
/// digits). Undamped values to compare with: 2 for the Verlet schemes and symplectic Euler,
/// 2√2 for RK4, 1.5734 for Forest–Ruth.
pub fn stability_limit(kind: IntegratorKind, damping_ratio: f64) -> f64 {
    static LIMITS: OnceLock<Mutex<HashMap<(IntegratorKind, u64), f64>>> = OnceLock::new();
    let zeta: f64 = format!("{damping_ratio:.2e}").parse().unwrap_or(0.0);
    let key = (kind, zeta.to_bits());
    let cache = LIMITS.get_or_init(Default::default);
    if let Some(&limit) = cache.lock().expect("the cache is never poisoned").get(&key) {
        return limit;
    }
    let limit = measure_limit(kind, zeta);
    cache.lock().expect("the cache is never poisoned").insert(key, limit);
    limit
}

/// Largest ω dt searched: beyond it every scheme here is unstable (RK4's limit is 2.83).
const LARGEST_LIMIT: f64 = 64.0;

fn measure_limit(kind: IntegratorKind, zeta: f64) -> f64 {
    let (mut low, mut high) = (0.0, 0.5);
    while stays_bounded(kind, zeta, high) {
        low = high;
        high *= 2.0;
        if high > LARGEST_LIMIT {
            return LARGEST_LIMIT;
        }
    }
    while high - low > 1e-6 * high {
        let middle = 0.5 * (low + high);
        if stays_bounded(kind, zeta, middle) {
            low = middle;
        } else {
            high = middle;
        }
    }
    low
}

/// Start amplitude of a trial (m, m/s) on a spring of rest length 1 m: small enough that a
/// growing run is caught (at [`ESCAPE_AMPLITUDE`]) while the spring is still exactly linear, large
/// enough that 1 + u keeps ten digits of u.
const TRIAL_AMPLITUDE: f64 = 1e-6;

/// A trial whose amplitude passes this (m) is unbounded: 1e4 × the start, where a bounded
/// scheme stays below 1/√(1 − (h/2)²) ≈ 700 × even 1e-6 inside velocity Verlet's limit.
const ESCAPE_AMPLITUDE: f64 = 1e-2;

/// Steps of each of the two halves of a stability trial.
const TRIAL_STEPS: u64 = 2000;

/// Largest amplitude √(u² + v²/ω²) seen over the second and the last quarter of a trial, and
/// whether it ever escaped.
#[derive(Default)]
struct Amplitudes {
    steps: u64,
    escaped: bool,
    early: f64,
    late: f64,
}

impl StepProbe for Amplitudes {
    fn observe(&mut self, state: &State) {
        let p = &state.particles;
        let amplitude = (p.x[1] - 1.0).hypot(p.vx[1]);
        // Beyond the escape amplitude the trial has grown 1e4-fold (and would soon leave the
        // linear range: past u = −1 the particles pass through each other).
        self.escaped |= amplitude.is_nan() || amplitude >= ESCAPE_AMPLITUDE;
        self.steps += 1;
        if self.steps > TRIAL_STEPS / 2 && self.steps <= TRIAL_STEPS {
            self.early = self.early.max(amplitude);
        } else if self.steps > 3 * TRIAL_STEPS / 2 {
            self.late = self.late.max(amplitude);
        }
    }
}

/// Runs the integrator at ω dt = `h` on the test oscillator (unit mass on a unit spring to a
/// fixed particle, dashpot 2ζ: ω = 1) for 2 × [`TRIAL_STEPS`] steps; bounded when it never
/// escapes and the late amplitude is within 1.5 × the early one. A scheme beyond its limit grows by a factor
/// ρ > 1 per step (ρ − 1 ~ √(h − h_c)), so 1000 steps show growth down to (h − h_c)/h_c ≈ 1e-6;
/// within the limit the amplitude is bounded (or decays).
fn stays_bounded(kind: IntegratorKind, zeta: f64, h: f64) -> bool {
    let mut particles = Particles::default();
    particles.push(0.0, 0.0, 1.0, Axes::FIXED);
    let moving = particles.push(1.0, 0.0, 1.0, Axes::ONLY_X_MOVES);
    particles.vx[moving] = TRIAL_AMPLITUDE;
    let lattice = SquareLattice {
        nx: 2,
        ny: 1,
        spacing: 1.0,
        k_x: 1.0,
        k_y: 0.0,
        k_rising: 0.0,
        k_falling: 0.0,
        periodic_x: false,
    };
    let sampling =
        Sampling { dt: h, steps: 2 * TRIAL_STEPS, every: 2 * TRIAL_STEPS, displacements: false, relaxation: None };
    let mut state = State::new(particles);
    let mut amplitudes = Amplitudes::default();
    if zeta > 0.0 {
        let spring = Spring::<Linear, BondDashpot, false> { law: Linear, dashpot: BondDashpot { gamma: 2.0 * zeta } };
        let mut field = LatticeNetwork::new(spring, lattice, 0.0);
        simulate_with(kind, &mut state, &mut field, &sampling, &mut amplitudes);
    } else {
        let spring = Spring::<Linear, NoDashpot, false> { law: Linear, dashpot: NoDashpot };
        let mut field = LatticeNetwork::new(spring, lattice, 0.0);
        simulate_with(kind, &mut state, &mut field, &sampling, &mut amplitudes);
    }
    !amplitudes.escaped && amplitudes.late <= 1.5 * amplitudes.early
}

/// Reads, validates and expands the campaign file at `path` ([`crate::spec::load`]), then
/// checks every run's stability ([`check_campaign`]): what every command starts from.
pub fn load_campaign(path: &std::path::Path) -> Result<Campaign, SpecError> {
    let mut campaign = crate::spec::load(path)?;
    check_campaign(&path.display().to_string(), &mut campaign)?;
    Ok(campaign)
}

/// [`load_campaign`] for campaign text; `file` names it in errors.
pub fn parse_campaign(file: &str, text: &str) -> Result<Campaign, SpecError> {
    let mut campaign = crate::spec::parse(file, text)?;
    check_campaign(file, &mut campaign)?;
    Ok(campaign)
}

/// Applies every run's `time.dt_omega_max` (dt = value / ω_max) and refuses, before anything
/// runs, a run whose dt · ω_max exceeds its integrator's limit unless it says
/// `time.allow_unstable: true`. Errors name the file, the scene, the grid values and the field.
pub fn check_campaign(file: &str, campaign: &mut Campaign) -> Result<(), SpecError> {
    let scenes = &campaign.scenes;
    campaign.runs.par_iter_mut().try_for_each(|spec| {
        let invalid = |detail: String| SpecError::Invalid { file: file.to_string(), detail };
        let index = scenes.iter().position(|(name, _)| *name == spec.scene).unwrap_or(0);
        let place = match spec.varied_label(|_| true) {
            label if label.is_empty() => format!("scenes[{index}] ({})", spec.scene),
            label => format!("scenes[{index}] ({}, run {label})", spec.scene),
        };
        let mut stability = estimate(spec);
        if let Some(target) = spec.dt_omega_max {
            if stability.omega_max <= 0.0 {
                return Err(invalid(format!(
                    "{place}.time.dt_omega_max = {target}: the scene has no moving mode (ω_max = 0); give dt or dt_per_tc"
                )));
            }
            spec.set_dt(target / stability.omega_max);
            if spec.steps > 2_000_000_000 {
                return Err(invalid(format!(
                    "{place}.time.dt_omega_max = {target}: gives {} steps; at most 2e9",
                    spec.steps
                )));
            }
            stability.dt_omega_max = target;
        }
        if stability.dt_omega_max > stability.limit && !spec.allow_unstable {
            let field = if spec.dt_omega_max.is_some() { "time.dt_omega_max" } else { "time.dt_per_tc (or time.dt)" };
            return Err(invalid(format!(
                "{place}.{field}: dt = {:.4e} s gives dt·ω_max = {:.4} (ω_max = {:.4e} rad/s, damping ratio {:.3}), beyond \
                 the stability limit {:.4} of {}; allowed: dt ≤ {:.4e} s (dt_per_tc ≥ {:.3}), or time.allow_unstable: \
                 true to run it anyway and watch it blow up",
                spec.dt,
                stability.dt_omega_max,
                stability.omega_max,
                stability.damping_ratio,
                stability.limit,
                spec.integrator.name(),
                stability.limit / stability.omega_max,
                spec.t_c * stability.omega_max / stability.limit,
            )));
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undamped_limits_match_the_known_values() {
        // Exact limits of the test equation: Verlet and symplectic Euler |1 − h²/2| ≤ 1 → 2;
        // RK4 on the imaginary axis 2√2; the bisection resolves 1e-6, the trial growth ~1e-5.
        for (kind, exact) in [
            (IntegratorKind::VelocityVerlet, 2.0),
            (IntegratorKind::PositionVerlet, 2.0),
            (IntegratorKind::SymplecticEuler, 2.0),
            (IntegratorKind::Rk4, 2.0 * 2f64.sqrt()),
        ] {
            let limit = stability_limit(kind, 0.0);
            assert!((limit - exact).abs() < 1e-3 * exact, "{}: {limit} against {exact}", kind.name());
        }
    }
}
