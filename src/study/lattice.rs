//! The lattice: an nx × ny spring network on its supports, loaded (force or velocity control,
//! relaxed to its moduli) or kicked (a wave). Its scene, its static answer (linear and
//! non-linear, `fem`), its continuum moduli and sound speeds, and its measurement.

use serde::{Deserialize, Serialize};

use std::collections::HashMap;
use std::sync::Arc;
use std::time::Instant;

use super::columns::{Block, Column, Row, Slot};
use super::common::{Stopped, relaxation, scene, sound_speed};
use crate::fem::{Answers, Shared, Solver, StaticAnswer, StaticSolution, Truss};
use crate::measure::{
    LatticeShape, anisotropic_moduli, constrained_modulus_y, constrained_shear_modulus, extension_error_allowed,
    homogeneity, lattice_constants, modulus_error_bound, network_constants, plane_wave_speeds, power_law_poisson_ratio,
    row_extension, row_extension_weights, shear_modulus, tensile_moduli,
};
use crate::model::{Axes, Bonds, Edges, ForceLaw, LatticeType, LawSpec, LawVisitor, Layout, Particles, SquareLattice};
use crate::sim::{Drive, Load, Network, Outcome, ProbeTrace, Relaxation, Scene, SharedPreconditioner, Trace};
use crate::spec::{
    Control, Diagonals, LatticeSpec, LoadCase, ProbeLine, RESIDUAL_OVER_ROUND_OFF, RunSpec, Supports, force_resolution,
    reference_extension, round_off_words,
};
use crate::theory::critical_damping;

/// What a lattice measures, with its static and continuum twins.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LatticeMetrics {
    /// Lattice, tensile: Young's modulus E (Pa) of the relaxed MD lattice.
    pub youngs_modulus: Option<f64>,
    /// Lattice, tensile: ν = −(ΔL_x/L_x)/(ΔL_y/L_y).
    pub poisson_ratio: Option<f64>,
    /// Lattice, tensile: the coursework's ΔL_x/ΔL_y.
    pub poisson_ratio_coursework: Option<f64>,
    /// Lattice, shear: shear modulus G (Pa).
    pub shear_modulus: Option<f64>,
    /// Lattice: largest deviation of the side columns from straight lines, relative to their
    /// mean lateral displacement.
    pub homogeneity: Option<f64>,
    /// Lattice: largest difference between the non-linear and the linear static answers,
    /// relative for E and G, absolute for ν (how far the load is from the linear regime).
    pub static_nonlinearity: Option<f64>,
    /// Lattice: ‖R‖/‖f‖ where the static solve's Newton–Raphson iteration stopped, the
    /// out-of-balance force left over the load (at most 1e-12 unless round-off ended it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub static_residual: Option<f64>,
    /// Lattice: the steps the static solve took down the potential energy from states whose
    /// tangent stiffness was not positive definite (`fem::Solver::descend`): 0 where Newton–
    /// Raphson alone found the answer; more where the answer of small displacements is an
    /// unstable equilibrium, a floppy mode under compression that the load buckles.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub static_descent_steps: Option<u64>,
    /// Lattice: E of the static solution of the same network, solved non-linearly like MD (Pa).
    pub youngs_modulus_fem: Option<f64>,
    /// Lattice: ν of the static solution.
    pub poisson_ratio_fem: Option<f64>,
    /// Lattice: G of the static solution (Pa).
    pub shear_modulus_fem: Option<f64>,
    /// Lattice: continuum E = (C11 − C12²/C11)/d (Pa).
    pub youngs_modulus_theory: Option<f64>,
    /// Lattice: continuum ν = C12/C11.
    pub poisson_ratio_theory: Option<f64>,
    /// Lattice: continuum G = C44/d (Pa).
    pub shear_modulus_theory: Option<f64>,
    /// Lattice with a tangent step: tangent E = ΔF/d/L_x / Δε (Pa) from the MD increments.
    #[serde(default)]
    pub youngs_modulus_tangent: Option<f64>,
    /// Lattice with a tangent step: ν from the MD increments.
    #[serde(default)]
    pub poisson_ratio_tangent: Option<f64>,
    /// Lattice with a tangent step: tangent G (Pa) from the MD increments.
    #[serde(default)]
    pub shear_modulus_tangent: Option<f64>,
    /// Tangent E (Pa) of the static answer, from its tangent stiffness K_t Δu = Δf.
    #[serde(default)]
    pub youngs_modulus_tangent_fem: Option<f64>,
    /// Tangent ν of the static answer.
    #[serde(default)]
    pub poisson_ratio_tangent_fem: Option<f64>,
    /// Tangent G (Pa) of the static answer.
    #[serde(default)]
    pub shear_modulus_tangent_fem: Option<f64>,
    /// Random lattice: fraction of the bonds kept after cutting.
    #[serde(default)]
    pub bond_fraction_kept: Option<f64>,
    /// Spread lattice in tension: E0 (Pa), the static E of the same lattice unspread.
    #[serde(default)]
    pub youngs_modulus_uniform: Option<f64>,
    /// Spread lattice in tension: the lower (Reuss) bound on its E (Pa), `spread_bounds`.
    #[serde(default)]
    pub youngs_modulus_reuss: Option<f64>,
    /// Spread lattice in tension: the upper (Voigt) bound on its E (Pa).
    #[serde(default)]
    pub youngs_modulus_voigt: Option<f64>,
    /// Loaded lattice: the softest stiffness k_min (N/m), a lower bound on the smallest
    /// eigenvalue of the tangent stiffness at the static answer (`fem`).
    #[serde(default)]
    pub stiffness_min: Option<f64>,
    /// Loaded lattice under force control: ‖K_t⁻¹ g‖₂ (m/N), where ΔL = gᵀu (see
    /// [`row_extension_weights`]) and K_t is the tangent stiffness at the static answer: an
    /// out-of-balance force r leaves ΔL within this × ‖r‖₂ of its value at rest.
    #[serde(default)]
    pub extension_sensitivity: Option<f64>,
    /// Loaded lattice: ΔL (m) of its measured modulus in the static answer (see
    /// [`row_extension`]).
    #[serde(default)]
    pub static_extension: Option<f64>,
    /// Loaded lattice with a tangent step: the increment of ΔL (m) in the static answer when
    /// the load rises by the step (the tangent response K_t Δu = step · f).
    #[serde(default)]
    pub static_tangent_extension: Option<f64>,
    /// Loaded lattice under force control: the bound on the relative error of E (tension) or
    /// G (shear) of the MD run against its state of rest, from the residual force at its end:
    /// ‖K_t⁻¹ g‖₂ ‖r‖₂/|ΔL| (see [`modulus_error_bound`]).
    #[serde(default)]
    pub relax_error_bound: Option<f64>,
    /// Loaded lattice with `damping.background: critical`: γ_g = 2 m ω_min = 2 √(k_min m)
    /// (N s/m), the critical damping of its slowest mode.
    #[serde(default)]
    pub gamma_background_critical: Option<f64>,
    /// E (Pa) of the linear static answer (small displacements), kept where the non-linear
    /// one fails to converge (floppy dangling pieces of a diluted network).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub youngs_modulus_linear: Option<f64>,
    /// G (Pa) of the linear static answer.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_modulus_linear: Option<f64>,
    /// Loaded lattice, relaxed: the displacements of its edge nodes, the profiles homogeneity
    /// is judged on (kept in the record for the report's figures; no result column).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_displacements: Option<EdgeDisplacements>,
}

