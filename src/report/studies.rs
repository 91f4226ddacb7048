//! Studies across the runs of a scene: work against precision over a dt sweep for each
//! integrator, and the stability map of runs swept across their integrator's limit.

use serde::Serialize;

use super::figures::{Figure, groups, representative};
use super::plots::{Chart, Scale, Series, heatmap, line_chart};
use super::{number, optional};
use crate::measure::{ARRIVAL_CRITERIA, Recommendation, convergence_order, recommended_dt};
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::spec::SceneKind;
use crate::table::scaling_fits;

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

/// The work–precision table of `scene` for the accuracy `target`.
pub fn precision_rows(records: &[RunRecord], scene: &str, target: f64) -> Vec<PrecisionRow> {
    sweeps(records, scene)
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

/// The error-against-wall-time and error-against-dt figures of `scene`, when it has sweeps.
pub fn precision_figures(records: &[RunRecord], scene: &str) -> anyhow::Result<Vec<Figure>> {
    let sweeps = sweeps(records, scene);
    if sweeps.is_empty() {
        return Ok(Vec::new());
    }
    let curves = |x: &dyn Fn(&RunRecord) -> f64| -> Vec<Series> {
        sweeps
            .iter()
            .map(|(label, members)| Series {
                label: label.clone(),
                points: members.iter().filter_map(|r| r.metrics.error.map(|e| (x(r), e))).collect(),
                markers: false,
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
            file: format!("plots/{scene}-work-precision.svg"),
            caption: format!(
                "Error against the wall time of the time loop, one line per integrator and setting, {scene}: \
                 lower left is better; a line's slope is −order (error ∝ dt^p ∝ time^(−p))."
            ),
            svg: line_chart(&work, &curves(&|r| r.trace.loop_s))?,
        },
        Figure {
            scene: scene.into(),
            file: format!("plots/{scene}-error-dt.svg"),
            caption: format!("Error against dt/t_c, {scene}: a slope of p on these axes is order p."),
            svg: line_chart(&convergence, &curves(&|r| 1.0 / r.spec.dt_per_tc()))?,
        },
    ])
}

/// True when `scene` studies stability: some run sets dt by dt·ω_max or may blow up.
pub fn is_stability_scene(records: &[RunRecord], scene: &str) -> bool {
    records.iter().any(|r| r.spec.scene == scene && (r.spec.allow_unstable || r.spec.dt_omega_max.is_some()))
}

/// True when `scene` sweeps dt·ω_max, so its runs map the stability limit.
fn sweeps_the_limit(records: &[RunRecord], scene: &str) -> bool {
    records.iter().any(|r| r.spec.scene == scene && r.spec.dt_omega_max.is_some())
}

/// The y coordinate of a run on the stability map: k_d/k for lattices, else the damping
/// ratio of the fastest mode; zero is drawn at [`MAP_FLOOR`] on the logarithmic axis.
fn map_y(r: &RunRecord) -> f64 {
    let y = match &r.spec.lattice {
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

/// The rows of a stability scene, and the predicted-against-observed summary.
pub fn stability_rows(records: &[RunRecord], scene: &str) -> (Vec<StabilityRow>, Vec<LimitRow>) {
    let mine: Vec<&RunRecord> = records.iter().filter(|r| r.spec.scene == scene).collect();
    let rows = mine
        .iter()
        .map(|r| {
            let m = &r.metrics;
            let predicted = match (m.dt_omega_max, m.stability_limit) {
                (Some(x), Some(limit)) if x > limit => "blows up",
                (Some(_), Some(_)) => "bounded",
                _ => "–",
            };
            StabilityRow {
                run_id: r.run_id.clone(),
                label: r.spec.varied_label(|_| true),
                integrator: r.spec.integrator.name(),
                dt_omega_max: optional(m.dt_omega_max),
                limit: optional(m.stability_limit),
                damping_ratio: optional(m.mode_damping_ratio),
                predicted,
                outcome: r.status,
                message: if r.message.is_empty() { "–".into() } else { r.message.clone() },
            }
        })
        .collect();
    if !sweeps_the_limit(records, scene) {
        return (rows, Vec::new());
    }
    let mut keys: Vec<(&'static str, String)> = Vec::new();
    for r in &mine {
        let key = (r.spec.integrator.name(), number(map_y(r)));
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    let limits = keys
        .into_iter()
        .filter_map(|(integrator, y)| {
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
                    format!("a bound: first blow-up {:+.1} % above it", 100.0 * (first_blown - predicted) / predicted)
                } else {
                    "bound violated: blew up at or below it".to_string()
                }
            } else if (last_bounded..=first_blown).contains(&predicted) {
                "inside the observed bracket".to_string()
            } else {
                let nearest = if predicted < last_bounded { last_bounded } else { first_blown };
                format!("outside by {:+.2} %", 100.0 * (predicted - nearest) / nearest)
            };
            Some(LimitRow {
                integrator,
                y,
                predicted: number(predicted),
                last_bounded: number(last_bounded),
                first_blown: number(first_blown),
                agreement,
            })
        })
        .collect();
    (rows, limits)
}

/// One stability map per integrator of a stability scene: runs that stayed bounded and runs
/// that blew up at their dt·ω_max and map y, with the predicted limit drawn through them.
pub fn stability_figures(records: &[RunRecord], scene: &str) -> anyhow::Result<Vec<Figure>> {
    if !sweeps_the_limit(records, scene) {
        return Ok(Vec::new());
    }
    let mine: Vec<&RunRecord> =
        records.iter().filter(|r| r.spec.scene == scene && r.metrics.dt_omega_max.is_some()).collect();
    let Some(first) = mine.first() else { return Ok(Vec::new()) };
    let lattice = first.spec.kind == SceneKind::Lattice;
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
            Series { label: "blew up (status unstable)".into(), points: points(true), markers: true },
            Series { label: "bounded".into(), points: points(false), markers: true },
            Series { label: format!("predicted limit of {}", integrator.name()), points: limit, markers: false },
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
            file: format!("plots/{scene}-stability-{}.svg", integrator.name()),
            caption: format!(
                "Stability map of {scene} with {}: each run at its dt·ω_max (ω_max estimated before the run), \
                 bounded or blown up, and the limit predicted from the integrator's test oscillator at the fastest \
                 mode's damping ratio.",
                integrator.name()
            ),
            svg: line_chart(&chart, &series)?,
        });
    }
    Ok(figures)
}

