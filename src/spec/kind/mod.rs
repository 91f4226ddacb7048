//! A run's scene kind with the fields only that kind has (`kind/pair.rs`, `kind/chain.rs`,
//! `kind/lattice.rs`, declared and re-exported here), and the dispatch to them: which YAML fields each kind takes, its part of
//! the resolution, the facts a run spec asks of it, and its stored columns. The
//! matches here (and in `study`) are where a new kind is added.

use serde::{Deserialize, Serialize};

pub use self::chain::ChainRun;
pub use self::lattice::{ImpulseSpec, LatticeRun, LatticeSpec, ProbeLine};
pub use self::packing::{Compression, PackingRun, PackingSpec, REFERENCE_OVERLAP as PACKING_REFERENCE_OVERLAP};
pub use self::pair::PairRun;

mod chain;
mod lattice;
mod lattice_type;
mod packing;
mod pair;

use self::lattice::{Solid, derive_from_solid};
use super::issue::{Issue, require};
use super::raw::{RawMaterial, RawScene, SceneKind};
use super::shared::{Deformation, RelaxSpec, WaveSpec};

/// The kind of a run's scene, carrying that kind's own fields.
#[derive(Clone, Debug, PartialEq)]
pub enum KindSpec {
    /// Two particles.
    Pair(PairRun),
    /// N particles between two walls.
    Chain(ChainRun),
    /// A square lattice.
    Lattice(LatticeRun),
    /// Discs in a periodic box.
    Packing(PackingRun),
}

impl KindSpec {
    /// The kind's tag.
    pub fn kind(&self) -> SceneKind {
        match self {
            KindSpec::Pair(_) => SceneKind::Pair,
            KindSpec::Chain(_) => SceneKind::Chain,
            KindSpec::Lattice(_) => SceneKind::Lattice,
            KindSpec::Packing(_) => SceneKind::Packing,
        }
    }

    /// The same kind without its relaxation and timed wave (what a network's modes do not
    /// depend on).
    pub fn without_relax_and_wave(&self) -> KindSpec {
        match self {
            KindSpec::Pair(pair) => KindSpec::Pair(*pair),
            KindSpec::Chain(chain) => KindSpec::Chain(ChainRun { relax: None, wave: None, ..chain.clone() }),
            KindSpec::Lattice(lattice) => KindSpec::Lattice(LatticeRun { relax: None, wave: None, ..lattice.clone() }),
            KindSpec::Packing(packing) => KindSpec::Packing(packing.clone()),
        }
    }

    /// A chain's fields; `None` for other kinds.
    pub fn chain(&self) -> Option<&ChainRun> {
        match self {
            KindSpec::Chain(chain) => Some(chain),
            _ => None,
        }
    }

    /// A lattice scene's lattice; `None` for other kinds.
    pub fn lattice(&self) -> Option<&LatticeSpec> {
        match self {
            KindSpec::Lattice(run) => Some(&run.lattice),
            _ => None,
        }
    }

    /// A packing scene's packing; `None` for other kinds.
    pub fn packing(&self) -> Option<&PackingSpec> {
        match self {
            KindSpec::Packing(run) => Some(&run.packing),
            _ => None,
        }
    }

    /// When the relaxation of a loaded lattice, a relaxing chain or a packing stops; `None`
    /// otherwise.
    pub fn relax(&self) -> Option<RelaxSpec> {
        match self {
            KindSpec::Pair(_) => None,
            KindSpec::Chain(chain) => chain.relax,
            KindSpec::Lattice(run) => run.relax,
            KindSpec::Packing(run) => Some(run.relax),
        }
    }

    /// The timed wave of a chain or an impulse lattice, if asked for.
    pub fn wave(&self) -> Option<&WaveSpec> {
        match self {
            KindSpec::Pair(_) | KindSpec::Packing(_) => None,
            KindSpec::Chain(chain) => chain.wave.as_ref(),
            KindSpec::Lattice(run) => run.wave.as_ref(),
        }
    }

