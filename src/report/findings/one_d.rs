//! The coursework's 1D items: two particles against the analytical contact duration and
//! restitution, the time step, the chain of 11 against its normal modes, Hertz springs, and the
//! chain between moved walls.

use super::finding::{
    Answer, EXPONENT_TOLERANCE, Evidence, SolitaryFront, Table, Verdict, at_50, cell, exponents, rel, relative, sig,
};
use crate::measure::{convergence_order, sorted_distinct};
use crate::model::LawSpec;
use crate::report::figure::{FigureKind, FigureRef};
use crate::report::kinds::{contact_time_words, law_name};
use crate::report::words::{counted, number, ordinal, scheme};
use crate::runner::RunRecord;
use crate::sim::IntegratorKind;
use crate::spec::SceneKind;

/// Largest relative error of t_c and r at dt ≈ t_c/50 that a second-order scheme should meet:
/// its t_c error is about (π/50)²/24 ≈ 1.6e-4; the dashpot's predicted velocity adds O(dt²) to
/// r; 2e-3 leaves a factor of ten.
const PAIR_TOLERANCE: f64 = 2e-3;

/// The same for the first-order symplectic Euler: its velocity lags its position by half a
/// step, ω dt/2 = π/100 ≈ 3e-2 of the speed at t_c/50 (measured: t_c and r of the damped contact
/// off by 7e-3 and 5e-3); the full mass in place of m/2 would still miss r by 0.1.
const FIRST_ORDER_PAIR_TOLERANCE: f64 = 3e-2;

/// The tolerance of a pair run's t_c and r at t_c/50 under its scheme: schemes of higher order
/// are held to the second order's.
fn pair_tolerance(r: &RunRecord) -> f64 {
    if first_order(r) { FIRST_ORDER_PAIR_TOLERANCE } else { PAIR_TOLERANCE }
}

/// A pair run with an analytical contact duration.
fn is_pair(r: &RunRecord) -> bool {
    r.spec.kind() == SceneKind::Pair && r.metrics.pair.contact_duration_theory.is_some()
}

/// The runs of `runs` nearest dt = t_c/50, one per scheme ([`scheme`]), Verlet's first and the
/// others in campaign order.
fn at_50_each<'a>(runs: &[&'a RunRecord]) -> Vec<&'a RunRecord> {
    let mut schemes: Vec<&str> = vec!["Verlet"];
    for r in runs {
        if !schemes.contains(&scheme(r.spec.integrator, true)) {
            schemes.push(scheme(r.spec.integrator, true));
        }
    }
    let of = |name: &str| -> Vec<&'a RunRecord> {
        runs.iter().copied().filter(|r| scheme(r.spec.integrator, true) == name).collect()
    };
    schemes.into_iter().filter_map(|name| at_50(&of(name))).collect()
}

/// Whether `runs` use more than one scheme: their sentences and tables then name each run's.
fn mixed(runs: &[&RunRecord]) -> bool {
    runs.iter().any(|r| scheme(r.spec.integrator, true) != scheme(runs[0].spec.integrator, true))
}

/// The order in dt at which a scheme's error falls: `p`, or where two errors of different
/// order add, anything from `p` up to `up_to` (the lower wins only at small enough dt), or
/// `at_least` `p` where only a lower bound holds.
#[derive(Clone, Copy)]
struct Order {
    p: u32,
    up_to: u32,
    at_least: bool,
}

impl Order {
    /// Order `p` exactly.
    const fn of(p: u32) -> Order {
        Order { p, up_to: p, at_least: false }
    }
}

/// How far below its order Gear's fitted order may fall: its six-value scheme is fifth order
/// once its start is accurate, measured 5.4–6 (docs/physics.md), never below 4.5
/// (tests/suite/integrators.rs holds the chain to that).
const GEAR_SLACK: f64 = 0.5;

/// The order of an undamped mode's phase, and so of an undamped bonded pair's t_c (a half
/// period). Symplectic Euler turns a mode as Verlet does (its step's matrix has the same trace
/// 2 − (ω dt)², so the same frequency 2 asin(ω dt/2)/dt): second order, not its energy's first.
fn phase_order(kind: IntegratorKind) -> Order {
    match kind {
        IntegratorKind::PositionVerlet | IntegratorKind::VelocityVerlet | IntegratorKind::SymplecticEuler => {
            Order::of(2)
        }
        IntegratorKind::Rk4 | IntegratorKind::ForestRuth => Order::of(4),
        IntegratorKind::Gear => Order { p: 5, up_to: 5, at_least: true },
    }
}

/// The order of positions and velocities together (the chain's normal-mode error): as the
/// phase's, but symplectic Euler's velocity lags its position by half a step, an O(dt) error
/// added to its second-order phase drift, which grows with the run and wins at coarse steps
/// (chain of 11 over 40 t_c: order 1.0 from t_c/50 to t_c/200, 1.34 fitted from t_c/10).
fn state_order(kind: IntegratorKind) -> Order {
    match kind {
        IntegratorKind::SymplecticEuler => Order { p: 1, up_to: 2, at_least: false },
        _ => phase_order(kind),
    }
}

/// Whether a `fitted` order meets the scheme's `order`: within `tolerance` of it (or of the
/// range from `p` to `up_to`), or for Gear not more than [`GEAR_SLACK`] below it.
fn meets(order: Order, fitted: f64, tolerance: f64) -> bool {
    if order.at_least {
        fitted >= order.p as f64 - GEAR_SLACK
    } else {
        fitted >= order.p as f64 - tolerance && fitted <= order.up_to as f64 + tolerance
    }
}

/// A scheme's order and what a fitted order must do to meet it, in words: "Verlet's second
/// order: the fitted order must lie within 0.1 of 2", or "… be at least 4.5" for Gear.
fn order_reference(kind: IntegratorKind, order: Order, tolerance: f64) -> String {
    let (name, p) = (scheme(kind, true), order.p as f64);
    if order.at_least {
        format!("{name}'s {} order or more: the fitted order must be at least {}", ordinal(order.p), p - GEAR_SLACK)
    } else if order.up_to > order.p {
        format!(
            "{name}'s {} order plus its {}-order phase drift: the fitted order must lie between {} and {}",
            ordinal(order.p),
            ordinal(order.up_to),
            p - tolerance,
            order.up_to as f64 + tolerance
        )
    } else {
        format!("{name}'s {} order: the fitted order must lie within {tolerance} of {}", ordinal(order.p), order.p)
    }
}

/// The run's time step in units of t_c: "t_c/50".
fn step_words(r: &RunRecord) -> String {
    format!("t_c/{}", number(r.spec.dt_per_tc()))
}

/// The distinct steps of `runs` in words: "t_c/50", or "t_c/5 and t_c/50".
fn steps_words(runs: &[&RunRecord]) -> String {
    let mut steps: Vec<String> = Vec::new();
    for step in runs.iter().map(|r| step_words(r)) {
        if !steps.contains(&step) {
            steps.push(step);
        }
    }
    crate::report::words::listed(&steps, "and")
}

/// The pair's case in words, with its integrator where the runs around it mix schemes
/// (`named`).
fn case(r: &RunRecord, named: bool) -> String {
    let law = law_name(r.spec.law);
    let joint = if r.spec.contact { "contact" } else { "bonded" };
    let damping = if r.spec.gamma > 0.0 { format!("γ = {} N s/m", sig(r.spec.gamma)) } else { "undamped".into() };
    let integrator = if named { format!(", {}", r.spec.integrator.name()) } else { String::new() };
    format!("{law} {joint}, {damping}{integrator}")
}

/// Relative errors of t_c and r.
type PairErrors = (Option<f64>, Option<f64>);

/// Errors of t_c and r of a pair run.
fn pair_errors(r: &RunRecord) -> PairErrors {
    let p = &r.metrics.pair;
    (relative(p.contact_duration, p.contact_duration_theory), relative(p.restitution, p.restitution_theory))
}

