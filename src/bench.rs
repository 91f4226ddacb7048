//! The reference workloads of the performance figures (docs/performance.md), as scenes.
//!
//! `kernel`: an N × N square lattice, spacing 1 m, masses 1 kg, springs k = 1 N/m to nearest
//! neighbours and k_d = 0.5 N/m across both diagonals, linear, undamped, all particles free, at
//! rest but for the top-right one at v = (0.1, 0.1) m/s; velocity Verlet, dt = 0.01 s.
//!
//! `relax`: the same N × N network as a relaxing coursework lattice (`lattice-tensile` of
//! campaigns/coursework.yaml): steel-like, k = 2e9 N/m, k_d/k = 0.5, m = 0.785 kg, a = 0.1 m,
//! bond dashpots for restitution 0.5, background damping 12000 N s/m, the bottom row clamped,
//! 1 kN up on every top-row node, the residual-force check every t_c; velocity Verlet,
//! dt = t_c/50.
//!
//! `packing`: N bidisperse discs (half of diameter 1 m, half 1.4 m, masses π r² kg) at
//! uniformly random positions (seed 1) in the periodic square box they cover to φ = 0.90,
//! linear contact springs k = 1 N/m with a dashpot γ = 0.5 m_eff (m_eff = π/8 kg, the small
//! pair's reduced mass, as LAMMPS's `hooke 1 0.5` gives that pair), contacts found by cell
//! lists with a skin of 0.2 m and rebuilt when a disc has moved half of it; velocity Verlet,
//! dt = t_c/50 with t_c = π/√(2k/m) of two small discs (m = π/4 kg). The same workload as
//! ../shared/bench/in.packing for LAMMPS. `--n` counts discs here, not a lattice side.
//!
//! Either lattice workload on another `lattice` type: the same springs k (k_d has no place there) on
//! an N-row triangular, honeycomb or kagome network of N nodes per row (N + 1 rows for a kagome
//! network at even N: its top and bottom rows must be full ones): the triangular one on the
//! stencil (its rows staggered), the honeycomb and kagome through the bond-list loop (their
//! rows are not full; `--bond-list` puts the triangular one there too). Pure: building and
//! timing the scenes does no I/O.

use serde::Serialize;

use crate::model::{Axes, LatticeType, LawSpec, Layout, Particles, PlanarLattice, SquareLattice};
use crate::sim::{IntegratorKind, Load, Network, Relaxation, Sampling, Scene};
use crate::spec::PackingSpec;
use crate::study::packing::discs_of;
use crate::theory::{gamma_for_restitution, linear_contact_duration};

/// Which scene to time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Workload {
    /// The undamped, unloaded lattice: the force kernel and the integrator alone.
    Kernel,
    /// The damped, loaded, clamped lattice with its relaxation checks: a relaxing run's step.
    Relax,
    /// N random bidisperse discs at φ = 0.90 whose contacts come and go (module docs).
    Packing,
}

impl Workload {
    /// The name on the command line and in the JSON line.
    pub fn name(self) -> &'static str {
        match self {
            Workload::Kernel => "kernel",
            Workload::Relax => "relax",
            Workload::Packing => "packing",
        }
    }
}

/// What to run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BenchConfig {
    /// Which scene.
    pub workload: Workload,
    /// Lattice side N (N² particles); discs for `packing`.
    pub n: usize,
    /// Steps to time.
    pub steps: u64,
    /// Fraction of bonds removed at random (0 keeps the regular lattice and its stencil loop;
    /// anything else runs the generic bond-list loop).
    pub dilute: f64,
    /// Run the full lattice through the generic bond-list loop.
    pub bond_list: bool,
    /// The network: the square lattice (stencil or bond list) or another type (bond list).
    pub lattice: LatticeType,
}

impl BenchConfig {
    /// Rows of the network: N, or N + 1 where N rows cannot make it (a kagome network needs an
    /// odd count, so that its top and bottom rows are full).
    pub fn rows(&self) -> usize {
        match PlanarLattice::size_problem(self.lattice, self.n, self.n, false) {
            Some(("ny", _)) => self.n + 1,
            _ => self.n,
        }
    }
}

