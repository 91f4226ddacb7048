//! What the report says per scene kind and per force law, so a new kind or law touches this one
//! report file: each kind's part of its scene (the energies every kind draws, then its own
//! figures and the rows of its own tables: a pair's collisions and orders, a chain's runs and
//! its relaxed walls, a lattice's moduli), which kinds a campaign has, the scene's physics in a
//! sentence, and a law's name, springs and contact time in words.

use serde::Serialize;

use super::edges::edge_figures;
use super::figure::{Part, group_label, groups, representative};
use super::figures::{convergence_figure, displacement_figure, energy_figures, relaxation_figure, size_figure};
use super::words::{error, impulse_words, number, optional};
use crate::measure::{convergence_order, relative_error};
use crate::model::LawSpec;
use crate::runner::RunRecord;
use crate::sim::{PreconditionerKind, RelaxMethod, RunStatus};
use crate::spec::{Campaign, PackingSpec, RunSpec, SceneKind};

/// The rows of a scene's own tables, by its kind (the others empty).
#[derive(Default, Serialize)]
pub(super) struct KindRows {
    /// The scene is a pair's: the template shows its collision table and orders.
    is_pair: bool,
    pair_rows: Vec<PairRow>,
    orders: Vec<OrderRow>,
    chain_rows: Vec<ChainRow>,
    /// Relaxed chains between moved walls.
    wall_rows: Vec<WallRow>,
    lattice_rows: Vec<LatticeRow>,
}

impl KindRows {
    /// True when the scene shows chains relaxed between moved walls (the report then explains
    /// the walls' method once).
    pub(super) fn has_walls(&self) -> bool {
        !self.wall_rows.is_empty()
    }
}

/// The runs of one scene, all of them and the `ok` ones grouped by grid values but dt.
struct SceneRuns<'a> {
    scene: &'a str,
    mine: Vec<&'a RunRecord>,
    groups: Vec<(String, Vec<&'a RunRecord>)>,
}

/// The kind's part of `scene`: the energies every kind draws, then the figures and rows of the
/// scene's own kind.
pub(super) fn part(records: &[RunRecord], scene: &str, kind: SceneKind) -> anyhow::Result<Part<KindRows>> {
    let runs = SceneRuns {
        scene,
        mine: records.iter().filter(|r| r.spec.scene == scene).collect(),
        groups: groups(records, scene),
    };
    let mut figures = energy_figures(scene, &runs.groups)?;
    let own = match kind {
        SceneKind::Pair => pair_part(&runs)?,
        SceneKind::Chain => chain_part(&runs)?,
        SceneKind::Lattice => lattice_part(&runs, records)?,
        SceneKind::Packing => {
            Part { figures: super::jamming::part(records, scene)?.figures, rows: KindRows::default() }
        }
    };
    figures.extend(own.figures);
    Ok(Part { figures, rows: own.rows })
}

/// A pair's part: its measurements against their analytical values over dt (with a sweep), its
/// collisions and the order of convergence of each sweep.
fn pair_part(runs: &SceneRuns) -> anyhow::Result<Part<KindRows>> {
    let swept = runs.groups.iter().any(|(_, members)| members.len() > 1);
    let figures = if swept { vec![convergence_figure(runs.scene, &runs.groups)?] } else { Vec::new() };
    let rows = KindRows {
        is_pair: true,
        pair_rows: runs.mine.iter().map(|r| pair_row(r)).collect(),
        orders: order_rows(&runs.groups),
        ..KindRows::default()
    };
    Ok(Part { figures, rows })
}

/// A chain's part: the displacements of its first group, its relaxation where it times a wave,
/// its moving runs and its runs relaxed between moved walls.
fn chain_part(runs: &SceneRuns) -> anyhow::Result<Part<KindRows>> {
    let mut figures = Vec::new();
    if let Some((label, members)) = runs.groups.first() {
        figures.push(displacement_figure(runs.scene, label, representative(members))?);
    }
    if runs.mine.iter().any(|r| r.spec.wave().is_some()) {
        figures.push(relaxation_figure(runs.scene, &runs.groups)?);
    }
    let (moving, relaxed): (Vec<&RunRecord>, Vec<&RunRecord>) =
        runs.mine.iter().partition(|r| r.spec.relax().is_none());
    let rows = KindRows {
        chain_rows: moving.iter().map(|r| chain_row(r)).collect(),
        wall_rows: relaxed.iter().map(|r| wall_row(r)).collect(),
        ..KindRows::default()
    };
    Ok(Part { figures, rows })
}