impl LatticeMetrics {
    /// Whether its load buckled the network: the static solve descended from an unstable
    /// state (`static_descent_steps` > 0), so its `*_fem` twins are those of a buckled state.
    pub fn buckled(&self) -> bool {
        self.static_descent_steps.is_some_and(|n| n > 0)
    }
}

/// The relaxed displacements (m) of a lattice's edge nodes: 2 N_y + N_x numbers, where a
/// homogeneous strain makes each profile a straight line (the top row flat under tension).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EdgeDisplacements {
    /// u_x of the left column's nodes, bottom to top.
    pub left_x: Vec<f64>,
    /// u_x of the right column's nodes, bottom to top.
    pub right_x: Vec<f64>,
    /// u_y of the top row's nodes, left to right.
    pub top_y: Vec<f64>,
}

impl EdgeDisplacements {
    /// The edge profiles of a lattice with `edges` from its node displacements `ux`, `uy`.
    fn of(edges: &Edges, ux: &[f64], uy: &[f64]) -> EdgeDisplacements {
        let pick = |u: &[f64], nodes: &[usize]| nodes.iter().map(|&n| u[n]).collect();
        EdgeDisplacements {
            left_x: pick(ux, &edges.left),
            right_x: pick(ux, &edges.right),
            top_y: pick(uy, &edges.top),
        }
    }
}

/// A lattice at rest on its supports (the square one's node (ix, iy) at (ix a, iy a)); the
/// regular square and triangular lattices as a stencil, a random lattice, a turned one and
/// the honeycomb and kagome as an irregular network (the stencil only knows whole bond
/// families of a grid of full rows). An impulse lattice is kicked (or its top row stepped):
/// no load case, drive or relaxation.
pub(super) fn build(spec: &RunSpec, l: &LatticeSpec) -> Scene {
    let layout = l.layout(spec.spacing);
    let mut particles = Particles::default();
    for node in 0..layout.len() {
        particles.push(layout.x[node], layout.y[node], spec.mass, Axes::FREE);
    }
    hold_supports(l.supports, &layout, &mut particles);
    if let Some(impulse) = l.impulse {
        particles.vx[impulse.node] = impulse.vx;
        particles.vy[impulse.node] = impulse.vy;
    }
    let stencil =
        !l.is_random() && (l.lattice_type.is_square() || (l.lattice_type == LatticeType::Triangular && !l.rotated));
    let network = if stencil { Network::Lattice(springs(spec, l)) } else { Network::Bonds(bonds(spec, l)) };
    let mut scene = scene(spec, particles, network, None);
    // The residual force is relative to the load per node; a velocity-driven lattice's is
    // known only from its static answer, which sets it (`static_answer`).
    scene.sampling.relaxation = relaxation(spec, l.force_per_node(), relaxing(l).0);
    let loaded = Some(l).filter(|l| l.impulse.is_none());
    scene.loads = match l.impulse.and_then(|i| i.top_row_force) {
        Some([fx, fy]) => layout.edges.top.iter().map(|&particle| Load { particle, fx, fy }).collect(),
        None => loaded.filter(|l| l.control == Control::Force).map(|l| top_row_loads(l, &layout)).unwrap_or_default(),
    };
    scene.drive = loaded.filter(|l| l.control == Control::Velocity).map(|l| top_row_drive(spec, l));
    scene.load_ramp = l.load_ramp_tc * spec.t_c;
    scene
}

/// The springs of a lattice scene as a stencil: the square lattice's k_x along rows, k_y
/// along columns, k_d across the diagonals it has; the triangular lattice's k on every bond,
/// its rows staggered (as `model::planar` lays them out and bonds them).
fn springs(spec: &RunSpec, l: &LatticeSpec) -> SquareLattice {
    let periodic_x = l.supports.periodic_x();
    if l.lattice_type == LatticeType::Triangular {
        return SquareLattice::triangular(l.nx, l.ny, spec.spacing, l.k_x, periodic_x);
    }
    let (k_rising, k_falling) = l.diagonal_stiffness();
    SquareLattice {
        nx: l.nx,
        ny: l.ny,
        spacing: spec.spacing,
        k_x: l.k_x,
        k_y: l.k_y,
        k_rising,
        k_falling,
        periodic_x,
        staggered: false,
    }
}

/// The bond list of a lattice scene: its springs, cut and spread at random when it asks.
/// The top (loaded) and bottom (supported) rows are held in rigid bands that are never cut:
/// the bonds that touch those rows, and the bonds between two nodes bonded to them. A loaded
/// node left hanging on one bond would make almost every diluted lattice a mechanism at its
/// edge, whatever its bulk does; and without the bonds along the second row, a triangular
/// lattice's top row is a chain of triangles hinged at its loaded nodes, one of which is ever
/// likelier to fold as nx grows (the rigidity threshold then rose with the size, 0.697 at 16
/// and 32 nodes to 0.71 at 128, away from the bulk's 0.660). Rigidity is lost, or not, in the
/// interior.
fn bonds(spec: &RunSpec, l: &LatticeSpec) -> Bonds {
    let all = uniform_bonds(spec, l);
    if !l.is_random() {
        return all;
    }
    let layout = l.layout(spec.spacing);
    let mut edge = vec![false; layout.len()];
    layout.edges.bottom.iter().chain(&layout.edges.top).for_each(|&node| edge[node] = true);
    // The edge rows' neighbours: the second row from the top and from the bottom.
    let mut beside_edge = vec![false; layout.len()];
    for (&i, &j) in all.i.iter().zip(&all.j) {
        beside_edge[i] |= edge[j];
        beside_edge[j] |= edge[i];
    }
    let key = upright_keys(spec, l, &all);
    all.randomised(
        l.cut_fraction,
        l.stiffness_spread,
        l.seed,
        |b| key[b],
        |i, j| edge[i] || edge[j] || (beside_edge[i] && beside_edge[j]),
    )
}

/// Every bond of the lattice, none cut or spread.
fn uniform_bonds(spec: &RunSpec, l: &LatticeSpec) -> Bonds {
    match l.planar(spec.spacing) {
        Some(planar) => planar.bonds(),
        None => springs(spec, l).bonds(),
    }
}

/// The key of each bond's random numbers: its index in the lattice as the campaign describes
/// it, so that a `tensile-x` run (simulated turned by 90°) spreads the same bonds as the
/// `tensile` and `shear` runs of its seed, and cuts the same ones but for the edge bands each
/// loading keeps whole ([`bonds`]): one network measured in both directions. The
/// other types keep their bond list when turned (only the layout turns); the square lattice is
/// rebuilt turned, node (ix', iy') of the turned block being the upright one's
/// (ix, iy) = (iy', ny − 1 − ix') (`Layout::turned`: x' = L_y − y, y' = x).
fn upright_keys(spec: &RunSpec, l: &LatticeSpec, all: &Bonds) -> Vec<u64> {
    if !(l.rotated && l.planar(spec.spacing).is_none()) {
        return (0..all.len() as u64).collect();
    }
    let upright = l.upright();
    let node = |turned: usize| {
        let (ix, iy) = (turned / l.nx, upright.ny - 1 - turned % l.nx);
        iy * upright.nx + ix
    };
    let listed = springs(spec, &upright).bonds();
    let index: HashMap<(usize, usize), u64> =
        (0..listed.len()).map(|b| ((listed.i[b].min(listed.j[b]), listed.i[b].max(listed.j[b])), b as u64)).collect();
    (0..all.len())
        .map(|b| {
            let (i, j) = (node(all.i[b]), node(all.j[b]));
            index[&(i.min(j), i.max(j))]
        })
        .collect()
}