/// Throughput of one timed run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BenchResult {
    /// `kernel`, `relax` or `packing`.
    pub workload: Workload,
    /// The network's type (a packing has none: `--lattice` as given).
    pub lattice: LatticeType,
    /// Lattice side N, or discs N.
    pub n: usize,
    /// Particles N² (N discs).
    pub particles: usize,
    /// Bonds (overlapping pairs at the start for a packing).
    pub bonds: usize,
    /// Steps timed.
    pub steps: u64,
    /// Threads of the pool the run used.
    pub threads: usize,
    /// `stencil`, `bond-list` or `contacts`.
    pub path: &'static str,
    /// Wall time of the stepping loop (s).
    pub wall_s: f64,
    /// particles × steps / wall time.
    pub particle_steps_per_s: f64,
    /// bonds × steps / wall time.
    pub bond_updates_per_s: f64,
    /// Drift of the energy balance B = E_kin + E_pot + E_dissipated − W_loads over the run,
    /// (B_end − B_0)/max(|B_0|, |W_end|): relative to the start's energy for the kernel (no
    /// loads), to the loads' work for `relax` (which starts at rest, B_0 = 0).
    pub energy_drift: f64,
}

/// The reference lattice's springs.
pub fn reference_lattice(n: usize) -> SquareLattice {
    SquareLattice {
        nx: n,
        ny: n,
        spacing: 1.0,
        k_x: 1.0,
        k_y: 1.0,
        k_rising: 0.5,
        k_falling: 0.5,
        periodic_x: false,
        staggered: false,
    }
}

/// The network of `lattice` as `config` asks: the stencil, the full bond list or a diluted one;
/// the triangular lattice on the stencil too (rows staggered, springs `k_x` of length
/// `spacing`, m), the other types as their bond list, diluted if asked.
fn network(config: &BenchConfig, lattice: SquareLattice) -> Network {
    if !config.bond_list && config.dilute == 0.0 {
        match config.lattice {
            LatticeType::Square => return Network::Lattice(lattice),
            LatticeType::Triangular => {
                let (n, spacing, k) = (lattice.nx, lattice.spacing, lattice.k_x);
                return Network::Lattice(SquareLattice::triangular(n, config.rows(), spacing, k, false));
            }
            LatticeType::Honeycomb | LatticeType::Kagome => {}
        }
    }
    let bonds = match planar(config, lattice.spacing, lattice.k_x) {
        Some(planar) => planar.bonds(),
        None => lattice.bonds(),
    };
    if config.dilute > 0.0 {
        Network::Bonds(bonds.randomised(config.dilute, 0.0, 0x5eed, |b| b as u64, |_, _| false))
    } else {
        Network::Bonds(bonds)
    }
}

/// The network of another type than square, N × N, springs `k` of length `spacing` (m).
fn planar(config: &BenchConfig, spacing: f64, k: f64) -> Option<PlanarLattice> {
    (!config.lattice.is_square()).then_some(PlanarLattice {
        kind: config.lattice,
        nx: config.n,
        ny: config.rows(),
        spacing,
        k,
        periodic_x: false,
    })
}

/// Node positions and edges of the workload's network.
fn layout(config: &BenchConfig, spacing: f64) -> Layout {
    match planar(config, spacing, 1.0) {
        Some(planar) => planar.layout(),
        None => Layout::square(config.n, config.n, spacing, false),
    }
}

/// The scene of `config`, sampled only at its start and end.
pub fn reference_scene(config: &BenchConfig) -> Scene {
    match config.workload {
        Workload::Kernel => kernel_scene(config),
        Workload::Relax => relax_scene(config),
        Workload::Packing => packing_scene(config.n, config.steps),
    }
}

/// The kernel workload (module docs).
fn kernel_scene(config: &BenchConfig) -> Scene {
    let mut particles = Particles::default();
    let layout = layout(config, 1.0);
    for node in 0..layout.len() {
        particles.push(layout.x[node], layout.y[node], 1.0, Axes::FREE);
    }
    let last = particles.len() - 1;
    particles.vx[last] = 0.1;
    particles.vy[last] = 0.1;
    Scene::new(
        particles,
        network(config, reference_lattice(config.n)),
        LawSpec::Linear,
        Sampling::new(0.01, config.steps),
    )
    .integrator(IntegratorKind::VelocityVerlet)
}

