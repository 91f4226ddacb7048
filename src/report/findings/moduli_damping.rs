//! The background damping the moduli scenes relax with, each scene's γ_g held against its own
//! runs' critical value γ_crit = 2√(k_min m) (k_min the slowest mode's stiffness, from the
//! static solve's record): the report advises γ_g near γ_crit, so it says how near each scene
//! is. Scenes that sweep γ_g (the dissipation study) are left to the dissipation item.

use super::finding::{Evidence, sig};
use crate::report::words::counted;
use crate::runner::RunRecord;
use crate::sim::RelaxMethod;
use crate::theory::critical_damping;

/// A loaded lattice brought to rest by damped MD with a background damping its scene fixes.
fn fixed_background(r: &RunRecord) -> bool {
    r.spec.lattice().is_some_and(|l| l.impulse.is_none())
        && r.spec.relax().is_some_and(|relax| relax.method == RelaxMethod::Damped)
        && r.spec.gamma_background > 0.0
        && !r.spec.varied.contains_key("damping.background")
}

/// One scene's γ_g values (as written) and its runs' γ_g/γ_crit, with the counts of runs
/// whose k_min is 0 (a floppy network has no slowest stiffness to be critical for) and of
/// runs that recorded none.
struct SceneDamping {
    scene: String,
    gammas: Vec<String>,
    ratios: Vec<f64>,
    floppy: usize,
    unknown: usize,
}

impl SceneDamping {
    fn words(&self) -> String {
        let mut ratios = self.ratios.clone();
        ratios.sort_by(f64::total_cmp);
        let range = match (ratios.first(), ratios.last()) {
            (Some(low), Some(high)) if sig(*low) == sig(*high) => format!("{} γ_crit", sig(*low)),
            (Some(low), Some(high)) => {
                let median = crate::measure::median(ratios.clone()).unwrap_or(f64::NAN);
                format!("{} to {} γ_crit (median {})", sig(*low), sig(*high), sig(median))
            }
            _ => String::new(),
        };
        let runs = counted(self.ratios.len(), "run");
        let mut rest: Vec<String> = Vec::new();
        if self.floppy > 0 {
            rest.push(format!("{} floppy, k_min = 0", self.floppy));
        }
        if self.unknown > 0 {
            rest.push(format!("{} without a recorded k_min", self.unknown));
        }
        let gammas = format!("{} γ_g = {} N s/m", self.scene, self.gammas.join(", "));
        match (range.is_empty(), rest.is_empty()) {
            (false, true) => format!("{gammas}, {range} over {runs}"),
            (false, false) => format!("{gammas}, {range} over {runs} (and {})", rest.join(", ")),
            (true, _) => format!("{gammas} ({} runs: {})", self.floppy + self.unknown, rest.join(", ")),
        }
    }
}

/// The moduli scenes' background damping against their critical values, one clause per
/// scene in the campaign's order; `None` when no scene fixes one.
pub(super) fn moduli_damping_sentence(e: &Evidence) -> Option<String> {
    let mut scenes: Vec<SceneDamping> = Vec::new();
    for r in e.ok(fixed_background) {
        if scenes.last().is_none_or(|s| s.scene != r.spec.scene) {
            let fresh = SceneDamping {
                scene: r.spec.scene.clone(),
                gammas: Vec::new(),
                ratios: Vec::new(),
                floppy: 0,
                unknown: 0,
            };
            scenes.push(fresh);
        }
        let s = scenes.last_mut()?;
        let gamma = sig(r.spec.gamma_background);
        if !s.gammas.contains(&gamma) {
            s.gammas.push(gamma);
        }
        match r.metrics.lattice.stiffness_min {
            Some(k_min) if k_min > 0.0 => s.ratios.push(r.spec.gamma_background / critical_damping(k_min, r.spec.mass)),
            Some(_) => s.floppy += 1,
            None => s.unknown += 1,
        }
    }
    if scenes.is_empty() {
        return None;
    }
    let clauses: Vec<String> = scenes.iter().map(SceneDamping::words).collect();
    Some(format!(
        "The moduli scenes relax with a background damping γ_g they fix, here against each run's own critical \
         value γ_crit = 2√(k_min m) (k_min the stiffness of its slowest mode, from the static solve): {}.",
        clauses.join("; ")
    ))
}
