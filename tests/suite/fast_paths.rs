//! The fast force loops (row stencil for lattices, blocked bond list, threads) against the
//! plainest possible loop over a bond list: same trajectories within 1e-12 relative over 1000
//! steps (200 on the threaded path: `sampling`), for linear, Hertz, damped, contact,
//! constrained and diluted networks.

use mdsolids::model::{Axes, LawSpec, Particles, SquareLattice};
use mdsolids::sim::{IntegratorKind, Network, Sampling, Scene, State};
use mdsolids_reference::Springs;

/// A deterministic pseudo-random number in [−1, 1) from an index (no RNG crate needed).
fn jitter(seed: u64) -> f64 {
    let z = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15).rotate_left(29).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// An nx × ny lattice with diagonals, every node displaced by up to 5 % of a spacing and
/// moving, so that every bond is stretched or compressed; `supports` holds the bottom row
/// vertically and the bottom-left node in both directions (the coursework's supports).
/// `staggered`: the triangular lattice instead, odd rows shifted by half a spacing and rows
/// √3/2 apart.
fn setup(nx: usize, ny: usize, supports: bool, periodic_x: bool, staggered: bool) -> (Particles, SquareLattice) {
    let lattice = SquareLattice {
        nx,
        ny,
        spacing: 1.0,
        k_x: 1.0,
        k_y: 1.3,
        k_rising: 0.5,
        k_falling: 0.4,
        periodic_x,
        staggered,
    };
    let (shift, pitch) = if staggered { (0.5, 3.0_f64.sqrt() / 2.0) } else { (0.0, 1.0) };
    let mut particles = Particles::default();
    for iy in 0..ny {
        for ix in 0..nx {
            let fixed = match (supports, ix, iy) {
                (true, 0, 0) => Axes::FIXED,
                (true, _, 0) => Axes { x: false, y: true },
                _ => Axes::FREE,
            };
            let p = lattice.node(ix, iy) as u64;
            let mass = 1.0 + 0.5 * jitter(4 * p + 3).abs();
            let (x, y) = (ix as f64 + shift * (iy % 2) as f64, iy as f64 * pitch);
            let i = particles.push(x + 0.05 * jitter(4 * p), y + 0.05 * jitter(4 * p + 1), mass, fixed);
            particles.vx[i] = 0.02 * jitter(4 * p + 2);
            particles.vy[i] = if fixed.y { 0.0 } else { 0.02 * jitter(4 * p + 5) };
            if fixed.x {
                particles.vx[i] = 0.0;
            }
        }
    }
    (particles, lattice)
}

/// Steps of a run of `nodes` nodes. A wrong force term, block boundary or thread's partial sum
/// moves a node by the order of its displacement from the first step on, so the lattices of
/// 10⁴ nodes and more (`PARALLEL_MIN_PARTICLES`, src/sim/parallel.rs: the threaded path, and the costliest for the reference loop, which the
/// test package compiles unoptimised: docs/performance.md, "Build and test times") run 200
/// steps; the smaller ones 1000, over which the integrators' histories and the round-off of
/// position Verlet's Störmer form play out.
fn sampling(nodes: usize) -> Sampling {
    Sampling::new(0.02, if nodes >= 10_000 { 200 } else { 1000 })
}

/// Largest position difference, relative to the largest position and to the largest
/// displacement from the start.
fn compare(fast: &State, slow: &State, start: &Particles) -> (f64, f64) {
    let (mut difference, mut position, mut displacement) = (0.0f64, 0.0f64, 0.0f64);
    let (f, s) = (&fast.particles, &slow.particles);
    for i in 0..start.len() {
        difference = difference.max((f.x[i] - s.x[i]).abs()).max((f.y[i] - s.y[i]).abs());
        position = position.max(s.x[i].abs()).max(s.y[i].abs());
        displacement = displacement.max((s.x[i] - start.x[i]).abs()).max((s.y[i] - start.y[i]).abs());
    }
    assert!(displacement > 1e-3, "the scene hardly moved ({displacement}); the comparison would prove nothing");
    (difference / position, difference / displacement)
}

