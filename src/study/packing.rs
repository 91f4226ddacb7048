//! The packing: bidisperse discs in a periodic square box, relaxed by a minimiser to a minimum
//! of their overlap energy. Its scene, and its measurement at rest: the virial pressure,
//! contacts, rattlers and coordination, whether it jammed, and its moduli twice, from the
//! stiffness matrix (non-affine relaxation and pre-stress included) and from the relaxed
//! energies of the packing strained a little both ways.

use std::collections::BTreeSet;

use serde::{Deserialize, Serialize};

use super::columns::{Block, Column, Slot};
use super::common::{relaxation, scene};
use crate::fem::{Entry, factor_and_solve};
use crate::measure::{ContactForces, DiscFrame, Discs};
use crate::model::{Axes, Contacts, Particles, PeriodicBox, random_bidisperse};
use crate::sim::{Network, Outcome, Packing, Scene};
use crate::spec::{PackingRun, PackingSpec, RunSpec};

/// The skin of the contact list, in small diameters (LAMMPS's `neighbor 0.2 bin` at d = 1).
const SKIN: f64 = 0.2;
/// The strain of the strained relaxations, either way: small enough that few contacts open or
/// close (the columns `*_strain_contact_changes` count them), large enough that ε² U'' stands
/// above the floor of the strained relaxations ([`STRAINED_RESIDUAL`]).
pub const STRAIN: f64 = 1e-6;
/// The largest static force the strained relaxations (and the rest state they are compared
/// with) relax to, a fraction of k d^β. A state relaxed to forces f_r holds an energy error of
/// order f_r²/λ (λ its softest stiffness), against a signal ε² U'' that is smallest near φ_J:
/// at the runs' default 1e-9, the Hertz G by strain parted from the stiffness matrix's by more
/// than 1 % in 60 of 178 jammed packings of `campaigns/jamming.yaml`; relaxed to 1e-11 or to
/// 1e-13, none of 23 of those near φ_J (N = 64 and 256, φ = 0.84 and 0.845) parted (largest
/// 0.55 % and 0.01 %), and over the campaign at 1e-13 only 2 of the 178 did, both across a
/// contact their strain makes or breaks.
pub const STRAINED_RESIDUAL: f64 = 1e-13;
/// How far above the round-off of a contact's force the strained relaxations' criterion stays
/// (a disc's force sums ~4 contacts, each off by a few units of round-off).
pub const ROUND_OFF_MARGIN: f64 = 16.0;
/// The strain gradients E of the two moduli (r → (I + εE) r, row-major): compression ...
const BULK: [f64; 4] = [1.0, 0.0, 0.0, 1.0];
/// ... and simple shear x → x + γ y.
const SHEAR: [f64; 4] = [0.0, 1.0, 0.0, 0.0];

