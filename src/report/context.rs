//! The data the templates see: pre-formatted numbers, one section per scene.

use serde::Serialize;

use super::exponents::{ExponentRow, exponent_rows};
use super::figure::{Figure, FigureRef, group_label, groups, movie_refs, representative};
use super::findings::{Evidence, Finding, Paragraph, discussion, findings};
use super::precision::{PrecisionRow, precision_rows};
use super::stability_map::{LimitRow, StabilityRow, is_stability_scene, stability_rows};
use super::waves::{WaveRow, wave_rows};
use super::words::{error, impulse_words, number, optional};
use crate::measure::convergence_order;
use crate::measure::relative_error;
use crate::model::LawSpec;
use crate::runner::{BUILD, RunRecord};
use crate::sim::RunStatus;
use crate::spec::{Campaign, RunSpec, SceneKind};
use crate::summary::ScalingFit;

/// Runs of the campaign that are not in a report, and why (`mdsolids report` of a store that
/// lacks some).
#[derive(Clone, Debug, Default)]
pub struct LeftOut {
    /// Runs without a stored record.
    pub missing: Vec<String>,
    /// Runs whose stored record is corrupt, with why.
    pub corrupt: Vec<(String, String)>,
    /// The row count of the previous, larger results table, when it was kept aside as
    /// `results.previous.csv` and `.parquet`.
    pub previous_table: Option<usize>,
}

/// Everything the report templates show.
#[derive(Serialize)]
pub struct ReportContext {
    name: String,
    title: String,
    description: String,
    /// This build (version + source fingerprint).
    build: &'static str,
    runs: usize,
    /// Runs of the campaign.
    campaign_runs: usize,
    ok: usize,
    failed: usize,
    /// Runs of the campaign without a stored record (a shard not run yet, or a task that died).
    missing: usize,
    /// Runs whose stored record is corrupt.
    corrupt: usize,
    /// The runs left out (corrupt ones first, then at most [`LISTED_MISSING`] missing ones).
    left_out: Vec<LeftOutRow>,
    /// Row count of the previous, larger table kept aside (0: none kept).
    previous_table: usize,
    /// Runs in the report made by another build.
    other_build: Vec<LeftOutRow>,
    wall_s: String,
    has_pair: bool,
    has_chain: bool,
    has_lattice: bool,
    has_wave: bool,
    target_error: String,
    /// The coursework's items this campaign answers, in the coursework's order.
    findings: Vec<Finding>,
    /// The discussion's paragraphs.
    discussion: Vec<Paragraph>,
    /// Which methods the scenes' tables need explained (once, not per scene).
    explains: Explains,
    scenes: Vec<SceneSection>,
    failures: Vec<FailureRow>,
}

/// The methods whose explanation the report needs: those of the tables some scene shows.
#[derive(Serialize)]
struct Explains {
    walls: bool,
    waves: bool,
    ensembles: bool,
    exponents: bool,
    precision: bool,
    stability: bool,
}

impl Explains {
    fn of(scenes: &[SceneSection]) -> Explains {
        let any = |has: fn(&SceneSection) -> bool| scenes.iter().any(has);
        Explains {
            walls: any(|s| !s.wall_rows.is_empty()),
            waves: any(|s| !s.wave_rows.is_empty()),
            ensembles: any(|s| !s.ensemble_rows.is_empty()),
            exponents: any(|s| !s.exponent_rows.is_empty()),
            precision: any(|s| !s.precision_rows.is_empty()),
            stability: any(|s| !s.stability_rows.is_empty()),
        }
    }
}

