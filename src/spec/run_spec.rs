//! One fully resolved run: every parameter explicit, in SI units, hashable.

use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::collections::BTreeMap;

use super::kind::{ChainRun, KindSpec, LatticeSpec};
use super::raw::{SceneKind, SeriesKept};
use super::shared::{Deformation, RelaxSpec, WaveSpec};
use crate::model::LawSpec;
use crate::sim::IntegratorKind;

/// Bumped whenever stored results of an unchanged spec would differ (new physics or columns),
/// so the cache never serves results of older code.
pub const RESULT_FORMAT: u32 = 11;

/// A resolved run. Units SI. Serialised flat (by `flat.rs`): the kind as the tag `kind` with
/// every kind's fields beside it, the keys being the results table's column names.
#[derive(Clone, Debug, PartialEq)]
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
    /// Which sampled series the run's files keep (`output.series`): stored with the run, not
    /// part of its id ([`RunSpec::run_id`]).
    pub series: SeriesKept,
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

    /// Why `spec` cannot start within this budget, if it cannot; naming `output.series: full`
    /// when the run would fit with its default series.
    pub fn refuses(&self, spec: &RunSpec) -> Option<String> {
        let memory = spec.estimated_memory_bytes();
        if memory <= self.memory_per_run {
            return None;
        }
        let mut why = format!(
            "the run would hold about {:.0} MB, beyond the budget of {:.0} MB per run (budget.memory_per_run_mb)",
            memory / 1e6,
            self.memory_per_run / 1e6
        );
        let default = RunSpec { series: SeriesKept::Default, ..spec.clone() }.estimated_memory_bytes();
        if spec.series == SeriesKept::Full && default <= self.memory_per_run {
            why += &format!(
                ", of which about {:.0} MB its series kept whole (output.series: full, every particle at every \
                 sample); keep the default series, record fewer time.samples or raise the budget",
                (memory - default) / 1e6
            );
        }
        Some(why)
    }

    /// Why `spec` is expected to exceed this budget, if it is (the plan's warning).
    pub fn warning(&self, spec: &RunSpec) -> Option<String> {
        self.refuses(spec).or_else(|| {
            let seconds = spec.estimated_seconds();
            (seconds > self.seconds_per_run).then(|| {
                format!(
                    "estimated {} s, beyond the budget of {} s per run (budget.seconds_per_run)",
                    seconds_words(seconds),
                    seconds_words(self.seconds_per_run)
                )
            })
        })
    }
}

/// Seconds in a message: whole above 10 s, to the millisecond below (a budget of 0.05 s was
/// written 0 s).
fn seconds_words(seconds: f64) -> String {
    if seconds >= 10.0 { format!("{seconds:.0}") } else { format!("{seconds:.3}") }
}

/// `seconds` (finite, ≥ 0) as a duration, capped at 1e9 s so that adding it to now never
/// overflows an `Instant`.
pub fn seconds_up_to_1e9(seconds: f64) -> std::time::Duration {
    std::time::Duration::from_secs_f64(seconds.min(1e9))
}

/// Networks with more bonds ([`RunSpec::bonds`]) than this get their modes from a node-by-node
/// bound in one pass (`plan::stability::node_bound`) instead of the Lanczos method, whose up to
/// 1000 steps (and as many again for the eigenvector) over 250 000 bonds take seconds and grow
/// with the network (a 2000 × 2000 lattice took 170 s and 1.7 GB under the power method before
/// `plan` printed anything). Every shipped campaign stays below it (its largest lattice,
/// 40 × 40, has 6 400 bonds; Lanczos converges there in 60–250 steps).
pub const LANCZOS_BONDS: usize = 250_000;

