//! From a merged raw scene to a [`RunSpec`]: defaults filled in, ranges checked, γ, t_c and dt
//! derived. Every rejection names the field path, the value and what is allowed.

use serde_json::Value;
use std::collections::BTreeMap;
use std::fmt::Display;

use super::MAX_NAME_LEN;
use super::kind::{ChainRun, KindSpec, LatticeRun, PairRun};
use super::raw::{
    Control, Diagonals, LoadCase, RawDamping, RawGeometry, RawImpulse, RawLattice, RawMaterial, RawMovie, RawProbes,
    RawScene, RawTime, RawWave, SceneKind, Supports,
};
use super::run_spec::{
    ImpulseSpec, LatticeSpec, MovieSpec, ProbeLine, RelaxSpec, RunSpec, WaveSpec, reference_extension,
};
use crate::model::{LawName, LawSpec};
use crate::sim::IntegratorKind;
use crate::theory;

/// A value the campaign may not have, with the field path (relative to the scene).
#[derive(Clone, Debug, PartialEq)]
pub struct Issue {
    /// Dotted field path, e.g. `damping.restitution`.
    pub path: String,
    /// The offending value as written.
    pub value: String,
    /// What is allowed instead.
    pub allowed: String,
}

fn require(ok: bool, path: &str, value: impl Display, allowed: &str) -> Result<(), Issue> {
    if ok {
        Ok(())
    } else {
        Err(Issue { path: path.to_string(), value: value.to_string(), allowed: allowed.to_string() })
    }
}

/// A number shown in a message: in full when it is short that way, else in exponent form
/// (`1e-300`, not three hundred zeros).
struct Num(f64);