    /// The kind's own fields before the time scale, from springs of stiffness `k` (N/m) and
    /// rest length `spacing` (m) and the solid's `depth` (m): a chain or a lattice (with how
    /// it was derived from a solid, if it was) and their relaxation; a pair's gap and a
    /// lattice's wave are decided with the time scale.
    pub(super) fn resolve(
        kind: SceneKind,
        raw: &RawScene,
        k: f64,
        spacing: f64,
        depth: Option<f64>,
        derived_from: Option<String>,
    ) -> Result<KindSpec, Issue> {
        Ok(match kind {
            SceneKind::Pair => KindSpec::Pair(PairRun { gap: None }),
            SceneKind::Chain => KindSpec::Chain(ChainRun::resolve(raw, spacing)?),
            SceneKind::Lattice => KindSpec::Lattice(LatticeRun::resolve(raw, k, depth, derived_from)?),
            SceneKind::Packing => KindSpec::Packing(PackingRun::resolve(raw, spacing)?),
        })
    }

    /// Checks of the kind's fields against the springs' rest length `spacing` (m) and `v0` (m/s).
    pub(super) fn check(&self, spacing: f64, v0: f64) -> Result<(), Issue> {
        match self {
            KindSpec::Chain(chain) => chain.check(spacing, v0),
            KindSpec::Pair(_) | KindSpec::Lattice(_) | KindSpec::Packing(_) => Ok(()),
        }
    }

    /// True when the run is a collision (a pair, a hit chain), whose contact time is the
    /// exact two-body one of its law; a loaded or relaxing scene takes the linear one.
    pub fn is_collision(&self) -> bool {
        match self {
            KindSpec::Pair(_) => true,
            KindSpec::Chain(chain) => chain.is_collision(),
            KindSpec::Lattice(_) | KindSpec::Packing(_) => false,
        }
    }

    /// The fields decided with the contact time, before the run's length: a contact pair's gap.
    pub(super) fn resolve_before_length(&mut self, raw: &RawScene, spacing: f64, contact: bool) -> Result<(), Issue> {
        if let KindSpec::Pair(pair) = self {
            pair.gap = PairRun::resolve_gap(raw, spacing, contact)?;
        }
        Ok(())
    }

    /// The fields decided after the run's length: an impulse lattice's timed wave.
    pub(super) fn resolve_after_length(&mut self, raw: &RawScene, spacing: f64) -> Result<(), Issue> {
        match self {
            KindSpec::Lattice(run) => run.resolve_wave(raw, spacing),
            KindSpec::Pair(_) | KindSpec::Chain(_) | KindSpec::Packing(_) => Ok(()),
        }
    }

    /// The run's default length (t_c), for v0 (m/s) and t_c (s); `None`: a relaxation's
    /// `relax.max_tc`.
    pub(super) fn default_duration_tc(&self, v0: f64, t_c: f64) -> Option<f64> {
        match self {
            KindSpec::Pair(pair) => Some(pair.default_duration_tc(v0, t_c)),
            KindSpec::Chain(chain) => chain.default_duration_tc(),
            KindSpec::Lattice(run) => run.default_duration_tc(),
            KindSpec::Packing(_) => None,
        }
    }

    /// Number of particles the scene simulates (walls included).
    pub(super) fn particles(&self) -> usize {
        match self {
            KindSpec::Pair(pair) => pair.particles(),
            KindSpec::Chain(chain) => chain.particles(),
            KindSpec::Lattice(run) => run.particles(),
            KindSpec::Packing(run) => run.particles(),
        }
    }

    /// Springs of the scene's network.
    pub(super) fn bonds(&self) -> usize {
        match self {
            KindSpec::Pair(pair) => pair.bonds(),
            KindSpec::Chain(chain) => chain.bonds(),
            KindSpec::Lattice(run) => run.bonds(),
            KindSpec::Packing(run) => run.bonds(),
        }
    }

    /// Particles whose series a record stores: a chain's all, a lattice's probed ones, none of
    /// a pair.
    pub(super) fn stored_nodes(&self) -> usize {
        match self {
            KindSpec::Pair(_) | KindSpec::Packing(_) => 0,
            KindSpec::Chain(chain) => chain.particles(),
            KindSpec::Lattice(run) => run.stored_nodes(),
        }
    }

