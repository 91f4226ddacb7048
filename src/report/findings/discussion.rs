//! The report's discussion: linear against non-linear springs, with against without diagonals,
//! bond against background damping and the one time step to use, each a paragraph computed from
//! the campaign's results.

use serde::Serialize;

use super::finding::{
    Answer, EXPONENT_TOLERANCE, Evidence, Table, Verdict, cell, distinct_exponents, fastest_relaxation, noise,
    predicted_exponent, regular, sig, size_on_coursework_supports,
};
use crate::model::LawSpec;
use crate::report::figure::FigureKind;
use crate::report::figure::{background_damping_only, bond_damping_only};
use crate::report::words;
use crate::runner::RunRecord;
use crate::sim::{PreconditionerKind, RelaxMethod, RunStatus};
use crate::spec::{Deformation, Diagonals, LoadCase, SceneKind};
use crate::summary::ScalingFit;

/// One paragraph of the discussion.
#[derive(Serialize)]
pub struct Paragraph {
    /// What it weighs.
    pub title: &'static str,
    /// The paragraph.
    pub text: String,
}

/// The discussion's paragraphs that `e` has the runs for: the coursework's themes, from its
/// evidence (square lattices relaxed by MD, `Evidence::coursework`).
pub fn discussion(e: &Evidence) -> Vec<Paragraph> {
    let e = &e.coursework();
    [linear_against_hertz(e), diagonals(e), damping(e), time_step(e)].into_iter().flatten().collect()
}

/// The fitted laws of `fits` in words, one per variable and exponent as written, with the
/// quantities that share it and (`scenes`) their scenes: "E and G ∝ the load per node F^0.333 (a, b)".
fn shared_laws<'a>(fits: impl Iterator<Item = &'a ScalingFit>, scenes: bool) -> Vec<String> {
    let mut laws: Vec<(String, Vec<String>, Vec<&str>)> = Vec::new();
    for f in fits {
        let against = format!("{}^{}", symbol(f.against), exponent(f.fit.exponent));
        let (quantity, scene) = (symbol(f.quantity), f.scene.as_str());
        match laws.iter_mut().find(|(a, _, _)| *a == against) {
            Some((_, quantities, shared)) => {
                (!quantities.contains(&quantity)).then(|| quantities.push(quantity));
                (!shared.contains(&scene)).then(|| shared.push(scene));
            }
            None => laws.push((against, vec![quantity], vec![scene])),
        }
    }
    let named = |s: &[&str]| if scenes { format!(" ({})", s.join(", ")) } else { String::new() };
    laws.iter().map(|(against, q, s)| format!("{} ∝ {against}{}", words::listed(q, "and"), named(s))).collect()
}

/// Exponents of the fitted scaling laws, linear against power-law springs.
fn linear_against_hertz(e: &Evidence) -> Option<Paragraph> {
    let hertz = shared_laws(e.fits.iter().filter(|f| f.law != "linear"), true);
    let linear = shared_laws(e.fits.iter().filter(|f| f.law == "linear"), false);
    (!hertz.is_empty()).then(|| Paragraph {
        title: "Linear against non-linear springs",
        text: format!(
            "A linear spring's stiffness does not depend on how far it is stretched, so nothing a linear network \
             does depends on the amplitude: here {}. A {} spring stiffens as it deforms and has no stiffness at \
             rest: its contact duration shortens with the impact speed, a chain between walls stiffens as the walls \
             move, the lattice's moduli grow with the load and its waves speed up with the kick: here {}. Superposition, \
             normal modes and one sound speed are linear ideas.",
            if linear.is_empty() { "no sweep over the amplitude".to_string() } else { linear.join(", ") },
            nonlinear_name(e),
            hertz.join(", ")
        ) + &two_d_numbers(e).map_or_else(String::new, |s| format!(" {s}")),
    })
}