/// Order of convergence of `error` over the runs differing from `reference` only in dt.
fn order_of(e: &Evidence, reference: &RunRecord, error: impl Fn(&RunRecord) -> Option<f64>) -> Option<f64> {
    let label = crate::report::figure::group_label(reference);
    let points: Vec<(f64, f64)> = e
        .ok(|r| r.spec.scene == reference.spec.scene && crate::report::figure::group_label(r) == label)
        .into_iter()
        .filter_map(|r| error(r).map(|x| (r.spec.dt, x)))
        .collect();
    convergence_order(&points)
}

/// The linear pairs' cases at t_c/50, those the campaign has: bonded and contact, each undamped
/// and then every dashpot each scene ran (one γ per restitution target), so that no target's
/// runs drop out of the item's verdict; each case once per scheme, Verlet's first (so the first
/// run of a case is the coursework's where there is one).
fn pair_cases<'a>(linear: &[&'a RunRecord]) -> Vec<&'a RunRecord> {
    let mut cases = Vec::new();
    for contact in [false, true] {
        for damped in [false, true] {
            let runs: Vec<&RunRecord> = linear
                .iter()
                .copied()
                .filter(|r| r.spec.contact == contact && (r.spec.gamma > 0.0) == damped)
                .collect();
            let mut dashpots: Vec<(&str, f64)> = Vec::new();
            for key in runs.iter().map(|r| (r.spec.scene.as_str(), r.spec.gamma)) {
                if !dashpots.contains(&key) {
                    dashpots.push(key);
                }
            }
            for (scene, gamma) in dashpots {
                let same: Vec<&RunRecord> =
                    runs.iter().copied().filter(|r| r.spec.scene == scene && r.spec.gamma == gamma).collect();
                cases.extend(at_50_each(&same));
            }
        }
    }
    cases
}

/// [`pair_cases`] of `e`'s linear pairs.
fn linear_pair_cases<'a>(e: &Evidence<'a>) -> Vec<&'a RunRecord> {
    pair_cases(&e.ok(|r| is_pair(r) && r.spec.law == LawSpec::Linear))
}

/// The largest |relative error| of t_c and of r over `cases` (0 where none has one).
fn worst_errors(cases: &[&RunRecord]) -> (f64, f64) {
    let worst = |pick: fn(PairErrors) -> Option<f64>| {
        cases.iter().filter_map(|r| pick(pair_errors(r))).map(f64::abs).fold(0.0, f64::max)
    };
    (worst(|e| e.0), worst(|e| e.1))
}

/// The largest error of t_c over the two particles' cases (item 2) run at the rule dt = t_c/50,
/// for the Discussion: it states the rule with the item's own number, never a smaller one.
pub(super) fn pair_error_at_rule(e: &Evidence) -> Option<f64> {
    let at_rule: Vec<&RunRecord> =
        linear_pair_cases(e).into_iter().filter(|r| (r.spec.dt_per_tc() - 50.0).abs() < 1.0).collect();
    (!at_rule.is_empty()).then(|| worst_errors(&at_rule).0)
}

/// How far the energy balance E_kin + E_pot + E_dissipated = W may miss at dt = t_c/50: ten
/// times a second-order scheme's error there, about (ω dt)²/4 = (π/50)²/4 ≈ 1e-3; a force or
/// dashpot of the wrong sign misses by order 1. Schemes of higher order are held to it as well.
const BALANCE_TOLERANCE: f64 = 1e-2;

/// The same for a first-order scheme (symplectic Euler), whose energy oscillates by about
/// ω dt/2 = π/100 ≈ 0.03 at t_c/50: ten times that still tells a wrong sign (a dashpot feeding
/// energy in at r = 0.5 misses by 3).
const FIRST_ORDER_BALANCE_TOLERANCE: f64 = 0.3;

/// Runs whose integrator's energy error is of first order.
fn first_order(r: &RunRecord) -> bool {
    r.spec.integrator.energy_order() == 1
}

/// The worst energy balance of `balances` and its run.
fn worst_balance<'a>(balances: &[(f64, &'a RunRecord)]) -> Option<(f64, &'a RunRecord)> {
    balances.iter().copied().max_by(|a, b| a.0.total_cmp(&b.0))
}

/// The first-order runs' balance in a sentence, held to their own tolerance, and whether it holds.
fn first_order_balance(balances: &[(f64, &RunRecord)]) -> Option<(String, bool)> {
    let first: Vec<(f64, &RunRecord)> = balances.iter().copied().filter(|(_, r)| first_order(r)).collect();
    let (worst, run) = worst_balance(&first)?;
    let sentence = format!(
        "The first-order symplectic Euler ({} at t_c/50) is held to ten times its own energy error, about \
         ω dt/2 = π/100 ≈ 0.03 there for a pair, that is {FIRST_ORDER_BALANCE_TOLERANCE}: it holds to {} at worst \
         ({}), {} it.",
        counted(first.len(), "run"),
        sig(worst),
        run.spec.scene,
        if worst <= FIRST_ORDER_BALANCE_TOLERANCE { "within" } else { "outside" }
    );
    Some((sentence, worst <= FIRST_ORDER_BALANCE_TOLERANCE))
}

/// The force function and the loops in words: the signs of n̂, δ and f, and the connectivity
/// apart from the force and both apart from the integration.
fn force_design() -> Vec<String> {
    vec![
        "One function computes every spring's force (Spring::force_on_i, for every law and every scene): with \
         n̂ = (x_i − x_j)/|x_i − x_j| and δ = |x_i − x_j| − x_e (positive when stretched: the coursework's overlap \
         with the opposite sign), f_i = −(s(δ) + γ δ̇) n̂ with δ̇ = (v_i − v_j)·n̂, so a stretched spring pulls i \
         towards j and a closing dashpot pushes them apart; j receives f_j = −f_i from the same call, one call per \
         pair."
            .to_string(),
        "The connectivity is kept apart from the force: a chain's bonds are its neighbours, a lattice's its \
         stencil's bond families (or a bond list for irregular networks); every step resets the forces, loops \
         over the bonds adding f_i to i and −f_i to j, and only then integrates: the integrator sees summed \
         forces, never a spring."
            .to_string(),
    ]
}

/// The coursework's first requirement: one force function, the loops around it and its signs,
/// judged by what a wrong sign would break: the energy balance of every run at t_c/50.
pub(super) fn force_function(e: &Evidence) -> Option<Answer> {
    // A minimiser's steps (FIRE, CG) follow no equation of motion, so no energy balance checks them.
    let integrated = |r: &RunRecord| r.spec.relax().is_none_or(|relax| !relax.method.is_minimiser());
    let runs = e.ok(|r| (r.spec.dt_per_tc() - 50.0).abs() < 1.0 && !r.spec.allow_unstable && integrated(r));
    let all: Vec<(f64, &RunRecord)> = runs.iter().filter_map(|r| Some((r.metrics.energy_error?.abs(), *r))).collect();
    let balances: Vec<(f64, &RunRecord)> = all.iter().copied().filter(|(_, r)| !first_order(r)).collect();
    let first = first_order_balance(&all);
    let mut sentences = force_design();
    let worst = worst_balance(&balances).map(|(worst, run)| {
        sentences.push(second_order_balance(&balances, worst, run));
        worst
    });
    sentences.extend(first.iter().map(|(sentence, _)| sentence.clone()));
    let damped = linear_pair_cases(e).into_iter().find(|r| r.spec.gamma > 0.0);
    if let Some(r) = damped {
        sentences.push(format!(
            "The damped pair's restitution, r = {} for γ = {} N s/m, is below 1 as a dashpot's must be: one of the \
             wrong sign would feed energy in (r > 1).",
            cell(r.metrics.pair.restitution),
            sig(r.spec.gamma)
        ));
    }
    let (short_worst, short_count) = match worst {
        Some(worst) => (worst, balances.len()),
        None => (worst_balance(&all)?.0, all.len()),
    };
    let first_reference = if first.is_some() {
        format!("; {FIRST_ORDER_BALANCE_TOLERANCE} for the first-order symplectic Euler (ten times π/100)")
    } else {
        String::new()
    };
    Some(Answer {
        title: "The force function and the loops",
        question: "One function for the force of every spring (n̂, δ, signs), the connectivity apart from the \
                   force, both apart from the integration; f_i←j = −f_j←i.",
        short: format!(
            "one force function; energy balance within {} over {} at t_c/50",
            sig(short_worst),
            counted(short_count, "run")
        ),
        sentences,
        reference: format!(
            "Newton's third law by construction; the energy balance within {BALANCE_TOLERANCE:e} at t_c/50 (ten \
             times the second-order error (π/50)²/4 ≈ 1e-3){first_reference}."
        ),
        see_also: None,
        verdict: Verdict::of([
            worst.is_none_or(|worst| worst <= BALANCE_TOLERANCE),
            first.is_none_or(|(_, within)| within),
        ]),
        figures: Vec::new(),
        table: None,
    })
}