/// What a packing measures at rest.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PackingMetrics {
    /// Σ π r² / L², the area fraction of the discs.
    pub packing_fraction: Option<f64>,
    /// L (m), the side of the periodic box.
    pub box_side: Option<f64>,
    /// 2D virial pressure p = Σ f_c l_c / 2A (N/m).
    pub pressure: Option<f64>,
    /// The pressure the relaxation's floor leaves (N/m): p below it is p = 0.
    pub pressure_floor: Option<f64>,
    /// `jammed` (p above the floor on a rigid backbone), `unjammed` (p = 0 within the floor, no
    /// backbone, or a floppy one) or `not relaxed` (within its budget).
    pub packing_state: Option<String>,
    /// Overlapping pairs.
    pub contacts: Option<u64>,
    /// Mean contacts per disc, rattlers removed.
    pub coordination: Option<f64>,
    /// Fraction of the discs that are rattlers.
    pub rattler_fraction: Option<f64>,
    /// Overlap energy Σ e(δ) (J).
    pub energy: Option<f64>,
    /// K = −A dp/dA = (1/4A) d²U/dε² + p/2 (N/m) under x → (1 + ε) x, from the stiffness
    /// matrix ([`bulk_modulus`]).
    pub bulk_modulus_2d: Option<f64>,
    /// G = (1/A) d²U/dγ² (N/m) under x → x + γ y, from the stiffness matrix.
    pub shear_modulus_2d: Option<f64>,
    /// K from relaxed energies at ε = ±1e-6 ([`strained_second_derivative`]; jammed packings).
    pub bulk_modulus_2d_strained: Option<f64>,
    /// G from relaxed energies at γ = ±1e-6 (jammed packings).
    pub shear_modulus_2d_strained: Option<f64>,
    /// Pairs of discs that touch in one of the relaxed states at compression ±ε and not in
    /// the run's state (where the stiffness matrix is taken), or the other way round, summed
    /// over the two: where any is, U is not smooth within the strain, and its second
    /// difference is no stiffness unless the contact carries next to nothing.
    pub bulk_strain_contact_changes: Option<u64>,
    /// The same under shear ±γ.
    pub shear_strain_contact_changes: Option<u64>,
    /// The packing's own jamming fraction φ_J (jammed packings): where its pressure vanishes as
    /// it is decompressed, relaxed after each step ([`own_onset`]).
    pub own_jamming_fraction: Option<f64>,
    /// The decompressions (each a relaxation) that found it.
    pub decompressions: Option<u64>,
}

/// The discs of a packing run as the spec places them: the field's geometry and the particles
/// (masses in proportion to the discs' areas, `mass` the small disc's), at rest.
/// A slowly compressed packing's discs are placed at its first stage's fraction.
pub fn discs(spec: &RunSpec, run: &PackingRun) -> (Packing, Particles) {
    let first = run.packing.stage_fractions()[0];
    discs_of(&PackingSpec { fraction: first, ..run.packing.clone() }, spec.spacing, spec.mass, spec.k)
}

/// The discs of `p`, small ones of diameter `spacing` (m) and mass `small_mass` (kg), larger
/// ones of mass ∝ area, contacts of stiffness constant `k`, at rest: the packing runs' and the
/// packing bench's (`crate::bench`).
pub fn discs_of(p: &PackingSpec, spacing: f64, small_mass: f64, k: f64) -> (Packing, Particles) {
    let small = 0.5 * spacing;
    let (periodic, x, y, radius) = random_bidisperse(p.n, small, p.radius_ratio, p.fraction, p.seed);
    let mut particles = Particles::default();
    for ((x, y), r) in x.iter().zip(&y).zip(&radius) {
        particles.push(*x, *y, small_mass * (r / small).powi(2), Axes::FREE);
    }
    (Packing { radius, periodic, k, skin: SKIN * spacing }, particles)
}

/// The force at which a packing's relaxation is judged (N): k d^β, a contact overlapped by one
/// small diameter d.
fn force_scale(spec: &RunSpec) -> f64 {
    spec.law.elastic_force(spec.k, spec.spacing).abs()
}

/// The packing's scene: its discs at their random positions, relaxed by its minimiser until
/// the largest static force is below `relax.residual_force` k d^β.
pub(super) fn build(spec: &RunSpec, run: &PackingRun) -> Scene {
    let (packing, particles) = discs(spec, run);
    packing_scene(spec, packing, particles)
}

/// The scene of the discs `particles` in `packing`, relaxed as `spec` asks.
fn packing_scene(spec: &RunSpec, packing: Packing, particles: Particles) -> Scene {
    let n = particles.len();
    let mut scene = scene(spec, particles, Network::Packing(packing), None);
    scene.sampling.relaxation = relaxation(spec, Some(force_scale(spec)), n);
    scene
}

/// The own φ_J ([`own_onset`]) of the discs `particles` placed in `packing`, relaxed by `spec`'s
/// minimiser first, and the decompressions it took; `None` where they are not jammed there. The
/// packing runs' measurement, for discs placed by hand.
pub fn own_jamming_fraction(spec: &RunSpec, packing: Packing, particles: Particles) -> Option<(f64, u64)> {
    let mut placed = packing_scene(spec, packing, particles);
    let outcome = placed.clone().run();
    outcome.trace.relaxed_at?;
    placed.particles = outcome.state.particles;
    let start = jammed_at(spec, &placed)?;
    Some(own_onset(spec, placed, start))
}

