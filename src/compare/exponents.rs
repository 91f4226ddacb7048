//! The exponents of a comparison: every fit of either side's `summary.csv`, matched on scene,
//! group and quantity, each set against the exponent its spring law predicts, in sentences, in
//! a compact table and in full (with R²) for the appendix.

use serde::Serialize;

use super::table::{Side, Table};
use super::words::{exponent, fixed};
use crate::summary::{jamming, predicted};

/// The columns a `summary.csv` row is identified by. `law` is not among them: comparing a linear
/// campaign with its Hertz twin means comparing fits of different laws.
const SUMMARY_KEYS: [&str; 3] = ["scene", "group", "quantity"];

/// How far a fitted exponent of an amplitude sweep may lie from its law's and still agree: 0.01,
/// 2 % of the largest predicted exponent (1/2), and above a fit's error over 2–3 decades of
/// clean power law (the campaigns fit within 3e-4).
const TOLERANCE: f64 = 0.01;

/// How far a fit against `against` may lie from its law's: [`TOLERANCE`], and for a packing's
/// scaling near jamming the item Jamming's ([`jamming::EXPONENT_TOLERANCE`]: its Δφ is uncertain
/// and the theory leaves out the corrections to scaling).
fn tolerance(against: &str) -> f64 {
    if jamming::is_fitted_against(against) { jamming::EXPONENT_TOLERANCE } else { TOLERANCE }
}

/// One side's fit.
struct Fit {
    law: String,
    /// The springs' exponent β of the fit's runs (1 for linear): `summary.csv`'s `beta`, or
    /// [`older_beta`].
    beta: Option<f64>,
    exponent: f64,
    r_squared: f64,
    /// Points the line went through (`summary.csv`'s `points`): through two, R² = 1 by
    /// construction and says nothing of the fit.
    points: Option<f64>,
    /// Particles of the fit's runs (`summary.csv`'s `particles`; none in an older one).
    particles: Option<f64>,
    /// Whether the verdict holds it against its law: every fit but a packing's scaling at a
    /// smaller N than its scene's largest of that law ([`judge_largest_packings`]).
    judged: bool,
}

/// A fitted quantity with the fits of A and B (either may be missing).
struct Matched {
    scene: String,
    group: String,
    quantity: String,
    against: String,
    a: Option<Fit>,
    b: Option<Fit>,
}

/// A fit's law in words (`linear`, `β = 1.5`) and its prediction (`0.2000 = (β−1)/(β+1)`).
fn law_words(fit: &Fit, (quantity, against): (&str, &str)) -> (String, String) {
    let Some(beta) = fit.beta else { return (fit.law.clone(), "–".into()) };
    let law = if beta == 1.0 { "linear".to_string() } else { format!("β = {beta}") };
    let prediction = match predicted(quantity, against, beta) {
        Some((p, _)) if beta == 1.0 => exponent(p, 4),
        Some((p, formula)) => format!("{} = {formula}", exponent(p, 4)),
        None => "–".into(),
    };
    (law, prediction)
}

impl Fit {
    /// The fit's R² for the table, or a dash and the point count through two points.
    fn r_squared_words(&self) -> String {
        match self.points {
            Some(points) if points <= 2.0 => format!("– ({points} points)"),
            _ => fixed(Some(self.r_squared)),
        }
    }

    /// |fitted − predicted|, where the law predicts one.
    fn miss(&self, (quantity, against): (&str, &str)) -> Option<f64> {
        predicted(quantity, against, self.beta?).map(|(p, _)| (self.exponent - p).abs())
    }
}

/// A row of the full exponent table (appendix).
#[derive(Serialize)]
pub(super) struct ExponentRow {
    scene: String,
    group: String,
    quantity: String,
    law_a: String,
    law_b: String,
    exponent_a: String,
    exponent_b: String,
    difference: String,
    r_squared_a: String,
    r_squared_b: String,
}

/// A row of the compact table: each side's exponent beside its law's.
#[derive(Serialize)]
pub(super) struct LawRow {
    scene: String,
    quantity: String,
    law_a: String,
    exponent_a: String,
    predicted_a: String,
    law_b: String,
    exponent_b: String,
    predicted_b: String,
}

