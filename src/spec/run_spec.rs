//! One fully resolved run: every parameter explicit, in SI units, hashable.

use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::collections::BTreeMap;

use super::flat::FlatRunSpec;
use super::kind::{KindSpec, LatticeRun};
use super::raw::{Control, Diagonals, LoadCase, Supports};
use crate::model::LawSpec;
use crate::sim::IntegratorKind;

/// Bumped whenever stored results of an unchanged spec would differ (new physics or columns),
/// so the cache never serves results of older code.
pub const RESULT_FORMAT: u32 = 11;

/// A resolved run. Units SI. Serialised flat ([`super::flat`]): the kind as the tag `kind`
/// with every kind's fields beside it, the keys being the results table's column names.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(into = "FlatRunSpec", try_from = "FlatRunSpec")]
pub struct RunSpec {
    /// Campaign name.
    pub campaign: String,
    /// Scene name.
    pub scene: String,
    /// Scene kind with its own fields.
    pub scene_kind: KindSpec,
    /// Grid values of this run, by dotted path.
    pub varied: BTreeMap<String, Value>,
    /// Particle mass m (kg).
    pub mass: f64,
    /// Spacing = rest length x_e (m).
    pub spacing: f64,
    /// Stiffness constant: k (N/m) for linear springs, C (N/m^β) for power-law springs.
    pub k: f64,
    /// Elastic law, serialised as the columns `law` and `beta` (1 for linear springs).
    pub law: LawSpec,
    /// Springs act only in compression.
    pub contact: bool,
    /// Bond dashpot γ (N s/m).
    pub gamma: f64,
    /// Restitution the campaign asked for, when γ was derived from it.
    pub restitution_target: Option<f64>,
    /// Background damping γ_g (N s/m).
    pub gamma_background: f64,
    /// Integrator.
    pub integrator: IntegratorKind,
    /// Reference two-body contact duration t_c (s) that sets dt.
    pub t_c: f64,
    /// Time step (s): from `time.dt` or `time.dt_per_tc` here; where `dt_omega_max` sets it,
    /// NaN until the plan decides it ([`crate::plan`]).
    pub dt: f64,
    /// The campaign's dt · ω_max, when it set dt that way (dt = this / ω_max, by the plan).
    pub dt_omega_max: Option<f64>,
    /// Also run at dt / this and measure the error against that reference.
    pub reference_refinement: Option<u32>,
    /// Run even beyond the integrator's stability limit.
    pub allow_unstable: bool,
    /// Run length (s).
    pub duration: f64,
    /// Steps to take, ⌈duration / dt⌉ (0 until planned where `dt_omega_max` sets dt).
    pub steps: u64,
    /// Samples recorded over the run.
    pub samples: u64,
    /// Pair: relative approach speed; chain: speed of the excited particle (m/s).
    pub v0: f64,
    /// The movie to record, if asked for.
    pub movie: Option<MovieSpec>,
}

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
}

/// An animated GIF of a run: `frames` frames of `width` × `height` pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct MovieSpec {
    /// Frames over the run.
    pub frames: u32,
    /// Width (pixels).
    pub width: u32,
    /// Height (pixels).
    pub height: u32,
    /// Also put the scene's runs side by side in one movie.
    #[serde(default)]
    pub side_by_side: bool,
    /// Colour the bonds by their strain.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub bond_strain: bool,
}

/// What one run may use: beyond it, the run is stopped (or not started) and recorded with
/// `status = budget`, and the campaign goes on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// Wall-clock seconds per run.
    pub seconds_per_run: f64,
    /// Bytes per run, by [`RunSpec::estimated_memory_bytes`].
    pub memory_per_run: f64,
}

impl Default for Budget {
    /// One hour and 4 GB per run: a coursework run takes seconds and megabytes, so only a
    /// mistake (a 2000 × 2000 lattice recording every sample, 2e9 steps) comes near.
    fn default() -> Budget {
        Budget { seconds_per_run: 3600.0, memory_per_run: 4e9 }
    }
}

impl Budget {
    /// The time budget per run as a duration: capped at 1e9 s (~32 years), which a deadline
    /// `Instant::now() + it` never overflows.
    pub fn time_per_run(&self) -> std::time::Duration {
        seconds_up_to_1e9(self.seconds_per_run)
    }

