//! From a merged raw scene to a [`RunSpec`]: defaults filled in, ranges checked, γ, t_c and dt
//! derived. Every rejection names the field path, the value and what is allowed.

use serde_json::Value;
use std::collections::BTreeMap;

use super::issue::{Issue, Num, positive, require};
use super::kind::{self, KindSpec};
use super::name::{MAX_NAME_LEN, is_safe_name};
use super::raw::{Background, RawDamping, RawGeometry, RawMaterial, RawMovie, RawScene, RawTime, SceneKind};
use super::run_spec::{MovieSpec, RunSpec, reference_extension};
use crate::model::{LawName, LawSpec};
use crate::sim::IntegratorKind;
use crate::theory;

/// Scene defaults when neither the scene nor `defaults` says otherwise.
const DEFAULT_MASS: f64 = 1.0;
const DEFAULT_STIFFNESS: f64 = 1.0;
const DEFAULT_SPACING: f64 = 1.0;
const DEFAULT_BETA: f64 = 1.5;
/// dt = t_c / this unless the campaign sets dt another way.
pub const DEFAULT_DT_PER_TC: f64 = 50.0;
const DEFAULT_SAMPLES: u64 = 400;
/// Longest run of a relaxing scene (t_c), unless `relax.max_tc` says.
const DEFAULT_MAX_TC: f64 = 5000.0;

/// Resolves one scene of campaign `campaign` with grid values `varied` already applied.
pub fn resolve(campaign: &str, raw: &RawScene, varied: BTreeMap<String, Value>) -> Result<RunSpec, Issue> {
    let name = raw.name.clone().unwrap_or_default();
    require(
        is_safe_name(&name),
        "name",
        format!("{name:?}"),
        &format!("1 to {MAX_NAME_LEN} letters, digits, '-' and '_' (it names files: plots/<name>-....svg)"),
    )?;
    let kind = raw.kind.ok_or_else(|| Issue {
        path: "kind".into(),
        value: "(missing)".into(),
        allowed: format!("one of {}", SceneKind::ALL.map(SceneKind::name).join(", ")),
    })?;
    let mut spec = resolve_body(campaign, name, kind, raw, varied)?;
    let time = raw.time.clone().unwrap_or_default();
    let (gamma, restitution_target, gamma_background, t_c) = resolve_contact_time(&spec, raw)?;
    let integrator = spec.integrator;
    let critical = spec.relax().is_some_and(|r| r.critical_background);
    require(
        critical || !matches!(raw.damping.as_ref().and_then(|d| d.background), Some(Background::Critical(_))),
        "damping.background",
        "critical",
        "is for loaded lattices, relaxing (`critical` is 2 m ω_min of their slowest mode); give a value (N s/m)",
    )?;
    require(
        integrator.allows_damping() || (gamma == 0.0 && gamma_background == 0.0 && !critical),
        "time.integrator",
        integrator.name(),
        "an integrator that allows damping (all but forest-ruth, whose backward sub-step would run the dashpots \
         backwards), or no damping",
    )?;
    let dt = resolve_dt(&time, t_c)?;
    let (spacing, contact) = (spec.spacing, spec.contact);
    spec.scene_kind.resolve_before_length(raw, spacing, contact)?;
    let (duration, steps, samples) = resolve_length(&spec, raw, t_c, dt)?;
    spec.scene_kind.resolve_after_length(raw, spacing)?;
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
    kind::check_fields(kind, raw)?;
    // A packing's springs are contacts whatever the material says (`check_fields` refuses false).
    let contact = contact || kind == SceneKind::Packing;
    let v0 = kind::resolve_v0(kind, raw, contact)?;
    let scene_kind = KindSpec::resolve(kind, raw, k, spacing, geometry.depth, derived_from)?;
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
        series: raw.output.as_ref().and_then(|o| o.series).unwrap_or_default(),
    };
    spec.scene_kind.check(spacing, v0)?;
    Ok(spec)
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
/// the solid a lattice stands for (with the note of how, see [`kind::solid`]).
fn resolve_springs(kind: SceneKind, raw: &RawScene, spacing: f64, depth: Option<f64>) -> Result<Springs, Issue> {
    let material = raw.material.clone().unwrap_or_default();
    let solid = kind::solid(kind, raw, &material, spacing, depth)?;
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
    let collision = spec.scene_kind.is_collision();
    let t_c = match law {
        LawSpec::Power { beta } if collision => theory::pair_omega(stiffness_for_damping, mass, gamma)
            .map(|_| theory::power_law_contact_duration(k, beta, mass, v0)),
        _ => theory::linear_contact_duration(stiffness_for_damping, mass, gamma),
    }
    .map_err(|e| Issue {
        path: "damping.gamma".into(),
        value: Num(gamma).to_string(),
        allowed: format!(
            "must be below the critical value √(2km) = {} N s/m (overdamped: no contact duration)",
            Num(e.critical)
        ),
    })?;
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
fn resolve_length(spec: &RunSpec, raw: &RawScene, t_c: f64, dt: f64) -> Result<(f64, u64, u64), Issue> {
    let time = raw.time.clone().unwrap_or_default();
    let default_duration_tc = spec
        .scene_kind
        .default_duration_tc(spec.v0, t_c)
        .unwrap_or_else(|| raw.relax.as_ref().and_then(|r| r.max_tc).unwrap_or(DEFAULT_MAX_TC));
    let duration_path = if spec.relax().is_some() { "relax.max_tc" } else { "time.duration_tc" };
    // A relaxing scene's length is its budget, relax.max_tc: a duration beside it would replace
    // that budget unseen.
    require(
        spec.relax().is_none() || time.duration_tc.is_none(),
        "time.duration_tc",
        "(set)",
        "not for relaxing scenes (loaded lattices, chains between moved walls, packings): they run until at rest, \
         up to relax.max_tc (in t_c); set that instead",
    )?;
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
    // `critical` is set by the lattice's study from its stiffness matrix (see `RelaxSpec`).
    let background = match damping.background {
        Some(Background::Value(value)) => value,
        Some(Background::Critical(_)) | None => 0.0,
    };
    require(background.is_finite() && background >= 0.0, "damping.background", background, "must be ≥ 0 (N s/m)")?;
    let (gamma, target) = match (damping.restitution, damping.gamma) {
        (Some(r), Some(g)) => {
            return Err(Issue {
                path: "damping".into(),
                value: format!("restitution = {}, gamma = {}", Num(r), Num(g)),
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
            value: format!("dt = {}, dt_per_tc = {}", Num(dt), Num(per_tc)),
            allowed: "give either dt or dt_per_tc, not both".into(),
        }),
    }
}