/// A lattice's part: its relaxation where something moved in time, its moduli against the size,
/// its relaxed edges, and its loaded runs' moduli.
fn lattice_part(runs: &SceneRuns, records: &[RunRecord]) -> anyhow::Result<Part<KindRows>> {
    let mut figures = Vec::new();
    // Energies against time only where something moved in time: not for a scene set to its
    // static answer or brought to rest by a minimiser.
    let in_time = |r: &RunRecord| r.spec.relax().is_none_or(|relax| relax.method == RelaxMethod::Damped);
    if runs.mine.iter().any(|r| in_time(r)) {
        figures.push(relaxation_figure(runs.scene, &runs.groups)?);
    }
    figures.extend(size_figure(runs.scene, &runs.mine)?);
    figures.extend(edge_figures(records, runs.scene)?);
    let rows =
        KindRows { lattice_rows: runs.mine.iter().filter_map(|r| lattice_row(r)).collect(), ..KindRows::default() };
    Ok(Part { figures, rows })
}

/// Which kinds of scene a campaign has: the template explains each kind's method once.
#[derive(Serialize)]
pub(super) struct KindsPresent {
    has_pair: bool,
    has_chain: bool,
    has_lattice: bool,
    /// A square lattice among them: the methods' continuum is its C11, C12, C44.
    has_square_lattice: bool,
}

impl KindsPresent {
    /// The kinds of `campaign`'s scenes.
    pub(super) fn of(campaign: &Campaign) -> KindsPresent {
        let has = |kind: SceneKind| campaign.scenes.iter().any(|(_, k)| *k == kind);
        KindsPresent {
            has_pair: has(SceneKind::Pair),
            has_chain: has(SceneKind::Chain),
            has_lattice: has(SceneKind::Lattice),
            has_square_lattice: campaign.runs.iter().any(|r| r.lattice().is_some_and(|l| l.lattice_type.is_square())),
        }
    }
}

#[derive(Serialize)]
struct LatticeRow {
    run_id: String,
    label: String,
    size: String,
    springs: String,
    supports: &'static str,
    load_case: String,
    modulus: &'static str,
    md: String,
    fem: String,
    theory: String,
    md_fem: String,
    fem_theory: String,
    poisson_md: String,
    poisson_fem: String,
    poisson_theory: String,
    poisson_coursework: String,
    tangent_md: String,
    tangent_fem: String,
    dissipation_time: String,
    relax_steps: String,
    homogeneity: String,
    status: RunStatus,
}

/// A chain between moved walls, relaxed.
#[derive(Serialize)]
struct WallRow {
    run_id: String,
    label: String,
    law: &'static str,
    wall_displacement: String,
    spacing: String,
    spacing_theory: String,
    spacing_spread: String,
    wall_force: String,
    wall_force_theory: String,
    secant: String,
    secant_theory: String,
    tangent: String,
    tangent_theory: String,
    dissipation_time: String,
    status: RunStatus,
}

#[derive(Serialize)]
struct PairRow {
    run_id: String,
    label: String,
    integrator: &'static str,
    dt_per_tc: String,
    duration: String,
    duration_theory: String,
    duration_error: String,
    restitution: String,
    restitution_theory: String,
    restitution_error: String,
    energy_error: String,
    status: RunStatus,
}

#[derive(Serialize)]
struct OrderRow {
    group: String,
    duration_order: String,
    restitution_order: String,
    duration_error_50: String,
    restitution_error_50: String,
}

#[derive(Serialize)]
struct ChainRow {
    run_id: String,
    label: String,
    n: String,
    node: String,
    dt_per_tc: String,
    energy_error: String,
    mode_error: String,
    wall_s: String,
    status: RunStatus,
}