/// Holds what the supports hold of the bottom row: its first node fixed and the others
/// vertically (`coursework`), every node fixed (`clamped-bottom`, `periodic-x`), or nothing.
fn hold_supports(supports: Supports, layout: &Layout, particles: &mut Particles) {
    for (at, &node) in layout.edges.bottom.iter().enumerate() {
        let axes = match (supports, at) {
            (Supports::Free | Supports::PeriodicXFree, _) => Axes::FREE,
            (Supports::Coursework, 0) | (Supports::ClampedBottom | Supports::PeriodicX, _) => Axes::FIXED,
            (Supports::Coursework, _) => Axes { x: false, y: true },
        };
        if axes.x {
            particles.hold(node, false);
        }
        if axes.y {
            particles.hold(node, true);
        }
    }
}

/// The load on every top-row node: up (tensile) or to the right (shear).
fn top_row_loads(l: &LatticeSpec, layout: &Layout) -> Vec<Load> {
    let (fx, fy) = match l.load_case {
        LoadCase::Tensile | LoadCase::TensileX => (0.0, l.load_per_node),
        LoadCase::Shear => (l.load_per_node, 0.0),
    };
    layout.edges.top.iter().map(|&particle| Load { particle, fx, fy }).collect()
}

/// The top-row nodes of a lattice.
fn top_row(spec: &RunSpec, l: &LatticeSpec) -> Vec<usize> {
    l.layout(spec.spacing).edges.top
}

/// How far the top row travels under velocity control: strain · L_y (m), up (tensile) or to
/// the right (shear).
fn drive_travel(spec: &RunSpec, l: &LatticeSpec) -> f64 {
    if l.lattice_type.is_square() {
        l.drive_strain * (l.ny - 1) as f64 * spec.spacing
    } else {
        l.drive_strain * l.layout(spec.spacing).edges.height
    }
}

/// The velocity boundary condition: the top row driven to `drive_travel` in `drive_tc` t_c.
fn top_row_drive(spec: &RunSpec, l: &LatticeSpec) -> Drive {
    let stop_time = l.drive_tc * spec.t_c;
    Drive {
        particles: top_row(spec, l),
        along_y: l.load_case == LoadCase::Tensile,
        velocity: drive_travel(spec, l) / stop_time,
        stop_time,
    }
}

/// The static answer of a loaded lattice, before its MD run: the fraction of bonds a random
/// lattice kept, the moduli of the static solution (see [`StaticSolve::solve`]), and what the scene's
/// relaxation needs from it ([`relaxation_from_static`]), on the network's symbolic analysis in
/// `shared` (made there if it is new), and from the answer another run of the campaign found
/// for the same network, load and law, if one did. Returns why the run has no criterion to stop
/// at, if it has none (it is then not run).
pub(super) fn static_answer(
    spec: &RunSpec,
    l: &LatticeSpec,
    scene: &mut Scene,
    (deadline, shared): (Instant, &Shared),
    metrics: &mut LatticeMetrics,
) -> Result<Option<String>, Stopped> {
    let bonds = bonds(spec, l);
    let uniform = l.is_random().then(|| uniform_bonds(spec, l));
    if let Some(all) = &uniform {
        metrics.bond_fraction_kept = Some(bonds.len() as f64 / all.len().max(1) as f64);
    }
    let (held_x, held_y, prescribed) = static_supports(spec, l, scene);
    let p = &scene.particles;
    let truss = Truss {
        x: &p.x,
        y: &p.y,
        bonds: &bonds,
        held_x: &held_x,
        held_y: &held_y,
        loads: &scene.loads,
        prescribed: &prescribed,
    };
    if let Some(uniform) = uniform.as_ref().filter(|_| has_spread_bounds(spec, l)) {
        let answer = Truss { bonds: uniform, ..truss }.solver(&shared.analyses).solve_linear();
        if let StaticSolution::Displacements { ux, uy } = answer {
            metrics.youngs_modulus_uniform = moduli(spec, l, l.total_load(), &ux, &uy).youngs_modulus;
            let bounds = metrics.youngs_modulus_uniform.map(|e| spread_bounds(&truss, uniform, (&ux, &uy), e));
            (metrics.youngs_modulus_reuss, metrics.youngs_modulus_voigt) = bounds.unzip();
        }
    }
    let solver = truss.solver(&shared.analyses);
    let answers = &shared.answers;
    let ((top_row_force, solution), preconditioner) =
        scene.law.dispatch(StaticSolve { spec, l, truss: &truss, solver, answers, deadline, metrics })?;
    if spec.static_only() {
        scene.rest = solution.map(|(ux, uy)| {
            let p = &scene.particles;
            (p.x.iter().zip(&ux).map(|(x, u)| x + u).collect(), p.y.iter().zip(&uy).map(|(y, u)| y + u).collect())
        });
    }
    if let Some(missing) = set_preconditioner(spec, scene, preconditioner, metrics) {
        return Ok(Some(missing));
    }
    Ok(relaxation_from_static(spec, l, scene, top_row_force, metrics))
}

/// True for the networks [`spread_bounds`] holds for: linear springs spread at random, none cut,
/// pulled by forces (E ∝ 1/F·u: equal loads on the top row, the bottom row held along them).
fn has_spread_bounds(spec: &RunSpec, l: &LatticeSpec) -> bool {
    l.stiffness_spread > 0.0
        && l.cut_fraction == 0.0
        && spec.law == LawSpec::Linear
        && l.control == Control::Force
        && matches!(l.load_case, LoadCase::Tensile | LoadCase::TensileX)
        && matches!(l.supports, Supports::Coursework | Supports::ClampedBottom)
}

/// (E_Reuss, E_Voigt) (Pa): the bounds on E of the spread network `spread.bonds`, k_b =
/// k0_b (1 + w U_b), from the answer `u0` of the same lattice with every spring k0_b (its
/// modulus `uniform_modulus` = E0) under the same loads. With e_b the bonds' extensions under
/// u0, the spread network's compliance C = F·u (= F ΔL, so E ∝ 1/C) is at least (Σ k0 e²)²/Σ k e²
/// (minimum potential energy over the fields λ u0) and at most Σ f0²/k of the uniform network's
/// bond forces f0 = k0 e, which balance the same loads (minimum complementary energy); with
/// C0 = Σ k0 e² (Clapeyron): E0 Σ k0 e² / Σ (k0 e)²/k ≤ E ≤ E0 Σ k e² / Σ k0 e², the Reuss and
/// Voigt averages of 1 + w U weighted by the uniform network's bond energies.
fn spread_bounds(spread: &Truss, uniform: &Bonds, (ux, uy): (&[f64], &[f64]), uniform_modulus: f64) -> (f64, f64) {
    let (mut energy, mut stiffened, mut softened) = (0.0, 0.0, 0.0);
    for b in 0..uniform.len() {
        let (i, j) = (uniform.i[b], uniform.j[b]);
        let (dx, dy) = (spread.x[i] - spread.x[j] + uniform.shift_x[b], spread.y[i] - spread.y[j]);
        let extension = ((ux[i] - ux[j]) * dx + (uy[i] - uy[j]) * dy) / dx.hypot(dy);
        let (k0, k) = (uniform.stiffness[b], spread.bonds.stiffness[b]);
        energy += k0 * extension * extension;
        stiffened += k * extension * extension;
        softened += k0 * k0 * extension * extension / k;
    }
    (uniform_modulus * energy / softened, uniform_modulus * stiffened / energy)
}