/// The extension (m) at which a power-law spring (no stiffness at δ = 0) is linearised for
/// t_c, the damping and the stability estimate: the deformation the run is expected to reach.
/// A collision or kick at speed v: the two-body overlap −δ_max(v); a loaded lattice: the
/// extension (F/C)^(1/β) of a spring carrying one node's load F (velocity control: strain · a);
/// a relaxing chain: its springs' equilibrium extension ΔW/(n + 1); a hit chain between moved
/// walls: that extension plus the collision's overlap. Linear springs: 0.
pub fn reference_extension(spec: &RunSpec) -> f64 {
    let LawSpec::Power { beta } = spec.law else {
        return 0.0;
    };
    match spec.deformation() {
        Deformation::Collision(speed) => -crate::theory::power_law_max_overlap(spec.k, beta, spec.mass, speed),
        Deformation::Carrying(force) => (force.abs() / spec.k).powf(1.0 / beta),
        Deformation::Extension(extension) => extension,
        Deformation::PreStressed { extension, speed } => {
            let overlap = crate::theory::power_law_max_overlap(spec.k, beta, spec.mass, speed);
            // Contacts held apart are slack: the particles fly free and then collide.
            // Otherwise the kick adds its overlap to the pre-stress: the stiffest the springs
            // get is at |δ| + δ_max (compressed when δ ≤ 0).
            if spec.contact && extension > 0.0 {
                -overlap
            } else if extension > 0.0 {
                extension + overlap
            } else {
                extension - overlap
            }
        }
    }
}

/// `relax.residual_force` below this many times the round-off of the static force
/// ([`force_resolution`]) is refused: on a 20 × 20 steel block (k = 2e9 N/m, damped MD)
/// criteria at 5 times the round-off ran to `max_tc`, and at 10 times stopped.
pub const RESIDUAL_OVER_ROUND_OFF: f64 = 10.0;

/// The round-off of a loaded lattice's static force on one degree of freedom (N), from the
/// resolution of its positions: a coordinate of size X (m) is held to ε X, so a spring between
/// two nodes of the block (X = [`LatticeSpec::extent`]) is known to ε X in length, and its
/// force to ε X times its tangent stiffness k_t at the extension the load gives it
/// ([`reference_extension`]; k for linear springs, of the stiffest family). No minimiser or
/// time step takes a residual below this, whatever the load. `None` for other scenes and for
/// static-only runs (solved in displacements, which carry no such floor).
pub fn force_resolution(spec: &RunSpec) -> Option<f64> {
    let l = spec.lattice().filter(|l| l.impulse.is_none() && !spec.static_only())?;
    let stiffest = l.k_x.max(l.k_y).max(l.k_diag);
    let extent = l.extent(spec.spacing);
    let tangent = match spec.law {
        LawSpec::Linear => stiffest,
        LawSpec::Power { beta } => {
            let extension = match spec.deformation() {
                Deformation::Carrying(force) => (force.abs() / stiffest).powf(1.0 / beta),
                _ => reference_extension(spec),
            };
            beta * stiffest * extension.abs().powf(beta - 1.0)
        }
    };
    Some(f64::EPSILON * extent * tangent)
}

/// Why the static forces of `spec` carry the round-off `floor` (N, [`force_resolution`]), in
/// words for the messages that name it.
pub fn round_off_words(spec: &RunSpec, floor: f64) -> String {
    format!(
        "the positions, up to X = {:.3e} m, are held to ε X, which leaves every static force uncertain by about \
         {floor:.2e} N (ε X times the stiffest spring's tangent stiffness)",
        spec.lattice().map_or(0.0, |l| l.extent(spec.spacing))
    )
}

impl RunSpec {
    /// The deformation the run is expected to reach, which a power law's t_c, damping and
    /// stability estimate are taken at ([`reference_extension`]).
    pub fn deformation(&self) -> Deformation {
        self.scene_kind.deformation(self.spacing, self.v0)
    }

