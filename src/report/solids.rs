//! Non-linear and random solids: moduli and stiffness against the load or the wall
//! displacement with their fitted power laws, and ensembles of random lattices over seeds
//! against the effective-medium line.

use serde::Serialize;

use super::figure::{Figure, FigureKind, Part};
use super::words::{fit_quality, number, optional};
use crate::draw::chart::{Chart, Mark, Scale, Series, line_chart};
use crate::measure::mean_spread;
use crate::model::LatticeType;
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::spec::Diagonals;
use crate::summary::ScalingFit;

/// The solids part of `scene`: the fitted power laws of what it swept, and the dilution figure
/// and the table of its ensembles of random lattices.
pub fn part(records: &[RunRecord], fits: &[ScalingFit], scene: &str) -> anyhow::Result<Part<Vec<EnsembleRow>>> {
    let ensembles = ensembles(records, scene);
    let mut figures = scaling_figures(fits, scene)?;
    figures.extend(ensemble_figure(&ensembles, scene)?);
    Ok(Part { figures, rows: ensemble_rows(ensembles) })
}

/// One figure per swept quantity of `scene` (not the sound speed, which the wave study draws):
/// measured points and the fitted power law on log–log axes.
fn scaling_figures(fits: &[ScalingFit], scene: &str) -> anyhow::Result<Vec<Figure>> {
    let fits: Vec<_> = fits.iter().filter(|f| f.scene == scene && f.quantity != "sound_speed").collect();
    let mut figures = Vec::new();
    for (against, kind) in
        [("load_per_node", FigureKind::AgainstLoad), ("wall_displacement", FigureKind::AgainstWallDisplacement)]
    {
        let mine: Vec<_> = fits.iter().filter(|f| f.against == against).collect();
        if mine.is_empty() {
            continue;
        }
        let mut series = Vec::new();
        for f in &mine {
            let label =
                if f.group.is_empty() { f.quantity.to_string() } else { format!("{}, {}", f.quantity, f.group) };
            let (x0, y0) = f.points[0];
            series.push(Series { label: format!("{label}: MD"), points: f.points.clone(), mark: Mark::Markers });
            series.push(Series {
                label: format!("{label}: fit x^{:.3} ({})", f.fit.exponent, fit_quality(&f.fit, 5)),
                points: f.points.iter().map(|&(x, _)| (x, y0 * (x / x0).powf(f.fit.exponent))).collect(),
                mark: Mark::Line,
            });
        }
        let (x_label, y_label, what) = match against {
            "load_per_node" => ("load per top-row node F (N)", "modulus (Pa)", "moduli against the load"),
            _ => ("wall displacement |ΔW| (m)", "stiffness of the chain (N/m)", "stiffness against |ΔW|"),
        };
        let chart = Chart {
            title: format!("{scene}: {what}"),
            x_label: x_label.into(),
            y_label: y_label.into(),
            scale: Scale::LogLog,
        };
        figures.push(Figure {
            scene: scene.into(),
            kind,
            file: format!("plots/{scene}-{against}.svg"),
            caption: format!(
                "{scene}: {what} on log–log axes, secant (from the total deformation) and tangent (from a small \
                 extra step), with fitted power laws (their exponents in the text)."
            ),
            image: line_chart(&chart, &series)?,
        });
    }
    Ok(figures)
}

/// Runs of a random scene that differ only in their seed: mean and spread of the moduli.
#[derive(Serialize)]
pub struct EnsembleRow {
    group: String,
    kept: String,
    seeds: usize,
    mechanisms: usize,
    youngs_mean: String,
    youngs_spread: String,
    shear_mean: String,
    shear_spread: String,
    poisson_mean: String,
    poisson_spread: String,
    md_static: String,
}

/// An ensemble: its label, the kept fraction of the interior bonds (1 − cut fraction) and its
/// runs.
type Ensemble<'a> = (String, f64, Vec<&'a RunRecord>);

fn ensembles<'a>(records: &'a [RunRecord], scene: &str) -> Vec<Ensemble<'a>> {
    let mut out: Vec<Ensemble> = Vec::new();
    for r in records.iter().filter(|r| r.spec.scene == scene) {
        let Some(l) = r.spec.lattice().filter(|l| l.is_random() || r.spec.varied.contains_key("seed")) else {
            continue;
        };
        let label = r.spec.varied_in_words(|path| path != "seed");
        match out.iter_mut().find(|(l, _, _)| *l == label) {
            Some((_, _, members)) => members.push(r),
            None => out.push((label, 1.0 - l.cut_fraction, vec![r])),
        }
    }
    out
}