/// Hands FIRE the metric it asks for (`relax.preconditioner: stiffness`); returns why the run
/// cannot have it: a floppy network (k_min = 0), whose regularised factor would blow its
/// zero-energy motions up by 1e12, or a tangent that could not be factored. The run is then not
/// run, rather than quietly relaxed without it.
fn set_preconditioner(
    spec: &RunSpec,
    scene: &mut Scene,
    made: Option<SharedPreconditioner>,
    metrics: &LatticeMetrics,
) -> Option<String> {
    if !spec.is_preconditioned() {
        return None;
    }
    let why = match (metrics.stiffness_min, made) {
        (Some(k), Some(made)) if k > 0.0 => {
            scene.preconditioner = Some(made);
            return None;
        }
        (Some(k), None) if k > 0.0 => "its tangent stiffness at the static answer could not be factored",
        _ => "this network is floppy (k_min = 0)",
    };
    Some(format!(
        "relax.preconditioner: stiffness needs the tangent stiffness at the static answer factored and positive \
         definite, its softest stiffness k_min > 0: {why}; give relax.preconditioner: none"
    ))
}

/// What a relaxation takes from the static answer: the displacement bound's residual
/// (`relax.tolerance`), critical background damping from k_min, and under velocity control the
/// residual force judged against the force the drive holds at equilibrium (per top-row node),
/// not the unused load_per_node. Returns why the run has no criterion to stop at: a floppy
/// network (k_min = 0) has neither a displacement bound nor a critical γ_g, and a run that asks
/// for either is not quietly judged by E_kin/E_pot instead.
fn relaxation_from_static(
    spec: &RunSpec,
    l: &LatticeSpec,
    scene: &mut Scene,
    top_row_force: f64,
    metrics: &mut LatticeMetrics,
) -> Option<String> {
    let (Some(relax), Some(relaxation)) = (spec.relax(), scene.sampling.relaxation.as_mut()) else { return None };
    let softest = metrics.stiffness_min.filter(|k| *k > 0.0);
    if let (Some(tolerance), Some(sensitivity), Some(extension)) =
        (relax.tolerance, metrics.extension_sensitivity, metrics.static_extension)
    {
        relaxation.residual_norm = Some(extension_error_allowed_at(extension, metrics, tolerance) / sensitivity);
    }
    if let (Control::Velocity, Some(fraction)) = (l.control, relax.residual_force) {
        relaxation.residual_force = Some(fraction * (top_row_force / l.top_row_len() as f64).abs());
    }
    let floppy = "this network is floppy (k_min = 0: zero-energy modes the load does not drive)";
    if relax.critical_background {
        let Some(k_min) = softest else {
            return Some(format!(
                "damping.background: critical needs the softest stiffness k_min > 0 (γ_g = 2√(k_min m)); {floppy}; \
                 give damping.background in N s/m"
            ));
        };
        // γ_g = 2 m ω_min with ω_min² = k_min/m.
        scene.background_gamma = critical_damping(k_min, spec.mass);
        metrics.gamma_background_critical = Some(scene.background_gamma);
    }
    let unbounded =
        relax.tolerance.is_some() && relaxation.residual_norm.is_none() && relaxation.residual_force.is_none();
    if unbounded {
        return Some(format!(
            "relax.tolerance (1e-4 by default for fire and cg) needs the displacement bound ‖K⁻¹g‖₂‖r‖₂, which needs \
             the softest stiffness k_min > 0; {floppy}; give relax.residual_force"
        ));
    }
    below_round_off(spec, &scene.particles, relaxation)
}

/// The displacement bound's residual below this many times σ √n (σ the round-off of one
/// static force, n the free degrees of freedom) is never reached: on 20 × 20 and 80 × 80 steel
/// blocks FIRE and CG stopped at 0.31 times and ran to `max_tc` at 0.19 times.
const NORM_OVER_ROUND_OFF: f64 = 0.25;

/// Why a relaxation's criterion lies below the round-off floor of the positions, if it does
/// (known only from the static answer: the displacement bound's residual, and under velocity
/// control the drive's force): σ = [`force_resolution`] on every static force, and about
/// σ √n on the norm over the n free degrees of freedom.
fn below_round_off(spec: &RunSpec, particles: &Particles, relaxation: &Relaxation) -> Option<String> {
    let floor = force_resolution(spec)?;
    let free = 2 * particles.len() - particles.held_x.len() - particles.held_y.len();
    let why = round_off_words(spec, floor);
    let norm_floor = NORM_OVER_ROUND_OFF * floor * (free as f64).sqrt();
    if let Some(target) = relaxation.residual_norm.filter(|target| *target < norm_floor) {
        let reachable = spec.relax().and_then(|r| r.tolerance).unwrap_or_default() * norm_floor / target;
        return Some(format!(
            "relax.tolerance: its displacement bound needs ‖r‖₂ ≤ {target:.2e} N, below the round-off floor \
             {norm_floor:.2e} N: {why}; reachable: relax.tolerance ≥ {reachable:.1e}, or a larger load"
        ));
    }
    let limit = relaxation.residual_force.filter(|limit| *limit < RESIDUAL_OVER_ROUND_OFF * floor)?;
    Some(format!(
        "relax.residual_force: {limit:.2e} N, below {RESIDUAL_OVER_ROUND_OFF} times the round-off floor: {why}; give a \
         larger relax.residual_force or load"
    ))
}

/// The error of ΔL (m) a relaxation may leave, by the displacement bound |δΔL| ≤ ‖K_t⁻¹ g‖₂ ‖r‖₂:
/// the modulus is within `tolerance` once ‖r‖₂ ≤ this/‖K_t⁻¹ g‖₂. With a tangent step both
/// relaxed states (before and after the step) are held to half the error the increment
/// Δ(ΔL) allows, so that the tangent modulus, ∝ 1/Δ(ΔL), is within the tolerance too.
fn extension_error_allowed_at(extension: f64, metrics: &LatticeMetrics, tolerance: f64) -> f64 {
    let allowed = extension_error_allowed(extension, tolerance);
    match metrics.static_tangent_extension {
        Some(increment) => allowed.min(extension_error_allowed(increment, tolerance) / 2.0),
        None => allowed,
    }
}

/// Held axes of the static problem and the displacements imposed on them: the scene's
/// supports, plus, under velocity control, the top row held where the drive leaves it.
type StaticSupports = (Vec<usize>, Vec<usize>, Vec<(usize, f64, f64)>);

fn static_supports(spec: &RunSpec, l: &LatticeSpec, scene: &Scene) -> StaticSupports {
    let mut supported = scene.particles.clone();
    let mut prescribed = Vec::new();
    if l.control == Control::Velocity {
        let travel = drive_travel(spec, l);
        let tensile = l.load_case == LoadCase::Tensile;
        for node in top_row(spec, l) {
            supported.hold(node, tensile);
            prescribed.push(if tensile { (node, 0.0, travel) } else { (node, travel, 0.0) });
        }
    }
    (supported.held_x, supported.held_y, prescribed)
}

/// The static answer of [`static_answer`], solved with the run's concrete law (from
/// [`crate::model::LawSpec::dispatch`]), by [`StaticSolve::solve`].
struct StaticSolve<'a> {
    spec: &'a RunSpec,
    l: &'a LatticeSpec,
    truss: &'a Truss<'a>,
    solver: Solver<'a>,
    answers: &'a Answers,
    deadline: Instant,
    metrics: &'a mut LatticeMetrics,
}

/// The top row's force (N) and the static displacements (m, x and y) it was taken at.
type Solved = (f64, Option<(Vec<f64>, Vec<f64>)>);