impl Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let size = self.0.abs();
        if size == 0.0 || (1e-4..1e15).contains(&size) || !size.is_finite() {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

fn non_negative(value: f64, path: &str) -> Result<f64, Issue> {
    require(
        value.is_finite() && value >= 0.0,
        path,
        Num(value),
        "must be a finite number ≥ 0 (0: no diagonal springs)",
    )?;
    Ok(value)
}

fn positive(value: f64, path: &str) -> Result<f64, Issue> {
    require(value.is_finite() && value > 0.0, path, Num(value), "must be a finite number > 0")?;
    Ok(value)
}

/// Scene defaults when neither the scene nor `defaults` says otherwise.
const DEFAULT_MASS: f64 = 1.0;
const DEFAULT_STIFFNESS: f64 = 1.0;
const DEFAULT_SPACING: f64 = 1.0;
const DEFAULT_BETA: f64 = 1.5;
/// dt = t_c / this unless the campaign sets dt another way.
pub const DEFAULT_DT_PER_TC: f64 = 50.0;
const DEFAULT_SAMPLES: u64 = 400;
/// Lattice defaults: k_d/k, load per top-row node (N), E_kin/E_pot tolerance, longest run (t_c).
const DEFAULT_K_DIAG_RATIO: f64 = 0.5;
const DEFAULT_LOAD_PER_NODE: f64 = 1000.0;
const DEFAULT_KINETIC_RATIO: f64 = 1e-8;
const DEFAULT_MAX_TC: f64 = 5000.0;
/// Default gap of a contact pair, in spacings: contact starts at a time not aligned with dt.
const DEFAULT_GAP_PER_SPACING: f64 = 0.05;

/// Threshold of the wave-arrival criteria, relative to the source's peak.
const DEFAULT_WAVE_THRESHOLD: f64 = 0.01;

/// Resolves one scene of campaign `campaign` with grid values `varied` already applied.
pub fn resolve(campaign: &str, raw: &RawScene, varied: BTreeMap<String, Value>) -> Result<RunSpec, Issue> {
    let name = raw.name.clone().unwrap_or_default();
    require(
        super::is_safe_name(&name),
        "name",
        format!("{name:?}"),
        &format!("1 to {MAX_NAME_LEN} letters, digits, '-' and '_' (it names files: plots/<name>-....svg)"),
    )?;
    let kind = raw.kind.ok_or_else(|| Issue {
        path: "kind".into(),
        value: "(missing)".into(),
        allowed: "one of pair, chain, lattice".into(),
    })?;
    let mut spec = resolve_body(campaign, name, kind, raw, varied)?;
    let time = raw.time.clone().unwrap_or_default();
    let (gamma, restitution_target, gamma_background, t_c) = resolve_contact_time(&spec, raw)?;
    let integrator = spec.integrator;
    require(
        integrator.allows_damping() || (gamma == 0.0 && gamma_background == 0.0),
        "time.integrator",
        integrator.name(),
        "an integrator that allows damping (all but forest-ruth, whose backward sub-step would run the dashpots \
         backwards), or no damping",
    )?;
    let dt = resolve_dt(&time, t_c)?;
    let (spacing, contact) = (spec.spacing, spec.contact);
    let gap = (kind == SceneKind::Pair && contact).then(|| raw.gap.unwrap_or(DEFAULT_GAP_PER_SPACING * spacing));
    if let Some(g) = gap {
        require(g.is_finite() && g >= 0.0, "gap", g, "must be a finite number ≥ 0")?;
    }
    let (duration, steps, samples) = resolve_length(&spec, raw, gap, t_c, dt)?;
    match (&mut spec.scene_kind, &raw.wave) {
        (KindSpec::Pair(pair), _) => pair.gap = gap,
        (KindSpec::Lattice(run), Some(w)) => run.wave = lattice_wave(&run.lattice, w, spacing)?,
        _ => {}
    }
    let movie = raw.movie.as_ref().map(resolve_movie).transpose()?;
    if let Some(r) = spec.reference_refinement {
        require((2..=1000).contains(&r), "time.reference_refinement", r, "an integer from 2 to 1000")?;
        require(
            steps.saturating_mul(u64::from(r)) <= 2_000_000_000,
            "time.reference_refinement",
            r,
            "a reference run of at most 2e9 steps",
        )?;
    }
    // Where dt_omega_max sets dt, dt and steps are the plan's to decide (unplanned: NaN and 0).
    let (dt, steps) = if spec.dt_omega_max.is_some() { (f64::NAN, 0) } else { (dt, steps) };
    Ok(RunSpec { gamma, restitution_target, gamma_background, t_c, dt, duration, steps, samples, movie, ..spec })
}

/// The spec before its time scale: material, v0 and the kind's own fields (lattice, chain,
/// relaxation), checked; γ, t_c, dt, the run's length, the gap and the movie still unset.
fn resolve_body(
    campaign: &str,
    name: String,
    kind: SceneKind,
    raw: &RawScene,
    varied: BTreeMap<String, Value>,
) -> Result<RunSpec, Issue> {
    let time = raw.time.clone().unwrap_or_default();
    let geometry = raw.geometry.clone().unwrap_or_default();
    let spacing = positive(geometry_spacing(&geometry), "geometry.spacing")?;
    let Springs { mass, k, law, contact, derived_from } = resolve_springs(kind, raw, spacing, geometry.depth)?;
    check_kind_fields(kind, raw)?;
    let v0 = resolve_v0(kind, raw, contact)?;
    let scene_kind = resolve_kind(kind, raw, k, spacing, geometry.depth, derived_from)?;
    let spec = RunSpec {
        campaign: campaign.to_string(),
        scene: name,
        scene_kind,
        varied,
        mass,
        spacing,
        k,
        law,
        contact,
        gamma: 0.0,
        restitution_target: None,
        gamma_background: 0.0,
        integrator: time.integrator.unwrap_or(IntegratorKind::PositionVerlet),
        t_c: 0.0,
        dt: 0.0,
        dt_omega_max: time.dt_omega_max,
        reference_refinement: time.reference_refinement,
        allow_unstable: time.allow_unstable.unwrap_or(false),
        duration: 0.0,
        steps: 0,
        samples: 0,
        v0,
        movie: None,
    };
    if let Some(chain) = spec.chain().filter(|_| raw.relax.is_some()) {
        check_relaxing_chain(&spec, chain)?;
    }
    Ok(spec)
}

/// The kind's own fields: a lattice (with how it was derived from a solid, if it was) or a
/// chain, and their relaxation; a pair's gap is decided with the time scale.
fn resolve_kind(
    kind: SceneKind,
    raw: &RawScene,
    k: f64,
    spacing: f64,
    depth: Option<f64>,
    derived_from: Option<String>,
) -> Result<KindSpec, Issue> {
    Ok(match kind {
        SceneKind::Pair => KindSpec::Pair(PairRun { gap: None }),
        SceneKind::Chain => {
            let chain = resolve_chain(raw, spacing)?;
            let relax = raw.relax.is_some().then(|| resolve_relax(raw, Control::Force)).transpose()?;
            KindSpec::Chain(ChainRun { relax, ..chain })
        }
        SceneKind::Lattice => {
            let lattice = LatticeSpec { derived_from, ..resolve_lattice(raw, k, depth)? };
            let relax = lattice.impulse.is_none().then(|| resolve_relax(raw, lattice.control)).transpose()?;
            KindSpec::Lattice(LatticeRun { lattice, relax, wave: None })
        }
    })
}

/// A scene's particles' mass (kg) and springs: stiffness, law, β, contact switch, and how
/// they were derived from a solid, if they were.
struct Springs {
    mass: f64,
    k: f64,
    law: LawSpec,
    contact: bool,
    derived_from: Option<String>,
}

/// Mass, stiffness, law, β and the contact switch of a scene's springs, from its material or
/// the solid a lattice stands for (with the note of how, see [`derive_from_solid`]).
fn resolve_springs(kind: SceneKind, raw: &RawScene, spacing: f64, depth: Option<f64>) -> Result<Springs, Issue> {
    let material = raw.material.clone().unwrap_or_default();
    let solid = derive_from_solid(kind, raw, &material, spacing, depth)?;
    let material = RawMaterial { mass: solid.mass.or(material.mass), k: solid.k.or(material.k), ..material };
    let (mass, k, law, contact) = resolve_material(&material)?;
    // Each finite and > 0, but a ratio beyond f64's range (m = 1e300, k = 1e-300) leaves no time scale.
    require(
        (k / mass).is_normal(),
        "material",
        format!("mass = {}, k = {}", Num(mass), Num(k)),
        &format!("k / mass = {} must be a normal number > 0 (mass and k too far apart)", Num(k / mass)),
    )?;
    Ok(Springs { mass, k, law, contact, derived_from: solid.note })
}

/// The initial speed v0 (m/s): none for a lattice, ≥ 0 for a relaxing chain (its walls may
/// be what moves it), > 0 and required otherwise; lattices and relaxing chains are bonded.
fn resolve_v0(kind: SceneKind, raw: &RawScene, contact: bool) -> Result<f64, Issue> {
    let relaxing_chain = kind == SceneKind::Chain && raw.relax.is_some();
    let v0 = match kind {
        SceneKind::Lattice => 0.0,
        SceneKind::Chain if relaxing_chain => {
            let v0 = raw.v0.unwrap_or(0.0);
            require(v0.is_finite() && v0 >= 0.0, "v0", v0, "must be a finite number ≥ 0 (m/s)")?;
            v0
        }
        _ => positive(raw.v0.ok_or_else(|| missing("v0", "the initial speed (m/s), > 0"))?, "v0")?,
    };
    if kind == SceneKind::Lattice || relaxing_chain {
        require(!contact, "material.contact", contact, "lattices and relaxing chains have bonded springs: false")?;
    }
    Ok(v0)
}

/// A relaxing chain's walls: far enough apart that its last spring does not collapse, and
/// moved (or the chain kicked), so that there is something to relax.
fn check_relaxing_chain(spec: &RunSpec, chain: &ChainRun) -> Result<(), Issue> {
    let walls = chain.wall_distance;
    let least = (chain.n as f64 + 0.1) * spec.spacing;
    require(
        walls > least,
        "wall_distance",
        walls,
        &format!(
            "more than (n + 0.1) · spacing = {least}: a relaxing chain starts at rest spacing from the left wall, \
             so the last spring takes the whole wall displacement at first and must not collapse"
        ),
    )?;
    require(
        spec.v0 > 0.0 || spec.chain_wall_extension().abs() > 1e-12 * walls,
        "wall_distance",
        walls,
        "a relaxing chain needs its walls moved from (n + 1) · spacing, or a v0",
    )?;
    // The residual-force criterion is relative to the equilibrium wall force: none when
    // the walls are not moved, and the run could never count as relaxed.
    require(
        chain.relax.is_none_or(|r| r.residual_force.is_none()) || spec.chain_wall_extension() != 0.0,
        "relax.residual_force",
        "(set)",
        "needs walls moved from (n + 1) · spacing (it is a fraction of the wall force); use relax.kinetic_ratio",
    )
}

/// The damping (γ, the restitution it came from, γ_g) and the contact time t_c (s) of `spec`.
fn resolve_contact_time(spec: &RunSpec, raw: &RawScene) -> Result<(f64, Option<f64>, f64, f64), Issue> {
    let (mass, k, law, v0) = (spec.mass, spec.k, spec.law, spec.v0);
    // A power law has no stiffness at δ = 0: its tangent β C |δ|^(β−1) at the reference
    // extension stands in for k where a linear formula is needed.
    let stiffness_for_damping = law.tangent_stiffness(k, reference_extension(spec));
    require(
        stiffness_for_damping > 0.0 && stiffness_for_damping.is_finite(),
        "material.law",
        law.name(),
        "a power law needs a deformation to have stiffness: a v0, a load or moved walls",
    )?;
    let damping = raw.damping.clone().unwrap_or_default();
    let (gamma, restitution_target, gamma_background) = resolve_damping(&damping, stiffness_for_damping, mass)?;
    // A collision (pair, kicked chain) has an exact power-law contact duration; a loaded or
    // relaxing scene takes the linear one at its tangent stiffness.
    let collision = spec.kind() == SceneKind::Pair || (spec.kind() == SceneKind::Chain && raw.relax.is_none());
    let t_c = match law {
        LawSpec::Power { beta } if collision => theory::pair_omega(stiffness_for_damping, mass, gamma)
            .map(|_| theory::power_law_contact_duration(k, beta, mass, v0)),
        _ => theory::linear_contact_duration(stiffness_for_damping, mass, gamma),
    }
    .map_err(|e| Issue { path: "damping".into(), value: format!("γ = {gamma}"), allowed: e.to_string() })?;
    // Extreme but finite inputs (m = 1e-300 with k = 1e300) can still over- or underflow here.
    require(
        t_c.is_finite() && t_c > 0.0,
        "material",
        format!("mass = {}, k = {}", Num(mass), Num(k)),
        &format!("give a contact time t_c = {} s; it must be finite and > 0 (mass, k and v0 too far apart)", Num(t_c)),
    )?;
    Ok((gamma, restitution_target, gamma_background, t_c))
}

/// The run's length: duration (s), steps of `dt` and samples, by default long enough for what
/// the kind shows (a contact, a few wave crossings, a relaxation up to `relax.max_tc`).
fn resolve_length(
    spec: &RunSpec,
    raw: &RawScene,
    gap: Option<f64>,
    t_c: f64,
    dt: f64,
) -> Result<(f64, u64, u64), Issue> {
    let time = raw.time.clone().unwrap_or_default();
    let default_duration_tc = match spec.kind() {
        SceneKind::Pair if spec.contact => gap.unwrap_or(0.0) / (spec.v0 * t_c) + 1.5,
        SceneKind::Pair => 3.0,
        SceneKind::Chain if raw.relax.is_none() => 20.0,
        // An impulse lattice runs until the wave has crossed it about three times.
        SceneKind::Lattice if raw.impulse.is_some() => 3.0 * spec.lattice().map_or(1, |l| l.nx.max(l.ny)) as f64,
        _ => raw.relax.as_ref().and_then(|r| r.max_tc).unwrap_or(DEFAULT_MAX_TC),
    };
    let duration_path = if spec.relax().is_some() { "relax.max_tc" } else { "time.duration_tc" };
    let duration = t_c * positive(time.duration_tc.unwrap_or(default_duration_tc), duration_path)?;
    let steps = (duration / dt).ceil() as u64;
    require(
        (1..=2_000_000_000).contains(&steps),
        duration_path,
        Num(duration / t_c),
        &format!("from 1 to 2e9 steps of dt = {} s (it gives {steps})", Num(dt)),
    )?;
    let samples = time.samples.unwrap_or(DEFAULT_SAMPLES);
    require(samples >= 2, "time.samples", samples, "must be ≥ 2")?;
    Ok((duration, steps, samples))
}

/// The movie a scene asks for: frames and size in range.
fn resolve_movie(m: &RawMovie) -> Result<MovieSpec, Issue> {
    let frames = m.frames.unwrap_or(60);
    require((2..=600).contains(&frames), "movie.frames", frames, "from 2 to 600")?;
    let (width, height) = (m.width.unwrap_or(720), m.height.unwrap_or(240));
    require((120..=1920).contains(&width), "movie.width", width, "from 120 to 1920 pixels")?;
    require((80..=1080).contains(&height), "movie.height", height, "from 80 to 1080 pixels")?;
    Ok(MovieSpec {
        frames,
        width,
        height,
        side_by_side: m.side_by_side.unwrap_or(false),
        bond_strain: m.bond_strain.unwrap_or(false),
    })
}

/// Mass and stiffness of a lattice derived from the solid it stands for, and how.
#[derive(Default)]
struct Solid {
    mass: Option<f64>,
    k: Option<f64>,
    note: Option<String>,
}

/// For a lattice scene with `material.density` and/or `material.youngs_modulus`: the node mass
/// m = ρ L_x L_y d / (N_x N_y), so the lattice weighs what the block of size L_x × L_y × d
/// weighs, and the spring stiffness k = E d / (1 + r − r²/(1 + r)) with r = k_d/k, so the
/// lattice's continuum Young's modulus (C11 − C12²/C11)/d equals E.
fn derive_from_solid(
    kind: SceneKind,
    raw: &RawScene,
    material: &RawMaterial,
    spacing: f64,
    depth: Option<f64>,
) -> Result<Solid, Issue> {
    if material.density.is_none() && material.youngs_modulus.is_none() {
        return Ok(Solid::default());
    }
    let only_lattices = "only for lattice scenes (give mass and k directly)";
    require(kind == SceneKind::Lattice, "material.density", "(set)", only_lattices)?;
    let lattice = raw.lattice.clone().unwrap_or_default();
    // Checked first: the node count divides the block's mass.
    let (nx, ny) = lattice_size(&lattice)?;
    let depth = depth.unwrap_or(1.0);
    let mut solid = Solid::default();
    let mut notes = Vec::new();
    if let Some(density) = material.density {
        require(material.mass.is_none(), "material.mass", "(set)", "give either mass or density, not both")?;
        let density = positive(density, "material.density")?;
        let block = density * (nx - 1) as f64 * (ny - 1) as f64 * spacing * spacing * depth;
        solid.mass = Some(block / (nx * ny) as f64);
        notes.push(format!(
            "m = ρ L_x L_y d / (N_x N_y) with ρ = {density} kg/m³ (the lattice weighs what the block weighs)"
        ));
    }
    if let Some(modulus) = material.youngs_modulus {
        require(material.k.is_none(), "material.k", "(set)", "give either k or youngs_modulus, not both")?;
        require(lattice.k_diag.is_none(), "lattice.k_diag", "(set)", "with youngs_modulus give k_diag_ratio instead")?;
        let modulus = positive(modulus, "material.youngs_modulus")?;
        let r = match lattice.diagonals {
            Some(Diagonals::None) => 0.0,
            _ => lattice.k_diag_ratio.unwrap_or(DEFAULT_K_DIAG_RATIO),
        };
        solid.k = Some(modulus * depth / (1.0 + r - r * r / (1.0 + r)));
        notes.push(format!("k = E d / (1 + r − r²/(1 + r)) with E = {modulus} Pa, r = k_d/k = {r} (the lattice's continuum E is the solid's)"));
    }
    solid.note = Some(notes.join("; "));
    Ok(solid)
}

fn missing(path: &str, allowed: &str) -> Issue {
    Issue { path: path.into(), value: "(missing)".into(), allowed: allowed.into() }
}

fn geometry_spacing(geometry: &RawGeometry) -> f64 {
    geometry.spacing.unwrap_or(DEFAULT_SPACING)
}

fn resolve_material(material: &RawMaterial) -> Result<(f64, f64, LawSpec, bool), Issue> {
    let mass = positive(material.mass.unwrap_or(DEFAULT_MASS), "material.mass")?;
    let k = positive(material.k.unwrap_or(DEFAULT_STIFFNESS), "material.k")?;
    let law = match material.law.unwrap_or(LawName::Linear) {
        LawName::Linear => LawSpec::Linear,
        LawName::Power => {
            let beta = material.beta.unwrap_or(DEFAULT_BETA);
            require(beta.is_finite() && beta >= 1.0, "material.beta", beta, "must be ≥ 1 (1.5 is Hertz)")?;
            LawSpec::Power { beta }
        }
    };
    Ok((mass, k, law, material.contact.unwrap_or(false)))
}

/// (γ, the restitution it came from, γ_g).
fn resolve_damping(damping: &RawDamping, k: f64, mass: f64) -> Result<(f64, Option<f64>, f64), Issue> {
    let background = damping.background.unwrap_or(0.0);
    require(background.is_finite() && background >= 0.0, "damping.background", background, "must be ≥ 0 (N s/m)")?;
    let (gamma, target) = match (damping.restitution, damping.gamma) {
        (Some(r), Some(g)) => {
            return Err(Issue {
                path: "damping".into(),
                value: format!("restitution = {r}, gamma = {g}"),
                allowed: "give either restitution or gamma, not both".into(),
            });
        }
        (Some(r), None) => {
            require(r > 0.0 && r <= 1.0, "damping.restitution", r, "must be in (0, 1]")?;
            (theory::gamma_for_restitution(r, k, mass), Some(r))
        }
        (None, Some(g)) => {
            require(g.is_finite() && g >= 0.0, "damping.gamma", g, "must be ≥ 0 (N s/m)")?;
            (g, None)
        }
        (None, None) => (0.0, None),
    };
    Ok((gamma, target, background))
}

fn resolve_dt(time: &RawTime, t_c: f64) -> Result<f64, Issue> {
    if let Some(target) = time.dt_omega_max {
        require(
            time.dt.is_none() && time.dt_per_tc.is_none(),
            "time.dt_omega_max",
            target,
            "give one of dt, dt_per_tc and dt_omega_max",
        )?;
        require(target.is_finite() && target > 0.0, "time.dt_omega_max", target, "must be > 0 (dt = value / ω_max)")?;
        // Nominal, for the range checks of the duration and the reference run only: the plan
        // decides dt = dt_omega_max / ω_max once the scene is built (`crate::plan`).
        return Ok(t_c / DEFAULT_DT_PER_TC);
    }
    match (time.dt, time.dt_per_tc) {
        (Some(dt), None) => positive(dt, "time.dt"),
        (None, per_tc) => {
            let per_tc = per_tc.unwrap_or(DEFAULT_DT_PER_TC);
            require(
                per_tc.is_finite() && per_tc >= 1.0,
                "time.dt_per_tc",
                per_tc,
                "must be ≥ 1 (dt = t_c / dt_per_tc)",
            )?;
            Ok(t_c / per_tc)
        }
        (Some(dt), Some(per_tc)) => Err(Issue {
            path: "time".into(),
            value: format!("dt = {dt}, dt_per_tc = {per_tc}"),
            allowed: "give either dt or dt_per_tc, not both".into(),
        }),
    }
}

/// Rejects fields that belong to another kind of scene.
fn check_kind_fields(kind: SceneKind, raw: &RawScene) -> Result<(), Issue> {
    let only = |present: bool, path: &str, owner: &str| {
        require(!present, path, "(set)", &format!("only for {owner}; remove it from this {} scene", kind.name()))
    };
    let contact = raw.material.as_ref().and_then(|m| m.contact).unwrap_or(false);
    let is = |wanted: SceneKind| kind == wanted;
    only(raw.gap.is_some() && !(is(SceneKind::Pair) && contact), "gap", "pairs with material.contact: true")?;
    for (present, path) in
        [(raw.n.is_some(), "n"), (raw.node.is_some(), "node"), (raw.wall_distance.is_some(), "wall_distance")]
    {
        only(present && !is(SceneKind::Chain), path, "chain scenes")?;
    }
    only(raw.wave.is_some() && is(SceneKind::Pair), "wave", "chain and lattice scenes")?;
    only(raw.impulse.is_some() && !is(SceneKind::Lattice), "impulse", "lattice scenes")?;
    only(
        raw.probes.is_some() && !is(SceneKind::Lattice),
        "probes",
        "lattice scenes (a chain records every particle; its wave.receiver picks the timed one)",
    )?;
    if raw.impulse.is_some() {
        only(raw.load.is_some(), "load", "loaded lattices (an impulse lattice is kicked, not loaded)")?;
        only(raw.relax.is_some(), "relax", "loaded lattices (an impulse lattice runs for time.duration_tc)")?;
    }
    only(
        raw.wave.as_ref().is_some_and(|w| w.receiver.is_some()) && is(SceneKind::Lattice),
        "wave.receiver",
        "chains (a lattice's receiver is its bottom row)",
    )?;
    only(raw.wave.is_some() && is(SceneKind::Lattice) && raw.impulse.is_none(), "wave", "chains and impulse lattices")?;
    for (present, path) in [
        (raw.lattice.is_some(), "lattice"),
        (raw.supports.is_some(), "supports"),
        (raw.load.is_some(), "load"),
        (raw.seed.is_some(), "seed"),
    ] {
        only(present && !is(SceneKind::Lattice), path, "lattice scenes")?;
    }
    only(raw.relax.is_some() && is(SceneKind::Pair), "relax", "lattices and chains between moved walls")?;
    only(raw.relax.is_some() && raw.wave.is_some(), "wave", "chains that are hit, not relaxed")?;
    only(raw.v0.is_some() && is(SceneKind::Lattice), "v0", "pair and chain scenes (lattices are loaded, not kicked)")
}

/// The lattice of a lattice scene.
fn resolve_lattice(raw: &RawScene, k: f64, depth: Option<f64>) -> Result<LatticeSpec, Issue> {
    let lattice = raw.lattice.clone().unwrap_or_default();
    let (nx, ny) = lattice_size(&lattice)?;
    let (diagonals, k_diag, k_x, k_y) = lattice_springs(&lattice, k)?;
    let cut_fraction = lattice.cut_fraction.unwrap_or(0.0);
    require((0.0..1.0).contains(&cut_fraction), "lattice.cut_fraction", cut_fraction, "must be in [0, 1)")?;
    let stiffness_spread = lattice.stiffness_spread.unwrap_or(0.0);
    require(
        (0.0..1.0).contains(&stiffness_spread),
        "lattice.stiffness_spread",
        stiffness_spread,
        "must be in [0, 1) (every stiffness times 1 + w·U[−1, 1])",
    )?;
    let supports = raw.supports.unwrap_or(Supports::Coursework);
    require(
        supports != Supports::PeriodicX || nx >= 3,
        "lattice.nx",
        nx,
        "must be ≥ 3 with supports: periodic-x (two nodes would be bonded twice)",
    )?;
    let load = resolve_load(raw)?;
    let impulse = raw.impulse.as_ref().map(|i| resolve_impulse(i, nx, ny)).transpose()?;
    let probes = resolve_probes(raw.probes.as_ref(), nx, ny)?;
    let upright = Upright { nx, ny, k_x, k_y, diagonals, load_case: raw.load.as_ref().and_then(|l| l.case) };
    let rotated = upright.load_case == Some(LoadCase::TensileX);
    let Upright { nx, ny, k_x, k_y, diagonals, load_case } =
        if rotated { turned(upright, &probes, supports)? } else { upright };
    Ok(LatticeSpec {
        nx,
        ny,
        k_diag,
        diagonals: if k_diag == 0.0 { Diagonals::None } else { diagonals },
        k_x,
        k_y,
        rotated,
        cut_fraction,
        stiffness_spread,
        seed: raw.seed.unwrap_or(1),
        depth: positive(depth.unwrap_or(1.0), "geometry.depth")?,
        supports,
        load_case: load_case.unwrap_or(LoadCase::Tensile),
        load_per_node: load.per_node,
        load_ramp_tc: load.ramp_tc,
        control: load.control,
        drive_strain: load.strain,
        drive_tc: load.drive_tc,
        derived_from: None,
        impulse,
        probes,
    })
}

/// The diagonals and the stiffnesses (k_d, k_x, k_y) (N/m) of a lattice's springs, from k and
/// the ratios (or k_d) it gives.
fn lattice_springs(lattice: &RawLattice, k: f64) -> Result<(Diagonals, f64, f64, f64), Issue> {
    // `diagonals: none` wins over a k_diag or k_diag_ratio set elsewhere, so a grid can switch
    // the diagonals off without touching their stiffness.
    let diagonals = lattice.diagonals.unwrap_or(Diagonals::Both);
    let k_diag = match (diagonals, lattice.k_diag, lattice.k_diag_ratio) {
        (Diagonals::None, _, _) => 0.0,
        (_, Some(_), Some(_)) => {
            return Err(Issue {
                path: "lattice".into(),
                value: "k_diag and k_diag_ratio".into(),
                allowed: "give either k_diag or k_diag_ratio, not both".into(),
            });
        }
        // Zero is allowed: the same lattice as `diagonals: none`, so a grid can start a sweep there.
        (_, Some(k_diag), None) => non_negative(k_diag, "lattice.k_diag")?,
        (_, None, ratio) => k * non_negative(ratio.unwrap_or(DEFAULT_K_DIAG_RATIO), "lattice.k_diag_ratio")?,
    };
    let ratio = |value: Option<f64>, path: &str| positive(value.unwrap_or(1.0), path).map(|r| r * k);
    let (k_x, k_y) = (ratio(lattice.k_x_ratio, "lattice.k_x_ratio")?, ratio(lattice.k_y_ratio, "lattice.k_y_ratio")?);
    Ok((diagonals, k_diag, k_x, k_y))
}

/// How a lattice is loaded: a force per top-row node (ramped over `ramp_tc` t_c), or its top
/// row driven to `strain` in `drive_tc` t_c.
struct Load {
    per_node: f64,
    ramp_tc: f64,
    control: Control,
    strain: f64,
    drive_tc: f64,
}

/// The `load:` section, each field checked against the control it belongs to.
fn resolve_load(raw: &RawScene) -> Result<Load, Issue> {
    let load = raw.load.clone().unwrap_or_default();
    let per_node = positive(load.per_node.unwrap_or(DEFAULT_LOAD_PER_NODE), "load.per_node")?;
    let ramp_tc = load.ramp_tc.unwrap_or(0.0);
    require(ramp_tc.is_finite() && ramp_tc >= 0.0, "load.ramp_tc", ramp_tc, "must be ≥ 0 (t_c)")?;
    let control = load.control.unwrap_or(Control::Force);
    let strain = load.strain.unwrap_or(1e-4);
    let drive_tc = load.drive_tc.unwrap_or(100.0);
    if control == Control::Velocity {
        let position_verlet = raw.time.as_ref().and_then(|t| t.integrator).unwrap_or(IntegratorKind::PositionVerlet)
            == IntegratorKind::PositionVerlet;
        require(
            !position_verlet,
            "time.integrator",
            "position-verlet",
            "any integrator but position-verlet under velocity control (its position history cannot stop the drive)",
        )?;
        require(
            load.per_node.is_none() && load.ramp_tc.is_none(),
            "load",
            "per_node/ramp_tc",
            "are for control: force",
        )?;
        require(
            strain.is_finite() && strain != 0.0 && strain.abs() < 0.5,
            "load.strain",
            strain,
            "must be non-zero, |strain| < 0.5",
        )?;
        positive(drive_tc, "load.drive_tc")?;
    } else {
        require(
            load.strain.is_none() && load.drive_tc.is_none(),
            "load",
            "strain/drive_tc",
            "are for control: velocity",
        )?;
    }
    Ok(Load { per_node, ramp_tc, control, strain, drive_tc })
}

/// The impulse of a wave lattice: the node it starts at and its kick or top-row force step.
fn resolve_impulse(i: &RawImpulse, nx: usize, ny: usize) -> Result<ImpulseSpec, Issue> {
    let node = match i.node.as_deref().unwrap_or("top-right") {
        "top-right" => ny * nx - 1,
        "top-left" => (ny - 1) * nx,
        "top-centre" | "top-center" => (ny - 1) * nx + nx / 2,
        other => {
            return Err(Issue {
                path: "impulse.node".into(),
                value: other.into(),
                allowed: "top-right, top-left or top-centre".into(),
            });
        }
    };
    let (path, [a, b]) = match (i.velocity, i.force) {
        (Some(v), None) => ("impulse.velocity", v),
        (None, Some(f)) => ("impulse.force", f),
        _ => {
            return Err(Issue {
                path: "impulse".into(),
                value: "velocity and force".into(),
                allowed: "one of velocity: [vx, vy] (m/s, a kick) or force: [fx, fy] (N, a step on the top row)".into(),
            });
        }
    };
    require(
        a.is_finite() && b.is_finite() && (a != 0.0 || b != 0.0),
        path,
        format!("[{a}, {b}]"),
        "two finite numbers, not both zero",
    )?;
    Ok(match i.force {
        Some(force) => ImpulseSpec { node, vx: 0.0, vy: 0.0, top_row_force: Some(force) },
        None => ImpulseSpec { node, vx: a, vy: b, top_row_force: None },
    })
}

/// A lattice's size, spring stiffnesses, diagonals and load case as the campaign gives them.
struct Upright {
    nx: usize,
    ny: usize,
    k_x: f64,
    k_y: f64,
    diagonals: Diagonals,
    load_case: Option<LoadCase>,
}

/// The lattice of `load.case: tensile-x`, simulated turned by +90° and pulled along y: x → y,
/// y → −x; the rising diagonal (1, 1) becomes (−1, 1), a falling one, and the falling (−1, 1)
/// becomes (−1, −1), a rising one. Not probed, and on supports that turn with it.
fn turned(upright: Upright, probes: &[ProbeLine], supports: Supports) -> Result<Upright, Issue> {
    require(
        probes.is_empty(),
        "probes",
        "(set)",
        "not with load.case: tensile-x (that lattice is simulated turned by 90°); probe the same lattice in a \
         load.case: tensile scene",
    )?;
    require(
        matches!(supports, Supports::Coursework | Supports::ClampedBottom),
        "supports",
        supports.name(),
        "coursework or clamped-bottom with load.case: tensile-x (the supports turn with the lattice)",
    )?;
    let Upright { nx, ny, k_x, k_y, diagonals, .. } = upright;
    let diagonals = match diagonals {
        Diagonals::Rising => Diagonals::Falling,
        Diagonals::Falling => Diagonals::Rising,
        other => other,
    };
    Ok(Upright { nx: ny, ny: nx, k_x: k_y, k_y: k_x, diagonals, load_case: Some(LoadCase::Tensile) })
}

/// Nodes per row and rows (nx, ny) of a lattice, each 2..=2000.
fn lattice_size(lattice: &RawLattice) -> Result<(usize, usize), Issue> {
    let size = |value: Option<usize>, path: &str| {
        let n = value.ok_or_else(|| missing(path, "the number of nodes, 2..=2000"))?;
        require((2..=2000).contains(&n), path, n, "must be in 2..=2000")?;
        Ok::<usize, Issue>(n)
    };
    if lattice.size.is_some() && (lattice.nx.is_some() || lattice.ny.is_some()) {
        return Err(Issue {
            path: "lattice.size".into(),
            value: format!("{:?}", lattice.size.unwrap_or_default()),
            allowed: "give either size (an N × N lattice) or nx and ny, not both".into(),
        });
    }
    Ok((size(lattice.nx.or(lattice.size), "lattice.nx")?, size(lattice.ny.or(lattice.size), "lattice.ny")?))
}

/// The probed rows and columns of an `nx` × `ny` lattice, rows first, each once.
fn resolve_probes(raw: Option<&RawProbes>, nx: usize, ny: usize) -> Result<Vec<ProbeLine>, Issue> {
    let Some(raw) = raw else { return Ok(Vec::new()) };
    let line = |value: &Value, path: &str, count: usize, ends: [&str; 2]| -> Result<usize, Issue> {
        let allowed = || format!("{}, centre, {} or a number 0..={}", ends[0], ends[1], count - 1);
        match value {
            Value::String(s) if s == ends[0] => Ok(0),
            Value::String(s) if s == ends[1] => Ok(count - 1),
            Value::String(s) if s == "centre" || s == "center" => Ok(count / 2),
            Value::Number(number) => match number.as_u64() {
                Some(i) if i < count as u64 => Ok(i as usize),
                _ => Err(Issue { path: path.into(), value: number.to_string(), allowed: allowed() }),
            },
            other => Err(Issue { path: path.into(), value: other.to_string(), allowed: allowed() }),
        }
    };
    let mut probes = Vec::new();
    for (i, value) in raw.rows.iter().flatten().enumerate() {
        probes.push(ProbeLine::Row(line(value, &format!("probes.rows[{i}]"), ny, ["bottom", "top"])?));
    }
    for (i, value) in raw.columns.iter().flatten().enumerate() {
        probes.push(ProbeLine::Column(line(value, &format!("probes.columns[{i}]"), nx, ["left", "right"])?));
    }
    let mut seen = Vec::new();
    probes.retain(|p| {
        if seen.contains(p) {
            false
        } else {
            seen.push(*p);
            true
        }
    });
    require(!probes.is_empty(), "probes", "(empty)", "at least one row or column (rows: [...], columns: [...])")?;
    Ok(probes)
}

/// When a relaxation counts as finished, and its tangent step.
fn resolve_relax(raw: &RawScene, control: Control) -> Result<RelaxSpec, Issue> {
    let relax = raw.relax.clone().unwrap_or_default();
    let kinetic_ratio = relax.kinetic_ratio.unwrap_or(DEFAULT_KINETIC_RATIO);
    require(kinetic_ratio > 0.0 && kinetic_ratio < 1.0, "relax.kinetic_ratio", kinetic_ratio, "must be in (0, 1)")?;
    if let Some(fraction) = relax.residual_force {
        require(
            fraction > 0.0 && fraction < 1.0,
            "relax.residual_force",
            fraction,
            "must be in (0, 1) (a fraction of the load per node, or of a chain's wall force)",
        )?;
    }
    if let Some(step) = relax.tangent_step {
        require(step > 0.0 && step <= 0.1, "relax.tangent_step", step, "must be in (0, 0.1] (a fraction of the load)")?;
        require(control == Control::Force, "relax.tangent_step", step, "is for control: force")?;
    }
    Ok(RelaxSpec { kinetic_ratio, residual_force: relax.residual_force, tangent_step: relax.tangent_step })
}

/// Number of particles, excited node (1..n), wall distance and timed wave of a chain scene
/// (its relaxation still unset).
fn resolve_chain(raw: &RawScene, spacing: f64) -> Result<ChainRun, Issue> {
    let n = raw.n.ok_or_else(|| missing("n", "the number of moving particles, 1..=100000"))?;
    require((1..=100_000).contains(&n), "n", n, "must be in 1..=100000")?;
    let node = particle(raw.node.as_ref(), n, n.div_ceil(2), "node")?;
    let walls = positive(raw.wall_distance.unwrap_or((n + 1) as f64 * spacing), "wall_distance")?;
    let wave = match &raw.wave {
        None => None,
        Some(w) => {
            let far_end = if node <= n / 2 { n } else { 1 };
            let receiver = particle(w.receiver.as_ref(), n, far_end, "wave.receiver")?;
            require(receiver != node, "wave.receiver", receiver, "a particle other than the excited one")?;
            let springs = receiver.abs_diff(node);
            Some(WaveSpec {
                source: node,
                receivers: vec![receiver],
                distance: springs as f64 * spacing,
                springs,
                threshold: wave_threshold(w)?,
            })
        }
    };
    Ok(ChainRun { n, node, wall_distance: walls, relax: None, wave })
}

fn wave_threshold(w: &RawWave) -> Result<f64, Issue> {
    let threshold = w.threshold.unwrap_or(DEFAULT_WAVE_THRESHOLD);
    require(threshold > 0.0 && threshold < 1.0, "wave.threshold", threshold, "must be in (0, 1)")?;
    Ok(threshold)
}

/// The wave of an impulse lattice: from the kicked node down to the bottom row.
fn lattice_wave(l: &LatticeSpec, w: &RawWave, spacing: f64) -> Result<Option<WaveSpec>, Issue> {
    let Some(impulse) = l.impulse else { return Ok(None) };
    let row = impulse.node / l.nx;
    Ok(Some(WaveSpec {
        source: impulse.node,
        receivers: (0..l.nx).collect(),
        distance: row as f64 * spacing,
        springs: row,
        threshold: wave_threshold(w)?,
    }))
}

/// A chain particle named `first`, `last`, `centre` or by its number 1..=n; `default` when absent.
fn particle(value: Option<&Value>, n: usize, default: usize, path: &str) -> Result<usize, Issue> {
    let allowed = || format!("centre, first, last or a particle number 1..={n}");
    match value {
        None => Ok(default),
        Some(Value::String(s)) if s == "centre" || s == "center" => Ok(n.div_ceil(2)),
        Some(Value::String(s)) if s == "first" => Ok(1),
        Some(Value::String(s)) if s == "last" => Ok(n),
        Some(Value::Number(number)) => match number.as_u64() {
            Some(i) if (1..=n as u64).contains(&i) => Ok(i as usize),
            _ => Err(Issue { path: path.into(), value: number.to_string(), allowed: allowed() }),
        },
        Some(other) => Err(Issue { path: path.into(), value: other.to_string(), allowed: allowed() }),
    }
}
