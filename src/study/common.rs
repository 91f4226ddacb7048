//! What every kind's study builds from: the scene's common parts, the relaxation criterion,
//! the linear sound speed, and why a run stopped before its time loop.

use crate::fem::Floppy;
use crate::model::Particles;
use crate::sim::{Network, Relaxation, Sampling, Scene};
use crate::spec::RunSpec;

/// Why a run ended before its time loop.
#[derive(Debug)]
pub enum Stopped {
    /// The load or the drive meets no stiffness (the static problem's [`Floppy`]): no MD run.
    Mechanism(Floppy),
    /// The deadline passed in this stage.
    PastDeadline {
        /// The stage, in words.
        stage: &'static str,
    },
}

/// The scene's parts every kind sets alike, around the kind's `particles` and `network`:
/// no loads, drive, ramp or relaxation (the kinds that have them set them).
pub(super) fn scene(
    spec: &RunSpec,
    particles: Particles,
    network: Network,
    contact_clock: Option<(usize, usize, f64)>,
) -> Scene {
    Scene {
        particles,
        network,
        law: spec.law,
        contact: spec.contact,
        gamma: spec.gamma,
        background_gamma: spec.gamma_background,
        integrator: spec.integrator,
        method: spec.relax().map(|r| r.method).unwrap_or_default(),
        // Set after the static solve, for `relax.method: static` and `relax.preconditioner`.
        rest: None,
        preconditioner: None,
        sampling: Sampling {
            dt: spec.dt,
            steps: spec.steps,
            every: (spec.steps / spec.samples).max(1),
            displacements: spec.records_displacements(),
            deadline: None,
            relaxation: None,
        },
        contact_clock,
        // A wave is timed every step, but never more than 10⁵ entries are kept.
        wave: spec.wave().map(|w| (w.source, w.receivers.clone(), (spec.steps / 100_000).max(1))),
        movie_frames: spec.movie.map(|m| u64::from(m.frames)),
        loads: Vec::new(),
        load_ramp: 0.0,
        drive: None,
    }
}

/// Checks (one t_c apart) that the relaxation criterion must pass in a row: 2N + 1 for the
/// larger side N of a lattice (or the chain's n), a window of 2N t_c. The slowest period
/// 2π√(m/k_min) of the coursework's blocks with diagonals is 2.3 to 5.7 N t_c (measured from
/// their static k_min, 5 × 5 to 40 × 40), so the window spans at least a third of it: a mode
/// still ringing comes within 30° of a crest of its kinetic energy (3/4 of it) inside the
/// window, and a turning point alone does not pass for rest.
pub(super) fn relaxation_checks(side: usize) -> u32 {
    (2 * side + 1) as u32
}

/// The relaxation criterion of a relaxing run (`None` for others): the residual force is
/// relative to `scale` (N), the force the kind's relaxation is judged against; `side` is the
/// kind's N of [`relaxation_checks`].
pub(super) fn relaxation(spec: &RunSpec, scale: Option<f64>, side: usize) -> Option<Relaxation> {
    spec.relax().map(|relax| Relaxation {
        kinetic_ratio: relax.kinetic_ratio,
        residual_force: relax.residual_force.zip(scale).map(|(fraction, scale)| fraction * scale),
        // Set by the kind from its static answer (the lattice's `static_answer`).
        residual_norm: None,
        check_every: (spec.t_c / spec.dt).round().max(1.0) as u64,
        confirmations: relaxation_checks(side),
    })
}

/// The linear sound speed a√(C/m) (m/s) for the stiffness C (N/m) along the path (the mass
/// per unit area is m/a²); `None` for power-law springs, which have no linear sound speed
/// without pre-load, and for C = 0.
pub(super) fn sound_speed(spec: &RunSpec, stiffness: f64) -> Option<f64> {
    (spec.law.is_linear() && stiffness > 0.0).then(|| spec.spacing * (stiffness / spec.mass).sqrt())
}
