//! Work against precision: per integrator, the error of a dt sweep, its order of convergence
//! and the dt (and loop time) that reaches the campaign's target error.

use serde::Serialize;

use super::figure::{Figure, FigureKind, Part, groups, representative};
use super::words::{number, optional};
use crate::draw::chart::{Chart, Mark, Scale, Series, line_chart};
use crate::measure::{Recommendation, convergence_order, recommended_dt};
use crate::runner::RunRecord;

/// One dt sweep of one integrator (a group of runs differing only in dt).
#[derive(Serialize)]
pub struct PrecisionRow {
    group: String,
    integrator: &'static str,
    measure: String,
    order: String,
    error_50: String,
    loop_s_50: String,
    recommended_dt_per_tc: String,
    recommended_dt: String,
    recommended_loop_s: String,
}

/// A sweep: its label and its ok runs with an error, by increasing dt.
type Sweep<'a> = (String, Vec<&'a RunRecord>);

/// The dt sweeps of `scene`: groups of two or more ok runs with an `error`.
fn sweeps<'a>(records: &'a [RunRecord], scene: &str) -> Vec<Sweep<'a>> {
    groups(records, scene)
        .into_iter()
        .map(|(label, members)| {
            let mut members: Vec<&RunRecord> = members.into_iter().filter(|r| r.metrics.error.is_some()).collect();
            members.sort_by(|a, b| a.spec.dt.total_cmp(&b.spec.dt));
            (label, members)
        })
        .filter(|(_, members)| members.len() > 1)
        .collect()
}

fn error_points(members: &[&RunRecord]) -> Vec<(f64, f64)> {
    members.iter().filter_map(|r| r.metrics.error.map(|e| (r.spec.dt, e))).collect()
}

/// The work–precision part of `scene`: its figures and its table for the accuracy `target`,
/// both from the scene's dt sweeps (none without sweeps).
pub fn part(records: &[RunRecord], scene: &str, target: f64) -> anyhow::Result<Part<Vec<PrecisionRow>>> {
    let sweeps = sweeps(records, scene);
    Ok(Part { figures: precision_figures(&sweeps, scene)?, rows: precision_rows(sweeps, target) })
}

/// The work–precision table of the `sweeps` for the accuracy `target`.
fn precision_rows(sweeps: Vec<Sweep>, target: f64) -> Vec<PrecisionRow> {
    sweeps
        .into_iter()
        .map(|(group, members)| {
            let points = error_points(&members);
            let order = convergence_order(&points);
            let at_50 = representative(&members);
            let recommendation = recommended_dt(&points, target, order);
            let t_c = at_50.spec.t_c;
            // The time loop costs ∝ 1/dt: scale the nearest run's loop time.
            let loop_s_at = |dt: f64| {
                let nearest = members
                    .iter()
                    .min_by(|a, b| (a.spec.dt / dt).ln().abs().total_cmp(&(b.spec.dt / dt).ln().abs()))
                    .expect("a sweep has runs");
                nearest.trace.loop_s * nearest.spec.dt / dt
            };
            let note = |how: Recommendation| match how {
                Recommendation::Interpolated => "",
                Recommendation::AtLargest => " (largest of the sweep; larger may do)",
                Recommendation::Extrapolated => " (extrapolated)",
            };
            PrecisionRow {
                integrator: at_50.spec.integrator.name(),
                measure: at_50.metrics.error_measure.clone().unwrap_or_default(),
                order: order.map(|p| format!("{p:.2}")).unwrap_or_else(|| "–".into()),
                error_50: format!(
                    "{} at t_c/{:.0}",
                    at_50.metrics.error.map(|e| format!("{e:.2e}")).unwrap_or_default(),
                    at_50.spec.dt_per_tc()
                ),
                loop_s_50: number(at_50.trace.loop_s),
                recommended_dt_per_tc: recommendation
                    .map(|(dt, how)| format!("t_c/{}{}", number(t_c / dt), note(how)))
                    .unwrap_or_else(|| "–".into()),
                recommended_dt: optional(recommendation.map(|(dt, _)| dt)),
                recommended_loop_s: optional(recommendation.map(|(dt, _)| loop_s_at(dt))),
                group,
            }
        })
        .collect()
}

/// The error-against-wall-time and error-against-dt figures of `scene`, when it has `sweeps`.
fn precision_figures(sweeps: &[Sweep], scene: &str) -> anyhow::Result<Vec<Figure>> {
    if sweeps.is_empty() {
        return Ok(Vec::new());
    }
    let curves = |x: &dyn Fn(&RunRecord) -> f64| -> Vec<Series> {
        sweeps
            .iter()
            .map(|(label, members)| Series {
                label: label.clone(),
                points: members.iter().filter_map(|r| r.metrics.error.map(|e| (x(r), e))).collect(),
                mark: Mark::Line,
            })
            .collect()
    };
    let measure = sweeps[0].1[0].metrics.error_measure.clone().unwrap_or_default();
    let work = Chart {
        title: format!("{scene}: work against precision"),
        x_label: "wall time of the time loop (s)".into(),
        y_label: format!("error ({measure})"),
        scale: Scale::LogLog,
    };
    let convergence = Chart {
        title: format!("{scene}: error against time step"),
        x_label: "dt / t_c".into(),
        y_label: format!("error ({measure})"),
        scale: Scale::LogLog,
    };
    Ok(vec![
        Figure {
            scene: scene.into(),
            kind: FigureKind::WorkPrecision,
            file: format!("plots/{scene}-work-precision.svg"),
            caption: format!(
                "Error against the wall time of the time loop, one line per integrator and setting, {scene}: \
                 lower left is better; a line's slope is −order (error ∝ dt^p ∝ time^(−p))."
            ),
            image: line_chart(&work, &curves(&|r| r.trace.loop_s))?,
        },
        Figure {
            scene: scene.into(),
            kind: FigureKind::ErrorDt,
            file: format!("plots/{scene}-error-dt.svg"),
            caption: format!("Error against dt/t_c, {scene}: a slope of p on these axes is order p."),
            image: line_chart(&convergence, &curves(&|r| 1.0 / r.spec.dt_per_tc()))?,
        },
    ])
}
