//! The coursework's questions (`../shared/coursework.md`) answered from a campaign's results:
//! for each item a finding in sentences with this campaign's numbers, the reference it is held
//! against with its tolerance, a verdict, the figures that show it and a compact table. Every
//! number is read from the records at render time; an item whose runs the campaign lacks is
//! left out.

mod discussion;
mod dynamics;
mod materials;
mod one_d;
mod relaxation;
mod two_d;
mod types;

use serde::Serialize;

use super::figure::{Figure, FigureRef, movie_refs};
// Numbers in sentences: 4 significant digits, plain or scientific as reads best.
use super::words::short as sig;
// (a − b)/b when both exist and b ≠ 0.
use crate::measure::relative_error as relative;
use crate::model::LatticeType;
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::summary::ScalingFit;

pub use self::discussion::{Paragraph, discussion};

/// How a finding stands against its reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Every compared number within its tolerance.
    Within,
    /// At least one outside; the finding says why.
    Outside,
    /// Nothing to hold it against: an observation (a movie, a trend).
    Observed,
}

impl Verdict {
    /// Within when every check holds, outside otherwise.
    fn of(checks: impl IntoIterator<Item = bool>) -> Verdict {
        if checks.into_iter().all(|ok| ok) { Verdict::Within } else { Verdict::Outside }
    }
}

/// A compact table: a header (units in it) and rows of formatted cells.
#[derive(Serialize)]
pub struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

/// One coursework item answered.
#[derive(Serialize)]
pub struct Finding {
    /// Position in the report (1, 2, ...), set when the list is made.
    pub number: usize,
    /// The heading's anchor: the slug of its text.
    pub id: String,
    /// Short title.
    pub title: &'static str,
    /// The coursework's question in one line.
    pub question: &'static str,
    /// The answer in a few words with its number, for the summary.
    pub short: String,
    /// The answer in sentences with this campaign's numbers.
    pub sentences: Vec<String>,
    /// What it is held against, with the tolerance and why.
    pub reference: String,
    /// Within, outside or observed.
    pub verdict: Verdict,
    /// Figures that show it.
    pub figures: Vec<FigureRef>,
    /// Its numbers in one table.
    pub table: Option<Table>,
}

/// A finding before it is numbered: what each question's function returns.
struct Answer {
    title: &'static str,
    question: &'static str,
    short: String,
    sentences: Vec<String>,
    reference: String,
    verdict: Verdict,
    figures: Vec<FigureRef>,
    table: Option<Table>,
}

/// What the questions read: the records, the scaling fits and the drawn figures.
#[derive(Clone)]
pub struct Evidence<'a> {
    records: Vec<&'a RunRecord>,
    fits: &'a [ScalingFit],
    figures: &'a [Figure],
    side_by_side: &'a [String],
}

impl<'a> Evidence<'a> {
    /// The evidence of one report.
    pub fn new(
        records: &'a [RunRecord],
        fits: &'a [ScalingFit],
        figures: &'a [Figure],
        side_by_side: &'a [String],
    ) -> Self {
        Evidence { records: records.iter().collect(), fits, figures, side_by_side }
    }

    /// The evidence the coursework's own questions are answered from: its questions are about
    /// the square lattice, with or without diagonals, relaxed by MD, so lattices of another
    /// type and runs set to their static answer (`relax.method: static`) are left to the
    /// lattice-type questions.
    fn coursework(&self) -> Evidence<'a> {
        let square_md = |r: &RunRecord| {
            r.spec.lattice().is_none_or(|l| l.lattice_type == LatticeType::Square && !r.spec.static_only())
        };
        Evidence { records: self.records.iter().copied().filter(|r| square_md(r)).collect(), ..self.clone() }
    }

    /// The movies of the runs `keep` selects: per scene, its side-by-side movie if drawn, and
    /// each run's own.
    fn movies(&self, keep: impl Fn(&RunRecord) -> bool) -> Vec<FigureRef> {
        let chosen = self.all(keep);
        let mut scenes: Vec<&str> = chosen.iter().map(|r| r.spec.scene.as_str()).collect();
        scenes.dedup();
        scenes
            .into_iter()
            .flat_map(|scene| {
                let mine: Vec<&RunRecord> = chosen.iter().copied().filter(|r| r.spec.scene == scene).collect();
                movie_refs(scene, &mine, self.side_by_side)
            })
            .collect()
    }

    /// The `ok` runs that `keep` selects, in campaign order.
    fn ok(&self, keep: impl Fn(&RunRecord) -> bool) -> Vec<&'a RunRecord> {
        self.records.iter().copied().filter(|r| r.status == RunStatus::Ok && keep(r)).collect()
    }

    /// The runs of any status that `keep` selects.
    fn all(&self, keep: impl Fn(&RunRecord) -> bool) -> Vec<&'a RunRecord> {
        self.records.iter().copied().filter(|r| keep(r)).collect()
    }

    /// The first figure of `scene` whose file name contains `part`.
    fn figure(&self, scene: &str, part: &str) -> Option<FigureRef> {
        self.figures
            .iter()
            .find(|f| f.scene == scene && f.file.contains(part))
            .map(|f| FigureRef { file: f.file.clone(), caption: f.caption.clone() })
    }

    /// The scaling fit of `quantity` in `scene`, if the scene swept its variable.
    fn fit(&self, scene: &str, quantity: &str) -> Option<&'a ScalingFit> {
        self.fits.iter().find(|f| f.scene == scene && f.quantity == quantity)
    }
}