    /// True when the kind records every particle's displacement and velocity: chains (normal
    /// modes, space–time), impulse and probed lattices.
    pub(super) fn records_displacements(&self) -> bool {
        match self {
            KindSpec::Packing(_) => false,
            // A pair's two particles cost nothing; the report draws their overlap against δ(t).
            KindSpec::Pair(_) | KindSpec::Chain(_) => true,
            KindSpec::Lattice(run) => run.records_displacements(),
        }
    }

    /// Degrees of freedom of the static problem solved beside MD (a loaded lattice); 0 when
    /// there is none.
    pub(super) fn static_dofs(&self) -> usize {
        match self {
            KindSpec::Lattice(run) => run.static_dofs(),
            KindSpec::Packing(run) => run.static_dofs(),
            KindSpec::Pair(_) | KindSpec::Chain(_) => 0,
        }
    }

    /// The deformation the run is expected to reach, for springs of rest length `spacing` (m)
    /// and v0 (m/s).
    pub(super) fn deformation(&self, spacing: f64, v0: f64) -> Deformation {
        match self {
            KindSpec::Pair(pair) => pair.deformation(v0),
            KindSpec::Chain(chain) => chain.deformation(spacing, v0),
            KindSpec::Lattice(run) => run.deformation(spacing),
            KindSpec::Packing(run) => run.deformation(spacing),
        }
    }
}

/// The initial speed v0 (m/s) of a `kind` scene: none for a lattice, ≥ 0 for a relaxing chain
/// (its walls may be what moves it), > 0 and required otherwise; lattices and relaxing chains
/// are bonded (`contact` false).
pub(super) fn resolve_v0(kind: SceneKind, raw: &RawScene, contact: bool) -> Result<f64, Issue> {
    match kind {
        SceneKind::Pair => PairRun::resolve_v0(raw),
        SceneKind::Chain => ChainRun::resolve_v0(raw, contact),
        SceneKind::Lattice => LatticeRun::resolve_v0(contact),
        // A packing starts at rest; `check_fields` refuses a v0.
        SceneKind::Packing => Ok(0.0),
    }
}

/// Mass and stiffness derived from the solid a lattice stands for (`material.density`,
/// `material.youngs_modulus`), refused for other kinds.
pub(super) fn solid(
    kind: SceneKind,
    raw: &RawScene,
    material: &RawMaterial,
    spacing: f64,
    depth: Option<f64>,
) -> Result<Solid, Issue> {
    match kind {
        SceneKind::Lattice => derive_from_solid(raw, material, spacing, depth),
        SceneKind::Pair | SceneKind::Chain | SceneKind::Packing => {
            let only_lattices = "only for lattice scenes (give mass and k directly)";
            let derived = material.density.is_some() || material.youngs_modulus.is_some();
            require(!derived, "material.density", "(set)", only_lattices)?;
            Ok(Solid::default())
        }
    }
}

