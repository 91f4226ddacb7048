//! The campaign summary: power-law fits y ∝ x^p of every quantity a scene sweeps, computed once
//! from the records and handed to both `summary.csv` (`table`) and the report.

pub mod jamming;

use crate::measure::{PowerLawFit, power_law_fit};
use crate::runner::RunRecord;
use crate::sim::RunStatus;

/// The exponent predicted for a quantity fitted against `against` with springs s ∝ δ^β: the
/// stiffness ds/dδ ∝ δ^(β−1) makes a chain's stiffness ∝ |ΔW|^(β−1), a lattice's moduli under
/// a load F ∝ δ^β scale as F^((β−1)/β), and the solitary wave of a chain without pre-load
/// travels at V ∝ v0^((β−1)/(β+1)) (Nesterenko); all 0 for linear springs (β = 1). A packing's
/// scalings near jamming depend on the quantity too ([`jamming::predicted`]). With the formula
/// in β.
pub fn predicted(quantity: &str, against: &str, beta: f64) -> Option<(f64, &'static str)> {
    match against {
        "v0" => Some(((beta - 1.0) / (beta + 1.0), "(β−1)/(β+1)")),
        "load_per_node" => Some(((beta - 1.0) / beta, "(β−1)/β")),
        "wall_displacement" => Some((beta - 1.0, "β−1")),
        _ => jamming::predicted(quantity, against, beta),
    }
}

/// A scaling law the summary fits, y ∝ x^p, over the runs of one scene that differ only in
/// the grid paths `paths`.
struct Scaling {
    quantity: &'static str,
    against: &'static str,
    paths: &'static [&'static str],
    x: fn(&RunRecord) -> Option<f64>,
    y: fn(&RunRecord) -> Option<f64>,
}

/// The impact speed of a chain wave or the kick speed of an impulse lattice (m/s).
fn excitation_speed(r: &RunRecord) -> Option<f64> {
    r.spec.wave()?;
    // A chain whose walls pre-load its springs has a linear sound speed √(s′(δ₀)/m) a: its front
    // is no solitary wave, and no exponent against v0 is predicted for it (nor fitted).
    if r.spec.chain().is_some_and(|c| crate::study::chain::is_preloaded(&r.spec, c)) {
        return None;
    }
    match r.spec.lattice().and_then(|l| l.impulse) {
        Some(i) if i.top_row_force.is_none() => Some(i.vx.hypot(i.vy)),
        Some(_) => None,
        None => Some(r.spec.v0),
    }
}

/// The load per top-row node of a force-loaded lattice (N).
fn load(r: &RunRecord) -> Option<f64> {
    r.spec.lattice().and_then(|l| l.force_per_node())
}

/// |ΔW| of a relaxing chain (m).
fn wall_displacement(r: &RunRecord) -> Option<f64> {
    r.spec.chain().and_then(|c| c.relax).map(|_| r.spec.chain_wall_extension().abs())
}

const SPEED: &[&str] = &["v0", "impulse.velocity"];
/// The grid path of the load per node: a load sweep's runs differ in it alone.
pub const LOAD: &[&str] = &["load.per_node"];
const WALLS: &[&str] = &["wall_distance"];

/// Every scaling law the summary looks for.
const SCALINGS: [Scaling; 7] = [
    Scaling {
        quantity: "sound_speed",
        against: "v0",
        paths: SPEED,
        x: excitation_speed,
        y: |r| r.metrics.recommended_sound_speed(),
    },
    Scaling {
        quantity: "youngs_modulus",
        against: "load_per_node",
        paths: LOAD,
        x: load,
        y: |r| r.metrics.lattice.youngs_modulus,
    },
    Scaling {
        quantity: "youngs_modulus_tangent",
        against: "load_per_node",
        paths: LOAD,
        x: load,
        y: |r| r.metrics.lattice.youngs_modulus_tangent,
    },
    Scaling {
        quantity: "shear_modulus",
        against: "load_per_node",
        paths: LOAD,
        x: load,
        y: |r| r.metrics.lattice.shear_modulus,
    },
    Scaling {
        quantity: "shear_modulus_tangent",
        against: "load_per_node",
        paths: LOAD,
        x: load,
        y: |r| r.metrics.lattice.shear_modulus_tangent,
    },
    Scaling {
        quantity: "secant_stiffness",
        against: "wall_displacement",
        paths: WALLS,
        x: wall_displacement,
        y: |r| r.metrics.chain.secant_stiffness,
    },
    Scaling {
        quantity: "tangent_stiffness",
        against: "wall_displacement",
        paths: WALLS,
        x: wall_displacement,
        y: |r| r.metrics.chain.tangent_stiffness,
    },
];

