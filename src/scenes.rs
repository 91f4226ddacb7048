//! From a [`RunSpec`] to the [`Scene`] it describes, and to the analytical answers it is
//! compared with. Pure: no I/O.

use crate::model::LawSpec;
use crate::model::{Axes, Bonds, Particles, SquareLattice};
use crate::sim::{Drive, Load, Network, Relaxation, Sampling, Scene};
use crate::spec::{Control, LatticeSpec, LoadCase, RunSpec, SceneKind, Supports};
use crate::theory;

/// Builds the scene of `spec`.
pub fn build_scene(spec: &RunSpec) -> Scene {
    let (particles, lattice, contact_clock) = match (spec.kind, &spec.lattice) {
        (SceneKind::Lattice, Some(l)) => solid(spec, l),
        (SceneKind::Chain, _) => chain(spec),
        _ => pair(spec),
    };
    // A random lattice is an irregular network: the stencil only knows whole bond families.
    let network = match &spec.lattice {
        Some(l) if l.is_random() => Network::Bonds(lattice_bonds(spec, l)),
        _ => Network::Lattice(lattice),
    };
    // An impulse lattice is kicked (or its top row stepped): no load case, drive or relaxation.
    let loaded = spec.lattice.as_ref().filter(|l| l.impulse.is_none());
    let step = spec.lattice.as_ref().and_then(|l| l.impulse.and_then(|i| i.top_row_force).map(|f| (l, f)));
    let loads = match step {
        Some((l, [fx, fy])) => top_row(l).into_iter().map(|particle| Load { particle, fx, fy }).collect(),
        None => loaded.filter(|l| l.control == Control::Force).map(top_row_loads).unwrap_or_default(),
    };
    let drive = loaded.filter(|l| l.control == Control::Velocity).map(|l| top_row_drive(spec, l));
    Scene {
        particles,
        network,
        law: spec.law,
        contact: spec.contact,
        gamma: spec.gamma,
        background_gamma: spec.gamma_background,
        integrator: spec.integrator,
        sampling: Sampling {
            dt: spec.dt,
            steps: spec.steps,
            every: (spec.steps / spec.samples).max(1),
            displacements: spec.records_displacements(),
            deadline: None,
            relaxation: spec.relax.map(|relax| Relaxation {
                kinetic_ratio: relax.kinetic_ratio,
                residual_force: relax.residual_force.zip(load_scale(spec)).map(|(fraction, scale)| fraction * scale),
                check_every: (spec.t_c / spec.dt).round().max(1.0) as u64,
                confirmations: relaxation_checks(spec),
            }),
        },
        contact_clock,
        // A wave is timed every step, but never more than 10⁵ entries are kept.
        wave: spec.wave.as_ref().map(|w| (w.source, w.receivers.clone(), (spec.steps / 100_000).max(1))),
        movie_frames: spec.movie.map(|m| u64::from(m.frames)),
        loads,
        load_ramp: spec.lattice.as_ref().map_or(0.0, |l| l.load_ramp_tc * spec.t_c),
        drive,
    }
}

type Parts = (Particles, SquareLattice, Option<(usize, usize, f64)>);

/// The chain of `nodes` particles joined by springs `k` of rest length `spacing`: an
/// `nodes × 1` lattice.
fn row(nodes: usize, spacing: f64, k: f64) -> SquareLattice {
    SquareLattice { nx: nodes, ny: 1, spacing, k_x: k, k_y: 0.0, k_rising: 0.0, k_falling: 0.0, periodic_x: false }
}

/// Two particles on the x axis, approaching at relative speed v0 (each at v0/2): a contact
/// pair starts `gap` apart (contact begins at t = gap/v0), a bonded pair at its rest length.
fn pair(spec: &RunSpec) -> Parts {
    let mut particles = Particles::default();
    let left = particles.push(0.0, 0.0, spec.mass, Axes::ONLY_X_MOVES);
    let right = particles.push(spec.spacing + spec.gap.unwrap_or(0.0), 0.0, spec.mass, Axes::ONLY_X_MOVES);
    particles.vx[left] = 0.5 * spec.v0;
    particles.vx[right] = -0.5 * spec.v0;
    (particles, row(2, spec.spacing, spec.k), Some((left, right, spec.spacing)))
}

