//! From a [`RunSpec`] to the [`Scene`] it describes, and to the analytical answers it is
//! compared with. Pure: no I/O.

use crate::model::{Axes, Particles, SquareLattice};
use crate::sim::{LawKind, Network, Sampling, Scene};
use crate::spec::{LawName, RunSpec, SceneKind};
use crate::theory;

/// Builds the scene of `spec`.
pub fn build_scene(spec: &RunSpec) -> Scene {
    let (particles, lattice, contact_clock) = match spec.kind {
        SceneKind::Pair => pair(spec),
        SceneKind::Chain => chain(spec),
    };
    Scene {
        particles,
        network: Network::Lattice(lattice),
        law: match spec.law {
            LawName::Linear => LawKind::Linear,
            LawName::Power => LawKind::Power { beta: spec.beta },
        },
        contact: spec.contact,
        gamma: spec.gamma,
        background_gamma: spec.gamma_background,
        integrator: spec.integrator,
        sampling: Sampling {
            dt: spec.dt,
            steps: spec.steps,
            every: (spec.steps / spec.samples).max(1),
            displacements: spec.kind == SceneKind::Chain,
        },
        contact_clock,
    }
}

type Parts = (Particles, SquareLattice, Option<(usize, usize, f64)>);

/// The chain of `nodes` particles joined by springs `k` of rest length `spacing`: an
/// `nodes × 1` lattice.
fn row(nodes: usize, spacing: f64, k: f64) -> SquareLattice {
    SquareLattice { nx: nodes, ny: 1, spacing, k_x: k, k_y: 0.0, k_rising: 0.0, k_falling: 0.0 }
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

/// n particles evenly between two fixed walls `wall_distance` apart, bonded as an (n+2) × 1
/// lattice (the walls are particles 0 and n+1); particle `node` starts at v0.
fn chain(spec: &RunSpec) -> Parts {
    let n = spec.n.unwrap_or(1);
    let walls = spec.wall_distance.unwrap_or((n + 1) as f64 * spec.spacing);
    let mut particles = Particles::default();
    for p in 0..n + 2 {
        let fixed = if p == 0 || p == n + 1 { Axes::FIXED } else { Axes::ONLY_X_MOVES };
        particles.push(p as f64 * walls / (n + 1) as f64, 0.0, spec.mass, fixed);
    }
    particles.vx[spec.node.unwrap_or(1)] = spec.v0;
    (particles, row(n + 2, spec.spacing, spec.k), None)
}

/// Analytical contact duration and restitution of a pair, where an exact answer exists:
/// linear springs with any bond damping, power laws only undamped; none with background damping.
pub fn pair_references(spec: &RunSpec) -> (Option<f64>, Option<f64>) {
    if spec.kind != SceneKind::Pair || spec.gamma_background > 0.0 {
        return (None, None);
    }
    match spec.law {
        LawName::Linear => (
            theory::linear_contact_duration(spec.k, spec.mass, spec.gamma).ok(),
            theory::linear_restitution(spec.k, spec.mass, spec.gamma).ok(),
        ),
        LawName::Power if spec.gamma == 0.0 => {
            (Some(theory::power_law_contact_duration(spec.k, spec.beta, spec.mass, spec.v0)), Some(1.0))
        }
        LawName::Power => (None, None),
    }
}

/// True when the chain has an exact normal-mode solution: linear bonded springs, no damping,
/// walls at the rest spacing.
pub fn chain_has_normal_modes(spec: &RunSpec) -> bool {
    spec.kind == SceneKind::Chain
        && spec.law == LawName::Linear
        && !spec.contact
        && spec.gamma == 0.0
        && spec.gamma_background == 0.0
        && spec.wall_distance.is_some_and(|w| (w - (spec.n.unwrap_or(0) + 1) as f64 * spec.spacing).abs() <= 1e-12 * w)
}
