//! The coursework's 2D items: units and time step, the diagonal springs, the lattice's time
//! step, the upper-right kick, E, ν and G against the static truss and the continuum, sound
//! speed, dissipation, homogeneity, Hertz lattices, anisotropic and random networks, MD against
//! FEM.

use std::collections::BTreeMap;

use super::block::Block;
use super::finding::{
    Answer, Evidence, Table, Verdict, cell, noise, regular, rel, relative, sig, size_on_coursework_supports,
};
use super::types::square_diagonal_stiffening;
use crate::measure::{anisotropic_moduli, convergence_order};
use crate::model::LawSpec;
use crate::report::figure::{FigureKind, group_label, representative};
use crate::report::kinds::contact_time_words;
use crate::report::waves::sideways_kick;
use crate::report::words::{capitalised, counted, listed, number, ordinal, scheme};
use crate::runner::RunRecord;
use crate::sim::{IntegratorKind, RunStatus};
use crate::spec::{Control, Diagonals, LatticeSpec, LoadCase, RunSpec, Supports};

/// Largest |MD − static|/static of a relaxed lattice's modulus that counts as agreement: the
/// relaxation stops at E_kin/E_pot < 1e-8 or a residual force of 1e-6 of the load, which leaves
/// the slowest mode's displacement error at about 1e-4 … 1e-3 of the deformation.
pub(super) const STATIC_TOLERANCE: f64 = 2e-3;

/// The fitted order, as text.
fn order_text(order: Option<f64>) -> String {
    order.map(|p| crate::report::words::exponent(p, 2)).unwrap_or_else(|| "–".into())
}

/// The scenes of `runs`, each once, in order.
fn scenes(runs: &[&RunRecord]) -> Vec<String> {
    let mut scenes: Vec<String> = Vec::new();
    for r in runs {
        if !scenes.contains(&r.spec.scene) {
            scenes.push(r.spec.scene.clone());
        }
    }
    scenes
}

/// Masses and stiffnesses of the lattice, the good time step and its stability margin.
pub(super) fn units_and_time_step(e: &Evidence) -> Option<Answer> {
    let lattices = e.ok(|r| r.spec.lattice().is_some() && r.metrics.dt_omega_max.is_some());
    let (example, mut sentences) = node_sentences(e, &lattices)?;
    let s = &example.spec;
    let closest = closest_to_stability_limit(&lattices);
    sentences.push(match closest {
        Some((runs, worst_step, worst_limit)) => format!(
            "The lattice's fastest mode is faster than the pair's (ω_max up to 2√((k + k_d)/m) with diagonals), so \
             the step is checked against it before every run: over the {} at dt = t_c/50 it comes closest to its \
             integrator's stability limit at dt·ω_max = {} against a limit of {} (2 for Verlet, lower with \
             damping), {} of it.",
            counted(runs, "lattice run"),
            sig(worst_step),
            sig(worst_limit),
            sig(worst_step / worst_limit)
        ),
        None => "No lattice run here steps at dt = t_c/50, so the coursework's step is not checked against the \
                 stability limit here."
            .into(),
    });
    let worst = closest.map(|(_, step, limit)| step / limit);
    Some(Answer {
        title: "Masses, stiffnesses and the lattice's time step",
        question: "Choose masses and stiffnesses so the lattice weighs what the solid weighs and dt is easy to \
                   estimate; what is a good time step?",
        short: match worst {
            Some(worst) => {
                format!("dt = t_c/50 (e.g. {} s), at most {} of the stability limit", sig(s.t_c / 50.0), sig(worst))
            }
            None => "no lattice run at t_c/50".into(),
        },
        sentences,
        reference: "The integrator's stability limit dt·ω_max ≤ 2 (Verlet), measured per run; verdict: every run \
                    below it."
            .into(),
        see_also: None,
        verdict: worst.map_or(Verdict::Observed, |worst| Verdict::of([worst < 1.0])),
        figures: Vec::new(),
        table: None,
    })
}

/// The run whose node the item describes, and the sentences on its masses and springs: the
/// block whose moduli the report gives (the abstract's), then a scene whose masses and springs
/// are derived from the solid, when the campaign has one besides it.
fn node_sentences<'a>(e: &Evidence<'a>, lattices: &[&'a RunRecord]) -> Option<(&'a RunRecord, Vec<String>)> {
    let block = Block::of(e).map(|b| b.first()).filter(|r| r.metrics.dt_omega_max.is_some());
    let derived = lattices.iter().copied().find(|r| r.spec.lattice().is_some_and(|l| l.derived_from.is_some()));
    let example = block.or(derived).or(lattices.first().copied())?;
    let s = &example.spec;
    let mut sentences = vec![format!("The block of scene {}: {}", s.scene, node_words(example)?)];
    if let Some(d) = derived.filter(|d| d.spec.scene != s.scene) {
        let note = d.spec.lattice()?.derived_from.as_deref().unwrap_or_default();
        sentences.push(format!(
            "Scene {} derives its masses and springs from the solid instead: {note}; there {}",
            d.spec.scene,
            node_words(d)?
        ));
    }
    let l = s.lattice()?;
    match &l.derived_from {
        Some(note) => sentences.insert(0, format!("The masses and springs are derived from the solid: {note}.")),
        None => sentences[0].push_str(&format!(
            " Each node carries the mass of its cell a × a × d (a = {} m, d = {} m): ρ = m/(a² d) = {} kg/m³.{}",
            sig(s.spacing),
            sig(l.depth),
            sig(s.mass / (s.spacing * s.spacing * l.depth)),
            solid_mass_words(s, l, derived),
        )),
    }
    Some((example, sentences))
}

/// N_x N_y square cells of a² d hold more than the solid of width (N_x − 1) a and height
/// (N_y − 1) a whose moduli the block measures (its edge nodes carry whole cells): 5 % more on
/// 40 × 40. Said of square lattices of at least 2 × 2, with the scene whose masses come from the
/// solid's density, if there is one.
fn solid_mass_words(s: &RunSpec, l: &LatticeSpec, derived: Option<&RunRecord>) -> String {
    if !(l.lattice_type.is_square() && l.nx >= 2 && l.ny >= 2) {
        return String::new();
    }
    let solid = s.mass * ((l.nx - 1) * (l.ny - 1)) as f64;
    let from_density = derived
        .filter(|d| d.spec.lattice().and_then(|l| l.derived_from.as_deref()).is_some_and(|n| n.contains("m = ρ")));
    format!(
        " The solid it measures, (N_x − 1) a by (N_y − 1) a, weighs {} kg: the edge nodes' whole cells add {}{}.",
        sig(solid),
        super::finding::percent(s.mass * (l.nx * l.ny) as f64 / solid - 1.0).trim_start_matches('+'),
        from_density.map_or_else(String::new, |d| format!("; scene {} below makes the two equal", d.spec.scene)),
    )
}