    /// Stable identifier: the scene name and a content hash of the resolved run, its numbers in
    /// one form (`-0.0` as `0`, `50.0` as `50`), so runs with the same physics share one id.
    /// `output.series` is left out: it changes which series the run's files keep, not its
    /// results, so switching it keeps the run's id (the runner simulates the run again for
    /// the files asked for).
    pub fn run_id(&self) -> String {
        let mut value = serde_json::to_value((RESULT_FORMAT, self)).expect("a RunSpec always serialises");
        if let Some(flat) = value.get_mut(1).and_then(Value::as_object_mut) {
            flat.remove("series");
        }
        let hash = blake3::hash(super::grid::canonical(&value).to_string().as_bytes()).to_hex();
        format!("{}-{}", self.scene, &hash[..12])
    }

    /// Cost model of the run in a release build (s), from `mdsolids bench` and the coursework
    /// campaign on the project machine: ~80 ns per step for the loop itself and the per-step
    /// probes, plus ~3 ns per particle-step (the reference lattice runs at ~330 million
    /// particle-steps/s) and force evaluation, for the run and its reference run, if any; a
    /// minimiser (`relax.method: fire | cg`) takes [`RunSpec::minimiser_evaluations`] of ~8 ns
    /// per particle instead (2.7 × an MD step: the power, mixing and norms of FIRE, CG's line
    /// search, each one more pass over the particles), not its cap `steps` (a packing's: its cap,
    /// once per stage of a slow compression); plus
    /// the stages around the loop: the ω_max estimate (1000 Lanczos steps at ~7 ns per
    /// bond, twice with bond dashpots: the cap of the eigenvalue's pass, where the shipped
    /// lattices take 60–250 steps and as many again for the eigenvector; one pass beyond [`LANCZOS_BONDS`]), a loaded
    /// lattice's static solve (sparse Cholesky of a 2D network: 3.5e-7 s · dofs^1.33, fitted to
    /// whole `relax.method: static` runs of 160² … 1000² nodes, 0.61 s … 81 s on one core), twice
    /// over when k_min is found as well (a second factorisation at the static answer) and the
    /// movie's GIF encoding (~0.2 µs per pixel and frame; faer and the GIF encoder are built
    /// without optimisation, see Cargo.toml). A static-only run has no loop and no ω_max.
    pub fn estimated_seconds(&self) -> f64 {
        let evaluations = self.integrator.evaluations_per_step() as f64;
        let particles = self.particles() as f64;
        // A reference run at dt/R takes R times as many steps.
        let runs = 1.0 + self.reference_refinement.map_or(0.0, f64::from);
        let stepped = if self.static_only() { 0.0 } else { 1.0 };
        // A slowly compressed packing relaxes once per stage.
        let stages = self.packing().map_or(1.0, |p| p.stage_fractions().len() as f64);
        // FIRE in the stiffness's metric solves with its factor at every evaluation: ~2.8e-7 s
        // per degree of freedom (0.20 s at 600², 0.57 s at 1000²).
        let solve = if self.is_preconditioned() { 2.8e-7 * self.static_dofs() } else { 0.0 };
        let time_loop = match self.minimiser_evaluations() {
            Some(minimiser) => runs * minimiser * (80e-9 + 8e-9 * particles + solve),
            None => stages * stepped * runs * self.steps as f64 * (80e-9 + 3e-9 * evaluations * particles),
        };
        let eigenproblems = if self.gamma > 0.0 { 2.0 } else { 1.0 };
        let passes = if self.bonds() > LANCZOS_BONDS { 1.0 } else { 1000.0 };
        let omega_max = stepped * eigenproblems * passes * 7e-9 * self.bonds() as f64;
        let static_solve = (1.0 + stepped) * 3.5e-7 * self.static_dofs().powf(1.33);
        let movie = self.movie.map_or(0.0, |m| 0.2e-6 * f64::from(m.frames) * f64::from(m.width) * f64::from(m.height));
        time_loop + omega_max + static_solve + movie
    }

