//! A scene's restitution, grouped by the target each run's dashpot was set for. A median over
//! runs set for different targets (r = 1 undamped, r = 0.5 damped) is no run's restitution and
//! meets no target, so the opening compares the two sides, and judges each side against its
//! target, one target at a time.

use std::f64::consts::PI;

use super::join::SceneRows;
use super::stats::{Stats, stats};

/// The restitution target of a row's run on each side (A's, B's); `None` where the run has
/// none (overdamped, or no damping ratio recorded) and, in one side's grouping, for the other.
pub(super) type Targets = (Option<f64>, Option<f64>);

/// The restitution over the rows that share their targets and their other grid values.
pub(super) struct ByTarget {
    pub(super) target: Targets,
    /// The rows' grid values besides the damping ("material.law = hertz"): a median over two
    /// laws set for one target is neither law's restitution.
    pub(super) grid: Vec<String>,
    /// Every run of the group has linear springs (β = 1), on side A and on side B: the
    /// formula that set γ is then exact, and a miss is the integration's.
    pub(super) linear: (bool, bool),
    pub(super) stats: Stats,
}

/// A scene's restitution by target: by the pair of targets, to set A against B; and by each
/// side's own target alone, to judge that side against it (one run of a side may meet runs of
/// the other set for different targets).
#[derive(Default)]
pub(super) struct Restitution {
    pub(super) both: Vec<ByTarget>,
    pub(super) a: Vec<ByTarget>,
    pub(super) b: Vec<ByTarget>,
}

/// Two targets closer than this (relative) are one: the runs of one grid value compute ζ from
/// the same inputs and differ in the last bits only (5e-16 between a linear and a Hertz run),
/// while two grid values differ by far more.
const SAME_TARGET: f64 = 1e-9;

/// The restitution the linear two-body mode has at damping ratio ζ, r* = exp(−πζ/√(1 − ζ²)):
/// the formula that set γ from `damping.restitution`, whatever the force law; none when the
/// mode is overdamped (ζ ≥ 1) and does not bounce.
fn target(zeta: f64) -> Option<f64> {
    (zeta < 1.0).then(|| (-PI * zeta / (1.0 - zeta * zeta).sqrt()).exp())
}

/// The target of the run of `side` (`a` or `b`) in row `r`, from the damping ratio it was given
/// (`mode_damping_ratio`).
fn row_target(rows: &SceneRows, side: &str, r: usize) -> Option<f64> {
    rows.column(&format!("mode_damping_ratio_{side}")).and_then(|c| c.number(r)).and_then(target)
}

fn same(x: Option<f64>, y: Option<f64>) -> bool {
    match (x, y) {
        (Some(x), Some(y)) => x == y || (x / y - 1.0).abs() <= SAME_TARGET,
        (x, y) => x.is_none() && y.is_none(),
    }
}

/// The restitution's [`stats`] over each group of the rows `both` that share `key`, in order of
/// first appearance.
fn grouped(rows: &SceneRows, both: &[usize], key: impl Fn(usize) -> Targets) -> Vec<ByTarget> {
    let mut groups: Vec<(Targets, Vec<String>, Vec<usize>)> = Vec::new();
    for &r in both {
        let (target, grid) = (key(r), rows.grid_values(r, "damping."));
        match groups.iter_mut().find(|(t, g, _)| same(t.0, target.0) && same(t.1, target.1) && *g == grid) {
            Some((_, _, members)) => members.push(r),
            None => groups.push((target, grid, vec![r])),
        }
    }
    let linear = |side: &str, members: &[usize]| {
        members.iter().all(|&r| rows.column(&format!("beta_{side}")).and_then(|c| c.number(r)) == Some(1.0))
    };
    groups
        .into_iter()
        .filter_map(|(target, grid, members)| {
            let linear = (linear("a", &members), linear("b", &members));
            Some(ByTarget { target, grid, linear, stats: stats(rows, &members, "restitution")? })
        })
        .collect()
}

/// The restitution of the rows `both` (ok on both sides) by target; empty where the scene
/// measures none, or the two tables do not both have it.
pub(super) fn restitution(rows: &SceneRows, both: &[usize]) -> Restitution {
    if rows.column("restitution_ratio").is_none() {
        return Restitution::default();
    }
    let side = |side: &'static str| move |r| row_target(rows, side, r);
    let (a, b) = (side("a"), side("b"));
    Restitution {
        both: grouped(rows, both, |r| (a(r), b(r))),
        a: grouped(rows, both, |r| (a(r), None)),
        b: grouped(rows, both, |r| (None, b(r))),
    }
}
