//! The packing's own fields (discs, size ratio, area fraction, seed, relaxation) and its part of
//! the resolution and of what a run spec tells: no v0, contact springs, a minimiser, its
//! particles and contacts.

use serde::{Deserialize, Serialize};

use crate::model::bidisperse_box;
use crate::sim::{PreconditionerKind, RelaxMethod};
use crate::spec::issue::{Issue, Num, missing, require};
use crate::spec::raw::{RawPacking, RawScene};
use crate::spec::shared::{Deformation, RelaxSpec};

/// Size ratio of the large discs to the small ones unless `packing.radius_ratio` says (O'Hern
/// et al. 2003's 1:1.4).
const DEFAULT_RADIUS_RATIO: f64 = 1.4;
/// The largest static force left at rest, as a fraction of k·d^β (the force of a contact
/// overlapped by one small diameter d), unless `relax.residual_force` says.
const DEFAULT_RESIDUAL_FORCE: f64 = 1e-9;
/// The overlap (in small diameters) at which a power law is linearised for t_c and the time
/// step: about the overlaps of a packing at φ ≈ 0.9.
pub const REFERENCE_OVERLAP: f64 = 0.03;
/// Most discs a packing may have.
const MOST_DISCS: usize = 10_000_000;
/// Steps of a slow compression unless `packing.compress_steps` says ...
pub(super) const DEFAULT_COMPRESS_STEPS: u32 = 10;
/// ... and the most it may have (each a relaxation of its own).
const MOST_COMPRESS_STEPS: u32 = 200;

/// The resolved packing of a packing scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PackingSpec {
    /// Discs; the first ⌈n/2⌉ small (diameter `geometry.spacing`), the rest large.
    pub n: usize,
    /// Large diameter / small diameter (≥ 1).
    pub radius_ratio: f64,
    /// Area fraction the discs cover in the box, in (0, 1).
    pub fraction: f64,
    /// Seed of the random positions.
    pub seed: u64,
    /// The slow compression the packing is made by, if any (none: made at `fraction`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub compression: Option<Compression>,
}

/// A slow (quasi-static) compression: the discs placed at random and relaxed at area fraction
/// `from`, then box and discs' positions shrunk together in `steps` equal steps of φ up to the
/// packing's fraction, relaxed after each, so that the packing passes through its jamming
/// point as a state followed, not quenched afresh.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Compression {
    /// The area fraction the discs are placed and first relaxed at.
    pub from: f64,
    /// Steps of φ from `from` to the packing's fraction.
    pub steps: u32,
}

impl PackingSpec {
    /// The side (m) of the periodic square box, for small discs of diameter `spacing` (m).
    pub fn box_side(&self, spacing: f64) -> f64 {
        self.box_side_at(self.fraction, spacing)
    }

    /// The side (m) of the box in which the discs cover `fraction`.
    pub fn box_side_at(&self, fraction: f64, spacing: f64) -> f64 {
        bidisperse_box(self.n, 0.5 * spacing, self.radius_ratio, fraction).side
    }

    /// The area fractions the packing is relaxed at, in order: `compression.from` and each
    /// step of φ up to `fraction` (which ends it exactly), or `fraction` alone.
    pub fn stage_fractions(&self) -> Vec<f64> {
        match self.compression {
            Some(c) => (0..=c.steps)
                .map(|k| {
                    if k == c.steps {
                        self.fraction
                    } else {
                        c.from + (self.fraction - c.from) * f64::from(k) / f64::from(c.steps)
                    }
                })
                .collect(),
            None => vec![self.fraction],
        }
    }
}

/// What only a packing has.
#[derive(Clone, Debug, PartialEq)]
pub struct PackingRun {
    /// The discs and their box.
    pub packing: PackingSpec,
    /// How it relaxes (a minimiser) and when it is at rest.
    pub relax: RelaxSpec,
}