/// Rejects fields that belong to another kind of scene.
pub(super) fn check_fields(kind: SceneKind, raw: &RawScene) -> Result<(), Issue> {
    let only = |present: bool, path: &str, owner: &str| {
        require(!present, path, "(set)", &format!("only for {owner}; remove it from this {} scene", kind.name()))
    };
    let contact = raw.material.as_ref().and_then(|m| m.contact).unwrap_or(false);
    let is = |wanted: SceneKind| kind == wanted;
    only(raw.gap.is_some() && !(is(SceneKind::Pair) && contact), "gap", "pairs with material.contact: true")?;
    for (present, path) in
        [(raw.n.is_some(), "n"), (raw.node.is_some(), "node"), (raw.wall_distance.is_some(), "wall_distance")]
    {
        only(present && !is(SceneKind::Chain), path, "chain scenes")?;
    }
    only(raw.wave.is_some() && is(SceneKind::Pair), "wave", "chain and lattice scenes")?;
    only(raw.impulse.is_some() && !is(SceneKind::Lattice), "impulse", "lattice scenes")?;
    only(
        raw.probes.is_some() && !is(SceneKind::Lattice),
        "probes",
        "lattice scenes (a chain records every particle; its wave.receiver picks the timed one)",
    )?;
    if raw.impulse.is_some() {
        only(raw.load.is_some(), "load", "loaded lattices (an impulse lattice is kicked, not loaded)")?;
        only(raw.relax.is_some(), "relax", "loaded lattices (an impulse lattice runs for time.duration_tc)")?;
    }
    only(
        raw.wave.as_ref().is_some_and(|w| w.receiver.is_some()) && is(SceneKind::Lattice),
        "wave.receiver",
        "chains (a lattice's receiver is its bottom row)",
    )?;
    only(raw.wave.is_some() && is(SceneKind::Lattice) && raw.impulse.is_none(), "wave", "chains and impulse lattices")?;
    for (present, path) in
        [(raw.lattice.is_some(), "lattice"), (raw.supports.is_some(), "supports"), (raw.load.is_some(), "load")]
    {
        only(present && !is(SceneKind::Lattice), path, "lattice scenes")?;
    }
    only(
        raw.seed.is_some() && !is(SceneKind::Lattice) && !is(SceneKind::Packing),
        "seed",
        "lattice and packing scenes",
    )?;
    check_packing_fields(kind, raw)?;
    only(raw.relax.is_some() && is(SceneKind::Pair), "relax", "lattices and chains between moved walls")?;
    only(raw.relax.is_some() && raw.wave.is_some(), "wave", "chains that are hit, not relaxed")?;
    only(raw.v0.is_some() && is(SceneKind::Lattice), "v0", "pair and chain scenes (lattices are loaded, not kicked)")
}

/// A packing's section only on a packing; a packing has no kick or damping (it relaxes by a
/// minimiser, which has no time: its movie is the start and the relaxed state), and its
/// springs are contacts.
fn check_packing_fields(kind: SceneKind, raw: &RawScene) -> Result<(), Issue> {
    let packing = kind == SceneKind::Packing;
    let only = |present: bool, path: &str, allowed: &str| require(!present, path, "(set)", allowed);
    only(raw.packing.is_some() && !packing, "packing", "only for packing scenes; remove it from this scene")?;
    if !packing {
        return Ok(());
    }
    let untimed = "not for packing scenes: a packing starts at rest and relaxes by a minimiser, which has no time";
    only(raw.v0.is_some(), "v0", untimed)?;
    only(raw.damping.is_some(), "damping", untimed)?;
    let time = raw.time.clone().unwrap_or_default();
    only(
        time.integrator.is_some(),
        "time.integrator",
        "not for packing scenes: FIRE and CG step by their own schemes (FIRE by semi-implicit Euler), whatever \
         time.integrator says; remove it",
    )?;
    only(
        time.reference_refinement.is_some(),
        "time.reference_refinement",
        "not for packing scenes: a minimiser's state has no trajectory to refine against",
    )?;
    only(raw.wave.is_some(), "wave", "not for packing scenes: a packing is relaxed, not hit")?;
    let strained = raw.movie.as_ref().and_then(|m| m.bond_strain) == Some(true);
    only(
        strained,
        "movie.bond_strain",
        "not for packing scenes: a packing has contacts, not bonds; its movie draws each contact as a line as wide as its force",
    )?;
    let bonded = raw.material.as_ref().and_then(|m| m.contact) == Some(false);
    require(!bonded, "material.contact", false, "a packing's springs are contacts (true, the default here)")?;
    compressed_movie_frames(raw)
}

/// A slowly compressed packing's movie has a frame for its start and one for each relaxed
/// stage: `movie.frames`, if given, must count them (the plan budgets the movie by it).
fn compressed_movie_frames(raw: &RawScene) -> Result<(), Issue> {
    let Some(section) = raw.packing.as_ref().filter(|p| p.compress_from.is_some()) else { return Ok(()) };
    let Some(frames) = raw.movie.as_ref().and_then(|m| m.frames) else { return Ok(()) };
    // The default of packing.compress_steps is checked with it in `packing::compression`.
    let stages = section.compress_steps.unwrap_or(packing::DEFAULT_COMPRESS_STEPS) + 1;
    require(
        frames == stages + 1,
        "movie.frames",
        frames,
        &format!(
            "must be {}: a slowly compressed packing's movie is its start and each of its {stages} relaxed stages \
             (packing.compress_steps + 2)",
            stages + 1
        ),
    )
}

