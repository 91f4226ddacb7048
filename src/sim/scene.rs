//! A scene: everything one run integrates, as plain data, and the one place where the run's
//! choices (law, dashpot, contact, integrator) are turned into monomorphised code.

use super::contacts::{ContactNetwork, Packing};
use super::field::{BondNetwork, ForceField};
use super::integrate::{
    ForestRuth, Gear, IntegratorKind, PositionVerlet, RungeKutta4, SymplecticEuler, VelocityVerlet,
};
use super::probe::{ContactClock, Crossing, Frame, FrameProbe, StepProbe, WaveProbe, WaveRecord};
use super::relax::{RelaxMethod, SharedPreconditioner, minimise};
use super::run::{Sampling, Trace, simulate};
use super::state::{Drive, Load, State};
use super::stencil::LatticeNetwork;
use crate::model::{
    BondDashpot, Bonds, Dashpot, ForceLaw, LawSpec, LawVisitor, NoDashpot, Particles, Spring, SquareLattice,
};

/// How the particles are connected.
#[derive(Clone, Debug, PartialEq)]
pub enum Network {
    /// A regular square lattice over all particles (node (ix, iy) is particle iy·nx + ix): the
    /// force loop walks rows, no bond list is stored.
    Lattice(SquareLattice),
    /// Any other network: an explicit bond list, sorted for sequential access.
    Bonds(Bonds),
    /// Discs in a periodic box, their contacts found as they move.
    Packing(Packing),
}

impl Network {
    /// Calls `visit(i, j, rest, k, shift_x)` for every bond (separation x_i − x_j + shift_x)
    /// at positions `(x, y)`: a packing's overlapping pairs there that do not cross the box's
    /// bottom edge (a bond has no y shift), for the plan's mode estimate and the movie.
    pub fn for_each_bond(&self, x: &[f64], y: &[f64], mut visit: impl FnMut(usize, usize, f64, f64, f64)) {
        match self {
            Network::Lattice(lattice) => lattice.for_each_bond(visit),
            Network::Bonds(bonds) => bonds.for_each(visit),
            Network::Packing(packing) => {
                let touching = packing.overlapping(x, y);
                for b in (0..touching.len()).filter(|&b| touching.shift_y[b] == 0.0) {
                    visit(touching.i[b], touching.j[b], touching.rest[b], packing.k, touching.shift_x[b]);
                }
            }
        }
    }
}

/// One run, fully built: particles, bonds, law, damping, integrator, sampling and probes.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Particles at t = 0.
    pub particles: Particles,
    /// Connectivity, rest lengths and stiffness constants.
    pub network: Network,
    /// Elastic law of all bonds.
    pub law: LawSpec,
    /// Bonds act only in compression.
    pub contact: bool,
    /// Bond dashpot γ (N s/m); 0 for none.
    pub gamma: f64,
    /// Background damping γ_g (N s/m); 0 for none.
    pub background_gamma: f64,
    /// Time integrator.
    pub integrator: IntegratorKind,
    /// Time step, length and what to record.
    pub sampling: Sampling,
    /// How a relaxing scene comes to rest: damped motion in time (the integrator's), or a
    /// minimiser, which has no time (nothing watched; a movie has two frames, the start and
    /// the end).
    pub method: RelaxMethod,
    /// Positions (m, x and y) of the static solution, which `RelaxMethod::Static` sets.
    pub rest: Option<(Vec<f64>, Vec<f64>)>,
    /// The stiffness FIRE moves in (`relax.preconditioner: stiffness`), from the static solver.
    pub preconditioner: Option<SharedPreconditioner>,
    /// Bond `(i, j, rest)` whose δ = 0 crossings are timed, if any.
    pub contact_clock: Option<(usize, usize, f64)>,
    /// A wave watched from a source particle to receivers, if any: `(source, receivers,
    /// record every this many steps)`.
    pub wave: Option<(usize, Vec<usize>, u64)>,
    /// Movie frames to keep over the run, if any (a minimiser keeps two: start and end).
    pub movie_frames: Option<u64>,
    /// External forces.
    pub loads: Vec<Load>,
    /// Time (s) over which the loads rise linearly to their full value; 0 for at once.
    pub load_ramp: f64,
    /// A velocity boundary condition, if any.
    pub drive: Option<Drive>,
}

/// What a run produced.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// Sampled series and status.
    pub trace: Trace,
    /// Timed crossings of the watched bond.
    pub crossings: Vec<Crossing>,
    /// The watched wave, every step.
    pub wave: Option<WaveRecord>,
    /// Movie frames (empty unless asked for; a minimiser's: the start and the end).
    pub frames: Vec<Frame>,
    /// State at the end.
    pub state: State,
}

impl Scene {
    /// `particles` joined by `network` under `law`, integrated over `sampling`: bonded springs,
    /// undamped, velocity Verlet, nothing watched, loaded or driven. The setters below change
    /// one choice each; the fields stay open for the rest.
    pub fn new(particles: Particles, network: Network, law: LawSpec, sampling: Sampling) -> Scene {
        Scene {
            particles,
            network,
            law,
            contact: false,
            gamma: 0.0,
            background_gamma: 0.0,
            integrator: IntegratorKind::VelocityVerlet,
            sampling,
            method: RelaxMethod::Damped,
            rest: None,
            preconditioner: None,
            contact_clock: None,
            wave: None,
            movie_frames: None,
            loads: Vec::new(),
            load_ramp: 0.0,
            drive: None,
        }
    }

