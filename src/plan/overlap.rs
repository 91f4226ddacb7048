//! How deep a collision drives its particles into each other, known before the run from
//! energy balances: a check beside the stability limit, which judges dt · ω_max on the
//! linearised network and so cannot see particles pass through each other. A linear contact
//! pair (m = 1 kg, k = 1 N/m, x_e = 1 m, v0 = 1 m/s) at dt = t_c/2 has dt · ω = π/2, inside
//! Verlet's limit 2, yet its first step of free flight, v0 dt = 1.11 m, is longer than its rest
//! length; the Hertz contact chain of 11 hit at v0 = 1 m/s has dt · ω_max = 0.11 and still
//! drives its last particle into the wall. Pure computation on the resolved run.

use crate::model::LawSpec;
use crate::spec::{Deformation, Num, RunSpec, SceneKind};
use crate::theory::power_law_max_overlap;

/// A collision is resolved when one step's free flight v0 dt stays below this fraction of the
/// two-body overlap δ₂: the contact then lasts t_c = π δ₂/v0 (linear; Hertz 2.94 δ₂/v0), at
/// least ~6 steps. Coarser steps run (the coursework's dt = t_c/10 is 0.31 δ₂), but their
/// contact duration and restitution are a few steps' guess.
const RESOLVED_STEP: f64 = 0.5;

/// The overlaps (m) a collision run may reach: what the plan refuses ([`check`]) or warns of
/// ([`collision_warning`]).
struct Overlap {
    /// Energy balance of the kick, ½ μ v0² = e(δ) = C δ^(β+1)/(β+1) (β = 1: linear). A pair:
    /// μ = m/2, exact. A compression-only chain: μ = m, all of the kick's energy in one contact,
    /// as when its solitary wave meets a wall: a bound, and nearly reached (the Hertz chain of 11,
    /// m = C = x_e = 1, hit at its centre collapses at v0 = 0.9 m/s, where it is 1.005 x_e, and
    /// runs at 0.85, 0.96 x_e). A bonded chain: μ = m/2, the kicked particle against one
    /// neighbour, an estimate (the rest goes into tension: the bound with μ = m would refuse the
    /// linear chain of 200 hit at its end at 1 m/s, which runs to 1.6 m/s and collapses at 2).
    kick: f64,
    /// v0 dt: how deep one step of free flight carries a contact before any force acts, at the
    /// worst phase of the contact's start (every integrator moves a free particle exactly).
    step: f64,
    /// The overlap from that worst start, the spring met `step` deep with all the kinetic
    /// energy still to stop: e(reach) = e(kick) + e(step).
    reach: f64,
    /// μ of the energy balance (kg).
    mass: f64,
    /// `kick` is exact or a bound the run comes near (pairs, compression-only chains: refused
    /// beyond x_e), not the estimate of a bonded chain (warned of).
    refusable: bool,
}

impl Overlap {
    /// The overlaps of `spec`, a pair or a chain hit with its walls at rest, once its dt is
    /// planned; `None` for other scenes (lattices, relaxing or pre-stressed chains, packings).
    fn of(spec: &RunSpec) -> Option<Overlap> {
        let Deformation::Collision(v0) = spec.deformation() else {
            return None;
        };
        if !matches!(spec.kind(), SceneKind::Pair | SceneKind::Chain) || !spec.dt.is_finite() {
            return None;
        }
        let chain_contact = spec.kind() == SceneKind::Chain && spec.contact;
        let mass = if chain_contact { spec.mass } else { 0.5 * spec.mass };
        let kick = energy_overlap(spec.law, spec.k, mass, v0);
        let step = v0 * spec.dt;
        let power = spec.law.beta() + 1.0;
        let reach = (kick.powf(power) + step.powf(power)).powf(1.0 / power);
        Some(Overlap { kick, step, reach, mass, refusable: spec.kind() == SceneKind::Pair || chain_contact })
    }

    /// The largest v0 (m/s) whose kick stays short of x_e: ½ μ v0² = e(x_e).
    fn largest_speed(&self, spec: &RunSpec) -> f64 {
        (2.0 * spec.law.energy(spec.k, spec.spacing) / self.mass).sqrt()
    }

