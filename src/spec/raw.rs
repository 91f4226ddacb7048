//! The campaign file as written: serde structs that mirror the YAML one to one. Every field is
//! optional here, because a scene inherits what it does not say from `defaults`; the
//! resolver (`resolve.rs`) decides what is required and what is allowed.

use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::collections::BTreeMap;

use crate::model::{LatticeType, LawName};
use crate::sim::IntegratorKind;

/// A parameter grid: dotted parameter path → the values it takes.
pub type Grid = BTreeMap<String, Vec<Value>>;

/// The whole campaign file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCampaign {
    /// Format version; must be 1.
    pub version: u32,
    /// Campaign name: output goes to `reports/<name>/`.
    pub name: String,
    /// One-line title for the report.
    #[serde(default)]
    pub title: Option<String>,
    /// Free text shown at the top of the report.
    #[serde(default)]
    pub description: Option<String>,
    /// Values every scene inherits unless it sets them itself.
    #[serde(default)]
    pub defaults: RawScene,
    /// The scenes.
    pub scenes: Vec<RawScene>,
    /// Cartesian grid applied to every scene.
    #[serde(default)]
    pub grid: Grid,
    /// Accuracy the work–precision report recommends a time step for (relative error;
    /// default 1e-3).
    #[serde(default)]
    pub target_error: Option<f64>,
    /// What one run may use before it is stopped with `status = budget`.
    #[serde(default)]
    pub budget: Option<RawBudget>,
}

/// `budget:` section of a campaign.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBudget {
    /// Wall-clock seconds one run may take (default 3600).
    pub seconds_per_run: Option<f64>,
    /// Memory one run may hold, in MB (10⁶ bytes), by the estimate made before it starts
    /// (default 4000).
    pub memory_per_run_mb: Option<f64>,
}

/// Kind of scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SceneKind {
    /// Two particles: a collision through a contact spring, or a bonded pair.
    Pair,
    /// N particles in a row between two fixed walls.
    Chain,
    /// An nx × ny square lattice on supports, loaded on its top row and relaxed.
    Lattice,
    /// Bidisperse discs in a periodic square box, relaxed to an energy minimum (jammed or not).
    Packing,
}

impl SceneKind {
    /// Every kind, in the order error messages list them.
    pub const ALL: [SceneKind; 4] = [SceneKind::Pair, SceneKind::Chain, SceneKind::Lattice, SceneKind::Packing];

    /// The name used in files and tables.
    pub fn name(self) -> &'static str {
        match self {
            SceneKind::Pair => "pair",
            SceneKind::Chain => "chain",
            SceneKind::Lattice => "lattice",
            SceneKind::Packing => "packing",
        }
    }
}

/// One scene as written (also the shape of `defaults`).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    /// Scene name (unique in the campaign).
    pub name: Option<String>,
    /// `pair`, `chain`, `lattice` or `packing`.
    pub kind: Option<SceneKind>,
    /// Masses and springs.
    pub material: Option<RawMaterial>,
    /// Bond and background damping.
    pub damping: Option<RawDamping>,
    /// Integrator, time step and duration.
    pub time: Option<RawTime>,
    /// Lengths.
    pub geometry: Option<RawGeometry>,
    /// Pair: relative approach speed; chain: speed given to the excited particle (m/s).
    pub v0: Option<f64>,
    /// Pair with a contact spring: initial gap between the surfaces (m).
    pub gap: Option<f64>,
    /// Chain: number of moving particles.
    pub n: Option<usize>,
    /// Chain: which particle gets v0: `centre`, `first`, `last` or a number 1..n.
    pub node: Option<Value>,
    /// Chain: distance between the two walls (m); default (n+1) · spacing.
    pub wall_distance: Option<f64>,
    /// Lattice: size and diagonal springs.
    pub lattice: Option<RawLattice>,
    /// Packing: discs, size ratio and area fraction.
    pub packing: Option<RawPacking>,
    /// Lattice: how the bottom is supported.
    pub supports: Option<Supports>,
    /// Lattice: the load on the top row.
    pub load: Option<RawLoad>,
    /// Lattice or chain: when the relaxation stops (a chain with `relax` starts at rest spacing
    /// between its moved walls and relaxes).
    pub relax: Option<RawRelax>,
    /// Chain: time the wave from the excited particle to a receiver (sound speed).
    pub wave: Option<RawWave>,
    /// Record a movie (animated GIF) of the run.
    pub movie: Option<RawMovie>,
    /// Which of the run's sampled series its files keep (`output.series`).
    pub output: Option<RawOutput>,
    /// Lattice: kick one node instead of loading the top row (a wave scene).
    pub impulse: Option<RawImpulse>,
    /// Lattice: rows and columns whose displacement and velocity are recorded at every sample.
    pub probes: Option<RawProbes>,
    /// Lattice: seed of the random bond cutting and stiffness spread; packing: of the discs'
    /// random positions (a grid axis for ensembles; default 1).
    pub seed: Option<u64>,
    /// Grid over this scene only (dotted paths), combined with the campaign's grid.
    pub grid: Option<Grid>,
}