/// Over the runs at the coursework's step dt = t_c/50 (those allowed beyond the limit too: at
/// t_c/50 they are ordinary runs): how many, and (dt·ω_max, its stability limit) of the one
/// closest to its limit; `None` without such a run.
fn closest_to_stability_limit(lattices: &[&RunRecord]) -> Option<(usize, f64, f64)> {
    let margins: Vec<(f64, f64)> = lattices
        .iter()
        .filter(|r| (r.spec.dt_per_tc() - 50.0).abs() < 1.0)
        .filter_map(|r| Some((r.metrics.dt_omega_max?, r.metrics.stability_limit?)))
        .collect();
    let (step, limit) = margins.iter().copied().max_by(|a, b| (a.0 / a.1).total_cmp(&(b.0 / b.1)))?;
    Some((margins.len(), step, limit))
}

/// A lattice run's node in words: its mass and springs, the pair's t_c, dt = t_c/50 and the
/// block's weight.
fn node_words(r: &RunRecord) -> Option<String> {
    let (s, l) = (&r.spec, r.spec.lattice()?);
    Some(format!(
        "a node of m = {} kg on springs k = {} N/m gives the pair's {}, so dt = t_c/50 = {} s; the whole {} × {} \
         block weighs {} kg.",
        sig(s.mass),
        sig(s.k),
        contact_time_words(s),
        sig(s.t_c / 50.0),
        l.nx,
        l.ny,
        sig(s.mass * (l.nx * l.ny) as f64)
    ))
}

/// k_d/k for equal Young's modulus along the diagonal chain, and the choice made.
pub(super) fn diagonal_stiffness(e: &Evidence) -> Option<Answer> {
    let runs = e.ok(|r| regular(r).is_some_and(|l| l.diagonals == Diagonals::Both && l.load_case == LoadCase::Tensile));
    let ratios = one_block_per_ratio(&runs);
    let first = *runs.first()?;
    let mut sentences = vec![
        "A spring of stiffness k and length L is a bar of E A = k L: a row of springs k of length a has \
         E A = k a, a chain of diagonal springs k_d of length a√2 has E A = k_d a√2; the two have the same Young's \
         modulus when k_d a√2 = k a, i.e. k_d/k = 1/√2 ≈ 0.7071."
            .to_string(),
    ];
    for r in ratios.values() {
        sentences.push(ratio_words(r)?);
    }
    // The choice is the ratio of the block item 4 measures E and ν on, where there is one.
    let chosen_run = Block::of(e).map_or(first, |b| b.first());
    let chosen = chosen_run.spec.lattice()?.k_diag / chosen_run.spec.k;
    let isotropic = (2.0 * chosen - 1.0).abs() < 1e-9;
    let several: Vec<String> = ratios.values().filter_map(|r| Some(sig(r.spec.lattice()?.k_diag / r.spec.k))).collect();
    sentences.push(choice_words(chosen, isotropic));
    if several.len() > 1 {
        sentences.push(several_ratios_words(&several));
    }
    Some(Answer {
        title: "The diagonal springs",
        question: "Choose k_diag so the diagonal chain has the same Young's modulus as the axial one: what is \
                   k_diag/k? Choose one and argue for it.",
        short: format!(
            "k_d/k = 1/√2 ≈ 0.7071 for equal E; {} chosen{}",
            number(chosen),
            if isotropic { " (isotropic, ν = 1/3)" } else { " (anisotropic)" }
        ),
        sentences,
        reference: "The continuum constants C11 = k + k_d, C12 = C44 = k_d (per unit depth).".into(),
        see_also: None,
        verdict: Verdict::Observed,
        figures: Vec::new(),
        table: None,
    })
}

/// One ratio k_d/k in words: the continuum's E and ν free to contract, whatever supports the
/// MD block has (C11 = k + k_d, C12 = k_d per unit depth: E = (C11 − C12²/C11)/d and ν = C12/C11),
/// and the ν its block measures; a periodic strip cannot contract sideways, so its ν is 0 by
/// construction and measures nothing.
fn ratio_words(r: &RunRecord) -> Option<String> {
    let l = r.spec.lattice()?;
    let (k_rising, k_falling) = l.diagonal_stiffness();
    let free = anisotropic_moduli(l.k_x, l.k_y, k_rising, k_falling, l.depth);
    let measured = if l.supports == Supports::PeriodicX {
        format!("MD's block here is a periodic strip (scene {}), which cannot contract sideways: no ν", r.spec.scene)
    } else {
        format!(
            "MD measures ν = {} on {} × {} ({} supports, scene {})",
            cell(r.metrics.lattice.poisson_ratio),
            l.nx,
            l.ny,
            l.supports.name(),
            r.spec.scene
        )
    };
    Some(format!(
        "With k = {} N/m and k_d/k = {} the continuum has E = (C11 − C12²/C11)/d = {} Pa, ν = k_d/(k + k_d) = {} \
         and E(45°)/E(0°) = {}; {measured}.",
        sig(r.spec.k),
        sig(l.k_diag / r.spec.k),
        sig(free.youngs_modulus_y),
        sig(free.poisson_ratio_yx),
        cell(square_diagonal_stiffening(l)),
    ))
}

/// The tensile runs' several ratios k_d/k (`ratios`, in words): only k_d/k = 1/2 is isotropic.
fn several_ratios_words(ratios: &[String]) -> String {
    let which =
        if ratios.iter().any(|r| r == "0.5000") { "of these only 1/2" } else { "none of them is 1/2, the one that" };
    format!(
        "Its tensile runs use k_d/k = {}; {which} makes the square lattice with both diagonals isotropic (Zener \
         ratio 2C44/(C11 − C12) = 2k_d/k = 1, ν = 1/3): at the others E depends on the direction.",
        listed(ratios, "and")
    )
}

