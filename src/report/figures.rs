//! The plain figures: energies per scene, chain displacements, relaxation, the finite-size
//! convergence of lattice moduli, the convergence of the pair measurements against their
//! analytical values (which kind draws which: `kinds.rs`), and the dissipation time against the
//! damping across scenes.

use super::figure::{
    Figure, FigureKind, background_damping_only, background_gamma, bond_damping_only, both_dampings, group_label,
    representative,
};
use crate::draw::chart::{Chart, Mark, Scale, Series, line_chart};
use crate::measure::relative_error;
use crate::runner::RunRecord;

/// The groups whose energies are worth a figure: an undamped one and a damped one (the first
/// of each), in runs that move rather than relax (a relaxing run's energies are its relaxation
/// figure's, and its samples are the relaxation checks, too few for a time history).
fn energy_groups<'a>(groups: &'a [(String, Vec<&'a RunRecord>)]) -> Vec<(usize, &'a (String, Vec<&'a RunRecord>))> {
    let damped = |r: &RunRecord| r.spec.gamma > 0.0 || r.spec.gamma_background > 0.0;
    let moving = |r: &RunRecord| r.spec.relax().is_none() && r.trace.time.len() >= MIN_ENERGY_SAMPLES;
    let mut chosen = Vec::new();
    for want_damped in [false, true] {
        if let Some(found) = groups.iter().enumerate().find(|(_, (_, members))| {
            let r = representative(members);
            moving(r) && damped(r) == want_damped
        }) {
            chosen.push(found);
        }
    }
    chosen
}

/// Fewer samples than this do not make a time history worth drawing.
const MIN_ENERGY_SAMPLES: usize = 20;

/// The energies of a scene against time, of the groups [`energy_groups`] chooses among its
/// `groups` (every kind draws them).
pub(super) fn energy_figures(scene: &str, groups: &[(String, Vec<&RunRecord>)]) -> anyhow::Result<Vec<Figure>> {
    energy_groups(groups)
        .into_iter()
        .map(|(index, (label, members))| energy_figure(scene, index, label, representative(members)))
        .collect()
}

/// The dissipation time of the loaded lattices whose damping the grid varies, against the
/// damping coefficient: bond damping γ and background damping γ_g (by stopping criterion) on
/// one pair of axes, so the two kinds compare at a glance.
pub(super) fn dissipation_figure(records: &[RunRecord]) -> anyhow::Result<Option<Figure>> {
    let swept = |r: &&RunRecord| {
        r.spec.lattice().is_some_and(|l| l.impulse.is_none() && !l.is_random())
            && r.spec.varied.keys().any(|k| k.starts_with("damping."))
    };
    let runs: Vec<&RunRecord> = records.iter().filter(swept).collect();
    let curve = |label: &str, keep: &dyn Fn(&RunRecord) -> bool, damping: fn(&RunRecord) -> f64| Series {
        label: label.into(),
        points: runs
            .iter()
            .filter(|r| keep(r))
            .filter_map(|r| Some((damping(r), r.metrics.dissipation_time?)))
            .collect(),
        mark: Mark::Markers,
    };
    let force_criterion = |r: &RunRecord| r.spec.relax().is_some_and(|x| x.residual_force.is_some());
    let series: Vec<Series> = [
        curve("bond damping γ", &bond_damping_only, |r| r.spec.gamma),
        curve(
            "background γ_g, energy criterion",
            &|r| background_damping_only(r) && !force_criterion(r),
            background_gamma,
        ),
        curve(
            "background γ_g, force criterion",
            &|r| background_damping_only(r) && force_criterion(r),
            background_gamma,
        ),
        curve(
            "background γ_g added to bond γ, energy criterion",
            &|r| both_dampings(r) && !force_criterion(r),
            background_gamma,
        ),
    ]
    .into_iter()
    .filter(|s| !s.points.is_empty())
    .collect();
    if series.len() < 2 {
        return Ok(None);
    }
    let chart = Chart {
        title: "Dissipation time against damping".into(),
        x_label: "damping coefficient γ or γ_g (N s/m)".into(),
        y_label: "dissipation time (s)".into(),
        scale: Scale::LogLog,
    };
    Ok(Some(Figure {
        scene: "dissipation".into(),
        kind: FigureKind::Damping,
        file: "plots/dissipation-damping.svg".into(),
        caption: "Time until each loaded lattice counts as relaxed, against its damping coefficient: bond damping \
                  alone, background damping alone by either stopping criterion, and background damping added to bond \
                  damping (against γ_g)."
            .into(),
        image: line_chart(&chart, &series)?,
    }))
}

fn energy_figure(scene: &str, index: usize, label: &str, record: &RunRecord) -> anyhow::Result<Figure> {
    let t = &record.trace;
    let series = |name: &str, values: Vec<f64>| Series {
        label: name.into(),
        points: t.time.iter().copied().zip(values).collect(),
        mark: Mark::Line,
    };
    let total: Vec<f64> = (0..t.time.len()).map(|s| t.kinetic[s] + t.potential[s] + t.dissipated[s]).collect();
    let chart = Chart {
        title: format!("{scene}: energies ({label}, dt = t_c/{:.0})", record.spec.dt_per_tc()),
        x_label: "time t (s)".into(),
        y_label: "energy (J)".into(),
        scale: Scale::Linear,
    };
    let image = line_chart(
        &chart,
        &[
            series("kinetic", t.kinetic.clone()),
            series("potential", t.potential.clone()),
            series("dissipated", t.dissipated.clone()),
            series("total (incl. dissipated)", total),
        ],
    )?;
    Ok(Figure {
        scene: scene.into(),
        kind: FigureKind::Energy,
        file: format!("plots/{scene}-energy-{index}.svg"),
        caption: format!("Kinetic, potential, dissipated and total energy against time, {scene} ({label})."),
        image,
    })
}

pub(super) fn displacement_figure(scene: &str, label: &str, record: &RunRecord) -> anyhow::Result<Figure> {
    let t = &record.trace;
    let particles = t.displacement_x.first().map_or(0, Vec::len);
    let largest = t.displacement_x.iter().flatten().fold(0.0f64, |m, u| m.max(u.abs())).max(f64::MIN_POSITIVE);
    // Waterfall: particle p drawn around height p, displacement scaled so the largest is 0.45.
    let series: Vec<Series> = (1..particles.saturating_sub(1))
        .map(|p| Series {
            label: if p == 1 { "u_p(t) (scaled) + p".into() } else { String::new() },
            points: t
                .time
                .iter()
                .zip(&t.displacement_x)
                .map(|(&time, u)| (time, p as f64 + 0.45 * u[p] / largest))
                .collect(),
            mark: Mark::Line,
        })
        .collect();
    let chart = Chart {
        title: format!("{scene}: displacements ({label}; largest |u| = {largest:.3e} m)"),
        x_label: "time t (s)".into(),
        y_label: "particle number p + u_p / (2.2 max|u|)".into(),
        scale: Scale::Linear,
    };
    Ok(Figure {
        scene: scene.into(),
        kind: FigureKind::Displacements,
        file: format!("plots/{scene}-displacements.svg"),
        caption: format!(
            "Displacement of every particle against time, {scene} ({label}): one line per particle, offset by its number."
        ),
        image: line_chart(&chart, &series)?,
    })
}

pub(super) fn convergence_figure(scene: &str, groups: &[(String, Vec<&RunRecord>)]) -> anyhow::Result<Figure> {
    let mut series = Vec::new();
    for (label, members) in groups {
        let curve = |name: &str, error: &dyn Fn(&RunRecord) -> Option<f64>| Series {
            label: format!("{name} ({label})"),
            points: members.iter().filter_map(|r| error(r).map(|e| (1.0 / r.spec.dt_per_tc(), e.abs()))).collect(),
            mark: Mark::Markers,
        };
        series.push(curve("t_c", &|r| {
            relative_error(r.metrics.pair.contact_duration, r.metrics.pair.contact_duration_theory)
        }));
        series.push(curve("r", &|r| relative_error(r.metrics.pair.restitution, r.metrics.pair.restitution_theory)));
    }
    series.extend(reference_slopes(&series));
    let chart = Chart {
        title: format!("{scene}: measured against analytical"),
        x_label: "dt / t_c".into(),
        y_label: "|relative error|".into(),
        scale: Scale::LogLog,
    };
    Ok(Figure {
        scene: scene.into(),
        kind: FigureKind::Convergence,
        file: format!("plots/{scene}-convergence.svg"),
        caption: format!(
            "Relative error of contact duration t_c and restitution r against dt/t_c, {scene}. A slope of 2 on these axes is second order."
        ),
        image: line_chart(&chart, &series)?,
    })
}

/// Reference lines of slope 1 and 2 on log–log axes, through the geometric middle of the
/// measured points (first and second order: error ∝ dt^p), over their dt range.
fn reference_slopes(measured: &[Series]) -> Vec<Series> {
    let points: Vec<(f64, f64)> =
        measured.iter().flat_map(|s| s.points.iter().copied()).filter(|&(x, y)| x > 0.0 && y > 1e-13).collect();
    let (Some(low), Some(high)) =
        (points.iter().map(|p| p.0).reduce(f64::min), points.iter().map(|p| p.0).reduce(f64::max))
    else {
        return Vec::new();
    };
    let mid_x = (low * high).sqrt();
    let mid_y = (points.iter().map(|p| p.1.ln()).sum::<f64>() / points.len() as f64).exp();
    [1.0, 2.0]
        .iter()
        .map(|&order: &f64| Series {
            label: format!("slope {order:.0} (order {order:.0}, reference)"),
            points: [low, high].iter().map(|&x| (x, mid_y * (x / mid_x).powf(order))).collect(),
            mark: Mark::Line,
        })
        .collect()
}

/// At most this many relaxation curves in one figure.
const MAX_RELAXATION_CURVES: usize = 6;

/// At most `most` groups, spread evenly over the list (first and last included), so a figure
/// shows the range of the grid rather than its first corner.
fn spread<T>(items: &[T], most: usize) -> Vec<&T> {
    if items.len() <= most {
        return items.iter().collect();
    }
    (0..most).map(|i| &items[i * (items.len() - 1) / (most - 1)]).collect()
}

pub(super) fn relaxation_figure(scene: &str, groups: &[(String, Vec<&RunRecord>)]) -> anyhow::Result<Figure> {
    let shown: Vec<&RunRecord> =
        spread(groups, MAX_RELAXATION_CURVES).into_iter().map(|(_, m)| representative(m)).collect();
    let ratio = |t: &crate::sim::Trace, s: usize| t.kinetic[s] / t.potential[s];
    let mut series: Vec<Series> = shown
        .iter()
        .map(|r| Series {
            label: group_label(r),
            points: (0..r.trace.time.len()).map(|s| (r.trace.time[s], ratio(&r.trace, s))).collect(),
            mark: Mark::Line,
        })
        .collect();
    // The energy criterion's threshold, where the runs shown stop by it.
    let energy_stopped: Vec<&&RunRecord> =
        shown.iter().filter(|r| r.spec.relax().is_some_and(|x| x.residual_force.is_none())).collect();
    let threshold = energy_stopped.first().and_then(|r| r.spec.relax()).map(|x| x.kinetic_ratio);
    if let (Some(threshold), Some(end)) =
        (threshold, shown.iter().filter_map(|r| r.trace.time.last()).copied().reduce(f64::max))
    {
        series.push(Series {
            label: format!("threshold E_kin/E_pot = {threshold:e}"),
            points: vec![(0.0, threshold), (end, threshold)],
            mark: Mark::Line,
        });
    }
    let relaxed: Vec<(f64, f64)> = shown
        .iter()
        .filter_map(|r| {
            let t = r.metrics.dissipation_time?;
            let s = r.trace.time.iter().position(|&x| x >= t).unwrap_or(r.trace.time.len().checked_sub(1)?);
            Some((t, ratio(&r.trace, s)))
        })
        .collect();
    if !relaxed.is_empty() {
        series.push(Series { label: "relaxed (dissipation time)".into(), points: relaxed, mark: Mark::Markers });
    }
    let chart = Chart {
        title: format!("{scene}: relaxation"),
        x_label: "time t (s)".into(),
        y_label: "E_kin / E_pot".into(),
        scale: Scale::LogY,
    };
    Ok(Figure {
        scene: scene.into(),
        kind: FigureKind::Relaxation,
        file: format!("plots/{scene}-relaxation.svg"),
        caption: format!(
            "Kinetic over potential energy against time, {scene}, {} of its {} runs spread over the grid: a loaded lattice relaxing (markers: where each run counts as relaxed; line: the energy criterion's threshold), or an impulse spreading.",
            shown.len(),
            groups.len()
        ),
        image: line_chart(&chart, &series)?,
    })
}

/// One curve of the finite-size figure: (N, modulus/continuum) from the static answer and MD.
struct SizeCurve {
    label: String,
    fem: Vec<(f64, f64)>,
    md: Vec<(f64, f64)>,
}

/// The modulus a lattice run measures, from MD and from the static answer, over its continuum value.
fn modulus_ratios(r: &RunRecord) -> Option<(f64, Option<f64>)> {
    let m = &r.metrics;
    let (md, fem, theory) = match (m.lattice.youngs_modulus_fem, m.lattice.shear_modulus_fem) {
        (Some(fem), _) => (m.lattice.youngs_modulus, fem, m.lattice.youngs_modulus_theory?),
        (None, Some(fem)) => (m.lattice.shear_modulus, fem, m.lattice.shear_modulus_theory?),
        (None, None) => return None,
    };
    Some((fem / theory, md.map(|v| v / theory)))
}

/// Static (lines) and MD (markers) moduli over their continuum value against the lattice
/// size, one curve per combination of the other grid values; `None` with a single size.
pub(super) fn size_figure(scene: &str, mine: &[&RunRecord]) -> anyhow::Result<Option<Figure>> {
    let size = |r: &RunRecord| r.spec.lattice().map_or(0, |l| l.nx.max(l.ny));
    let sizes: std::collections::BTreeSet<usize> = mine.iter().map(|r| size(r)).collect();
    if sizes.len() < 2 {
        return Ok(None);
    }
    let mut curves: Vec<SizeCurve> = Vec::new();
    for r in mine {
        let Some((fem, md)) = modulus_ratios(r) else { continue };
        let label = r.spec.varied_in_words(|p| !p.starts_with("lattice.size") && !p.starts_with("lattice.n"));
        let index = match curves.iter().position(|c| c.label == label) {
            Some(index) => index,
            None => {
                curves.push(SizeCurve { label, fem: Vec::new(), md: Vec::new() });
                curves.len() - 1
            }
        };
        curves[index].fem.push((size(r) as f64, fem));
        if let Some(md) = md {
            curves[index].md.push((size(r) as f64, md));
        }
    }
    let mut series = Vec::new();
    for SizeCurve { label, mut fem, mut md } in curves {
        fem.sort_by(|a, b| a.0.total_cmp(&b.0));
        md.sort_by(|a, b| a.0.total_cmp(&b.0));
        series.push(Series { label: format!("static, {label}"), points: fem, mark: Mark::Line });
        series.push(Series { label: format!("MD, {label}"), points: md, mark: Mark::Markers });
    }
    let chart = Chart {
        title: format!("{scene}: finite-size convergence"),
        x_label: "lattice size N (nodes per side)".into(),
        y_label: "modulus / continuum value".into(),
        scale: Scale::Linear,
    };
    Ok(Some(Figure {
        scene: scene.into(),
        kind: FigureKind::Size,
        file: format!("plots/{scene}-size.svg"),
        caption: format!(
            "E (tensile) or G (shear) of the {scene} lattices over the continuum value, against size: lines the static answer, markers the relaxed MD."
        ),
        image: line_chart(&chart, &series)?,
    }))
}
