//! Probed lines of a lattice: the space–time maps of their displacement and velocity (every
//! node's series is in `probes/<run_id>.parquet`, which the runner stores: `runner::record`).

use super::figure::{Figure, FigureKind, Part};
use crate::draw::chart::{Chart, Scale, heatmap};
use crate::runner::{RunRecord, is_asked_for};
use crate::sim::RunStatus;

/// The probe part of `scene`: figures only (the probed series are tables of their own, stored
/// by the runner).
pub fn part(records: &[RunRecord], scene: &str) -> anyhow::Result<Part> {
    Ok(Part { figures: probe_figures(records, scene)?, rows: () })
}

/// The probed rows and columns of the first `ok` run of `scene` that asks for probes: per line,
/// the displacement and the velocity along its livelier axis as space–time maps.
fn probe_figures(records: &[RunRecord], scene: &str) -> anyhow::Result<Vec<Figure>> {
    let Some(r) = records.iter().find(|r| {
        r.spec.scene == scene && r.status == RunStatus::Ok && r.spec.lattice().is_some_and(|l| !l.probes.is_empty())
    }) else {
        return Ok(Vec::new());
    };
    let mut figures = Vec::new();
    let run = r.spec.varied_in_words(|_| true);
    for probe in r.trace.probes.iter().filter(|p| is_asked_for(&r.spec, p)) {
        let along = if probe.name.starts_with("row") {
            "node along the row (0: left)"
        } else {
            "node up the column (0: bottom)"
        };
        for (what, unit, x, y) in [
            ("displacement", "m", &probe.displacement_x, &probe.displacement_y),
            ("velocity", "m/s", &probe.velocity_x, &probe.velocity_y),
        ] {
            let largest = |series: &[Vec<f64>]| series.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
            let (axis, values, peak) =
                if largest(x) >= largest(y) { ("x", x, largest(x)) } else { ("y", y, largest(y)) };
            if r.trace.time.len() < 2 || values.first().is_none_or(Vec::is_empty) {
                continue;
            }
            let slug = probe.name.replace(' ', "-");
            let chart = Chart {
                title: format!("{scene}, {}: {what} along {axis} ({run})", probe.name),
                x_label: "time t (s)".into(),
                y_label: along.into(),
                scale: Scale::Linear,
            };
            figures.push(Figure {
                scene: scene.into(),
                kind: FigureKind::Probe,
                file: format!("plots/{scene}-probe-{slug}-{what}.svg"),
                caption: format!(
                    "Probe on {} of {scene}: {what} along {axis} of each of its nodes against time, red positive, \
                     blue negative, scaled to the largest |value| ({peak:.3e} {unit}). Every node's series is in \
                     probes/{}.parquet.",
                    probe.name, r.run_id
                ),
                image: heatmap(&chart, &r.trace.time, values)?,
            });
        }
    }
    Ok(figures)
}