fn pair_row(r: &RunRecord) -> PairRow {
    let m = &r.metrics;
    PairRow {
        run_id: r.run_id.clone(),
        label: group_label(r),
        integrator: r.spec.integrator.name(),
        dt_per_tc: number(r.spec.dt_per_tc()),
        duration: optional(m.pair.contact_duration),
        duration_theory: optional(m.pair.contact_duration_theory),
        duration_error: error(relative_error(m.pair.contact_duration, m.pair.contact_duration_theory)),
        restitution: optional(m.pair.restitution),
        restitution_theory: optional(m.pair.restitution_theory),
        restitution_error: error(relative_error(m.pair.restitution, m.pair.restitution_theory)),
        energy_error: error(m.energy_error),
        status: r.status,
    }
}

/// Measured order of convergence per group of runs that differ only in dt.
fn order_rows(groups: &[(String, Vec<&RunRecord>)]) -> Vec<OrderRow> {
    groups
        .iter()
        .filter(|(_, members)| members.len() > 1)
        .map(|(group, members)| {
            let order = |error: &dyn Fn(&RunRecord) -> Option<f64>| {
                let points: Vec<(f64, f64)> = members.iter().filter_map(|r| error(r).map(|e| (r.spec.dt, e))).collect();
                convergence_order(&points).map(|p| format!("{p:.2}")).unwrap_or_else(|| "–".into())
            };
            let duration =
                |r: &RunRecord| relative_error(r.metrics.pair.contact_duration, r.metrics.pair.contact_duration_theory);
            let restitution =
                |r: &RunRecord| relative_error(r.metrics.pair.restitution, r.metrics.pair.restitution_theory);
            let reference = representative(members);
            OrderRow {
                duration_error_50: format!("{} at t_c/{:.0}", error(duration(reference)), reference.spec.dt_per_tc()),
                restitution_error_50: error(restitution(reference)),
                duration_order: order(&duration),
                restitution_order: order(&restitution),
                group: group.clone(),
            }
        })
        .collect()
}

fn chain_row(r: &RunRecord) -> ChainRow {
    ChainRow {
        run_id: r.run_id.clone(),
        label: group_label(r),
        n: r.spec.chain().map(|c| c.n.to_string()).unwrap_or_default(),
        node: r.spec.chain().map(|c| c.node.to_string()).unwrap_or_default(),
        dt_per_tc: number(r.spec.dt_per_tc()),
        energy_error: error(r.metrics.energy_error),
        mode_error: error(r.metrics.chain.chain_mode_error),
        wall_s: number(r.wall_s),
        status: r.status,
    }
}

/// Relative difference (a − b)/b as a signed percentage.
fn percent(a: Option<f64>, b: Option<f64>) -> String {
    relative_error(a, b).map(super::words::percent).unwrap_or_else(|| "–".into())
}

fn wall_row(r: &RunRecord) -> WallRow {
    let m = &r.metrics;
    WallRow {
        run_id: r.run_id.clone(),
        label: r.spec.varied_in_words(|_| true),
        law: r.spec.law.name(),
        wall_displacement: number(r.spec.chain_wall_extension()),
        spacing: optional(m.chain.equilibrium_spacing),
        spacing_theory: optional(m.chain.equilibrium_spacing_theory),
        spacing_spread: optional(m.chain.spacing_spread),
        wall_force: optional(m.chain.wall_force),
        wall_force_theory: optional(m.chain.wall_force_theory),
        secant: optional(m.chain.secant_stiffness),
        secant_theory: optional(m.chain.secant_stiffness_theory),
        tangent: optional(m.chain.tangent_stiffness),
        tangent_theory: optional(m.chain.tangent_stiffness_theory),
        dissipation_time: optional(m.dissipation_time),
        status: r.status,
    }
}

