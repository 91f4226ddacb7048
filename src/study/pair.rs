//! The pair: two particles meeting head on. Its scene, its analytical contact duration and
//! restitution, and its measurement (the contact timed inside the step).

use serde::{Deserialize, Serialize};

use super::columns::{Block, Column, Slot};
use super::common::scene;
use crate::measure::{contact_timing, relative_error};
use crate::model::LawSpec;
use crate::model::{Axes, Particles, SquareLattice};
use crate::sim::{Network, Outcome, Scene};
use crate::spec::{PairRun, RunSpec};
use crate::theory;

/// What a pair measures, with its analytical twins.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PairMetrics {
    /// Contact duration (s), crossings located inside the step.
    pub contact_duration: Option<f64>,
    /// Analytical contact duration (s).
    pub contact_duration_theory: Option<f64>,
    /// Restitution coefficient.
    pub restitution: Option<f64>,
    /// Analytical restitution.
    pub restitution_theory: Option<f64>,
}

/// Two particles on the x axis, approaching at relative speed v0 (each at v0/2): a contact
/// pair starts `gap` apart (contact begins at t = gap/v0), a bonded pair at its rest length.
pub(super) fn build(spec: &RunSpec, pair: &PairRun) -> Scene {
    let mut particles = Particles::default();
    let left = particles.push(0.0, 0.0, spec.mass, Axes::ONLY_X_MOVES);
    let right = particles.push(spec.spacing + pair.gap.unwrap_or(0.0), 0.0, spec.mass, Axes::ONLY_X_MOVES);
    particles.vx[left] = 0.5 * spec.v0;
    particles.vx[right] = -0.5 * spec.v0;
    let network = Network::Lattice(SquareLattice::chain(2, spec.spacing, spec.k));
    scene(spec, particles, network, Some((left, right, spec.spacing)))
}

/// Analytical contact duration and restitution of a pair, where an exact answer exists:
/// linear springs with any bond damping, power laws only undamped; none with background damping.
pub fn references(spec: &RunSpec) -> (Option<f64>, Option<f64>) {
    if spec.gamma_background > 0.0 {
        return (None, None);
    }
    match spec.law {
        LawSpec::Linear => (
            theory::linear_contact_duration(spec.k, spec.mass, spec.gamma).ok(),
            theory::linear_restitution(spec.k, spec.mass, spec.gamma).ok(),
        ),
        LawSpec::Power { beta } if spec.gamma == 0.0 => {
            (Some(theory::power_law_contact_duration(spec.k, beta, spec.mass, spec.v0)), Some(1.0))
        }
        // A damped power law (and any law without a closed form here) has no exact answer.
        _ => (None, None),
    }
}

/// The contact's duration and restitution, measured and analytical.
pub(super) fn measure(spec: &RunSpec, outcome: &Outcome, metrics: &mut PairMetrics) {
    let timing = contact_timing(&outcome.crossings);
    let (contact_duration_theory, restitution_theory) = references(spec);
    metrics.contact_duration = timing.map(|t| t.duration);
    metrics.contact_duration_theory = contact_duration_theory;
    metrics.restitution = timing.map(|t| t.restitution);
    metrics.restitution_theory = restitution_theory;
}

/// The error against the exact answer: of the contact duration when `undamped`, else of the
/// restitution; with the name of what it measures.
pub(super) fn exact_error(undamped: bool, m: &PairMetrics) -> (Option<f64>, &'static str) {
    let relative = |a, b| relative_error(a, b).map(f64::abs);
    if undamped {
        (relative(m.contact_duration, m.contact_duration_theory), "contact_duration")
    } else {
        (relative(m.restitution, m.restitution_theory), "restitution")
    }
}

/// Why a pair that ended well has no contact duration.
pub(super) fn caveat(m: &PairMetrics) -> Option<&'static str> {
    m.contact_duration.is_none().then_some("the contact did not close and open again within the run")
}

/// The pair's result columns: its contact beside the exact answer, with their relative errors.
pub(super) fn columns() -> Vec<Block<PairMetrics>> {
    use Column::Number;
    let columns: Vec<Column<PairMetrics>> = vec![
        Number("contact_duration", |r| r.group.contact_duration),
        Number("contact_duration_theory", |r| r.group.contact_duration_theory),
        Number("contact_duration_error", |r| relative_error(r.group.contact_duration, r.group.contact_duration_theory)),
        Number("restitution", |r| r.group.restitution),
        Number("restitution_theory", |r| r.group.restitution_theory),
        Number("restitution_error", |r| relative_error(r.group.restitution, r.group.restitution_theory)),
    ];
    vec![Block { slot: Slot::Measured, shown: None, columns }]
}