/// `lattice:` section.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLattice {
    /// The network: `square` (default), `triangular`, `honeycomb` or `kagome`.
    #[serde(rename = "type")]
    pub lattice_type: Option<LatticeType>,
    /// Nodes per row and rows of a square N × N lattice, instead of `nx` and `ny`.
    pub size: Option<usize>,
    /// Nodes per row (≥ 2).
    pub nx: Option<usize>,
    /// Rows (≥ 2).
    pub ny: Option<usize>,
    /// `none` or `both`.
    pub diagonals: Option<Diagonals>,
    /// Diagonal stiffness k_d (N/m).
    pub k_diag: Option<f64>,
    /// k_d / k, instead of `k_diag` (default 0.5).
    pub k_diag_ratio: Option<f64>,
    /// Horizontal springs k_x = k_x_ratio · k (default 1): an anisotropic lattice.
    pub k_x_ratio: Option<f64>,
    /// Vertical springs k_y = k_y_ratio · k (default 1).
    pub k_y_ratio: Option<f64>,
    /// Fraction of the bonds cut at random (from `seed`), in [0, 1).
    pub cut_fraction: Option<f64>,
    /// Every kept bond's stiffness times 1 + w·U with U uniform in [−1, 1] (from `seed`);
    /// w in [0, 1).
    pub stiffness_spread: Option<f64>,
}

/// `packing:` section.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPacking {
    /// Number of discs (≥ 2), half small (diameter `geometry.spacing`), half large.
    pub n: Option<usize>,
    /// Large diameter / small diameter (default 1.4).
    pub radius_ratio: Option<f64>,
    /// Area fraction φ the discs cover in the periodic square box, in (0, 1).
    pub fraction: Option<f64>,
    /// A slow compression: the discs are placed and relaxed at this area fraction (below
    /// `fraction`), then squeezed to `fraction` in `compress_steps` equal steps of φ, relaxed
    /// after each.
    pub compress_from: Option<f64>,
    /// Steps of the compression (default 10; only with `compress_from`).
    pub compress_steps: Option<u32>,
}

/// Which diagonal springs a lattice has.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Diagonals {
    /// Nearest neighbours only: no shear stiffness.
    None,
    /// Both diagonals of every cell.
    Both,
    /// Only the rising diagonals (ix, iy)–(ix+1, iy+1): an anisotropic lattice.
    Rising,
    /// Only the falling diagonals (ix+1, iy)–(ix, iy+1).
    Falling,
}

impl Diagonals {
    /// The same diagonals after the block turns by 90°: a rising family falls, a falling one
    /// rises (and back).
    pub fn turned(self) -> Diagonals {
        match self {
            Diagonals::Rising => Diagonals::Falling,
            Diagonals::Falling => Diagonals::Rising,
            other => other,
        }
    }