/// One case of the table below, on the square lattice or, `staggered`, the triangular one.
#[allow(clippy::too_many_arguments)] // one case of the table below
fn check(
    name: &str,
    springs: Springs,
    law: LawSpec,
    gamma: f64,
    background: f64,
    integrator: IntegratorKind,
    (nx, ny, supports, periodic_x): (usize, usize, bool, bool),
    dilute: f64,
    staggered: bool,
) {
    let (particles, lattice) = setup(nx, ny, supports, periodic_x, staggered);
    let bonds = if dilute > 0.0 {
        lattice.bonds().randomised(dilute, 0.0, 7, |b| b as u64, |_, _| false)
    } else {
        lattice.bonds()
    };
    let network = if dilute > 0.0 { Network::Bonds(bonds.clone()) } else { Network::Lattice(lattice) };
    let scene = Scene::new(particles.clone(), network, law, sampling(particles.len()))
        .contact(matches!(springs, Springs::PowerContact { .. }))
        .damping(gamma, background)
        .integrator(integrator);
    // Two threads, so that systems of 10⁴ particles and more take the threaded path.
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let fast = pool.install(|| scene.run().state);
    // The reference, optimised in a package of its own (tests/reference).
    let slow = mdsolids_reference::run(springs, &particles, &bonds, background, integrator, &sampling(particles.len()));
    // Only the order of the force sums differs, so the paths part by round-off: positions of
    // up to ~100 m carry ~1e-14 m each step, a random walk to ~1e-13 m over 1000 steps
    // (measured ≤ 2e-15 of the positions for velocity Verlet, 7e-14 for position Verlet, whose
    // Störmer form gathers round-off). Against the displacements (~0.5 m) that is up to 5e-11;
    // any real difference in a force would be of the order of the displacement itself.
    let (to_position, to_displacement) = compare(&fast, &slow, &particles);
    // The energy dissipated, summed in another order: round-off of the sum, ~1e-13 of it.
    let dissipated = (fast.dissipated - slow.dissipated).abs() / slow.dissipated.abs().max(f64::MIN_POSITIVE);
    assert!(
        slow.dissipated == 0.0 && fast.dissipated == 0.0 || dissipated < 1e-9,
        "{name}: dissipated {:e} J on the fast path, {:e} J on the reference",
        fast.dissipated,
        slow.dissipated
    );
    assert!(to_position < 1e-12, "{name}: fast path differs from the reference by {to_position:e} of the positions");
    assert!(
        to_displacement < 1e-9,
        "{name}: fast path differs from the reference by {to_displacement:e} of the displacements"
    );
}

/// (nx, ny, coursework supports, periodic across the sides)
const SMALL: (usize, usize, bool, bool) = (9, 7, false, false);
const LARGE: (usize, usize, bool, bool) = (120, 90, false, false);
const SUPPORTED: (usize, usize, bool, bool) = (40, 30, true, false);
const PERIODIC_SMALL: (usize, usize, bool, bool) = (9, 7, true, true);
const PERIODIC_LARGE: (usize, usize, bool, bool) = (120, 90, true, true);

#[test]
fn linear_lattice() {
    let spring = Springs::Linear;
    for size in [SMALL, LARGE] {
        check("linear", spring, LawSpec::Linear, 0.0, 0.0, IntegratorKind::VelocityVerlet, size, 0.0, false);
    }
    check(
        "linear, position Verlet",
        spring,
        LawSpec::Linear,
        0.0,
        0.0,
        IntegratorKind::PositionVerlet,
        LARGE,
        0.0,
        false,
    );
}

