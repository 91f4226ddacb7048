//! What every figure module shares: the drawn [`Figure`], and the runs of a scene grouped as
//! the figures and tables show them (by grid values other than dt, each group with the run
//! that represents it).

use serde::Serialize;

use crate::output::{movie_name, side_by_side_name};
use crate::runner::RunRecord;
use crate::sim::{RelaxMethod, RunStatus};
use crate::spec::RunSpec;

/// A drawn figure.
pub struct Figure {
    /// Scene it belongs to.
    pub scene: String,
    /// Path relative to the campaign directory (`plots/….svg`); `render` gives it the extension
    /// of the drawn image before it is written (`.png` for a heavy figure, `Image::file_name`).
    pub file: String,
    /// Caption, plain text: the report escapes it (no Markdown of its own).
    pub caption: String,
    /// The drawing: SVG, or PNG when heavy.
    pub image: crate::draw::chart::Image,
}

/// A figure or movie as the report shows it: its file and caption.
#[derive(Clone, Serialize)]
pub struct FigureRef {
    /// Path relative to the report.
    pub file: String,
    /// Caption, plain text.
    pub caption: String,
}

/// The movies of a scene: its runs side by side if drawn (the same panels as the runs' own
/// movies, so those are then left out), otherwise each run's own.
pub fn movie_refs(scene: &str, mine: &[&RunRecord], side_by_side: &[String]) -> Vec<FigureRef> {
    let together = side_by_side.iter().any(|s| s == scene);
    let own = mine.iter().filter(|r| !together && r.has_movie());
    together
        .then(|| FigureRef {
            file: side_by_side_name(scene),
            caption: format!("All runs of {scene} side by side, on one colour scale (m/s)."),
        })
        .into_iter()
        .chain(own.map(|r| FigureRef {
            file: movie_name(&r.run_id),
            caption: format!(
                "Movie of {scene} ({}): particles coloured by speed (colour bar in m/s), {}{}; \
                 displacements are drawn to scale unless the frame states a magnification × M.{}",
                r.spec.varied_in_words(|_| true),
                match r.spec.movie {
                    Some(movie) if movie.bond_strain => "bonds coloured by strain (red stretched, blue compressed)",
                    _ => "bonds in grey",
                },
                supports_in_words(&r.spec),
                untimed_in_words(&r.spec),
            ),
        }))
        .collect()
}

/// What the frames of a run with no time show (a minimiser or the static solve): two states,
/// not a motion.
fn untimed_in_words(spec: &RunSpec) -> &'static str {
    match spec.relax().map(|r| r.method) {
        Some(RelaxMethod::Fire | RelaxMethod::Cg) => {
            " The minimiser has no time: two frames, the start and the state it stopped at (captioned)."
        }
        Some(RelaxMethod::Static) => " The static solve has no time: two frames, the start and the static answer.",
        _ => "",
    }
}

/// How a movie draws what holds the scene: a chain's walls, a lattice's held nodes.
fn supports_in_words(spec: &RunSpec) -> &'static str {
    match spec.lattice() {
        None if spec.chain().is_some() => ", the walls at both ends as black bars",
        Some(lattice) if !lattice.supports.holds_nothing() => {
            ", held nodes as black squares (filled: held in x and y, open: held in one axis)"
        }
        _ => "",
    }
}

/// A run relaxed by bond damping γ alone (no background damping).
pub fn bond_damping_only(r: &RunRecord) -> bool {
    r.spec.gamma > 0.0 && r.spec.gamma_background == 0.0
}

/// A run relaxed by background damping γ_g alone (no bond damping).
pub fn background_damping_only(r: &RunRecord) -> bool {
    r.spec.gamma == 0.0 && r.spec.gamma_background > 0.0
}

/// The label of a run's grid values other than the time step: runs with the same group label
/// differ only in dt, so they form one convergence curve.
pub fn group_label(record: &RunRecord) -> String {
    let label = record.spec.varied_in_words(|path| !path.starts_with("time.dt"));
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
