//! The lattice's own fields (size, springs, supports, load or impulse, probes, relaxation,
//! timed wave) and its part of the resolution (a lattice derived from a solid, a lattice
//! turned for `tensile-x`), its layout, and its part of what a run spec tells: its particles,
//! bonds and stored series.

use serde::{Deserialize, Serialize};
use serde_json::Value;

use super::lattice_type::{network_wave, resolve_type, top_row};
use crate::model::{LatticeType, Layout, PlanarLattice};
use crate::sim::IntegratorKind;
use crate::spec::issue::{Issue, Num, missing, positive, require};
use crate::spec::raw::{
    Control, Diagonals, LoadCase, RawImpulse, RawLattice, RawMaterial, RawProbes, RawScene, RawWave, Supports,
};
use crate::spec::shared::{Deformation, RelaxSpec, WaveSpec, bonded, resolve_relax, wave_threshold};

/// Lattice defaults: k_d/k and the load per top-row node (N).
const DEFAULT_K_DIAG_RATIO: f64 = 0.5;
const DEFAULT_LOAD_PER_NODE: f64 = 1000.0;

/// The impulse of a wave lattice: one node kicked at t = 0, or a force step on the top row.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ImpulseSpec {
    /// The kicked node, or the top-row node the wave is timed from.
    pub node: usize,
    /// Its initial velocity (m/s); zero under a force step.
    pub vx: f64,
    /// Its initial velocity (m/s).
    pub vy: f64,
    /// Step force (fx, fy) (N) on every top-row node, if this is a force step.
    #[serde(default)]
    pub top_row_force: Option<[f64; 2]>,
}

impl ImpulseSpec {
    /// The direction of the impulse: the kick's velocity or the step's force.
    pub fn direction(&self) -> [f64; 2] {
        self.top_row_force.unwrap_or([self.vx, self.vy])
    }

    /// True for an impulse mostly along x: on a lattice loaded from its top row, a transverse
    /// wave.
    pub fn is_sideways(&self) -> bool {
        let [x, y] = self.direction();
        x.abs() > y.abs()
    }
}

/// The resolved lattice of a lattice scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LatticeSpec {
    /// Nodes per row.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// Diagonal stiffness k_d (N/m); 0 without diagonals.
    pub k_diag: f64,
    /// Which diagonals are present (of the lattice as simulated, see `rotated`).
    pub diagonals: Diagonals,
    /// Horizontal springs k_x (N/m, or C for power laws).
    pub k_x: f64,
    /// Vertical springs k_y.
    pub k_y: f64,
    /// The campaign's lattice turned by 90° (counter-clockwise) so that its x direction is
    /// loaded from the top row (`load.case: tensile-x`): nx/ny, k_x/k_y and the diagonal
    /// families are swapped here; measured E and ν are the original's E_x and ν_xy.
    pub rotated: bool,
    /// Fraction of the bonds cut at random.
    pub cut_fraction: f64,
    /// Relative half-width w of the uniform stiffness spread 1 + w·U[−1, 1].
    pub stiffness_spread: f64,
    /// Seed of the random cutting and spread.
    pub seed: u64,
    /// Depth d (m).
    pub depth: f64,
    /// Supports.
    pub supports: Supports,
    /// Load case.
    pub load_case: LoadCase,
    /// Force on each top-row node (N).
    pub load_per_node: f64,
    /// Time over which the load rises linearly to its full value, in t_c (0: at once).
    pub load_ramp_tc: f64,
    /// Force or velocity control.
    pub control: Control,
    /// Velocity control: strain the top row is driven to.
    pub drive_strain: f64,
    /// Velocity control: duration of the drive, in t_c.
    pub drive_tc: f64,
    /// How mass and stiffness were derived from a solid, when they were.
    pub derived_from: Option<String>,
    /// The kicked node of an impulse scene (no load, no relaxation).
    #[serde(default)]
    pub impulse: Option<ImpulseSpec>,
    /// Rows and columns whose displacement and velocity are recorded at every sample.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub probes: Vec<ProbeLine>,
    /// The network (`lattice.type`); not stored when square, so existing run ids stay.
    #[serde(default, rename = "type", skip_serializing_if = "LatticeType::is_square")]
    pub lattice_type: LatticeType,
}

