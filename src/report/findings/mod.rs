//! The coursework's questions (`../shared/coursework.md`) answered from a campaign's results:
//! for each item a finding in sentences with this campaign's numbers, the reference it is held
//! against with its tolerance, a verdict, the figures that show it and a compact table. Every
//! number is read from the records at render time; an item whose runs the campaign lacks is
//! left out. This file lists the questions; `finding.rs` is the vocabulary they answer in.

mod appendix;
mod block;
mod combined_damping;
mod curves;
mod discussion;
mod dynamics;
mod finding;
mod jamming;
mod materials;
mod moduli_damping;
mod one_d;
mod random;
mod relaxation;
mod two_d;
mod types;

use std::collections::HashSet;

use self::finding::Answer;
use crate::model::LatticeType;
use crate::sim::RelaxMethod;

pub use self::appendix::{AppendixWords, appendix_words};
pub use self::discussion::Paragraph;
pub use self::finding::{Evidence, Finding, Table, Verdict, rel};

/// One item's answer from the evidence it is asked of, if that has its runs.
type Question = fn(&Evidence) -> Option<Answer>;

/// The questions `evidence` answers, numbered: a study's own (time to a modulus, the lattice
/// types), asked of every run, where the campaign is a study ([`study_answers`]), after the
/// coursework items its other runs answer (a pair or chain beside the study's lattices);
/// otherwise the coursework's items, in the coursework's order. A study campaign's square
/// lattices would answer coursework items too, but that is the coursework report's text again,
/// not the study's.
pub fn findings(evidence: &Evidence) -> Vec<Finding> {
    let answers = match study_answers(evidence) {
        Some(study) => {
            let mut answers = coursework(&evidence.coursework().beside_study());
            answers.extend(study);
            answers
        }
        None => coursework(&evidence.coursework()),
    };
    answers.into_iter().enumerate().map(|(i, answer)| answer.numbered(i + 1)).collect()
}

/// A study's answers, when the campaign is a study, not coursework: it compares relaxation
/// methods (its runs stopped by the displacement bound use more than one, critical damping
/// counting as one) or lattice types (one of its lattices is not square), and a study question
/// answers it. A coursework block relaxed by one minimiser is still coursework.
fn study_answers(evidence: &Evidence) -> Option<Vec<Answer>> {
    let lattices = evidence.all(|r| r.spec.lattice().is_some());
    let methods: HashSet<(RelaxMethod, bool)> = lattices
        .iter()
        .filter_map(|r| r.spec.relax().filter(|relax| relax.tolerance.is_some()))
        .map(|relax| (relax.method, relax.critical_background))
        .collect();
    let types = lattices.iter().filter_map(|r| r.spec.lattice()).any(|l| l.lattice_type != LatticeType::Square);
    if !(methods.len() > 1 || types) {
        return None;
    }
    Some(studies(evidence)).filter(|answers| !answers.is_empty())
}

/// The studies' own questions that `evidence` answers.
fn studies(evidence: &Evidence) -> Vec<Answer> {
    let asked: [Question; 6] = [
        relaxation::time_to_modulus,
        types::moduli,
        types::isotropy,
        types::directions,
        types::percolation,
        types::waves,
    ];
    asked.iter().filter_map(|question| question(evidence)).collect()
}

/// The coursework's items that its evidence ([`Evidence::coursework`]: square lattices relaxed
/// by MD) answers, in the coursework's order.
fn coursework(coursework: &Evidence) -> Vec<Answer> {
    let asked: [Question; 26] = [
        one_d::force_function,
        one_d::two_particles,
        one_d::time_step,
        one_d::chain,
        curves::motion,
        one_d::hertz_pair_and_chain,
        curves::power_contacts,
        one_d::walls,
        one_d::chain_as_row,
        two_d::units_and_time_step,
        two_d::diagonal_stiffness,
        two_d::lattice_time_step,
        two_d::kick,
        curves::dispersion_relation,
        two_d::youngs_and_poisson,
        two_d::shear,
        dynamics::sound_speed,
        dynamics::dissipation,
        materials::homogeneity,
        materials::hertz_moduli,
        dynamics::hertz_kick,
        materials::anisotropic,
        random::random,
        materials::md_and_fem,
        jamming::jamming,
        discussion::linear_and_hertz,
    ];
    asked.iter().filter_map(|question| question(coursework)).collect()
}

/// The discussion's paragraphs: a study's own where the campaign is one (as [`findings`]
/// decides), otherwise the coursework's themes.
pub fn discussion(evidence: &Evidence) -> Vec<Paragraph> {
    if study_answers(evidence).is_none() {
        return discussion::discussion(evidence);
    }
    let paragraphs: [fn(&Evidence) -> Option<Paragraph>; 2] = [relaxation::which_method, types::against_continuum];
    paragraphs.iter().filter_map(|paragraph| paragraph(evidence)).collect()
}

/// The abstract: the campaign's answers in a few sentences, each computed from its results
/// (the coursework's evidence); a sentence whose runs the campaign lacks is left out.
pub fn overview(evidence: &Evidence) -> Vec<String> {
    let e = evidence.coursework();
    let block = block::Block::of(&e);
    [
        one_d::pair_headline(&e),
        block.as_ref().map(block::Block::moduli_sentence),
        block.as_ref().map(block::Block::sound_sentence),
        dynamics::dissipation_headline(&e),
        materials::fem_headline(&e),
        discussion::hertz_headline(&e),
    ]
    .into_iter()
    .flatten()
    .collect()
}