/// The 2D difference in numbers: the loaded Hertz block's Young's modulus over its loads beside
/// the linear block's of the same size, supports and constant at one of those loads, and the
/// kicked Hertz lattice's front speeds beside the linear lattice's.
fn two_d_numbers(e: &Evidence) -> Option<String> {
    let loaded = |r: &RunRecord| {
        r.spec
            .lattice()
            .is_some_and(|l| l.impulse.is_none() && !l.is_random() && l.load_case == LoadCase::Tensile && !l.rotated)
            && r.metrics.lattice.youngs_modulus.is_some()
    };
    let mut hertz = e.ok(|r| !r.spec.law.is_linear() && loaded(r));
    hertz.sort_by(|a, b| load(a).total_cmp(&load(b)));
    let (soft, stiff) = (*hertz.first()?, *hertz.last()?);
    let same = |r: &RunRecord, h: &RunRecord| {
        let (l, m) = (r.spec.lattice(), h.spec.lattice());
        r.spec.k == h.spec.k
            && l.zip(m).is_some_and(|(l, m)| (l.nx, l.supports, l.diagonals) == (m.nx, m.supports, m.diagonals))
    };
    let linear = e.ok(|r| r.spec.law.is_linear() && loaded(r));
    let (twin, at) =
        hertz.iter().find_map(|h| linear.iter().find(|r| same(r, h) && load(r) == load(h)).map(|r| (*r, *h)))?;
    let l = twin.spec.lattice()?;
    Some(format!(
        "In 2D: the linear {} × {} block on {} supports has E = {} Pa at {} N per node (being linear, at any \
         load); the Hertz block whose springs have the same constant (C = {} N/m^{} against k = {} N/m) has {} Pa at \
         the same load, and from {} Pa at {} N to {} Pa at {} N: ×{} for ×{} the load.",
        l.nx,
        l.ny,
        l.supports.name(),
        cell(twin.metrics.lattice.youngs_modulus),
        sig(load(at)),
        sig(at.spec.k),
        at.spec.law.beta(),
        sig(twin.spec.k),
        cell(at.metrics.lattice.youngs_modulus),
        cell(soft.metrics.lattice.youngs_modulus),
        sig(load(soft)),
        cell(stiff.metrics.lattice.youngs_modulus),
        sig(load(stiff)),
        sig(stiff.metrics.lattice.youngs_modulus? / soft.metrics.lattice.youngs_modulus?),
        sig(load(stiff) / load(soft))
    ))
}

/// The load per node (N) of a loaded lattice, 0 for any other run.
fn load(r: &RunRecord) -> f64 {
    r.spec.lattice().map_or(0.0, |l| l.load_per_node)
}

/// The square lattice with and without diagonal springs.
fn diagonals(e: &Evidence) -> Option<Paragraph> {
    // Pulled along y (not turned), k_x = k_y, linear, uncut: E is then k/d, ν 0, without diagonals.
    let tensile =
        |d: Diagonals| e.ok(|r| regular(r).is_some_and(|l| l.diagonals == d && l.load_case == LoadCase::Tensile));
    let (none, both) = (tensile(Diagonals::None), tensile(Diagonals::Both));
    // The two runs compared are the same block but for the diagonals: the largest without
    // them (the coursework's supports first), and with them on the same supports and size.
    let n = largest(&none)?;
    let alike =
        |r: &&&RunRecord| r.spec.lattice().map(|l| (l.supports, l.nx)) == n.spec.lattice().map(|l| (l.supports, l.nx));
    let b = *both.iter().filter(alike).find(|r| r.spec.scene == n.spec.scene).or_else(|| both.iter().find(alike))?;
    let supports = n.spec.lattice().map_or("", |l| l.supports.name());
    // Every sheared square lattice without diagonals, cut or not: how many were mechanisms.
    let sheared = e.all(|r| {
        r.spec
            .lattice()
            .is_some_and(|l| l.diagonals == Diagonals::None && l.load_case == LoadCase::Shear && l.impulse.is_none())
    });
    let floppy = sheared.iter().filter(|r| r.status == RunStatus::Mechanism).count();
    let shear = match sheared.len() {
        0 => String::new(),
        all => format!(" ({floppy} of its {all} shear runs end as mechanism)"),
    };
    Some(Paragraph {
        title: "With and without diagonals",
        text: format!(
            "Without diagonals a square lattice is a set of independent chains: on {} × {} ({supports} supports), \
             E = {} Pa (k/d up to the finite size), ν = {}, no shear stiffness{shear}, \
             and a kick stays in its column. The diagonals tie rows to columns: on the same block, E = {} Pa and \
             ν = {}, and on the periodic strip G = k_d/d: a solid that contracts sideways, carries shear and spreads a \
             kick.",
            n.spec.lattice().map_or(0, |l| l.nx),
            n.spec.lattice().map_or(0, |l| l.ny),
            cell(n.metrics.lattice.youngs_modulus),
            noise(n.metrics.lattice.poisson_ratio, 1.0),
            cell(b.metrics.lattice.youngs_modulus),
            noise(b.metrics.lattice.poisson_ratio, 1.0),
        ),
    })
}