    /// Bonds act only in compression (`true`) or always (`false`).
    pub fn contact(self, contact: bool) -> Scene {
        Scene { contact, ..self }
    }

    /// Bond dashpot γ and background damping γ_g (N s/m).
    pub fn damping(self, gamma: f64, background_gamma: f64) -> Scene {
        Scene { gamma, background_gamma, ..self }
    }

    /// The time integrator.
    pub fn integrator(self, integrator: IntegratorKind) -> Scene {
        Scene { integrator, ..self }
    }

    /// Integrates the scene. The law, dashpot and contact switch are chosen here, once, so the
    /// bond loop is compiled for exactly this combination.
    pub fn run(self) -> Outcome {
        self.law.dispatch(WithLaw(self))
    }

    fn with_contact<L: ForceLaw, D: Dashpot>(self, law: L, dashpot: D) -> Outcome {
        if self.contact {
            self.with_spring(Spring::<L, D, true>::new(law, dashpot))
        } else {
            self.with_spring(Spring::<L, D, false>::new(law, dashpot))
        }
    }

    fn with_spring<L: ForceLaw, D: Dashpot, const CONTACT: bool>(self, spring: Spring<L, D, CONTACT>) -> Outcome {
        match &self.network {
            Network::Lattice(lattice) => {
                let field = LatticeNetwork::new(spring, *lattice, self.background_gamma);
                self.integrate(field)
            }
            Network::Bonds(bonds) => {
                let field = BondNetwork::new(spring, bonds, self.particles.len(), self.background_gamma);
                self.integrate(field)
            }
            Network::Packing(packing) => {
                let field = ContactNetwork::new(spring, packing.clone(), self.background_gamma);
                self.integrate(field)
            }
        }
    }

    fn integrate<F: ForceField>(self, mut field: F) -> Outcome {
        let mut state = State::with_loads(self.particles, self.loads, self.load_ramp);
        if let Some(drive) = self.drive {
            state = state.with_drive(drive);
        }
        // A minimiser has no time to spread frames over: its movie is the start and the state
        // it stopped at (relaxed, or where it gave up).
        let start = (self.movie_frames.is_some() && self.method != RelaxMethod::Damped).then(|| Frame::of(&state));
        if let Some(trace) = minimise(
            self.method,
            (self.rest.as_ref(), self.preconditioner.as_ref()),
            &mut state,
            &mut field,
            &self.sampling,
        ) {
            let frames = start.map(|start| vec![start, Frame::of(&state)]).unwrap_or_default();
            return Outcome { trace, crossings: Vec::new(), wave: None, frames, state };
        }
        let clock = self.contact_clock.map(|(i, j, rest)| ContactClock::new(i, j, rest));
        let wave = self.wave.map(|(source, receivers, every)| WaveProbe::new(source, receivers, every));
        let movie = self.movie_frames.map(|frames| FrameProbe::new(self.sampling.steps, frames));
        let mut probes = ((clock, wave), movie);
        let trace = simulate_with(self.integrator, &mut state, &mut field, &self.sampling, &mut probes);
        let ((clock, wave), movie) = probes;
        Outcome {
            trace,
            crossings: clock.map(|c| c.crossings).unwrap_or_default(),
            wave: wave.map(|w| w.record),
            frames: movie.map(|m| m.frames).unwrap_or_default(),
            state,
        }
    }
}

/// A scene handed its concrete law by [`LawSpec::dispatch`]; chooses the dashpot next.
struct WithLaw(Scene);

impl LawVisitor for WithLaw {
    type Output = Outcome;
    fn visit<L: ForceLaw>(self, law: L) -> Outcome {
        let scene = self.0;
        let gamma = scene.gamma;
        if gamma > 0.0 { scene.with_contact(law, BondDashpot { gamma }) } else { scene.with_contact(law, NoDashpot) }
    }
}

/// Runs `sampling` on `state` under `field` with the integrator `kind`: the one place that
/// turns the choice into monomorphised code.
pub fn simulate_with<F: ForceField, P: StepProbe>(
    kind: IntegratorKind,
    state: &mut State,
    field: &mut F,
    sampling: &Sampling,
    probe: &mut P,
) -> Trace {
    match kind {
        IntegratorKind::PositionVerlet => simulate(state, field, &mut PositionVerlet::default(), sampling, probe),
        IntegratorKind::VelocityVerlet => simulate(state, field, &mut VelocityVerlet::default(), sampling, probe),
        IntegratorKind::SymplecticEuler => simulate(state, field, &mut SymplecticEuler, sampling, probe),
        IntegratorKind::Rk4 => simulate(state, field, &mut RungeKutta4::default(), sampling, probe),
        IntegratorKind::ForestRuth => simulate(state, field, &mut ForestRuth::default(), sampling, probe),
        IntegratorKind::Gear => simulate(state, field, &mut Gear::default(), sampling, probe),
    }
}