/// One item's answer from the evidence it is asked of, if that has its runs.
type Question = fn(&Evidence) -> Option<Answer>;

/// The coursework's items that `evidence` answers, in the coursework's order, numbered.
pub fn findings(evidence: &Evidence) -> Vec<Finding> {
    // The coursework's questions see its evidence ([`Evidence::coursework`]); the lattice
    // types' see every run.
    let coursework = evidence.coursework();
    let asked: [(Question, &Evidence); 26] = [
        (one_d::two_particles, &coursework),
        (one_d::time_step, &coursework),
        (one_d::chain, &coursework),
        (one_d::hertz_pair_and_chain, &coursework),
        (one_d::walls, &coursework),
        (two_d::units_and_time_step, &coursework),
        (two_d::diagonal_stiffness, &coursework),
        (two_d::lattice_time_step, &coursework),
        (two_d::kick, &coursework),
        (two_d::youngs_and_poisson, &coursework),
        (two_d::shear, &coursework),
        (dynamics::sound_speed, &coursework),
        (dynamics::dissipation, &coursework),
        (materials::homogeneity, &coursework),
        (materials::hertz_moduli, &coursework),
        (dynamics::hertz_kick, &coursework),
        (materials::anisotropic, &coursework),
        (materials::random, &coursework),
        (materials::md_and_fem, &coursework),
        (relaxation::time_to_modulus, evidence),
        (types::moduli, evidence),
        (types::isotropy, evidence),
        (types::directions, evidence),
        (types::percolation, evidence),
        (types::waves, evidence),
        (discussion::linear_and_hertz, &coursework),
    ];
    asked
        .iter()
        .filter_map(|(question, evidence)| question(evidence))
        .enumerate()
        .map(|(i, a)| {
            let number = i + 1;
            Finding {
                number,
                id: super::page::slug(&format!("{number}. {}", a.title)),
                title: a.title,
                question: a.question,
                short: a.short,
                sentences: a.sentences,
                reference: a.reference,
                verdict: a.verdict,
                figures: a.figures,
                table: a.table,
            }
        })
        .collect()
}

/// A relative error as a signed number with 2 digits (`+1.6e-4`).
pub fn rel(e: f64) -> String {
    format!("{e:+.1e}")
}

/// The shortest dissipation time (s) among `runs`; infinite when none relaxed.
fn fastest_relaxation(runs: &[&RunRecord]) -> f64 {
    runs.iter().filter_map(|r| r.metrics.dissipation_time).fold(f64::INFINITY, f64::min)
}

/// The smallest and largest of `values` (∞ and −∞ when there are none).
fn extremes(values: &[f64]) -> (f64, f64) {
    values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), &x| (low.min(x), high.max(x)))
}

/// `x` when present, a dash otherwise.
fn cell(x: Option<f64>) -> String {
    x.map(sig).unwrap_or_else(|| "–".into())
}

/// `x` as [`cell`] writes it, or 0 when it is below the result's precision: round-off of a
/// quantity whose scale is `scale` (a Poisson ratio of 3e-13 is 0).
fn noise(x: Option<f64>, scale: f64) -> String {
    match x {
        Some(v) if v.abs() < 1e-9 * scale => "0".into(),
        other => cell(other),
    }
}
