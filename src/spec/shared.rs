//! What chains and lattices share (when a relaxation stops, a timed wave) and what every
//! kind's resolution may use: the speed of a kick, bonded springs, the deformation a run
//! reaches.

use serde::{Deserialize, Serialize};

use super::issue::{Issue, missing, positive, require};
use super::raw::{Control, RawScene, RawWave};

/// E_kin/E_pot below which a relaxation is finished, unless `relax.kinetic_ratio` says.
const DEFAULT_KINETIC_RATIO: f64 = 1e-8;

/// Threshold of the wave-arrival criteria, relative to the source's peak.
const DEFAULT_WAVE_THRESHOLD: f64 = 0.01;

/// When a relaxation is finished, and the small extra step that measures tangent moduli.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RelaxSpec {
    /// Relaxed when E_kin/E_pot stays below this ...
    pub kinetic_ratio: f64,
    /// ... or, when given, when the largest static force stays below this fraction of the
    /// load per node (lattice) or of the equilibrium wall force (chain).
    pub residual_force: Option<f64>,
    /// After relaxing, raise the load (a chain's wall displacement) by this fraction, relax
    /// again and measure tangent moduli (stiffness) from the increments.
    pub tangent_step: Option<f64>,
}

/// A timed wave: from the excited particle to the receivers (a chain's particle, a lattice's
/// bottom row).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WaveSpec {
    /// Excited particle.
    pub source: usize,
    /// Receiving particles: the wave arrives when the first of them moves.
    pub receivers: Vec<usize>,
    /// Distance from the source to the receivers along the wave (m).
    pub distance: f64,
    /// Springs along that distance, N_s (for the coursework's estimate t_s = N_s t_c).
    pub springs: usize,
    /// Threshold of the threshold criteria, relative to the source's peak.
    pub threshold: f64,
}

/// When a relaxation counts as finished, and its tangent step.
pub(super) fn resolve_relax(raw: &RawScene, control: Control) -> Result<RelaxSpec, Issue> {
    let relax = raw.relax.clone().unwrap_or_default();
    let kinetic_ratio = relax.kinetic_ratio.unwrap_or(DEFAULT_KINETIC_RATIO);
    require(kinetic_ratio > 0.0 && kinetic_ratio < 1.0, "relax.kinetic_ratio", kinetic_ratio, "must be in (0, 1)")?;
    if let Some(fraction) = relax.residual_force {
        require(
            fraction > 0.0 && fraction < 1.0,
            "relax.residual_force",
            fraction,
            "must be in (0, 1) (a fraction of the load per node, or of a chain's wall force)",
        )?;
    }
    if let Some(step) = relax.tangent_step {
        require(step > 0.0 && step <= 0.1, "relax.tangent_step", step, "must be in (0, 0.1] (a fraction of the load)")?;
        require(control == Control::Force, "relax.tangent_step", step, "is for control: force")?;
    }
    Ok(RelaxSpec { kinetic_ratio, residual_force: relax.residual_force, tangent_step: relax.tangent_step })
}

/// The threshold of a timed wave's arrival criteria.
pub(super) fn wave_threshold(w: &RawWave) -> Result<f64, Issue> {
    let threshold = w.threshold.unwrap_or(DEFAULT_WAVE_THRESHOLD);
    require(threshold > 0.0 && threshold < 1.0, "wave.threshold", threshold, "must be in (0, 1)")?;
    Ok(threshold)
}

/// The initial speed v0 (m/s) of a kicked scene: required, > 0.
pub(super) fn kick_speed(raw: &RawScene) -> Result<f64, Issue> {
    positive(raw.v0.ok_or_else(|| missing("v0", "the initial speed (m/s), > 0"))?, "v0")
}

/// Lattices and relaxing chains are bonded: no contact springs.
pub(super) fn bonded(contact: bool) -> Result<(), Issue> {
    require(!contact, "material.contact", contact, "lattices and relaxing chains have bonded springs: false")
}

/// The deformation a run is expected to reach, from which a power-law spring's reference
/// extension follows (`reference_extension`).
pub(super) enum Deformation {
    /// A collision or kick at this speed (m/s): the two-body overlap.
    Collision(f64),
    /// A spring carrying this force (N).
    Carrying(f64),
    /// This extension itself (m).
    Extension(f64),
}
