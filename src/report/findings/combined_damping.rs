//! Item 18's last question: how the relaxation changes when background damping is added to the
//! bond damping. Each run with both is set against the bond damping alone (the same γ) and the
//! background damping alone (the same γ_g, the energy criterion), on the same lattice.

use super::finding::{percent, sig};
use crate::report::figure::background_gamma;
use crate::report::words::number;
use crate::runner::RunRecord;
use crate::theory::critical_damping;

/// A change of the dissipation time by at most this share, or by two of the checks (one t_c
/// apart) that time it, whichever is larger, is no change: the load's ramp and the envelope's
/// phase move the crossing of the threshold by about a check (1.4 % of the fastest relaxation
/// of the coursework's sweep, 0.0032 s at t_c = 4.4e-5 s).
const SAME_TIME: f64 = 0.02;

/// One run with both dampings, and the dissipation times (s) of it and of its two references.
struct Added {
    background: f64,
    both: f64,
    /// The share of `both` that counts as no change ([`SAME_TIME`]).
    same: f64,
    background_alone: Option<f64>,
    bond_alone: Option<f64>,
}

/// The sentence on background damping added to bond damping, if the campaign has such runs:
/// those of the first one's block and bond damping, against γ_crit = 2√(k_min m) of that block.
pub(super) fn sentence(both: &[&RunRecord], bond: &[&RunRecord], background: &[&RunRecord]) -> Option<String> {
    let first = both.first()?;
    let swept: Vec<&RunRecord> = both
        .iter()
        .copied()
        .filter(|r| r.spec.gamma == first.spec.gamma && r.spec.lattice() == first.spec.lattice())
        .collect();
    let added = matched(&swept, bond, background);
    let critical =
        first.metrics.lattice.stiffness_min.filter(|k| *k > 0.0).map(|k| critical_damping(k, first.spec.mass));
    let times = added.iter().map(|a| sig(a.both)).collect::<Vec<_>>().join(", ");
    let against_bond = bond_words(&added);
    let against_background = background_words(&added, critical);
    Some(format!(
        "Background damping added to the bond damping (γ = {} N s/m{}): γ_g = {} N s/m give {times} \
         s{against_bond}{against_background}.",
        sig(first.spec.gamma),
        first.spec.restitution_target.map_or_else(String::new, |r| format!(", r = {}", number(r))),
        added.iter().map(|a| sig(a.background)).collect::<Vec<_>>().join(", "),
    ))
}

/// The runs with both dampings by rising γ_g, each with the bond-only run of its γ and the
/// background-only run of its γ_g on the same lattice, where the campaign has them.
fn matched(both: &[&RunRecord], bond: &[&RunRecord], background: &[&RunRecord]) -> Vec<Added> {
    // The same network, springs, masses, supports and load: all but the damping.
    let same_block = |a: &RunRecord, b: &RunRecord| {
        a.spec.lattice() == b.spec.lattice()
            && (a.spec.mass, a.spec.k, a.spec.law) == (b.spec.mass, b.spec.k, b.spec.law)
    };
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
    let time_of = |runs: &[&RunRecord], keep: &dyn Fn(&RunRecord) -> bool| {
        runs.iter().find(|r| keep(r)).and_then(|r| r.metrics.dissipation_time)
    };
    let mut added: Vec<Added> = both
        .iter()
        .filter_map(|r| {
            Some(Added {
                background: background_gamma(r),
                both: r.metrics.dissipation_time?,
                same: SAME_TIME.max(2.0 * r.spec.t_c / r.metrics.dissipation_time?),
                background_alone: time_of(background, &|b| {
                    same_block(r, b) && close(background_gamma(b), background_gamma(r))
                }),
                bond_alone: time_of(bond, &|b| same_block(r, b) && close(b.spec.gamma, r.spec.gamma)),
            })
        })
        .collect();
    added.sort_by(|a, b| a.background.total_cmp(&b.background));
    added
}

/// "; against the bond damping alone (0.159 s) 6.5 to 49 times faster".
fn bond_words(added: &[Added]) -> String {
    let speedups: Vec<(f64, f64)> =
        added.iter().filter_map(|a| Some((a.bond_alone?, a.bond_alone? / a.both))).collect();
    let Some(&(alone, _)) = speedups.first() else {
        return String::new();
    };
    let (low, high) = crate::measure::extremes(speedups.iter().map(|s| s.1));
    let factor = if low == high { sig(low) } else { format!("{} to {}", sig(low), sig(high)) };
    let than = if low > 1.0 { "faster than" } else { "as fast as" };
    format!(", {factor} times {than} the bond damping alone ({} s)", sig(alone))
}

/// How the bond damping changes the background damping's time at each γ_g, and what that shows
/// against γ_crit where it is known: below it the slowest mode is underdamped and the bond
/// dashpot adds to its damping; from γ_crit up the background damping alone sets the pace.
fn background_words(added: &[Added], critical: Option<f64>) -> String {
    // (γ_g, the change against the background alone, the change that counts as none).
    let changes: Vec<(f64, f64, f64)> =
        added.iter().filter_map(|a| Some((a.background, a.both / a.background_alone? - 1.0, a.same))).collect();
    if changes.is_empty() {
        return String::new();
    }
    let listed = changes.iter().map(|c| percent(c.1)).collect::<Vec<_>>().join(", ");
    let pattern = critical.and_then(|critical| {
        let below: Vec<_> = changes.iter().filter(|c| c.0 < critical).collect();
        let above: Vec<_> = changes.iter().filter(|c| c.0 >= critical).collect();
        let helps_below = below.iter().all(|c| c.1 < -c.2);
        let same_above = above.iter().all(|c| c.1.abs() <= c.2);
        match (below.is_empty(), above.is_empty()) {
            (false, false) if helps_below && same_above => Some(format!(
                ": below γ_crit = {} N s/m the dashpot adds to the underdamped slowest mode's damping; from γ_crit up \
                 (within {} % or two checks) the background sets the pace",
                sig(critical),
                number(100.0 * SAME_TIME)
            )),
            (false, true) if helps_below => Some(format!(
                ": all below γ_crit = {} N s/m, where the dashpot adds to the underdamped slowest mode's damping",
                sig(critical)
            )),
            (true, false) if same_above => Some(format!(
                ": from γ_crit = {} N s/m up (within {} % or two checks) the background sets the pace",
                sig(critical),
                number(100.0 * SAME_TIME)
            )),
            _ => None,
        }
    });
    format!(", and {listed} against the background alone{}", pattern.unwrap_or_default())
}