/// The balance of the runs of second or higher order in a sentence: the kinds of scene, how
/// many non-linear and damped, the worst and its scene.
fn second_order_balance(balances: &[(f64, &RunRecord)], worst: f64, worst_run: &RunRecord) -> String {
    let kinds: Vec<&str> = sorted_distinct(balances.iter().map(|(_, r)| r.spec.kind().name()));
    let count = |keep: fn(&RunRecord) -> bool| balances.iter().filter(|(_, r)| keep(r)).count();
    format!(
        "A wrong sign would break the energy balance E_kin + E_pot + E_dissipated = W: over the {} runs at \
             dt = t_c/50 ({}; {} with a non-linear law, {} damped) it holds to {} at worst ({}), the scheme's \
             O(dt{}) error.",
        balances.len(),
        kinds.join(", "),
        count(|r| !r.spec.law.is_linear()),
        count(|r| r.spec.gamma > 0.0 || r.spec.gamma_background > 0.0),
        sig(worst),
        worst_run.spec.scene,
        // That run's own order: Gear's and Verlet's energy balance are second order, RK4's fourth.
        if worst_run.spec.integrator.energy_order() == 4 { "⁴" } else { "²" }
    )
}

/// The abstract's sentence on two particles: the undamped contact duration against π/ω and the
/// damped restitution against its target.
pub(super) fn pair_headline(e: &Evidence) -> Option<String> {
    let cases = linear_pair_cases(e);
    let undamped = cases.iter().find(|r| r.spec.gamma == 0.0)?;
    let (t_err, _) = pair_errors(undamped);
    let damped = cases.iter().find(|r| r.spec.gamma > 0.0).map_or_else(String::new, |r| {
        format!(
            "; γ = {} N s/m gives r = {} for the target {}",
            sig(r.spec.gamma),
            cell(r.metrics.pair.restitution),
            cell(r.spec.restitution_target)
        )
    });
    Some(format!(
        "Two particles of {} kg on a spring of {} N/m stay in contact for t_c = π/ω = {} s, MD within {} of it at \
         dt = {}{damped}.",
        sig(undamped.spec.mass),
        sig(undamped.spec.k),
        sig(undamped.spec.t_c),
        t_err.map_or_else(|| "–".into(), |x| format!("{:.1e}", x.abs())),
        step_words(undamped)
    ))
}

/// Two particles: t_c and r against π/ω and exp(−γ t_c/m), undamped and damped.
pub(super) fn two_particles(e: &Evidence) -> Option<Answer> {
    let cases = linear_pair_cases(e);
    let first = *cases.first()?;
    let mut sentences = vec![format!(
        "Two particles of m = {} kg joined by k = {} N/m move with the reduced mass m/2: ω = √(2k/m − (γ/m)²), \
         t_c = π/ω = {} s undamped, and r = exp(−γ t_c/m).",
        sig(first.spec.mass),
        sig(first.spec.k),
        sig(first.spec.t_c)
    )];
    let mut checks = Vec::new();
    for r in &cases {
        let (sentence, within) = pair_case(e, r, mixed(&cases));
        checks.push(within);
        sentences.push(sentence);
    }
    sentences.extend(energy_gain(e));
    if let Some(damped) = cases.iter().find(|r| r.spec.gamma > 0.0) {
        sentences.push(format!(
            "The damping for r ≈ {} is γ = −ln r · √(2km)/√(π² + ln² r) = {} N s/m; the contact force is not clamped \
             to stay repulsive (clamping would raise r{}){}.",
            sig(damped.spec.restitution_target.unwrap_or(0.5)),
            sig(damped.spec.gamma),
            clamped(damped).map_or_else(String::new, |(_, clamped)| format!(" to {clamped:.3}")),
            full_mass_words(damped).map_or_else(String::new, |words| format!(", and {words}"))
        ));
    }
    let table = pair_table(&cases);
    let (worst_t, worst_r) = worst_errors(&cases);
    Some(Answer {
        title: "Two particles: contact duration and restitution",
        question: "Compare the pair's contact duration and restitution with the analytical solution, without and \
                   with dissipation; choose γ for r ≈ 0.5.",
        short: format!(
            "at {}: t_c within {worst_t:.1e} of π/ω, r within {worst_r:.1e} of exp(−γt_c/m)",
            steps_words(&cases)
        ),
        sentences,
        reference: pair_reference(&cases),
        see_also: None,
        verdict: Verdict::of(checks),
        figures: e.figures(&[
            ("pair-bonded", FigureKind::Energy),
            ("pair-bonded", FigureKind::Convergence),
            ("pair-contact", FigureKind::Convergence),
        ]),
        table: Some(table),
    })
}

/// The two particles' reference: the analytical oscillator and the tolerances of the `cases`'
/// schemes, the first-order symplectic Euler's only where it runs.
fn pair_reference(cases: &[&RunRecord]) -> String {
    let first = if cases.iter().any(|r| first_order(r)) {
        format!(
            "; {FIRST_ORDER_PAIR_TOLERANCE:e} for the first-order symplectic Euler (its velocity lags half a step, \
             ω dt/2 = π/100 there)"
        )
    } else {
        String::new()
    };
    format!(
        "Analytical damped oscillator of the reduced mass; tolerance {PAIR_TOLERANCE:e} at t_c/50 (a second-order \
         scheme errs by about (π/50)²/24 ≈ 1.6e-4 there){first}."
    )
}

/// What the full mass m in place of the reduced mass m/2 would make of the damped linear pair
/// among `e`'s runs at t_c/50 ([`full_mass_words`]), for the methods' appendix.
pub(super) fn full_mass_sentence(e: &Evidence) -> Option<String> {
    let cases = linear_pair_cases(e);
    full_mass_words(cases.into_iter().find(|r| r.spec.gamma > 0.0)?)
}

/// The damped linear pair among `e`'s runs at t_c/50 with its contact force clamped to stay
/// repulsive ([`crate::theory::clamped_restitution`]), for the methods' appendix.
pub(super) fn clamped_sentence(e: &Evidence) -> Option<String> {
    let cases = linear_pair_cases(e);
    let (reduced, clamped) = clamped(cases.into_iter().find(|r| r.spec.gamma > 0.0)?)?;
    Some(format!(
        "Clamping it would turn r = {reduced:.3} into {clamped:.3}: the pair would part where k δ + γ δ̇ first \
         vanishes, at the phase θ = ω_d t with tan θ = −γ ω_d/(k − γ²/m), before δ does"
    ))
}

