//! Time integration of a [`Scene`]: the bond force loop, the integrators, per-step probes and
//! the sampled [`Trace`]. Pure computation: no files, no terminal, no threads.

pub use self::field::{BondNetwork, ForceField};
pub use self::integrate::{Integrator, IntegratorKind, PositionVerlet, VelocityVerlet};
pub use self::probe::{ContactClock, Crossing, StepProbe};
pub use self::run::{RunStatus, Sampling, Trace, simulate};
pub use self::scene::{LawKind, Outcome, Scene};
pub use self::state::State;

mod field;
mod integrate;
mod probe;
mod run;
mod scene;
mod state;
