//! The reference the fast force loops are checked against (`tests/suite/fast_paths.rs`): every
//! bond in list order, safe indexing, no blocks, no threads. Its entry point, [`run`], is not
//! generic, so that the loop is compiled here, optimised, and not in the unoptimised tests.

use mdsolids::model::{BondDashpot, Bonds, Dashpot, ForceLaw, Linear, NoDashpot, Particles, PowerLaw, Spring};
use mdsolids::sim::{ForceField, IntegratorKind, PositionVerlet, Sampling, State, VelocityVerlet, simulate};

/// The springs the fast paths are checked with.
#[derive(Clone, Copy, Debug)]
pub enum Springs {
    /// Linear springs, undamped.
    Linear,
    /// Linear springs with a dashpot γ (N s/m) on every bond.
    LinearDamped { gamma: f64 },
    /// Power-law springs of exponent `beta`, bonded (in tension and compression), undamped.
    Power { beta: f64 },
    /// Power-law contact springs (compression only), undamped.
    PowerContact { beta: f64 },
    /// Power-law bonded springs with a dashpot γ (N s/m).
    PowerDamped { beta: f64, gamma: f64 },
}

/// `particles` moved by `integrator` (position or velocity Verlet) over `sampling` under
/// `springs` on `bonds`, with background damping `background` (N s/m), through the plain loop.
pub fn run(
    springs: Springs,
    particles: &Particles,
    bonds: &Bonds,
    background: f64,
    integrator: IntegratorKind,
    sampling: &Sampling,
) -> State {
    let dashpot = |gamma| BondDashpot { gamma };
    let run = Run { particles, bonds, background, integrator, sampling };
    match springs {
        Springs::Linear => run.with(Spring::<_, _, false>::new(Linear, NoDashpot)),
        Springs::LinearDamped { gamma } => run.with(Spring::<_, _, false>::new(Linear, dashpot(gamma))),
        Springs::Power { beta } => run.with(Spring::<_, _, false>::new(PowerLaw { beta }, NoDashpot)),
        Springs::PowerContact { beta } => run.with(Spring::<_, _, true>::new(PowerLaw { beta }, NoDashpot)),
        Springs::PowerDamped { beta, gamma } => run.with(Spring::<_, _, false>::new(PowerLaw { beta }, dashpot(gamma))),
    }
}

/// What a reference run moves, and how.
struct Run<'a> {
    particles: &'a Particles,
    bonds: &'a Bonds,
    background: f64,
    integrator: IntegratorKind,
    sampling: &'a Sampling,
}

impl Run<'_> {
    /// The run under `spring`.
    fn with<L: ForceLaw, D: Dashpot, const CONTACT: bool>(&self, spring: Spring<L, D, CONTACT>) -> State {
        let mut field = ReferenceLoop { spring, bonds: self.bonds.clone(), background_gamma: self.background };
        let mut state = State::new(self.particles.clone());
        // The two schemes the fast paths serve (the others would be compiled here for nothing:
        // each spring and scheme is an instance of the whole time loop).
        match self.integrator {
            IntegratorKind::PositionVerlet => {
                simulate(&mut state, &mut field, &mut PositionVerlet::default(), self.sampling, &mut ())
            }
            IntegratorKind::VelocityVerlet => {
                simulate(&mut state, &mut field, &mut VelocityVerlet::default(), self.sampling, &mut ())
            }
            other => panic!("the reference runs the Verlet schemes only, not {other:?}"),
        };
        state
    }
}

/// Every bond in list order through the one spring force, then the background damping.
struct ReferenceLoop<L, D, const CONTACT: bool> {
    spring: Spring<L, D, CONTACT>,
    bonds: Bonds,
    background_gamma: f64,
}

impl<L: ForceLaw, D: Dashpot, const CONTACT: bool> ForceField for ReferenceLoop<L, D, CONTACT> {
    fn uses_velocity(&self) -> bool {
        D::ACTIVE || self.background_gamma > 0.0
    }

    fn add_forces(&mut self, x: &[f64], y: &[f64], vx: &[f64], vy: &[f64], fx: &mut [f64], fy: &mut [f64]) -> f64 {
        let b = &self.bonds;
        let mut power = 0.0;
        for n in 0..b.len() {
            let (i, j) = (b.i[n], b.j[n]);
            let f = self.spring.force_on_i(
                b.stiffness[n],
                b.rest[n],
                x[i] - x[j] + b.shift_x[n],
                y[i] - y[j],
                vx[i] - vx[j],
                vy[i] - vy[j],
            );
            fx[i] += f.fx;
            fy[i] += f.fy;
            fx[j] -= f.fx;
            fy[j] -= f.fy;
            power += f.dissipation;
        }
        for i in 0..fx.len() {
            fx[i] -= self.background_gamma * vx[i];
            fy[i] -= self.background_gamma * vy[i];
            power += self.background_gamma * (vx[i] * vx[i] + vy[i] * vy[i]);
        }
        power
    }

    fn bond_energy(&self, k: f64, rest: f64, dx: f64, dy: f64) -> f64 {
        self.spring.energy(k, rest, dx, dy)
    }

    fn for_each_bond(&self, visit: &mut dyn FnMut(usize, usize, f64, f64, f64)) {
        self.bonds.for_each(visit);
    }
}
