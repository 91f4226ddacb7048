//! A run's scene kind with the fields only that kind has (a pair's gap, a chain's particles
//! and walls, a lattice), and the questions [`RunSpec`] answers from them.

use super::raw::SceneKind;
use super::run_spec::{LatticeSpec, RelaxSpec, RunSpec, WaveSpec};

/// The kind of a run's scene, carrying that kind's own fields.
#[derive(Clone, Debug, PartialEq)]
pub enum KindSpec {
    /// Two particles.
    Pair(PairRun),
    /// N particles between two walls.
    Chain(ChainRun),
    /// A square lattice.
    Lattice(LatticeRun),
}

/// What only a pair has.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairRun {
    /// Initial gap between the surfaces (m), for a pair with a contact spring.
    pub gap: Option<f64>,
}

/// What only a chain has.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainRun {
    /// Moving particles.
    pub n: usize,
    /// Excited particle, 1..n.
    pub node: usize,
    /// Distance between the walls (m).
    pub wall_distance: f64,
    /// A relaxing chain: when the relaxation stops, and the tangent step.
    pub relax: Option<RelaxSpec>,
    /// The wave timed from the excited particle to a receiver, if asked for.
    pub wave: Option<WaveSpec>,
}

/// What only a lattice has.
#[derive(Clone, Debug, PartialEq)]
pub struct LatticeRun {
    /// The lattice, its load and supports.
    pub lattice: LatticeSpec,
    /// A loaded lattice: when the relaxation stops, and the tangent step.
    pub relax: Option<RelaxSpec>,
    /// An impulse lattice: the wave timed from the kicked node to the bottom row, if asked for.
    pub wave: Option<WaveSpec>,
}

impl KindSpec {
    /// The kind's tag.
    pub fn kind(&self) -> SceneKind {
        match self {
            KindSpec::Pair(_) => SceneKind::Pair,
            KindSpec::Chain(_) => SceneKind::Chain,
            KindSpec::Lattice(_) => SceneKind::Lattice,
        }
    }

    /// The same kind without its relaxation and timed wave (what a network's modes do not
    /// depend on).
    pub fn without_relax_and_wave(&self) -> KindSpec {
        match self {
            KindSpec::Pair(pair) => KindSpec::Pair(*pair),
            KindSpec::Chain(chain) => KindSpec::Chain(ChainRun { relax: None, wave: None, ..chain.clone() }),
            KindSpec::Lattice(lattice) => KindSpec::Lattice(LatticeRun { relax: None, wave: None, ..lattice.clone() }),
        }
    }
}

impl RunSpec {
    /// The scene kind.
    pub fn kind(&self) -> SceneKind {
        self.scene_kind.kind()
    }

    /// A chain's fields; `None` for other kinds.
    pub fn chain(&self) -> Option<&ChainRun> {
        match &self.scene_kind {
            KindSpec::Chain(chain) => Some(chain),
            _ => None,
        }
    }

    /// A lattice scene's lattice; `None` for other kinds.
    pub fn lattice(&self) -> Option<&LatticeSpec> {
        match &self.scene_kind {
            KindSpec::Lattice(run) => Some(&run.lattice),
            _ => None,
        }
    }

    /// When the relaxation of a loaded lattice or a relaxing chain stops; `None` otherwise.
    pub fn relax(&self) -> Option<RelaxSpec> {
        match &self.scene_kind {
            KindSpec::Pair(_) => None,
            KindSpec::Chain(chain) => chain.relax,
            KindSpec::Lattice(run) => run.relax,
        }
    }

    /// The timed wave of a chain or an impulse lattice, if asked for.
    pub fn wave(&self) -> Option<&WaveSpec> {
        match &self.scene_kind {
            KindSpec::Pair(_) => None,
            KindSpec::Chain(chain) => chain.wave.as_ref(),
            KindSpec::Lattice(run) => run.wave.as_ref(),
        }
    }
}