#[derive(Serialize)]
struct SceneSection {
    name: String,
    kind: &'static str,
    is_pair: bool,
    physics: String,
    t_c: String,
    dt_50: String,
    figures: Vec<FigureRef>,
    pair_rows: Vec<PairRow>,
    orders: Vec<OrderRow>,
    chain_rows: Vec<ChainRow>,
    lattice_rows: Vec<LatticeRow>,
    wall_rows: Vec<WallRow>,
    precision_rows: Vec<PrecisionRow>,
    stability_rows: Vec<StabilityRow>,
    limit_rows: Vec<LimitRow>,
    wave_rows: Vec<WaveRow>,
    exponent_rows: Vec<ExponentRow>,
    ensemble_rows: Vec<super::solids::EnsembleRow>,
    movies: Vec<FigureRef>,
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

/// A run and a reason: why it is left out, or the build that made it.
#[derive(Serialize)]
struct LeftOutRow {
    run_id: String,
    why: String,
}

/// Missing runs listed by name in a report (a cluster job may lack thousands).
const LISTED_MISSING: usize = 50;

#[derive(Serialize)]
struct FailureRow {
    run_id: String,
    status: RunStatus,
    message: String,
}

/// Builds the context from the campaign, its records, their scaling fits and the drawn figures.
pub fn build(
    campaign: &Campaign,
    records: &[RunRecord],
    fits: &[ScalingFit],
    left_out: &LeftOut,
    figures: &[Figure],
    side_by_side: &[String],
) -> ReportContext {
    let ok = records.iter().filter(|r| r.status == RunStatus::Ok).count();
    let evidence = Evidence::new(records, fits, figures, side_by_side);
    let scenes: Vec<SceneSection> = campaign
        .scenes
        .iter()
        .filter_map(|(scene, kind)| section(scene, *kind, records, fits, figures, campaign.target_error, side_by_side))
        .collect();
    let row = |run_id: &String, why: String| LeftOutRow { run_id: run_id.clone(), why };
    let mut left_out_rows: Vec<LeftOutRow> =
        left_out.corrupt.iter().map(|(run_id, why)| row(run_id, format!("corrupt record: {why}"))).collect();
    left_out_rows
        .extend(left_out.missing.iter().take(LISTED_MISSING).map(|run_id| row(run_id, "no stored result".into())));
    if left_out.missing.len() > LISTED_MISSING {
        let more = left_out.missing.len() - LISTED_MISSING;
        left_out_rows.push(LeftOutRow { run_id: format!("… and {more} more"), why: "no stored result".into() });
    }
    ReportContext {
        name: campaign.name.clone(),
        title: campaign.title.clone(),
        description: campaign.description.clone(),
        build: BUILD,
        runs: records.len(),
        campaign_runs: campaign.runs.len(),
        ok,
        failed: records.len() - ok,
        missing: left_out.missing.len(),
        corrupt: left_out.corrupt.len(),
        left_out: left_out_rows,
        previous_table: left_out.previous_table.unwrap_or(0),
        other_build: records.iter().filter(|r| r.build != BUILD).map(|r| row(&r.run_id, r.build.clone())).collect(),
        wall_s: number(records.iter().map(|r| r.wall_s).sum()),
        has_pair: campaign.scenes.iter().any(|(_, k)| *k == SceneKind::Pair),
        has_chain: campaign.scenes.iter().any(|(_, k)| *k == SceneKind::Chain),
        has_lattice: campaign.scenes.iter().any(|(_, k)| *k == SceneKind::Lattice),
        target_error: format!("{:e}", campaign.target_error),
        has_wave: records.iter().any(|r| r.spec.wave().is_some()),
        findings: findings(&evidence),
        discussion: discussion(&evidence),
        explains: Explains::of(&scenes),
        scenes,
        failures: records
            .iter()
            .filter(|r| r.status != RunStatus::Ok)
            .map(|r| FailureRow { run_id: r.run_id.clone(), status: r.status, message: r.message.clone() })
            .collect(),
    }
}

fn section(
    scene: &str,
    kind: SceneKind,
    records: &[RunRecord],
    fits: &[ScalingFit],
    figures: &[Figure],
    target_error: f64,
    side_by_side: &[String],
) -> Option<SceneSection> {
    let mine: Vec<&RunRecord> = records.iter().filter(|r| r.spec.scene == scene).collect();
    let s = &mine.first()?.spec;
    let physics = physics_words(s);
    let (stability_rows, limit_rows) =
        if is_stability_scene(records, scene) { stability_rows(records, scene) } else { Default::default() };
    Some(SceneSection {
        name: scene.into(),
        kind: kind.name(),
        is_pair: kind == SceneKind::Pair,
        physics,
        t_c: number(s.t_c),
        dt_50: number(s.t_c / 50.0),
        figures: figures.iter().filter(|f| f.scene == scene).map(Figure::reference).collect(),
        pair_rows: if kind == SceneKind::Pair { mine.iter().map(|r| pair_row(r)).collect() } else { Vec::new() },
        orders: if kind == SceneKind::Pair { order_rows(records, scene) } else { Vec::new() },
        chain_rows: mine
            .iter()
            .filter(|r| kind == SceneKind::Chain && r.spec.relax().is_none())
            .map(|r| chain_row(r))
            .collect(),
        wall_rows: mine
            .iter()
            .filter(|r| kind == SceneKind::Chain && r.spec.relax().is_some())
            .map(|r| wall_row(r))
            .collect(),
        lattice_rows: mine.iter().filter_map(|r| lattice_row(r)).collect(),
        precision_rows: precision_rows(records, scene, target_error),
        stability_rows,
        limit_rows,
        wave_rows: wave_rows(records, scene),
        exponent_rows: exponent_rows(fits, scene),
        ensemble_rows: super::solids::ensemble_rows(records, scene),
        movies: movie_refs(scene, &mine, side_by_side),
    })
}

/// The scene's physics in one sentence: springs, masses, geometry, supports and load, scheme.
fn physics_words(s: &RunSpec) -> String {
    let law = match s.law {
        LawSpec::Linear => format!("linear springs k = {} N/m", number(s.k)),
        LawSpec::Power { beta } => format!("power-law springs C = {} N/m^β, β = {}", number(s.k), number(beta)),
    };
    match s.lattice() {
        Some(l) => {
            // Another type than square has one spring to every nearest neighbour, no diagonals.
            let network = if l.lattice_type.is_square() {
                format!(
                    "{law} along rows and columns, diagonals k_d = {} N/m (k_d/k = {})",
                    number(l.k_diag),
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
        None => format!(
            "{law}, {}, m = {} kg, x_e = {} m, v0 = {} m/s, {}",
            if s.contact { "contact (compression only)" } else { "bonded (tension and compression)" },
            number(s.mass),
            number(s.spacing),
            number(s.v0),
            s.integrator.name()
        ),
    }
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
fn order_rows(records: &[RunRecord], scene: &str) -> Vec<OrderRow> {
    groups(records, scene)
        .into_iter()
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
            let reference = representative(&members);
            OrderRow {
                duration_error_50: format!("{} at t_c/{:.0}", error(duration(reference)), reference.spec.dt_per_tc()),
                restitution_error_50: error(restitution(reference)),
                duration_order: order(&duration),
                restitution_order: order(&restitution),
                group,
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
    relative_error(a, b).map(|e| format!("{:+.3} %", 100.0 * e)).unwrap_or_else(|| "–".into())
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