/// The damped linear pair's restitution (r = exp(−γ t_c/m)) and what clamping its contact
/// force would make of it, from the run's k, m and γ.
fn clamped(r: &RunRecord) -> Option<(f64, f64)> {
    let (k, m, gamma) = (r.spec.k, r.spec.mass, r.spec.gamma);
    Some((crate::theory::linear_restitution(k, m, gamma).ok()?, crate::theory::clamped_restitution(k, m, gamma).ok()?))
}

/// The restitution a damped linear pair's γ would give with the full mass m used consistently
/// instead of m/2, against the reduced mass's: computed from the run's k, m and γ.
fn full_mass_words(r: &RunRecord) -> Option<String> {
    let (k, m, gamma) = (r.spec.k, r.spec.mass, r.spec.gamma);
    let reduced = crate::theory::linear_restitution(k, m, gamma).ok()?;
    let full = crate::theory::full_mass_restitution(k, m, gamma).ok()?;
    Some(format!(
        "using the full mass m instead of m/2 consistently (ω = √(k/m − (γ/2m)²), r = exp(−γ t_c/(2m))) would \
         give r = {:.3} for γ = {} N s/m, not the reduced mass's r = {:.3}",
        full,
        sig(gamma),
        reduced
    ))
}

/// One pair case at t_c/50 in a sentence, and whether it is within the tolerance (if not, the
/// sentence says why).
fn pair_case(e: &Evidence, r: &RunRecord, named: bool) -> (String, bool) {
    let (t_err, r_err) = pair_errors(r);
    let p = &r.metrics.pair;
    let tolerance = pair_tolerance(r);
    let within = [t_err, r_err].iter().flatten().all(|x| x.abs() <= tolerance);
    let mut sentence = format!(
        "{} at dt = t_c/{:.0}: t_c = {} s against {} s ({}), r = {} against {} ({}), energy balance kept to {}",
        case(r, named),
        r.spec.dt_per_tc(),
        cell(p.contact_duration),
        cell(p.contact_duration_theory),
        t_err.map(rel).unwrap_or_default(),
        cell(p.restitution),
        cell(p.restitution_theory),
        r_err.map(rel).unwrap_or_default(),
        r.metrics.energy_error.map(rel).unwrap_or_default(),
    );
    if !within {
        // The tolerance is of t_c and r; the energy balance before it is said, not judged here.
        let outside: Vec<String> = [("t_c", t_err), ("r", r_err)]
            .iter()
            .filter(|(_, x)| x.is_some_and(|x| x.abs() > tolerance))
            .map(|(name, _)| name.to_string())
            .collect();
        sentence += &format!("; {} outside {tolerance:e}", crate::report::words::listed(&outside, "and"));
        if let Some(order) = order_of(e, r, |x| pair_errors(x).1) {
            sentence += &format!("; the error falls at order {order:.2} with dt");
        }
    }
    (sentence + ".", within)
}

/// The pair cases at t_c/50 in one table.
fn pair_table(cases: &[&RunRecord]) -> Table {
    let named = mixed(cases);
    Table {
        header: ["case", "t_c/dt", "t_c (s)", "π/ω (s)", "error", "r", "exp(−γt_c/m)", "error"]
            .map(String::from)
            .to_vec(),
        rows: cases
            .iter()
            .map(|r| {
                let (t_err, r_err) = pair_errors(r);
                vec![
                    case(r, named),
                    format!("{:.0}", r.spec.dt_per_tc()),
                    cell(r.metrics.pair.contact_duration),
                    cell(r.metrics.pair.contact_duration_theory),
                    t_err.map(rel).unwrap_or_default(),
                    cell(r.metrics.pair.restitution),
                    cell(r.metrics.pair.restitution_theory),
                    r_err.map(rel).unwrap_or_default(),
                ]
            })
            .collect(),
    }
}

/// A restitution above 1 by less than this is round-off, not an energy gain: the velocity ratio
/// of a collision of a few hundred steps carries ~1e-14 of it.
const RESTITUTION_ROUND_OFF: f64 = 1e-12;

/// Undamped pairs whose restitution exceeds 1 beyond round-off: a result that contradicts
/// theory, said so.
fn energy_gain(e: &Evidence) -> Option<String> {
    let gains = e.ok(|r| {
        is_pair(r) && r.spec.gamma == 0.0 && r.metrics.pair.restitution.is_some_and(|x| x > 1.0 + RESTITUTION_ROUND_OFF)
    });
    let named = mixed(&e.ok(is_pair));
    let worst = gains.iter().max_by(|a, b| {
        a.metrics.pair.restitution.unwrap_or(0.0).total_cmp(&b.metrics.pair.restitution.unwrap_or(0.0))
    })?;
    Some(format!(
        "{} of the undamped runs give r > 1 beyond round-off ({RESTITUTION_ROUND_OFF:e}), which no passive spring \
         can: the largest, r = 1 + {:.2e} at t_c/{:.0} \
         ({}), is the scheme's energy error over the collision, not physics; it shrinks with dt.",
        gains.len(),
        worst.metrics.pair.restitution? - 1.0,
        worst.spec.dt_per_tc(),
        case(worst, named)
    ))
}

/// The time step: t_c of the pair, the coursework's t_c/50, larger and smaller steps, each
/// scheme's sweep held to its own order of t_c ([`phase_order`]). Without a sweep of dt there is
/// no order to judge: the item then says so and gives no verdict.
pub(super) fn time_step(e: &Evidence) -> Option<Answer> {
    let bonded = e.ok(|r| is_pair(r) && r.spec.law == LawSpec::Linear && !r.spec.contact && r.spec.gamma == 0.0);
    let reference = at_50(&bonded)?;
    let s = &reference.spec;
    let mut sentences = vec![format!(
        "For two particles of mass m = {} kg and stiffness k = {} N/m, {}, so the coursework's dt = t_c/50 = {} s. \
         Steps and durations are given in units of t_c (time.dt_per_tc, default 50, and time.duration_tc), so the \
         step is easy to estimate whatever m and k are; t_c itself would be 1 s with k = π² m/2 = {} N/m.",
        sig(s.mass),
        sig(s.k),
        contact_time_words(s),
        sig(s.t_c / 50.0),
        sig(std::f64::consts::PI.powi(2) * s.mass / 2.0)
    )];
    let (words, sweeps) = sweeps_words(e, &bonded);
    sentences.extend(words);
    let dt = format!("dt = t_c/50 = {} s", sig(s.t_c / 50.0));
    let named = sweeps.len() > 1;
    let orders: Vec<String> = sweeps
        .iter()
        .map(|(r, p)| if named { format!("dt^{p:.2} ({})", r.spec.integrator.name()) } else { format!("dt^{p:.2}") })
        .collect();
    let references: Vec<String> = at_50_each(&bonded)
        .iter()
        .map(|r| order_reference(r.spec.integrator, phase_order(r.spec.integrator), 0.1))
        .collect();
    Some(Answer {
        title: "The time step",
        question: "What is a good time step for two particles of mass m and stiffness k? Confirm with larger and \
                   smaller steps.",
        short: if sweeps.is_empty() {
            format!("{dt}; no dt sweep")
        } else {
            format!("{dt}; error ∝ {}", orders.join(", "))
        },
        sentences,
        reference: references.join("; ") + ".",
        see_also: None,
        verdict: if sweeps.is_empty() {
            Verdict::Observed
        } else {
            Verdict::of(sweeps.iter().map(|(r, p)| meets(phase_order(r.spec.integrator), *p, 0.1)))
        },
        figures: e.figures(&[
            ("pair-bonded", FigureKind::ErrorDt),
            ("pair-bonded", FigureKind::WorkPrecision),
            ("integrators", FigureKind::WorkPrecision),
        ]),
        table: None,
    })
}

