//! Waves: the sound speed of chain waves and impulse lattices by each arrival criterion, its
//! power law against the impact speed, and the space–time picture of one run.

use serde::Serialize;

use super::figure::{Figure, FigureKind, Part};
use super::words::{fit_quality, impulse_words, number, optional};
use crate::draw::chart::{Chart, Mark, Scale, Series, heatmap, line_chart};
use crate::measure::ARRIVAL_CRITERIA;
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::spec::SceneKind;
use crate::study::lattice::sideways_kick_speeds;
use crate::summary::ScalingFit;

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

/// The wave part of `scene`: V_s against v0 (with the fitted power law), the space–time picture
/// of one run and the table of its waves (all empty when it times no wave and fits no speed).
pub fn part(records: &[RunRecord], fits: &[ScalingFit], scene: &str) -> anyhow::Result<Part<Vec<WaveRow>>> {
    let figures = speed_figure(fits, scene)?.into_iter().chain(space_time_figure(records, scene)?).collect();
    Ok(Part { figures, rows: wave_rows(records, scene) })
}

/// The chain-wave rows of `scene` (empty when it times no wave).
fn wave_rows(records: &[RunRecord], scene: &str) -> Vec<WaveRow> {
    records
        .iter()
        .filter(|r| r.spec.scene == scene && r.spec.wave().is_some())
        .map(|r| {
            let m = &r.metrics;
            WaveRow {
                run_id: r.run_id.clone(),
                label: r.spec.varied_in_words(|_| true),
                v0: match r.spec.lattice().and_then(|l| l.impulse) {
                    Some(i) => impulse_words(&i),
                    None => format!("v0 = {} m/s", number(r.spec.v0)),
                },
                distance: optional(m.wave_distance),
                arrival_time: optional(m.arrival_time()),
                speeds: ARRIVAL_CRITERIA.iter().map(|c| optional(m.sound_speed(c))).collect(),
                estimate: optional(m.wave_distance.zip(m.arrival_time_tc_estimate).map(|(l, t)| l / t)),
                theory: reference_speed(r, number),
                status: r.status,
            }
        })
        .collect()
}

/// The reference speed of a wave run in words, its numbers written by `write`: the kind's one
/// linear speed, or for a node kicked sideways the two that bracket its first arrival
/// ([`sideways_kick_speeds`]'s argument), so that no single speed shows as a miss.
pub(crate) fn reference_speed(r: &RunRecord, write: fn(f64) -> String) -> String {
    match sideways_kick(r) {
        Some((c_t, c_l)) => format!("{} (c_T) … {} (c_L)", write(c_t), write(c_l)),
        None => r.metrics.sound_speed_theory.map_or_else(|| "–".into(), write),
    }
}

/// The speeds (c_T, c_L) (m/s) bracketing the front of a node kicked sideways, if `r` is one.
pub(crate) fn sideways_kick(r: &RunRecord) -> Option<(f64, f64)> {
    r.spec.lattice().and_then(|l| sideways_kick_speeds(&r.spec, l))
}

/// V_s against v0 of `scene`, measured and with its fitted power law; `None` without a fit.
fn speed_figure(fits: &[ScalingFit], scene: &str) -> anyhow::Result<Option<Figure>> {
    let fits: Vec<_> = fits.iter().filter(|f| f.scene == scene && f.quantity == "sound_speed").collect();
    if fits.is_empty() {
        return Ok(None);
    }
    let mut series = Vec::new();
    for f in &fits {
        let label = if f.group.is_empty() { f.law.to_string() } else { format!("{}, {}", f.law, f.group) };
        let (x0, y0) = f.points[0];
        let line = f.points.iter().map(|&(x, _)| (x, y0 * (x / x0).powf(f.fit.exponent))).collect();
        series.push(Series { label: format!("{label}: measured"), points: f.points.clone(), mark: Mark::Markers });
        series.push(Series {
            label: format!("{label}: fit v0^{:.3} ({})", f.fit.exponent, fit_quality(&f.fit, 5)),
            points: line,
            mark: Mark::Line,
        });
    }
    let chart = Chart {
        title: format!("{scene}: sound speed against impact speed"),
        x_label: "v0 (m/s)".into(),
        y_label: "V_s = L / t_s (m/s)".into(),
        scale: Scale::LogLog,
    };
    Ok(Some(Figure {
        scene: scene.into(),
        kind: FigureKind::SpeedAgainstV0,
        file: format!("plots/{scene}-speed-v0.svg"),
        caption: format!(
            "Sound speed by the recommended criterion against the impact speed v0, {scene}, with the fitted power \
             law: linear springs give the same speed at every v0 (exponent 0); a chain of springs s ∝ δ^β without \
             pre-load carries a solitary wave whose speed grows as v0^((β − 1)/(β + 1)), v0^(1/5) for Hertz."
        ),
        image: line_chart(&chart, &series)?,
    }))
}

/// The displacement in space and time of the first ok wave run of `scene`: a chain's
/// particles (walls left out), or the kicked column of an impulse lattice; `None` without one.
fn space_time_figure(records: &[RunRecord], scene: &str) -> anyhow::Result<Option<Figure>> {
    let first_ok =
        records.iter().find(|r| r.spec.scene == scene && r.spec.wave().is_some() && r.status == RunStatus::Ok);
    let Some(r) = first_ok else { return Ok(None) };
    let t = &r.trace;
    let (values, rows, what): (Vec<Vec<f64>>, &str, &str) = match r.spec.kind() {
        SceneKind::Lattice => {
            // The displacement along the impulse: a sideways step sends a transverse wave, whose
            // u_y is round-off.
            let sideways = r.spec.lattice().and_then(|l| l.impulse).is_some_and(|i| i.is_sideways());
            let probe = t.probes.first();
            let values = if sideways { probe.map(|p| &p.displacement_x) } else { probe.map(|p| &p.displacement_y) };
            (
                values.cloned().unwrap_or_default(),
                "node of the kicked column (0: bottom)",
                if sideways { "x" } else { "y" },
            )
        }
        _ => {
            (t.displacement_x.iter().map(|row| row[1..row.len().saturating_sub(1)].to_vec()).collect(), "particle", "x")
        }
    };
    if t.time.len() < 2 || values.first().is_none_or(|row| row.is_empty()) {
        return Ok(None);
    }
    // A free body under a step force also moves as a whole: the line's mean displacement at
    // each sample is that rigid drift, not the wave, and is taken out.
    let free = r.spec.lattice().is_some_and(|l| l.supports.holds_nothing());
    let values: Vec<Vec<f64>> = if free {
        values
            .into_iter()
            .map(|row| {
                let mean = row.iter().sum::<f64>() / row.len() as f64;
                row.into_iter().map(|u| u - mean).collect()
            })
            .collect()
    } else {
        values
    };
    let chart = Chart {
        title: format!("{scene}: u_{what} in space and time ({})", r.spec.varied_in_words(|_| true)),
        x_label: "time t (s)".into(),
        y_label: rows.into(),
        scale: Scale::Linear,
    };
    Ok(Some(Figure {
        scene: scene.into(),
        kind: FigureKind::SpaceTime,
        file: format!("plots/{scene}-space-time.svg"),
        caption: format!(
            "Displacement along {what} of every {rows} against time, {scene}: red positive, blue negative, \
             white at rest, scaled to the largest |u| (colour bar in m{}). The wave front is the edge of the coloured \
             region; its slope is the sound speed.",
            if free { "; the free lattice's rigid drift, the line's mean displacement, taken out" } else { "" }
        ),
        image: heatmap(&chart, &t.time, &values)?,
    }))
}
