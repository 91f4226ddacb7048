//! The comparison's section of one scene: the statuses of rows not `ok` on both sides, the
//! medians of every metric over the rows `ok` on both with whether the two sides differ beyond
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
    /// Joined rows that are not `ok` on both sides, by (status A, status B).
    statuses: Vec<StatusCount>,
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
struct StatusCount {
    a: String,
    b: String,
    rows: usize,
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

/// The report section of one scene: the statuses of rows not `ok` on both sides, the metrics
/// table (medians over the rows `ok` on both sides, each run counted once) and the overlaid
/// figures (each side's `ok` runs) of the metrics that are neither costs nor inputs equal on
/// both sides.
pub(super) fn scene_section(a: &Side, b: &Side, joined: &Joined, scene: &SceneJoin) -> anyhow::Result<SceneSection> {
    let rows = joined.scene_rows(scene);
    let both: Vec<usize> = rows.rows.iter().copied().filter(|&r| rows.ok("a", r) && rows.ok("b", r)).collect();
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

/// The rows not `ok` on both sides, counted by (status A, status B) in order of appearance.
fn status_counts(rows: &SceneRows) -> Vec<StatusCount> {
    let mut statuses: Vec<StatusCount> = Vec::new();
    for &r in rows.rows.iter().filter(|&&r| !(rows.ok("a", r) && rows.ok("b", r))) {
        let (sa, sb) = (rows.cell("status_a", r).unwrap_or_default(), rows.cell("status_b", r).unwrap_or_default());
        match statuses.iter_mut().find(|c| c.a == sa && c.b == sb) {
            Some(count) => count.rows += 1,
            None => statuses.push(StatusCount { a: sa, b: sb, rows: 1 }),
        }
    }
    statuses
}
