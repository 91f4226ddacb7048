//! How deep a collision drives its particles into each other, known before the run from
//! energy balances: a check beside the stability limit, which judges dt · ω_max on the
//! linearised network and so cannot see particles pass through each other. A linear contact
//! pair (m = 1 kg, k = 1 N/m, x_e = 1 m, v0 = 1 m/s) at dt = t_c/2 has dt · ω = π/2, inside
//! Verlet's limit 2, yet its first step of free flight, v0 dt = 1.11 m, is longer than its rest
//! length; the Hertz contact chain of 11 hit at v0 = 1 m/s has dt · ω_max = 0.11 and still
//! drives its last particle into the wall. The limit is the run's own: a bond counts as
//! collapsed once its length falls below [`COLLAPSE_RATIO`] of its start length. Pure
//! computation on the resolved run.

use crate::model::LawSpec;
use crate::sim::COLLAPSE_RATIO;
use crate::spec::{Deformation, KindSpec, Num, RunSpec, SceneKind};

/// A collision is resolved when one step's free flight v0 dt stays below this fraction of the
/// two-body overlap δ₂: the contact then lasts t_c = π δ₂/v0 (linear; Hertz 2.94 δ₂/v0), at
/// least ~6 steps. Coarser steps run (the coursework's dt = t_c/10 is 0.31 δ₂), but their
/// contact duration and restitution are a few steps' guess.
const RESOLVED_STEP: f64 = 0.5;

/// The energy balance of the kick on one spring, about its start: ½ μ v0² = B(δ), with
/// B(δ) = e(δ) − e(δ_p) − s(δ_p)(δ − δ_p) the spring's energy above its tangent at the walls'
/// pre-overlap δ_p (B = e(δ) = C δ^(β+1)/(β+1) at rest). Between fixed walls the overlaps sum
/// to (n + 1) δ_p at every instant, so Σ s(δ_p)(δ_i − δ_p) = 0 and the kick's energy ½ m v0²
/// is Σ B(δ_i) with every B ≥ 0 (e convex, and zero in tension for a contact): B(δ) ≤ ½ m v0²
/// in any one spring. A pair: μ = m/2, exact. A compression-only chain: μ = m, that bound,
/// nearly reached as its solitary wave meets a wall (the Hertz chain of 11, m = C = x_e = 1, hit
/// at v0 = 0.86 m/s, B = 0.37 J, reaches 0.969 x_e by the bound and collapses). A bonded chain:
/// μ = m/2, the kicked particle against one neighbour, an estimate (the rest goes into tension:
/// the bound with μ = m would refuse the linear chain of 200 hit at its end at 1 m/s, which runs
/// to 1.6 m/s and collapses at 2).
#[derive(Clone, Copy)]
struct Balance {
    law: LawSpec,
    /// k (N/m) or C (N/m^β).
    k: f64,
    /// μ (kg).
    mass: f64,
    /// δ_p (m): the walls' overlap per spring at the start (negative: stretched bonded springs).
    preload: f64,
    /// A damped linear pair's dashpot on the overlap, γ + γ_g/2 (N s/m; (m/2) δ̈ = −k δ −
    /// (γ + γ_g/2) δ̇ with background damping −γ_g v on each particle), underdamped: its
    /// overlap has a closed form ([`damped_linear_overlap`]). 0 otherwise.
    dashpot: f64,
}

impl Balance {
    /// The overlap (m) reached from a contact met `step` (m) deep at the speed `v` (m/s), all
    /// of the kick's energy still to stop: B(δ) = ½ μ v² + e(step), undamped (an upper bound
    /// with any dashpot: damping only takes energy out), or the damped linear pair's maximum.
    fn reach(&self, v: f64, step: f64) -> f64 {
        if self.dashpot > 0.0 {
            return damped_linear_overlap(self.k, self.mass, self.dashpot, step, v);
        }
        let energy = 0.5 * self.mass * v * v + self.law.energy(self.k, step);
        if self.preload == 0.0 {
            // e(δ) = C δ^(β+1)/(β+1) inverted.
            let power = self.law.beta() + 1.0;
            return (power * energy / self.k).powf(1.0 / power);
        }
        let (law, k, p) = (self.law, self.k, self.preload);
        let above = |d: f64| law.energy(k, p + d) - law.energy(k, p) - law.elastic_force(k, p) * d;
        p + largest_below(above, energy)
    }
}

/// The maximum overlap (m) of the damped linear pair μ δ̈ = −k δ − γ δ̇ started at δ = `s` (m)
/// moving in at `v` (m/s), underdamped (a = γ/2μ < ω0 = √(k/μ), ω_d = √(ω0² − a²)):
/// δ = e^(−at) (s cos ω_d t + b sin ω_d t) with b = (v + a s)/ω_d stops growing where
/// tan ω_d t = v/(a b + s ω_d). At s = 0 that is (v/ω0) exp(−(ζ/√(1−ζ²)) atan(√(1−ζ²)/ζ)),
/// ζ = a/ω0; undamped √(s² + (v/ω0)²).
fn damped_linear_overlap(k: f64, mu: f64, gamma: f64, s: f64, v: f64) -> f64 {
    let a = gamma / (2.0 * mu);
    let omega_d = (k / mu - a * a).sqrt();
    let b = (v + a * s) / omega_d;
    let phase = v.atan2(a * b + s * omega_d);
    (-a * phase / omega_d).exp() * (s * phase.cos() + b * phase.sin())
}