    /// Force evaluations a minimiser (`relax.method: fire | cg`) is expected to take to its
    /// displacement bound, capped at `steps` (`relax.max_tc`); `None` for any other run, and
    /// for a network that may be floppy (bonds cut) with `relax.residual_force` given: that
    /// fallback took 10–300 × as many, erratically (14 000 – 630 000 at 20 … 160 rows), so the
    /// cap stands. Fitted to runs of `campaigns/relax-methods.yaml`'s steel block (docs/performance.md), n rows along the load:
    /// - at tolerance 1e-4 under tension, FIRE 8.5 · n^1.04 (n = 20 … 1000) but at least 250
    ///   (319 at n = 10, 232 at 20: it first spends ~45 steps growing its step from dt to
    ///   Δt_max), and CG 4.7 · n^1.25 (n = 10 … 320), each within 1.4 × of every measured count;
    /// - times ln(1/tol)/ln(1e4): both converge linearly, so each decade of tolerance costs the
    ///   same (1e-6 took 1.2–1.9 × the evaluations of 1e-4; this says 1.5);
    /// - times 2.5 in shear (FIRE 2.0 ×, CG 3.1 ×);
    /// - FIRE times max(1, (t_c/dt)/100): its largest step Δt_max = 10 dt sets its count, which
    ///   grows as t_c/dt once Δt_max is well inside the stability limit 2/ω_max (2.2 × from
    ///   t_c/100 to t_c/200); at coarser dt it restarts near that limit and takes as many as at
    ///   t_c/100. Below t_c/50 it thrashes (t_c/25: 28 × t_c/50's); not modelled.
    /// - FIRE in the stiffness's metric (`relax.preconditioner: stiffness`) 25, whatever the
    ///   size and load case: 17–18 under tension and 17–25 in shear on 12² … 300² linear blocks
    ///   (the only springs it takes: Hertz blocks, measured before the spec refused them with
    ///   it, took 30–35 and 73–75).
    pub fn minimiser_evaluations(&self) -> Option<f64> {
        let (relax, lattice) = (self.relax()?, self.lattice()?);
        let (scale, exponent, floor) = match relax.method {
            crate::sim::RelaxMethod::Fire if self.is_preconditioned() => (25.0, 0.0, 0.0),
            crate::sim::RelaxMethod::Fire => (8.5, 1.04, 250.0),
            crate::sim::RelaxMethod::Cg => (4.7, 1.25, 0.0),
            _ => return None,
        };
        if lattice.cut_fraction > 0.0 && relax.residual_force.is_some() {
            return None;
        }
        let tolerance = relax.tolerance.unwrap_or(super::shared::DEFAULT_TOLERANCE);
        let decades = tolerance.recip().ln() / 1e4f64.ln();
        // The metric is FIRE's only (the spec refuses it with any other method).
        let preconditioned = self.is_preconditioned();
        let shear = if lattice.load_case == super::raw::LoadCase::Shear && !preconditioned { 2.5 } else { 1.0 };
        let by_masses = relax.method == crate::sim::RelaxMethod::Fire && !preconditioned;
        let coarse_steps = if by_masses { (self.dt_per_tc() / 100.0).max(1.0) } else { 1.0 };
        let evaluations = scale * (lattice.ny as f64).powf(exponent) * decades * shear * coarse_steps;
        Some(evaluations.max(floor).min(self.steps as f64))
    }

    /// True when FIRE moves in the metric of the network's stiffness
    /// (`relax.preconditioner: stiffness`).
    pub fn is_preconditioned(&self) -> bool {
        self.relax().is_some_and(|r| r.preconditioner != crate::sim::PreconditionerKind::None)
    }

    /// Springs of the run's network: at most one per node and bond family in a lattice (cut
    /// bonds counted), n + 1 in a chain, one in a pair.
    pub fn bonds(&self) -> usize {
        self.scene_kind.bonds()
    }

    /// Degrees of freedom of the static problem solved beside MD (a loaded lattice): two per
    /// node (held ones counted); 0 when there is none.
    fn static_dofs(&self) -> f64 {
        self.scene_kind.static_dofs() as f64
    }

    /// Numbers per sample of what a record stores of the trace: time and four energies, and
    /// four per particle (a chain) or per probed node (a lattice's kicked column and probes).
    fn stored_numbers_per_sample(&self) -> usize {
        5 + 4 * self.scene_kind.stored_nodes()
    }