/// The springs of a lattice in words: k_d/k, and what makes it anisotropic or random.
fn springs(r: &RunRecord, l: &crate::spec::LatticeSpec) -> String {
    let mut words = vec![if l.lattice_type.is_square() {
        format!("k_d/k = {}", number(l.k_diag / r.spec.k))
    } else {
        l.lattice_type.name().to_string()
    }];
    if !matches!(l.diagonals, crate::spec::Diagonals::Both | crate::spec::Diagonals::None) {
        words.push(format!("{} diagonals only", l.diagonals.name()));
    }
    if l.k_x != l.k_y {
        words.push(format!("k_x/k = {}, k_y/k = {}", number(l.k_x / r.spec.k), number(l.k_y / r.spec.k)));
    }
    if l.rotated {
        words.push("turned by 90° (loads x)".into());
    }
    if l.cut_fraction > 0.0 {
        words.push(format!("{} cut", number(l.cut_fraction)));
    }
    if l.stiffness_spread > 0.0 {
        words.push(format!("k × (1 ± {})", number(l.stiffness_spread)));
    }
    if l.is_random() {
        words.push(format!("seed {}", l.seed));
    }
    if let Some(kept) = r.metrics.lattice.bond_fraction_kept {
        words.push(format!("{} of the bonds kept", number(kept)));
    }
    words.join(", ")
}

fn lattice_row(r: &RunRecord) -> Option<LatticeRow> {
    let l = r.spec.lattice().filter(|l| l.impulse.is_none())?;
    let m = &r.metrics;
    let tensile = l.load_case == crate::spec::LoadCase::Tensile;
    let (modulus, md, fem, theory, tangent_md, tangent_fem) = match (tensile, l.rotated) {
        (true, rotated) => (
            if rotated { "E_x (Pa)" } else { "E_y (Pa)" },
            m.lattice.youngs_modulus,
            m.lattice.youngs_modulus_fem,
            m.lattice.youngs_modulus_theory,
            m.lattice.youngs_modulus_tangent,
            m.lattice.youngs_modulus_tangent_fem,
        ),
        (false, _) => (
            "G (Pa)",
            m.lattice.shear_modulus,
            m.lattice.shear_modulus_fem,
            m.lattice.shear_modulus_theory,
            m.lattice.shear_modulus_tangent,
            m.lattice.shear_modulus_tangent_fem,
        ),
    };
    Some(LatticeRow {
        run_id: r.run_id.clone(),
        label: r.spec.varied_in_words(|_| true),
        size: format!("{} × {}", l.nx, l.ny),
        springs: springs(r, l),
        supports: l.supports.name(),
        load_case: match l.control {
            crate::spec::Control::Force => l.load_case.name().to_string(),
            crate::spec::Control::Velocity => {
                format!("{} (driven to strain {})", l.load_case.name(), number(l.drive_strain))
            }
        },
        modulus,
        md: optional(md),
        fem: optional(fem),
        theory: optional(theory),
        md_fem: percent(md, fem),
        fem_theory: percent(fem, theory),
        poisson_md: optional(m.lattice.poisson_ratio),
        poisson_fem: optional(m.lattice.poisson_ratio_fem),
        poisson_theory: if tensile { optional(m.lattice.poisson_ratio_theory) } else { "–".into() },
        poisson_coursework: optional(m.lattice.poisson_ratio_coursework),
        tangent_md: optional(tangent_md),
        tangent_fem: optional(tangent_fem),
        dissipation_time: optional(m.dissipation_time),
        relax_steps: r.steps.to_string(),
        homogeneity: optional(m.lattice.homogeneity),
        status: r.status,
    })
}