/// The largest x ≥ 0 (to rounding) with `f(x) < target`, for `f` increasing without bound and
/// `f(0) < target` (0 otherwise): doubling, then bisection.
fn largest_below(f: impl Fn(f64) -> f64, target: f64) -> f64 {
    let (mut low, mut high) = (0.0f64, 1.0f64);
    while f(high) < target && high < f64::MAX {
        (low, high) = (high, 2.0 * high);
    }
    loop {
        let middle = 0.5 * (low + high);
        if middle <= low || middle >= high {
            return if f(low) < target { low } else { 0.0 };
        }
        if f(middle) < target {
            low = middle;
        } else {
            high = middle;
        }
    }
}

/// The overlaps (m) a collision run may reach: what the plan refuses ([`check`]) or warns of
/// ([`collision_warning`]).
struct Overlap {
    /// The balance the overlaps come from.
    balance: Balance,
    /// The kick's overlap, the spring met at its start: B(kick) = ½ μ v0².
    kick: f64,
    /// v0 dt: how deep one step of free flight carries a contact before any force acts, at the
    /// worst phase of the contact's start (every integrator moves a free particle exactly).
    step: f64,
    /// The overlap from that worst start, the spring met `step` deep with all the kinetic
    /// energy still to stop: B(reach) = ½ μ v0² + e(step). Conservative, and blind to the
    /// integrator: linear contact pairs (v0 = 1 m/s) at position Verlet's dt_per_tc 2.3 … 3.5
    /// are refused and do not collapse.
    reach: f64,
    /// The overlap at which the run stops the bond as collapsed: x_e − COLLAPSE_RATIO · L0, with
    /// L0 its start length (a contact pair's x_e + gap; a hit chain's wall_distance/(n + 1)).
    limit: f64,
    /// `kick` is exact or a bound the run comes near (undamped or the damped linear pair, and
    /// compression-only chains: refused beyond `limit`), not an estimate (warned of).
    refusable: bool,
}

impl Overlap {
    /// The overlaps of `spec`, a pair or a hit chain (walls at rest or moved), once its dt is
    /// planned; `None` for other scenes (lattices, relaxing chains, packings).
    fn of(spec: &RunSpec) -> Option<Overlap> {
        // The springs' start extension ΔW/(n + 1) between moved walls, and a contact pair's gap (m).
        let (v0, extension, gap) = match (&spec.scene_kind, spec.deformation()) {
            (KindSpec::Pair(pair), Deformation::Collision(v0)) => (v0, 0.0, pair.gap.unwrap_or(0.0)),
            (KindSpec::Chain(_), Deformation::Collision(v0)) => (v0, 0.0, 0.0),
            (KindSpec::Chain(_), Deformation::PreStressed { extension, speed }) => (speed, extension, 0.0),
            _ => return None,
        };
        if !spec.dt.is_finite() {
            return None;
        }
        let pair = spec.kind() == SceneKind::Pair;
        let chain_contact = !pair && spec.contact;
        let mass = if chain_contact { spec.mass } else { 0.5 * spec.mass };
        // Slack walls open every contact's gap: the chain is at rest, with room to fly.
        let preload = if spec.contact { (-extension).max(0.0) } else { -extension };
        let dashpot = spec.gamma + 0.5 * spec.gamma_background;
        let closed = pair && spec.law.is_linear() && dashpot > 0.0 && dashpot * dashpot < 4.0 * spec.k * mass;
        let balance = Balance { law: spec.law, k: spec.k, mass, preload, dashpot: if closed { dashpot } else { 0.0 } };
        let step = v0 * spec.dt;
        Some(Overlap {
            balance,
            kick: balance.reach(v0, 0.0),
            step,
            reach: balance.reach(v0, step),
            limit: spec.spacing - COLLAPSE_RATIO * (spec.spacing + extension + gap),
            refusable: (pair || chain_contact) && (dashpot == 0.0 || closed),
        })
    }

    /// The largest v0 (m/s) whose reach at the run's dt stays short of the limit.
    fn largest_speed(&self, spec: &RunSpec) -> f64 {
        largest_below(|v| self.balance.reach(v, v * spec.dt), self.limit)
    }

    /// The largest dt (s) whose reach at v0 stays short of the limit (the kick's is).
    fn largest_dt(&self, spec: &RunSpec) -> f64 {
        largest_below(|dt| self.balance.reach(spec.v0, spec.v0 * dt), self.limit)
    }