/// Relaxes the packing's `scene` at each of its stages ([`PackingSpec::stage_fractions`]): at
/// the fraction it is placed at, then, for a slow compression, squeezed to each next fraction
/// (box and positions shrunk together, at rest) and relaxed again, until a stage does not relax.
/// The scene of the last stage run (its box) and that stage's outcome, with the force
/// evaluations of every stage and, for a movie, the random start and each relaxed stage.
pub(super) fn relax(spec: &RunSpec, scene: Scene) -> (Scene, Outcome) {
    let stages = spec.packing().map(PackingSpec::stage_fractions).unwrap_or_default();
    let mut stage = scene.clone();
    let mut outcome = scene.run();
    let (mut frames, mut evaluations) = (std::mem::take(&mut outcome.frames), outcome.trace.steps);
    for pair in stages.windows(2) {
        if outcome.trace.relaxed_at.is_none() {
            break;
        }
        stage = squeezed(&stage, &outcome.state.particles, (pair[0] / pair[1]).sqrt());
        outcome = stage.clone().run();
        frames.extend(outcome.frames.pop());
        evaluations += outcome.trace.steps;
    }
    (outcome.frames, outcome.trace.steps) = (frames, evaluations);
    (stage, outcome)
}

/// `scene` with the discs at `particles`' positions, at rest, their positions and the box
/// scaled by `factor` (L ∝ 1/√φ: the ratio √(φ/φ′) of two fractions; below 1 a squeeze, above
/// 1 a decompression).
fn squeezed(scene: &Scene, particles: &Particles, factor: f64) -> Scene {
    let mut next = scene.clone();
    if let Network::Packing(packing) = &mut next.network {
        packing.periodic.side *= factor;
        packing.periodic.tilt *= factor;
    }
    let (x, y) = (&particles.x, &particles.y);
    let p = &mut next.particles;
    for i in 0..x.len() {
        (p.x[i], p.y[i], p.vx[i], p.vy[i]) = (factor * x[i], factor * y[i], 0.0, 0.0);
    }
    next
}

/// The movie frames of a packing's run as discs with their contact forces
/// ([`crate::measure::DiscFrame`]), each in its box (a compressed packing's shrinks: the start
/// and the first relaxed state share the first stage's): `None` for another network.
pub(super) fn movie_discs(spec: &RunSpec, scene: &Scene, outcome: &Outcome) -> Option<Discs> {
    let (Network::Packing(packing), Some(p)) = (&scene.network, spec.packing()) else { return None };
    let stages = p.stage_fractions();
    let boxes = std::iter::once(stages[0]).chain(stages.iter().copied()).map(|fraction| Packing {
        periodic: PeriodicBox::square(p.box_side_at(fraction, spec.spacing)),
        ..packing.clone()
    });
    let frames =
        outcome.frames.iter().zip(boxes).map(|(f, boxed)| DiscFrame::of(&boxed, spec.law, &f.x, &f.y)).collect();
    Some(Discs { radius: packing.radius.clone(), frames })
}

