//! The comparison's figures: each metric of a scene against each parameter both campaigns vary
//! there, A's and B's `ok` runs overlaid.

use anyhow::Context as _;
use serde::Serialize;
use std::collections::BTreeSet;

use super::join::{SceneJoin, SceneRows, is_dotted};
use super::table::{Side, Values};
use crate::draw::chart::{Chart, Mark, Scale, Series, line_chart};
use crate::output::escape_for_terminal;

/// The figures of one scene against one parameter.
#[derive(Serialize)]
pub(super) struct PlotGroup {
    parameter: String,
    pub(super) plots: Vec<PlotLink>,
}

#[derive(Serialize)]
pub(super) struct PlotLink {
    metric: String,
    pub(super) file: String,
    #[serde(skip)]
    pub(super) image: crate::draw::chart::Image,
}

/// The figures of `scene`: per key parameter with two values or more in its rows, one figure
/// per metric of `metrics` that has something to show against it.
pub(super) fn plot_groups(
    sides: (&Side, &Side),
    rows: &SceneRows,
    scene: &SceneJoin,
    metrics: &[&str],
) -> anyhow::Result<Vec<PlotGroup>> {
    let mut plots = Vec::new();
    for parameter in &scene.keys {
        // A top-level key is a metric column too; being a key, its two sides agree.
        let column = if is_dotted(parameter) { parameter.clone() } else { format!("{parameter}_a") };
        let Some(Values::Numbers(x)) = rows.column(&column) else { continue };
        if rows.rows.iter().filter_map(|&r| x[r]).map(f64::to_bits).collect::<BTreeSet<_>>().len() < 2 {
            continue;
        }
        let mut group = PlotGroup { parameter: parameter.clone(), plots: Vec::new() };
        for metric in metrics {
            group.plots.extend(plot(sides, rows, (&scene.scene, parameter), x, metric)?);
        }
        if !group.plots.is_empty() {
            plots.push(group);
        }
    }
    Ok(plots)
}

/// `metric` against `parameter` (its value `x[r]` in row `r`) in `scene`, A and B overlaid;
/// `None` when the figure would say no more than the table.
fn plot(
    (a, b): (&Side, &Side),
    rows: &SceneRows,
    (scene, parameter): (&str, &str),
    x: &[Option<f64>],
    metric: &str,
) -> anyhow::Result<Option<PlotLink>> {
    let points = |side: &str| -> Vec<(f64, f64)> {
        let own: Vec<usize> = rows.rows.iter().copied().filter(|&r| rows.ok(side, r)).collect();
        let mut points: Vec<(f64, f64)> = rows
            .once(side, &own)
            .into_iter()
            .filter_map(|r| Some((x[r]?, rows.metric(metric, side).number(r)?)))
            .collect();
        points.sort_by(|p, q| p.0.total_cmp(&q.0));
        points
    };
    let (pa, pb) = (points("a"), points("b"));
    let all: Vec<(f64, f64)> = pa.iter().chain(&pb).copied().collect();
    let count_distinct =
        |get: fn(&(f64, f64)) -> f64| all.iter().map(|p| get(p).to_bits()).collect::<BTreeSet<_>>().len();
    // One x or one y value in all, or the parameter itself (`dt_per_tc` against
    // `time.dt_per_tc`): the table above says all there is.
    if count_distinct(|p| p.0) < 2 || count_distinct(|p| p.1) < 2 || all.iter().all(|p| p.0 == p.1) {
        return Ok(None);
    }
    let chart = Chart {
        title: format!("{scene}: {metric} against {parameter}"),
        x_label: parameter.to_string(),
        y_label: metric.to_string(),
        scale: scale(&all),
    };
    let series = [series(format!("A: {}", a.name), pa), series(format!("B: {}", b.name), pb)];
    let image = line_chart(&chart, &series).with_context(|| {
        let [metric, parameter, scene] = [metric, parameter, scene].map(escape_for_terminal);
        format!("cannot draw {metric} against {parameter} for scene {scene}")
    })?;
    let file =
        image.file_name(&format!("plots/{}-{}-vs-{}.svg", file_part(scene), file_part(metric), file_part(parameter)));
    Ok(Some(PlotLink { metric: metric.to_string(), file, image }))
}

/// A side's points as one series: a line through one run per parameter value, markers where
/// other grid values put several runs at one value.
fn series(label: String, points: Vec<(f64, f64)>) -> Series {
    let several = points.windows(2).any(|w| w[0].0 == w[1].0);
    Series { label, points, mark: if several { Mark::Markers } else { Mark::Line } }
}

/// Logarithmic along each axis whose values are positive and span more than a decade.
fn scale(points: &[(f64, f64)]) -> Scale {
    let spans_decades = |get: fn(&(f64, f64)) -> f64| {
        let (lo, hi) = crate::measure::extremes(points.iter().map(get));
        lo > 0.0 && hi > 10.0 * lo
    };
    match (spans_decades(|p| p.0), spans_decades(|p| p.1)) {
        (true, true) => Scale::LogLog,
        (true, false) => Scale::LogX,
        (false, true) => Scale::LogY,
        (false, false) => Scale::Linear,
    }
}

/// A name made safe for a file name.
fn file_part(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || "-_.".contains(c) { c } else { '_' }).collect()
}

impl PlotGroup {
    /// The parameter this group's figures are drawn against.
    pub(super) fn parameter(&self) -> &str {
        &self.parameter
    }
}

impl PlotLink {
    /// The quantity this figure shows.
    pub(super) fn metric(&self) -> &str {
        &self.metric
    }
}