/// One chain-wave run: the sound speed by each criterion beside the estimates.
#[derive(Serialize)]
pub struct WaveRow {
    run_id: String,
    label: String,
    v0: String,
    distance: String,
    arrival_time: String,
    speeds: Vec<String>,
    estimate: String,
    theory: String,
    status: RunStatus,
}

/// The chain-wave rows of `scene` (empty when it times no wave).
pub fn wave_rows(records: &[RunRecord], scene: &str) -> Vec<WaveRow> {
    records
        .iter()
        .filter(|r| r.spec.scene == scene && r.spec.wave.is_some())
        .map(|r| {
            let m = &r.metrics;
            WaveRow {
                run_id: r.run_id.clone(),
                label: r.spec.varied_label(|_| true),
                v0: match r.spec.lattice.as_ref().and_then(|l| l.impulse) {
                    Some(i) => super::context::impulse_words(&i),
                    None => format!("v0 = {} m/s", number(r.spec.v0)),
                },
                distance: optional(m.wave_distance),
                arrival_time: optional(m.arrival_time()),
                speeds: ARRIVAL_CRITERIA.iter().map(|c| optional(m.sound_speed(c))).collect(),
                estimate: optional(m.wave_distance.zip(m.arrival_time_tc_estimate).map(|(l, t)| l / t)),
                theory: optional(m.sound_speed_theory),
                status: r.status,
            }
        })
        .collect()
}

/// A fitted y ∝ x^p of one group.
#[derive(Serialize)]
pub struct ExponentRow {
    group: String,
    law: &'static str,
    quantity: &'static str,
    against: &'static str,
    exponent: String,
    r_squared: String,
    points: usize,
    range: String,
}

/// The exponent rows of `scene`: every scaling law fitted over its runs.
pub fn exponent_rows(records: &[RunRecord], scene: &str) -> Vec<ExponentRow> {
    scaling_fits(records)
        .into_iter()
        .filter(|f| f.scene == scene)
        .map(|f| ExponentRow {
            group: if f.group.is_empty() { "all".into() } else { f.group },
            law: f.law,
            quantity: f.quantity,
            against: f.against,
            exponent: format!("{:.4}", f.fit.exponent),
            r_squared: format!("{:.6}", f.fit.r_squared),
            points: f.points.len(),
            range: format!("{} … {}", number(f.points[0].0), number(f.points[f.points.len() - 1].0)),
        })
        .collect()
}