/// Measures the packing where its run stopped (relaxed or not): its geometry, contacts and
/// pressure, whether it jammed, and its moduli from the stiffness matrix (relaxed runs) and by
/// strain (jammed packings).
pub(super) fn measure(spec: &RunSpec, scene: &Scene, outcome: &Outcome, m: &mut PackingMetrics) {
    let Network::Packing(packing) = &scene.network else { return };
    let p = &outcome.state.particles;
    let n = p.len();
    let area = packing.periodic.area();
    let forces = ContactForces::of(packing, spec.law, &p.x, &p.y);
    let rattler = forces.rattlers(n);
    let backbone = forces.backbone(&rattler);
    let pressure = forces.pressure(area);
    let pressure_floor = pressure_floor(spec, packing);
    let relaxed = outcome.trace.relaxed_at.is_some();
    let (bulk, shear) =
        if relaxed { backbone_moduli(&forces, &backbone, &rattler, (area, pressure)) } else { (None, None) };
    // Jammed: a pressure above the floor, carried by a rigid backbone. A backbone with a floppy
    // mode (its matrix has no Cholesky factor: no K) is not rigid, and its pressure is the
    // relaxation's doing: 1000 times tighter a criterion took it 550 to 2·10⁵ times lower in 10
    // of jamming.yaml's 22 such packings (all at φ ≤ 0.84, hypostatic: z 3.4 to 4.0; 2 more
    // tried did not relax there).
    let jammed = relaxed && carried(pressure, pressure_floor, &backbone) && bulk.is_some();
    let state = match (relaxed, jammed) {
        (false, _) => "not relaxed",
        (true, true) => "jammed",
        (true, false) => "unjammed",
    };
    let kept = n - rattler.iter().filter(|&&r| r).count();
    *m = PackingMetrics {
        packing_fraction: Some(packing.area_fraction()),
        box_side: Some(packing.periodic.side),
        pressure: Some(pressure),
        pressure_floor: Some(pressure_floor),
        packing_state: Some(state.into()),
        contacts: Some(forces.pairs.len() as u64),
        coordination: Some(if kept > 0 { 2.0 * backbone.len() as f64 / kept as f64 } else { 0.0 }),
        rattler_fraction: Some((n - kept) as f64 / n as f64),
        energy: Some(forces.total_energy()),
        ..PackingMetrics::default()
    };
    (m.bulk_modulus_2d, m.shear_modulus_2d) = (bulk, shear);
    if let Some((rest, energy)) = jammed.then(|| polished(spec, scene, outcome)).flatten() {
        let touching = pair_set(&forces.pairs);
        let strained = |strain| strained_second_derivative(&rest, energy, &touching, strain);
        let (bulk, bulk_changes) = strained(BULK).unzip();
        let (shear, shear_changes) = strained(SHEAR).unzip();
        (m.bulk_modulus_2d_strained, m.bulk_strain_contact_changes) =
            (bulk.map(|u| bulk_modulus(u, area, pressure)), bulk_changes);
        (m.shear_modulus_2d_strained, m.shear_strain_contact_changes) = (shear.map(|u| u / area), shear_changes);
    }
    if let Some(start) =
        bulk.filter(|_| jammed).map(|k| Jammed { fraction: packing.area_fraction(), pressure, bulk: k })
    {
        let rest = Scene { particles: p.clone(), ..scene.clone() };
        let (fraction, steps) = own_onset(spec, rest, start);
        (m.own_jamming_fraction, m.decompressions) = (Some(fraction), Some(steps));
    }
}

/// A pressure above the relaxation's floor, carried by a backbone: the part of "jammed" that
/// needs no stiffness matrix (the rest: the backbone is rigid, it has a K).
fn carried(pressure: f64, floor: f64, backbone: &[usize]) -> bool {
    pressure > floor && !backbone.is_empty()
}

/// The pressure a packing's relaxation leaves (N/m), below which p is p = 0: every contact
/// carrying at most the residual force f_r (z ≤ 6: at most 3n contacts) gives
/// p ≤ 3 n f_r (2 r_max) / 2A.
fn pressure_floor(spec: &RunSpec, packing: &Packing) -> f64 {
    let residual = spec.relax().and_then(|r| r.residual_force).unwrap_or(0.0) * force_scale(spec);
    let largest = packing.radius.iter().fold(0.0f64, |a, r| a.max(*r));
    3.0 * packing.radius.len() as f64 * residual * 2.0 * largest / (2.0 * packing.periodic.area())
}

/// A jammed packing at rest: its area fraction, pressure p (N/m) and bulk modulus K (N/m).
#[derive(Clone, Copy, Debug)]
struct Jammed {
    fraction: f64,
    pressure: f64,
    bulk: f64,
}

