//! Numerical stability, known before a run starts: the fastest mode ω_max of a scene (the
//! Lanczos method on its dynamical matrix, [`super::lanczos`]; a rigorous node-by-node bound on networks too large for
//! that, see [`LANCZOS_BONDS`]) and the largest ω dt its integrator survives (measured on the
//! damped test oscillator with the integrator's own code). Pure computation, no I/O and no global
//! state: what is estimated once is kept in the [`Estimates`] value its owner (the plan) passes.

use std::collections::HashMap;
use std::sync::Mutex;

use crate::fem::Shared;
use crate::model::{Axes, BondDashpot, Linear, NoDashpot, Particles, Spring, SquareLattice};
use crate::sim::{BondNetwork, Gear, IntegratorKind, Sampling, Scene, State, StepProbe, simulate_with};
use crate::spec::{LANCZOS_BONDS, RunSpec};
use crate::study::build_scene;

/// What is known about a run's stability before it starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stability {
    /// Angular frequency of the fastest mode (rad/s), springs at their reference stiffness.
    pub omega_max: f64,
    /// Damping ratio ζ of that mode (dashpots and background damping).
    pub damping_ratio: f64,
    /// dt · ω_max.
    pub dt_omega_max: f64,
    /// Largest dt · ω the integrator survives at that damping ratio (Gear: over the run's
    /// length, see [`Estimates::stability_limit`]).
    pub limit: f64,
    /// ν_max (1/s): the largest decay rate damping alone imposes.
    pub damping_rate: f64,
}

impl Stability {
    /// What is known about `spec` from its network's `modes` at time step `dt` (s) over `steps`
    /// steps. The limit, in units of dt · ω_max, is the smaller of the fastest mode's (the test
    /// oscillator at its ζ) and the one damping alone sets: a heavily damped slow mode decays at
    /// rate up to ν_max, and an explicit scheme needs dt · ν_max below its limit on ẋ' = −ν ẋ
    /// (RK4 2.79, symplectic Euler 2, ...).
    fn at(modes: Modes, dt: f64, kind: IntegratorKind, steps: u64, estimates: &Estimates) -> Stability {
        let oscillation = estimates.stability_limit(kind, modes.damping_ratio, steps);
        let damping = if modes.damping_rate > 0.0 && modes.omega_max > 0.0 {
            estimates.damping_limit(kind, steps) * modes.omega_max / modes.damping_rate
        } else {
            f64::INFINITY
        };
        Stability {
            omega_max: modes.omega_max,
            damping_ratio: modes.damping_ratio,
            dt_omega_max: modes.omega_max * dt,
            limit: oscillation.min(damping),
            damping_rate: modes.damping_rate,
        }
    }
}

/// The stability of `spec` as it stands (its dt and steps final), estimated afresh: for a
/// single run. A campaign's runs share their networks' estimates through [`Estimates`].
pub fn estimate(spec: &RunSpec) -> Stability {
    Estimates::default().stability(spec)
}

/// The estimates made so far, so that runs of one network (a grid over dt, integrators, run
/// lengths) compute its modes once, and runs of one integrator its limit once: the plan fills
/// it while checking a campaign, and the runs read it again for their records. The runs also
/// share through it their static solves: each network's symbolic analysis, and each loaded
/// network's answer.
#[derive(Debug, Default)]
pub struct Estimates {
    /// The modes of each network, by [`network_key`].
    modes: Mutex<HashMap<String, Modes>>,
    /// The stability limits measured, by integrator, test equation and run length.
    limits: Mutex<HashMap<LimitKey, f64>>,
    /// The static solves' analyses and answers.
    shared: Shared,
}

impl Estimates {
    /// What the runs share of their static solves: the symbolic analyses of the networks and
    /// the answers of the loaded networks solved so far.
    pub fn shared(&self) -> &Shared {
        &self.shared
    }

    /// How many networks' modes have been estimated so far.
    pub fn networks(&self) -> usize {
        self.modes.lock().expect("the cache is never poisoned").len()
    }

