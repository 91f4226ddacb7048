//! What every figure module shares: the drawn [`Figure`], and the runs of a scene grouped as
//! the figures and tables show them (by grid values other than dt, each group with the run
//! that represents it).

use serde::Serialize;

use crate::output::{movie_name, side_by_side_name};
use crate::runner::RunRecord;
use crate::sim::{RelaxMethod, RunStatus};
use crate::spec::RunSpec;

/// What a figure shows: the key a finding asks for it by, set where the figure is drawn, so a
/// finding names the figure it wants by what it is rather than by a piece of its file name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FigureKind {
    /// Kinetic, potential and dissipated energy against time (`figures.rs`).
    Energy,
    /// A chain's displacements, one line per particle (`figures.rs`).
    Displacements,
    /// A pair's contact duration and restitution against dt (`figures.rs`).
    Convergence,
    /// E_kin/E_pot against time while a lattice relaxes or a chain's wave spreads (`figures.rs`).
    Relaxation,
    /// Moduli over the continuum's against the lattice size (`figures.rs`).
    Size,
    /// The dissipation time against the damping coefficient, across scenes (`figures.rs`).
    Damping,
    /// The relaxed edge profiles u_x of the left and right edges (`edges.rs`).
    Edges,
    /// The relaxed u_y of the loaded top row (`edges.rs`).
    TopRow,
    /// Error against the time loop's wall time (`precision.rs`).
    WorkPrecision,
    /// Error against dt/t_c (`precision.rs`).
    ErrorDt,
    /// A probe's field against time (`probes.rs`).
    Probe,
    /// Moduli against the load per node, with their power laws (`solids.rs`).
    AgainstLoad,
    /// A chain's stiffness against the wall displacement, with its power law (`solids.rs`).
    AgainstWallDisplacement,
    /// Random lattices' moduli against the kept bond fraction (`solids.rs`).
    Dilution,
    /// The stability map of one integrator (`stability_map.rs`).
    Stability,
    /// The sound speed against the impact speed v0 (`waves.rs`).
    SpeedAgainstV0,
    /// Displacement of every row or particle against time (`waves.rs`).
    SpaceTime,
    /// A pair's overlap δ(t) over the damped oscillator's (`curves.rs`).
    Overlap,
    /// A chain's displacements over its normal-mode sum (`curves.rs`).
    NormalModes,
    /// A damped power-law contact's restitution against v0 (`curves.rs`).
    RestitutionV0,
    /// A power-law contact's duration against v0 (`curves.rs`).
    DurationV0,
    /// A lattice strip's dispersion relation ω(q) over its branches (`curves.rs`).
    Dispersion,
    /// A lattice's relaxation under background damping over its late envelope (`curves.rs`).
    Envelope,
    /// A packing scene's p, z − 4, K and G against φ − φ_J with their power laws (`jamming.rs`).
    Jamming,
    /// A packing scene's G/K against z − 4 with its power law and the theory's (`jamming.rs`).
    JammingRatio,
}

/// A drawn figure.
pub struct Figure {
    /// Scene it belongs to.
    pub scene: String,
    /// What it shows.
    pub kind: FigureKind,
    /// Path relative to the campaign directory (`plots/….svg`); `render` gives it the extension
    /// of the drawn image before it is written (`.png` for a heavy figure, `Image::file_name`).
    pub file: String,
    /// Caption, plain text: the report escapes it (no Markdown of its own).
    pub caption: String,
    /// The drawing: SVG, or PNG when heavy.
    pub image: crate::draw::chart::Image,
}

/// One topic's share of a scene's section (`scene.rs` asks each topic once per scene): the
/// figures it draws and the rows of its tables; a topic that only draws has no rows (`()`).
pub struct Part<Rows = ()> {
    /// The figures, in the order the scene shows them.
    pub figures: Vec<Figure>,
    /// The rows of the topic's tables.
    pub rows: Rows,
}

impl Figure {
    /// The figure as the report shows it.
    pub fn reference(&self) -> FigureRef {
        FigureRef { file: self.file.clone(), caption: self.caption.clone() }
    }
}

/// A figure or movie as the report shows it: its file and caption.
#[derive(Clone, Serialize)]
pub struct FigureRef {
    /// Path relative to the report.
    pub file: String,
    /// Caption, plain text.
    pub caption: String,
}

/// The movies of a scene: its runs side by side if drawn (runs shown side by side have no
/// movie of their own), and each other run's own.
pub fn movie_refs(scene: &str, mine: &[&RunRecord], side_by_side: &[String]) -> Vec<FigureRef> {
    let together = side_by_side.iter().any(|s| s == scene);
    let own = mine.iter().filter(|r| r.has_own_movie());
    together
        .then(|| FigureRef {
            file: side_by_side_name(scene),
            caption: format!("All runs of {scene} side by side, on one colour scale (m/s)."),
        })
        .into_iter()
        .chain(own.map(|r| FigureRef {
            file: movie_name(&r.run_id),
            caption: if r.spec.packing().is_some() {
                packing_movie_caption(scene, r)
            } else {
                format!(
                    "Movie of {scene}{}: particles coloured by speed (colour bar in m/s), {}{}; \
                 displacements are drawn to scale unless the frame states a magnification × M.{}",
                    grid_values(r),
                    match r.spec.movie {
                        Some(movie) if movie.bond_strain => "bonds coloured by strain (red stretched, blue compressed)",
                        _ => "bonds in grey",
                    },
                    supports_in_words(&r.spec),
                    untimed_in_words(&r.spec),
                )
            },
        }))
        .collect()
}