/// The sweeps of dt of the `bonded` pairs in words, one per scheme with its fitted order of
/// t_c and the steps left out of it, and each swept scheme's run at t_c/50 with its order; a
/// campaign without a sweep is told how to make one.
fn sweeps_words<'a>(e: &Evidence, bonded: &[&'a RunRecord]) -> (Vec<String>, Vec<(&'a RunRecord, f64)>) {
    let sweeps: Vec<(&RunRecord, f64)> = at_50_each(bonded)
        .into_iter()
        .filter_map(|r| Some((r, order_of(e, r, |x: &RunRecord| pair_errors(x).0)?)))
        .collect();
    let mut sentences = Vec::new();
    if sweeps.is_empty() {
        sentences.push(
            "This campaign runs the pair at one time step only, so no order of convergence is measured: sweep \
             time.dt_per_tc (say 10 to 500) to confirm the choice with larger and smaller steps."
                .into(),
        );
    }
    for &(r, p) in &sweeps {
        sentences.extend(sweep_sentence(bonded, r, p));
        sentences.extend(failed_steps_sentence(e, r));
    }
    (sentences, sweeps)
}

/// The steps of the `reference`'s sweep (its scene, integrator and group) that did not finish
/// (a step past the integrator's limit, or one so large the particles pass through each
/// other), left out of it: each with its status and why.
fn failed_steps_sentence(e: &Evidence, reference: &RunRecord) -> Option<String> {
    let label = crate::report::figure::group_label(reference);
    let failed = e.all(|r| {
        r.spec.scene == reference.spec.scene
            && r.spec.integrator == reference.spec.integrator
            && crate::report::figure::group_label(r) == label
            && r.status != crate::sim::RunStatus::Ok
    });
    let each: Vec<String> =
        failed.iter().map(|r| format!("{} ({}: {})", step_words(r), r.status.as_str(), r.message)).collect();
    (!each.is_empty()).then(|| {
        format!(
            "Left out of the sweep, as {} did not finish: {}.",
            if failed.len() == 1 { "it" } else { "they" },
            crate::report::words::listed(&each, "and")
        )
    })
}

/// The time step's sweep in words: the fitted `order` of the error of t_c and its values at
/// the coarsest, the `reference` (t_c/50) and the finest step of the `bonded` pairs swept with it.
fn sweep_sentence(bonded: &[&RunRecord], reference: &RunRecord, order: f64) -> Option<String> {
    let t_error = |r: &RunRecord| pair_errors(r).0;
    let sweep: Vec<&RunRecord> = bonded
        .iter()
        .copied()
        .filter(|r| {
            r.spec.integrator == reference.spec.integrator
                && crate::report::figure::group_label(r) == crate::report::figure::group_label(reference)
        })
        .collect();
    let coarsest = sweep.iter().max_by(|a, b| a.spec.dt.total_cmp(&b.spec.dt))?;
    let finest = sweep.iter().min_by(|a, b| a.spec.dt.total_cmp(&b.spec.dt))?;
    Some(format!(
        "Over the sweep the error of t_c falls as dt^{order:.2} ({}): {} at {}, {} at {} and {} at {}.{}",
        reference.spec.integrator.name(),
        t_error(coarsest).map(rel).unwrap_or_default(),
        step_words(coarsest),
        t_error(reference).map(rel).unwrap_or_default(),
        step_words(reference),
        t_error(finest).map(rel).unwrap_or_default(),
        step_words(finest),
        cost_words(coarsest, reference, finest, t_error)
    ))
}

/// Performance against accuracy over the sweep: the cost of a run is its number of steps (one
/// force evaluation each, the same work per step at every dt), so a step n times smaller costs n
/// times as much; against that, how many times the error (`t_error`: of t_c, or a lattice's
/// energy) grows or shrinks.
pub(super) fn cost_words(
    coarsest: &RunRecord,
    reference: &RunRecord,
    finest: &RunRecord,
    t_error: impl Fn(&RunRecord) -> Option<f64>,
) -> String {
    let steps = |r: &RunRecord| r.spec.dt_per_tc();
    // (steps against the reference's, error against the reference's), for a run at another step
    // with a non-zero error.
    let against = |r: &RunRecord| {
        let (error, reference_error) = (t_error(r)?.abs(), t_error(reference)?.abs());
        (steps(r) != steps(reference) && error > 0.0 && reference_error > 0.0)
            .then(|| (steps(r) / steps(reference), error / reference_error))
    };
    // "5 times fewer": a ratio x as a factor above 1, the word saying which way.
    let times = |x: f64, write: fn(f64) -> String, [up, down]: [&str; 2]| {
        if x >= 1.0 { format!("{} times {up}", write(x)) } else { format!("{} times {down}", write(1.0 / x)) }
    };
    let words = |r: &RunRecord, (cost, error): (f64, f64)| {
        format!(
            "t_c/{:.0} takes {} steps for an error {}",
            steps(r),
            times(cost, number, ["more", "fewer"]),
            times(error, sig, ["larger", "smaller"])
        )
    };
    let parts: Vec<String> = [coarsest, finest].into_iter().filter_map(|r| Some(words(r, against(r)?))).collect();
    if parts.is_empty() {
        return String::new();
    }
    format!(
        " The cost is the steps, {:.0} per t_c at t_c/{:.0}: {} (the work–precision figures: error against run time).",
        steps(reference),
        steps(reference),
        parts.join(", ")
    )
}

/// The linear chain kicked between its walls that is held against its exact normal modes: the
/// run at t_c/50 (Verlet where there is one).
fn normal_mode_chain<'a>(e: &Evidence<'a>) -> Option<&'a RunRecord> {
    let linear = e.ok(|r| {
        r.spec.chain().is_some_and(|c| c.relax.is_none() && c.wave.is_none())
            && r.spec.movie.is_none()
            && r.spec.law == LawSpec::Linear
            && r.metrics.chain.chain_mode_error.is_some()
    });
    at_50(&linear)
}

/// N × 1 gives back the chain: the chain scenes run the 2D code's (n + 2) × 1 lattice, and
/// that row's motion is the chain's exact normal-mode solution to within its scheme's own
/// phase drift ([`top_mode_drift`]): the error, relative to the largest displacement, sums the
/// modes' drifts weighted by their share, so it stays below the top mode's unless the force or
/// the integration is wrong.
pub(super) fn chain_as_row(e: &Evidence) -> Option<Answer> {
    let reference = normal_mode_chain(e)?;
    let (spec, chain) = (&reference.spec, reference.spec.chain()?);
    let error = reference.metrics.chain.chain_mode_error?;
    let top = 2.0
        * (spec.k / spec.mass).sqrt()
        * (chain.n as f64 * std::f64::consts::PI / (2.0 * (chain.n + 1) as f64)).sin();
    let drift = top_mode_drift(spec.integrator);
    let own = drift.map_or(scheme(spec.integrator, true), |(own, ..)| own);
    let bound = drift.map(|(_, formula, c, p)| (formula, c * (top * spec.dt).powi(p) * top * spec.duration));
    // A phase error φ moves a mode by 2 sin(φ/2) of its amplitude, ≈ φ while φ is small; past
    // a radian any error up to 2 fits under it, and it tells nothing.
    let within = bound.filter(|(_, drift)| *drift <= MOST_TESTING_DRIFT).map(|(_, drift)| error <= drift);
    let sentences = vec![
        format!(
            "The chain of {} particles between walls is the 2D code's {} × 1 lattice: one row of the lattices' \
             stencil with its end nodes fixed as the walls, positions and velocities as 2D vectors, the one spring \
             force function and the same integrators. Every spring lies along x, so n̂ = (±1, 0) and no force acts \
             along y: the row moves as the 1D chain (the 1D scenes also hold y, which changes no bit of the run).",
            chain.n,
            chain.n + 2
        ),
        format!(
            "At dt = t_c/{:.0} over {} t_c its motion follows the chain's exact normal modes \
             ω_n = 2√(k/m) sin(nπ/(2(N+1))) to {} of its largest displacement and speed, {}",
            spec.dt_per_tc(),
            sig(spec.duration / spec.t_c),
            sig(error),
            row_verdict_words(own, spec.integrator == IntegratorKind::SymplecticEuler, error, bound, within)
        ),
    ];
    Some(Answer {
        title: "N × 1: the chain as a lattice",
        question: "Set up the code for N_x × N_y particles such that N × 1 gives back the linear chain.",
        short: format!("the {} × 1 lattice follows the chain's normal modes to {}", chain.n + 2, sig(error)),
        sentences,
        reference: match bound {
            Some((formula, _)) => format!(
                "The chain's exact normal-mode solution, within {own}'s phase drift of its top mode over the run, \
                 {formula}."
            ),
            None => format!("The chain's exact normal-mode solution; {own}'s error has no phase drift to bound it."),
        },
        see_also: None,
        verdict: within.map_or(Verdict::Observed, |within| Verdict::of([within])),
        figures: Vec::new(),
        table: None,
    })
}