/// The wave figures of `scene`: V_s against v0 (with the fitted power law) and the space–time
/// picture of one run.
pub fn wave_figures(records: &[RunRecord], scene: &str) -> anyhow::Result<Vec<Figure>> {
    let mut figures = Vec::new();
    let fits: Vec<_> =
        scaling_fits(records).into_iter().filter(|f| f.scene == scene && f.quantity == "sound_speed").collect();
    if !fits.is_empty() {
        let mut series = Vec::new();
        for f in &fits {
            let label = if f.group.is_empty() { f.law.to_string() } else { format!("{}, {}", f.law, f.group) };
            let (x0, y0) = f.points[0];
            let line = f.points.iter().map(|&(x, _)| (x, y0 * (x / x0).powf(f.fit.exponent))).collect();
            series.push(Series { label: format!("{label}: measured"), points: f.points.clone(), markers: true });
            series.push(Series {
                label: format!("{label}: fit v0^{:.3} (R² = {:.5})", f.fit.exponent, f.fit.r_squared),
                points: line,
                markers: false,
            });
        }
        let chart = Chart {
            title: format!("{scene}: sound speed against impact speed"),
            x_label: "v0 (m/s)".into(),
            y_label: "V_s = L / t_s (m/s)".into(),
            scale: Scale::LogLog,
        };
        figures.push(Figure {
            scene: scene.into(),
            file: format!("plots/{scene}-speed-v0.svg"),
            caption: format!(
                "Sound speed by the recommended criterion against the impact speed v0, {scene}, with the fitted power \
                 law: linear springs give the same speed at every v0 (exponent 0); a Hertz chain without pre-load \
                 carries a solitary wave whose speed grows as v0^(1/5)."
            ),
            svg: line_chart(&chart, &series)?,
        });
    }
    // A chain's particles (walls left out), or the kicked column of an impulse lattice, in time.
    let first_ok = records.iter().find(|r| r.spec.scene == scene && r.spec.wave.is_some() && r.status == RunStatus::Ok);
    if let Some(r) = first_ok {
        let t = &r.trace;
        let (values, rows, what): (Vec<Vec<f64>>, &str, &str) = match r.spec.kind {
            SceneKind::Lattice => (
                t.probes.first().map(|p| p.displacement_y.clone()).unwrap_or_default(),
                "node of the kicked column (0: bottom)",
                "y",
            ),
            _ => (
                t.displacement_x.iter().map(|row| row[1..row.len().saturating_sub(1)].to_vec()).collect(),
                "particle",
                "x",
            ),
        };
        if t.time.len() >= 2 && values.first().is_some_and(|row| !row.is_empty()) {
            let chart = Chart {
                title: format!("{scene}: displacement in space and time ({})", r.spec.varied_label(|_| true)),
                x_label: "time t (s)".into(),
                y_label: rows.into(),
                scale: Scale::Linear,
            };
            figures.push(Figure {
                scene: scene.into(),
                file: format!("plots/{scene}-space-time.svg"),
                caption: format!(
                    "Displacement along {what} of every {rows} against time, {scene}: red positive, blue negative, \
                     white at rest, scaled to the largest |u|. The wave front is the edge of the coloured region; its \
                     slope is the sound speed."
                ),
                svg: heatmap(&chart, &t.time, &values)?,
            });
        }
    }
    Ok(figures)
}

/// The probed rows and columns of the first `ok` run of `scene` that asks for probes: per line,
/// the displacement and the velocity along its livelier axis as space–time maps.
pub fn probe_figures(records: &[RunRecord], scene: &str) -> anyhow::Result<Vec<Figure>> {
    let Some(r) = records.iter().find(|r| {
        r.spec.scene == scene
            && r.status == RunStatus::Ok
            && r.spec.lattice.as_ref().is_some_and(|l| !l.probes.is_empty())
    }) else {
        return Ok(Vec::new());
    };
    let mut figures = Vec::new();
    let run = r.spec.varied_label(|_| true);
    for probe in r.trace.probes.iter().filter(|p| r.spec.lattice.as_ref().is_some_and(|l| is_requested(l, p))) {
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
                svg: heatmap(&chart, &r.trace.time, values)?,
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
    if record.spec.lattice.as_ref().is_none_or(|l| l.probes.is_empty()) || probes.is_empty() {
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
