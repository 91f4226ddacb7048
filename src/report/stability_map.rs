//! Stability maps: runs swept across their integrator's limit (dt·ω_max), the limit predicted
//! before the run against the bracket the runs observed, as a table and one figure per integrator.

use serde::Serialize;

use super::figure::{Figure, FigureKind, Part};
use super::words::{number, optional};
use crate::draw::chart::{Chart, Mark, Scale, Series, line_chart};
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::spec::SceneKind;

/// The stability part of `scene`: its maps and its tables, when it studies stability (none
/// otherwise).
pub fn part(records: &[RunRecord], scene: &str) -> anyhow::Result<Part<StabilityRows>> {
    if !is_stability_scene(records, scene) {
        return Ok(Part { figures: Vec::new(), rows: StabilityRows::default() });
    }
    Ok(Part { figures: stability_figures(records, scene)?, rows: stability_rows(records, scene) })
}

/// True when `scene` studies stability: some run sets dt by dt·ω_max or may blow up.
fn is_stability_scene(records: &[RunRecord], scene: &str) -> bool {
    records.iter().any(|r| r.spec.scene == scene && (r.spec.allow_unstable || r.spec.dt_omega_max.is_some()))
}

/// True when `scene` sweeps dt·ω_max, so its runs map the stability limit.
fn sweeps_the_limit(records: &[RunRecord], scene: &str) -> bool {
    records.iter().any(|r| r.spec.scene == scene && r.spec.dt_omega_max.is_some())
}

/// The y coordinate of a run on the stability map: k_d/k for lattices, else the damping
/// ratio of the fastest mode; zero is drawn at [`MAP_FLOOR`] on the logarithmic axis.
fn map_y(r: &RunRecord) -> f64 {
    let y = match r.spec.lattice() {
        Some(l) => l.k_diag / r.spec.k,
        None => r.metrics.mode_damping_ratio.unwrap_or(0.0),
    };
    y.max(MAP_FLOOR)
}

const MAP_FLOOR: f64 = 1e-3;

/// A run blew up (as opposed to staying bounded, relaxed or not).
fn blew_up(r: &RunRecord) -> bool {
    r.status == RunStatus::Unstable
}

/// One run of a stability scene: what was predicted and what happened.
#[derive(Serialize)]
pub struct StabilityRow {
    run_id: String,
    label: String,
    integrator: &'static str,
    dt_omega_max: String,
    limit: String,
    damping_ratio: String,
    predicted: &'static str,
    outcome: RunStatus,
    message: String,
}

/// Predicted against observed limit for one integrator and one map row (same y).
#[derive(Serialize)]
pub struct LimitRow {
    integrator: &'static str,
    y: String,
    predicted: String,
    last_bounded: String,
    first_blown: String,
    agreement: String,
}

/// The two tables of a stability scene: what each run did, and where the runs put each limit.
#[derive(Default, Serialize)]
pub struct StabilityRows {
    /// Each run's predicted fate beside its outcome.
    pub stability_rows: Vec<StabilityRow>,
    /// Predicted against observed limit, per integrator and map row (empty unless the scene
    /// sweeps dt·ω_max).
    pub limit_rows: Vec<LimitRow>,
}