    /// The stability of `spec` as it stands (its dt and steps final).
    pub fn stability(&self, spec: &RunSpec) -> Stability {
        Stability::at(self.modes(spec), spec.dt, spec.integrator, spec.steps, self)
    }

    /// The stability of `spec` if it takes time steps; `None` for a static-only run
    /// (`relax.method: static`): it has nothing to be stable, and a large network's estimate
    /// (a thousand passes over its bonds) would be wasted.
    pub fn stepped_stability(&self, spec: &RunSpec) -> Option<Stability> {
        (!spec.static_only()).then(|| self.stability(spec))
    }

    /// ω_max of `spec`'s network (rad/s), whatever its time step.
    pub fn omega_max(&self, spec: &RunSpec) -> f64 {
        self.modes(spec).omega_max
    }

    /// The fastest mode of `spec`'s network: the Lanczos method, or the node bound beyond
    /// [`LANCZOS_BONDS`].
    fn modes(&self, spec: &RunSpec) -> Modes {
        let key = network_key(spec);
        let known = self.modes.lock().expect("the cache is never poisoned").get(&key).copied();
        known.unwrap_or_else(|| {
            let (scene, extension) = (build_scene(spec), crate::spec::reference_extension(spec));
            let modes =
                if spec.bonds() > LANCZOS_BONDS { node_bound(&scene, extension) } else { modes(&scene, extension) };
            self.modes.lock().expect("the cache is never poisoned").insert(key, modes);
            modes
        })
    }

    /// The largest ω dt for which `kind` stays bounded on the test oscillator ẍ = −ω²x − 2ζωẋ
    /// (ζ = `damping_ratio`), to 1e-4 relative; kept per integrator and ζ (rounded to three
    /// digits). Undamped values to compare with: 2 for the Verlet schemes and symplectic Euler,
    /// 2√2 for RK4, 1.5734 for Forest–Ruth.
    ///
    /// Gear's amplification exceeds 1 by a little almost everywhere (~1e-7 per step at ω dt = 0.2,
    /// ~1e-4 at 0.45), so "bounded" depends on how long it runs: its limit is the largest ω dt
    /// below which every mode grows by at most [`RUN_GROWTH`] over `steps` steps (rounded up to a
    /// power of two), from the spectral radius of its amplification matrix ([`gear_limit`]).
    /// The other schemes' limits do not depend on `steps`.
    pub fn stability_limit(&self, kind: IntegratorKind, damping_ratio: f64, steps: u64) -> f64 {
        let zeta: f64 = format!("{damping_ratio:.2e}").parse().unwrap_or(0.0);
        self.limit(kind, TestEquation::Oscillator { zeta }, steps)
    }

    /// The largest ν dt for which `kind` stays bounded on pure damping, ẋ' = −ν ẋ (a slow mode
    /// under heavy damping), measured and kept like [`Estimates::stability_limit`].
    pub fn damping_limit(&self, kind: IntegratorKind, steps: u64) -> f64 {
        self.limit(kind, TestEquation::Damping, steps)
    }

    fn limit(&self, kind: IntegratorKind, test: TestEquation, steps: u64) -> f64 {
        // Only Gear's limit depends on the run's length: a power of two at least `steps`.
        let span = if kind == IntegratorKind::Gear { steps.max(1).next_power_of_two() } else { 0 };
        let key = (kind, if let TestEquation::Oscillator { zeta } = test { zeta.to_bits() } else { u64::MAX }, span);
        if let Some(&limit) = self.limits.lock().expect("the cache is never poisoned").get(&key) {
            return limit;
        }
        let limit = if kind == IntegratorKind::Gear { gear_limit(test, span) } else { measure_limit(kind, test) };
        self.limits.lock().expect("the cache is never poisoned").insert(key, limit);
        limit
    }
}

/// Springs of a scene for the eigenvalue estimates: (i, j, weight, n̂x, n̂y), the weight a
/// stiffness (N/m) or a dashpot constant (N s/m).
type Springs = Vec<(usize, usize, f64, f64, f64)>;