impl Jammed {
    /// Newton's estimate of its own φ_J for contact forces ∝ δ^β ([`own_onset`]):
    /// φ − β p φ/K, no lower than `below`, a fraction known to be unjammed. `None` where K ≤ 0
    /// (a jammed state that softens under compression, seen in monodisperse packings): the
    /// step would go up, past the state's own φ, where it is known to be jammed.
    fn onset_estimate(&self, beta: f64, below: f64) -> Option<f64> {
        (self.bulk > 0.0).then(|| (self.fraction - beta * self.pressure * self.fraction / self.bulk).max(below))
    }
}

/// The most decompressions [`own_onset`] makes: Newton's steps take a packing from φ = 0.92 to
/// its φ_J within [`ONSET_PRECISION`] in 2 to 6 (jamming.yaml).
const MAX_DECOMPRESSIONS: u64 = 16;
/// [`own_onset`] stops when φ_J is known to this fraction of φ: its Newton step, or its bracket
/// [unjammed, jammed], is narrower. A finite packing unjams at a small finite p (a contact
/// opens and its backbone turns floppy: p ~ 1e-5 k/d at N = 1024, a Newton step of ~3e-5 left),
/// so each halving of the bracket below that costs a relaxation; 5e-5 of φ (4e-5) is 4 % of the
/// smallest Δφ of jamming.yaml's packings (~1e-3), and the fits start at 5 times it.
pub const ONSET_PRECISION: f64 = 5e-5;

/// The packing's own φ_J and the decompressions it took: O'Hern et al.'s jamming point of one
/// state, where its pressure vanishes as it is decompressed (box and positions grown together,
/// relaxed after each step). Newton's method on p^(1/β)(φ) = 0, p ∝ Δφ^β near φ_J: with
/// K = −A dp/dA = φ dp/dφ (A ∝ 1/φ), d p^(1/β)/dφ = p^(1/β − 1) K/(βφ), so the step is
/// Δφ = β p φ/K. A step that unjams the packing bounds φ_J below; the next stays above that
/// bound (halfway to it at least). A state with K ≤ 0 has no Newton step: the bracket is halved.
/// The answer is the last jammed state's Newton estimate (or the bracket's middle), within the
/// bracket [unjammed, jammed].
fn own_onset(spec: &RunSpec, mut rest: Scene, start: Jammed) -> (f64, u64) {
    let beta = spec.law.beta();
    let (mut at, mut below) = (start, 0.0f64);
    let middle = |at: &Jammed, below: f64| 0.5 * (at.fraction + below);
    for step in 0..MAX_DECOMPRESSIONS {
        let estimate = at.onset_estimate(beta, below);
        if let Some(estimate) = estimate.filter(|e| at.fraction - e < ONSET_PRECISION * at.fraction) {
            return (estimate, step);
        }
        let target = estimate.unwrap_or(below).max(middle(&at, below));
        let (next, relaxed) = decompressed(&rest, target / at.fraction);
        match relaxed.then(|| jammed_at(spec, &next)).flatten() {
            Some(state) => (rest, at) = (next, state),
            None => below = target,
        }
    }
    (at.onset_estimate(beta, below).unwrap_or_else(|| middle(&at, below)), MAX_DECOMPRESSIONS)
}

/// `rest` with its box and positions grown to the fraction `ratio` times its own (L ∝ 1/√φ) and
/// relaxed again from rest, and whether it relaxed.
fn decompressed(rest: &Scene, ratio: f64) -> (Scene, bool) {
    let mut next = squeezed(rest, &rest.particles, ratio.sqrt().recip());
    let outcome = next.clone().run();
    next.particles = outcome.state.particles;
    (next, outcome.trace.relaxed_at.is_some())
}