/// n particles between two fixed walls `wall_distance` apart, bonded as an (n+2) × 1
/// lattice (the walls are particles 0 and n+1); particle `node` starts at v0. They start
/// evenly spaced (at equilibrium), or, in a relaxing chain, at rest spacing from the left
/// wall, so the last spring takes the whole wall displacement and the chain must relax.
fn chain(spec: &RunSpec) -> Parts {
    let n = spec.n.unwrap_or(1);
    let walls = spec.wall_distance.unwrap_or((n + 1) as f64 * spec.spacing);
    let gap = if spec.relax.is_some() { spec.spacing } else { walls / (n + 1) as f64 };
    let mut particles = Particles::default();
    for p in 0..n + 2 {
        let fixed = if p == 0 || p == n + 1 { Axes::FIXED } else { Axes::ONLY_X_MOVES };
        let x = if p == n + 1 { walls } else { p as f64 * gap };
        particles.push(x, 0.0, spec.mass, fixed);
    }
    particles.vx[spec.node.unwrap_or(1)] = spec.v0;
    (particles, row(n + 2, spec.spacing, spec.k), None)
}

/// Checks (one t_c apart) that the relaxation criterion must pass in a row: 2N + 1 for the
/// larger side N of a lattice (or the chain's n), a window of 2N t_c, longer than the slowest
/// mode's period (≈ 4N/√(k/m) = 1.8 N t_c for a column of N springs), so no turning point
/// of a ringing lattice passes for rest.
pub fn relaxation_checks(spec: &RunSpec) -> u32 {
    let side = spec.lattice.as_ref().map_or(spec.n.unwrap_or(1), |l| l.nx.max(l.ny));
    (2 * side + 1) as u32
}

/// The force (N) the residual-force criterion is relative to: the load per node of a
/// force-loaded lattice, the equilibrium spring force s(ΔW/(n + 1)) of a relaxing chain.
/// `None` for a velocity-driven lattice: the force its drive must hold is known only from the
/// static answer of its network, and the runner scales the criterion by that
/// (`runner::execute`); its `load_per_node` is an unused default.
pub fn load_scale(spec: &RunSpec) -> Option<f64> {
    match &spec.lattice {
        Some(l) => l.force_per_node(),
        None => Some(chain_equilibrium(spec).1.abs()),
    }
}

/// A relaxing chain's equilibrium: every spring extended by δ = ΔW/(n + 1), carrying
/// s(δ); returns (δ (m), s (N), secant stiffness of the whole chain s/ΔW (N/m), tangent
/// stiffness s′(δ)/(n + 1) (N/m)). The secant is the tangent for ΔW = 0.
pub fn chain_equilibrium(spec: &RunSpec) -> (f64, f64, f64, f64) {
    let springs = (spec.n.unwrap_or(0) + 1) as f64;
    let delta = spec.chain_wall_extension() / springs;
    let law = spec.law;
    let (force, tangent) = (law.elastic_force(spec.k, delta), law.tangent_stiffness(spec.k, delta));
    let secant = if delta == 0.0 { tangent / springs } else { force / (delta * springs) };
    (delta, force, secant, tangent / springs)
}

/// The springs of a lattice scene: k_x along rows, k_y along columns, k_d across the
/// diagonals it has.
pub fn lattice_springs(spec: &RunSpec, l: &LatticeSpec) -> SquareLattice {
    let (k_rising, k_falling) = l.diagonal_stiffness();
    SquareLattice {
        nx: l.nx,
        ny: l.ny,
        spacing: spec.spacing,
        k_x: l.k_x,
        k_y: l.k_y,
        k_rising,
        k_falling,
        periodic_x: l.supports == Supports::PeriodicX,
    }
}

/// The bond list of a lattice scene: its springs, cut and spread at random when it asks.
/// Bonds that touch the top (loaded) or the bottom (supported) row are never cut: a loaded
/// node left hanging on one bond would make almost every diluted lattice a mechanism at its
/// edge, whatever its bulk does; rigidity is lost, or not, in the interior.
pub fn lattice_bonds(spec: &RunSpec, l: &LatticeSpec) -> Bonds {
    let edge = |node: usize| node < l.nx || node >= (l.ny - 1) * l.nx;
    lattice_springs(spec, l).bonds().randomised(l.cut_fraction, l.stiffness_spread, l.seed, |i, j| edge(i) || edge(j))
}