/// The free axes of a scene and its mass scaling M^(−½).
struct FreeAxes {
    free_x: Vec<f64>,
    free_y: Vec<f64>,
    scale: Vec<f64>,
}

impl FreeAxes {
    fn of(p: &Particles) -> FreeAxes {
        let n = p.len();
        let (mut free_x, mut free_y) = (vec![1.0; n], vec![1.0; n]);
        for &i in &p.held_x {
            free_x[i] = 0.0;
        }
        for &i in &p.held_y {
            free_y[i] = 0.0;
        }
        FreeAxes { free_x, free_y, scale: p.inv_mass.iter().map(|im| im.sqrt()).collect() }
    }

    /// The displacement u = M^(−½) w of a mass-weighted vector w, on the free axes.
    #[inline]
    fn displacement(&self, wx: &[f64], wy: &[f64], i: usize) -> (f64, f64) {
        (wx[i] * self.scale[i] * self.free_x[i], wy[i] * self.scale[i] * self.free_y[i])
    }
}

/// The largest eigenvalue of M^(−½) A M^(−½) over the free axes, A = Σ w_b n̂ n̂ᵀ over
/// `springs`, by the Lanczos method ([`super::lanczos`]), with (if `vector`) its unit
/// mass-weighted eigenvector (x components, then y).
fn largest_eigenvalue(springs: &Springs, axes: &FreeAxes, vector: bool) -> (f64, Option<Vec<f64>>) {
    let n = axes.scale.len();
    // The displacements once per product, not once per spring end (three gathers each).
    let mut u = vec![0.0; 2 * n];
    let apply = move |w: &[f64], y: &mut [f64]| {
        let (wx, wy) = w.split_at(n);
        let (ux, uy) = u.split_at_mut(n);
        for i in 0..n {
            (ux[i], uy[i]) = axes.displacement(wx, wy, i);
        }
        y.fill(0.0);
        let (yx, yy) = y.split_at_mut(n);
        for &(i, j, weight, nx, ny) in springs {
            let s = weight * (nx * (ux[i] - ux[j]) + ny * (uy[i] - uy[j]));
            yx[i] += s * nx;
            yy[i] += s * ny;
            yx[j] -= s * nx;
            yy[j] -= s * ny;
        }
        for i in 0..n {
            yx[i] *= axes.scale[i] * axes.free_x[i];
            yy[i] *= axes.scale[i] * axes.free_y[i];
        }
    };
    // A fixed, irregular start vector (reproducible, not orthogonal to the top mode).
    let irregular = |i: usize, shift: f64| ((i as f64 + 1.0) * (0.754_877_666 + shift)).fract() - 0.5;
    let start: Vec<f64> = (0..n)
        .map(|i| irregular(i, 0.0) * axes.free_x[i])
        .chain((0..n).map(|i| irregular(i, 0.31) * axes.free_y[i]))
        .collect();
    super::lanczos::largest(apply, &start, vector)
}

/// The part of `spec` its modes depend on (the network, masses, supports, dashpots and the
/// extension springs are linearised at), as text: runs that differ only in their time step,
/// integrator, length, sampling, outputs or start speed v0 have the same. v0 moves no particle
/// and sets no spring; it reaches the modes only through the extension a power law is
/// linearised at (the collision's largest overlap), which the key holds instead.
pub fn network_key(spec: &RunSpec) -> String {
    let extension = crate::spec::reference_extension(spec);
    let network = RunSpec {
        campaign: String::new(),
        scene: String::new(),
        varied: Default::default(),
        integrator: IntegratorKind::VelocityVerlet,
        dt: 0.0,
        dt_omega_max: None,
        reference_refinement: None,
        allow_unstable: false,
        duration: 0.0,
        steps: 0,
        samples: 0,
        scene_kind: spec.scene_kind.without_relax_and_wave(),
        movie: None,
        series: Default::default(),
        v0: 0.0,
        ..spec.clone()
    };
    let network = serde_json::to_string(&network).expect("a RunSpec always serialises");
    format!("{network} linearised at {:x}", extension.to_bits())
}