/// The packing of `scene` where its discs are, when jammed there: p above the relaxation's
/// floor, carried by a rigid backbone (one with a K).
fn jammed_at(spec: &RunSpec, scene: &Scene) -> Option<Jammed> {
    let Network::Packing(packing) = &scene.network else { return None };
    let p = &scene.particles;
    let forces = ContactForces::of(packing, spec.law, &p.x, &p.y);
    let rattler = forces.rattlers(p.len());
    let backbone = forces.backbone(&rattler);
    let area = packing.periodic.area();
    let pressure = forces.pressure(area);
    if !carried(pressure, pressure_floor(spec, packing), &backbone) {
        return None;
    }
    let u_eps = stiffness_modulus(&forces, &backbone, &rattler, BULK)?;
    Some(Jammed { fraction: packing.area_fraction(), pressure, bulk: bulk_modulus(u_eps, area, pressure) })
}

/// The packing of `scene` at rest where `outcome` left it, relaxed again by the run's own
/// minimiser to forces below [`strained_residual`] (or the run's criterion, if tighter): the
/// state the strained relaxations start from and are compared with, as a scene (its discs
/// there, at rest, the tighter criterion) and its energy (J). `None` when it does not relax.
fn polished(spec: &RunSpec, scene: &Scene, outcome: &Outcome) -> Option<(Scene, f64)> {
    let Network::Packing(packing) = &scene.network else { return None };
    let limit = strained_residual(spec, packing.periodic.side);
    let mut rest = scene.clone();
    let relaxation = rest.sampling.relaxation.as_mut()?;
    relaxation.residual_force = Some(relaxation.residual_force.map_or(limit, |run| run.min(limit)));
    rest.particles = outcome.state.particles.clone();
    at_rest(&mut rest.particles);
    let polished = rest.clone().run();
    let energy = polished.trace.relaxed_at.and(polished.trace.potential.last().copied())?;
    rest.particles = polished.state.particles;
    at_rest(&mut rest.particles);
    Some((rest, energy))
}

/// `particles` brought to rest where they are (a minimiser starts from rest).
fn at_rest(particles: &mut Particles) {
    particles.vx.fill(0.0);
    particles.vy.fill(0.0);
}

/// The largest static force (N) the strained relaxations relax to: [`STRAINED_RESIDUAL`] of
/// k d^β, or, in a box so large that this is below it, [`ROUND_OFF_MARGIN`] times the
/// round-off of a contact's force, k d^(β−1) L ε_mach (an overlap is a difference of two
/// positions of size up to the box side L, each resolved to L ε_mach).
fn strained_residual(spec: &RunSpec, side: f64) -> f64 {
    let scale = force_scale(spec);
    (STRAINED_RESIDUAL * scale).max(ROUND_OFF_MARGIN * scale / spec.spacing * side * f64::EPSILON)
}

/// K = (1/4A) d²U/dε² + p/2 ([`bulk_modulus`]) and G = (1/A) d²U/dγ² (N/m) of a packing at rest
/// with contacts `forces` among `discs` discs in a box of area `area` (m²), from its stiffness
/// matrix ([`stiffness_modulus`]); `None` for a floppy backbone.
pub fn stiffness_moduli(forces: &ContactForces, discs: usize, area: f64) -> (Option<f64>, Option<f64>) {
    let rattler = forces.rattlers(discs);
    backbone_moduli(forces, &forces.backbone(&rattler), &rattler, (area, forces.pressure(area)))
}

/// [`stiffness_moduli`] of the backbone's contacts `backbone`, rattlers `rattler`, found, in a
/// box of area `area` at the pressure `pressure` of `forces` (the caller has it already).
fn backbone_moduli(
    forces: &ContactForces,
    backbone: &[usize],
    rattler: &[bool],
    (area, pressure): (f64, f64),
) -> (Option<f64>, Option<f64>) {
    // Without a backbone nothing carries a strain or a pressure: K = G = 0 (the pressure's
    // p/2 would be the relaxation floor's round-off).
    if backbone.is_empty() {
        return (Some(0.0), Some(0.0));
    }
    let moduli = |strain| stiffness_modulus(forces, backbone, rattler, strain);
    (moduli(BULK).map(|u| bulk_modulus(u, area, pressure)), moduli(SHEAR).map(|u| u / area))
}