/// Which axes of node (ix, iy) the supports hold.
pub fn support(supports: Supports, ix: usize, iy: usize) -> Axes {
    match (supports, ix, iy) {
        (_, _, 1..) | (Supports::Free, _, _) => Axes::FREE,
        (Supports::Coursework, 0, 0) | (Supports::ClampedBottom | Supports::PeriodicX, _, 0) => Axes::FIXED,
        (Supports::Coursework, _, 0) => Axes { x: false, y: true },
    }
}

/// The load on every top-row node: up (tensile) or to the right (shear).
pub fn top_row_loads(l: &LatticeSpec) -> Vec<Load> {
    let (fx, fy) = match l.load_case {
        LoadCase::Tensile | LoadCase::TensileX => (0.0, l.load_per_node),
        LoadCase::Shear => (l.load_per_node, 0.0),
    };
    top_row(l).into_iter().map(|particle| Load { particle, fx, fy }).collect()
}

/// The top-row nodes of a lattice.
pub fn top_row(l: &LatticeSpec) -> Vec<usize> {
    ((l.ny - 1) * l.nx..l.ny * l.nx).collect()
}

/// How far the top row travels under velocity control: strain · L_y (m), up (tensile) or to
/// the right (shear).
pub fn drive_travel(spec: &RunSpec, l: &LatticeSpec) -> f64 {
    l.drive_strain * (l.ny - 1) as f64 * spec.spacing
}

/// The velocity boundary condition: the top row driven to `drive_travel` in `drive_tc` t_c.
fn top_row_drive(spec: &RunSpec, l: &LatticeSpec) -> Drive {
    let stop_time = l.drive_tc * spec.t_c;
    Drive {
        particles: top_row(l),
        along_y: l.load_case == LoadCase::Tensile,
        velocity: drive_travel(spec, l) / stop_time,
        stop_time,
    }
}

/// An nx × ny lattice at rest on its supports; node (ix, iy) at (ix a, iy a).
fn solid(spec: &RunSpec, l: &LatticeSpec) -> Parts {
    let mut particles = Particles::default();
    for iy in 0..l.ny {
        for ix in 0..l.nx {
            particles.push(ix as f64 * spec.spacing, iy as f64 * spec.spacing, spec.mass, support(l.supports, ix, iy));
        }
    }
    if let Some(impulse) = l.impulse {
        particles.vx[impulse.node] = impulse.vx;
        particles.vy[impulse.node] = impulse.vy;
    }
    (particles, lattice_springs(spec, l), None)
}

/// Analytical contact duration and restitution of a pair, where an exact answer exists:
/// linear springs with any bond damping, power laws only undamped; none with background damping.
pub fn pair_references(spec: &RunSpec) -> (Option<f64>, Option<f64>) {
    if spec.kind != SceneKind::Pair || spec.gamma_background > 0.0 {
        return (None, None);
    }
    match spec.law {
        LawSpec::Linear => (
            theory::linear_contact_duration(spec.k, spec.mass, spec.gamma).ok(),
            theory::linear_restitution(spec.k, spec.mass, spec.gamma).ok(),
        ),
        LawSpec::Power { beta } if spec.gamma == 0.0 => {
            (Some(theory::power_law_contact_duration(spec.k, beta, spec.mass, spec.v0)), Some(1.0))
        }
        LawSpec::Power { .. } => (None, None),
    }
}

/// True when the chain has an exact normal-mode solution: linear bonded springs, no damping,
/// walls at the rest spacing.
pub fn chain_has_normal_modes(spec: &RunSpec) -> bool {
    spec.kind == SceneKind::Chain
        && spec.law.is_linear()
        && !spec.contact
        && spec.gamma == 0.0
        && spec.gamma_background == 0.0
        && spec.wall_distance.is_some_and(|w| (w - (spec.n.unwrap_or(0) + 1) as f64 * spec.spacing).abs() <= 1e-12 * w)
}