/// Why the moduli runs' k_d/k: with both diagonals C11 = k + k_d and C12 = C44 = k_d, so the
/// Zener ratio 2C44/(C11 − C12) = 2k_d/k is 1, and the lattice isotropic, only at k_d = k/2.
fn choice_words(chosen: f64, isotropic: bool) -> String {
    if isotropic {
        format!(
            "This campaign's moduli runs use k_d/k = {}, the one ratio at which the square lattice with both \
             diagonals and k_y = k is isotropic: its Zener ratio 2C44/(C11 − C12) = 2k_d/k is 1, so E and ν are the \
             same in every direction, as in the isotropic solid it stands for, with ν = 1/3.",
            number(chosen)
        )
    } else {
        format!(
            "This campaign's moduli runs use k_d/k = {}: its Zener ratio 2C44/(C11 − C12) = 2k_d/k is {}, so its E \
             depends on the direction (isotropic only at k_d/k = 1/2).",
            sig(chosen),
            sig(2.0 * chosen)
        )
    }
}

/// One run for each ratio k_d/k among `runs`, compared on one block: the largest size every
/// ratio was run at (else each ratio's largest), on the coursework's supports where there is a
/// choice, from a scene that runs every ratio where one does (the ratios then compare like with
/// like); of runs alike in these, the first in the campaign (a moduli scene before the damping
/// sweeps and ensembles that load the same block, whose ν differs in the sixth digit).
fn one_block_per_ratio<'a>(runs: &[&'a RunRecord]) -> BTreeMap<String, &'a RunRecord> {
    let mut by_ratio: BTreeMap<String, Vec<&RunRecord>> = BTreeMap::new();
    for &r in runs {
        if let Some(l) = r.spec.lattice() {
            by_ratio.entry(sig(l.k_diag / r.spec.k)).or_default().push(r);
        }
    }
    let size = |r: &RunRecord| size_on_coursework_supports(r).0;
    let run_at = |n: usize| by_ratio.values().all(|rs| rs.iter().any(|r| size(r) == n));
    let common = runs.iter().map(|r| size(r)).filter(|&n| run_at(n)).max();
    let complete: Vec<&str> = runs
        .iter()
        .map(|r| r.spec.scene.as_str())
        .filter(|scene| by_ratio.values().all(|rs| rs.iter().any(|r| r.spec.scene == *scene)))
        .collect();
    let every_ratio = |scene: &str| complete.contains(&scene);
    let preference = |r: &&&RunRecord| {
        (common.is_none_or(|n| size(r) == n), every_ratio(&r.spec.scene), size_on_coursework_supports(r))
    };
    // `max_by_key` keeps the last of equals: reversed, the first.
    by_ratio.into_iter().filter_map(|(ratio, rs)| Some((ratio, *rs.iter().rev().max_by_key(preference)?))).collect()
}

/// The sweeps over dt of the kicked lattice runs `kicked`: the runs of one scene alike in every
/// grid value but the step ([`group_label`]: network, kick, law, damping, integrator), so that
/// their errors differ by dt alone, each from the largest step to the smallest. Only groups of
/// three distinct steps count (a fitted order needs three), and only those of the first scene
/// that has one: runs that differ in the kick speed, say, at one t_c/dt are no sweep.
fn dt_sweeps<'a>(kicked: &[&'a RunRecord]) -> Vec<Vec<&'a RunRecord>> {
    // (scene, grid values but dt, runs), in campaign order.
    let mut groups: Vec<(&str, String, Vec<&RunRecord>)> = Vec::new();
    for &r in kicked {
        let (scene, label) = (r.spec.scene.as_str(), group_label(r));
        match groups.iter_mut().find(|g| g.0 == scene && g.1 == label) {
            Some(group) => group.2.push(r),
            None => groups.push((scene, label, vec![r])),
        }
    }
    groups.retain(|g| distinct_steps(&g.2) >= 3);
    let Some(&(scene, ..)) = groups.first() else { return Vec::new() };
    groups
        .into_iter()
        .filter(|g| g.0 == scene)
        .map(|(.., mut sweep)| {
            sweep.sort_by(|a, b| b.spec.dt.total_cmp(&a.spec.dt));
            sweep
        })
        .collect()
}

/// The number of distinct time steps among `runs`.
fn distinct_steps(runs: &[&RunRecord]) -> usize {
    let mut steps: Vec<f64> = runs.iter().map(|r| r.spec.dt).collect();
    steps.sort_by(f64::total_cmp);
    steps.dedup();
    steps.len()
}

/// How far below its integrator's energy order ([`IntegratorKind::energy_order`]) a sweep's
/// fitted order may fall: the next order's term at the largest steps moves a least-squares
/// slope by a few hundredths (symplectic Euler 1.02 and Forest–Ruth 4.05 over t_c/10 … t_c/100
/// on a 12 × 12 lattice, velocity Verlet 2.01 over t_c/5 … t_c/200 on the coursework's 20 × 20).
const ORDER_TOLERANCE: f64 = 0.2;

/// One sweep over dt fitted: its runs (largest step first), the fitted order of the energy error
/// and its integrator's.
struct Sweep<'a> {
    runs: Vec<&'a RunRecord>,
    fitted: Option<f64>,
    expected: u32,
}