/// The run of the largest lattice among `runs`, on the coursework's supports where there is a
/// choice.
fn largest<'a>(runs: &[&'a RunRecord]) -> Option<&'a RunRecord> {
    runs.iter().copied().max_by_key(|r| size_on_coursework_supports(r))
}

/// Bond damping against background damping.
fn damping(e: &Evidence) -> Option<Paragraph> {
    let time = |alone: fn(&RunRecord) -> bool| fastest_relaxation(&e.ok(|r| r.spec.lattice().is_some() && alone(r)));
    let (bond, background) = (time(bond_damping_only), time(background_damping_only));
    (bond.is_finite() && background.is_finite()).then(|| Paragraph {
        title: "Bond against background damping",
        text: format!(
            "Bond damping is physical (it sets each spring's restitution) but acts only on relative motion, which the \
             slow, nearly rigid modes of a block barely have: the fastest bond-damped relaxation here takes {} s; \
             background damping, on every node's velocity, {} s, {}. Static answers (moduli) want \
             background damping near the slowest mode's critical value, dynamics (restitution) the bond damping alone.",
            sig(bond),
            sig(background),
            crate::report::words::times(bond / background, "faster", "slower")
        ),
    })
}

/// A fitted exponent with three decimals, a round-off of zero written 0.000 (not −0.000).
fn exponent(p: f64) -> String {
    crate::report::words::exponent(p, 3)
}

/// One time-step recommendation for every scene, each sentence said only where this campaign
/// has what it speaks of: pairs, the integrated networks' fastest modes, minimisers, power-law
/// springs, a time-step sweep of a network by a Verlet scheme, work–precision figures.
fn time_step(e: &Evidence) -> Option<Paragraph> {
    let rule_dt = |r: &RunRecord| (r.spec.dt_per_tc() - 50.0).abs() < 1.0;
    let at_rule = |r: &RunRecord| r.metrics.dt_omega_max.is_some() && rule_dt(r);
    let linear = e.ok(|r| r.spec.law == LawSpec::Linear && at_rule(r));
    let power = e.ok(|r| r.spec.law != LawSpec::Linear && at_rule(r));
    if linear.is_empty() && power.is_empty() {
        return None;
    }
    // Item 2's worst at the rule, every damping target and scheme counted: the summary's number.
    let pair_error = super::one_d::pair_error_at_rule(e);
    let integrated: Vec<&RunRecord> = linear
        .iter()
        .copied()
        .filter(|r| r.spec.kind() != SceneKind::Pair && !minimised(r) && !r.spec.static_only())
        .collect();
    let text = [
        Some(rule_words(pair_error)),
        fastest_mode_words(&integrated, verlet_network_sweep(e)),
        // Every minimised run, relaxed or not: a method whose runs all failed is still used.
        minimiser_words(
            &e.all(|r| rule_dt(r) && minimised(r)),
            &e.ok(|r| at_rule(r) && !minimised(r) && matches!(r.spec.kind(), SceneKind::Chain | SceneKind::Lattice)),
        ),
        power_law_words(&power),
        e.has_figure(FigureKind::WorkPrecision)
            .then(|| "The work–precision figures give the largest dt for a stated error.".to_string()),
    ];
    Some(Paragraph { title: "The time step", text: text.into_iter().flatten().collect::<Vec<_>>().join(" ") })
}

/// True for a run relaxed by a minimiser (FIRE, CG), which follows no trajectory in time.
fn minimised(r: &RunRecord) -> bool {
    r.spec.relax().is_some_and(|relax| relax.method.is_minimiser())
}

/// True when a network (chain or lattice) of the campaign ran at several dt by a Verlet scheme,
/// whose second order the "errors fall as dt²" of [`fastest_mode_words`] stands on.
fn verlet_network_sweep(e: &Evidence) -> bool {
    let verlet = e.ok(|r| {
        matches!(r.spec.kind(), SceneKind::Chain | SceneKind::Lattice)
            && !minimised(r)
            && r.spec.integrator.name().ends_with("verlet")
    });
    verlet.iter().any(|a| verlet.iter().any(|b| a.spec.scene == b.spec.scene && a.spec.dt != b.spec.dt))
}