    /// The largest dt (s) whose reach stays short of x_e: v0 dt = (x_e^(β+1) − kick^(β+1))^(1/(β+1)).
    fn largest_dt(&self, spec: &RunSpec) -> f64 {
        let power = spec.law.beta() + 1.0;
        (spec.spacing.powf(power) - self.kick.powf(power)).powf(1.0 / power) / spec.v0
    }

    /// The overlaps in words, for the refusal and the warning.
    fn words(&self, spec: &RunSpec) -> String {
        let balance = if spec.law.is_linear() { "½ μ v0² = k δ²/2" } else { "½ μ v0² = C δ^(β+1)/(β+1)" };
        let whole = if self.refusable && spec.kind() == SceneKind::Chain {
            ": all of the kick's energy in one contact, as when the wave meets a wall"
        } else {
            ""
        };
        format!(
            "v0 = {} m/s gives the overlap δ = {:.4} m ({balance}, μ = {} kg{whole}), and one step's free flight \
             v0·dt = {:.4} m into the contact makes it up to {:.4} m, not less than the rest length x_e = {} m",
            Num(spec.v0),
            self.kick,
            Num(self.mass),
            self.step,
            self.reach,
            Num(spec.spacing)
        )
    }
}

/// δ (m) with e(δ) = ½ μ v² for the law `law` of constant `k`: where a collision of reduced
/// mass `mu` (kg) at relative speed `v` (m/s) stops, undamped (damping only shortens it).
fn energy_overlap(law: LawSpec, k: f64, mu: f64, v: f64) -> f64 {
    // power_law_max_overlap takes the pair's masses m, μ = m/2; its β = 1 is the linear law.
    power_law_max_overlap(k, law.beta(), 2.0 * mu, v)
}

/// Refuses, before anything runs, a pair or compression-only chain whose particles may pass
/// through each other (its reach at x_e or beyond, where the bond's length is zero), unless it
/// says `time.allow_unstable: true`, as a step beyond the stability limit is. `dt_field` is the
/// campaign field that set dt. The error names the field and what it allows: v0 when the kick
/// alone reaches x_e (no dt helps), else dt.
pub(super) fn check(spec: &RunSpec, dt_field: &str) -> Result<(), String> {
    let Some(overlap) = Overlap::of(spec).filter(|o| o.refusable && o.reach >= spec.spacing) else {
        return Ok(());
    };
    if spec.allow_unstable {
        return Ok(());
    }
    let (field, allowed) = if overlap.kick >= spec.spacing {
        let speed = overlap.largest_speed(spec);
        (format!("v0 = {}", Num(spec.v0)), format!("v0 < {speed:.4e} m/s (or a stiffer material.k)"))
    } else {
        let dt = overlap.largest_dt(spec);
        (format!("{dt_field}: dt = {:.4e} s", spec.dt), format!("dt < {dt:.4e} s (dt_per_tc > {:.4})", spec.t_c / dt))
    };
    Err(format!(
        "{field}: the particles may pass through each other: {}; allowed: {allowed}, or time.allow_unstable: true to \
         run it anyway and watch it collapse",
        overlap.words(spec)
    ))
}

/// Why `plan` warns of `spec`, if it does: a bonded chain whose kicked particle's two-body
/// overlap reaches x_e (it may pass through its neighbour), or a collision whose step is too
/// coarse to resolve its contact (v0·dt beyond [`RESOLVED_STEP`] of the two-body overlap).
pub fn collision_warning(spec: &RunSpec) -> Option<String> {
    let overlap = Overlap::of(spec)?;
    if !overlap.refusable && overlap.reach >= spec.spacing {
        return Some(format!(
            "the kicked particle may pass through its neighbour: {} (v0 < {:.4e} m/s stays short of it)",
            overlap.words(spec),
            overlap.largest_speed(spec)
        ));
    }
    let two_body = energy_overlap(spec.law, spec.k, 0.5 * spec.mass, spec.v0);
    (overlap.step > RESOLVED_STEP * two_body).then(|| {
        format!(
            "one step's free flight v0·dt = {:.4e} m is {:.2} of the two-body overlap {two_body:.4e} m (beyond \
             {RESOLVED_STEP}): the contact is resolved by a few steps only; dt_per_tc > {:.2} resolves it",
            overlap.step,
            overlap.step / two_body,
            spec.t_c * spec.v0 / (RESOLVED_STEP * two_body)
        )
    })
}
