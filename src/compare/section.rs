//! The comparison's section of one scene: the statuses of rows not compared, the medians of
//! every metric over the rows compared (`ok` on both sides, packings jammed on both) with whether the two sides differ beyond
//! the metric's noise, and the overlaid figures.

use serde::Serialize;

use super::join::{Joined, SceneJoin, SceneRows};
use super::plots::{PlotGroup, plot_groups};
use super::quantity::Class;
use super::restitution::{Restitution, restitution};
use super::stats::{Stats, stats};
use super::table::Side;
use super::words::{fixed, value};

#[derive(Serialize)]
pub(super) struct SceneSection {
    pub(super) name: String,
    keys: Vec<String>,
    only_a: Vec<String>,
    only_b: Vec<String>,
    rows: usize,
    rows_a: usize,
    rows_b: usize,
    ok: usize,
    /// Joined rows not compared, by (status A, status B), a packing's state with its status.
    pub(super) statuses: Vec<StatusCount>,
    metrics: Vec<MetricRow>,
    pub(super) plots: Vec<PlotGroup>,
    /// The numbers behind `metrics`, for the opening of the report.
    #[serde(skip)]
    pub(super) stats: Vec<Stats>,
    /// The restitution by the target each run was set for, for the opening.
    #[serde(skip)]
    pub(super) restitution: Restitution,
}

#[derive(Serialize)]
pub(super) struct StatusCount {
    pub(super) a: String,
    pub(super) b: String,
    pub(super) rows: usize,
}

#[derive(Serialize)]
struct MetricRow {
    metric: String,
    a: String,
    b: String,
    ratio: String,
    range: String,
    ratios: usize,
}

impl MetricRow {
    fn of(stats: &Stats) -> MetricRow {
        MetricRow {
            metric: stats.metric.clone(),
            a: value(stats.a),
            b: value(stats.b),
            ratio: fixed(stats.ratio),
            range: stats
                .range
                .map_or_else(String::new, |(lo, hi)| format!("{} … {}", fixed(Some(lo)), fixed(Some(hi)))),
            ratios: stats.ratios,
        }
    }
}

/// The report section of one scene: the statuses of rows not compared, the metrics table
/// (medians over the rows compared, [`SceneRows::comparable`], each run counted once) and the overlaid
/// figures (each side's `ok` runs) of the metrics that are neither costs nor inputs equal on
/// both sides.
pub(super) fn scene_section(a: &Side, b: &Side, joined: &Joined, scene: &SceneJoin) -> anyhow::Result<SceneSection> {
    let rows = joined.scene_rows(scene);
    let both: Vec<usize> = rows.rows.iter().copied().filter(|&r| rows.comparable(r)).collect();
    let stats: Vec<Stats> = joined.metrics.iter().filter_map(|name| stats(&rows, &both, name)).collect();
    let shown = |s: &Stats| match s.class {
        Class::Cost => false,
        Class::Setup => s.differs,
        Class::Deviation | Class::Result => true,
    };
    let names: Vec<&str> = stats.iter().filter(|s| shown(s)).map(|s| s.metric.as_str()).collect();
    let plots = plot_groups((a, b), &rows, scene, &names)?;
    Ok(SceneSection {
        name: scene.scene.clone(),
        keys: scene.keys.clone(),
        only_a: scene.only_a.clone(),
        only_b: scene.only_b.clone(),
        rows: rows.rows.len(),
        rows_a: scene.rows_a,
        rows_b: scene.rows_b,
        ok: both.len(),
        statuses: status_counts(&rows),
        metrics: stats.iter().map(MetricRow::of).collect(),
        plots,
        stats,
        restitution: restitution(&rows, &both),
    })
}

/// The rows not compared ([`SceneRows::comparable`]), counted by (state A, state B) in order
/// of appearance: the run's status, with a packing's state where it ended `ok`.
fn status_counts(rows: &SceneRows) -> Vec<StatusCount> {
    let state = |side: &str, r: usize| {
        let status = rows.cell(&format!("status_{side}"), r).unwrap_or_default();
        match rows.cell(&format!("packing_state_{side}"), r) {
            Some(packing) if rows.ok(side, r) => format!("{status}, {packing}"),
            _ => status,
        }
    };
    let mut statuses: Vec<StatusCount> = Vec::new();
    for &r in rows.rows.iter().filter(|&&r| !rows.comparable(r)) {
        let (sa, sb) = (state("a", r), state("b", r));
        match statuses.iter_mut().find(|c| c.a == sa && c.b == sb) {
            Some(count) => count.rows += 1,
            None => statuses.push(StatusCount { a: sa, b: sb, rows: 1 }),
        }
    }
    statuses
}