/// A line of lattice nodes a probe records.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ProbeLine {
    /// Row 0..ny−1, from the bottom.
    Row(usize),
    /// Column 0..nx−1, from the left.
    Column(usize),
}

impl ProbeLine {
    /// `row 3` or `column 0`.
    pub fn name(self) -> String {
        match self {
            ProbeLine::Row(r) => format!("row {r}"),
            ProbeLine::Column(c) => format!("column {c}"),
        }
    }

    /// Its nodes (index iy·nx + ix) of a lattice of `nx` × `ny` nodes: a row left to right, a
    /// column bottom to top.
    pub fn nodes(self, nx: usize, ny: usize) -> Vec<usize> {
        match self {
            ProbeLine::Row(r) => (0..nx).map(|ix| r * nx + ix).collect(),
            ProbeLine::Column(c) => (0..ny).map(|iy| iy * nx + c).collect(),
        }
    }
}

impl LatticeSpec {
    /// The load case as the campaign names it: `tensile-x` for a lattice simulated turned.
    pub fn load_name(&self) -> &'static str {
        if self.rotated { LoadCase::TensileX.name() } else { self.load_case.name() }
    }

    /// The lattice as its campaign describes it: a `tensile-x` square lattice turned back
    /// (nx/ny, k_x/k_y and the diagonal families swapped again, see `turned`); any other as is.
    pub fn upright(&self) -> LatticeSpec {
        if !self.rotated || !self.lattice_type.is_square() {
            return self.clone();
        }
        let diagonals = self.diagonals.turned();
        LatticeSpec {
            nx: self.ny,
            ny: self.nx,
            k_x: self.k_y,
            k_y: self.k_x,
            diagonals,
            rotated: false,
            ..self.clone()
        }
    }

    /// Total force on the top row under force control, load_per_node times its nodes (N).
    pub fn total_load(&self) -> f64 {
        self.load_per_node * self.top_row_len() as f64
    }

    /// The largest coordinate (m) of a node, springs `spacing` (m) long, to within a factor
    /// of order one: the larger of nx and ny times the spacing (nodes start at the origin).
    pub fn extent(&self, spacing: f64) -> f64 {
        self.nx.max(self.ny) as f64 * spacing
    }

    /// Nodes in the loaded top row as simulated: nx (the square lattice's nx is already the
    /// turned block's), or the turned network's side column under `tensile-x`: ny nodes of a
    /// triangular block, (ny + 1)/2 of a kagome one (its sparse rows have no end node there).
    pub fn top_row_len(&self) -> usize {
        match self.planar(1.0) {
            Some(_) if self.rotated => self.layout(1.0).edges.top.len(),
            _ => self.nx,
        }
    }

    /// The force on every top-row node (N) where there is a force load: a loaded lattice under
    /// force control. `None` under velocity control (the drive's force is measured, not given)
    /// and for impulse lattices, whose `load_per_node` is an unused default.
    pub fn force_per_node(&self) -> Option<f64> {
        (self.impulse.is_none() && self.control == Control::Force).then_some(self.load_per_node)
    }

    /// Stiffness of the rising and falling diagonals (0 where absent).
    pub fn diagonal_stiffness(&self) -> (f64, f64) {
        match self.diagonals {
            Diagonals::None => (0.0, 0.0),
            Diagonals::Both => (self.k_diag, self.k_diag),
            Diagonals::Rising => (self.k_diag, 0.0),
            Diagonals::Falling => (0.0, self.k_diag),
        }
    }

    /// Bonds per node of the network uncut (z): a square lattice's 4 along its rows and columns
    /// and 2 per diagonal family present (8 with both); another type's own.
    pub fn coordination(&self) -> f64 {
        if !self.lattice_type.is_square() {
            return self.lattice_type.coordination();
        }
        let (rising, falling) = self.diagonal_stiffness();
        4.0 + 2.0 * (f64::from(u8::from(rising > 0.0)) + f64::from(u8::from(falling > 0.0)))
    }

    /// True when bonds are cut or their stiffness spread at random.
    pub fn is_random(&self) -> bool {
        self.cut_fraction > 0.0 || self.stiffness_spread > 0.0
    }

    /// The network of a lattice of another type than square, its springs `spacing` (m)
    /// long; `None` for the square lattice (`SquareLattice`, with its families).
    pub fn planar(&self, spacing: f64) -> Option<PlanarLattice> {
        (!self.lattice_type.is_square()).then_some(PlanarLattice {
            kind: self.lattice_type,
            nx: self.nx,
            ny: self.ny,
            spacing,
            k: self.k_x,
            periodic_x: self.supports.periodic_x(),
        })
    }

    /// Node positions and edges as simulated, spacing `spacing` (m): a lattice of another
    /// type loaded along x (`tensile-x`) turned by 90° (the square one is turned in its
    /// resolution, by its families).
    pub fn layout(&self, spacing: f64) -> Layout {
        match self.planar(spacing) {
            None => Layout::square(self.nx, self.ny, spacing, self.supports.periodic_x()),
            Some(planar) if self.rotated => planar.layout().turned(),
            Some(planar) => planar.layout(),
        }
    }
}