    /// True when the run records every particle's displacement and velocity at every sample:
    /// chains (normal modes, space–time), reference runs, waves, impulse and probed lattices,
    /// and every run that keeps its full series (`output.series: full`).
    pub fn records_displacements(&self) -> bool {
        self.scene_kind.records_displacements()
            || self.reference_refinement.is_some()
            || self.wave().is_some()
            || self.series == SeriesKept::Full
    }

    /// Numbers the run's stored series hold over `samples` samples: thinned within
    /// [`crate::sim::stored_samples`] by default; with `output.series: full` time, energies and
    /// four per particle at every sample.
    fn stored_numbers(&self, samples: f64) -> f64 {
        match self.series {
            SeriesKept::Default => {
                let numbers = self.stored_numbers_per_sample();
                samples.min(crate::sim::stored_samples(numbers) as f64) * numbers as f64
            }
            SeriesKept::Full => samples * (5.0 + 4.0 * self.particles() as f64),
        }
    }

    /// Estimated peak memory (bytes) of the run over all its stages, summed (an upper bound:
    /// the stages' transient parts do not overlap), from what they allocate:
    /// - the time loop: per particle ~40 numbers of state, integrator history and forces plus
    ///   ~4 bonds of 5 numbers; per sample 5 numbers, and when displacements are recorded 4
    ///   rows of one number per particle and ~7 of the row's own (header and allocation); 3 per particle per movie frame (and one per bond with bond strain); a
    ///   wave probe's at most 10⁵ entries of 7 numbers; a reference run holds its own copy;
    /// - the ω_max estimate: two lists of 5 numbers per bond and ~8 vectors over the particles;
    /// - a loaded lattice's static solve: ~800 bytes per bond (the stiffness entries, 16 of
    ///   24 bytes per bond, and faer's sorted copy) and the Cholesky factor, whose fill
    ///   on a 2D network grows as dofs · log dofs: ~70 bytes · dofs · log₂ dofs (measured
    ///   ~1100 bytes per dof at 200 × 200 nodes), kept through the loop by FIRE in the
    ///   stiffness's metric;
    /// - the record: its stored series ([`RunSpec::stored_numbers`]: thinned, or every sample
    ///   with `output.series: full`) in memory and as they are written (~50 bytes per number:
    ///   a Parquet table's columns, pages and file, and the copy a full run's record keeps of
    ///   what the report draws); figures draw at most 2000 points per line, a few MB at most.
    ///
    /// Numbers are 8 bytes.
    pub fn estimated_memory_bytes(&self) -> f64 {
        let particles = self.particles() as f64;
        let bonds = self.bonds() as f64;
        let samples = (self.samples + 2) as f64;
        // Four rows per sample (u and v along x and y), each a Vec: its particles' numbers and
        // ~7 more, the 24-byte header and the allocator's ~32 bytes, which a pair's 2 are not.
        let per_sample = 5.0 + if self.records_displacements() { 4.0 * (particles + 7.0) } else { 0.0 };
        let strain = |m: &MovieSpec| if m.bond_strain { bonds } else { 0.0 };
        let frames = self.movie.map_or(0.0, |m| f64::from(m.frames) * (3.0 * particles + strain(&m)));
        let wave = if self.wave().is_some() { 7.0 * 1e5 } else { 0.0 };
        let copies = if self.reference_refinement.is_some() { 2.0 } else { 1.0 };
        let time_loop = 8.0 * copies * (particles * (40.0 + 4.0 * 5.0) + samples * per_sample + frames + wave);
        let omega_max = 8.0 * (10.0 * bonds + 8.0 * particles);
        let dofs = self.static_dofs();
        let static_solve = if dofs > 0.0 { 800.0 * bonds + 70.0 * dofs * dofs.log2().max(1.0) } else { 0.0 };
        time_loop + omega_max + static_solve + (8.0 + 50.0) * self.stored_numbers(samples)
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
        self.chain().map_or(0.0, |chain| chain.wall_extension(self.spacing))
    }