/// A scheme's phase drift of a mode of ω over a run of T at dt, c ω (ω dt)^p T, as the scheme it
/// is named after, its formula, c and p: Verlet turns a mode at 2 asin(ω dt/2)/dt =
/// ω (1 + (ω dt)²/24 + …), and so does symplectic Euler (the same trace 2 − (ω dt)²; its
/// velocity's half-step lag comes on top, unbounded by it); RK4 at the argument of
/// 1 + iω dt − (ω dt)²/2 − i(ω dt)³/6 + (ω dt)⁴/24, ω (1 − (ω dt)⁴/120 + …) (its amplitude
/// loss, (ω dt)⁶/144 a step, is ω dt/1.2 times smaller); Forest–Ruth at the angle of its three
/// velocity-Verlet sub-steps' product, ω (1 − 0.0661 (ω dt)⁴ + …) (expanded numerically:
/// 0.06615 at ω dt = 0.02). Gear's phase error has no closed form here: `None`.
fn top_mode_drift(kind: IntegratorKind) -> Option<(&'static str, &'static str, f64, i32)> {
    match kind {
        IntegratorKind::PositionVerlet | IntegratorKind::VelocityVerlet | IntegratorKind::SymplecticEuler => {
            Some(("Verlet", "ω_N³ dt² T/24", 1.0 / 24.0, 2))
        }
        IntegratorKind::Rk4 => Some(("RK4", "ω_N⁵ dt⁴ T/120", 1.0 / 120.0, 4)),
        IntegratorKind::ForestRuth => Some(("Forest–Ruth", "0.0661 ω_N⁵ dt⁴ T", 0.0661, 4)),
        IntegratorKind::Gear => None,
    }
}

/// The row's error against the phase drift of the top mode its scheme shares with `own`
/// ([`top_mode_drift`]) in words: inside or beyond it and what that says, or why it is not
/// judged (`within` is `None`); symplectic Euler is told apart from Verlet (`lag`).
fn row_verdict_words(own: &str, lag: bool, error: f64, bound: Option<(&str, f64)>, within: Option<bool>) -> String {
    let Some((formula, drift)) = bound else {
        return format!(
            "which no phase drift bounds for {own} (its phase error has no closed form here), so N × 1 is not judged \
             here; item 4 holds its error to its order in dt."
        );
    };
    format!(
        "{} {own}'s phase drift of the top mode, {formula} = {} rad{}: {}.",
        if error <= drift { "inside" } else { "beyond" },
        sig(drift),
        if lag { ", which symplectic Euler's phase shares (its velocity lags half a step on top)" } else { "" },
        match within {
            None => "a drift of more than a radian bounds nothing (any error up to 2 fits under it), so this step \
                     cannot test the row: run it at a finer one"
                .to_string(),
            Some(true) => "N × 1 gives back the chain".to_string(),
            Some(false) => format!("more than {own}'s own error allows, so not the chain's answer at this step"),
        }
    )
}

/// The largest phase drift of the top mode (rad) that still bounds the row's error: the
/// displacement error 2 sin(φ/2) is within 4 % of φ up to φ = 1.
const MOST_TESTING_DRIFT: f64 = 1.0;

/// The coursework's choice of masses and springs for a chain of `n` particles: the chain's
/// total mass M is n m, so m = M/n; n + 1 springs of length a = L/(n + 1) in series are as stiff
/// as a rod of Young's modulus E and cross-section A, E A/L, when k = E A/a.
fn chain_mass_words(r: &RunRecord, n: usize) -> String {
    format!(
        "Its {n} particles of m = {} kg weigh n m = {} kg: a chain of mass M and length L takes m = M/n, and k = E A/a \
         (a = L/(n + 1), n + 1 springs in series) to be as stiff as a rod E A/L; here a = {} m, L = {} m.",
        number(r.spec.mass),
        number(r.spec.mass * n as f64),
        number(r.spec.spacing),
        number(r.spec.spacing * (n + 1) as f64)
    )
}

/// The chain of N kicked at its centre against its exact normal-mode solution.
pub(super) fn chain(e: &Evidence) -> Option<Answer> {
    let reference = normal_mode_chain(e)?;
    let chain = reference.spec.chain()?;
    let order = order_of(e, reference, |r| r.metrics.chain.chain_mode_error);
    // Positions and velocities both count in the error, so its order is the state's.
    let expected = state_order(reference.spec.integrator);
    let own = order_reference(reference.spec.integrator, expected, 0.2);
    let movies = e.movies(|r| r.spec.chain().is_some_and(|c| c.n == chain.n && c.relax.is_none()));
    let mut sentences = vec![
        format!(
            "A chain of {} particles between fixed walls, particle {} given v0 = {} m/s: at dt = t_c/{:.0} the MD \
             positions and velocities follow the exact normal-mode sum u_j(t) = Σ B_n sin(ω_n t) sin(njπ/(N+1)), \
             ω_n = 2√(k/m) sin(nπ/(2(N+1))), to {} over {} t_c, and the energy is kept to {}.",
            chain.n,
            chain.node,
            sig(reference.spec.v0),
            reference.spec.dt_per_tc(),
            cell(reference.metrics.chain.chain_mode_error),
            sig(reference.spec.duration / reference.spec.t_c),
            cell(reference.metrics.energy_error),
        ),
        match order {
            Some(p) => {
                format!("The error grows with time as the modes' phases drift and falls as dt^{p:.2} with the step.")
            }
            None => "The error grows with time as the modes' phases drift; its order in dt needs the scene at several \
                     time steps, which this campaign does not run, so it is not judged."
                .into(),
        },
    ];
    sentences.push(chain_mass_words(reference, chain.n));
    if !movies.is_empty() {
        sentences.push(
            "The movie shows the kick splitting into two pulses that run to the walls and reflect, particles coloured \
             by speed."
                .into(),
        );
    }
    let mut figures = e.figures(&[(&reference.spec.scene, FigureKind::Displacements)]);
    figures.extend(movies);
    Some(Answer {
        title: "The chain of 11, kicked at its centre",
        question: "Chain of 11 particles between walls, the central one given v0: display the motion, and a movie \
                   coloured by velocity.",
        short: format!(
            "normal modes matched to {} at t_c/{:.0}",
            cell(reference.metrics.chain.chain_mode_error),
            reference.spec.dt_per_tc()
        ),
        sentences,
        reference: format!("The exact normal-mode solution; the error must fall at {own}."),
        see_also: None,
        verdict: order.map_or(Verdict::Observed, |p| Verdict::of([meets(expected, p, 0.2)])),
        figures,
        table: None,
    })
}

