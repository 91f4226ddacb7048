//! What chains and lattices share (when a relaxation stops, a timed wave) and what every
//! kind's resolution may use: the speed of a kick, bonded springs, the deformation a run
//! reaches.

use serde::{Deserialize, Serialize};

use super::issue::{Issue, Num, missing, positive, require};
use super::raw::{Background, Control, RawDamping, RawRelax, RawScene, RawWave};
use crate::model::LawName;
use crate::sim::{PreconditionerKind, RelaxMethod};

/// E_kin/E_pot below which a relaxation is finished, unless `relax.kinetic_ratio` says.
const DEFAULT_KINETIC_RATIO: f64 = 1e-8;

/// Relative error of the moduli a minimiser (`fire`, `cg`) stops at, unless `relax.tolerance`
/// says.
pub const DEFAULT_TOLERANCE: f64 = 1e-4;

/// Threshold of the wave-arrival criteria, relative to the source's peak.
const DEFAULT_WAVE_THRESHOLD: f64 = 0.01;

/// When a relaxation is finished, and the small extra step that measures tangent moduli.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RelaxSpec {
    /// Relaxed when E_kin/E_pot stays below this ...
    pub kinetic_ratio: f64,
    /// ... or, when given, when the largest static force stays below this fraction of the
    /// load per node (lattice) or of the equilibrium wall force (chain).
    pub residual_force: Option<f64>,
    /// After relaxing, raise the load (a chain's wall displacement) by this fraction, relax
    /// again and measure tangent moduli (stiffness) from the increments.
    pub tangent_step: Option<f64>,
    /// Lattice: how it comes to rest (damped MD, FIRE, CG). Stored only when not `damped`, so
    /// the run ids of earlier runs stay.
    #[serde(default, skip_serializing_if = "is_damped")]
    pub method: RelaxMethod,
    /// Lattice: the relative error of the moduli the displacement bound stops at, when in force
    /// (always for a minimiser).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// Lattice: background damping critical for the slowest mode, γ_g = 2 m ω_min
    /// (`damping.background: critical`).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub critical_background: bool,
    /// Lattice, FIRE: the metric it moves in. Stored only when not `none`, so the run ids of
    /// earlier runs stay.
    #[serde(default, skip_serializing_if = "is_unpreconditioned")]
    pub preconditioner: PreconditionerKind,
}

fn is_unpreconditioned(kind: &PreconditionerKind) -> bool {
    *kind == PreconditionerKind::None
}

fn is_damped(method: &RelaxMethod) -> bool {
    *method == RelaxMethod::Damped
}

/// A timed wave: from the excited particle to the receivers (a chain's particle, a lattice's
/// bottom row).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WaveSpec {
    /// Excited particle.
    pub source: usize,
    /// Receiving particles: the wave arrives when the first of them moves.
    pub receivers: Vec<usize>,
    /// Distance from the source to the receivers along the wave (m).
    pub distance: f64,
    /// Springs along that distance, N_s (for the coursework's estimate t_s = N_s t_c).
    pub springs: usize,
    /// Threshold of the threshold criteria, relative to the source's peak.
    pub threshold: f64,
}

/// When a relaxation counts as finished, and its tangent step; `load_ramp_tc` is a lattice's
/// load ramp (t_c), `None` for a chain, which has neither a static answer for the displacement
/// bound nor a minimiser.
pub(super) fn resolve_relax(raw: &RawScene, control: Control, load_ramp_tc: Option<f64>) -> Result<RelaxSpec, Issue> {
    let relax = raw.relax.clone().unwrap_or_default();
    let kinetic_ratio = relax.kinetic_ratio.unwrap_or(DEFAULT_KINETIC_RATIO);
    require(kinetic_ratio > 0.0 && kinetic_ratio < 1.0, "relax.kinetic_ratio", kinetic_ratio, "must be in (0, 1)")?;
    check_residual_and_step(&relax, control)?;
    let damping = raw.damping.clone().unwrap_or_default();
    let critical_background = matches!(damping.background, Some(Background::Critical(_)));
    let method = relax.method.unwrap_or_default();
    if load_ramp_tc.is_none() {
        check_chain_relaxation(method, relax.tolerance, critical_background)?;
    }
    if let Some(tolerance) = relax.tolerance {
        check_tolerance(tolerance, control, method)?;
    }
    if method != RelaxMethod::Damped {
        check_untimed(method, control, load_ramp_tc.unwrap_or_default(), &damping)?;
    }
    let preconditioner = relax.preconditioner.unwrap_or_default();
    let law = raw.material.as_ref().and_then(|m| m.law).unwrap_or(LawName::Linear);
    check_preconditioner(preconditioner, (method, control), law)?;
    // A minimiser stops only on the displacement bound (or the residual force): it needs a
    // tolerance even where none is given.
    let tolerance = relax.tolerance.or(method.is_minimiser().then_some(DEFAULT_TOLERANCE));
    Ok(RelaxSpec {
        kinetic_ratio,
        residual_force: relax.residual_force,
        tangent_step: relax.tangent_step,
        method,
        tolerance,
        critical_background,
        preconditioner,
    })
}