/// The kind's own fields in their flat columns, `None` where the kind has no such field.
///
/// Stored beside the other fields of a run spec, in this order: a new kind's own field must
/// be skipped when null (`#[serde(default, skip_serializing_if = "Option::is_none")]`), or
/// every stored run would get a new id.
#[derive(Default, Serialize, Deserialize)]
pub(super) struct KindColumns {
    gap: Option<f64>,
    n: Option<usize>,
    node: Option<usize>,
    wall_distance: Option<f64>,
    #[serde(default)]
    relax: Option<RelaxSpec>,
    lattice: Option<LatticeSpec>,
    #[serde(default)]
    wave: Option<WaveSpec>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    packing: Option<PackingSpec>,
}

impl From<KindSpec> for KindColumns {
    fn from(kind: KindSpec) -> KindColumns {
        match kind {
            KindSpec::Pair(PairRun { gap }) => KindColumns { gap, ..KindColumns::default() },
            KindSpec::Chain(ChainRun { n, node, wall_distance, relax, wave }) => KindColumns {
                n: Some(n),
                node: Some(node),
                wall_distance: Some(wall_distance),
                relax,
                wave,
                ..KindColumns::default()
            },
            KindSpec::Lattice(LatticeRun { lattice, relax, wave }) => {
                KindColumns { lattice: Some(lattice), relax, wave, ..KindColumns::default() }
            }
            KindSpec::Packing(PackingRun { packing, relax }) => {
                KindColumns { packing: Some(packing), relax: Some(relax), ..KindColumns::default() }
            }
        }
    }
}

impl KindColumns {
    /// The kind `kind` with its fields, refusing a field another kind has or a missing one.
    pub(super) fn into_kind(self, kind: SceneKind) -> Result<KindSpec, String> {
        let KindColumns { gap, n, node, wall_distance, relax, lattice, wave, packing } = self;
        let refuse = |fields: &[(bool, &str)]| match fields.iter().find(|(present, _)| *present) {
            Some((_, field)) => Err(format!("a {} run has no `{field}`, yet it is set", kind.name())),
            None => Ok(()),
        };
        let needed = |field: &str| format!("a {} run needs `{field}`, yet it is null", kind.name());
        Ok(match kind {
            SceneKind::Pair => {
                refuse(&[
                    (n.is_some(), "n"),
                    (node.is_some(), "node"),
                    (wall_distance.is_some(), "wall_distance"),
                    (relax.is_some(), "relax"),
                    (lattice.is_some(), "lattice"),
                    (wave.is_some(), "wave"),
                    (packing.is_some(), "packing"),
                ])?;
                KindSpec::Pair(PairRun { gap })
            }
            SceneKind::Chain => {
                refuse(&[(gap.is_some(), "gap"), (lattice.is_some(), "lattice"), (packing.is_some(), "packing")])?;
                KindSpec::Chain(ChainRun {
                    n: n.ok_or_else(|| needed("n"))?,
                    node: node.ok_or_else(|| needed("node"))?,
                    wall_distance: wall_distance.ok_or_else(|| needed("wall_distance"))?,
                    relax,
                    wave,
                })
            }
            SceneKind::Lattice => {
                refuse(&[
                    (gap.is_some(), "gap"),
                    (n.is_some(), "n"),
                    (node.is_some(), "node"),
                    (wall_distance.is_some(), "wall_distance"),
                    (packing.is_some(), "packing"),
                ])?;
                KindSpec::Lattice(LatticeRun { lattice: lattice.ok_or_else(|| needed("lattice"))?, relax, wave })
            }
            SceneKind::Packing => {
                refuse(&[
                    (gap.is_some() || n.is_some() || node.is_some(), "gap, n or node"),
                    (wall_distance.is_some() || lattice.is_some() || wave.is_some(), "wall_distance, lattice or wave"),
                ])?;
                let packing = packing.ok_or_else(|| needed("packing"))?;
                KindSpec::Packing(PackingRun { packing, relax: relax.ok_or_else(|| needed("relax"))? })
            }
        })
    }
}