/// Hertz springs in 1D: each power law's pair contact duration, the kicked chain's energy
/// balance, and each hit chain's solitary wave against Nesterenko's exponent: whichever of the
/// three the campaign ran.
pub(super) fn hertz_pair_and_chain(e: &Evidence) -> Option<Answer> {
    let pairs = e.ok(|r| is_pair(r) && r.spec.law != LawSpec::Linear);
    // Every exponent the pairs ran, each told and judged: one would hide the others' runs.
    let laws: Vec<PowerPairs> =
        exponents(pairs.iter().copied()).into_iter().filter_map(|b| power_pairs(&pairs, b)).collect();
    let chain = at_50(&kicked_power_chains(e));
    let waves = solitary_chain_waves(e);
    if laws.is_empty() && chain.is_none() && waves.is_empty() {
        return None;
    }
    let mut sentences: Vec<String> = laws.iter().map(|law| power_contact_words(law.told)).collect();
    let mut checks: Vec<bool> = laws.iter().map(|law| law.within).collect();
    if let Some(c) = chain {
        sentences.push(chain_energy_words(e, c));
        checks.push(c.metrics.energy_error.is_some_and(|x| x.abs() <= 1e-3));
    }
    sentences.extend(waves.iter().map(solitary_words));
    checks.extend(waves.iter().map(SolitaryFront::within));
    let short = laws.iter().map(power_pairs_short).chain(waves.iter().map(solitary_short)).collect::<Vec<_>>();
    Some(Answer {
        title: "Hertz springs in 1D",
        question: "Repeat the steps with a non-linear contact f ∝ C δ^β (Hertz, β = 3/2).",
        short: short.join("; "),
        sentences,
        reference: hertz_reference(!laws.is_empty(), chain.is_some(), !waves.is_empty()),
        see_also: None,
        verdict: Verdict::of(checks),
        figures: hertz_figures(e, &laws, &waves),
        table: None,
    })
}

/// The references of what the item told: the pairs' exact contact duration, the kicked
/// chain's energy balance, the solitary wave's exponent.
fn hertz_reference(pairs: bool, chain: bool, waves: bool) -> String {
    let parts = [
        pairs.then(|| format!("the exact Hertz contact duration (tolerance {PAIR_TOLERANCE:e} at t_c/50)")),
        chain.then(|| "the chain's energy balance to 1e-3 at t_c/50".to_string()),
        waves.then(|| format!("Nesterenko's solitary wave, V ∝ v0^((β − 1)/(β + 1)), within {EXPONENT_TOLERANCE}")),
    ];
    let told: Vec<String> = parts.into_iter().flatten().collect();
    format!("{}.", crate::report::words::capitalised(&told.join("; ")))
}

/// The undamped power-law chains kicked without a wave to time: their energy balance is told.
fn kicked_power_chains<'a>(e: &Evidence<'a>) -> Vec<&'a RunRecord> {
    e.ok(|r| {
        r.spec.chain().is_some_and(|c| c.relax.is_none() && c.wave.is_none())
            && r.spec.movie.is_none()
            && r.spec.law != LawSpec::Linear
            && r.spec.gamma == 0.0
    })
}

/// The power-law chain `c`'s energy balance at t_c/50 and its order in dt.
fn chain_energy_words(e: &Evidence, c: &RunRecord) -> String {
    let order = order_of(e, c, |r| r.metrics.energy_error);
    format!(
        "The Hertz chain of {} kicked at its centre has no normal modes to compare with; its energy balance holds to \
         {} at t_c/{:.0}{}.",
        c.spec.chain().map_or(0, |x| x.n),
        cell(c.metrics.energy_error),
        c.spec.dt_per_tc(),
        order.map_or(String::new(), |p| format!(" and improves as dt^{p:.2}"))
    )
}

/// The fits of a non-linear hit chain's front speed against v0, its solitary wave: each told
/// here but the one a kicked power-law lattice's item tells beside the lattice's own front
/// ([`SolitaryFront::kicked_lattice`]), so that each is said once.
fn solitary_chain_waves<'a>(e: &Evidence<'a>) -> Vec<SolitaryFront<'a>> {
    let beside = SolitaryFront::kicked_lattice(e).and_then(|(_, chain)| chain).map(|c| c.fit);
    SolitaryFront::all(e).filter(|f| !f.of_lattice(e) && beside.is_none_or(|b| !std::ptr::eq(b, f.fit))).collect()
}

/// A chain's solitary wave in words: its speeds over the kicks, the fitted exponent against
/// Nesterenko's. Two runs give an exponent (their ratio's) but no spread to test the power
/// law's form, and say so.
fn solitary_words(front: &SolitaryFront) -> String {
    let fit = front.fit;
    let (low, high) = (fit.points[0], fit.points[fit.points.len() - 1]);
    let group = if fit.group.is_empty() { String::new() } else { format!(", {}", fit.group) };
    let two = if fit.points.len() == 2 { " (two runs: their ratio, no spread to test the law's form)" } else { "" };
    format!(
        "Hit at v0 = {} to {} m/s ({}{group}), a {} chain carries a solitary wave, {} to {} m/s: V ∝ v0^{:.3} over \
         {}{two}, {}.",
        sig(low.0),
        sig(high.0),
        fit.scene,
        front.name(),
        sig(low.1),
        sig(high.1),
        fit.fit.exponent,
        counted(fit.points.len(), "run"),
        front.against_prediction()
    )
}

/// The summary's part of a chain's solitary wave.
fn solitary_short(front: &SolitaryFront) -> String {
    format!("chain V ∝ v0^{:.3} ({:.3})", front.fit.fit.exponent, front.predicted)
}

/// The item's figures: each exponent's pair convergence, each solitary wave's speeds against
/// v0, one movie of a non-linear chain.
fn hertz_figures(e: &Evidence, laws: &[PowerPairs], waves: &[SolitaryFront]) -> Vec<FigureRef> {
    let mut figures: Vec<FigureRef> =
        laws.iter().flat_map(|law| e.figures(&[(&law.told.spec.scene, FigureKind::Convergence)])).collect();
    figures.extend(waves.iter().flat_map(|w| e.figures(&[(&w.fit.scene, FigureKind::SpeedAgainstV0)])));
    // Two exponents of one scene (a grid over β) share its figure.
    figures.dedup_by(|a, b| a.file == b.file);
    figures.extend(e.movies(|r| r.spec.chain().is_some() && r.spec.law != LawSpec::Linear).into_iter().take(1));
    figures
}

/// One power law's undamped pairs at the step told: the run told (nearest t_c/50, Verlet's
/// first), the largest |error of t_c| over every run of the law at that step, and whether each
/// is within the item's stated [`PAIR_TOLERANCE`].
struct PowerPairs<'a> {
    told: &'a RunRecord,
    worst: f64,
    within: bool,
}

/// The undamped pairs of `pairs` with springs s ∝ δ^`beta`, told by one run, judged by all at
/// its step.
fn power_pairs<'a>(pairs: &[&'a RunRecord], beta: f64) -> Option<PowerPairs<'a>> {
    let law: Vec<&RunRecord> = pairs.iter().copied().filter(|r| r.spec.law.beta() == beta).collect();
    let told = at_50(&law)?;
    let judged: Vec<f64> = law
        .iter()
        .filter(|r| r.spec.dt_per_tc() == told.spec.dt_per_tc())
        .filter_map(|r| Some(pair_errors(r).0?.abs()))
        .collect();
    Some(PowerPairs {
        told,
        worst: judged.iter().copied().fold(0.0, f64::max),
        within: !judged.is_empty() && judged.iter().all(|&error| error <= PAIR_TOLERANCE),
    })
}

/// The summary's words of one power law: "Hertz t_c within 2.1e-4 of 2.9433 δ_max/v".
fn power_pairs_short(law: &PowerPairs) -> String {
    let beta = law.told.spec.law.beta();
    format!(
        "{} t_c within {} of {:.4} δ_max/v",
        if beta == 1.5 { "Hertz".to_string() } else { format!("β = {}:", number(beta)) },
        rel(law.worst).trim_start_matches('+'),
        duration_over_overlap(beta)
    )
}

