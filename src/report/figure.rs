//! What every figure module shares: the drawn [`Figure`], and the runs of a scene grouped as
//! the figures and tables show them (by grid values other than dt, each group with the run
//! that represents it).

use crate::runner::RunRecord;
use crate::sim::RunStatus;

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
