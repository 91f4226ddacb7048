//! The reference workload of the performance figures (README, "Performance"), as a scene:
//! an N × N square lattice, spacing 1 m, masses 1 kg, springs k = 1 N/m to nearest neighbours
//! and k_d = 0.5 N/m across both diagonals, linear, undamped, all particles free, at rest but
//! for the top-right one at v = (0.1, 0.1) m/s; velocity Verlet, dt = 0.01 s.
//! Pure: building and timing the scene does no I/O.

use serde::Serialize;

use crate::model::{Axes, LawSpec, Particles, SquareLattice};
use crate::sim::{IntegratorKind, Network, Sampling, Scene};

/// What to run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BenchConfig {
    /// Lattice side N (N² particles).
    pub n: usize,
    /// Steps to time.
    pub steps: u64,
    /// Fraction of bonds removed at random (0 keeps the regular lattice and its stencil loop;
    /// anything else runs the generic bond-list loop).
    pub dilute: f64,
    /// Run the full lattice through the generic bond-list loop.
    pub bond_list: bool,
}

/// Throughput of one timed run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BenchResult {
    /// Lattice side N.
    pub n: usize,
    /// Particles N².
    pub particles: usize,
    /// Bonds.
    pub bonds: usize,
    /// Steps timed.
    pub steps: u64,
    /// Threads of the pool the run used.
    pub threads: usize,
    /// `stencil` or `bond-list`.
    pub path: &'static str,
    /// Wall time of the stepping loop (s).
    pub wall_s: f64,
    /// particles × steps / wall time.
    pub particle_steps_per_s: f64,
    /// bonds × steps / wall time.
    pub bond_updates_per_s: f64,
    /// (E_end − E_0)/E_0.
    pub energy_drift: f64,
}

/// The reference lattice's springs.
pub fn reference_lattice(n: usize) -> SquareLattice {
    SquareLattice { nx: n, ny: n, spacing: 1.0, k_x: 1.0, k_y: 1.0, k_rising: 0.5, k_falling: 0.5, periodic_x: false }
}

/// The reference scene for `config`, sampled only at its start and end.
pub fn reference_scene(config: &BenchConfig) -> Scene {
    let lattice = reference_lattice(config.n);
    let mut particles = Particles::default();
    for iy in 0..config.n {
        for ix in 0..config.n {
            particles.push(ix as f64, iy as f64, 1.0, Axes::FREE);
        }
    }
    let last = particles.len() - 1;
    particles.vx[last] = 0.1;
    particles.vy[last] = 0.1;
    let network = if config.dilute > 0.0 {
        Network::Bonds(lattice.bonds().randomised(config.dilute, 0.0, 0x5eed, |_, _| false))
    } else if config.bond_list {
        Network::Bonds(lattice.bonds())
    } else {
        Network::Lattice(lattice)
    };
    Scene::new(particles, network, LawSpec::Linear, Sampling::new(0.01, config.steps))
        .integrator(IntegratorKind::VelocityVerlet)
}

/// Runs the reference scene once on the current rayon pool and measures it.
pub fn run_once(config: &BenchConfig) -> BenchResult {
    let scene = reference_scene(config);
    let (path, bonds) = match &scene.network {
        Network::Lattice(lattice) => ("stencil", lattice.bond_count()),
        Network::Bonds(bonds) => ("bond-list", bonds.len()),
    };
    let particles = scene.particles.len();
    let trace = scene.run().trace;
    let energy = |s: usize| trace.kinetic[s] + trace.potential[s];
    let last = trace.time.len() - 1;
    let steps = trace.steps;
    BenchResult {
        n: config.n,
        particles,
        bonds,
        steps,
        threads: rayon::current_num_threads(),
        path,
        wall_s: trace.loop_s,
        particle_steps_per_s: (particles as f64) * steps as f64 / trace.loop_s,
        bond_updates_per_s: (bonds as f64) * steps as f64 / trace.loop_s,
        energy_drift: (energy(last) - energy(0)) / energy(0),
    }
}