impl<'a> Sweep<'a> {
    fn of(runs: Vec<&'a RunRecord>) -> Sweep<'a> {
        let points: Vec<(f64, f64)> =
            runs.iter().filter_map(|r| r.metrics.energy_error.map(|x| (r.spec.dt, x))).collect();
        let expected = runs[0].spec.integrator.energy_order();
        Sweep { fitted: convergence_order(&points), expected, runs }
    }

    /// Whether the energy error falls at least at its integrator's order: faster is no fault (a
    /// scheme's order bounds its error's fall from below; RK4's energy on linear springs falls at
    /// the fifth, see [`rk4_words`]).
    fn within(&self) -> bool {
        self.fitted.is_some_and(|p| p >= f64::from(self.expected) - ORDER_TOLERANCE)
    }

    /// The sweep in a few words, for sentences and the table when the scene sweeps more than one
    /// setting: its grid values but dt, the integrator named where the grid does not name it.
    fn label(&self) -> String {
        let (label, integrator) = (group_label(self.runs[0]), self.runs[0].spec.integrator.name());
        if label.split(", ").any(|part| part == integrator) { label } else { format!("{label}, {integrator}") }
    }
}

/// A dt sweep on a kicked lattice: energy error and arrival time against dt, each integrator
/// (each setting the scene sweeps) fitted and judged on its own.
pub(super) fn lattice_time_step(e: &Evidence) -> Option<Answer> {
    let kicked = e.ok(|r| r.spec.lattice().is_some_and(|l| l.impulse.is_some()) && r.metrics.energy_error.is_some());
    let sweeps: Vec<Sweep> = dt_sweeps(&kicked).into_iter().map(Sweep::of).collect();
    let scene = sweeps.first()?.runs[0].spec.scene.clone();
    let several = sweeps.len() > 1;
    let sentences: Vec<String> = sweeps.iter().filter_map(|s| sweep_sentence(s, several)).collect();
    let mut header: Vec<String> =
        ["t_c/dt", "dt·ω_max", "energy error", "arrival (s)", "vs finest"].map(String::from).to_vec();
    if several {
        header.insert(0, "sweep".into());
    }
    let orders: Vec<String> = sweeps
        .iter()
        .map(|s| {
            let order = format!("dt^{}", order_text(s.fitted));
            if several { format!("{order} ({})", s.label()) } else { order }
        })
        .collect();
    Some(Answer {
        title: "The time step on a lattice",
        question: "Confirm performance and accuracy on the lattice with larger and smaller time steps.",
        short: format!("energy error ∝ {}", orders.join(", ")),
        sentences,
        reference: order_reference(&sweeps),
        see_also: None,
        verdict: Verdict::of(sweeps.iter().map(Sweep::within)),
        figures: e.figures(&[(&scene, FigureKind::WorkPrecision), (&scene, FigureKind::ErrorDt)]),
        table: Some(Table { header, rows: sweeps.iter().flat_map(|s| sweep_rows(s, several)).collect() }),
    })
}

/// A sweep's rows of the item's table: per step its fastest mode, energy error and arrival time
/// against the sweep's own finest step; led by the sweep's label when the scene has several.
fn sweep_rows(sweep: &Sweep, several: bool) -> Vec<Vec<String>> {
    let finest = sweep.runs.last().map(|r| r.metrics.arrival_time());
    sweep
        .runs
        .iter()
        .map(|r| {
            let mut row = vec![
                format!("{:.0}", r.spec.dt_per_tc()),
                cell(r.metrics.dt_omega_max),
                cell(r.metrics.energy_error),
                cell(r.metrics.arrival_time()),
                relative(r.metrics.arrival_time(), finest.flatten()).map(rel).unwrap_or_else(|| "–".into()),
            ];
            if several {
                row.insert(0, sweep.label());
            }
            row
        })
        .collect()
}

/// A sweep in a sentence: its energy error's fitted order and end points, the arrival time's
/// drift, the step nearest t_c/50 and the cost of the others. Where the scene sweeps several
/// settings the sentence names its own and its integrator's order.
fn sweep_sentence(sweep: &Sweep, several: bool) -> Option<String> {
    let (coarsest, finest, usual) = (*sweep.runs.first()?, *sweep.runs.last()?, representative(&sweep.runs));
    let cost = super::one_d::cost_words(coarsest, usual, finest, |r| r.metrics.energy_error);
    let setting = if several {
        format!(" with {} (energy error of order {})", sweep.label(), sweep.expected)
    } else {
        String::new()
    };
    let s = &coarsest.spec;
    let damping = if s.gamma == 0.0 && s.gamma_background == 0.0 { "undamped" } else { "damped" };
    Some(format!(
        "The same kick on the lattice of scene {}{setting}, {damping}, from dt = t_c/{:.0} to t_c/{:.0}: the \
         energy error falls as dt^{} ({} at the largest step, {} at the smallest), and the arrival time at the \
         bottom row moves by {} between the largest and the smallest step. dt = t_c/{:.0} keeps the energy to {} \
         here, with the lattice's fastest mode at dt·ω_max = {}.{cost}",
        s.scene,
        s.dt_per_tc(),
        finest.spec.dt_per_tc(),
        order_text(sweep.fitted),
        cell(coarsest.metrics.energy_error),
        cell(finest.metrics.energy_error),
        relative(coarsest.metrics.arrival_time(), finest.metrics.arrival_time()).map(rel).unwrap_or_else(|| "–".into()),
        usual.spec.dt_per_tc(),
        cell(usual.metrics.energy_error),
        cell(usual.metrics.dt_omega_max),
    ))
}

/// The item's reference: the order of each integrator the sweeps ran, by
/// [`IntegratorKind::energy_order`], and the tolerance below it.
fn order_reference(sweeps: &[Sweep]) -> String {
    let mut kinds: Vec<IntegratorKind> = Vec::new();
    for s in sweeps {
        if !kinds.contains(&s.runs[0].spec.integrator) {
            kinds.push(s.runs[0].spec.integrator);
        }
    }
    let orders: Vec<String> =
        kinds.iter().map(|&k| format!("{}'s {} order", scheme(k, false), ordinal(k.energy_order()))).collect();
    let bound = match kinds.as_slice() {
        [only] => {
            let order = only.energy_order();
            format!(
                "fitted order at least {}, no more than {ORDER_TOLERANCE} below {order}",
                number(f64::from(order) - ORDER_TOLERANCE)
            )
        }
        _ => format!("each sweep's fitted order no more than {ORDER_TOLERANCE} below its integrator's"),
    };
    format!(
        "{} of the energy error: {bound} (a faster fall is no fault{}).",
        capitalised(&listed(&orders, "and")),
        rk4_words(sweeps)
    )
}

/// Why RK4's energy error may fall faster than its order, said where an RK4 sweep of linear
/// springs ran: on a linear mode of frequency ω its step multiplies the energy by
/// |R(iω dt)|² = 1 − (ω dt)⁶/72 + O((ω dt)⁸), so T/dt steps lose a share ∝ dt⁵.
fn rk4_words(sweeps: &[Sweep]) -> &'static str {
    let linear_rk4 = |s: &Sweep| s.runs[0].spec.integrator == IntegratorKind::Rk4 && s.runs[0].spec.law.is_linear();
    if sweeps.iter().any(linear_rk4) {
        ": RK4 removes a share (ω dt)⁶/72 of a linear mode's energy per step, so its energy error on linear springs \
         falls as dt⁵"
    } else {
        ""
    }
}

/// The front's first passage through the bottom row: up to twice its arrival time (s) by the
/// speed threshold. The wave reflected at the bottom comes back to it only after three transits,
/// and a column left sliding by the kick fills the row's later samples: neither is the front.
fn first_passage(r: &RunRecord) -> Option<f64> {
    r.metrics.arrival_times.get("speed_threshold").map(|t| 2.0 * t)
}

