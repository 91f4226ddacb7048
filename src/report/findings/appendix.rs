//! The sentences of the methods' appendix that depend on the campaign's runs: each computed
//! from the records, as the items' are, so the appendix's general text states this campaign's
//! numbers where it names one.

use serde::Serialize;

use super::finding::Evidence;
use super::{dynamics, moduli_damping, one_d};

/// The appendix's data-dependent sentences (each `None` when the campaign lacks its runs).
#[derive(Default, Serialize)]
pub struct AppendixWords {
    /// The damped pair's restitution with its contact force clamped to stay repulsive.
    clamped: Option<String>,
    /// The damped pair's restitution with the full mass in place of the reduced mass.
    full_mass: Option<String>,
    /// The linear chain's first maximum against its long-wavelength speed a√(k/m).
    first_maximum: Option<String>,
    /// The moduli scenes' background damping against their critical values.
    moduli_damping: Option<String>,
}

/// The appendix's sentences from the coursework evidence of `evidence`.
pub fn appendix_words(evidence: &Evidence) -> AppendixWords {
    let e = evidence.coursework();
    AppendixWords {
        clamped: one_d::clamped_sentence(&e),
        full_mass: one_d::full_mass_sentence(&e),
        first_maximum: dynamics::first_maximum_words(&e),
        moduli_damping: moduli_damping::moduli_damping_sentence(&e),
    }
}
