//! Time integration of a [`Scene`]: the bond force loop, the integrators, per-step probes and
//! the sampled [`Trace`]. Pure computation: no files, no terminal, no threads.

pub use self::contacts::{ContactNetwork, Packing};
pub use self::field::{BondNetwork, ForceField};
pub use self::integrate::{
    ForestRuth, Gear, Integrator, IntegratorKind, PositionVerlet, RungeKutta4, SymplecticEuler, VelocityVerlet,
};
pub use self::probe::{ContactClock, Crossing, Frame, FrameProbe, StepProbe, WaveProbe, WaveRecord};
pub use self::relax::{Preconditioner, PreconditionerKind, RelaxMethod, SharedPreconditioner, euclidean_norm};
pub use self::run::{
    COLLAPSE_RATIO, ProbeTrace, Relaxation, RunStatus, STORED_NUMBERS, STORED_SAMPLES, Sampling, Trace, simulate,
    stored_samples,
};
pub use self::scene::{Network, Outcome, Scene, simulate_with};
pub use self::state::{Drive, Load, State};
pub use self::stencil::LatticeNetwork;

mod contacts;
mod field;
mod integrate;
pub(crate) mod parallel;
mod probe;
mod relax;
mod run;
mod scene;
mod state;
mod stencil;