/// The share of the kinetic energy reaching the bottom row during the front's first passage
/// (Σ over those samples of v², from its probe) that arrives at the kicked node's column: 1 when
/// the kick stays in its column.
fn column_share(r: &RunRecord) -> Option<f64> {
    let l = r.spec.lattice()?;
    let column = l.impulse?.node % l.nx;
    let bottom = r.trace.probes.iter().find(|p| p.name == "row 0")?;
    let at = bottom.nodes.iter().position(|&n| n % l.nx == column)?;
    let passage = first_passage(r)?;
    let samples = r.trace.time.iter().take_while(|&&t| t <= passage).count();
    let (mut kicked, mut all) = (0.0, 0.0);
    for (vx, vy) in bottom.velocity_x.iter().zip(&bottom.velocity_y).take(samples) {
        for (i, (x, y)) in vx.iter().zip(vy).enumerate() {
            let energy = x * x + y * y;
            all += energy;
            if i == at {
                kicked += energy;
            }
        }
    }
    (all > 0.0).then(|| kicked / all)
}

/// The share in words, when the run recorded its bottom row, with the kick's strain v0/c: the
/// linear picture holds while it is small.
fn share_words(r: &RunRecord) -> String {
    let kick = r.spec.lattice().and_then(|l| l.impulse).map_or(0.0, |i| i.vx.hypot(i.vy));
    let strain = r.metrics.sound_speed_theory.map(|c| kick / c);
    column_share(r)
        .zip(first_passage(r))
        .map(|(share, passage)| {
            format!(
                " During the front's first passage through the bottom row (t ≤ 2 t_arrival = {} s), {:.2} % of \
                 the kinetic energy reaching it arrives in the kicked column; the kick's strain is v0/c = {}.",
                sig(passage),
                100.0 * share,
                cell(strain)
            )
        })
        .unwrap_or_default()
}

/// The summary's line: how much of the kick stays in its column, without and with diagonals.
fn kick_short(kicked: &[&RunRecord]) -> String {
    let share = |d: Diagonals| quoted_kick(kicked, d).and_then(|(r, _)| column_share(r));
    match (share(Diagonals::None), share(Diagonals::Both)) {
        (Some(none), Some(both)) => format!(
            "{:.1} % of the front's energy stays in the kicked column without diagonals, {:.1} % with them",
            100.0 * none,
            100.0 * both
        ),
        _ => "the kick's path with and without diagonals".into(),
    }
}

/// The run of `kicked` whose front the item quotes for `diagonals`, and the words that say which
/// it is. Of the first scene that kicks a lattice with these diagonals, the most accurate run:
/// the highest order of energy error ([`IntegratorKind::energy_order`]), then the smallest step,
/// then the first in campaign order; named by its grid values when the scene has other runs
/// with these diagonals (over a sweep the speed moves by per cents: on a 12 × 12 lattice
/// symplectic Euler at t_c/10 times the front 1.6 % slower than RK4 at t_c/100).
fn quoted_kick<'a>(kicked: &[&'a RunRecord], diagonals: Diagonals) -> Option<(&'a RunRecord, String)> {
    let alike: Vec<&RunRecord> =
        kicked.iter().copied().filter(|r| r.spec.lattice().is_some_and(|l| l.diagonals == diagonals)).collect();
    let scene = &alike.first()?.spec.scene;
    let of_scene: Vec<&RunRecord> = alike.iter().copied().filter(|r| r.spec.scene == *scene).collect();
    // The ordered, undamped network's front is the one c_L speaks of: cut, spread or damped
    // runs only where the scene has no other.
    let plain = |r: &&RunRecord| {
        r.spec.gamma == 0.0 && r.spec.gamma_background == 0.0 && r.spec.lattice().is_some_and(|l| !l.is_random())
    };
    let candidates: Vec<&RunRecord> = match of_scene.iter().copied().filter(plain).collect::<Vec<_>>() {
        plain if plain.is_empty() => of_scene,
        plain => plain,
    };
    let order = |r: &RunRecord| r.spec.integrator.energy_order();
    // `max_by` keeps the last of equals: reversed, the first.
    let best = candidates
        .iter()
        .rev()
        .copied()
        .max_by(|a, b| order(a).cmp(&order(b)).then(a.spec.dt_per_tc().total_cmp(&b.spec.dt_per_tc())))?;
    let label = best.spec.varied_in_words(|path| path != "lattice.diagonals");
    if candidates.len() == 1 || label.is_empty() {
        return Some((best, String::new()));
    }
    let with = if diagonals == Diagonals::None { "without" } else { "with" };
    let which = format!(
        " ({label}: the smallest step at the highest order among the scene's {} {with} diagonals, undamped and \
         ordered where any is)",
        counted(candidates.len(), "run")
    );
    Some((best, which))
}

/// The upper-right node kicked, with and without diagonals.
pub(super) fn kick(e: &Evidence) -> Option<Answer> {
    let kicked = e.ok(|r| {
        r.spec.lattice().is_some_and(|l| l.impulse.is_some_and(|i| i.top_row_force.is_none()))
            && r.spec.law == LawSpec::Linear
            && r.metrics.sound_speed_theory.is_some()
    });
    let mut sentences = Vec::new();
    let mut quoted = Vec::new();
    for diagonals in [Diagonals::None, Diagonals::Both] {
        let Some((r, which)) = quoted_kick(&kicked, diagonals) else {
            continue;
        };
        quoted.push(r);
        sentences.push(match diagonals {
            Diagonals::None => format!(
                "Without diagonals the kicked column is a chain of its own: the vertical kick runs down it at \
                 {} m/s{which} against a√(k/m) = {} m/s, and a square lattice without diagonals has no shear \
                 stiffness to pass it sideways.{}",
                cell(r.metrics.recommended_sound_speed()),
                cell(r.metrics.sound_speed_theory),
                share_words(r)
            ),
            _ => format!(
                "With diagonals every node is tied to its neighbours across the cell: the kick spreads into the \
                 whole block and reaches the bottom row at {} m/s{which} against c_L = a√((k + k_d)/m) = {} m/s.{}",
                cell(r.metrics.recommended_sound_speed()),
                cell(r.metrics.sound_speed_theory),
                share_words(r)
            ),
        });
    }
    sentences.extend(damped_kicks(&kicked, &quoted));
    let sideways = e.ok(|r| r.spec.law == LawSpec::Linear && sideways_kick(r).is_some());
    sentences.extend(sideways.first().and_then(|r| sideways_words(r)));
    let first = *kicked.first().or(sideways.first())?;
    let mut shown = e.movies(|r| {
        r.spec.lattice().is_some_and(|l| l.impulse.is_some()) && r.spec.movie.is_some() && r.spec.law == LawSpec::Linear
    });
    shown.truncate(1);
    shown.extend(e.figures(&[(&first.spec.scene, FigureKind::SpaceTime)]));
    Some(Answer {
        title: "The upper-right kick, with and without diagonals",
        question: "Give the upper-right particle an initial velocity, animate the motion, and explain the \
                   differences between the structures with and without diagonal springs.",
        short: kick_short(&kicked),
        sentences,
        reference: "The chain's front speed a√(k/m) and the lattice's c_L; an observation.".into(),
        see_also: None,
        verdict: Verdict::Observed,
        figures: shown,
        table: None,
    })
}