impl LawVisitor for StaticSolve<'_> {
    type Output = Result<(Solved, Option<SharedPreconditioner>), Stopped>;
    fn visit<L: ForceLaw>(mut self, law: L) -> Self::Output {
        let solved = self.solve(&law)?;
        // The factor the bounds made, of the tangent at the static answer (`set_preconditioner`
        // hands it on only where the network is rigid).
        let metric = self.spec.is_preconditioned().then(|| self.solver.take_preconditioner()).flatten();
        Ok((solved, metric.map(|p| Arc::new(p) as SharedPreconditioner)))
    }
}

/// Where the static solve stops when its deadline passes.
fn past_deadline() -> Stopped {
    Stopped::PastDeadline { stage: "static solve" }
}

impl StaticSolve<'_> {
    /// The static solution beside MD: its moduli (`*_fem`), solved non-linearly like MD; for
    /// linear springs how far that is from the linear answer; the bounds on a relaxation's
    /// error ([`StaticSolve::bound_errors`]). Returns the total force on the top row at the
    /// static equilibrium (N): the load, or what the drive must hold (non-linear answer where
    /// it exists, else linear), and the displacements (m, x and y) of that answer: the linear
    /// one stands in where Newton's iteration does not converge (a diluted network's floppy
    /// dangling parts leave its tangent singular while the linear solver skips them). `Err`
    /// when the load drives a mechanism, or when the deadline passes (checked between
    /// factorisations).
    fn solve<L: ForceLaw>(&mut self, law: &L) -> Result<Solved, Stopped> {
        self.check_deadline()?;
        let answer = self.answer(law);
        let (linear, linear_answer) = self.linear(answer.linear)?;
        let (ux, uy) = match answer.nonlinear {
            Some(StaticSolution::Displacements { ux, uy }) => (ux, uy),
            Some(StaticSolution::PastDeadline) => return Err(past_deadline()),
            // Newton did not converge: the linear answer stands, and no residual of Newton's.
            _ => return Ok(linear_answer),
        };
        self.metrics.static_residual = Some(answer.residual).filter(|r| r.is_finite());
        self.metrics.static_descent_steps = Some(answer.descents as u64);
        let top_row_force = self.top_row_force(|top| self.truss.reaction(law, &ux, &uy, top));
        let fem = moduli(self.spec, self.l, top_row_force, &ux, &uy);
        if self.spec.law.is_linear() {
            self.metrics.static_nonlinearity = nonlinearity(&fem, &linear);
        }
        self.metrics.youngs_modulus_fem = fem.youngs_modulus;
        self.metrics.poisson_ratio_fem = fem.poisson_ratio;
        self.metrics.shear_modulus_fem = fem.shear_modulus;
        self.check_deadline()?;
        self.bound_errors(law, &ux, &uy)?;
        Ok((top_row_force, Some((ux, uy))))
    }

    /// The static answer of this run's network, load and law ([`Solver::solve_static`]):
    /// solved here, or by another run of the campaign that asked first ([`Answers`]). What the
    /// solver does after it must not depend on which: a relaxing run factors the tangent afresh
    /// for its bounds, but a static-only run's tangent step solves with the factor its own
    /// static solve left, so that run solves its answer itself.
    fn answer<L: ForceLaw>(&mut self, law: &L) -> StaticAnswer {
        let extension = reference_extension(self.spec);
        let (solver, setting, deadline) = (&mut self.solver, (self.spec.law.is_linear(), extension), self.deadline);
        if self.spec.static_only() && self.spec.relax().and_then(|r| r.tangent_step).is_some() {
            return solver.solve_static(law, setting, deadline);
        }
        let key = self.truss.answer_key(&format!("{:?} linearised at {:x}", self.spec.law, extension.to_bits()));
        self.answers.get(key, || solver.solve_static(law, setting, deadline))
    }

    /// The linear answer `solution`, which decides whether the network carries the load at
    /// all (a power law's linear answer means nothing else): its moduli, kept as `*_linear`,
    /// and its top row's force and displacements. A drive's force is the linear problem's own
    /// reaction, first order about the rest geometry like the answer ([`Truss::linear_reaction`]):
    /// the springs' forces at the displaced state ([`Truss::reaction`], the non-linear answer's)
    /// would add a second-order part, of the order of the strain relative.
    fn linear(&mut self, solution: StaticSolution) -> Result<(Moduli, Solved), Stopped> {
        let (linear, answer) = match solution {
            StaticSolution::Mechanism(floppy) => return Err(Stopped::Mechanism(floppy)),
            StaticSolution::PastDeadline => return Err(past_deadline()),
            StaticSolution::Displacements { ux, uy } => {
                let top = self.top_row_force(|top| self.truss.linear_reaction(&ux, &uy, top));
                (moduli(self.spec, self.l, top, &ux, &uy), (top, Some((ux, uy))))
            }
        };
        self.metrics.youngs_modulus_linear = linear.youngs_modulus;
        self.metrics.shear_modulus_linear = linear.shear_modulus;
        Ok((linear, answer))
    }

    /// The force on the top row (N): the load, or what the supports must apply to hold the
    /// driven row where it is, along the drive, of `reaction` (N, x and y) of the top row's nodes.
    fn top_row_force(&self, reaction: impl FnOnce(&[usize]) -> (f64, f64)) -> f64 {
        match self.l.control {
            Control::Force => self.l.total_load(),
            Control::Velocity => {
                let (fx, fy) = reaction(&top_row(self.spec, self.l));
                if self.l.load_case == LoadCase::Tensile { fy } else { fx }
            }
        }
    }

    /// What bounds a relaxation's error, at the static answer `ux`, `uy`: k_min and ΔL's
    /// sensitivity (a static-only run has no relaxation to bound), ΔL itself, and with a
    /// tangent step its increment ([`StaticSolve::tangent`]).
    fn bound_errors<L: ForceLaw>(&mut self, law: &L, ux: &[f64], uy: &[f64]) -> Result<(), Stopped> {
        let (spec, l) = (self.spec, self.l);
        let edges = l.layout(spec.spacing).edges;
        let shape = LatticeShape { edges: &edges, depth: l.depth };
        // Under velocity control the modulus comes from the drive's force, whose error the bound
        // on ΔL does not cover: nothing is measured, so no sensitivity is solved for.
        let measured = if l.control == Control::Force { extension_dofs(l, &shape) } else { Vec::new() };
        if !spec.static_only()
            && let Some(bounds) = self.solver.error_bounds(law, ux, uy, &measured)
        {
            self.metrics.stiffness_min = Some(bounds.stiffness_min);
            self.metrics.extension_sensitivity = bounds.sensitivity;
        }
        self.metrics.static_extension = Some(extension(l, &shape, ux, uy));
        if let Some(step) = spec.relax().and_then(|r| r.tangent_step) {
            self.check_deadline()?;
            self.tangent(law, &shape, (ux, uy), step);
        }
        Ok(())
    }

    /// The static answer's tangent moduli (`*_tangent_fem`) and the increment of ΔL when the
    /// load rises by the fraction `step`, from the tangent stiffness at the displacements `at`:
    /// K_t Δu = Δf, Δu per unit load factor being the increment of the whole load.
    fn tangent<L: ForceLaw>(&mut self, law: &L, shape: &LatticeShape, (ux, uy): (&[f64], &[f64]), step: f64) {
        let Some((dx, dy)) = self.solver.tangent_response(law, ux, uy) else { return };
        let tangent = moduli(self.spec, self.l, self.l.total_load(), &dx, &dy);
        self.metrics.static_tangent_extension = Some(step * extension(self.l, shape, &dx, &dy));
        self.metrics.youngs_modulus_tangent_fem = tangent.youngs_modulus;
        self.metrics.poisson_ratio_tangent_fem = tangent.poisson_ratio;
        self.metrics.shear_modulus_tangent_fem = tangent.shear_modulus;
    }

    /// `Err` once the deadline has passed.
    fn check_deadline(&self) -> Result<(), Stopped> {
        if Instant::now() > self.deadline { Err(past_deadline()) } else { Ok(()) }
    }
}