/// A power-law contact's undamped duration over δ_max/v: 2 B(1/(β+1), ½)/(β+1) (2.9433 for
/// Hertz, π/2 for linear springs).
fn duration_over_overlap(beta: f64) -> f64 {
    2.0 * crate::theory::special::beta(1.0 / (beta + 1.0), 0.5) / (beta + 1.0)
}

/// The power-law pair's contact duration against the exact one, in a sentence: a contact's
/// collision, or a bonded pair's half period (a symmetric law swings out as long as in).
fn power_contact_words(pair: &RunRecord) -> String {
    let beta = pair.spec.law.beta();
    let (subject, hit, lasts) = if pair.spec.contact {
        ("A power-law contact", "hit at", "lasts")
    } else {
        ("A bonded power-law pair", "given", "swings half a period in")
    };
    format!(
        "{subject} s = C δ^{} (Hertz: β = 3/2) {hit} v = {} m/s {lasts} t_c = 2 (δ_max/v) B(1/(β+1), ½)/(β+1) \
         with δ_max = ((β+1)(m/2)v²/(2C))^(1/(β+1)), i.e. {:.4} δ_max/v for β = {}: MD gives {} s against {} s \
         ({}) at t_c/{:.0}, and r = {} (no damping: 1).",
        sig(beta),
        sig(pair.spec.v0),
        duration_over_overlap(beta),
        number(beta),
        cell(pair.metrics.pair.contact_duration),
        cell(pair.metrics.pair.contact_duration_theory),
        pair_errors(pair).0.map(rel).unwrap_or_default(),
        pair.spec.dt_per_tc(),
        cell(pair.metrics.pair.restitution),
    )
}

/// The chain between walls moved in and out: equal gaps, secant and tangent stiffness.
pub(super) fn walls(e: &Evidence) -> Option<Answer> {
    let relaxed =
        e.ok(|r| r.spec.chain().is_some_and(|c| c.relax.is_some()) && r.metrics.chain.secant_stiffness.is_some());
    let first = *relaxed.first()?;
    let betas = exponents(relaxed.iter().copied());
    let (mut sentences, mut checks) = (Vec::new(), Vec::new());
    for &beta in &betas {
        let law: Vec<&RunRecord> = relaxed.iter().copied().filter(|r| r.spec.law.beta() == beta).collect();
        if let Some((sentence, within)) = walls_sentence(first, &law, beta) {
            sentences.push(sentence);
            checks.push(within);
        }
    }
    let mut scenes: Vec<String> = relaxed.iter().map(|r| r.spec.scene.clone()).collect();
    scenes.dedup();
    for fit in scenes.iter().filter_map(|s| e.fit(s, "secant_stiffness").filter(|f| f.law != "linear")) {
        let Some(predicted) = super::finding::predicted_exponent(fit) else { continue };
        sentences.push(format!(
            "Fitted over |ΔW| from {} to {} m: {}'s secant stiffness ∝ |ΔW|^{:.3} ({}) against the predicted \
             β − 1 = {predicted:.3}.",
            sig(fit.points.first().map_or(0.0, |p| p.0)),
            sig(fit.points.last().map_or(0.0, |p| p.0)),
            fit.scene,
            fit.fit.exponent,
            crate::report::words::fit_quality(&fit.fit, 4)
        ));
        checks.push((fit.fit.exponent - predicted).abs() <= super::finding::EXPONENT_TOLERANCE);
    }
    let figures = scenes.iter().filter_map(|s| e.figure(s, FigureKind::AgainstWallDisplacement)).collect();
    Some(Answer {
        title: "The chain between moved walls",
        question: "Move the walls of the chain to different distances and analyse the equilibria (linear and \
                   non-linear).",
        short: walls_short(&betas),
        sentences,
        reference: format!(
            "Static equilibrium of n+1 equal springs; tolerance {WALL_TOLERANCE:e} ({}); power-law springs s ∝ δ^β: \
             the exponent within {} of β − 1 (Hertz: 1/2).",
            stopping_words(&relaxed),
            super::finding::EXPONENT_TOLERANCE
        ),
        see_also: None,
        verdict: Verdict::of(checks),
        figures,
        table: None,
    })
}

/// The summary's line of the walls: equal gaps, and each law's stiffness against |ΔW|.
fn walls_short(betas: &[f64]) -> String {
    let laws: Vec<String> = betas
        .iter()
        .map(|&beta| match beta {
            1.0 => "linear stiffness k/(n+1)".to_string(),
            1.5 => "Hertz ∝ |ΔW|^½".to_string(),
            _ => format!("β = {} ∝ |ΔW|^{}", number(beta), number(beta - 1.0)),
        })
        .collect();
    format!("equal gaps; {}", laws.join(", "))
}

/// The relaxed chains of one law (springs s ∝ δ^`beta`) against the static answer in a
/// sentence, and whether spacing and stiffness are within [`WALL_TOLERANCE`].
fn walls_sentence(first: &RunRecord, runs: &[&RunRecord], beta: f64) -> Option<(String, bool)> {
    // The error of the largest magnitude, with its sign (a chain softer than k/(n+1) is −).
    let worst = |pair: fn(&RunRecord) -> PairErrors| {
        runs.iter().filter_map(|r| relative(pair(r).0, pair(r).1)).max_by(|a, b| a.abs().total_cmp(&b.abs()))
    };
    let sp = worst(|r| (r.metrics.chain.equilibrium_spacing, r.metrics.chain.equilibrium_spacing_theory))?;
    let se = worst(|r| (r.metrics.chain.secant_stiffness, r.metrics.chain.secant_stiffness_theory)).unwrap_or(0.0);
    let ta = worst(|r| (r.metrics.chain.tangent_stiffness, r.metrics.chain.tangent_stiffness_theory)).unwrap_or(0.0);
    let n = first.spec.chain().map_or(0, |c| c.n);
    let sentence = if beta == 1.0 {
        format!(
            "Linear springs: the {n} particles relax to equal gaps W/(n+1) (W the walls' distance; largest error {}), and the chain's \
             secant and tangent stiffness equal k/(n+1) = {} N/m at every wall displacement (errors {} and {}).",
            rel(sp),
            sig(first.spec.k / (n as f64 + 1.0)),
            rel(se),
            rel(ta)
        )
    } else {
        format!(
            "{} springs (β = {}): equal gaps again (error {}), but the stiffness depends on how far the walls moved: \
             secant and tangent follow s(δ)/ΔW (ΔW the walls' displacement) and s′(δ)/(n+1) (errors {} and {}); the \
             tangent is {} × the secant (β) and an unloaded chain of them has no stiffness at all.",
            if beta == 1.5 { "Hertz" } else { "Power-law" },
            number(beta),
            rel(sp),
            rel(se),
            rel(ta),
            number(beta)
        )
    };
    Some((sentence, sp.abs().max(se.abs()).max(ta.abs()) <= WALL_TOLERANCE))
}

/// How the relaxed chains stopped, from their specs: at a residual force (a fraction of the
/// equilibrium wall force) or when E_kin/E_pot stays below its ratio; each distinct rule once.
fn stopping_words(relaxed: &[&RunRecord]) -> String {
    let mut rules: Vec<String> = Vec::new();
    for relax in relaxed.iter().filter_map(|r| r.spec.chain()?.relax) {
        let rule = match relax.residual_force {
            Some(force) => format!("a residual force of {force:e} of the equilibrium wall force"),
            None => format!("E_kin/E_pot below {:e}", relax.kinetic_ratio),
        };
        if !rules.contains(&rule) {
            rules.push(rule);
        }
    }
    format!("the relaxation stops at {}", crate::report::words::listed(&rules, "or"))
}

/// Relative tolerance on a relaxed chain's spacing and stiffness against the static answer.
const WALL_TOLERANCE: f64 = 1e-3;