/// The rule, with the pairs' largest error `pair_error` in t_c at it.
fn rule_words(pair_error: Option<f64>) -> String {
    let pairs = pair_error.map_or(String::new(), |error| format!(" On two particles it keeps t_c to {error:.1e}."));
    format!(
        "One rule serves every scene: dt = t_c/50 with t_c the contact time of two of the scene's masses on its \
         spring k (material.k): π√(m/(2k)) undamped, \
         π/√(2k/m − (γ/m)²) with its bond dashpot.{pairs}"
    )
}

/// The fastest mode of the `integrated` networks at the rule, against each run's own stability
/// limit (2 for undamped Verlet, less with damping: `plan::stability`), and their order when
/// `swept`.
fn fastest_mode_words(integrated: &[&RunRecord], swept: bool) -> Option<String> {
    let largest = integrated.iter().filter_map(|r| r.metrics.dt_omega_max).reduce(f64::max)?;
    let share = integrated
        .iter()
        .filter_map(|r| Some(r.metrics.dt_omega_max? / r.metrics.stability_limit?))
        .reduce(f64::max)
        .map_or(String::new(), |share| {
            format!(", at most {} of the run's own stability limit (2 for undamped Verlet)", sig(share))
        });
    Some(format!(
        "On the {} of this campaign it puts the fastest mode at dt·ω_max ≤ {}{share}{}; each run checks its \
         fastest mode first, so stiffer springs than k (k_y, the diagonals) are caught.",
        kinds_in_words(integrated),
        sig(largest),
        if swept { ", and errors fall as dt²" } else { "" }
    ))
}

/// What the rule's dt is to the `runs` relaxed by a minimiser (of any status): FIRE in the
/// masses' metric steps from dt up to 10 dt, so its largest step is held against the limit 2;
/// FIRE in the stiffness's metric takes a step of its own and CG none, so dt bounds nothing
/// there. Where networks of the same kind are `integrated` in time, the minimised ones are named
/// by scene; each method's runs that did not relax are counted.
fn minimiser_words(runs: &[&RunRecord], integrated: &[&RunRecord]) -> Option<String> {
    let uses = |method: RelaxMethod| runs.iter().any(|r| r.spec.relax().is_some_and(|x| x.method == method));
    let used: Vec<(RelaxMethod, &str)> = [(RelaxMethod::Fire, "FIRE"), (RelaxMethod::Cg, "conjugate gradients")]
        .into_iter()
        .filter(|&(method, _)| uses(method))
        .collect();
    let methods: Vec<String> = used.iter().map(|(_, name)| name.to_string()).collect();
    // FIRE in the masses' metric steps from dt up to 10 dt: its largest step meets ω_max there.
    let fire_largest = runs
        .iter()
        .filter(|r| {
            r.spec
                .relax()
                .is_some_and(|x| x.method == RelaxMethod::Fire && x.preconditioner == PreconditionerKind::None)
        })
        .filter_map(|r| r.metrics.dt_omega_max)
        .reduce(f64::max);
    let bound = match fire_largest {
        Some(x) => format!(
            ": FIRE's step grows from dt to at most Δt_max = 10 dt and is halved whenever the motion turns uphill; \
             here ω_max Δt_max ≤ {}, {} the limit 2 of its semi-implicit Euler",
            sig(10.0 * x),
            if 10.0 * x < 2.0 { "inside" } else { "beyond (the halving keeps it stable)" }
        ),
        None => ": for them dt·ω_max is no stability bound".into(),
    };
    let kinds = kinds_in_words(runs);
    let whose = if integrated.iter().any(|r| runs.iter().any(|m| m.spec.kind() == r.spec.kind())) {
        let mut scenes: Vec<String> = runs.iter().map(|r| r.spec.scene.clone()).collect();
        scenes.dedup();
        format!("{kinds} of scene{} {}", if scenes.len() > 1 { "s" } else { "" }, words::listed(&scenes, "and"))
    } else {
        format!("{kinds} of this campaign")
    };
    let unrelaxed = unrelaxed_words(runs, &used).map_or_else(String::new, |u| format!("; {u}"));
    (!methods.is_empty()).then(|| {
        format!(
            "The {whose} are relaxed by a minimiser ({}), not followed in time{bound}{unrelaxed}.",
            words::listed(&methods, "or")
        )
    })
}