/// How far the non-linear static answer (`fem`) lies from the linear one over the moduli the
/// load case measures ([`moduli`] leaves the others `None`, so a shear's E and ν never enter):
/// the largest of |E/E_lin − 1| and |ν − ν_lin| in tension (ν absolute: it is 0 without
/// diagonals and on `periodic-x`), |G/G_lin − 1| in shear. O(ε) at strain ε, but O(γ²) in a
/// shear that the mirror x → −x maps onto itself sheared back, whose G is even in γ: γ²/4 for
/// the periodic square strip at k_d/k = 1/2 (`tests/suite/shear_nonlinearity.rs`).
fn nonlinearity(fem: &Moduli, linear: &Moduli) -> Option<f64> {
    let relative = |a: Option<f64>, b: Option<f64>| crate::measure::relative_error(a, b).map(f64::abs);
    let absolute = fem.poisson_ratio.zip(linear.poisson_ratio).map(|(a, b)| (a - b).abs());
    [relative(fem.youngs_modulus, linear.youngs_modulus), relative(fem.shear_modulus, linear.shear_modulus), absolute]
        .into_iter()
        .flatten()
        .reduce(f64::max)
}

/// The moduli a lattice's load case measures; the others stay `None`.
struct Moduli {
    youngs_modulus: Option<f64>,
    poisson_ratio: Option<f64>,
    poisson_ratio_coursework: Option<f64>,
    shear_modulus: Option<f64>,
}

/// The moduli from the total top-row force `force` (N) and the node displacements.
fn moduli(spec: &RunSpec, l: &LatticeSpec, force: f64, ux: &[f64], uy: &[f64]) -> Moduli {
    let edges = l.layout(spec.spacing).edges;
    let shape = LatticeShape { edges: &edges, depth: l.depth };
    match l.load_case {
        LoadCase::Tensile | LoadCase::TensileX => {
            let t = tensile_moduli(&shape, force, ux, uy);
            Moduli {
                youngs_modulus: Some(t.youngs_modulus),
                poisson_ratio: Some(t.poisson_ratio),
                poisson_ratio_coursework: Some(t.poisson_ratio_coursework),
                shear_modulus: None,
            }
        }
        LoadCase::Shear => Moduli {
            youngs_modulus: None,
            poisson_ratio: None,
            poisson_ratio_coursework: None,
            shear_modulus: Some(shear_modulus(&shape, force, ux)),
        },
    }
}

/// ΔL (m) of the modulus the load case measures: the top row's mean u_y (tension) or u_x
/// (shear) relative to the bottom row's.
fn extension(l: &LatticeSpec, shape: &LatticeShape, ux: &[f64], uy: &[f64]) -> f64 {
    match l.load_case {
        LoadCase::Tensile | LoadCase::TensileX => row_extension(shape, uy),
        LoadCase::Shear => row_extension(shape, ux),
    }
}

/// ΔL of [`extension`] as weights of degrees of freedom (dof 2i is x of node i, 2i + 1 its y).
fn extension_dofs(l: &LatticeSpec, shape: &LatticeShape) -> Vec<(usize, f64)> {
    let axis = match l.load_case {
        LoadCase::Tensile | LoadCase::TensileX => 1,
        LoadCase::Shear => 0,
    };
    row_extension_weights(shape).into_iter().map(|(node, weight)| (2 * node + axis, weight)).collect()
}

/// A loaded lattice's moduli and homogeneity (only when it came to rest: those of a run that
/// never did would be snapshots of an oscillation) beside the continuum's; nothing of an
/// impulse lattice (its wave is measured with the other kinds').
pub(super) fn measure(
    spec: &RunSpec,
    l: &LatticeSpec,
    outcome: &Outcome,
    start: &(Vec<f64>, Vec<f64>),
    metrics: &mut LatticeMetrics,
) {
    if l.impulse.is_some() {
        return;
    }
    let p = &outcome.state.particles;
    let ux: Vec<f64> = p.x.iter().zip(&start.0).map(|(x, x0)| x - x0).collect();
    let uy: Vec<f64> = p.y.iter().zip(&start.1).map(|(y, y0)| y - y0).collect();
    let relaxed = outcome.trace.relaxed_at.is_some();
    let force = match l.control {
        Control::Force => l.total_load(),
        Control::Velocity => outcome.state.drive_force,
    };
    let md = moduli(spec, l, force, &ux, &uy);
    let keep = |value: Option<f64>| value.filter(|_| relaxed);
    // A run set to its static answer ran no MD: its moduli are the `*_fem` ones, and MD columns
    // left empty keep every MD-against-static comparison to runs that have both.
    let keep_md = |value: Option<f64>| keep(value).filter(|_| !spec.static_only());
    metrics.youngs_modulus = keep_md(md.youngs_modulus);
    metrics.poisson_ratio = keep_md(md.poisson_ratio);
    metrics.poisson_ratio_coursework = keep_md(md.poisson_ratio_coursework);
    metrics.shear_modulus = keep_md(md.shear_modulus);
    let largest = ux.iter().chain(&uy).fold(0.0, |m: f64, u| m.max(u.abs()));
    let edges = l.layout(spec.spacing).edges;
    let shape = LatticeShape { edges: &edges, depth: l.depth };
    metrics.homogeneity = keep(homogeneity(&shape, &ux, largest));
    metrics.edge_displacements = relaxed.then(|| EdgeDisplacements::of(&edges, &ux, &uy));
    if let (Some(sensitivity), Some(residual)) = (metrics.extension_sensitivity, outcome.trace.residual_norm) {
        let bound = modulus_error_bound(extension(l, &shape, &ux, &uy), sensitivity * residual);
        metrics.relax_error_bound = keep(Some(bound));
    }
    if spec.law.is_linear() {
        continuum(spec, l, metrics);
    } else {
        power_law_continuum(spec, l, metrics);
    }
}

/// The continuum's ν of a lattice of power-law springs (its E grows with the load and has no
/// one value): 0 on a periodic strip, which cannot contract sideways (as for linear springs);
/// free to contract, [`power_law_poisson_ratio`] of a regular square lattice with both
/// diagonals, whose derivation needs k_x = k_y and both diagonals.
fn power_law_continuum(spec: &RunSpec, l: &LatticeSpec, metrics: &mut LatticeMetrics) {
    let square_symmetric = l.lattice_type.is_square() && l.diagonals == Diagonals::Both && l.k_x == l.k_y;
    if l.supports == Supports::PeriodicX {
        metrics.poisson_ratio_theory = Some(0.0);
    } else if square_symmetric && !l.is_random() {
        metrics.poisson_ratio_theory = Some(power_law_poisson_ratio(l.k_diag / l.k_x, spec.law.beta()));
    }
}

/// The side N of the relaxation window (the larger side) and the force the residual-force
/// criterion is relative to.
pub(super) fn relaxing(l: &LatticeSpec) -> (usize, &'static str) {
    let scale = match l.control {
        Control::Velocity => "the drive's static force per node",
        Control::Force => "the load per node",
    };
    (l.nx.max(l.ny), scale)
}