/// What the eigenvalue estimates of a scene give.
#[derive(Clone, Copy, Debug)]
pub struct Modes {
    /// ω_max (rad/s).
    pub omega_max: f64,
    /// ζ of the fastest mode.
    pub damping_ratio: f64,
    /// ν_max (1/s): the largest decay rate damping alone imposes, λ_max(M⁻¹C).
    pub damping_rate: f64,
}

/// ω_max from K, each bond's tangent stiffness k_t = ds/dδ at `extension` along its direction
/// (K_bond = k_t n̂ n̂ᵀ; the geometric stiffness of pre-stress is left out); the damping ratio
/// of that mode u, ζ = uᵀCu / (2 ω uᵀMu), C from the bond dashpots γ n̂ n̂ᵀ and background
/// damping γ_g I; and ν_max = λ_max(M^(−½) C_bonds M^(−½)) + max γ_g/m (an upper bound).
pub fn modes(scene: &Scene, extension: f64) -> Modes {
    let p = &scene.particles;
    let axes = FreeAxes::of(p);
    let mut springs = Springs::new();
    let mut dashpots = Springs::new();
    for_each_bond_direction(scene, extension, |i, j, k_t, nx, ny| {
        springs.push((i, j, k_t, nx, ny));
        dashpots.push((i, j, scene.gamma, nx, ny));
    });
    // Without dashpots or background damping the fastest mode's damping is 0 whatever the mode,
    // so its eigenvector (a second pass of the Lanczos recurrence) is not made.
    let damped = scene.gamma > 0.0 || scene.background_gamma > 0.0;
    let (lambda, mode) = largest_eigenvalue(&springs, &axes, damped);
    let omega_max = lambda.sqrt();
    let damping = mode.map_or(0.0, |mode| mode_damping(scene, &axes, &dashpots, &mode));
    let bond_rate = if scene.gamma > 0.0 { largest_eigenvalue(&dashpots, &axes, false).0 } else { 0.0 };
    Modes::new(omega_max, damping, bond_rate + background_rate(scene, &axes))
}

/// uᵀCu / uᵀMu of the unit mass-weighted mode `mode` (1/s): its bonds' dashpots and the
/// background damping.
fn mode_damping(scene: &Scene, axes: &FreeAxes, dashpots: &Springs, mode: &[f64]) -> f64 {
    let (wx, wy) = mode.split_at(scene.particles.len());
    let mut damping = 0.0;
    for &(i, j, gamma, nx, ny) in dashpots {
        let ((uxi, uyi), (uxj, uyj)) = (axes.displacement(wx, wy, i), axes.displacement(wx, wy, j));
        damping += gamma * (nx * (uxi - uxj) + ny * (uyi - uyj)).powi(2);
    }
    damping
        + scene.background_gamma
            * (0..wx.len()).map(|i| axes.displacement(wx, wy, i)).map(|(ux, uy)| ux * ux + uy * uy).sum::<f64>()
}

impl Modes {
    /// From ω_max (rad/s), uᵀCu / uᵀMu of the fastest mode u (1/s) and ν_max (1/s):
    /// ζ = uᵀCu / (2 ω_max uᵀMu).
    fn new(omega_max: f64, mode_damping: f64, damping_rate: f64) -> Modes {
        Modes {
            omega_max,
            damping_ratio: if omega_max > 0.0 { mode_damping / (2.0 * omega_max) } else { 0.0 },
            damping_rate,
        }
    }
}

/// Calls `visit(i, j, k_t, n̂x, n̂y)` for every bond of `scene`: its tangent stiffness at
/// `extension` (N/m) and its unit direction from j to i.
fn for_each_bond_direction(scene: &Scene, extension: f64, mut visit: impl FnMut(usize, usize, f64, f64, f64)) {
    let p = &scene.particles;
    scene.network.for_each_bond(&p.x, &p.y, |i, j, _rest, k, shift| {
        let (dx, dy) = (p.x[i] - p.x[j] + shift, p.y[i] - p.y[j]);
        let r = dx.hypot(dy);
        visit(i, j, scene.law.tangent_stiffness(k, extension), dx / r, dy / r);
    });
}

