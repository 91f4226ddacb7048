//! The vocabulary every question's answer is written in: the [`Evidence`] it reads, the
//! [`Answer`] it returns with its [`Verdict`] and [`Table`], the numbered [`Finding`] the report
//! shows, and the small number helpers the sentences and tables share. It sits below the
//! questions (`one_d.rs`, `two_d.rs`, …) so they import it rather than the list that asks them.

use serde::Serialize;
use std::collections::BTreeSet;

use crate::model::{LatticeType, LawSpec};
use crate::report::figure::{Figure, FigureKind, FigureRef, movie_refs};
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::spec::{LatticeSpec, LoadCase, Supports};
use crate::summary::ScalingFit;

// Numbers in sentences: 4 significant digits, plain or scientific as reads best.
pub(super) use crate::report::words::short as sig;
// (a − b)/b when both exist and b ≠ 0.
pub(super) use crate::measure::relative_error as relative;

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
    pub(super) fn of(checks: impl IntoIterator<Item = bool>) -> Verdict {
        if checks.into_iter().all(|ok| ok) { Verdict::Within } else { Verdict::Outside }
    }
}

/// A compact table: a header (units in it) and rows of formatted cells.
#[derive(Serialize)]
pub struct Table {
    pub(super) header: Vec<String>,
    pub(super) rows: Vec<Vec<String>>,
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
    /// Where the question goes on: another campaign's report, with a sentence.
    pub see_also: Option<SeeAlso>,
    /// Within, outside or observed.
    pub verdict: Verdict,
    /// Figures that show it.
    pub figures: Vec<FigureRef>,
    /// Its numbers in one table.
    pub table: Option<Table>,
}

/// A pointer from an item to another campaign that takes its question further: what that
/// campaign does, its file, and its report's page relative to this one (reports side by side
/// under one folder).
#[derive(Clone, Debug, Serialize)]
pub struct SeeAlso {
    /// What the other campaign does and answers, in a sentence.
    pub text: String,
    /// The campaign file that makes it, from the crate's folder.
    pub campaign: &'static str,
    /// Its report's page, relative to this report's folder.
    pub page: &'static str,
    /// Whether that page was there when this report was rendered (it is linked only then).
    pub written: bool,
}

/// A finding before it is numbered: what each question's function returns.
pub(super) struct Answer {
    pub(super) title: &'static str,
    pub(super) question: &'static str,
    pub(super) short: String,
    pub(super) sentences: Vec<String>,
    pub(super) reference: String,
    pub(super) see_also: Option<SeeAlso>,
    pub(super) verdict: Verdict,
    pub(super) figures: Vec<FigureRef>,
    pub(super) table: Option<Table>,
}

impl Answer {
    /// The finding this answer is at position `number` of the report, its anchor the slug of
    /// its numbered heading.
    pub(super) fn numbered(self, number: usize) -> Finding {
        Finding {
            number,
            id: crate::report::page::slug(&format!("{number}. {}", self.title)),
            title: self.title,
            question: self.question,
            short: self.short,
            sentences: self.sentences,
            reference: self.reference,
            see_also: self.see_also,
            verdict: self.verdict,
            figures: self.figures,
            table: self.table,
        }
    }
}

