//! The coursework's questions (`../shared/coursework.md`) answered from a campaign's results:
//! for each item a finding in sentences with this campaign's numbers, the reference it is held
//! against with its tolerance, a verdict, the figures that show it and a compact table. Every
//! number is read from the records at render time; an item whose runs the campaign lacks is
//! left out. This file lists the questions; `finding.rs` is the vocabulary they answer in.

mod block;
mod curves;
mod discussion;
mod dynamics;
mod finding;
mod jamming;
mod materials;
mod one_d;
mod relaxation;
mod two_d;
mod types;

use self::finding::Answer;

pub use self::discussion::{Paragraph, discussion};
pub use self::finding::{Evidence, Finding, Table, Verdict, rel};

/// One item's answer from the evidence it is asked of, if that has its runs.
type Question = fn(&Evidence) -> Option<Answer>;

/// The coursework's items that `evidence` answers, in the coursework's order, numbered.
pub fn findings(evidence: &Evidence) -> Vec<Finding> {
    // The coursework's questions see its evidence ([`Evidence::coursework`]); the lattice
    // types' see every run.
    let coursework = evidence.coursework();
    let asked: [(Question, &Evidence); 31] = [
        (one_d::force_function, &coursework),
        (one_d::two_particles, &coursework),
        (one_d::time_step, &coursework),
        (one_d::chain, &coursework),
        (curves::motion, &coursework),
        (one_d::hertz_pair_and_chain, &coursework),
        (curves::power_contacts, &coursework),
        (one_d::walls, &coursework),
        (two_d::units_and_time_step, &coursework),
        (two_d::diagonal_stiffness, &coursework),
        (two_d::lattice_time_step, &coursework),
        (two_d::kick, &coursework),
        (curves::dispersion_relation, &coursework),
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
        (jamming::jamming, evidence),
        (discussion::linear_and_hertz, &coursework),
    ];
    asked
        .iter()
        .filter_map(|(question, evidence)| question(evidence))
        .enumerate()
        .map(|(i, answer)| answer.numbered(i + 1))
        .collect()
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