/// The minimised `runs` that ended unrelaxed, per method of `used`: "all 9 runs by FIRE and 9
/// of the 18 runs by conjugate gradients ended unrelaxed (status no_equilibrium)"; `None` when
/// every one relaxed.
fn unrelaxed_words(runs: &[&RunRecord], used: &[(RelaxMethod, &str)]) -> Option<String> {
    let mut statuses: Vec<String> = Vec::new();
    let counts: Vec<String> = used
        .iter()
        .filter_map(|&(method, name)| {
            let mine: Vec<&RunRecord> =
                runs.iter().copied().filter(|r| r.spec.relax().is_some_and(|x| x.method == method)).collect();
            let failed: Vec<&RunRecord> = mine.iter().copied().filter(|r| r.status != RunStatus::Ok).collect();
            for r in &failed {
                let status = r.status.as_str().to_string();
                (!statuses.contains(&status)).then(|| statuses.push(status));
            }
            match (failed.len(), mine.len()) {
                (0, _) => None,
                (1, 1) => Some(format!("the one run by {name}")),
                (f, all) if f == all => Some(format!("all {all} runs by {name}")),
                (f, all) => Some(format!("{f} of the {all} runs by {name}")),
            }
        })
        .collect();
    (!counts.is_empty()).then(|| {
        format!("{} ended unrelaxed (status {})", words::listed(&counts, "and"), words::listed(&statuses, "or"))
    })
}

/// Where the power-law springs of `power` take their t_c: each run's expected deformation.
fn power_law_words(power: &[&RunRecord]) -> Option<String> {
    let mut expected: Vec<String> = Vec::new();
    for deformation in power.iter().map(|r| deformation_words(r.spec.kind(), r.spec.deformation())) {
        if !expected.contains(&deformation) {
            expected.push(deformation);
        }
    }
    (!expected.is_empty()).then(|| {
        format!(
            "A Hertz spring's t_c depends on the amplitude: it is taken at the deformation the scene expects ({}).",
            words::listed(&expected, "or")
        )
    })
}

/// The scene kinds of `runs` in the plural, each once, in the order of [`SceneKind::ALL`]:
/// "chains and lattices".
fn kinds_in_words(runs: &[&RunRecord]) -> String {
    let kinds: Vec<String> = SceneKind::ALL
        .into_iter()
        .filter(|&k| runs.iter().any(|r| r.spec.kind() == k))
        .map(|k| format!("{}s", k.name()))
        .collect();
    words::listed(&kinds, "and")
}

/// A run's expected deformation (`RunSpec::deformation`) in words, by its scene's kind.
fn deformation_words(kind: SceneKind, deformation: Deformation) -> String {
    match (kind, deformation) {
        (_, Deformation::Collision(_)) => "the impact speed".into(),
        (_, Deformation::Carrying(_)) => "the force a spring carries".into(),
        (SceneKind::Chain, Deformation::Extension(_)) => "the walls' displacement".into(),
        // A hit chain's t_c is the free collision's at v0; the plan's fastest mode (and so its
        // dt's stability) is taken at the walls' pre-stress plus the kick's overlap.
        (_, Deformation::PreStressed { .. }) => {
            "the walls' displacement plus the impact speed (a hit chain's fastest mode; its t_c is the collision's)"
                .into()
        }
        (SceneKind::Packing, Deformation::Extension(_)) => format!(
            "an overlap of {} % of a small diameter",
            words::number(crate::spec::PACKING_REFERENCE_OVERLAP * 100.0)
        ),
        (_, Deformation::Extension(_)) => "the driven strain".into(),
    }
}

/// A fitted quantity's symbol as the report writes it (E, G, c, F, v0, the walls' Δ, the
/// chain's stiffness, each tangent one), its column name in words where it has none.
pub(super) fn symbol(column: &str) -> String {
    match column {
        "youngs_modulus" => "E".into(),
        "shear_modulus" => "G".into(),
        "sound_speed" => "c".into(),
        "load_per_node" => "the load per node F".into(),
        "v0" => "the kick v0".into(),
        "wall_displacement" => "the walls' displacement Δ".into(),
        "youngs_modulus_tangent" => "the tangent E".into(),
        "shear_modulus_tangent" => "the tangent G".into(),
        "secant_stiffness" => "the chain's secant stiffness".into(),
        "tangent_stiffness" => "the chain's tangent stiffness".into(),
        other => other.replace('_', " "),
    }
}

/// The exponents β of the non-linear fits, each once.
fn nonlinear_exponents(e: &Evidence) -> Vec<f64> {
    distinct_exponents(e.fits.iter().filter(|f| f.law != "linear").map(|f| f.beta))
}