/// What the questions read: the records, the scaling fits and the drawn figures.
#[derive(Clone)]
pub struct Evidence<'a> {
    pub(super) records: Vec<&'a RunRecord>,
    pub(super) fits: &'a [ScalingFit],
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
    pub(super) fn coursework(&self) -> Evidence<'a> {
        let square_md = |r: &RunRecord| {
            r.spec.lattice().is_none_or(|l| l.lattice_type == LatticeType::Square && !r.spec.static_only())
        };
        Evidence { records: self.records.iter().copied().filter(|r| square_md(r)).collect(), ..self.clone() }
    }

    /// The evidence a study's campaign answers coursework items from beside its own questions:
    /// its runs that are no lattice (pairs, chains, packings), whose items no study question
    /// asks; its lattices answer the study's.
    pub(super) fn beside_study(&self) -> Evidence<'a> {
        Evidence {
            records: self.records.iter().copied().filter(|r| r.spec.lattice().is_none()).collect(),
            ..self.clone()
        }
    }

    /// The movies of the runs `keep` selects: per scene, its side-by-side movie if drawn, and
    /// each run's own.
    pub(super) fn movies(&self, keep: impl Fn(&RunRecord) -> bool) -> Vec<FigureRef> {
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
    pub(super) fn ok(&self, keep: impl Fn(&RunRecord) -> bool) -> Vec<&'a RunRecord> {
        self.records.iter().copied().filter(|r| r.status == RunStatus::Ok && keep(r)).collect()
    }

    /// The runs of any status that `keep` selects.
    pub(super) fn all(&self, keep: impl Fn(&RunRecord) -> bool) -> Vec<&'a RunRecord> {
        self.records.iter().copied().filter(|r| keep(r)).collect()
    }

    /// The first figure of `scene` that shows `kind`.
    pub(super) fn figure(&self, scene: &str, kind: FigureKind) -> Option<FigureRef> {
        self.figures.iter().find(|f| f.scene == scene && f.kind == kind).map(Figure::reference)
    }

    /// True when a figure of `kind` was drawn for any scene.
    pub(super) fn has_figure(&self, kind: FigureKind) -> bool {
        self.figures.iter().any(|f| f.kind == kind)
    }

    /// The figures `(scene, kind)` that were drawn, in the order asked.
    pub(super) fn figures(&self, wanted: &[(&str, FigureKind)]) -> Vec<FigureRef> {
        wanted.iter().filter_map(|&(scene, kind)| self.figure(scene, kind)).collect()
    }

    /// The scaling fit of `quantity` in `scene`, if the scene swept its variable.
    pub(super) fn fit(&self, scene: &str, quantity: &str) -> Option<&'a ScalingFit> {
        self.fits.iter().find(|f| f.scene == scene && f.quantity == quantity)
    }
}

/// A relative error as a signed number with 2 digits (`+1.6e-4`).
pub fn rel(e: f64) -> String {
    crate::report::words::minus_sign(format!("{e:+.1e}"))
}

/// The spring laws' exponents β among `runs` (1 for linear springs), rising, each once.
pub(super) fn exponents<'a>(runs: impl IntoIterator<Item = &'a RunRecord>) -> Vec<f64> {
    distinct_exponents(runs.into_iter().map(|r| r.spec.law.beta()))
}

/// The exponents β among `betas`, rising, each once.
pub(super) fn distinct_exponents(betas: impl IntoIterator<Item = f64>) -> Vec<f64> {
    let mut betas: Vec<f64> = betas.into_iter().collect();
    betas.sort_by(f64::total_cmp);
    betas.dedup();
    betas
}

/// A loaded (not kicked), regular, linear lattice: the coursework's moduli runs.
pub(super) fn regular(r: &RunRecord) -> Option<&LatticeSpec> {
    r.spec.lattice().filter(|l| {
        l.impulse.is_none() && !l.is_random() && l.k_x == l.k_y && !l.rotated && r.spec.law == LawSpec::Linear
    })
}

/// The modulus a loaded lattice run measures, named for what it is: E in tension, G in shear
/// on a periodic strip (homogeneous shear), and on other supports the whole block's apparent G,
/// which the supports bend (item 16: 0.40 of k_d/d on the 40 × 40 coursework supports).
pub(super) fn modulus_name(l: &LatticeSpec) -> String {
    match l.load_case {
        LoadCase::Shear if !l.supports.periodic_x() => format!("apparent G ({} supports)", l.supports.name()),
        LoadCase::Shear => "G".into(),
        LoadCase::Tensile | LoadCase::TensileX => "E".into(),
    }
}

/// What the shear runs among `runs` measure ([`modulus_name`]), each name once (`G / apparent G
/// (coursework supports)` where they stand on both); G when there are none.
pub(super) fn shear_name(runs: &[&RunRecord]) -> String {
    let names: BTreeSet<String> = runs
        .iter()
        .filter_map(|r| r.spec.lattice())
        .filter(|l| l.load_case == LoadCase::Shear)
        .map(modulus_name)
        .collect();
    if names.is_empty() { "G".into() } else { names.into_iter().collect::<Vec<_>>().join(" / ") }
}