#[test]
fn hertz_lattice_bonded_and_contact() {
    let bonded = Springs::Power { beta: 1.5 };
    check("hertz", bonded, LawSpec::Power { beta: 1.5 }, 0.0, 0.0, IntegratorKind::VelocityVerlet, LARGE, 0.0, false);
    let contact = Springs::PowerContact { beta: 1.5 };
    check(
        "hertz contact",
        contact,
        LawSpec::Power { beta: 1.5 },
        0.0,
        0.0,
        IntegratorKind::VelocityVerlet,
        SMALL,
        0.0,
        false,
    );
}

#[test]
fn damped_lattice() {
    let spring = Springs::LinearDamped { gamma: 0.05 };
    // SUPPORTED has several blocks of rows below the parallel threshold: one thread sums the
    // background power row by row and damps each row once its last bond is in.
    for size in [SMALL, SUPPORTED, LARGE] {
        check("damped", spring, LawSpec::Linear, 0.05, 0.01, IntegratorKind::VelocityVerlet, size, 0.0, false);
    }
    for size in [SMALL, SUPPORTED] {
        check(
            "damped, position Verlet",
            spring,
            LawSpec::Linear,
            0.05,
            0.01,
            IntegratorKind::PositionVerlet,
            size,
            0.0,
            false,
        );
    }
}

#[test]
fn constrained_lattice() {
    let spring = Springs::Linear;
    check("supported", spring, LawSpec::Linear, 0.0, 0.0, IntegratorKind::VelocityVerlet, SUPPORTED, 0.0, false);
    check(
        "supported, position Verlet",
        spring,
        LawSpec::Linear,
        0.0,
        0.0,
        IntegratorKind::PositionVerlet,
        SUPPORTED,
        0.0,
        false,
    );
}

#[test]
fn periodic_lattice() {
    let spring = Springs::LinearDamped { gamma: 0.05 };
    for size in [PERIODIC_SMALL, PERIODIC_LARGE] {
        check("periodic", spring, LawSpec::Linear, 0.05, 0.0, IntegratorKind::VelocityVerlet, size, 0.0, false);
    }
    // The bond-list path keeps the wrapped bonds (with their shift) in a list of their own.
    check(
        "periodic, diluted",
        spring,
        LawSpec::Linear,
        0.05,
        0.0,
        IntegratorKind::VelocityVerlet,
        PERIODIC_LARGE,
        0.1,
        false,
    );
}

/// The triangular lattice on the stencil (rows staggered, one diagonal family between each
/// pair of rows) against the bond list of the same springs: free, supported and periodic,
/// linear and damped, threaded (LARGE) and not.
#[test]
fn triangular_lattice_stencil() {
    let spring = Springs::Linear;
    let damped = Springs::LinearDamped { gamma: 0.05 };
    for size in [SMALL, LARGE, SUPPORTED] {
        check("triangular", spring, LawSpec::Linear, 0.0, 0.0, IntegratorKind::VelocityVerlet, size, 0.0, true);
        check(
            "triangular damped",
            damped,
            LawSpec::Linear,
            0.05,
            0.01,
            IntegratorKind::VelocityVerlet,
            size,
            0.0,
            true,
        );
    }
    for size in [PERIODIC_SMALL, PERIODIC_LARGE] {
        check(
            "triangular periodic",
            damped,
            LawSpec::Linear,
            0.05,
            0.0,
            IntegratorKind::VelocityVerlet,
            size,
            0.0,
            true,
        );
    }
}

#[test]
fn diluted_network_bond_list() {
    let spring = Springs::Linear;
    for size in [SMALL, LARGE] {
        check("diluted", spring, LawSpec::Linear, 0.0, 0.0, IntegratorKind::VelocityVerlet, size, 0.15, false);
    }
    let damped = Springs::PowerDamped { beta: 1.5, gamma: 0.05 };
    check(
        "diluted hertz damped",
        damped,
        LawSpec::Power { beta: 1.5 },
        0.05,
        0.0,
        IntegratorKind::VelocityVerlet,
        LARGE,
        0.15,
        false,
    );
}