/// The exponents of a comparison, as the report shows them.
#[derive(Serialize, Default)]
pub(super) struct Exponents {
    /// What they say, with their numbers.
    pub(super) sentences: Vec<String>,
    pub(super) laws: Vec<LawRow>,
    /// The full table, for the appendix.
    pub(super) rows: Vec<ExponentRow>,
    /// The `summary.csv` files that do not exist (then no exponent is compared).
    pub(super) missing: Vec<String>,
    /// Whether some fits are over an amplitude (speed, load, walls), and whether some are a
    /// packing's near jamming: the laws the report explains.
    pub(super) sweeps: bool,
    pub(super) packings: bool,
}

/// The exponents of both `summary.csv` files, matched on [`SUMMARY_KEYS`] (a fit without a
/// partner shows – on the other side), or the missing `summary.csv` files (the template names
/// them; paths are data, escaped there).
pub(super) fn exponents(a: &Side, b: &Side) -> anyhow::Result<Exponents> {
    let (Some(sa), Some(sb)) = (&a.summary, &b.summary) else {
        let missing = [a, b]
            .iter()
            .filter(|side| side.summary.is_none())
            .map(|side| side.summary_path().display().to_string())
            .collect();
        return Ok(Exponents { missing, ..Exponents::default() });
    };
    let (mut fa, mut fb) = (fits(a, sa)?, fits(b, sb)?);
    judge_largest_packings(&mut fa);
    judge_largest_packings(&mut fb);
    let mut fb: Vec<Option<([String; 3], String, Fit)>> = fb.into_iter().map(Some).collect();
    let mut matched = Vec::new();
    for (keys, against, fit) in fa {
        let partner = fb.iter_mut().find(|f| f.as_ref().is_some_and(|(k, _, _)| *k == keys)).and_then(Option::take);
        matched.push(Matched::new(keys, against, Some(fit), partner.map(|p| p.2)));
    }
    matched.extend(fb.into_iter().flatten().map(|(keys, against, fit)| Matched::new(keys, against, None, Some(fit))));
    let near_jamming = |m: &Matched| jamming::is_fitted_against(&m.against);
    Ok(Exponents {
        sentences: sentences(&matched),
        laws: matched.iter().map(Matched::law_row).collect(),
        rows: matched.iter().map(Matched::row).collect(),
        missing: Vec::new(),
        sweeps: !matched.iter().all(near_jamming),
        packings: matched.iter().any(near_jamming),
    })
}

/// The fits of one `summary.csv` that have an exponent: their keys ([`SUMMARY_KEYS`]), what
/// they are fitted against, and the fit.
fn fits(side: &Side, summary: &Table) -> anyhow::Result<Vec<([String; 3], String, Fit)>> {
    let text = |name: &str, row: usize| summary.column(name).and_then(|c| c.key(row)).unwrap_or_default();
    let (exponent, r_squared) = (summary.require("exponent")?, summary.require("r_squared")?);
    Ok((0..summary.height)
        .filter_map(|row| {
            let keys = SUMMARY_KEYS.map(|k| text(k, row));
            let law = text("law", row);
            let fit = Fit {
                beta: match summary.column("beta") {
                    Some(betas) => betas.number(row),
                    None => older_beta(side, &keys, &law),
                },
                law,
                exponent: exponent.number(row)?,
                r_squared: r_squared.number(row).unwrap_or(f64::NAN),
                points: summary.column("points").and_then(|c| c.number(row)),
                particles: summary.column("particles").and_then(|c| c.number(row)),
                judged: true,
            };
            Some((keys, text("against", row), fit))
        })
        .collect())
}