/// The scene's physics in one sentence: springs, masses, geometry, supports and load, scheme.
pub(super) fn physics_words(s: &RunSpec) -> String {
    let law = spring_words(s);
    match s.lattice() {
        Some(l) => {
            // Another type than square has one spring to every nearest neighbour, no diagonals.
            let network = if l.lattice_type.is_square() {
                // The diagonals follow the same law: C_d in N/m^β for a power law.
                let (symbol, unit) = match s.law {
                    LawSpec::Linear => ("k_d", "N/m".to_string()),
                    LawSpec::Power { beta } => ("C_d", format!("N/m^{}", number(beta))),
                };
                format!(
                    "{law} along rows and columns, diagonals {symbol} = {} {unit} ({symbol}/{} = {})",
                    number(l.k_diag),
                    if s.law.is_linear() { "k" } else { "C" },
                    number(l.k_diag / s.k)
                )
            } else {
                format!(
                    "a {} network (z = {}), {law} to every nearest neighbour",
                    l.lattice_type.name(),
                    l.lattice_type.coordination()
                )
            };
            format!(
                "{network}, m = {} kg, a = {} m, depth d = {} m, {} supports, {}, {}",
                number(s.mass),
                number(s.spacing),
                number(l.depth),
                l.supports.name(),
                match l.impulse {
                    Some(i) => impulse_words(&i),
                    None => match l.force_per_node() {
                        Some(force) => format!("{} load {} N per top node", l.load_case.name(), number(force)),
                        None => format!(
                            "{}, the top row driven to a strain of {} over {} t_c",
                            l.load_case.name(),
                            number(l.drive_strain),
                            number(l.drive_tc)
                        ),
                    },
                },
                s.integrator.name()
            ) + &l.derived_from.as_ref().map(|note| format!(". Derived from the solid: {note}")).unwrap_or_default()
        }
        None => match s.packing() {
            Some(p) => packing_words(s, p, &law),
            None => format!(
                "{law}, {}, m = {} kg, x_e = {} m, v0 = {} m/s, {}",
                if s.contact { "contact (compression only)" } else { "bonded (tension and compression)" },
                number(s.mass),
                number(s.spacing),
                number(s.v0),
                s.integrator.name()
            ),
        },
    }
}

/// A packing scene's physics: its contact springs, its two kinds of disc and how it comes to
/// rest (a minimiser, not the scene's integrator: `relax.method`).
fn packing_words(s: &RunSpec, p: &PackingSpec, law: &str) -> String {
    let ratio = p.radius_ratio;
    // A packing relaxes by a minimiser (the spec refuses the others).
    let method = if s.relax().is_some_and(|r| r.method == RelaxMethod::Cg) { "conjugate gradients" } else { "FIRE" };
    // Whether each run got there within its budget is the run's own (its row's packing_state).
    let until = s
        .relax()
        .and_then(|r| r.residual_force)
        .map_or(String::new(), |f| format!(" until its largest force is below {} k d^β", number(f)));
    let made = p.compression.map_or(String::new(), |c| {
        format!(", made by a slow compression from φ = {} in {} steps", number(c.from), c.steps)
    });
    // The first ⌈n/2⌉ discs are small, the rest large (PackingSpec::n).
    let (small, large) = (p.n.div_ceil(2), p.n / 2);
    // One spec speaks for its scene: a count or ratio its grid varies is not this run's alone.
    let varies = |path: &str| s.varied.contains_key(path);
    let discs = if varies("packing.n") || varies("packing.radius_ratio") {
        format!(
            "N discs (packing.n) in two halves, the first ⌈N/2⌉ of diameter d = {} m and mass m = {} kg and the rest \
             packing.radius_ratio times as wide and its square times as heavy (mass ∝ area), as the grid sets them",
            number(s.spacing),
            number(s.mass)
        )
    } else if ratio == 1.0 {
        format!("{} equal discs of diameter d = {} m and mass m = {} kg", p.n, number(s.spacing), number(s.mass))
    } else {
        format!(
            "{small} discs of diameter d = {} m and mass m = {} kg and {large} discs {} times as wide and {} times as \
             heavy (mass ∝ area)",
            number(s.spacing),
            number(s.mass),
            number(ratio),
            number(ratio * ratio)
        )
    };
    format!(
        "{law} between touching discs (contacts, compression only); {discs}, in a periodic square box, relaxed towards \
         an energy minimum by {method}{until}{made}"
    )
}