/// The rows of a stability scene, and the predicted-against-observed summary.
fn stability_rows(records: &[RunRecord], scene: &str) -> StabilityRows {
    let mine: Vec<&RunRecord> = records.iter().filter(|r| r.spec.scene == scene).collect();
    let stability_rows = mine.iter().map(|r| stability_row(r)).collect();
    if !sweeps_the_limit(records, scene) {
        return StabilityRows { stability_rows, limit_rows: Vec::new() };
    }
    let mut keys: Vec<(&'static str, String)> = Vec::new();
    for r in &mine {
        let key = (r.spec.integrator.name(), number(map_y(r)));
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    let limit_rows = keys.into_iter().filter_map(|(integrator, y)| limit_row(&mine, integrator, y)).collect();
    StabilityRows { stability_rows, limit_rows }
}

/// One run of a stability scene: its predicted fate beside its outcome.
fn stability_row(r: &RunRecord) -> StabilityRow {
    let m = &r.metrics;
    let predicted = match (m.dt_omega_max, m.stability_limit) {
        (Some(x), Some(limit)) if x > limit => "blows up",
        (Some(_), Some(_)) => "bounded",
        _ => "–",
    };
    StabilityRow {
        run_id: r.run_id.clone(),
        label: r.spec.varied_in_words(|_| true),
        integrator: r.spec.integrator.name(),
        dt_omega_max: optional(m.dt_omega_max),
        limit: optional(m.stability_limit),
        damping_ratio: optional(m.mode_damping_ratio),
        predicted,
        outcome: r.status,
        message: if r.message.is_empty() { "–".into() } else { r.message.clone() },
    }
}

/// The limit row of `integrator` at map height `y` (as [`number`] writes it) over the runs
/// `mine`; `None` unless its runs bracket the limit.
fn limit_row(mine: &[&RunRecord], integrator: &'static str, y: String) -> Option<LimitRow> {
    let row: Vec<&&RunRecord> =
        mine.iter().filter(|r| r.spec.integrator.name() == integrator && number(map_y(r)) == y).collect();
    let at = |r: &&&RunRecord| r.metrics.dt_omega_max.unwrap_or(f64::NAN);
    let last_bounded = row.iter().filter(|r| !blew_up(r)).map(at).fold(f64::NAN, f64::max);
    let first_blown = row.iter().filter(|r| blew_up(r)).map(at).fold(f64::NAN, f64::min);
    let predicted = row.iter().filter_map(|r| r.metrics.stability_limit).fold(f64::NAN, f64::min);
    // Only a row that brackets the limit (bounded below, blown up above) measures it.
    if last_bounded.is_nan() || first_blown.is_nan() {
        return None;
    }
    let agreement = if integrator == crate::sim::IntegratorKind::Gear.name() {
        // Gear's limit bounds its growth over the run (≤ RUN_GROWTH), not where it
        // blows up (energy × 1000): it holds when nothing at or below it blew up.
        if predicted < first_blown {
            format!("a bound: first blow-up {} above it", super::words::percent((first_blown - predicted) / predicted))
        } else {
            "bound violated: blew up at or below it".to_string()
        }
    } else if (last_bounded..=first_blown).contains(&predicted) {
        "inside the observed bracket".to_string()
    } else {
        let nearest = if predicted < last_bounded { last_bounded } else { first_blown };
        format!("outside by {}", super::words::percent((predicted - nearest) / nearest))
    };
    Some(LimitRow {
        integrator,
        y,
        predicted: number(predicted),
        last_bounded: number(last_bounded),
        first_blown: number(first_blown),
        agreement,
    })
}

/// One stability map per integrator of a stability scene: runs that stayed bounded and runs
/// that blew up at their dt·ω_max and map y, with the predicted limit drawn through them.
fn stability_figures(records: &[RunRecord], scene: &str) -> anyhow::Result<Vec<Figure>> {
    if !sweeps_the_limit(records, scene) {
        return Ok(Vec::new());
    }
    let mine: Vec<&RunRecord> =
        records.iter().filter(|r| r.spec.scene == scene && r.metrics.dt_omega_max.is_some()).collect();
    let Some(first) = mine.first() else { return Ok(Vec::new()) };
    let lattice = first.spec.kind() == SceneKind::Lattice;
    let mut integrators: Vec<crate::sim::IntegratorKind> = Vec::new();
    for r in &mine {
        if !integrators.contains(&r.spec.integrator) {
            integrators.push(r.spec.integrator);
        }
    }
    let mut figures = Vec::new();
    for integrator in integrators {
        let runs: Vec<&&RunRecord> = mine.iter().filter(|r| r.spec.integrator == integrator).collect();
        let points = |blown: bool| -> Vec<(f64, f64)> {
            runs.iter()
                .filter(|r| blew_up(r) == blown)
                .map(|r| (r.metrics.dt_omega_max.unwrap_or(0.0), map_y(r)))
                .collect()
        };
        let mut limit: Vec<(f64, f64)> =
            runs.iter().filter_map(|r| r.metrics.stability_limit.map(|l| (l, map_y(r)))).collect();
        limit.sort_by(|a, b| a.1.total_cmp(&b.1));
        limit.dedup_by(|a, b| a.1 == b.1);
        if let [(x, y)] = limit[..] {
            // One row only: draw the limit as a short vertical line through it.
            limit = vec![(x, y / 2.0), (x, y * 2.0)];
        }
        // Palette order: red for the runs that blew up, green for those that did not.
        let series = vec![
            Series { label: "blew up (status unstable)".into(), points: points(true), mark: Mark::Markers },
            Series { label: "bounded".into(), points: points(false), mark: Mark::Markers },
            Series { label: format!("predicted limit of {}", integrator.name()), points: limit, mark: Mark::Line },
        ];
        let y_label =
            if lattice { "k_d / k (0 drawn at 1e-3)" } else { "damping ratio ζ of the fastest mode (0 at 1e-3)" };
        let chart = Chart {
            title: format!("{scene}: stability of {}", integrator.name()),
            x_label: "dt · ω_max".into(),
            y_label: y_label.into(),
            scale: Scale::LogY,
        };
        figures.push(Figure {
            scene: scene.into(),
            kind: FigureKind::Stability,
            file: format!("plots/{scene}-stability-{}.svg", integrator.name()),
            caption: format!(
                "Stability map of {scene} with {}: each run at its dt·ω_max (ω_max estimated before the run), \
                 bounded or blown up, and the limit predicted from the integrator's test oscillator at the fastest \
                 mode's damping ratio.",
                integrator.name()
            ),
            image: line_chart(&chart, &series)?,
        });
    }
    Ok(figures)
}