/// The relax workload (module docs). Its residual-force tolerance is 0 N, which no state
/// passes (the check asks |f| < 0), so every check costs what it costs in a campaign and none
/// ends the timed loop early.
fn relax_scene(config: &BenchConfig) -> Scene {
    let (n, k, mass, spacing, load) = (config.n, 2.0e9, 0.785, 0.1, 1000.0);
    let lattice = SquareLattice {
        nx: n,
        ny: n,
        spacing,
        k_x: k,
        k_y: k,
        k_rising: 0.5 * k,
        k_falling: 0.5 * k,
        periodic_x: false,
        staggered: false,
    };
    let mut particles = Particles::default();
    let layout = layout(config, spacing);
    for node in 0..layout.len() {
        particles.push(layout.x[node], layout.y[node], mass, Axes::FREE);
    }
    for &node in &layout.edges.bottom {
        particles.hold(node, false);
        particles.hold(node, true);
    }
    let gamma = gamma_for_restitution(0.5, k, mass);
    let t_c = linear_contact_duration(k, mass, gamma).expect("restitution 0.5 is underdamped");
    let mut sampling = Sampling::new(t_c / 50.0, config.steps);
    sampling.relaxation = Some(Relaxation {
        kinetic_ratio: 1e-6,
        residual_force: Some(0.0),
        residual_norm: None,
        check_every: 50,
        confirmations: 2 * n as u32 + 1,
    });
    let mut scene = Scene::new(particles, network(config, lattice), LawSpec::Linear, sampling)
        .damping(gamma, 12000.0)
        .integrator(IntegratorKind::VelocityVerlet);
    scene.loads = layout.edges.top.iter().map(|&particle| Load { particle, fx: 0.0, fy: load }).collect();
    scene
}

/// The packing workload (module docs): `n` discs, `steps` steps.
fn packing_scene(n: usize, steps: u64) -> Scene {
    let (k, small_mass) = (1.0, std::f64::consts::PI * 0.25);
    let discs = PackingSpec { n, radius_ratio: 1.4, fraction: 0.90, seed: 1, compression: None };
    let (packing, particles) = discs_of(&discs, 1.0, small_mass, k);
    // Two small discs: reduced mass m/2, undamped t_c = π/√(k/(m/2)) (LAMMPS's dt).
    let t_c = linear_contact_duration(k, small_mass, 0.0).expect("an undamped pair oscillates");
    Scene::new(particles, Network::Packing(packing), LawSpec::Linear, Sampling::new(t_c / 50.0, steps))
        .contact(true)
        .damping(0.5 * 0.5 * small_mass, 0.0)
        .integrator(IntegratorKind::VelocityVerlet)
}

/// Runs the scene of `config` once on the current rayon pool and measures it.
pub fn run_once(config: &BenchConfig) -> BenchResult {
    let scene = reference_scene(config);
    let (path, bonds) = match &scene.network {
        Network::Lattice(lattice) => ("stencil", lattice.bond_count()),
        Network::Bonds(bonds) => ("bond-list", bonds.len()),
        Network::Packing(packing) => ("contacts", packing.overlapping(&scene.particles.x, &scene.particles.y).len()),
    };
    let particles = scene.particles.len();
    let trace = scene.run().trace;
    let balance = |s: usize| trace.kinetic[s] + trace.potential[s] + trace.dissipated[s] - trace.work[s];
    let last = trace.time.len() - 1;
    let scale = balance(0).abs().max(trace.work[last].abs());
    let steps = trace.steps;
    BenchResult {
        workload: config.workload,
        lattice: config.lattice,
        n: config.n,
        particles,
        bonds,
        steps,
        threads: rayon::current_num_threads(),
        path,
        wall_s: trace.loop_s,
        particle_steps_per_s: (particles as f64) * steps as f64 / trace.loop_s,
        bond_updates_per_s: (bonds as f64) * steps as f64 / trace.loop_s,
        energy_drift: (balance(last) - balance(0)) / scale,
    }
}