/// What only a lattice has.
#[derive(Clone, Debug, PartialEq)]
pub struct LatticeRun {
    /// The lattice, its load and supports.
    pub lattice: LatticeSpec,
    /// A loaded lattice: when the relaxation stops, and the tangent step.
    pub relax: Option<RelaxSpec>,
    /// An impulse lattice: the wave timed from the kicked node to the bottom row, if asked for.
    pub wave: Option<WaveSpec>,
}

impl LatticeRun {
    /// The lattice of a lattice scene (with how it was derived from a solid, if it was) and
    /// a loaded lattice's relaxation; an impulse lattice's wave waits for the time scale.
    pub(super) fn resolve(
        raw: &RawScene,
        k: f64,
        depth: Option<f64>,
        derived_from: Option<String>,
    ) -> Result<LatticeRun, Issue> {
        let lattice = LatticeSpec { derived_from, ..resolve_lattice(raw, k, depth)? };
        let relax = lattice
            .impulse
            .is_none()
            .then(|| resolve_relax(raw, lattice.control, Some(lattice.load_ramp_tc)))
            .transpose()?;
        Ok(LatticeRun { lattice, relax, wave: None })
    }

    /// A lattice is loaded or kicked through its impulse, never given a v0; its springs are
    /// bonded.
    pub(super) fn resolve_v0(contact: bool) -> Result<f64, Issue> {
        bonded(contact)?;
        Ok(0.0)
    }

    /// An impulse lattice's timed wave, if the scene asks for one, its springs `spacing` (m) long.
    pub(super) fn resolve_wave(&mut self, raw: &RawScene, spacing: f64) -> Result<(), Issue> {
        if let Some(w) = &raw.wave {
            self.wave = lattice_wave(&self.lattice, w, spacing)?;
        }
        Ok(())
    }

    /// The run's default length (t_c): an impulse lattice runs until the wave has crossed it
    /// about three times; a loaded one's is `relax.max_tc`.
    pub(super) fn default_duration_tc(&self) -> Option<f64> {
        let l = &self.lattice;
        l.impulse.is_some().then(|| 3.0 * l.nx.max(l.ny) as f64)
    }

    /// Its nodes.
    pub(super) fn particles(&self) -> usize {
        match self.lattice.planar(1.0) {
            Some(planar) => planar.layout().len(),
            None => self.lattice.nx * self.lattice.ny,
        }
    }

    /// At most one spring per node and bond family (cut bonds counted); of another type, at
    /// most the triangular lattice's three per node.
    pub(super) fn bonds(&self) -> usize {
        let l = &self.lattice;
        if !l.lattice_type.is_square() {
            return 3 * self.particles();
        }
        let families = match l.diagonals {
            Diagonals::None => 2,
            Diagonals::Both => 4,
            Diagonals::Rising | Diagonals::Falling => 3,
        };
        families * l.nx * l.ny
    }

    /// Nodes whose series a record stores: a square impulse lattice's kicked column and the
    /// probes.
    pub(super) fn stored_nodes(&self) -> usize {
        let l = &self.lattice;
        let kicked = if l.impulse.is_some() && l.lattice_type.is_square() { l.ny } else { 0 };
        kicked + l.probes.iter().map(|line| line.nodes(l.nx, l.ny).len()).sum::<usize>()
    }