/// `relax.preconditioner`: FIRE's, on a network with a stiffness matrix held as the loads
/// leave it (force control: under velocity control the drive moves the top row, which the
/// matrix holds), of linear springs: a power law has no stiffness at δ = 0, so far from rest
/// its forces have little to do with the tangent at rest (a Hertz kagome pulled along its rows,
/// whose softest tangent stiffness is 1e-6 of k, ran away in that metric).
fn check_preconditioner(
    kind: PreconditionerKind,
    (method, control): (RelaxMethod, Control),
    law: LawName,
) -> Result<(), Issue> {
    if kind == PreconditionerKind::None {
        return Ok(());
    }
    let field = "relax.preconditioner";
    require(method == RelaxMethod::Fire, field, kind.name(), "is for relax.method: fire")?;
    require(control == Control::Force, field, kind.name(), "is for control: force (a drive moves the held top row)")?;
    require(
        law == LawName::Linear,
        field,
        kind.name(),
        "is for material.law: linear (a power law has no stiffness at rest)",
    )
}

/// `relax.residual_force`, a fraction, and `relax.tangent_step`, a small one under force
/// control.
fn check_residual_and_step(relax: &RawRelax, control: Control) -> Result<(), Issue> {
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
    Ok(())
}

/// A chain relaxes by damped MD only, judged without a tolerance or critical background
/// damping: all three need the static answer a chain does not have.
fn check_chain_relaxation(method: RelaxMethod, tolerance: Option<f64>, critical_background: bool) -> Result<(), Issue> {
    let for_lattices = "is for lattices (a chain has no static answer to bound its error by)";
    require(method == RelaxMethod::Damped, "relax.method", method.name(), for_lattices)?;
    require(tolerance.is_none(), "relax.tolerance", tolerance.unwrap_or_default(), for_lattices)?;
    require(!critical_background, "damping.background", "critical", for_lattices)
}

/// `relax.tolerance`: a relative error of the moduli, under force control, for a method that
/// stops short of the static answer (not `static`, which is that answer).
fn check_tolerance(tolerance: f64, control: Control, method: RelaxMethod) -> Result<(), Issue> {
    require(
        tolerance > 0.0 && tolerance <= 0.1,
        "relax.tolerance",
        tolerance,
        "must be in (0, 0.1] (the relative error of the moduli)",
    )?;
    require(
        control == Control::Force,
        "relax.tolerance",
        tolerance,
        "is for control: force (under control: velocity the modulus comes from the drive's force, whose error \
         the displacement bound does not cover; give relax.residual_force)",
    )?;
    let exact = "has no tolerance: the static solution is solved to round-off (Newton, ‖R‖ ≤ 1e-12 ‖f‖)";
    let bounded = methods_in_words(|m| m != RelaxMethod::Static);
    require(
        method != RelaxMethod::Static,
        "relax.tolerance",
        tolerance,
        &format!("is for {bounded}; relax.method: static {exact}"),
    )
}

/// A method with no time (a minimiser, or the static answer) has no load ramp, drive or
/// damping to follow in time: force control, the whole load at once, no dashpots.
fn check_untimed(method: RelaxMethod, control: Control, ramp_tc: f64, damping: &RawDamping) -> Result<(), Issue> {
    let name = method.name();
    let untimed = format!("{} have no time: use relax.method: damped", methods_in_words(|m| m != RelaxMethod::Damped));
    require(control == Control::Force, "relax.method", name, &format!("needs control: force; {untimed}"))?;
    require(
        ramp_tc == 0.0,
        "relax.method",
        name,
        &format!("needs no load.ramp_tc (it is {}); {untimed}", Num(ramp_tc)),
    )?;
    let damped = [
        ("damping.restitution", damping.restitution.is_some()),
        ("damping.gamma", damping.gamma.is_some()),
        ("damping.background", damping.background.is_some()),
    ];
    match damped.iter().find(|(_, set)| *set) {
        Some((field, _)) => {
            require(false, "relax.method", name, &format!("has no damping ({field} is set); {untimed}"))
        }
        None => Ok(()),
    }
}

/// The YAML names of the relaxation methods `which` picks, in the order of
/// [`RelaxMethod::ALL`], as words ("fire, cg and static"), so that a message names a new
/// method without being edited.
fn methods_in_words(which: impl Fn(RelaxMethod) -> bool) -> String {
    let names: Vec<&str> = RelaxMethod::ALL.into_iter().filter(|m| which(*m)).map(RelaxMethod::name).collect();
    match names.split_last() {
        Some((last, [])) => (*last).to_string(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// The threshold of a timed wave's arrival criteria.
pub(super) fn wave_threshold(w: &RawWave) -> Result<f64, Issue> {
    let threshold = w.threshold.unwrap_or(DEFAULT_WAVE_THRESHOLD);
    require(threshold > 0.0 && threshold < 1.0, "wave.threshold", threshold, "must be in (0, 1)")?;
    Ok(threshold)
}

/// The initial speed v0 (m/s) of a kicked scene: required, > 0.
pub(super) fn kick_speed(raw: &RawScene) -> Result<f64, Issue> {
    positive(raw.v0.ok_or_else(|| missing("v0", "the initial speed (m/s), > 0"))?, "v0")
}

/// Lattices and relaxing chains are bonded: no contact springs.
pub(super) fn bonded(contact: bool) -> Result<(), Issue> {
    require(!contact, "material.contact", contact, "lattices and relaxing chains have bonded springs: false")
}

/// The deformation a run is expected to reach, from which a power-law spring's reference
/// extension follows (`reference_extension`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Deformation {
    /// A collision or kick at this speed (m/s): the two-body overlap.
    Collision(f64),
    /// A spring carrying this force (N).
    Carrying(f64),
    /// This extension itself (m).
    Extension(f64),
    /// A kick on springs held stretched or squeezed by moved walls: the two-body overlap on top
    /// of the pre-stress.
    PreStressed {
        /// The springs' extension between the walls, ΔW/(n + 1) (m).
        extension: f64,
        /// The kick (m/s).
        speed: f64,
    },
}