/// The largest decay rate background damping alone imposes, γ_g / m of the lightest free
/// particle (1/s).
fn background_rate(scene: &Scene, axes: &FreeAxes) -> f64 {
    let p = &scene.particles;
    let lightest =
        (0..p.len()).filter(|&i| axes.free_x[i] + axes.free_y[i] > 0.0).map(|i| p.inv_mass[i]).fold(0.0, f64::max);
    scene.background_gamma * lightest
}

/// The modes of a large network from one pass over its bonds. With S_i = Σ_{b∋i} k_t n̂n̂ᵀ
/// (2 × 2, N/m, on node i's free axes) and (n̂·(u_i − u_j))² ≤ 2(n̂·u_i)² + 2(n̂·u_j)²,
/// uᵀKu ≤ 2 Σ_i u_iᵀ S_i u_i, so ω_max² ≤ max_i 2 λ_max(S_i) / m_i: an upper bound (dt from
/// `time.dt_omega_max` errs small, the stability check errs safe). It is attained where
/// neighbours move opposite along S_i's top direction, the staggered mode: the chain's
/// 4k/m and the square lattice's 4(k + k_d)/m with both diagonal families or none are exact
/// for the infinite network (one family: ~7 % high at k_d = k/2). ζ is that staggered mode's,
/// (2 eᵀG_i e + γ_g) / (2 ω_max m_i) with G_i = Σ_{b∋i} γ n̂n̂ᵀ along S_i's top direction e, and
/// ν_max ≤ max_i 2 λ_max(G_i) / m_i + max γ_g / m by the same inequality.
pub fn node_bound(scene: &Scene, extension: f64) -> Modes {
    let p = &scene.particles;
    let axes = FreeAxes::of(p);
    // Per node: [xx, xy, yy] of S_i (N/m) and of G_i (N s/m).
    let mut stiffness = vec![[0.0; 3]; p.len()];
    let mut dashpots = vec![[0.0; 3]; p.len()];
    for_each_bond_direction(scene, extension, |i, j, k_t, nx, ny| {
        for node in [i, j] {
            for (sum, weight) in [(&mut stiffness[node], k_t), (&mut dashpots[node], scene.gamma)] {
                sum[0] += weight * nx * nx;
                sum[1] += weight * nx * ny;
                sum[2] += weight * ny * ny;
            }
        }
    });
    // The 2 × 2 block on node i's free axes.
    let free = |i: usize, m: [f64; 3]| {
        let (fx, fy) = (axes.free_x[i], axes.free_y[i]);
        [m[0] * fx, m[1] * fx * fy, m[2] * fy]
    };
    let mut fastest: (f64, f64) = (0.0, 0.0); // (ω², eᵀCe / m of the staggered mode)
    let mut bond_rate: f64 = 0.0;
    for i in 0..p.len() {
        let (s, g) = (free(i, stiffness[i]), free(i, dashpots[i]));
        let (lambda, (ex, ey)) = largest_symmetric_2x2(s);
        let omega_squared = 2.0 * lambda * p.inv_mass[i];
        if omega_squared > fastest.0 {
            let along = g[0] * ex * ex + 2.0 * g[1] * ex * ey + g[2] * ey * ey;
            fastest = (omega_squared, (2.0 * along + scene.background_gamma) * p.inv_mass[i]);
        }
        bond_rate = bond_rate.max(2.0 * largest_symmetric_2x2(g).0 * p.inv_mass[i]);
    }
    Modes::new(fastest.0.sqrt(), fastest.1, bond_rate + background_rate(scene, &axes))
}