/// The damped kicks the item leaves out of its quoted fronts (undamped where their scene has
/// both), with their speeds; where each is bond-damped and arrives sooner than the quoted front
/// with its diagonals, why. Measured on a free 30 × 30 lattice kicked down at a corner (no
/// diagonals): V = 1.14, 1.20, 1.30, 1.44 m/s at r = 1, 0.8, 0.5, 0.2, but 1.09 m/s with
/// background damping γ_g = 0.1 N s/m alone. A dashpot pushes a neighbour by the relative
/// velocity γ(v_j − v_i) at once, a spring only once stretched (the next node's speed starts as
/// (γ/m) v0 t, not (k/m) v0 t²/2), so the leading edge reaches θ of the kick sooner; background
/// damping pushes on no neighbour and only slows it.
fn damped_kicks(kicked: &[&RunRecord], quoted: &[&RunRecord]) -> Option<String> {
    let damped = |r: &RunRecord| r.spec.gamma > 0.0 || r.spec.gamma_background > 0.0;
    let diagonals = |r: &RunRecord| r.spec.lattice().map(|l| l.diagonals);
    let left_out: Vec<&RunRecord> = kicked
        .iter()
        .copied()
        .filter(|r| damped(r) && quoted.iter().any(|q| !damped(q) && q.spec.scene == r.spec.scene))
        .collect();
    let speeds: Vec<String> = left_out
        .iter()
        .map(|r| format!("{} m/s at {}", cell(r.metrics.recommended_sound_speed()), r.spec.varied_in_words(|_| true)))
        .collect();
    let sooner = left_out.iter().all(|r| {
        let undamped = quoted.iter().find(|q| diagonals(q) == diagonals(r) && !damped(q));
        r.spec.gamma > 0.0
            && r.spec.gamma_background == 0.0
            && undamped.is_some_and(|q| r.metrics.recommended_sound_speed() > q.metrics.recommended_sound_speed())
    });
    (!left_out.is_empty()).then(|| {
        format!(
            "The damped kicks are left out ({}){}.",
            speeds.join("; "),
            if sooner {
                ": they arrive sooner than undamped, for a bond dashpot pushes its neighbour at once, a spring only \
                 once stretched"
            } else {
                ""
            }
        )
    })
}

/// A node kicked sideways: its front between c_T and c_L, unjudged, and each criterion's side
/// ([`crate::study::lattice::sideways_kick_speeds`] has the argument). Before L/c_T no S wave
/// has arrived, so an earlier front is the P wave's, met obliquely.
fn sideways_words(r: &RunRecord) -> Option<String> {
    let (c_t, c_l) = sideways_kick(r)?;
    let (v, distance) = (r.metrics.recommended_sound_speed()?, r.metrics.wave_distance?);
    let s_wave = format!("any S wave (L/c_T = {} s)", sig(distance / c_t));
    let why = if v > c_t {
        format!(
            "it comes sooner than {s_wave}, so it is P, which has no amplitude straight below the kick and meets the row obliquely"
        )
    } else {
        format!("it comes no sooner than {s_wave}")
    };
    let side = |v: f64| match v {
        v if v > c_l => "above c_L",
        v if v < c_t => "below c_T",
        v if c_l - v < v - c_t => "nearer c_L",
        _ => "nearer c_T",
    };
    let others: Vec<String> = crate::measure::ARRIVAL_CRITERIA[1..]
        .iter()
        .filter_map(|c| r.metrics.sound_speed(c).map(|v| format!("{} {} ({})", c.replace('_', " "), sig(v), side(v))))
        .collect();
    let others = if others.is_empty() { String::new() } else { format!("; by the {}", listed(&others, "and")) };
    Some(format!(
        "Kicked sideways ({}), the front reaches the bottom row at {} m/s by the speed threshold, between c_T = {} \
         and c_L = {} m/s and unjudged: {why}{others}.",
        r.spec.scene,
        sig(v),
        sig(c_t),
        sig(c_l),
    ))
}