    /// The name used in files and tables.
    pub fn name(self) -> &'static str {
        match self {
            Diagonals::None => "none",
            Diagonals::Both => "both",
            Diagonals::Rising => "rising",
            Diagonals::Falling => "falling",
        }
    }
}

/// How a lattice's bottom row is supported.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Supports {
    /// As the coursework states: bottom row held vertically, free horizontally; the
    /// bottom-left node held in both directions.
    Coursework,
    /// Bottom row held in both directions.
    ClampedBottom,
    /// Bonds wrap across the left and right sides (a strip of an infinite lattice); bottom row
    /// held in both directions.
    PeriodicX,
    /// Nothing held (impulse scenes: a wave reaches the bottom row unhindered).
    Free,
    /// Bonds wrap across the left and right sides and nothing is held (impulse scenes): a
    /// plane wave runs down an unbounded strip with no side edges to shed other waves, and
    /// reaches a free bottom row.
    PeriodicXFree,
}

impl Supports {
    /// The name used in files and tables.
    pub fn name(self) -> &'static str {
        match self {
            Supports::Coursework => "coursework",
            Supports::ClampedBottom => "clamped-bottom",
            Supports::PeriodicX => "periodic-x",
            Supports::Free => "free",
            Supports::PeriodicXFree => "periodic-x-free",
        }
    }

    /// Bonds wrap across the left and right sides.
    pub fn periodic_x(self) -> bool {
        matches!(self, Supports::PeriodicX | Supports::PeriodicXFree)
    }

    /// Nothing is held: the body is free to move as a whole.
    pub fn holds_nothing(self) -> bool {
        matches!(self, Supports::Free | Supports::PeriodicXFree)
    }
}

/// Which way the top row is pulled.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LoadCase {
    /// Up: Young's modulus E_y and Poisson ratio ν_yx.
    Tensile,
    /// The loading turned by 90°: the right column pulled to the right, the left column on
    /// rollers: E_x and ν_xy.
    TensileX,
    /// To the right: shear modulus.
    Shear,
}

impl LoadCase {
    /// The name used in files and tables.
    pub fn name(self) -> &'static str {
        match self {
            LoadCase::Tensile => "tensile",
            LoadCase::TensileX => "tensile-x",
            LoadCase::Shear => "shear",
        }
    }
}

/// `load:` section.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLoad {
    /// `tensile` (up), `tensile-x` (to the right) or `shear`.
    pub case: Option<LoadCase>,
    /// Force on every top-row node (N), default 1000.
    pub per_node: Option<f64>,
    /// Time over which the load rises linearly to its full value, in t_c (default 0: at once).
    pub ramp_tc: Option<f64>,
    /// `force` (a force on every top-row node) or `velocity` (the top row driven to a strain).
    pub control: Option<Control>,
    /// Velocity control: the strain the top row is driven to (default 1e-4).
    pub strain: Option<f64>,
    /// Velocity control: how long the drive takes, in t_c (default 100).
    pub drive_tc: Option<f64>,
}

/// How a lattice is loaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Control {
    /// A force on every top-row node (the coursework's left figure).
    Force,
    /// The top row driven at constant velocity to a strain, then held (the right figure).
    Velocity,
}

impl Control {
    /// The name used in tables.
    pub fn name(self) -> &'static str {
        match self {
            Control::Force => "force",
            Control::Velocity => "velocity",
        }
    }
}

/// `wave:` section of a chain.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawWave {
    /// Particle whose motion marks the arrival: `first`, `last` or 1..n (default: the end
    /// farther from the excited particle).
    pub receiver: Option<Value>,
    /// Threshold of the threshold criteria, relative to the source's peak (default 0.01).
    pub threshold: Option<f64>,
}