/// A scene's time step as its runs took it: "dt = t_c/50 = 0.04443 s", the range of a grid over
/// it, or what a minimiser or the static solve takes instead (FIRE starts from dt and grows its
/// step to at most 10 dt; CG and the static solve take none).
pub(super) fn time_step_words(runs: &[&RunRecord]) -> String {
    let method = |r: &RunRecord| r.spec.relax().map_or(RelaxMethod::Damped, |x| x.method);
    let timed: Vec<&RunRecord> = runs.iter().filter(|r| method(r) == RelaxMethod::Damped).copied().collect();
    let mut steps: Vec<f64> = timed.iter().map(|r| r.spec.dt_per_tc()).collect();
    steps.sort_by(f64::total_cmp);
    steps.dedup();
    let dt = |per: f64| timed.iter().find(|r| r.spec.dt_per_tc() == per).map_or(f64::NAN, |r| r.spec.dt);
    let mut parts: Vec<String> = match steps[..] {
        [] => Vec::new(),
        [one] => vec![format!("dt = t_c/{} = {} s", number(one), number(dt(one)))],
        [.., fine] => vec![format!("dt from t_c/{} to t_c/{} over its runs", number(steps[0]), number(fine))],
    };
    let metric = |r: &RunRecord| r.spec.relax().is_some_and(|x| x.preconditioner != PreconditionerKind::None);
    if runs.iter().any(|r| method(r) == RelaxMethod::Fire && metric(r)) {
        // Its step is dimensionless: P⁻¹K's frequencies are near 1 (`sim::relax::fire`).
        parts.push("FIRE in the stiffness metric steps from a dimensionless 0.5 up to 1".into());
    }
    if let Some(r) = runs.iter().find(|r| method(r) == RelaxMethod::Fire && !metric(r)) {
        parts.push(format!(
            "FIRE starts from Δt = t_c/{} = {} s and grows it to at most 10 Δt",
            number(r.spec.dt_per_tc()),
            number(r.spec.dt)
        ));
    }
    if runs.iter().any(|r| matches!(method(r), RelaxMethod::Cg | RelaxMethod::Static)) {
        parts.push("conjugate gradients and the static solve take no time step".into());
    }
    parts.join("; ")
}

/// A scene's springs in words, with their stiffness: "linear springs k = … N/m".
fn spring_words(s: &RunSpec) -> String {
    match s.law {
        LawSpec::Linear => format!("linear springs k = {} N/m", number(s.k)),
        LawSpec::Power { beta } => format!("power-law springs C = {} N/m^β, β = {}", number(s.k), number(beta)),
    }
}

/// The contact time t_c (s) a scene's dt is set from, with the formula that gives it: the
/// undamped linear pair's π√(m/(2k)), the damped one's π/√(2k/m − (γ/m)²) (the bond dashpot
/// slows the pair) or a power law's duration at the scene's deformation. `spec.t_c` is the
/// damped value, so a formula without γ next to it would be wrong by the damping's share.
pub(super) fn contact_time_words(spec: &RunSpec) -> String {
    let undamped = std::f64::consts::PI * (spec.mass / (2.0 * spec.k)).sqrt();
    match spec.law {
        LawSpec::Linear if spec.gamma == 0.0 => format!("t_c = π√(m/(2k)) = {} s", number(spec.t_c)),
        LawSpec::Linear => format!(
            "t_c = π/√(2k/m − (γ/m)²) = {} s with the bond dashpot γ = {} N s/m (π√(m/(2k)) = {} s undamped)",
            number(spec.t_c),
            number(spec.gamma),
            number(undamped)
        ),
        LawSpec::Power { .. } if spec.scene_kind.is_collision() => format!(
            "t_c = {} s, the {} pair's contact duration at the scene's impact speed",
            number(spec.t_c),
            law_name(spec.law)
        ),
        LawSpec::Power { .. } if spec.gamma == 0.0 => format!(
            "t_c = π√(m/(2k_t)) = {} s, the {} pair linearised at the deformation the scene expects (k_t its \
             tangent stiffness there)",
            number(spec.t_c),
            law_name(spec.law)
        ),
        LawSpec::Power { .. } => format!(
            "t_c = π/√(2k_t/m − (γ/m)²) = {} s, the {} pair linearised at the deformation the scene expects (k_t its \
             tangent stiffness there) with the bond dashpot γ = {} N s/m",
            number(spec.t_c),
            law_name(spec.law),
            number(spec.gamma)
        ),
    }
}

/// A spring law's name in a sentence, capitalised: `Linear`, `Hertz` for the power law of
/// β = 3/2 (`law: hertz`), `Power-law (β = 2)` for any other exponent.
pub fn law_name(law: LawSpec) -> String {
    match law {
        LawSpec::Linear => "Linear".into(),
        LawSpec::Power { beta: 1.5 } => "Hertz".into(),
        LawSpec::Power { beta } => format!("Power-law (β = {})", number(beta)),
    }
}
