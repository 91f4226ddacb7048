//! Probed lines of a lattice: the space–time maps of their displacement and velocity, and
//! every node's series as `probes/<run_id>.csv`.

use super::figure::{Figure, physics_label};
use crate::draw::chart::{Chart, Scale, heatmap};
use crate::runner::RunRecord;
use crate::sim::RunStatus;

/// The probed rows and columns of the first `ok` run of `scene` that asks for probes: per line,
/// the displacement and the velocity along its livelier axis as space–time maps.
pub fn probe_figures(records: &[RunRecord], scene: &str) -> anyhow::Result<Vec<Figure>> {
    let Some(r) = records.iter().find(|r| {
        r.spec.scene == scene && r.status == RunStatus::Ok && r.spec.lattice().is_some_and(|l| !l.probes.is_empty())
    }) else {
        return Ok(Vec::new());
    };
    let mut figures = Vec::new();
    let run = physics_label(r, |_| true);
    for probe in r.trace.probes.iter().filter(|p| r.spec.lattice().is_some_and(|l| is_requested(l, p))) {
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
                file: format!("plots/{scene}-probe-{slug}-{what}.svg"),
                caption: format!(
                    "Probe on {} of {scene}: {what} along {axis} of each of its nodes against time, red positive, \
                     blue negative, scaled to the largest |value| ({peak:.3e} {unit}). Every node's series is in \
                     probes/{}.csv.",
                    probe.name, r.run_id
                ),
                image: heatmap(&chart, &r.trace.time, values)?,
            });
        }
    }
    Ok(figures)
}

/// True when `probe` is one the campaign asked for (not only the kicked column of a wave).
fn is_requested(lattice: &crate::spec::LatticeSpec, probe: &crate::sim::ProbeTrace) -> bool {
    lattice.probes.iter().any(|line| line.name() == probe.name)
}

/// The probed lines of a run as CSV: one row per sample and node (time, probe, node, position
/// along the line, displacements and velocities); `None` unless the run asks for probes.
pub fn probe_table(record: &RunRecord) -> Option<String> {
    let probes = &record.trace.probes;
    if record.spec.lattice().is_none_or(|l| l.probes.is_empty()) || probes.is_empty() {
        return None;
    }
    let mut csv = String::from("time,probe,node,index,displacement_x,displacement_y,velocity_x,velocity_y\n");
    for (s, time) in record.trace.time.iter().enumerate() {
        for probe in probes {
            for (index, node) in probe.nodes.iter().enumerate() {
                csv.push_str(&format!(
                    "{time:e},{},{node},{index},{:e},{:e},{:e},{:e}\n",
                    probe.name,
                    probe.displacement_x[s][index],
                    probe.displacement_y[s][index],
                    probe.velocity_x[s][index],
                    probe.velocity_y[s][index],
                ));
            }
        }
    }
    Some(csv)
}