/// The modulus a run measures: its name, MD, static and continuum values (Pa).
type Modulus = (&'static str, Option<f64>, Option<f64>, Option<f64>);

/// The modulus a run measures.
fn modulus(r: &RunRecord) -> Option<Modulus> {
    let (m, l) = (&r.metrics.lattice, r.spec.lattice()?);
    // A periodic strip cannot contract sideways: its tensile test measures the modulus of
    // uniaxial strain C11/d = (k + k_d)/d, not E.
    let tensile = if l.supports == Supports::PeriodicX { "C11/d" } else { "E" };
    match l.load_case {
        LoadCase::Tensile | LoadCase::TensileX => {
            Some((tensile, m.youngs_modulus, m.youngs_modulus_fem, m.youngs_modulus_theory))
        }
        LoadCase::Shear => Some(("G", m.shear_modulus, m.shear_modulus_fem, m.shear_modulus_theory)),
    }
}

/// One load case's moduli answered: sentences, table, checks, and the scenes it read.
struct Moduli {
    sentences: Vec<String>,
    table: Table,
    checks: Vec<bool>,
    scenes: Vec<String>,
}

/// A lattice's size, diagonals and supports in a few words.
fn lattice_words(l: &LatticeSpec) -> String {
    let diagonals = match l.diagonals {
        Diagonals::None => "no".to_string(),
        other => other.name().to_string(),
    };
    format!("{} × {}, {diagonals} diagonals, {} supports", l.nx, l.ny, l.supports.name())
}

/// The moduli answer of one load case: sentences, table, checks.
fn moduli(e: &Evidence, case: LoadCase) -> Option<Moduli> {
    let runs = e.all(|r| regular(r).is_some_and(|l| l.load_case == case && l.control == Control::Force));
    let ok: Vec<&RunRecord> = runs.iter().copied().filter(|r| r.status == RunStatus::Ok).collect();
    let largest = ok.iter().map(|r| r.spec.lattice().map_or(0, |l| l.nx)).max()?;
    let mut rows = Vec::new();
    let mut worst: f64 = 0.0;
    for r in &ok {
        let (_, md, fem, _) = modulus(r)?;
        worst = worst.max(relative(md, fem).map_or(0.0, f64::abs));
    }
    for r in ok.iter().filter(|r| r.spec.lattice().is_some_and(|l| l.nx == largest)) {
        let (name, md, fem, theory) = modulus(r)?;
        let l = r.spec.lattice()?;
        rows.push(vec![
            lattice_words(l),
            format!("{name} (Pa)"),
            cell(md),
            cell(fem),
            cell(theory),
            relative(md, fem).map(rel).unwrap_or_else(|| "–".into()),
            relative(fem, theory).map(rel).unwrap_or_else(|| "–".into()),
            noise(r.metrics.lattice.poisson_ratio, 1.0),
        ]);
    }
    let sentences = vec![format!(
        "Over the {} relaxed runs the MD modulus agrees with the static truss answer of the same network to {} at \
         worst; the table shows the lattices {largest} nodes wide, where the static answer still differs from the \
         continuum by the finite size and the supports.{}",
        ok.len(),
        rel(worst).trim_start_matches('+'),
        mechanism_words(&runs)
    )];
    let header = ["lattice", "modulus", "MD", "static", "continuum", "MD − static", "static − continuum", "ν MD"]
        .map(String::from)
        .to_vec();
    Some(Moduli {
        sentences,
        table: Table { header, rows },
        checks: vec![worst <= STATIC_TOLERANCE],
        scenes: scenes(&ok),
    })
}

/// A lattice sheared without diagonal stiffness (`diagonals: none`, or k_d = 0): it has no
/// shear stiffness (C44 = k_d), so its shear is a mechanism.
fn sheared_unbraced(l: &LatticeSpec) -> bool {
    l.load_case == LoadCase::Shear && l.diagonal_stiffness() == (0.0, 0.0)
}

/// The runs among `runs` that end as mechanism, in words, and why where the campaign shows it:
/// a lattice sheared without diagonals (none, or k_d = 0) has no shear stiffness (C44 = k_d);
/// any other mechanism (diagonals too soft for the static solver, say) is counted, not explained.
fn mechanism_words(runs: &[&RunRecord]) -> String {
    let mechanisms: Vec<&RunRecord> = runs.iter().copied().filter(|r| r.status == RunStatus::Mechanism).collect();
    let unbraced = mechanisms.iter().filter(|r| r.spec.lattice().is_some_and(sheared_unbraced)).count();
    let why = match unbraced {
        0 => String::new(),
        n if n == mechanisms.len() => " (a lattice without diagonals has no shear stiffness)".into(),
        n => format!(" ({n} of them sheared without diagonals, which have no shear stiffness)"),
    };
    match mechanisms.len() {
        0 => String::new(),
        n => format!(
            " {} ended as mechanism: the load meets a zero-stiffness motion{why}, and no modulus exists.",
            counted(n, "run")
        ),
    }
}

/// (a) and (b): Young's modulus and Poisson's ratio, and the velocity boundary condition under tension.
pub(super) fn youngs_and_poisson(e: &Evidence) -> Option<Answer> {
    let Moduli { mut sentences, table, mut checks, scenes } = moduli(e, LoadCase::Tensile)?;
    let both = e.ok(|r| regular(r).is_some_and(|l| l.load_case == LoadCase::Tensile && l.diagonals == Diagonals::Both));
    // The largest block, a free one before a periodic strip, on the coursework's supports first.
    let largest = both.iter().max_by_key(|r| {
        r.spec.lattice().map_or((0, false, false), |l| {
            (l.nx, l.supports != Supports::PeriodicX, l.supports == Supports::Coursework)
        })
    });
    if let Some(r) = largest {
        // A periodic strip cannot contract sideways: its continuum ν is 0, not k_d/(k + k_d).
        let periodic = r.spec.lattice().is_some_and(|l| l.supports == Supports::PeriodicX);
        let continuum_nu = if periodic { "0: the strip cannot contract sideways" } else { "k_d/(k + k_d) = " };
        sentences.insert(
            0,
            format!(
                "{} N up on every top-row node of the {}, F = {} N in all: E = (F/d/L_x)/(ΔL_y/L_y) = {} Pa \
                 (continuum {} Pa), ν = −(ΔL_x/L_x)/(ΔL_y/L_y) = {} (continuum {continuum_nu}{}; the coursework's \
                 ΔL_x/ΔL_y with the sign that makes a sideways contraction positive); without diagonals E = k/d \
                 (of an infinite block) and ν = 0: nothing ties the columns to the rows.",
                sig(r.spec.lattice().map_or(0.0, |l| l.load_per_node)),
                r.spec.lattice().map(lattice_words).unwrap_or_default(),
                sig(r.spec.lattice().map_or(0.0, |l| l.total_load())),
                cell(r.metrics.lattice.youngs_modulus),
                cell(r.metrics.lattice.youngs_modulus_theory),
                noise(r.metrics.lattice.poisson_ratio, 1.0),
                if periodic { String::new() } else { cell(r.metrics.lattice.poisson_ratio_theory) },
            ),
        );
    }
    let block = Block::of(e);
    sentences.extend(block.as_ref().and_then(Block::extrapolation_sentence));
    checks.extend(block.as_ref().and_then(Block::continuum_check));
    sentences.extend(control_sentences(e, LoadCase::Tensile));
    Some(Answer {
        title: "Young's modulus and Poisson's ratio",
        question: "(a, b) Measure E and ν under 1 kN up on every top-row node.",
        short: block
            .as_ref()
            .map_or_else(|| format!("MD = static truss within {STATIC_TOLERANCE}"), Block::youngs_short),
        sentences,
        reference: format!(
            "The static truss answer of the same network (tolerance {STATIC_TOLERANCE:e}: the relaxation's stopping \
             rule) and the continuum constants (finite size explains the rest: E and ν extrapolated over blocks of \
             one shape, where two sizes or more give them, within {} of their uncertainties).",
            super::block::CONTINUUM_UNCERTAINTIES
        ),
        see_also: None,
        verdict: Verdict::of(checks),
        figures: scenes
            .iter()
            .take(1)
            .flat_map(|s| e.figures(&[(s, FigureKind::Size), (s, FigureKind::Relaxation)]))
            .collect(),
        table: Some(table),
    })
}

/// (c): the shear modulus, and the velocity boundary condition under shear.
pub(super) fn shear(e: &Evidence) -> Option<Answer> {
    let Moduli { mut sentences, table, checks, scenes } = moduli(e, LoadCase::Shear)?;
    let periodic = e.ok(|r| {
        regular(r).is_some_and(|l| {
            l.load_case == LoadCase::Shear && l.supports == Supports::PeriodicX && l.control == Control::Force
        })
    });
    if let Some(r) = periodic.first() {
        sentences.push(format!(
            "Only the periodic strip (bonds wrapped from the right edge to the left, the bottom row held: a strip \
             of an infinite block) shears homogeneously: there G = {} Pa against k_d/d = {} Pa{}.",
            cell(r.metrics.lattice.shear_modulus),
            cell(r.metrics.lattice.shear_modulus_theory),
            supported_shear_words(e)
        ));
    }
    sentences.extend(control_sentences(e, LoadCase::Shear));
    Some(Answer {
        title: "The shear modulus",
        question: "(c) Measure G under a horizontal load on every top-row node.",
        short: shear_short(e),
        sentences,
        reference: format!("The static truss answer (tolerance {STATIC_TOLERANCE:e}) and G = k_d/d."),
        see_also: None,
        verdict: Verdict::of(checks),
        figures: scenes.iter().take(1).flat_map(|s| e.figures(&[(s, FigureKind::Size)])).collect(),
        table: Some(table),
    })
}

/// Item 16's line in the summary: the block's G on each of its boundary conditions, and that a
/// lattice without diagonals has none where the campaign shears one: every such run a mechanism.
fn shear_short(e: &Evidence) -> String {
    let unbraced = e.all(|r| r.spec.lattice().is_some_and(|l| l.impulse.is_none() && sheared_unbraced(l)));
    let none = !unbraced.is_empty() && unbraced.iter().all(|r| r.status == RunStatus::Mechanism);
    match (Block::of(e).and_then(|b| b.shear_short()), none) {
        (Some(g), true) => format!("{g}; none without diagonals"),
        (Some(g), false) => g,
        (None, true) => "G measured; no shear stiffness without diagonals".into(),
        (None, false) => "G measured".into(),
    }
}

/// The apparent G of the largest sheared block with diagonals on the coursework's supports and
/// on a clamped bottom, each as a share of k_d/d with why its supports bend it, and whether both
/// fall short of it: only the supports the campaign shears a block on.
fn supported_shear_words(e: &Evidence) -> String {
    let shares: Vec<(String, f64)> = [Supports::Coursework, Supports::ClampedBottom]
        .into_iter()
        .filter_map(|supports| super::block::largest_sheared(e, supports, |_| true))
        .filter_map(|r| {
            let (m, l) = (&r.metrics.lattice, r.spec.lattice()?);
            let share = m.shear_modulus? / m.shear_modulus_theory?;
            let why = match l.supports {
                Supports::Coursework => "the whole shear force passes through the single pinned corner",
                _ => "the clamped bottom bends the block",
            };
            let words = format!(
                "{} Pa on {} × {} {} supports ({share:.2} of k_d/d: {why})",
                cell(m.shear_modulus),
                l.nx,
                l.ny,
                l.supports.name()
            );
            Some((words, share))
        })
        .collect();
    if shares.is_empty() {
        return String::new();
    }
    let verdict = if shares.iter().all(|s| s.1 < 1.0) { ", short of k_d/d" } else { "" };
    let list: Vec<String> = shares.into_iter().map(|s| s.0).collect();
    format!("; elsewhere the apparent G is {}{verdict}", list.join(" and "))
}

/// Two static answers closer than this are the same modulus: the static solver's precision is
/// about 1e-9 of it.
const SAME_STATIC: f64 = 1e-6;

/// A velocity-driven run against its force-loaded twin (same load case, supports, size and
/// springs), when the campaign has one: the modulus both give, and why they differ where they
/// do. An imposed displacement holds the top row straight, equal forces let it bend, so the
/// two boundary conditions have different static answers wherever the strain is not
/// homogeneous; MD meets each of its own.
fn control_sentence(e: &Evidence, driven: &RunRecord) -> Option<String> {
    let d = driven.spec.lattice()?;
    let (name, md_v, fem_v, _) = modulus(driven)?;
    let twin = e.ok(|r| {
        regular(r).is_some_and(|l| {
            l.control == Control::Force
                && (l.load_case, l.supports, l.nx, l.ny, l.diagonals)
                    == (d.load_case, d.supports, d.nx, d.ny, d.diagonals)
                && l.k_diag == d.k_diag
        }) && (r.spec.mass, r.spec.k, r.spec.spacing) == (driven.spec.mass, driven.spec.k, driven.spec.spacing)
    });
    let head = format!(
        "Velocity control ({}): the top row driven to a strain of {}, {name} from the supports' force = {} Pa \
         against its static {} Pa",
        lattice_words(d),
        sig(d.drive_strain),
        cell(md_v),
        cell(fem_v)
    );
    let Some(force) = twin.first() else { return Some(head + ".") };
    let (_, md_f, fem_f, _) = modulus(force)?;
    let gap = relative(fem_v, fem_f)?;
    let why = if gap.abs() < SAME_STATIC {
        "the same modulus: the strain is homogeneous, so it does not matter whether the top row is moved or pulled"
            .to_string()
    } else {
        format!(
            "the static answers of the two boundary conditions differ by {}: the imposed displacement holds the top \
             row straight where equal forces let it bend, so the driven block is {}",
            rel(gap),
            if gap > 0.0 { "stiffer" } else { "softer" }
        )
    };
    Some(format!("{head}; force control gives {} Pa (static {} Pa): {why}.", cell(md_f), cell(fem_f)))
}

/// The velocity-driven runs of `load_case` (at most two, the item's answer is E or G) each
/// against its force-loaded twin ([`control_sentence`]): the tensile ones under E and ν, the
/// sheared ones under G.
fn control_sentences(e: &Evidence, load_case: LoadCase) -> Vec<String> {
    let driven = e.ok(|r| regular(r).is_some_and(|l| l.control == Control::Velocity && l.load_case == load_case));
    driven.into_iter().take(2).filter_map(|r| control_sentence(e, r)).collect()
}
