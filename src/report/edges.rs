//! Homogeneity seen: the relaxed displacement profiles of a loaded lattice's edges (the left and
//! right columns' sideways displacement against height, the top row's vertical displacement
//! along x), one representative run per set-up of a scene that compares set-ups (with and
//! without diagonals, or supports). A homogeneous strain makes every profile a straight line.

use super::figure::{Figure, FigureKind};
use crate::draw::chart::{Chart, Mark, Scale, Series, line_chart};
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::spec::{Control, Diagonals, LoadCase};

/// The edge-profile figures of `scene`: its sideways edge profiles, and for tensile runs the top
/// row's; none unless all its lattices are regular, linear and loaded by force, its grid varies
/// the diagonals or the supports (the set-ups the homogeneity finding compares) and some run
/// relaxed with its edges recorded.
pub fn edge_figures(records: &[RunRecord], scene: &str) -> anyhow::Result<Vec<Figure>> {
    let shown = profiled_setups(records, scene);
    if shown.is_empty() {
        return Ok(Vec::new());
    }
    let tensile: Vec<&RunRecord> =
        shown.iter().copied().filter(|r| r.spec.lattice().is_some_and(|l| l.load_case == LoadCase::Tensile)).collect();
    let mut figures = vec![sideways_figure(scene, &shown)?];
    if !tensile.is_empty() {
        figures.push(top_row_figure(scene, &tensile, shown[0].spec.spacing)?);
    }
    Ok(figures)
}

/// The largest relaxed lattice of each set-up of `scene` with its edges recorded; none unless
/// every run of the scene is one homogeneity is judged on and its grid compares set-ups.
fn profiled_setups<'a>(records: &'a [RunRecord], scene: &str) -> Vec<&'a RunRecord> {
    let compares = |r: &RunRecord| r.spec.varied.keys().any(|k| k == "lattice.diagonals" || k == "supports");
    // The regular, linear lattices homogeneity is judged on (a scene with anisotropic or random
    // ones compares those instead), under a force load (a driven top row is flat by construction).
    let regular = |r: &RunRecord| {
        r.spec.law.is_linear()
            && r.spec.lattice().is_some_and(|l| {
                !l.is_random()
                    && l.k_x == l.k_y
                    && !l.rotated
                    && matches!(l.diagonals, Diagonals::None | Diagonals::Both)
                    && l.control == Control::Force
            })
    };
    let runs: Vec<&RunRecord> = records.iter().filter(|r| r.spec.scene == scene && r.status == RunStatus::Ok).collect();
    if !runs.iter().all(|r| regular(r) && compares(r)) {
        return Vec::new();
    }
    let mine: Vec<&RunRecord> = runs.into_iter().filter(|r| r.metrics.lattice.edge_displacements.is_some()).collect();
    largest_per_setup(&mine)
}