/// The largest eigenvalue of the symmetric [[a, b], [b, c]] given as [a, b, c], with its unit
/// eigenvector.
fn largest_symmetric_2x2([a, b, c]: [f64; 3]) -> (f64, (f64, f64)) {
    let half_gap = (0.5 * (a - c)).hypot(b);
    let lambda = 0.5 * (a + c) + half_gap;
    // (b, λ − a) and (λ − c, b) are both eigenvectors; take the longer (one vanishes when b = 0).
    let (u, v) = if a >= c { (lambda - c, b) } else { (b, lambda - a) };
    let length = u.hypot(v);
    if length > 0.0 { (lambda, (u / length, v / length)) } else { (lambda, (1.0, 0.0)) }
}

/// The largest factor by which Gear's own amplification may grow any mode over a whole run at
/// its stability limit (the blow-up check of a run fires at 1000× the energy, ~32× the
/// amplitude).
pub const RUN_GROWTH: f64 = 2.0;

/// The scalar problems whose stability limits are measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TestEquation {
    /// ẍ = −ω²x − 2ζωẋ with ω = 1.
    Oscillator {
        /// The damping ratio ζ.
        zeta: f64,
    },
    /// ẍ = −ν ẋ with ν = 1.
    Damping,
}

/// A cached limit's key: the integrator, ζ's bits (`u64::MAX` for pure damping) and the run
/// length it holds for (0 where the limit does not depend on it).
type LimitKey = (IntegratorKind, u64, u64);

/// Largest ω dt searched: beyond it every scheme here is unstable (RK4's limit is 2.83).
const LARGEST_LIMIT: f64 = 64.0;