/// A lattice run's size, then whether it stands on the coursework's supports: the key that
/// picks the largest block, on those supports where there is a choice ((0, false) off a lattice).
pub(super) fn size_on_coursework_supports(r: &RunRecord) -> (usize, bool) {
    r.spec.lattice().map_or((0, false), |l| (l.nx, l.supports == Supports::Coursework))
}

/// The shortest dissipation time (s) among `runs`; infinite when none relaxed.
pub(super) fn fastest_relaxation(runs: &[&RunRecord]) -> f64 {
    runs.iter().filter_map(|r| r.metrics.dissipation_time).fold(f64::INFINITY, f64::min)
}

/// The smallest and largest of a list of numbers, for the findings' ranges.
pub(super) use crate::measure::extremes;

/// A lattice run's size in words (`40 × 40`); empty off a lattice.
pub(super) fn lattice_size(r: &RunRecord) -> String {
    r.spec.lattice().map(|l| format!("{} × {}", l.nx, l.ny)).unwrap_or_default()
}

/// `x` when present, a dash otherwise.
pub(super) fn cell(x: Option<f64>) -> String {
    x.map(sig).unwrap_or_else(|| "–".into())
}

/// `x` as [`cell`] writes it, or 0 when it is below the result's precision: round-off of a
/// quantity whose scale is `scale` (a Poisson ratio of 3e-13 is 0).
pub(super) fn noise(x: Option<f64>, scale: f64) -> String {
    match x {
        Some(v) if v.abs() < 1e-9 * scale => "0".into(),
        other => cell(other),
    }
}

/// `x ± u` with the uncertainty's two significant digits setting the value's last, both on one
/// power of ten (`(2.6650 ± 0.0090)e11`, `0.3330 ± 0.0011`); `x` alone when there is no
/// uncertainty to state.
pub(super) fn plus_minus(x: f64, u: f64) -> String {
    // An uncertainty below 1e-9 of the value is round-off (samples that are one state), no spread.
    if !(u > 1e-9 * x.abs() && u.is_finite() && x.is_finite() && x != 0.0) {
        return sig(x);
    }
    let magnitude = x.abs().log10().floor() as i32;
    let power = if (-3..5).contains(&magnitude) { 0 } else { magnitude };
    let (x, u) = (x / 10f64.powi(power), u / 10f64.powi(power));
    let decimals = (1 - u.log10().floor() as i32).clamp(0, 8) as usize;
    let x = crate::report::words::minus_sign(format!("{x:.decimals$}"));
    if power == 0 { format!("{x} ± {u:.decimals$}") } else { format!("({x} ± {u:.decimals$})e{power}") }
}

/// Signed numbers and per cents, as the whole report writes them.
pub(super) use crate::report::words::{percent, signed};

/// A run's wave threshold θ, the fraction of the source's peak its threshold criteria wait
/// for, in per cent (`wave.threshold`, 0.01 unless the scene sets it).
pub(super) fn threshold_percent(r: &RunRecord) -> String {
    r.spec.wave().map_or_else(|| "–".into(), |w| format!("{} %", crate::report::words::number(100.0 * w.threshold)))
}

/// The exponent springs s ∝ δ^β predict for a fitted quantity against its variable (β its
/// group's, [`ScalingFit::beta`]): the solitary wave's speed ∝ v0^((β−1)/(β+1)) (Nesterenko),
/// moduli ∝ F^((β−1)/β) and a chain's stiffness ∝ |ΔW|^(β−1), since s′ ∝ δ^(β−1) and F ∝ δ^β.
/// Hertz (β = 3/2): 1/5, 1/3 and 1/2; linear (β = 1): 0.
pub(super) fn predicted_exponent(fit: &ScalingFit) -> Option<f64> {
    crate::summary::predicted(fit.quantity, fit.against, fit.beta).map(|(exponent, _)| exponent)
}

