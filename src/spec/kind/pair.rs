//! The pair's own fields (a contact pair's gap) and its part of the resolution and of what a
//! run spec tells: its v0 rule, its default length, its particles and bonds.

use crate::spec::issue::{Issue, require};
use crate::spec::raw::RawScene;
use crate::spec::shared::{Deformation, kick_speed};

/// Default gap of a contact pair, in spacings: contact starts at a time not aligned with dt.
const DEFAULT_GAP_PER_SPACING: f64 = 0.05;

/// What only a pair has.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairRun {
    /// Initial gap between the surfaces (m), for a pair with a contact spring.
    pub gap: Option<f64>,
}

impl PairRun {
    /// A pair is kicked: its v0 is required, > 0.
    pub(super) fn resolve_v0(raw: &RawScene) -> Result<f64, Issue> {
        kick_speed(raw)
    }

    /// The gap of a contact pair (default a fraction of the spacing, m); none for a bonded pair.
    pub(super) fn resolve_gap(raw: &RawScene, spacing: f64, contact: bool) -> Result<Option<f64>, Issue> {
        let gap = contact.then(|| raw.gap.unwrap_or(DEFAULT_GAP_PER_SPACING * spacing));
        if let Some(g) = gap {
            require(g.is_finite() && g >= 0.0, "gap", g, "must be a finite number ≥ 0")?;
        }
        Ok(gap)
    }

    /// The run's default length (t_c): a contact pair closes its gap at v0 (m/s), then 1.5 t_c
    /// of contact and flight; a bonded pair 3 t_c.
    pub(super) fn default_duration_tc(&self, v0: f64, t_c: f64) -> f64 {
        match self.gap {
            Some(gap) => gap / (v0 * t_c) + 1.5,
            None => 3.0,
        }
    }

    /// Two particles.
    pub(super) fn particles(&self) -> usize {
        2
    }

    /// One spring.
    pub(super) fn bonds(&self) -> usize {
        1
    }

    /// A pair meets head on at v0 (m/s).
    pub(super) fn deformation(&self, v0: f64) -> Deformation {
        Deformation::Collision(v0)
    }
}