/// The table of a scene's `ensembles` (empty unless it is random or sweeps seeds).
fn ensemble_rows(ensembles: Vec<Ensemble>) -> Vec<EnsembleRow> {
    ensembles
        .into_iter()
        .map(|(group, kept, members)| {
            let ok = || members.iter().filter(|r| r.status == RunStatus::Ok);
            let (youngs_mean, youngs_spread) = mean_spread(ok().map(|r| at_rest(r)[YOUNGS]));
            let (shear_mean, shear_spread) = mean_spread(ok().map(|r| at_rest(r)[SHEAR]));
            let (poisson_mean, poisson_spread) = mean_spread(ok().map(|r| at_rest(r)[POISSON]));
            let md_static = ok()
                .flat_map(|r| {
                    let m = &r.metrics;
                    [
                        (m.lattice.youngs_modulus, m.lattice.youngs_modulus_fem),
                        (m.lattice.shear_modulus, m.lattice.shear_modulus_fem),
                    ]
                })
                .filter_map(|(md, fem)| crate::measure::relative_error(md, fem).map(f64::abs))
                .reduce(f64::max);
            EnsembleRow {
                group: if group.is_empty() { "all".into() } else { group },
                kept: number(kept),
                seeds: members.len(),
                mechanisms: members.iter().filter(|r| r.status == RunStatus::Mechanism).count(),
                youngs_mean: optional(youngs_mean),
                youngs_spread: optional(youngs_spread),
                shear_mean: optional(shear_mean),
                shear_spread: optional(shear_spread),
                poisson_mean: optional(poisson_mean),
                poisson_spread: optional(poisson_spread),
                md_static: md_static.map(|e| format!("{e:.1e}")).unwrap_or_else(|| "–".into()),
            }
        })
        .collect()
}

/// Kept bond fraction below which a central-force network in d = 2 dimensions with bulk
/// coordination z loses rigidity in effective-medium theory: p_c = 2d/z (1/2 for the square
/// lattice with both diagonals, 2/3 triangular); `None` where the intact network is no more
/// than isostatic (z ≤ 4: no diagonals, kagome, honeycomb).
fn rigidity_threshold(l: &crate::spec::LatticeSpec) -> Option<f64> {
    let z = match (l.lattice_type, l.diagonals) {
        (LatticeType::Square, Diagonals::None) => 4.0,
        (LatticeType::Square, Diagonals::Rising | Diagonals::Falling) => 6.0,
        (kind, _) => kind.coordination(),
    };
    (z > 4.0).then(|| 4.0 / z)
}

/// Where [`at_rest`] puts E (Pa), G (Pa) and ν.
const YOUNGS: usize = 0;
const SHEAR: usize = 1;
const POISSON: usize = 2;

/// E, G and ν of a run at rest: MD's, or for a run set to its static answer (`relax.method:
/// static`, no MD) the static answer's, E and G the linear ones where no non-linear one exists
/// or where the load buckled the network (`static_descent_steps` > 0: the buckled state's
/// moduli are the load's, not the network's linear elasticity the ensembles are set against).
fn at_rest(r: &RunRecord) -> [Option<f64>; 3] {
    let l = &r.metrics.lattice;
    match (r.spec.static_only(), l.buckled()) {
        (true, true) => [l.youngs_modulus_linear, l.shear_modulus_linear, None],
        (true, false) => [
            l.youngs_modulus_fem.or(l.youngs_modulus_linear),
            l.shear_modulus_fem.or(l.shear_modulus_linear),
            l.poisson_ratio_fem,
        ],
        (false, _) => [l.youngs_modulus, l.shear_modulus, l.poisson_ratio],
    }
}