/// Leaves a packing's scalings at every N but its scene's largest (per β) out of the verdict,
/// as the report's item Jamming judges them: at small N the finite size bends them beyond the
/// tolerance ([`jamming::EXPONENT_TOLERANCE`]). Fits without a particle count stay judged.
fn judge_largest_packings(fits: &mut [([String; 3], String, Fit)]) {
    let largest = |fits: &[([String; 3], String, Fit)], scene: &str, beta: Option<f64>| {
        fits.iter()
            .filter(|(keys, against, fit)| keys[0] == scene && jamming::is_fitted_against(against) && fit.beta == beta)
            .filter_map(|(_, _, fit)| fit.particles)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    for k in 0..fits.len() {
        let (keys, against, fit) = &fits[k];
        if let (true, Some(n)) = (jamming::is_fitted_against(against), fit.particles) {
            fits[k].2.judged = n == largest(fits, &keys[0], fit.beta);
        }
    }
}

/// The springs' β of a fit of a `summary.csv` written by an older mdsolids, without the `beta`
/// column: its group label's `beta=` where the grid varies β, 1 for linear springs (`law`),
/// else the one β of its scene's runs in the results table, `None` where they have several
/// (`law=hertz` or `power` does not say β: a power law takes the campaign's).
fn older_beta(side: &Side, [scene, group, _]: &[String; 3], law: &str) -> Option<f64> {
    let labelled = group.split(", ").find_map(|part| part.strip_prefix("beta=")).and_then(|b| b.parse().ok());
    if let Some(beta) = labelled.or((law == "linear").then_some(1.0)) {
        return Some(beta);
    }
    let (scenes, betas) = (side.results.column("scene")?, side.results.column("beta")?);
    let mut values = (0..side.results.height)
        .filter(|&r| scenes.key(r).as_deref() == Some(scene.as_str()))
        .filter_map(|r| betas.number(r));
    let first = values.next()?;
    values.all(|beta| beta == first).then_some(first)
}

impl Matched {
    fn new([scene, group, quantity]: [String; 3], against: String, a: Option<Fit>, b: Option<Fit>) -> Matched {
        Matched { scene, group, quantity, against, a, b }
    }

    /// The scene, with the group's grid values where there are some.
    fn scene_words(&self) -> String {
        if self.group.is_empty() { self.scene.clone() } else { format!("{} ({})", self.scene, self.group) }
    }

    fn law_row(&self) -> LawRow {
        let side = |fit: &Option<Fit>| match fit {
            Some(fit) => {
                let (law, prediction) = law_words(fit, (&self.quantity, &self.against));
                (law, exponent(fit.exponent, 4), prediction)
            }
            None => ("–".into(), "–".into(), "–".into()),
        };
        let ((law_a, exponent_a, predicted_a), (law_b, exponent_b, predicted_b)) = (side(&self.a), side(&self.b));
        LawRow {
            scene: self.scene_words(),
            quantity: format!("{} ∝ {}^p", self.quantity, self.against),
            law_a,
            exponent_a,
            predicted_a,
            law_b,
            exponent_b,
            predicted_b,
        }
    }

    fn row(&self) -> ExponentRow {
        let (a, b) = (self.a.as_ref(), self.b.as_ref());
        let law = |fit: Option<&Fit>| fit.map_or_else(|| "–".into(), |f| f.law.clone());
        ExponentRow {
            scene: self.scene.clone(),
            group: self.group.clone(),
            quantity: self.quantity.clone(),
            law_a: law(a),
            law_b: law(b),
            exponent_a: fixed(a.map(|f| f.exponent)),
            exponent_b: fixed(b.map(|f| f.exponent)),
            difference: fixed(a.zip(b).map(|(a, b)| b.exponent - a.exponent)),
            r_squared_a: a.map_or_else(|| fixed(None), Fit::r_squared_words),
            r_squared_b: b.map_or_else(|| fixed(None), Fit::r_squared_words),
        }
    }

    /// One side's fit in words: `p = 0.2000 (β = 1.5, predicted 0.2000 = (β−1)/(β+1))`.
    fn fit_words(&self, fit: &Fit) -> String {
        let (law, prediction) = law_words(fit, (&self.quantity, &self.against));
        format!("p = {} ({law}, predicted {prediction})", exponent(fit.exponent, 4))
    }
}

/// What the exponents say: whether they follow their laws, each quantity fitted on both sides
/// with its two exponents, and those fitted on one side only.
fn sentences(matched: &[Matched]) -> Vec<String> {
    let mut sentences = vec![verdict(matched)];
    for m in matched {
        if let (Some(a), Some(b)) = (&m.a, &m.b) {
            sentences.push(format!(
                "{}: {} ∝ {}^p with {} in A and {} in B.",
                m.scene_words(),
                m.quantity,
                m.against,
                m.fit_words(a),
                m.fit_words(b)
            ));
        }
    }
    for side in ["A", "B"] {
        let words: Vec<String> = matched
            .iter()
            .filter_map(|m| {
                let (own, other) = if side == "A" { (&m.a, &m.b) } else { (&m.b, &m.a) };
                let fit = own.as_ref().filter(|_| other.is_none())?;
                Some(format!("{} ∝ {}^p in {}, {}", m.quantity, m.against, m.scene_words(), m.fit_words(fit)))
            })
            .collect();
        if !words.is_empty() {
            sentences.push(format!("Fitted in {side} only: {}.", words.join("; ")));
        }
    }
    sentences
}

/// Whether the fitted exponents follow their spring laws within their [`tolerance`], naming
/// those that do not, and how many packing fits at smaller N are not judged.
fn verdict(matched: &[Matched]) -> String {
    let fits = || matched.iter().flat_map(|m| [("A", &m.a), ("B", &m.b)].map(|(side, fit)| (m, side, fit)));
    let unjudged = fits().filter(|(_, _, fit)| fit.as_ref().is_some_and(|f| !f.judged)).count();
    let misses: Vec<(&Matched, &str, f64)> = fits()
        .filter_map(|(m, side, fit)| {
            Some((m, side, fit.as_ref().filter(|f| f.judged)?.miss((&m.quantity, &m.against))?))
        })
        .collect();
    let agreement = agreement(&misses);
    match unjudged {
        0 => agreement,
        n => format!(
            "{agreement} The packings' scalings at a scene's smaller N ({n} fits) are not judged: the finite size \
             bends them, and the report's item Jamming judges the largest N only."
        ),
    }
}

/// The verdict over the judged fits' `misses` (scene, side and |fitted − predicted|).
fn agreement(misses: &[(&Matched, &str, f64)]) -> String {
    let within = tolerance_words(misses.iter().map(|(m, _, _)| m.against.as_str()));
    let outside: Vec<String> = misses
        .iter()
        .filter(|(m, _, miss)| *miss > tolerance(&m.against))
        .map(|(m, side, miss)| format!("{} {} in {side} (off by {})", m.scene_words(), m.quantity, exponent(*miss, 4)))
        .collect();
    let largest = misses.iter().map(|(_, _, miss)| *miss).fold(0.0, f64::max);
    match (misses.len(), outside.len()) {
        (0, _) => "No fitted exponent has a spring law to be held against.".to_string(),
        (n, 0) => {
            let all = match n {
                1 => "The fitted exponent agrees with the exponent its spring law predicts".to_string(),
                2 => "Both fitted exponents agree with the exponents their spring laws predict".to_string(),
                _ => format!("All {n} fitted exponents agree with the exponents their spring laws predict"),
            };
            format!("{all} within {within} (largest difference {largest:.1e}).")
        }
        (n, k) => format!(
            "{} of {n} fitted exponents agree with their spring laws within {within}; these do not: {}.",
            n - k,
            outside.join("; ")
        ),
    }
}

/// The tolerances of fits against `against` in words: `0.01`, `0.15` near jamming, or both.
fn tolerance_words<'a>(against: impl Iterator<Item = &'a str>) -> String {
    let (mut sweeps, mut packings) = (false, false);
    for a in against {
        if jamming::is_fitted_against(a) { packings = true } else { sweeps = true }
    }
    match (sweeps, packings) {
        (true, true) => {
            format!("{TOLERANCE} ({} for the packings' scalings near jamming)", jamming::EXPONENT_TOLERANCE)
        }
        (false, true) => jamming::EXPONENT_TOLERANCE.to_string(),
        _ => TOLERANCE.to_string(),
    }
}