/// How one measured quantity of one group of runs (a scene's runs that differ only in the
/// swept parameter) scales with it: y ∝ x^p.
#[derive(Clone, Debug, PartialEq)]
pub struct ScalingFit {
    /// Scene.
    pub scene: String,
    /// The group's other grid values.
    pub group: String,
    /// Elastic law of the group.
    pub law: &'static str,
    /// The springs' exponent β of the group's runs (force ∝ δ^β; 1 for linear springs): the
    /// law its exponent is predicted from ([`predicted`]).
    pub beta: f64,
    /// The measured quantity (a results column).
    pub quantity: &'static str,
    /// What it is plotted against (`v0`, `load_per_node`, `wall_displacement`; a packing's
    /// `fraction_excess` Δφ or `coordination_excess` z − 4, [`jamming::fits`]).
    pub against: &'static str,
    /// (x, y) of its ok runs, sorted by x.
    pub points: Vec<(f64, f64)>,
    /// The fit.
    pub fit: PowerLawFit,
    /// Particles of each of the group's runs (a packing's discs, a lattice's nodes): a
    /// packing's scalings are judged on a scene's largest N only ([`jamming::EXPONENT_TOLERANCE`]).
    pub particles: usize,
}

impl ScalingFit {
    /// The fit `fit` of `quantity` against `against` over the `points` of one group of runs,
    /// labelled `group`, whose first run is `first`: the scene and law are the first run's, one
    /// for the whole group ([`scene_groups`]).
    fn of(
        first: &RunRecord,
        group: String,
        (quantity, against): (&'static str, &'static str),
        points: Vec<(f64, f64)>,
        fit: PowerLawFit,
    ) -> ScalingFit {
        let law = first.spec.law;
        ScalingFit {
            scene: first.spec.scene.clone(),
            group,
            law: law.name(),
            beta: law.beta(),
            quantity,
            against,
            points,
            fit,
            particles: first.spec.particles(),
        }
    }
}

/// `items` of runs in groups of one scene whose runs differ only in the grid paths `swept`: each
/// group's first run, its label (its other grid values) and its items, in campaign order. A
/// group has one spring law, so that its fit has one β to be held against: a law the grid
/// varies is in the label, and runs whose laws differ under one label (a law no grid value
/// sets) are kept apart all the same.
fn scene_groups<'a, T>(
    items: impl IntoIterator<Item = (&'a RunRecord, T)>,
    swept: &[&str],
) -> Vec<(&'a RunRecord, String, Vec<T>)> {
    let mut groups: Vec<(&RunRecord, String, Vec<T>)> = Vec::new();
    for (r, item) in items {
        let label = r.spec.varied_label(|path| !swept.contains(&path));
        let same = |first: &RunRecord| first.spec.scene == r.spec.scene && first.spec.law == r.spec.law;
        match groups.iter_mut().find(|(first, l, _)| same(first) && *l == label) {
            Some((_, _, members)) => members.push(item),
            None => groups.push((r, label, vec![item])),
        }
    }
    groups
}

/// The power-law fits of every quantity that a scene sweeps over at least two values: the
/// sound speed against v0, moduli against the load, a chain's stiffness against |ΔW|.
pub fn scaling_fits(records: &[RunRecord]) -> Vec<ScalingFit> {
    let mut fits = Vec::new();
    for scaling in &SCALINGS {
        let points = records
            .iter()
            .filter(|r| r.status == RunStatus::Ok)
            .filter_map(|r| Some((r, (scaling.x)(r).zip((scaling.y)(r))?)));
        fits.extend(scene_groups(points, scaling.paths).into_iter().filter_map(|(first, group, mut points)| {
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let fit = power_law_fit(&points)?;
            Some(ScalingFit::of(first, group, (scaling.quantity, scaling.against), points, fit))
        }));
    }
    fits
}