/// A non-linear front's speed fitted against the kick v0 (a chain's or a kicked lattice's),
/// with the exponent (β − 1)/(β + 1) Nesterenko's solitary wave has for its group's springs
/// s ∝ δ^β: its overlap δ_max ∝ v0^(2/(β+1)) sets the stiffness s′ ∝ δ^(β−1), and c ∝ √(s′/m).
pub(super) struct SolitaryFront<'a> {
    pub(super) fit: &'a ScalingFit,
    pub(super) predicted: f64,
}

impl<'a> SolitaryFront<'a> {
    /// The front of `fit`, a speed against v0; `None` for another fit.
    pub(super) fn of(fit: &'a ScalingFit) -> Option<SolitaryFront<'a>> {
        (fit.quantity == "sound_speed" && fit.against == "v0")
            .then(|| Some(SolitaryFront { fit, predicted: predicted_exponent(fit)? }))
            .flatten()
    }

    /// The non-linear fronts of `e`'s fits, in campaign order (a chain whose walls pre-load its
    /// springs has none: the summary fits no speed against v0 for it).
    pub(super) fn all<'e>(e: &Evidence<'e>) -> impl Iterator<Item = SolitaryFront<'e>> {
        e.fits.iter().filter(|f| f.law != "linear").filter_map(SolitaryFront::of)
    }

    /// The first kicked power-law lattice's front and the chain's front told beside it (the
    /// first of another scene), for the item "A Hertz lattice kicked at several speeds".
    pub(super) fn kicked_lattice<'e>(e: &Evidence<'e>) -> Option<(SolitaryFront<'e>, Option<SolitaryFront<'e>>)> {
        let kicked = Self::all(e).find(|f| f.of_lattice(e))?;
        let beside = Self::all(e).find(|f| f.fit.scene != kicked.fit.scene);
        Some((kicked, beside))
    }

    /// Whether its scene is a kicked lattice's (else a hit chain's: the two kinds whose speed is
    /// fitted against v0).
    pub(super) fn of_lattice(&self, e: &Evidence) -> bool {
        e.records.iter().any(|r| r.spec.scene == self.fit.scene && r.spec.lattice().is_some())
    }

    /// Whether its exponent lies within [`EXPONENT_TOLERANCE`] of the prediction.
    pub(super) fn within(&self) -> bool {
        (self.fit.fit.exponent - self.predicted).abs() <= EXPONENT_TOLERANCE
    }

    /// "Hertz" or "power-law (β = 2)", mid-sentence.
    pub(super) fn name(&self) -> String {
        crate::report::kinds::law_name(LawSpec::Power { beta: self.fit.beta }).replacen("Power", "power", 1)
    }

    /// "against Nesterenko's (β − 1)/(β + 1) = 0.333 for β = 2, within 0.05".
    pub(super) fn against_prediction(&self) -> String {
        format!(
            "against Nesterenko's (β − 1)/(β + 1) = {:.3} for β = {}, {} {EXPONENT_TOLERANCE}",
            self.predicted,
            crate::report::words::number(self.fit.beta),
            if self.within() { "within" } else { "outside" }
        )
    }
}

/// The run nearest dt = t_c/50 among `runs`, preferring the coursework's position Verlet.
pub(super) fn at_50<'a>(runs: &[&'a RunRecord]) -> Option<&'a RunRecord> {
    let verlet: Vec<&RunRecord> =
        runs.iter().copied().filter(|r| r.spec.integrator == crate::sim::IntegratorKind::PositionVerlet).collect();
    let pool = if verlet.is_empty() { runs } else { &verlet[..] };
    (!pool.is_empty()).then(|| crate::report::figure::representative(pool))
}

/// How close a fitted exponent must come to its prediction: three to four points over two or
/// three decades fix it to a few hundredths. One tolerance for every scaling law of the report
/// (the abstract, item 20 and this table say the same).
pub(super) const EXPONENT_TOLERANCE: f64 = 0.05;
