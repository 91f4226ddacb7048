//! The static answers of the loaded networks solved so far, shared by the runs of a campaign:
//! runs that differ only in what the static answer does not depend on (the relaxation method,
//! its tolerance, the time step, damping, what is recorded) solve it once. At 10⁶ nodes the
//! answer is two sparse factorisations and Newton's iteration (~24 s); `campaigns/million.yaml`'s
//! static run and FIRE run, started side by side, solved it twice, sharing one memory bus.
//! Pure: no I/O.

use super::kept::Kept;
use super::{Analyses, StaticSolution};

/// What the static solve of one loaded network found ([`super::Solver::solve_static`]).
#[derive(Clone, Debug, PartialEq)]
pub struct StaticAnswer {
    /// The linear answer (springs at their rest geometry).
    pub linear: StaticSolution,
    /// Newton's answer of the full non-linear problem; `None` when the linear answer is a
    /// mechanism or the iteration did not converge.
    pub nonlinear: Option<StaticSolution>,
    /// ‖R‖/‖f‖ where Newton's iteration stopped, as [`super::Convergence::residual`].
    pub residual: f64,
    /// Steps down the potential energy on the way, as [`super::Convergence::descents`].
    pub descents: usize,
}

impl StaticAnswer {
    /// Whether a deadline cut the solve short.
    fn past_deadline(&self) -> bool {
        [Some(&self.linear), self.nonlinear.as_ref()].into_iter().flatten().any(|s| *s == StaticSolution::PastDeadline)
    }
}

/// Answers kept: at 10⁶ nodes one holds ~64 MB (the linear and the non-linear displacements).
const KEPT_ANSWERS: usize = 2;

/// The loaded networks solved so far, by [`super::Truss::answer_key`].
#[derive(Default)]
pub struct Answers {
    kept: Kept<StaticAnswer, KEPT_ANSWERS>,
}

impl Answers {
    /// How many answers are kept.
    pub fn len(&self) -> usize {
        self.kept.len()
    }

    /// Whether no answer is kept.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The answer of the problem hashed as `key`, solved by `solve` on a miss and waited for
    /// while another run solves it. An answer a deadline cut short is not kept: the next run
    /// solves again, and a run that waited for it solves on its own (stopping at its own
    /// deadline, which may lie later). The run whose own solve was cut keeps its cut answer:
    /// solving again, past its deadline, would only repeat the linear factorisation.
    pub fn get(&self, key: [u8; 32], mut solve: impl FnMut() -> StaticAnswer) -> StaticAnswer {
        let mut solved_here = false;
        let answer = self.kept.get(key, || {
            solved_here = true;
            solve()
        });
        if !answer.past_deadline() {
            return (*answer).clone();
        }
        self.kept.forget(key);
        if solved_here { (*answer).clone() } else { solve() }
    }
}

/// What the runs of a campaign share of their static solves: the networks' symbolic analyses
/// and the loaded networks' answers.
#[derive(Default)]
pub struct Shared {
    /// The symbolic analyses, by network structure.
    pub analyses: Analyses,
    /// The answers, by network, load and force law.
    pub answers: Answers,
}

impl std::fmt::Debug for Shared {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Shared({:?}, {} answers)", self.analyses, self.answers.len())
    }
}