/// The continuum moduli of the regular linear lattice (a random one is compared with it); of
/// another type its isotropic constants, of which the honeycomb (μ = 0: no shear stiffness
/// with central springs) has only the constrained modulus of a periodic strip.
fn continuum(spec: &RunSpec, l: &LatticeSpec, metrics: &mut LatticeMetrics) {
    if let Some(c) = network_constants(l.lattice_type, l.k_x, spec.spacing) {
        if l.supports == Supports::PeriodicX {
            metrics.youngs_modulus_theory = Some(c.constrained_modulus(l.depth));
            metrics.poisson_ratio_theory = Some(0.0);
        } else if c.mu > 0.0 {
            metrics.youngs_modulus_theory = Some(c.youngs_modulus(l.depth));
            metrics.poisson_ratio_theory = Some(c.poisson_ratio());
        }
        metrics.shear_modulus_theory = Some(c.shear_modulus(l.depth)).filter(|&g| g > 0.0);
        return;
    }
    let (k_rising, k_falling) = l.diagonal_stiffness();
    let continuum = anisotropic_moduli(l.k_x, l.k_y, k_rising, k_falling, l.depth);
    // A periodic strip cannot contract sideways: in tension it measures the constrained
    // modulus (C22 = (k + k_d)/d with both diagonals), with ν = 0.
    // In shear it cannot stretch along x either: C66 − C26²/C22, not the free 1/S66.
    if l.supports == Supports::PeriodicX {
        metrics.youngs_modulus_theory = Some(constrained_modulus_y(l.k_x, l.k_y, k_rising, k_falling, l.depth));
        metrics.poisson_ratio_theory = Some(0.0);
        metrics.shear_modulus_theory = constrained_shear_modulus(l.k_x, l.k_y, k_rising, k_falling, l.depth);
    } else {
        metrics.youngs_modulus_theory = Some(continuum.youngs_modulus_y);
        metrics.poisson_ratio_theory = Some(continuum.poisson_ratio_yx);
        metrics.shear_modulus_theory = continuum.shear_modulus;
    }
}

/// The linear sound speed along an impulse lattice's wave (m/s): kicked or stepped mostly
/// along y (the bottom row is below) the longitudinal c_L, stepped mostly along x on the whole
/// top row (a plane shear front) the transverse c_T ([`speeds_along_y`]). A single node kicked
/// mostly along x has none: its first arrival at the bottom row lies between c_T and c_L
/// ([`sideways_kick_speeds`]), so no one speed is its reference.
pub(super) fn wave_speed(spec: &RunSpec, l: &LatticeSpec) -> Option<f64> {
    let impulse = l.impulse?;
    let (c_l, c_t) = speeds_along_y(spec, l)?;
    match (impulse.is_sideways(), impulse.top_row_force) {
        (false, _) => Some(c_l),
        (true, Some(_)) => c_t,
        (true, None) => None,
    }
}

/// The speeds (c_T, c_L) (m/s) that bracket the first arrival of a single node kicked mostly
/// along x, `None` for any other impulse or without both speeds. Why a bracket: a point force
/// on the free surface radiates P along its line and S across it; straight below a sideways
/// kick the P wave's motion (along the ray, u_y) vanishes by symmetry (u_y is odd in x), so the
/// receivers (the whole bottom row, a distance L below) meet P first where it arrives obliquely,
/// over √(L² + x²) > L, and S (full amplitude below) by L/c_T at the latest. Hence
/// c_T ≲ L/t_s ≲ c_L, where along the row the threshold fires is set by the radiation pattern
/// and the block's width, not by one speed: kicked at its top centre, a free block 30 nodes high
/// (k_d/k = 0.5: c_T = 0.707, c_L = 1.225 m/s) gives L/t_s = 0.81 … 0.91 c_L over widths 6 … 90
/// nodes, arriving before L/c_T = 41 s: the P wave's.
pub fn sideways_kick_speeds(spec: &RunSpec, l: &LatticeSpec) -> Option<(f64, f64)> {
    l.impulse.filter(|i| i.top_row_force.is_none() && i.is_sideways())?;
    let (c_l, c_t) = speeds_along_y(spec, l)?;
    Some((c_t?, c_l))
}

/// The linear speeds (c_L, c_T) (m/s) of the lattice's plane waves along y: on the square
/// lattice a√(C22/m) and a√(C66/m) (C per unit depth; C22 = k + k_d, C66 = k_d with both
/// diagonals), on the other types the slopes of their acoustic Bloch branches
/// ([`plane_wave_speeds`]: the continuum's but for the kagome's transverse; the honeycomb has
/// no c_T). `None` for a non-linear law.
fn speeds_along_y(spec: &RunSpec, l: &LatticeSpec) -> Option<(f64, Option<f64>)> {
    if !l.lattice_type.is_square() {
        return plane_wave_speeds(l.lattice_type, l.k_x, spec.spacing, spec.mass).filter(|_| spec.law.is_linear());
    }
    let (k_rising, k_falling) = l.diagonal_stiffness();
    let c = lattice_constants(l.k_x, l.k_y, k_rising, k_falling);
    Some((sound_speed(spec, c.c22)?, sound_speed(spec, c.c66)))
}

/// The tangent moduli of the tangent step: the increments from the relaxed particles `start`
/// to `end` under the load raised by the fraction `step`.
pub(super) fn tangent_moduli(
    spec: &RunSpec,
    l: &LatticeSpec,
    step: f64,
    start: &Particles,
    end: &Particles,
    metrics: &mut LatticeMetrics,
) {
    let dx: Vec<f64> = end.x.iter().zip(&start.x).map(|(b, a)| b - a).collect();
    let dy: Vec<f64> = end.y.iter().zip(&start.y).map(|(b, a)| b - a).collect();
    let tangent = moduli(spec, l, step * l.total_load(), &dx, &dy);
    metrics.youngs_modulus_tangent = tangent.youngs_modulus;
    metrics.poisson_ratio_tangent = tangent.poisson_ratio;
    metrics.shear_modulus_tangent = tangent.shear_modulus;
}

/// Picks a lattice's probed lines out of its per-particle series, once measured: an impulse
/// lattice's kicked column (the wave's straight path down, for the space–time picture) and the
/// user's. The per-particle series are recorded to compare with a reference run or to follow a
/// wave; the runner keeps them only where `output.series: full` asks (`runner::series`).
pub(super) fn keep_probes(l: &LatticeSpec, t: &mut Trace) {
    // The kicked column is a column of the square grid only.
    let kicked = l.impulse.filter(|_| l.lattice_type.is_square()).map(|impulse| ProbeLine::Column(impulse.node % l.nx));
    let mut lines: Vec<ProbeLine> = kicked.into_iter().collect();
    lines.extend(l.probes.iter().filter(|&&line| Some(line) != kicked));
    if !t.displacement_x.is_empty() {
        t.probes =
            lines.into_iter().map(|line| ProbeTrace::from_trace(line.name(), line.nodes(l.nx, l.ny), t)).collect();
    }
}

/// The lattice's result columns: [`lattice_columns`] when the table has a lattice,
/// [`type_columns`] beside another type, [`directional_columns`] when a lattice is anisotropic.
pub(super) fn columns() -> Vec<Block<LatticeMetrics>> {
    vec![
        Block { slot: Slot::Tail, shown: Some(|spec| spec.lattice().is_some()), columns: lattice_columns() },
        Block {
            slot: Slot::Tail,
            shown: Some(|spec| spec.lattice().is_some_and(|l| !l.lattice_type.is_square())),
            columns: type_columns(),
        },
        Block {
            slot: Slot::Tail,
            shown: Some(|spec| spec.lattice().is_some_and(is_anisotropic)),
            columns: directional_columns(),
        },
    ]
}