/// The bulk modulus K = −A dp/dA (N/m; O'Hern et al.'s B) of a packing at pressure `pressure`
/// (N/m) in a box of area `area` (m²), from U_εε = d²U/dε² (J) under x → (1 + ε) x: there
/// A = A₀ (1 + ε)² and p = −dU/dA, so U_εε = 4A² d²U/dA² − 2A p and K = A d²U/dA² =
/// U_εε/(4A) + p/2. (U_εε/(4A) alone is K − p/2: the pre-stress's share left out.) Simple shear
/// keeps the area, so G = (1/A) d²U/dγ² needs no such term.
fn bulk_modulus(u_eps: f64, area: f64, pressure: f64) -> f64 {
    u_eps / (4.0 * area) + 0.5 * pressure
}

/// d²U/dε² (J) of the relaxed packing under the strain gradient `strain`, from its stiffness
/// matrix: the affine part less Ξᵀ H⁻¹ Ξ, H = Σ over the backbone's contacts of the blocks
/// k_t n̂n̂ᵀ + (s/l)(I − n̂n̂ᵀ) (the second the pre-stress), over the discs that are not
/// rattlers, one of them held (H's null space is the two translations, to which Ξ is
/// orthogonal); its callers give a packing without a backbone 0. `None` when H is singular
/// beyond the translations (a floppy backbone).
fn stiffness_modulus(forces: &ContactForces, backbone: &[usize], rattler: &[bool], strain: [f64; 4]) -> Option<f64> {
    let discs = rattler.len();
    let (affine, mixed) = forces.affine(backbone, strain, discs);
    let mut dof = vec![usize::MAX; 2 * discs];
    let mut free = 0;
    // The first disc of the backbone is held: its dofs stay unnumbered.
    for p in (0..discs).filter(|&p| !rattler[p]).skip(1) {
        (dof[2 * p], dof[2 * p + 1]) = (free, free + 1);
        free += 2;
    }
    let mut entries: Vec<Entry> = Vec::with_capacity(16 * backbone.len());
    for &c in backbone {
        let (n, s, k_t, l) = (forces.normal[c], forces.tension[c], forces.tangent[c], forces.length[c]);
        let n = [n.0, n.1];
        let block = |a: usize, b: usize| k_t * n[a] * n[b] + s / l * (f64::from(u8::from(a == b)) - n[a] * n[b]);
        let (i, j) = (forces.pairs.i[c], forces.pairs.j[c]);
        for (p, sign_p) in [(i, 1.0), (j, -1.0)] {
            for (q, sign_q) in [(i, 1.0), (j, -1.0)] {
                for a in 0..2 {
                    for b in 0..2 {
                        let (row, col) = (dof[2 * p + a], dof[2 * q + b]);
                        if row != usize::MAX && col != usize::MAX {
                            entries.push(Entry { row, col, val: sign_p * sign_q * block(a, b) });
                        }
                    }
                }
            }
        }
    }
    let mut rhs = vec![0.0; free];
    for (d, &index) in dof.iter().enumerate().filter(|(_, index)| **index != usize::MAX) {
        rhs[index] = mixed[d];
    }
    let u = factor_and_solve(free, &mut entries, &rhs)?;
    Some(affine - rhs.iter().zip(&u).map(|(a, b)| a * b).sum::<f64>())
}

/// d²U/dε² (J) by relaxed energies: the packing at rest `rest` (energy `at_rest`, J) strained
/// by ±ε along `strain` and relaxed again ([`strained_state`]), (U(+ε) − 2U(0) + U(−ε))/ε²,
/// with the pairs of discs that touch in either strained state and not in `touching` (the
/// run's state's pairs), or the other way round, over both. `None` when either does not relax.
fn strained_second_derivative(
    rest: &Scene,
    at_rest: f64,
    touching: &BTreeSet<(usize, usize)>,
    strain: [f64; 4],
) -> Option<(f64, u64)> {
    let (plus, made_plus) = strained_state(rest, touching, STRAIN, strain)?;
    let (minus, made_minus) = strained_state(rest, touching, -STRAIN, strain)?;
    Some(((plus - 2.0 * at_rest + minus) / (STRAIN * STRAIN), made_plus + made_minus))
}