    /// The overlaps in words, for the refusal and the warning.
    fn words(&self, spec: &RunSpec) -> String {
        let b = &self.balance;
        let balance = match (b.dashpot > 0.0, b.preload != 0.0) {
            (true, _) => format!("the damped linear pair, dashpot {} N s/m on the overlap", Num(b.dashpot)),
            (false, false) => "½ μ v0² = e(δ)".to_string(),
            (false, true) => {
                format!("½ μ v0² = e(δ) − e(δ_p) − s(δ_p)(δ − δ_p), the walls' pre-overlap δ_p = {:.4e} m", b.preload)
            }
        };
        let whole = if self.refusable && spec.kind() == SceneKind::Chain {
            ", all of the kick's energy in one contact, as when the wave meets a wall"
        } else {
            ""
        };
        format!(
            "v0 = {} m/s gives the overlap δ = {:.4} m ({balance}; μ = {} kg{whole}), and one step's free flight \
             v0·dt = {:.4} m into the contact makes it up to {:.4} m (a conservative estimate, whatever the \
             integrator), not less than {:.4} m, where the bond's length falls below {} of its start length and the \
             run stops it as collapsed",
            Num(spec.v0),
            self.kick,
            Num(b.mass),
            self.step,
            self.reach,
            self.limit,
            COLLAPSE_RATIO
        )
    }
}

/// What a dt (s) in place of the run's means in the field that set it: `time.dt_omega_max`
/// scales with dt; otherwise dt itself and its dt_per_tc.
fn dt_advice(spec: &RunSpec, dt: f64) -> String {
    match spec.dt_omega_max {
        Some(target) => format!("time.dt_omega_max < {:.4}", target * dt / spec.dt),
        None => format!("dt < {dt:.4e} s (dt_per_tc > {:.4})", spec.t_c / dt),
    }
}

/// Refuses, before anything runs, a pair or compression-only chain whose particles may pass
/// through each other (its reach at or beyond the run's collapse limit), unless it says
/// `time.allow_unstable: true`, as a step beyond the stability limit is. `dt_field` is the
/// campaign field that set dt. The error names the field and what it allows: v0 when the kick
/// alone reaches the limit (no dt helps), else dt.
pub(super) fn check(spec: &RunSpec, dt_field: &str) -> Result<(), String> {
    let Some(overlap) = Overlap::of(spec).filter(|o| o.refusable && o.reach >= o.limit) else {
        return Ok(());
    };
    if spec.allow_unstable {
        return Ok(());
    }
    let (field, allowed) = if overlap.kick >= overlap.limit {
        let speed = overlap.largest_speed(spec);
        (format!("v0 = {}", Num(spec.v0)), format!("v0 < {speed:.4e} m/s at this dt (or a stiffer material.k)"))
    } else {
        (format!("{dt_field}: dt = {:.4e} s", spec.dt), dt_advice(spec, overlap.largest_dt(spec)))
    };
    Err(format!(
        "{field}: the particles may pass through each other: {}; allowed: {allowed}, or time.allow_unstable: true to \
         run it anyway and watch whether it collapses",
        overlap.words(spec)
    ))
}

/// `x` to three significant digits: 0.50007 is 0.500, not 0.50.
fn three_digits(x: f64) -> String {
    let decimals = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

/// Why `plan` and `run` warn of `spec`, if they do: a collision whose reach passes the collapse
/// limit but is only estimated (a bonded chain's kicked particle against its neighbour; a
/// dashpot without a closed form, whose undamped bound may be far from the run), or a contact
/// (pair or compression-only chain) whose step is too coarse to resolve it (v0·dt beyond
/// [`RESOLVED_STEP`] of the two-body overlap).
pub fn collision_warning(spec: &RunSpec) -> Option<String> {
    let overlap = Overlap::of(spec)?;
    if !overlap.refusable && overlap.reach >= overlap.limit {
        let damped = spec.gamma + spec.gamma_background > 0.0;
        let damped = if damped { " (undamped: the dashpot only shortens it)" } else { "" };
        return Some(format!(
            "the kicked particle may pass through its neighbour{damped}: {} (v0 < {:.4e} m/s stays short of it)",
            overlap.words(spec),
            overlap.largest_speed(spec)
        ));
    }
    if !spec.contact {
        return None;
    }
    let two_body = Balance { mass: 0.5 * spec.mass, preload: 0.0, ..overlap.balance }.reach(spec.v0, 0.0);
    (overlap.step > RESOLVED_STEP * two_body).then(|| {
        format!(
            "one step's free flight v0·dt = {:.4e} m is {} of the two-body overlap {two_body:.4e} m (beyond \
             {RESOLVED_STEP}): the contact is resolved by a few steps only; {} resolves it",
            overlap.step,
            three_digits(overlap.step / two_body),
            dt_advice(spec, RESOLVED_STEP * two_body / spec.v0)
        )
    })
}