    /// True when every node's displacement and velocity are recorded: impulse and probed
    /// lattices.
    pub(super) fn records_displacements(&self) -> bool {
        self.lattice.impulse.is_some() || !self.lattice.probes.is_empty()
    }

    /// Degrees of freedom of a loaded lattice's static problem: two per node (held ones
    /// counted); none for an impulse lattice.
    pub(super) fn static_dofs(&self) -> usize {
        if self.lattice.impulse.is_none() { 2 * self.particles() } else { 0 }
    }

    /// A force step carries its force, a kick collides at its speed; a loaded lattice's
    /// springs carry one node's load, or under velocity control stretch by strain · a
    /// (`spacing`, m).
    pub(super) fn deformation(&self, spacing: f64) -> Deformation {
        let l = &self.lattice;
        match l.impulse {
            Some(ImpulseSpec { top_row_force: Some([fx, fy]), .. }) => Deformation::Carrying(fx.hypot(fy)),
            Some(i) => Deformation::Collision(i.vx.hypot(i.vy)),
            None if l.control == Control::Velocity => Deformation::Extension(l.drive_strain.abs() * spacing),
            None => Deformation::Carrying(l.load_per_node),
        }
    }
}

/// Mass and stiffness of a lattice derived from the solid it stands for, and how.
#[derive(Default)]
pub(in crate::spec) struct Solid {
    /// Node mass (kg).
    pub(in crate::spec) mass: Option<f64>,
    /// Spring stiffness (N/m).
    pub(in crate::spec) k: Option<f64>,
    /// How they were derived.
    pub(in crate::spec) note: Option<String>,
}

/// For a lattice scene with `material.density` and/or `material.youngs_modulus`: the node mass
/// m = ρ L_x L_y d / (N_x N_y), so the lattice weighs what the block of size L_x × L_y × d
/// weighs, and the spring stiffness k = E d / (1 + r − r²/(1 + r)) with r = k_d/k, so the
/// lattice's continuum Young's modulus (C11 − C12²/C11)/d equals E.
pub(super) fn derive_from_solid(
    raw: &RawScene,
    material: &RawMaterial,
    spacing: f64,
    depth: Option<f64>,
) -> Result<Solid, Issue> {
    if material.density.is_none() && material.youngs_modulus.is_none() {
        return Ok(Solid::default());
    }
    let lattice = raw.lattice.clone().unwrap_or_default();
    require(
        lattice.lattice_type.unwrap_or_default().is_square(),
        "material",
        "density/youngs_modulus",
        "derive the square lattice's m and k only; give material.mass and material.k for another lattice.type",
    )?;
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
        notes.push(format!("k = E d / (1 + r − r²/(1 + r)) with E = {modulus:e} Pa, r = k_d/k = {r} (the lattice's continuum E is the solid's)"));
    }
    solid.note = Some(notes.join("; "));
    Ok(solid)
}

/// The lattice of a lattice scene.
fn resolve_lattice(raw: &RawScene, k: f64, depth: Option<f64>) -> Result<LatticeSpec, Issue> {
    let lattice = raw.lattice.clone().unwrap_or_default();
    let (nx, ny) = lattice_size(&lattice)?;
    let supports = raw.supports.unwrap_or(Supports::Coursework);
    let probes = resolve_probes(raw.probes.as_ref(), nx, ny)?;
    let lattice_type = resolve_type(&lattice, (nx, ny), supports, !probes.is_empty())?;
    // Another type has one spring k between nearest neighbours and no families.
    let (diagonals, k_diag, k_x, k_y) =
        if lattice_type.is_square() { lattice_springs(&lattice, k)? } else { (Diagonals::None, 0.0, k, k) };
    let (cut_fraction, stiffness_spread) = resolve_randomness(&lattice)?;
    require(
        !supports.periodic_x() || nx >= 3,
        "lattice.nx",
        nx,
        "must be ≥ 3 with supports: periodic-x or periodic-x-free (two nodes would be bonded twice)",
    )?;
    let load = resolve_load(raw)?;
    let top = top_row(lattice_type, nx, ny, supports.periodic_x());
    let impulse = raw.impulse.as_ref().map(|i| resolve_impulse(i, &top)).transpose()?;
    require(
        impulse.is_some() || !supports.holds_nothing(),
        "supports",
        supports.name(),
        "holds nothing, so it serves impulse scenes only (a load would carry the whole lattice away): give \
         an impulse, or supports coursework, clamped-bottom or periodic-x",
    )?;
    let upright = Upright { nx, ny, k_x, k_y, diagonals, load_case: raw.load.as_ref().and_then(|l| l.case) };
    let rotated = upright.load_case == Some(LoadCase::TensileX);
    let Upright { nx, ny, k_x, k_y, diagonals, load_case } =
        if rotated { turned(upright, &probes, supports, lattice_type)? } else { upright };
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
        lattice_type,
    })
}

