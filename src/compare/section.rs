//! The comparison's section of one scene: the statuses of rows not `ok` on both sides, the
//! medians of every metric over the rows `ok` on both, and the overlaid figures.

use serde::Serialize;

use super::join::{Joined, SceneJoin, SceneRows};
use super::plots::{PlotGroup, plot_groups};
use super::table::Side;
use super::words::{fixed, value};

#[derive(Serialize)]
pub(super) struct SceneSection {
    name: String,
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

fn median(mut values: Vec<f64>) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(values[n / 2]),
        _ => Some(0.5 * (values[n / 2 - 1] + values[n / 2])),
    }
}

/// The report section of one scene: the statuses of rows not `ok` on both sides, the metrics
/// table (medians over the rows `ok` on both sides, each run counted once) and the overlaid
/// figures (each side's `ok` runs).
pub(super) fn scene_section(a: &Side, b: &Side, joined: &Joined, scene: &SceneJoin) -> anyhow::Result<SceneSection> {
    let rows = joined.scene_rows(scene);
    let both: Vec<usize> = rows.rows.iter().copied().filter(|&r| rows.ok("a", r) && rows.ok("b", r)).collect();
    let metrics: Vec<MetricRow> = joined.metrics.iter().filter_map(|name| metric_row(&rows, &both, name)).collect();
    let names: Vec<&str> = metrics.iter().map(|m| m.metric.as_str()).collect();
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
        metrics,
        plots,
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

/// The medians of metric `name` on each side and of their ratio over the rows `both` ended
/// `ok` on; `None` when neither side has a value there.
fn metric_row(rows: &SceneRows, both: &[usize], name: &str) -> Option<MetricRow> {
    let with_ratio: Vec<usize> =
        both.iter().copied().filter(|&r| rows.metric(name, "ratio").number(r).is_some()).collect();
    // A and B over the rows behind the ratios, so that the three agree; where there is no
    // ratio (a value of zero or missing on one side), over every row ok on both sides.
    let basis = if with_ratio.is_empty() { both } else { &with_ratio };
    let values = |side: &str| -> Vec<f64> {
        rows.once(side, basis).into_iter().filter_map(|r| rows.metric(name, side).number(r)).collect()
    };
    let (va, vb) = (values("a"), values("b"));
    if va.is_empty() && vb.is_empty() {
        return None;
    }
    let ratios: Vec<f64> = with_ratio.iter().filter_map(|&r| rows.metric(name, "ratio").number(r)).collect();
    let (lo, hi) = ratios.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    Some(MetricRow {
        metric: name.to_string(),
        a: value(median(va)),
        b: value(median(vb)),
        range: if ratios.len() > 1 { format!("{} … {}", fixed(Some(lo)), fixed(Some(hi))) } else { String::new() },
        ratios: ratios.len(),
        ratio: fixed(median(ratios)),
    })
}