/// `impulse:` section of a lattice.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawImpulse {
    /// `top-right` (default), `top-left` or `top-centre`.
    pub node: Option<String>,
    /// Initial velocity (vx, vy) of the node (m/s).
    pub velocity: Option<[f64; 2]>,
    /// Instead of a kick: a step force (fx, fy) (N) on every top-row node from t = 0; the node
    /// is then where the wave is timed from.
    pub force: Option<[f64; 2]>,
}

/// `probes:` section of a lattice: the rows and columns to record.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawProbes {
    /// Rows: `bottom`, `centre`, `top` or 0..ny−1 (0 at the bottom).
    pub rows: Option<Vec<Value>>,
    /// Columns: `left`, `centre`, `right` or 0..nx−1 (0 at the left).
    pub columns: Option<Vec<Value>>,
}

/// `movie:` section: an animated GIF of the particles coloured by speed.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMovie {
    /// Frames over the run (default 60).
    pub frames: Option<u32>,
    /// Width in pixels (default 720).
    pub width: Option<u32>,
    /// Height in pixels (default 240).
    pub height: Option<u32>,
    /// Also show all runs of the scene side by side in one movie (`plots/<scene>-side-by-side.gif`).
    pub side_by_side: Option<bool>,
    /// Colour the bonds by their strain (red stretched, blue compressed) instead of grey.
    pub bond_strain: Option<bool>,
}

/// `output:` section: what a run's files keep.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOutput {
    /// `default` (what the report draws) or `full` (every particle's displacements and
    /// velocities at every sample, in double precision).
    pub series: Option<SeriesKept>,
}

/// Which sampled series a run's files keep (`output.series`, `series/<run_id>.parquet` and
/// `series/<run_id>.particles.parquet`). Not part of the run's id: it changes the files, not
/// the results.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SeriesKept {
    /// What the report draws: the sample times and energies, a chain's or pair's particles,
    /// a lattice's probed lines and kicked column, thinned to a bounded size, in single
    /// precision where the values fit.
    #[default]
    Default,
    /// Every particle's displacements and velocities and the energies at every sample, in
    /// double precision (within the run's memory budget).
    Full,
}

impl SeriesKept {
    /// The word in campaign files and records.
    pub fn name(self) -> &'static str {
        match self {
            SeriesKept::Default => "default",
            SeriesKept::Full => "full",
        }
    }

    /// True for [`SeriesKept::Default`] (records leave it out, so run ids stay as they were).
    pub fn is_default(&self) -> bool {
        *self == SeriesKept::Default
    }
}

/// `relax:` section.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRelax {
    /// Stop when E_kin/E_pot stays below this (default 1e-8).
    pub kinetic_ratio: Option<f64>,
    /// Stop instead when the largest static force (springs and loads, no damping) on any free
    /// axis stays below this fraction of the load per node.
    pub residual_force: Option<f64>,
    /// Lattice: `damped` (default: damped MD in time), `fire` (FIRE 2.0) or `cg` (conjugate
    /// gradients): how the lattice is brought to rest.
    pub method: Option<crate::sim::RelaxMethod>,
    /// Lattice: stop once the moduli are provably within this relative error of the state of
    /// rest (the displacement bound: the error of the measured ΔL is at most ‖K_t⁻¹ g‖₂ ‖r‖₂);
    /// default 1e-4 for `fire` and `cg`, off for `damped` unless given; control: force only.
    pub tolerance: Option<f64>,
    /// Give up after this many t_c (default 5000): `status = no_equilibrium`.
    pub max_tc: Option<f64>,
    /// Tangent moduli (stiffness): after relaxing, raise the load (a chain's wall displacement)
    /// by this fraction, relax again and divide the increments (e.g. 0.01).
    pub tangent_step: Option<f64>,
    /// Lattice, `fire`, control: force: `stiffness` moves FIRE in the metric of the network's
    /// tangent stiffness at its static answer, factored for the error bound (default `none`:
    /// the masses).
    pub preconditioner: Option<crate::sim::PreconditionerKind>,
}