/// A run's grid values in parentheses, after its scene's name in a caption; nothing for a
/// scene without a grid ("Movie of compress ()" had an empty pair).
fn grid_values(r: &RunRecord) -> String {
    let values = r.spec.varied_in_words(|_| true);
    if values.is_empty() { String::new() } else { format!(" ({values})") }
}

/// A packing's movie in words: discs to scale in their periodic box, coloured by their load,
/// the contacts as lines as wide as their force.
fn packing_movie_caption(scene: &str, r: &RunRecord) -> String {
    format!(
        "Movie of {scene}{}: the discs drawn to scale in their periodic box (red), each coloured by its load, \
         the sum of its contact forces Σ|f| (colour bar in N; discs that carry nothing, rattlers among them, dark), and every contact \
         as a black line from centre to centre whose width grows with its force: the force chains that carry the \
         pressure. The scales are those of the frames after the start; the random start's larger overlaps are drawn at full colour \
         and width.{}",
        grid_values(r),
        compression_in_words(r.spec.packing()).unwrap_or_else(|| untimed_in_words(&r.spec).to_string()),
    )
}

/// A slowly compressed packing's frames in words; `None` for a packing made at its fraction.
fn compression_in_words(packing: Option<&crate::spec::PackingSpec>) -> Option<String> {
    let packing = packing?;
    let compression = packing.compression?;
    Some(format!(
        " A slow compression, one frame per state, not a motion: the random start at φ = {:.4}, then the packing \
         relaxed there and after each of {} equal steps of φ up to {:.4}, its box (red) shrinking with it \
         (captioned). A relaxed packing below its jamming point carries no force: its lines appear at the stage where it jams.",
        compression.from, compression.steps, packing.fraction
    ))
}

/// What the frames of a run with no time show (a minimiser or the static solve): two states,
/// not a motion.
fn untimed_in_words(spec: &RunSpec) -> &'static str {
    match spec.relax().map(|r| r.method) {
        Some(method) if method.is_minimiser() => {
            " The minimiser has no time: two frames, the start and the state it stopped at (captioned)."
        }
        Some(RelaxMethod::Static) => " The static solve has no time: two frames, the start and the static answer.",
        _ => "",
    }
}

/// How a movie draws what holds the scene: a chain's walls, a lattice's held nodes.
fn supports_in_words(spec: &RunSpec) -> &'static str {
    match spec.lattice() {
        None if spec.chain().is_some() => ", the walls at both ends as black bars",
        Some(lattice) if !lattice.supports.holds_nothing() => {
            ", held nodes as black squares (filled: held in x and y, open: held in one axis)"
        }
        _ => "",
    }
}

/// The background damping γ_g (N s/m) a run ran with: `damping.background: critical` leaves 0
/// in the spec (γ_crit = 2√(k_min m) needs k_min, which only the static answer gives) and the
/// run records the value it used in `gamma_background_critical`.
pub fn background_gamma(r: &RunRecord) -> f64 {
    r.metrics.lattice.gamma_background_critical.unwrap_or(r.spec.gamma_background)
}

/// A run relaxed by bond damping γ alone (no background damping).
pub fn bond_damping_only(r: &RunRecord) -> bool {
    r.spec.gamma > 0.0 && background_gamma(r) == 0.0
}

/// A run relaxed by background damping γ_g alone (no bond damping).
pub fn background_damping_only(r: &RunRecord) -> bool {
    r.spec.gamma == 0.0 && background_gamma(r) > 0.0
}

/// A run relaxed by background damping γ_g added to bond damping γ.
pub fn both_dampings(r: &RunRecord) -> bool {
    r.spec.gamma > 0.0 && background_gamma(r) > 0.0
}

/// The label of a run's grid values other than the time step: runs with the same group label
/// differ only in dt, so they form one convergence curve.
pub fn group_label(record: &RunRecord) -> String {
    let label = record.spec.varied_in_words(|path| !path.starts_with("time.dt"));
    if label.is_empty() { "all".into() } else { label }
}

/// The runs of `scene` that are `ok`, grouped by [`group_label`] in campaign order.
pub fn groups<'a>(records: &'a [RunRecord], scene: &str) -> Vec<(String, Vec<&'a RunRecord>)> {
    let mut groups: Vec<(String, Vec<&RunRecord>)> = Vec::new();
    for record in records.iter().filter(|r| r.spec.scene == scene && r.status == RunStatus::Ok) {
        let label = group_label(record);
        match groups.iter_mut().find(|(l, _)| *l == label) {
            Some((_, members)) => members.push(record),
            None => groups.push((label, vec![record])),
        }
    }
    groups
}

/// The run of a group whose dt is closest to t_c/50 (the coursework's choice).
pub fn representative<'a>(members: &[&'a RunRecord]) -> &'a RunRecord {
    let distance = |r: &&RunRecord| (r.spec.dt_per_tc().ln() - 50f64.ln()).abs();
    members.iter().copied().min_by(|a, b| distance(a).total_cmp(&distance(b))).expect("groups are never empty")
}