/// The campaign's non-linear springs by name: "Hertz" where every one is β = 3/2, else
/// "power-law" (with its β where there is one).
fn nonlinear_name(e: &Evidence) -> String {
    match nonlinear_exponents(e).as_slice() {
        [] | [1.5] => "Hertz".into(),
        [beta] => format!("power-law (β = {})", words::number(*beta)),
        _ => "power-law".into(),
    }
}

/// A fit's spring law in the table: linear, Hertz, or the power law's β.
fn fit_law(fit: &ScalingFit) -> String {
    match fit.beta {
        1.0 => "linear".into(),
        1.5 => "Hertz".into(),
        _ => format!("β = {}", words::number(fit.beta)),
    }
}

/// Linear against Hertz springs: every fitted scaling law side by side with its prediction.
pub(super) fn linear_and_hertz(e: &Evidence) -> Option<Answer> {
    let mut rows = Vec::new();
    let mut checks = Vec::new();
    for fit in e.fits {
        let Some(predicted) = predicted_exponent(fit) else { continue };
        checks.push((fit.fit.exponent - predicted).abs() <= EXPONENT_TOLERANCE);
        rows.push(vec![
            fit.scene.clone(),
            fit_law(fit),
            format!("{} against {}", symbol(fit.quantity), symbol(fit.against)),
            exponent(fit.fit.exponent),
            exponent(predicted),
            // About a constant, R² compares the scatter with itself: no measure of the fit.
            if predicted == 0.0 { "– (flat)".into() } else { words::fit_quality_cell(&fit.fit, 4) },
        ]);
    }
    let linear = e.fits.iter().filter(|f| f.law == "linear").count();
    let hertz = e.fits.iter().filter(|f| f.law != "linear").count();
    let name = nonlinear_name(e);
    let stiffness = if name == "Hertz" { "δ^(1/2)" } else { "δ^(β − 1)" };
    (linear > 0 && hertz > 0).then(|| Answer {
        title: if name == "Hertz" { "Linear against Hertz springs" } else { "Linear against power-law springs" },
        question: "Discuss the difference between the linear and the non-linear model (1D and 2D).",
        short: format!("{linear} linear and {hertz} {name} scaling laws against their predictions"),
        sentences: vec![format!(
            "Every quantity this campaign sweeps over an amplitude (impact speed, load, wall displacement) is fitted \
             to a power law, {linear} with linear and {hertz} with {name} springs: linear springs give exponent 0, \
             {name} springs the exponent their stiffness s′(δ) ∝ {stiffness} predicts. The discussion below puts \
             the difference in words."
        )],
        reference: format!("Exponent 0 (linear) and the {name} predictions; tolerance {EXPONENT_TOLERANCE}."),
        see_also: None,
        verdict: Verdict::of(checks),
        figures: Vec::new(),
        table: Some(Table {
            header: ["scene", "law", "quantity", "exponent", "predicted", "R²"].map(String::from).to_vec(),
            rows,
        }),
    })
}

/// The abstract's sentence on Hertz springs: every fitted law of the non-linear scenes that has
/// a prediction, its exponent beside it, and the linear springs' 0.
pub(super) fn hertz_headline(e: &Evidence) -> Option<String> {
    let mut laws: Vec<String> = Vec::new();
    for fit in e
        .fits
        .iter()
        .filter(|f| f.law != "linear" && !f.quantity.starts_with("tangent") && !f.quantity.ends_with("tangent"))
    {
        let Some(predicted) = predicted_exponent(fit) else { continue };
        let verdict = if (fit.fit.exponent - predicted).abs() <= EXPONENT_TOLERANCE { "within" } else { "outside" };
        let law = format!(
            "{} ∝ {}^{} (predicted {predicted:.3}, {verdict} {EXPONENT_TOLERANCE})",
            symbol(fit.quantity),
            symbol(fit.against),
            exponent(fit.fit.exponent)
        );
        if !laws.iter().any(|l| l.starts_with(&law[..law.find('^').unwrap_or(0)])) {
            laws.push(law);
        }
    }
    (!laws.is_empty()).then(|| {
        format!(
            "{} springs make the answers depend on the amplitude, where linear springs give exponent 0: {}.",
            words::capitalised(&nonlinear_name(e)),
            laws.join(", ")
        )
    })
}