/// The left and right edges' sideways displacement against height, one colour per set-up.
fn sideways_figure(scene: &str, shown: &[&RunRecord]) -> anyhow::Result<Figure> {
    let size = |r: &RunRecord| r.spec.lattice().map_or(0, |l| l.nx.max(l.ny));
    let sizes: Vec<String> = shown
        .iter()
        .map(|r| size(r))
        .collect::<std::collections::BTreeSet<_>>()
        .iter()
        .map(|n| format!("{n} × {n}"))
        .collect();
    let spacing = shown[0].spec.spacing;
    // Each set-up one series: its left edge, a break, its right edge.
    let series: Vec<Series> = shown
        .iter()
        .map(|r| {
            let edges = r.metrics.lattice.edge_displacements.as_ref().expect("filtered");
            let profile = |u: &[f64]| -> Vec<(f64, f64)> {
                u.iter().enumerate().map(|(iy, &u)| (u / MICROMETRE, iy as f64 * spacing)).collect()
            };
            let mut points = profile(&edges.left_x);
            points.push((f64::NAN, f64::NAN));
            points.extend(profile(&edges.right_x));
            Series { label: setup_label(r), points, mark: Mark::Line }
        })
        .collect();
    let chart = Chart {
        title: format!("{scene}: sideways displacement of the edges ({})", sizes.join(", ")),
        x_label: "sideways displacement u_x of an edge node (µm)".into(),
        y_label: "height y (m)".into(),
        scale: Scale::Linear,
    };
    Ok(Figure {
        scene: scene.into(),
        kind: FigureKind::Edges,
        file: format!("plots/{scene}-edges.svg"),
        caption: format!(
            "{scene}: the relaxed sideways displacement u_x of the left and right edge nodes (two lines of one \
             colour per set-up) against their height, the largest lattice of each set-up. A homogeneous strain keeps \
             each edge a straight line: upright under tension (u_x = −ν ε x), leaning under shear (u_x = γ y); where \
             a line bends, the supports or the point loads on the top row disturb the strain.{}",
            if shown
                .iter()
                .any(|r| r.spec.lattice().is_some_and(|l| l.lattice_type.is_square() && l.diagonals == Diagonals::None))
            {
                " Without diagonals (ν = 0) the edges do not move sideways under tension: their lines lie on u_x = 0."
            } else {
                ""
            }
        ),
        image: line_chart(&chart, &series)?,
    })
}

/// The loaded top row's vertical displacement along x, one line per tensile set-up, its nodes
/// `spacing` apart.
fn top_row_figure(scene: &str, tensile: &[&RunRecord], spacing: f64) -> anyhow::Result<Figure> {
    let series: Vec<Series> = tensile
        .iter()
        .map(|r| {
            let edges = r.metrics.lattice.edge_displacements.as_ref().expect("filtered");
            Series {
                label: setup_label(r),
                points: edges.top_y.iter().enumerate().map(|(ix, &u)| (ix as f64 * spacing, u / MICROMETRE)).collect(),
                mark: Mark::Line,
            }
        })
        .collect();
    let chart = Chart {
        title: format!("{scene}: vertical displacement of the top row"),
        x_label: "position x along the top row (m)".into(),
        y_label: "vertical displacement u_y (µm)".into(),
        scale: Scale::Linear,
    };
    Ok(Figure {
        scene: scene.into(),
        kind: FigureKind::TopRow,
        file: format!("plots/{scene}-top-row.svg"),
        caption: format!(
            "{scene}: the relaxed vertical displacement u_y of the loaded top row against x, the largest lattice \
             of each set-up under tension. A homogeneous stretch lifts the row flat (u_y = ε L_y everywhere); a \
             bow is the supports' and the free sides' disturbance."
        ),
        image: line_chart(&chart, &series)?,
    })
}

/// 1 µm in m: the edges of a loaded lattice move by micrometres, read best in their unit.
const MICROMETRE: f64 = 1e-6;

/// A run's set-up in words: its grid values but the lattice's size and the time step.
fn setup_label(r: &RunRecord) -> String {
    let label = r.spec.varied_in_words(|path| {
        !path.starts_with("lattice.size") && !path.starts_with("lattice.n") && !path.starts_with("time.dt")
    });
    if label.is_empty() { "all".into() } else { label }
}

/// The run of the largest lattice of each set-up ([`setup_label`]), in campaign order.
fn largest_per_setup<'a>(runs: &[&'a RunRecord]) -> Vec<&'a RunRecord> {
    let size = |r: &RunRecord| r.spec.lattice().map_or(0, |l| l.nx * l.ny);
    let mut chosen: Vec<(String, &RunRecord)> = Vec::new();
    for &r in runs {
        let label = setup_label(r);
        match chosen.iter_mut().find(|(l, _)| *l == label) {
            Some((_, best)) if size(r) > size(best) => *best = r,
            Some(_) => {}
            None => chosen.push((label, r)),
        }
    }
    chosen.into_iter().map(|(_, r)| r).collect()
}