impl PackingRun {
    /// The packing's discs, box and relaxation, for small discs of diameter `spacing` (m).
    pub(super) fn resolve(raw: &RawScene, spacing: f64) -> Result<PackingRun, Issue> {
        let section =
            raw.packing.clone().ok_or_else(|| missing("packing", "packing: {n: ≥ 2, fraction: in (0, 1)}"))?;
        let n = section.n.ok_or_else(|| missing("packing.n", "the number of discs, ≥ 2"))?;
        require((2..=MOST_DISCS).contains(&n), "packing.n", n, &format!("an integer from 2 to {MOST_DISCS}"))?;
        let fraction =
            section.fraction.ok_or_else(|| missing("packing.fraction", "the discs' area fraction, in (0, 1)"))?;
        require(fraction > 0.0 && fraction < 1.0, "packing.fraction", Num(fraction), "must be in (0, 1)")?;
        let radius_ratio = section.radius_ratio.unwrap_or(DEFAULT_RADIUS_RATIO);
        require(
            radius_ratio.is_finite() && (1.0..=100.0).contains(&radius_ratio),
            "packing.radius_ratio",
            Num(radius_ratio),
            "must be from 1 to 100 (large diameter / small diameter)",
        )?;
        let compression = compression(&section, fraction)?;
        let packing = PackingSpec { n, radius_ratio, fraction, seed: raw.seed.unwrap_or(1), compression };
        let (side, largest) = (packing.box_side(spacing), radius_ratio * spacing);
        require(
            side > largest,
            "packing.n",
            n,
            &format!(
                "more discs, or a lower packing.fraction: the box side {} m is not larger than a large disc's \
                 diameter {} m (a disc would overlap itself)",
                Num(side),
                Num(largest)
            ),
        )?;
        Ok(PackingRun { packing, relax: resolve_relax(raw)? })
    }

    /// The discs.
    pub(super) fn particles(&self) -> usize {
        self.packing.n
    }

    /// Contacts, at most: three per disc (z ≤ 6 in a 2D packing of discs).
    pub(super) fn bonds(&self) -> usize {
        3 * self.packing.n
    }

    /// The stiffness matrix's degrees of freedom (two per disc), solved for the moduli.
    pub(super) fn static_dofs(&self) -> usize {
        2 * self.packing.n
    }

    /// Contacts overlapped by a few per cent of a small diameter `spacing` (m).
    pub(super) fn deformation(&self, spacing: f64) -> Deformation {
        Deformation::Extension(-REFERENCE_OVERLAP * spacing)
    }
}

/// The slow compression of `packing.compress_from` (below `fraction`) in `packing.compress_steps`
/// steps, if asked for.
fn compression(section: &RawPacking, fraction: f64) -> Result<Option<Compression>, Issue> {
    let Some(from) = section.compress_from else {
        let steps = section.compress_steps;
        require(steps.is_none(), "packing.compress_steps", "(set)", "needs packing.compress_from (where it starts)")?;
        return Ok(None);
    };
    require(
        from > 0.0 && from < fraction,
        "packing.compress_from",
        Num(from),
        &format!("must be in (0, packing.fraction = {}): the compression ends at packing.fraction", Num(fraction)),
    )?;
    let steps = section.compress_steps.unwrap_or(DEFAULT_COMPRESS_STEPS);
    require(
        (1..=MOST_COMPRESS_STEPS).contains(&steps),
        "packing.compress_steps",
        steps,
        &format!("an integer from 1 to {MOST_COMPRESS_STEPS}"),
    )?;
    Ok(Some(Compression { from, steps }))
}

/// A packing relaxes by a minimiser (`fire` by default, or `cg`) until its largest static force
/// is below `relax.residual_force` (a fraction of k·d^β); the lattices' tolerance, tangent step
/// and damped or static methods have no meaning here.
fn resolve_relax(raw: &RawScene) -> Result<RelaxSpec, Issue> {
    let relax = raw.relax.clone().unwrap_or_default();
    let method = relax.method.unwrap_or(RelaxMethod::Fire);
    require(
        method.is_minimiser(),
        "relax.method",
        method.name(),
        "fire or cg: a packing relaxes by a minimiser (it has no static answer, and no time to damp)",
    )?;
    let for_lattices = "is for lattices and chains; a packing stops on relax.residual_force";
    require(relax.tolerance.is_none(), "relax.tolerance", "(set)", for_lattices)?;
    require(relax.tangent_step.is_none(), "relax.tangent_step", "(set)", for_lattices)?;
    require(relax.kinetic_ratio.is_none(), "relax.kinetic_ratio", "(set)", for_lattices)?;
    require(
        relax.preconditioner.is_none_or(|kind| kind == PreconditionerKind::None),
        "relax.preconditioner",
        "(set)",
        "is for lattices (a packing's contacts change as it moves: it has no one stiffness matrix to factor)",
    )?;
    let residual = relax.residual_force.unwrap_or(DEFAULT_RESIDUAL_FORCE);
    require(
        residual > 0.0 && residual < 1e-2,
        "relax.residual_force",
        Num(residual),
        "must be in (0, 0.01) (the largest force left, a fraction of k·d^β)",
    )?;
    Ok(RelaxSpec {
        kinetic_ratio: 1.0,
        residual_force: Some(residual),
        tangent_step: None,
        method,
        tolerance: None,
        critical_background: false,
        preconditioner: PreconditionerKind::None,
    })
}