/// `material:` section.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMaterial {
    /// Particle mass m (kg).
    pub mass: Option<f64>,
    /// Stiffness constant: k (N/m) for linear, C (N/m^β) for power-law springs.
    pub k: Option<f64>,
    /// `linear`, `power` or `hertz`.
    pub law: Option<LawName>,
    /// Power-law exponent β (default 1.5).
    pub beta: Option<f64>,
    /// Springs act only in compression.
    pub contact: Option<bool>,
    /// Lattice: density ρ of the solid (kg/m³), instead of `mass`: every node gets an equal
    /// share of the block's mass.
    pub density: Option<f64>,
    /// Lattice: Young's modulus of the solid (Pa), instead of `k`: k is chosen so that the
    /// lattice's continuum E equals it.
    pub youngs_modulus: Option<f64>,
}

/// `damping:` section.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDamping {
    /// Target restitution r in (0, 1]; sets γ analytically.
    pub restitution: Option<f64>,
    /// Bond dashpot γ (N s/m), instead of `restitution`.
    pub gamma: Option<f64>,
    /// Background damping γ_g (N s/m), or `critical`: 2 m ω_min, critical for the slowest mode
    /// of a relaxing lattice (ω_min² = k_min/m from its stiffness matrix).
    pub background: Option<Background>,
}

/// `damping.background`: a value (N s/m) or the word `critical`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Background {
    /// γ_g (N s/m).
    Value(f64),
    /// Critical for the slowest mode.
    Critical(Critical),
}

/// The word `critical`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Critical {
    /// γ_g = 2 m ω_min.
    Critical,
}

/// Read by hand, not as serde's untagged enum: that one refuses a typo with "data did not
/// match any variant of untagged enum Background", naming neither the value nor `critical`.
impl<'de> Deserialize<'de> for Background {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Background, D::Error> {
        deserializer.deserialize_any(BackgroundVisitor)
    }
}

struct BackgroundVisitor;

impl serde::de::Visitor<'_> for BackgroundVisitor {
    type Value = Background;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a number (γ_g ≥ 0, N s/m) or the word `critical`")
    }
    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<Background, E> {
        Ok(Background::Value(v))
    }
    fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<Background, E> {
        Ok(Background::Value(v as f64))
    }
    fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<Background, E> {
        Ok(Background::Value(v as f64))
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Background, E> {
        match v {
            "critical" => Ok(Background::Critical(Critical::Critical)),
            _ => Err(E::invalid_value(serde::de::Unexpected::Str(v), &self)),
        }
    }
}

/// `time:` section.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTime {
    /// `position-verlet` (default), `velocity-verlet`, `symplectic-euler`, `rk4`, `forest-ruth` or `gear`.
    pub integrator: Option<IntegratorKind>,
    /// dt = t_c / dt_per_tc (default 50).
    pub dt_per_tc: Option<f64>,
    /// Time step (s), instead of `dt_per_tc`.
    pub dt: Option<f64>,
    /// dt = dt_omega_max / ω_max, the scene's fastest mode (instead of `dt` or `dt_per_tc`):
    /// to sweep a step across an integrator's stability limit.
    pub dt_omega_max: Option<f64>,
    /// Also run the scene at dt / reference_refinement and measure the error of this run
    /// against it (lattices, where no exact solution exists); ≥ 2.
    pub reference_refinement: Option<u32>,
    /// Run even when dt · ω_max exceeds the integrator's stability limit (to show the
    /// instability); refused otherwise.
    pub allow_unstable: Option<bool>,
    /// Run length in units of t_c.
    pub duration_tc: Option<f64>,
    /// Samples recorded over the run (default 400).
    pub samples: Option<u64>,
}

/// `geometry:` section.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawGeometry {
    /// Particle spacing = spring rest length x_e (m).
    pub spacing: Option<f64>,
    /// Depth d of the solid (m), for stresses and moduli (default 1).
    pub depth: Option<f64>,
}