    /// Why `spec` cannot start within this budget, if it cannot.
    pub fn refuses(&self, spec: &RunSpec) -> Option<String> {
        let memory = spec.estimated_memory_bytes();
        (memory > self.memory_per_run).then(|| {
            format!(
                "the run would hold about {:.0} MB, beyond the budget of {:.0} MB per run (budget.memory_per_run_mb)",
                memory / 1e6,
                self.memory_per_run / 1e6
            )
        })
    }

    /// Why `spec` is expected to exceed this budget, if it is (the plan's warning).
    pub fn warning(&self, spec: &RunSpec) -> Option<String> {
        self.refuses(spec).or_else(|| {
            let seconds = spec.estimated_seconds();
            (seconds > self.seconds_per_run).then(|| {
                format!(
                    "estimated {seconds:.0} s, beyond the budget of {:.0} s per run (budget.seconds_per_run)",
                    self.seconds_per_run
                )
            })
        })
    }
}

/// `seconds` (finite, ≥ 0) as a duration, capped at 1e9 s so that adding it to now never
/// overflows an `Instant`.
pub fn seconds_up_to_1e9(seconds: f64) -> std::time::Duration {
    std::time::Duration::from_secs_f64(seconds.min(1e9))
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
    /// Total force on the top row under force control, load_per_node · nx (N).
    pub fn total_load(&self) -> f64 {
        self.load_per_node * self.nx as f64
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

    /// True when bonds are cut or their stiffness spread at random.
    pub fn is_random(&self) -> bool {
        self.cut_fraction > 0.0 || self.stiffness_spread > 0.0
    }
}

/// Networks with more bonds ([`RunSpec::bonds`]) than this get their modes from a node-by-node
/// bound in one pass (`plan::stability::node_bound`) instead of the power method, whose up to 1000
/// passes over 250 000 bonds take about a second and grow with the network (a 2000 × 2000
/// lattice took 170 s and 1.7 GB before `plan` printed anything). Every shipped campaign stays
/// below it (its largest lattice, 40 × 40, has 6 400 bonds).
pub const POWER_METHOD_BONDS: usize = 250_000;

/// The extension (m) at which a power-law spring (no stiffness at δ = 0) is linearised for
/// t_c, the damping and the stability estimate: the deformation the run is expected to reach.
/// A collision or kick at speed v: the two-body overlap −δ_max(v); a loaded lattice: the
/// extension (F/C)^(1/β) of a spring carrying one node's load F (velocity control: strain · a);
/// a relaxing chain: its springs' equilibrium extension ΔW/(n + 1). Linear springs: 0.
pub fn reference_extension(spec: &RunSpec) -> f64 {
    let LawSpec::Power { beta } = spec.law else {
        return 0.0;
    };
    let overlap = |speed: f64| -crate::theory::power_law_max_overlap(spec.k, beta, spec.mass, speed);
    let carrying = |force: f64| (force.abs() / spec.k).powf(1.0 / beta);
    match &spec.scene_kind {
        KindSpec::Lattice(LatticeRun { lattice: l, .. }) => match l.impulse {
            Some(ImpulseSpec { top_row_force: Some([fx, fy]), .. }) => carrying(fx.hypot(fy)),
            Some(i) => overlap(i.vx.hypot(i.vy)),
            None if l.control == Control::Velocity => l.drive_strain.abs() * spec.spacing,
            None => carrying(l.load_per_node),
        },
        KindSpec::Chain(chain) if chain.relax.is_some() && spec.chain_wall_extension() != 0.0 => {
            spec.chain_wall_extension() / (chain.n + 1) as f64
        }
        _ => overlap(spec.v0),
    }
}

impl RunSpec {
    /// Stable identifier: the scene name and a content hash of the resolved run, its numbers in
    /// one form (`-0.0` as `0`, `50.0` as `50`), so runs with the same physics share one id.
    pub fn run_id(&self) -> String {
        let value = serde_json::to_value((RESULT_FORMAT, self)).expect("a RunSpec always serialises");
        let hash = blake3::hash(super::grid::canonical(&value).to_string().as_bytes()).to_hex();
        format!("{}-{}", self.scene, &hash[..12])
    }

    /// Cost model of the run in a release build (s), from `mdsolids bench` and the coursework
    /// campaign on the project machine: ~80 ns per step for the loop itself and the per-step
    /// probes, plus ~3 ns per particle-step (the reference lattice runs at ~330 million
    /// particle-steps/s) and force evaluation, for the run and its reference run, if any; plus
    /// the stages around the loop: the ω_max estimate (≤ 1000 power iterations at ~7 ns per
    /// bond, twice with bond dashpots; one pass beyond [`POWER_METHOD_BONDS`]), a loaded lattice's static solve (sparse Cholesky of a
    /// 2D network, ~O(dofs^1.5): 2.5e-7 s · dofs^1.5, ~6 s for 200 × 200 nodes) and the movie's
    /// GIF encoding (~0.2 µs per pixel and frame; faer and the GIF encoder are built without
    /// optimisation, see Cargo.toml).
    pub fn estimated_seconds(&self) -> f64 {
        let evaluations = self.integrator.evaluations_per_step() as f64;
        // A reference run at dt/R takes R times as many steps.
        let runs = 1.0 + self.reference_refinement.map_or(0.0, f64::from);
        let time_loop = runs * self.steps as f64 * (80e-9 + 3e-9 * evaluations * self.particles() as f64);
        let eigenproblems = if self.gamma > 0.0 { 2.0 } else { 1.0 };
        let passes = if self.bonds() > POWER_METHOD_BONDS { 1.0 } else { 1000.0 };
        let omega_max = eigenproblems * passes * 7e-9 * self.bonds() as f64;
        let static_solve = 2.5e-7 * self.static_dofs().powf(1.5);
        let movie = self.movie.map_or(0.0, |m| 0.2e-6 * f64::from(m.frames) * f64::from(m.width) * f64::from(m.height));
        time_loop + omega_max + static_solve + movie
    }

    /// Springs of the run's network: at most one per node and bond family in a lattice (cut
    /// bonds counted), n + 1 in a chain, one in a pair.
    pub fn bonds(&self) -> usize {
        match &self.scene_kind {
            KindSpec::Lattice(LatticeRun { lattice: l, .. }) => {
                let families = match l.diagonals {
                    Diagonals::None => 2,
                    Diagonals::Both => 4,
                    Diagonals::Rising | Diagonals::Falling => 3,
                };
                families * l.nx * l.ny
            }
            KindSpec::Chain(chain) => chain.n + 1,
            KindSpec::Pair(_) => 1,
        }
    }

    /// Degrees of freedom of the static problem solved beside MD (a loaded lattice): two per
    /// node (held ones counted); 0 when there is none.
    fn static_dofs(&self) -> f64 {
        match self.lattice() {
            Some(l) if l.impulse.is_none() => 2.0 * (l.nx * l.ny) as f64,
            _ => 0.0,
        }
    }

    /// Numbers per sample of what a record stores of the trace: time and four energies, and
    /// four per particle (a chain) or per probed node (a lattice's kicked column and probes).
    fn stored_numbers_per_sample(&self) -> usize {
        let nodes = match &self.scene_kind {
            KindSpec::Lattice(LatticeRun { lattice: l, .. }) => {
                let kicked = if l.impulse.is_some() { l.ny } else { 0 };
                kicked + l.probes.iter().map(|line| line.nodes(l.nx, l.ny).len()).sum::<usize>()
            }
            KindSpec::Chain(_) => self.particles(),
            KindSpec::Pair(_) => 0,
        };
        5 + 4 * nodes
    }

    /// True when the run records every particle's displacement and velocity at every sample:
    /// chains (normal modes, space–time), reference runs, waves, impulse and probed lattices.
    pub fn records_displacements(&self) -> bool {
        self.chain().is_some()
            || self.reference_refinement.is_some()
            || self.wave().is_some()
            || self.lattice().is_some_and(|l| l.impulse.is_some() || !l.probes.is_empty())
    }

    /// Estimated peak memory (bytes) of the run over all its stages, summed (an upper bound:
    /// the stages' transient parts do not overlap), from what they allocate:
    /// - the time loop: per particle ~40 numbers of state, integrator history and forces plus
    ///   ~4 bonds of 5 numbers; per sample 5 numbers, and 4 per particle when displacements
    ///   are recorded; 3 per particle per movie frame (and one per bond with bond strain); a
    ///   wave probe's at most 10⁵ entries of 7 numbers; a reference run holds its own copy;
    /// - the ω_max estimate: two lists of 5 numbers per bond and ~8 vectors over the particles;
    /// - a loaded lattice's static solve: ~1200 bytes per bond (the stiffness entries twice,
    ///   16 of 24 bytes per bond, and faer's sorted copy) and the Cholesky factor, whose fill
    ///   on a 2D network grows as dofs · log dofs: ~70 bytes · dofs · log₂ dofs (measured
    ///   ~1100 bytes per dof at 200 × 200 nodes);
    /// - the record: its thinned trace ([`crate::sim::stored_samples`]) in memory and as JSON
    ///   text (~50 bytes per number with the buffer's growth); figures draw at most
    ///   2000 points per line, a few MB at most.
    ///
    /// Numbers are 8 bytes.
    pub fn estimated_memory_bytes(&self) -> f64 {
        let particles = self.particles() as f64;
        let bonds = self.bonds() as f64;
        let samples = (self.samples + 2) as f64;
        let per_sample = 5.0 + if self.records_displacements() { 4.0 * particles } else { 0.0 };
        let strain = |m: &MovieSpec| if m.bond_strain { bonds } else { 0.0 };
        let frames = self.movie.map_or(0.0, |m| f64::from(m.frames) * (3.0 * particles + strain(&m)));
        let wave = if self.wave().is_some() { 7.0 * 1e5 } else { 0.0 };
        let copies = if self.reference_refinement.is_some() { 2.0 } else { 1.0 };
        let time_loop = 8.0 * copies * (particles * (40.0 + 4.0 * 5.0) + samples * per_sample + frames + wave);
        let omega_max = 8.0 * (10.0 * bonds + 8.0 * particles);
        let dofs = self.static_dofs();
        let static_solve = if dofs > 0.0 { 1200.0 * bonds + 70.0 * dofs * dofs.log2().max(1.0) } else { 0.0 };
        let numbers = self.stored_numbers_per_sample();
        let stored = samples.min(crate::sim::stored_samples(numbers) as f64) * numbers as f64;
        time_loop + omega_max + static_solve + (8.0 + 50.0) * stored
    }

    /// True once dt and steps are decided: always, except a run whose dt `dt_omega_max` sets
    /// before the plan ([`crate::plan`]) decides it. Only planned runs may run.
    pub fn is_planned(&self) -> bool {
        self.dt.is_finite() && self.steps > 0
    }

    /// Sets the time step to `dt` (s) and the step count to cover the same duration.
    pub fn set_dt(&mut self, dt: f64) {
        self.dt = dt;
        self.steps = (self.duration / dt).ceil() as u64;
    }

    /// Chain: how far the walls are moved from the rest length (n + 1) a, ΔW (m); 0 otherwise.
    pub fn chain_wall_extension(&self) -> f64 {
        self.chain().map_or(0.0, |chain| chain.wall_distance - (chain.n + 1) as f64 * self.spacing)
    }

    /// t_c / dt, to 12 significant digits: dt = t_c / 100 divided back gives 99.99999999999999
    /// for some t_c (0.9 s), and no table needs more digits of a step ratio.
    pub fn dt_per_tc(&self) -> f64 {
        let ratio = self.t_c / self.dt;
        format!("{ratio:.11e}").parse().unwrap_or(ratio)
    }

    /// Number of particles the scene simulates (walls included).
    pub fn particles(&self) -> usize {
        match &self.scene_kind {
            KindSpec::Pair(_) => 2,
            KindSpec::Chain(chain) => chain.n + 2,
            KindSpec::Lattice(LatticeRun { lattice: l, .. }) => l.nx * l.ny,
        }
    }

    /// Label of the grid values whose dotted path passes `keep`, e.g.
    /// `restitution=0.5, dt_per_tc=50`; empty when there are none.
    pub fn varied_label(&self, keep: impl Fn(&str) -> bool) -> String {
        let text = |value: &Value| value.as_str().map_or_else(|| value.to_string(), str::to_string);
        let parts: Vec<String> = self
            .varied
            .iter()
            .filter(|(path, _)| keep(path))
            .map(|(path, value)| format!("{}={}", path.rsplit('.').next().unwrap_or(path), text(value)))
            .collect();
        parts.join(", ")
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn dt_per_tc_reads_back_what_was_asked() {
        // dt = t_c/100 divided back is 99.99999999999999 for t_c = 0.9 s (and 1.8, 3.5, ...);
        // the ratio must read back exactly, whatever t_c.
        let yaml = "version: 1\nname: t\nscenes:\n  - {name: p, kind: pair, v0: 1.0, time: {dt_per_tc: 100}}\n";
        let mut spec = crate::spec::parse("t.yaml", yaml).unwrap().runs.remove(0);
        for t_c in [0.9, 1.8, 3.5, spec.t_c] {
            spec.t_c = t_c;
            spec.set_dt(t_c / 100.0);
            assert_eq!(spec.dt_per_tc(), 100.0, "t_c = {t_c}");
        }
    }
}
