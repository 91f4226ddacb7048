//! Which figures a campaign gets (`draw_all`, the one list of them), and the plain ones:
//! energies per scene, chain displacements, relaxation, the finite-size convergence of lattice
//! moduli, and the convergence of the pair measurements against their analytical values.

use super::figure::{Figure, groups, representative};
use super::{precision, probes, solids, stability_map, waves};
use crate::draw::chart::{Chart, Scale, Series, line_chart};
use crate::measure::relative_error;
use crate::runner::RunRecord;
use crate::spec::{Campaign, SceneKind};
use crate::summary::ScalingFit;

/// At most this many energy figures per scene (one per group).
const MAX_ENERGY_FIGURES: usize = 4;

/// Every figure of the report.
pub fn draw_all(campaign: &Campaign, records: &[RunRecord], fits: &[ScalingFit]) -> anyhow::Result<Vec<Figure>> {
    let mut figures = Vec::new();
    for (scene, kind) in &campaign.scenes {
        let groups = groups(records, scene);
        for (index, (label, members)) in groups.iter().enumerate().take(MAX_ENERGY_FIGURES) {
            figures.push(energy_figure(scene, index, label, representative(members))?);
        }
        match kind {
            SceneKind::Pair if groups.iter().any(|(_, m)| m.len() > 1) => {
                figures.push(convergence_figure(scene, &groups)?)
            }
            SceneKind::Chain => {
                if let Some((label, members)) = groups.first() {
                    figures.push(displacement_figure(scene, label, representative(members))?);
                }
                if records.iter().any(|r| r.spec.scene == *scene && r.spec.wave().is_some()) {
                    figures.push(relaxation_figure(scene, &groups)?);
                }
            }
            SceneKind::Lattice => {
                figures.push(relaxation_figure(scene, &groups)?);
                if let Some(figure) = size_figure(scene, records)? {
                    figures.push(figure);
                }
            }
            SceneKind::Pair => {}
        }
        figures.extend(precision::precision_figures(records, scene)?);
        figures.extend(waves::wave_figures(records, fits, scene)?);
        figures.extend(probes::probe_figures(records, scene)?);
        figures.extend(solids::scaling_figures(fits, scene)?);
        figures.extend(solids::ensemble_figure(records, scene)?);
        if stability_map::is_stability_scene(records, scene) {
            figures.extend(stability_map::stability_figures(records, scene)?);
        }
    }
    Ok(figures)
}

fn energy_figure(scene: &str, index: usize, label: &str, record: &RunRecord) -> anyhow::Result<Figure> {
    let t = &record.trace;
    let series = |name: &str, values: Vec<f64>| Series {
        label: name.into(),
        points: t.time.iter().copied().zip(values).collect(),
        markers: false,
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
        file: format!("plots/{scene}-energy-{index}.svg"),
        caption: format!("Kinetic, potential, dissipated and total energy against time, {scene} ({label})."),
        image,
    })
}

fn displacement_figure(scene: &str, label: &str, record: &RunRecord) -> anyhow::Result<Figure> {
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
            markers: false,
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
        file: format!("plots/{scene}-displacements.svg"),
        caption: format!(
            "Displacement of every particle against time, {scene} ({label}): one line per particle, offset by its number."
        ),
        image: line_chart(&chart, &series)?,
    })
}

fn convergence_figure(scene: &str, groups: &[(String, Vec<&RunRecord>)]) -> anyhow::Result<Figure> {
    let mut series = Vec::new();
    for (label, members) in groups {
        let curve = |name: &str, error: &dyn Fn(&RunRecord) -> Option<f64>| Series {
            label: format!("{name} ({label})"),
            points: members.iter().filter_map(|r| error(r).map(|e| (1.0 / r.spec.dt_per_tc(), e.abs()))).collect(),
            markers: true,
        };
        series.push(curve("t_c", &|r| {
            relative_error(r.metrics.pair.contact_duration, r.metrics.pair.contact_duration_theory)
        }));
        series.push(curve("r", &|r| relative_error(r.metrics.pair.restitution, r.metrics.pair.restitution_theory)));
    }
    let chart = Chart {
        title: format!("{scene}: measured against analytical"),
        x_label: "dt / t_c".into(),
        y_label: "|relative error|".into(),
        scale: Scale::LogLog,
    };
    Ok(Figure {
        scene: scene.into(),
        file: format!("plots/{scene}-convergence.svg"),
        caption: format!(
            "Relative error of contact duration t_c and restitution r against dt/t_c, {scene}. A slope of 2 on these axes is second order."
        ),
        image: line_chart(&chart, &series)?,
    })
}

/// At most this many relaxation curves in one figure.
const MAX_RELAXATION_CURVES: usize = 8;

fn relaxation_figure(scene: &str, groups: &[(String, Vec<&RunRecord>)]) -> anyhow::Result<Figure> {
    let series: Vec<Series> = groups
        .iter()
        .take(MAX_RELAXATION_CURVES)
        .map(|(label, members)| {
            let t = &representative(members).trace;
            Series {
                label: label.clone(),
                points: (0..t.time.len()).map(|s| (t.time[s], t.kinetic[s] / t.potential[s])).collect(),
                markers: false,
            }
        })
        .collect();
    let chart = Chart {
        title: format!("{scene}: relaxation"),
        x_label: "time t (s)".into(),
        y_label: "E_kin / E_pot".into(),
        scale: Scale::LogY,
    };
    Ok(Figure {
        scene: scene.into(),
        file: format!("plots/{scene}-relaxation.svg"),
        caption: format!(
            "Kinetic over potential energy against time, {scene}: a loaded lattice relaxing, or an impulse spreading."
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
fn size_figure(scene: &str, records: &[RunRecord]) -> anyhow::Result<Option<Figure>> {
    let mine: Vec<&RunRecord> = records.iter().filter(|r| r.spec.scene == scene).collect();
    let size = |r: &RunRecord| r.spec.lattice().map_or(0, |l| l.nx.max(l.ny));
    let sizes: std::collections::BTreeSet<usize> = mine.iter().map(|r| size(r)).collect();
    if sizes.len() < 2 {
        return Ok(None);
    }
    let mut curves: Vec<SizeCurve> = Vec::new();
    for r in &mine {
        let Some((fem, md)) = modulus_ratios(r) else { continue };
        let label = r.spec.varied_label(|p| !p.starts_with("lattice.size") && !p.starts_with("lattice.n"));
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
        series.push(Series { label: format!("static, {label}"), points: fem, markers: false });
        series.push(Series { label: format!("MD, {label}"), points: md, markers: true });
    }
    let chart = Chart {
        title: format!("{scene}: finite-size convergence"),
        x_label: "lattice size N (nodes per side)".into(),
        y_label: "modulus / continuum value".into(),
        scale: Scale::Linear,
    };
    Ok(Some(Figure {
        scene: scene.into(),
        file: format!("plots/{scene}-size.svg"),
        caption: format!(
            "E (tensile) or G (shear) of the {scene} lattices over the continuum value, against size: lines the static answer, markers the relaxed MD."
        ),
        image: line_chart(&chart, &series)?,
    }))
}