/// The lattice's randomness: the fraction of its interior bonds cut and the spread w of its
/// stiffnesses, each checked to lie in [0, 1).
fn resolve_randomness(lattice: &RawLattice) -> Result<(f64, f64), Issue> {
    let cut_fraction = lattice.cut_fraction.unwrap_or(0.0);
    require((0.0..1.0).contains(&cut_fraction), "lattice.cut_fraction", cut_fraction, "must be in [0, 1)")?;
    let stiffness_spread = lattice.stiffness_spread.unwrap_or(0.0);
    require(
        (0.0..1.0).contains(&stiffness_spread),
        "lattice.stiffness_spread",
        stiffness_spread,
        "must be in [0, 1) (every stiffness times 1 + w·U[−1, 1])",
    )?;
    Ok((cut_fraction, stiffness_spread))
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

/// The impulse of a wave lattice: the node of its `top` row it starts at and its kick or
/// top-row force step.
fn resolve_impulse(i: &RawImpulse, top: &[usize]) -> Result<ImpulseSpec, Issue> {
    let node = match i.node.as_deref().unwrap_or("top-right") {
        "top-right" => top[top.len() - 1],
        "top-left" => top[0],
        "top-centre" | "top-center" => top[top.len() / 2],
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
        format!("[{}, {}]", Num(a), Num(b)),
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
/// becomes (−1, −1), a rising one. Not probed, and on supports that turn with it. A lattice
/// of another type keeps its size here: its layout is turned (`LatticeSpec::layout`).
fn turned(upright: Upright, probes: &[ProbeLine], supports: Supports, kind: LatticeType) -> Result<Upright, Issue> {
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
    if !kind.is_square() {
        return Ok(Upright { load_case: Some(LoadCase::Tensile), ..upright });
    }
    let Upright { nx, ny, k_x, k_y, diagonals, .. } = upright;
    Ok(Upright {
        nx: ny,
        ny: nx,
        k_x: k_y,
        k_y: k_x,
        diagonals: diagonals.turned(),
        load_case: Some(LoadCase::Tensile),
    })
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
    // An error names the field the campaign wrote: `size`, or `nx` and `ny`.
    match lattice.size {
        Some(n) => size(Some(n), "lattice.size").map(|n| (n, n)),
        None => Ok((size(lattice.nx, "lattice.nx")?, size(lattice.ny, "lattice.ny")?)),
    }
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

/// The wave of an impulse lattice: from the kicked node down to the bottom row.
fn lattice_wave(l: &LatticeSpec, w: &RawWave, spacing: f64) -> Result<Option<WaveSpec>, Issue> {
    let Some(impulse) = l.impulse else { return Ok(None) };
    if !l.lattice_type.is_square() {
        return Ok(Some(network_wave(l.layout(spacing), impulse.node, l.ny, wave_threshold(w)?)));
    }
    let row = impulse.node / l.nx;
    Ok(Some(WaveSpec {
        source: impulse.node,
        receivers: (0..l.nx).collect(),
        distance: row as f64 * spacing,
        springs: row,
        threshold: wave_threshold(w)?,
    }))
}

pub(super) fn non_negative(value: f64, path: &str) -> Result<f64, Issue> {
    require(
        value.is_finite() && value >= 0.0,
        path,
        Num(value),
        "must be a finite number ≥ 0 (0: no diagonal springs)",
    )?;
    Ok(value)
}