/// The resolved lattice, each modulus from MD, from the static solution and from the
/// continuum, and its relaxation.
fn lattice_columns() -> Vec<Column<LatticeMetrics>> {
    use Column::{Count, Number, Word};
    vec![
        Count("nx", |r| r.spec.lattice().map(|l| l.nx as u64)),
        Count("ny", |r| r.spec.lattice().map(|l| l.ny as u64)),
        Number("k_diag", |r| r.spec.lattice().map(|l| l.k_diag)),
        Word("diagonals", |r| r.spec.lattice().map(|l| l.diagonals.name().into())),
        Number("k_x", |r| r.spec.lattice().map(|l| l.k_x)),
        Number("k_y", |r| r.spec.lattice().map(|l| l.k_y)),
        Number("cut_fraction", |r| r.spec.lattice().map(|l| l.cut_fraction)),
        Number("stiffness_spread", |r| r.spec.lattice().map(|l| l.stiffness_spread)),
        Count("seed", |r| r.spec.lattice().map(|l| l.seed)),
        Number("bond_fraction_kept", |r| r.group.bond_fraction_kept),
        Number("youngs_modulus_uniform", |r| r.group.youngs_modulus_uniform),
        Number("youngs_modulus_reuss", |r| r.group.youngs_modulus_reuss),
        Number("youngs_modulus_voigt", |r| r.group.youngs_modulus_voigt),
        Number("depth", |r| r.spec.lattice().map(|l| l.depth)),
        Word("supports", |r| r.spec.lattice().map(|l| l.supports.name().into())),
        Word("load_case", |r| r.spec.lattice().map(|l| l.load_name().into())),
        Word("load_control", |r| r.spec.lattice().map(|l| l.control.name().into())),
        Number("drive_strain", |r| r.spec.lattice().filter(|l| l.control == Control::Velocity).map(|l| l.drive_strain)),
        Number("load_per_node", |r| r.spec.lattice().and_then(|l| l.force_per_node())),
        Number("youngs_modulus", |r| r.group.youngs_modulus),
        Number("youngs_modulus_fem", |r| r.group.youngs_modulus_fem),
        Number("youngs_modulus_theory", |r| r.group.youngs_modulus_theory),
        Number("poisson_ratio", |r| r.group.poisson_ratio),
        Number("poisson_ratio_fem", |r| r.group.poisson_ratio_fem),
        Number("poisson_ratio_theory", |r| r.group.poisson_ratio_theory),
        Number("poisson_ratio_coursework", |r| r.group.poisson_ratio_coursework),
        Number("shear_modulus", |r| r.group.shear_modulus),
        Number("shear_modulus_fem", |r| r.group.shear_modulus_fem),
        Number("shear_modulus_theory", |r| r.group.shear_modulus_theory),
        Number("youngs_modulus_tangent", |r| r.group.youngs_modulus_tangent),
        Number("youngs_modulus_tangent_fem", |r| r.group.youngs_modulus_tangent_fem),
        Number("poisson_ratio_tangent", |r| r.group.poisson_ratio_tangent),
        Number("poisson_ratio_tangent_fem", |r| r.group.poisson_ratio_tangent_fem),
        Number("shear_modulus_tangent", |r| r.group.shear_modulus_tangent),
        Number("shear_modulus_tangent_fem", |r| r.group.shear_modulus_tangent_fem),
        Number("static_nonlinearity", |r| r.group.static_nonlinearity),
        Number("static_residual", |r| r.group.static_residual),
        Count("static_descent_steps", |r| r.group.static_descent_steps),
        Number("homogeneity", |r| r.group.homogeneity),
        Number("dissipation_time", |r| r.dissipation_time),
        Word("dissipation_criterion", |r| r.dissipation_criterion.map(str::to_string)),
        Count("relax_steps", |r| r.spec.lattice().map(|_| r.steps)),
        Word("relax_method", |r| r.spec.relax().filter(|_| r.spec.lattice().is_some()).map(|m| m.method.name().into())),
        Number("relax_tolerance", |r| r.spec.lattice().and(r.spec.relax()).and_then(|m| m.tolerance)),
        Number("relax_error_bound", |r| r.group.relax_error_bound),
        Number("stiffness_min", |r| r.group.stiffness_min),
        Number("extension_sensitivity", |r| r.group.extension_sensitivity),
        Number("critical_bound_steps", |r| {
            r.group.stiffness_min.filter(|k| *k > 0.0).map(|k| critical_bound_steps(r.spec, k))
        }),
        Number("gamma_background_critical", |r| r.group.gamma_background_critical),
    ]
}

/// The moduli by direction: a run loaded up (`tensile`) measures E_y and ν_yx, one loaded
/// along x (`tensile-x`, simulated turned by 90°) E_x and ν_xy; each beside its static value.
fn directional_columns() -> Vec<Column<LatticeMetrics>> {
    use Column::Number;
    vec![
        Number("youngs_modulus_x", |r| along(r, true, r.group.youngs_modulus)),
        Number("youngs_modulus_x_fem", |r| along(r, true, r.group.youngs_modulus_fem)),
        Number("youngs_modulus_y", |r| along(r, false, r.group.youngs_modulus)),
        Number("youngs_modulus_y_fem", |r| along(r, false, r.group.youngs_modulus_fem)),
        Number("poisson_ratio_xy", |r| along(r, true, r.group.poisson_ratio)),
        Number("poisson_ratio_xy_fem", |r| along(r, true, r.group.poisson_ratio_fem)),
        Number("poisson_ratio_yx", |r| along(r, false, r.group.poisson_ratio)),
        Number("poisson_ratio_yx_fem", |r| along(r, false, r.group.poisson_ratio_fem)),
    ]
}

/// The lattice's type and what tells the types apart. Shown only beside another type than
/// square, so the square lattices' tables keep their columns.
fn type_columns() -> Vec<Column<LatticeMetrics>> {
    use Column::{Number, Word};
    vec![
        Word("lattice_type", |r| r.spec.lattice().map(|l| l.lattice_type.name().into())),
        Number("coordination", |r| r.spec.lattice().map(|l| l.coordination())),
        Number("youngs_modulus_linear", |r| r.group.youngs_modulus_linear),
        Number("shear_modulus_linear", |r| r.group.shear_modulus_linear),
    ]
}

/// The critically damped bound (steps of dt): the slowest mode, ω_min² = k_min/m, critically
/// damped and started from rest at x₀ from equilibrium moves as x₀ (1 + ω t) e^{−ω t}, which
/// falls to 1e-4 of x₀ at ω_min t = 11.75 (the 9/ω_min is e^{−ω t} = 1e-4 alone).
pub fn critical_bound_steps(spec: &RunSpec, stiffness_min: f64) -> f64 {
    CRITICAL_DECAY_1E4 / (stiffness_min / spec.mass).sqrt() / spec.dt
}

/// ω t at which (1 + ω t) e^{−ω t} = 1e-4.
pub const CRITICAL_DECAY_1E4: f64 = 11.75;

/// True when the lattice's moduli differ by direction: turned, with unequal springs along x
/// and y, or with one diagonal family.
fn is_anisotropic(l: &LatticeSpec) -> bool {
    l.rotated || l.k_x != l.k_y || matches!(l.diagonals, Diagonals::Rising | Diagonals::Falling)
}

/// `value` of a lattice run loaded along x (`x`, the `tensile-x` case) or along y (not `x`).
fn along(r: &Row<LatticeMetrics>, x: bool, value: Option<f64>) -> Option<f64> {
    r.spec.lattice().filter(|l| l.rotated == x).and(value)
}
