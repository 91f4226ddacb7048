//! What every figure module shares: the drawn [`Figure`], and the runs of a scene grouped as
//! the figures and tables show them (by grid values other than dt, each group with the run
//! that represents it).

use serde::Serialize;

use crate::runner::RunRecord;
use crate::sim::RunStatus;

/// A drawn figure.
pub struct Figure {
    /// Scene it belongs to.
    pub scene: String,
    /// Path relative to the campaign directory (`plots/…svg`).
    pub file: String,
    /// Caption, plain text: the report escapes it (no Markdown of its own).
    pub caption: String,
    /// The SVG document.
    pub svg: String,
}

/// A figure or movie as the report shows it: its file and caption.
#[derive(Clone, Serialize)]
pub struct FigureRef {
    /// Path relative to the report.
    pub file: String,
    /// Caption, plain text.
    pub caption: String,
}

/// The movies of a scene: its runs side by side, if drawn, then each run's own.
pub fn movie_refs(scene: &str, mine: &[&RunRecord], side_by_side: &[String]) -> Vec<FigureRef> {
    side_by_side
        .iter()
        .filter(|s| *s == scene)
        .map(|_| FigureRef {
            file: format!("plots/{scene}-side-by-side.gif"),
            caption: format!("All runs of {scene} side by side, on one colour scale (m/s)."),
        })
        .chain(mine.iter().filter(|r| r.spec.movie.is_some() && r.status != RunStatus::Panicked).map(|r| FigureRef {
            file: format!("runs/{}.gif", r.run_id),
            caption: format!(
                "Movie of {scene} ({}): particles coloured by speed (colour bar in m/s), {}.",
                r.spec.varied_label(|_| true),
                match r.spec.movie {
                    Some(movie) if movie.bond_strain => "bonds coloured by strain (red stretched, blue compressed)",
                    _ => "bonds in grey",
                }
            ),
        }))
        .collect()
}

/// The label of a run's grid values other than the time step: runs with the same group label
/// differ only in dt, so they form one convergence curve.
pub fn group_label(record: &RunRecord) -> String {
    let label = record.spec.varied_label(|path| !path.starts_with("time.dt"));
    if label.is_empty() { "all".into() } else { label }
}

/// The runs of `scene` that are `ok`, grouped by [`group_label`] in campaign order.
pub fn groups<'a>(records: &'a [RunRecord], scene: &str) -> Vec<(String, Vec<&'a RunRecord>)> {
    let mut groups: Vec<(String, Vec<&RunRecord>)> = Vec::new();
    for record in records.iter().filter(|r| r.spec.scene == scene && r.status == RunStatus::Ok) {
        let label = group_label(record);
        match groups.iter_mut().find(|(l, _)| *l == label) {
            Some((_, members)) => members.push(record),
            None => groups.push((label, vec![record])),
        }
    }
    groups
}

/// The run of a group whose dt is closest to t_c/50 (the coursework's choice).
pub fn representative<'a>(members: &[&'a RunRecord]) -> &'a RunRecord {
    let distance = |r: &&RunRecord| (r.spec.dt_per_tc().ln() - 50f64.ln()).abs();
    members.iter().copied().min_by(|a, b| distance(a).total_cmp(&distance(b))).expect("groups are never empty")
}