/// The packing at rest `rest` strained by `epsilon` along `strain` (positions and box
/// together), relaxed again by its minimiser and criterion: its energy (J) and how many pairs
/// of discs touch there but not in `touching`, or the other way round. `None` when it does
/// not relax.
fn strained_state(
    rest: &Scene,
    touching: &BTreeSet<(usize, usize)>,
    epsilon: f64,
    strain: [f64; 4],
) -> Option<(f64, u64)> {
    let mut strained = rest.clone();
    let Network::Packing(packing) = &mut strained.network else { return None };
    let box_0 = packing.periodic;
    // The box's edges (L, 0) and (tilt, L) deform with the discs.
    packing.periodic = PeriodicBox {
        side: box_0.side * (1.0 + epsilon * strain[3]),
        tilt: box_0.tilt + epsilon * (strain[0] * box_0.tilt + strain[1] * box_0.side),
    };
    let (x, y) = (&rest.particles.x, &rest.particles.y);
    for i in 0..x.len() {
        strained.particles.x[i] = x[i] + epsilon * (strain[0] * x[i] + strain[1] * y[i]);
        strained.particles.y[i] = y[i] + epsilon * (strain[2] * x[i] + strain[3] * y[i]);
    }
    let relaxed = strained.clone().run();
    let energy = relaxed.trace.relaxed_at.and(relaxed.trace.potential.last().copied())?;
    let Network::Packing(packing) = &strained.network else { return None };
    let now = pair_set(&packing.overlapping(&relaxed.state.particles.x, &relaxed.state.particles.y));
    Some((energy, touching.symmetric_difference(&now).count() as u64))
}

/// The pairs of discs of `contacts` as (i, j), i < j (a pair touching through two images at
/// once, possible only in a box under two large diameters wide, counts once).
fn pair_set(contacts: &Contacts) -> BTreeSet<(usize, usize)> {
    contacts.i.iter().zip(&contacts.j).map(|(&i, &j)| (i.min(j), i.max(j))).collect()
}

/// The packing's result columns: what was asked, what it became, and its moduli both ways.
pub(super) fn columns() -> Vec<Block<PackingMetrics>> {
    use Column::{Count, Number, Word};
    let columns: Vec<Column<PackingMetrics>> = vec![
        Count("discs", |r| r.spec.packing().map(|p| p.n as u64)),
        Number("radius_ratio", |r| r.spec.packing().map(|p| p.radius_ratio)),
        Number("packing_fraction", |r| r.group.packing_fraction),
        Number("box_side", |r| r.group.box_side),
        Word("packing_state", |r| r.group.packing_state.clone()),
        Number("pressure", |r| r.group.pressure),
        Number("pressure_floor", |r| r.group.pressure_floor),
        Count("contacts", |r| r.group.contacts),
        Number("backbone_coordination", |r| r.group.coordination),
        Number("rattler_fraction", |r| r.group.rattler_fraction),
        Number("energy", |r| r.group.energy),
        Number("bulk_modulus_2d", |r| r.group.bulk_modulus_2d),
        Number("bulk_modulus_2d_strained", |r| r.group.bulk_modulus_2d_strained),
        Number("shear_modulus_2d", |r| r.group.shear_modulus_2d),
        Number("shear_modulus_2d_strained", |r| r.group.shear_modulus_2d_strained),
        Count("bulk_strain_contact_changes", |r| r.group.bulk_strain_contact_changes),
        Count("shear_strain_contact_changes", |r| r.group.shear_strain_contact_changes),
        Count("packing_relax_steps", |r| r.spec.packing().map(|_| r.steps)),
        Number("own_jamming_fraction", |r| r.group.own_jamming_fraction),
        Count("decompressions", |r| r.group.decompressions),
    ];
    vec![Block { slot: Slot::Tail, shown: Some(|spec| spec.packing().is_some()), columns }]
}
