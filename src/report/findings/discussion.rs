//! The report's discussion: linear against non-linear springs, with against without diagonals,
//! bond against background damping and the one time step to use, each a paragraph computed from
//! the campaign's results.

use serde::Serialize;

use super::{Evidence, sig};
use crate::model::LawSpec;
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::spec::{Diagonals, LoadCase};

/// One paragraph of the discussion.
#[derive(Serialize)]
pub struct Paragraph {
    /// What it weighs.
    pub title: &'static str,
    /// The paragraph.
    pub text: String,
}

/// The discussion's paragraphs that `e` has the runs for.
pub fn discussion(e: &Evidence) -> Vec<Paragraph> {
    [linear_against_hertz(e), diagonals(e), damping(e), time_step(e)].into_iter().flatten().collect()
}

/// Exponents of the fitted scaling laws, linear against power-law springs.
fn linear_against_hertz(e: &Evidence) -> Option<Paragraph> {
    let hertz: Vec<String> = e
        .fits
        .iter()
        .filter(|f| f.law != "linear")
        .map(|f| {
            format!(
                "{} ∝ {}^{:.3} ({})",
                f.quantity.replace('_', " "),
                f.against.replace('_', " "),
                f.fit.exponent,
                f.scene
            )
        })
        .collect();
    let linear: Vec<String> = e
        .fits
        .iter()
        .filter(|f| f.law == "linear")
        .map(|f| format!("{} ∝ {}^{:.3}", f.quantity.replace('_', " "), f.against.replace('_', " "), f.fit.exponent))
        .collect();
    (!hertz.is_empty()).then(|| Paragraph {
        title: "Linear against non-linear springs",
        text: format!(
            "A linear spring's stiffness does not depend on how far it is stretched, so nothing a linear network \
             does depends on the amplitude: here {}. A Hertz spring stiffens as it deforms and has no stiffness at \
             rest: its contact duration shortens with the impact speed, a chain between walls stiffens as the walls \
             move, the lattice's moduli grow with the load and its waves speed up with the kick: here {}. In 1D and \
             2D alike, the non-linear network's response is set by its state of deformation, which a linear \
             network's is not; superposition, normal modes and one sound speed are linear ideas.",
            if linear.is_empty() { "no sweep over the amplitude".to_string() } else { linear.join(", ") },
            hertz.join(", ")
        ),
    })
}

/// The square lattice with and without diagonal springs.
fn diagonals(e: &Evidence) -> Option<Paragraph> {
    let tensile = |d: Diagonals| {
        e.ok(|r| {
            r.spec.law == LawSpec::Linear
                && r.spec.lattice().is_some_and(|l| {
                    l.diagonals == d && l.load_case == LoadCase::Tensile && !l.is_random() && l.impulse.is_none()
                })
        })
    };
    let (none, both) = (tensile(Diagonals::None), tensile(Diagonals::Both));
    let (n, b): (&RunRecord, &RunRecord) = (none.first()?, both.first()?);
    let floppy = e
        .all(|r| r.status == RunStatus::Mechanism && r.spec.lattice().is_some_and(|l| l.diagonals == Diagonals::None))
        .len();
    Some(Paragraph {
        title: "With and without diagonals",
        text: format!(
            "Without diagonals a square lattice is a set of independent chains: E = k/d = {} Pa, ν = {} and no \
             shear stiffness at all ({floppy} shear runs end as mechanism), and a kick stays in its column. The \
             diagonals tie rows to columns: E = {} Pa, ν = {} and G = k_d/d, a solid that contracts sideways and \
             carries shear, and a kick spreads through the whole block.",
            sig(n.metrics.lattice.youngs_modulus.unwrap_or(f64::NAN)),
            sig(n.metrics.lattice.poisson_ratio.unwrap_or(f64::NAN)),
            sig(b.metrics.lattice.youngs_modulus.unwrap_or(f64::NAN)),
            sig(b.metrics.lattice.poisson_ratio.unwrap_or(f64::NAN)),
        ),
    })
}

/// Bond damping against background damping.
fn damping(e: &Evidence) -> Option<Paragraph> {
    let time = |bond: bool| {
        e.ok(|r| {
            r.spec.lattice().is_some()
                && r.metrics.dissipation_time.is_some()
                && if bond {
                    r.spec.gamma > 0.0 && r.spec.gamma_background == 0.0
                } else {
                    r.spec.gamma == 0.0 && r.spec.gamma_background > 0.0
                }
        })
        .iter()
        .filter_map(|r| r.metrics.dissipation_time)
        .fold(f64::INFINITY, f64::min)
    };
    let (bond, background) = (time(true), time(false));
    (bond.is_finite() && background.is_finite()).then(|| Paragraph {
        title: "Bond against background damping",
        text: format!(
            "Bond damping is physical (it sets the restitution of each spring) but acts only on relative motion, so \
             the slow, nearly rigid modes of a large block barely feel it: the fastest bond-damped relaxation here \
             takes {} s. Background damping acts on every node's velocity and every mode: {} s, {:.0}× faster. For \
             static answers (moduli) use background damping near the slowest mode's critical value; for dynamics \
             (restitution, dissipation) keep the bond damping and no background.",
            sig(bond),
            sig(background),
            bond / background
        ),
    })
}

/// One time-step recommendation for every scene.
fn time_step(e: &Evidence) -> Option<Paragraph> {
    let linear: Vec<f64> = e
        .ok(|r| {
            r.spec.law == LawSpec::Linear && r.metrics.dt_omega_max.is_some() && (r.spec.dt_per_tc() - 50.0).abs() < 1.0
        })
        .iter()
        .filter_map(|r| r.metrics.dt_omega_max)
        .collect();
    let largest = linear.iter().copied().fold(0.0, f64::max);
    (!linear.is_empty()).then(|| Paragraph {
        title: "The time step",
        text: format!(
            "One rule serves every scene: dt = t_c/50 with t_c = π√(m/(2k)) of the stiffest pair of the network. On \
             two particles it keeps t_c and r to about 2e-4; on the chains and lattices of this campaign it puts \
             the fastest mode at dt·ω_max ≤ {} against the Verlet limit 2, and errors fall as dt². For Hertz \
             springs t_c depends on the amplitude: mdsolids takes t_c at the deformation the scene expects (the \
             impact speed, the load or the wall displacement), so the same rule holds there. The work–precision \
             figures give the largest dt for a stated error.",
            sig(largest)
        ),
    })
}