fn measure_limit(kind: IntegratorKind, test: TestEquation) -> f64 {
    let (mut low, mut high) = (0.0, 0.5);
    while stays_bounded(kind, test, high) {
        low = high;
        high *= 2.0;
        if high > LARGEST_LIMIT {
            return LARGEST_LIMIT;
        }
    }
    while high - low > 1e-4 * high {
        let middle = 0.5 * (low + high);
        if stays_bounded(kind, test, middle) {
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
        // √(u² + v²) written out: `hypot`'s guard against overflow costs a library call per
        // step, and these amplitudes stay between 1e-6 and the escape amplitude.
        let (u, v) = (p.x[1] - 1.0, p.vx[1]);
        let amplitude = (u * u + v * v).sqrt();
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

    /// An escaped trial is unbounded whatever follows: its run ends there.
    fn seen_enough(&self) -> bool {
        self.escaped
    }
}

/// Runs the integrator at ω dt (or ν dt) = `h` on the test equation (unit mass on a unit spring
/// to a fixed particle with a dashpot 2ζ, ω = 1; or on background damping 1 alone, ν = 1) for 2 × [`TRIAL_STEPS`] steps; bounded when it never
/// escapes and the late amplitude is within 1.5 × the early one. A scheme beyond its limit grows by a factor
/// ρ > 1 per step (ρ − 1 ~ √(h − h_c)), so 1000 steps show growth down to (h − h_c)/h_c ≈ 1e-6;
/// within the limit the amplitude is bounded (or decays).
fn stays_bounded(kind: IntegratorKind, test: TestEquation, h: f64) -> bool {
    let (mut state, field) = test_problem(test);
    state.particles.vx[TEST_PARTICLE] = TRIAL_AMPLITUDE;
    let sampling = Sampling {
        dt: h,
        steps: 2 * TRIAL_STEPS,
        every: 2 * TRIAL_STEPS,
        displacements: false,
        relaxation: None,
        deadline: None,
    };
    let mut amplitudes = Amplitudes::default();
    match field {
        TestField::Damped(mut field) => simulate_with(kind, &mut state, &mut field, &sampling, &mut amplitudes),
        TestField::Undamped(mut field) => simulate_with(kind, &mut state, &mut field, &sampling, &mut amplitudes),
    };
    !amplitudes.escaped && amplitudes.late <= 1.5 * amplitudes.early
}

/// The moving particle of a test problem (particle 0 is fixed).
pub const TEST_PARTICLE: usize = 1;

/// The force field of a test problem: with a bond dashpot, or without anything that reads
/// velocities (Gear's corrector weight c₀ depends on which). A bond list of one bond: the same
/// force function as every network's, without the lattice stencil's set-up per evaluation, which
/// for these two particles made the stability trials two thirds of `plan`'s time.
pub enum TestField {
    /// The spring with its bond dashpot.
    Damped(BondNetwork<Linear, BondDashpot, false>),
    /// The spring alone.
    Undamped(BondNetwork<Linear, NoDashpot, false>),
}

/// The test equation as a scene: a unit mass at rest at x = 1 on a spring of rest length 1
/// (stiffness 1, dashpot 2ζ) to a fixed particle at 0, ω = 1; or on background damping 1
/// alone, ν = 1.
pub fn test_problem(test: TestEquation) -> (State, TestField) {
    let (k, gamma, background) = match test {
        TestEquation::Oscillator { zeta } => (1.0, 2.0 * zeta, 0.0),
        TestEquation::Damping => (0.0, 0.0, 1.0),
    };
    let mut particles = Particles::default();
    particles.push(0.0, 0.0, 1.0, Axes::FIXED);
    particles.push(1.0, 0.0, 1.0, Axes::ONLY_X_MOVES);
    let bonds = SquareLattice::chain(2, 1.0, k).bonds();
    let field = if gamma > 0.0 {
        let spring = Spring::<Linear, BondDashpot, false>::new(Linear, BondDashpot { gamma });
        TestField::Damped(BondNetwork::new(spring, &bonds, particles.len(), background))
    } else {
        let spring = Spring::<Linear, NoDashpot, false>::new(Linear, NoDashpot);
        TestField::Undamped(BondNetwork::new(spring, &bonds, particles.len(), background))
    };
    (State::new(particles), field)
}

/// Spectral radius of Gear's amplification matrix on the test equation at ω dt (or ν dt) = `h`.
pub fn gear_spectral_radius(test: TestEquation, h: f64) -> f64 {
    let (state, field) = test_problem(test);
    let matrix = match field {
        TestField::Damped(mut field) => Gear::amplification_matrix(&state, &mut field, TEST_PARTICLE, h),
        TestField::Undamped(mut field) => Gear::amplification_matrix(&state, &mut field, TEST_PARTICLE, h),
    };
    let eigenvalues = faer::Mat::<f64>::from_fn(6, 6, |i, j| matrix[i][j]).eigenvalues();
    // A 6 × 6 matrix of finite numbers always converges; should it not, count it as unstable.
    eigenvalues.map_or(f64::INFINITY, |values| values.iter().map(|z| z.norm()).fold(0.0, f64::max))
}

/// Steps of the scan up from ω dt = 0 for Gear's limit: its spectral radius varies smoothly
/// (no growth interval this narrow shows between 0 and its limits of 0.1 … 0.8), and each
/// step costs `plan` six Gear steps and an eigenvalue problem.
const GEAR_SCAN: f64 = 0.05;

/// Gear's limit over a run of `steps` steps: the first ω dt, scanning up from 0, at which the
/// spectral radius ρ of its amplification passes RUN_GROWTH^(1/steps), refined by bisection
/// to 1e-4: below it every mode (every smaller ω dt) grows by at most [`RUN_GROWTH`] over the
/// run, ρ^steps ≤ RUN_GROWTH.
fn gear_limit(test: TestEquation, steps: u64) -> f64 {
    let allowed = RUN_GROWTH.ln() / steps as f64;
    let grows = |h: f64| gear_spectral_radius(test, h).ln() > allowed;
    let mut low = 0.0;
    let mut high = GEAR_SCAN;
    while !grows(high) {
        low = high;
        high += GEAR_SCAN;
        if high > LARGEST_LIMIT {
            return LARGEST_LIMIT;
        }
    }
    while high - low > 1e-4 * high {
        let middle = 0.5 * (low + high);
        if grows(middle) {
            high = middle;
        } else {
            low = middle;
        }
    }
    low
}