    /// t_c / dt, to 12 significant digits: dt = t_c / 100 divided back gives 99.99999999999999
    /// for some t_c (0.9 s), and no table needs more digits of a step ratio.
    pub fn dt_per_tc(&self) -> f64 {
        let ratio = self.t_c / self.dt;
        format!("{ratio:.11e}").parse().unwrap_or(ratio)
    }

    /// Number of particles the scene simulates (walls included).
    pub fn particles(&self) -> usize {
        self.scene_kind.particles()
    }

    /// The scene kind.
    pub fn kind(&self) -> SceneKind {
        self.scene_kind.kind()
    }

    /// A chain's fields; `None` for other kinds.
    pub fn chain(&self) -> Option<&ChainRun> {
        self.scene_kind.chain()
    }

    /// A lattice scene's lattice; `None` for other kinds.
    pub fn lattice(&self) -> Option<&LatticeSpec> {
        self.scene_kind.lattice()
    }

    /// A packing scene's packing; `None` for other kinds.
    pub fn packing(&self) -> Option<&super::kind::PackingSpec> {
        self.scene_kind.packing()
    }

    /// When the relaxation of a loaded lattice or a relaxing chain stops; `None` otherwise.
    pub fn relax(&self) -> Option<RelaxSpec> {
        self.scene_kind.relax()
    }

    /// A loaded lattice set to its static answer, which runs no MD (`relax.method: static`).
    pub fn static_only(&self) -> bool {
        self.relax().is_some_and(|r| r.method == crate::sim::RelaxMethod::Static)
    }

    /// The timed wave of a chain or an impulse lattice, if asked for.
    pub fn wave(&self) -> Option<&WaveSpec> {
        self.scene_kind.wave()
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

    /// The grid values whose dotted path passes `keep`, in the words of physics (`r = 0.5`,
    /// `γ_g = 3000 N s/m`, `40 × 40`) rather than the campaign's YAML keys: figure legends and
    /// movie titles. Empty when none.
    pub fn varied_in_words(&self, keep: impl Fn(&str) -> bool) -> String {
        let parts: Vec<String> =
            self.varied.iter().filter(|(path, _)| keep(path)).map(|(path, value)| physics_words(path, value)).collect();
        parts.join(", ")
    }
}

/// One grid value in words: the symbol of its quantity with its unit.
fn physics_words(path: &str, value: &Value) -> String {
    let text = value.as_str().map_or_else(|| value.to_string(), str::to_string);
    let symbol = match path {
        "damping.restitution" => "r",
        // `critical` is a word (2 m ω_min, decided per run), not a number of N s/m.
        "damping.background" if value.is_string() => return format!("γ_g = {text}"),
        "damping.background" => return format!("γ_g = {text} N s/m"),
        "time.dt_per_tc" => return format!("dt = t_c/{text}"),
        "time.integrator" | "material.law" | "load.case" => return text,
        "lattice.diagonals" if text == "none" => return "no diagonals".into(),
        "lattice.diagonals" => return format!("{text} diagonals"),
        "lattice.size" => return format!("{text} × {text}"),
        "supports" => return format!("{text} supports"),
        "load.per_node" => return format!("F = {text} N per node"),
        "v0" => return format!("v0 = {text} m/s"),
        "impulse.velocity" => return format!("kick {text} m/s"),
        "wall_distance" => return format!("W = {text} m"),
        "relax.residual_force" if value.is_null() => return "energy criterion".into(),
        "relax.residual_force" => return format!("force criterion {text}"),
        "lattice.k_diag_ratio" => "k_d/k",
        "lattice.k_y_ratio" => "k_y/k",
        "lattice.cut_fraction" => "cut fraction",
        "lattice.stiffness_spread" => "spread w",
        "packing.fraction" => "φ",
        "packing.n" => "N",
        other => other.rsplit('.').next().unwrap_or(other),
    };
    format!("{symbol} = {text}")
}