/// Mean E and G (± one standard deviation over seeds) of a scene's ensembles against the kept
/// fraction, one series per ensemble label (e.g. each size), with the effective-medium line
/// M(p) = M(1) (p − p_c)/(1 − p_c), p_c = 2d/z ([`rigidity_threshold`]), drawn from the uncut
/// network's mean (or the best-kept ensemble's, scaled, when there is no uncut one). A network
/// that lost its rigidity (status mechanism) has no stiffness and counts as 0.
fn ensemble_figure(ensembles: &[Ensemble], scene: &str) -> anyhow::Result<Option<Figure>> {
    if ensembles.iter().map(|(_, kept, _)| kept.to_bits()).collect::<std::collections::BTreeSet<_>>().len() < 2 {
        return Ok(None);
    }
    let Some(threshold) = ensembles
        .iter()
        .flat_map(|(_, _, members)| members.first())
        .find_map(|r| r.spec.lattice().and_then(rigidity_threshold))
    else {
        return Ok(None);
    };
    let series = ensemble_series(ensembles, threshold);
    if series.is_empty() {
        return Ok(None);
    }
    let chart = Chart {
        title: format!("{scene}: moduli against the kept bond fraction"),
        x_label: "kept fraction p of the interior bonds".into(),
        y_label: "modulus (Pa)".into(),
        scale: Scale::Linear,
    };
    Ok(Some(Figure {
        scene: scene.into(),
        kind: FigureKind::Dilution,
        file: format!("plots/{scene}-dilution.svg"),
        caption: format!(
            "{scene}: {} of randomly diluted lattices (mean over seeds, its error bar ± one \
             standard deviation) against the kept fraction p of the interior bonds, beside the effective-medium line, \
             zero at p = 2d/z = {threshold:.3}. Networks that lost rigidity (status mechanism) count as 0; runs that did \
             not settle are left out.{}",
            match (series.iter().any(|s| s.label.starts_with('E')), series.iter().any(|s| s.label.starts_with('G'))) {
                (true, true) => "Young's and shear moduli",
                (true, false) => "Young's modulus",
                _ => "the shear modulus",
            },
            if ensembles.iter().any(|(_, _, m)| m.iter().any(|r| r.spec.static_only())) {
                " Moduli of the static answer (relax.method: static, no MD)."
            } else {
                ""
            }
        ),
        image: line_chart(&chart, &series)?,
    }))
}

/// The series of [`ensemble_figure`]: per modulus, each ensemble label's mean over seeds against
/// the kept fraction with its spread, and one effective-medium line through the first series
/// that vanishes at `threshold`.
fn ensemble_series(ensembles: &[Ensemble], threshold: f64) -> Vec<Series> {
    // One series per ensemble's grid values but its seeds and its kept fraction (the x axis).
    let series_label = |members: &[&RunRecord]| {
        members[0].spec.varied_in_words(|path| path != "seed" && path != "lattice.cut_fraction")
    };
    // In the campaign's order (sizes 16, 32, 64, 128; not as strings, 128 before 16).
    let mut labels: Vec<String> = Vec::new();
    for (_, _, members) in ensembles {
        let label = series_label(members);
        if !labels.contains(&label) {
            labels.push(label);
        }
    }
    let mut series = Vec::new();
    for (which, name) in [(YOUNGS, "E"), (SHEAR, "G")] {
        let mut with_line = false;
        for label in &labels {
            let mut points: Vec<(f64, f64, f64)> = ensembles
                .iter()
                .filter(|(_, _, members)| series_label(members) == *label)
                .filter_map(|(_, kept, members)| {
                    let values = members.iter().filter_map(|r| match r.status {
                        RunStatus::Mechanism => Some(Some(0.0)),
                        RunStatus::Ok => Some(at_rest(r)[which]),
                        _ => None,
                    });
                    let (mean, spread) = mean_spread(values);
                    mean.map(|m| (*kept, m, spread.unwrap_or(0.0)))
                })
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            points.dedup_by(|a, b| a.0 == b.0);
            if points.iter().all(|p| p.1 == 0.0) {
                continue;
            }
            let of = if label.is_empty() { String::new() } else { format!(" ({label})") };
            series.push(Series {
                label: format!("{name}{of}: mean over seeds ± one standard deviation"),
                points: points.iter().map(|p| (p.0, p.1)).collect(),
                mark: Mark::ErrorBars(points.iter().map(|p| p.2).collect()),
            });
            // One line per modulus, from the first series (the sizes' uncut moduli differ by
            // their edges' O(1/N) only).
            if !with_line {
                let &(best_kept, best, _) = points.last().expect("not empty");
                let full = best / ((best_kept - threshold) / (1.0 - threshold)).max(f64::MIN_POSITIVE);
                series.push(Series {
                    label: format!("{name}: effective medium, zero at p = 2d/z = {threshold:.3}"),
                    points: vec![(threshold, 0.0), (1.0, full)],
                    mark: Mark::Line,
                });
                with_line = true;
            }
        }
    }
    series
}
