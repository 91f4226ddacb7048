//! Velocity control on floppy networks: the run's status against an exact rank argument made
//! here, not taken from `fem.rs`. The force-controlled network's stiffness K (the scene's
//! supports only, the top row free) is assembled densely at its rest geometry and factored by
//! Cholesky with its zero pivots skipped; back substitution gives a basis N of its zero-energy
//! motions. A velocity drive (the top row held where it stops, moved by the same amount along
//! the drive, free across it) is taken by a zero-energy motion exactly when the drive pattern d
//! (1 on every top-row node's driven axis) lies in the span of P N, P the top row's driven
//! components: then a motion with no energy moves the top row as the drive does. A force load
//! (d per node) drives a mechanism when some zero mode moves the top row on average, dᵀP v ≠ 0.
//! The networks are those of the vk campaign: every lattice type on both supports, tensile and
//! shear, 12 × 11 nodes.

use crate::common::{execute, runs};
use mdsolids::fem::{Analyses, StaticSolution, Truss};
use mdsolids::model::{Bonds, Linear};
use mdsolids::runner::RunRecord;
use mdsolids::sim::{Load, RunStatus};
use mdsolids::spec::{Control, LoadCase, RunSpec, Supports};
use mdsolids::study::build_scene;

/// The vk campaign's scene under `load` (MD stopped after 1 t_c: the static answer, which
/// decides the status, comes first and is complete).
fn campaign(load: &str) -> String {
    format!(
        "version: 1\nname: vk\ndefaults:\n  material: {{mass: 0.785, k: 2.0e9}}\n  geometry: {{spacing: 0.1, depth: 0.01}}\n  time: {{integrator: velocity-verlet, dt_per_tc: 50}}\nscenes:\n  - name: l\n    kind: lattice\n    damping: {{restitution: 0.5, background: 12000.0}}\n    lattice: {{nx: 12, ny: 11}}\n    load: {load}\n    relax: {{max_tc: 1}}\n    grid:\n      lattice.type: [square, triangular, honeycomb, kagome]\n      supports: [coursework, periodic-x]\n      load.case: [tensile, shear]\n"
    )
}

const VELOCITY: &str = "{control: velocity, strain: 1.0e-4}";
const FORCE: &str = "{per_node: 1000.0}";

/// A pivot at most this fraction of K's largest diagonal entry s is a zero-energy mode. The
/// networks here split by twelve decades: dropped pivots at most 1.6e-15 s (round-off of
/// eliminations that cancel), kept ones at least 4e-3 s.
const ZERO_PIVOT: f64 = 1e-10;
/// The drive lies in the span of the zero modes' top-row motions when its part outside is at
/// most this fraction of ‖d‖: measured at most 1.7e-15 where it does, at least 0.82 where not.
const IN_SPAN: f64 = 1e-6;
/// A unit zero mode moves the top row when its top-row motion (or, for a force load, that
/// motion's mean, dᵀP v/‖d‖) exceeds this: round-off of the back substitution leaves at most
/// 1.5e-14, a motion is at least 0.04.
const MOVES: f64 = 1e-9;

/// A spring: (i, j, k (N/m), vector d₀ from j to i at rest (m), its rest length |d₀|).
type Spring = (usize, usize, f64, [f64; 2]);

/// A spring's unit vector n̂ (from j to i), tension s (N) and tangent block
/// A = k n̂ n̂ᵀ + (s/r)(I − n̂ n̂ᵀ) (N/m) at displacements `u` (m, by node and axis), its force on
/// i being −s n̂ and −A Δu more to first order in a further relative move Δu: at rest s = 0 and
/// A = k n̂ n̂ᵀ.
fn spring_state(&(i, j, k, d0): &Spring, u: &impl Fn(usize, usize) -> f64) -> ([f64; 2], f64, [[f64; 2]; 2]) {
    let d = [d0[0] + u(i, 0) - u(j, 0), d0[1] + u(i, 1) - u(j, 1)];
    let r = d[0].hypot(d[1]);
    let (n, tension) = ([d[0] / r, d[1] / r], k * (r - d0[0].hypot(d0[1])));
    let block =
        [0, 1].map(|p| [0, 1].map(|q| k * n[p] * n[q] + tension / r * (f64::from(u8::from(p == q)) - n[p] * n[q])));
    (n, tension, block)
}

/// A network's springs over the free degrees of freedom of its supports.
struct Network {
    springs: Vec<Spring>,
    /// Row of each degree of freedom (2i: x of node i, 2i + 1: y) among the free ones.
    free: Vec<Option<usize>>,
    rows: usize,
}

impl Network {
    /// The scene's network on the scene's supports; `held` more nodes held along the drive.
    fn of(spec: &RunSpec, held: &[usize], along_y: bool) -> Network {
        let scene = build_scene(spec);
        let p = &scene.particles;
        let mut springs = Vec::new();
        scene.network.for_each_bond(&p.x, &p.y, |i, j, _, k, shift| {
            springs.push((i, j, k, [p.x[i] - p.x[j] + shift, p.y[i] - p.y[j]]));
        });
        let mut free = vec![None; 2 * p.len()];
        let mut rows = 0;
        for (dof, slot) in free.iter_mut().enumerate() {
            let (node, y) = (dof / 2, dof % 2 == 1);
            let supported = if y { p.held_y.contains(&node) } else { p.held_x.contains(&node) };
            if !(supported || y == along_y && held.contains(&node)) {
                *slot = Some(rows);
                rows += 1;
            }
        }
        Network { springs, free, rows }
    }

    /// The tangent stiffness over the free degrees of freedom at displacements `u` (dense,
    /// row-major): each spring's block ([`spring_state`]); at rest K, k n̂ n̂ᵀ per spring.
    fn stiffness(&self, u: &impl Fn(usize, usize) -> f64) -> Vec<f64> {
        let n = self.rows;
        let mut k = vec![0.0; n * n];
        for spring in &self.springs {
            let (_, _, block) = spring_state(spring, u);
            for (a, sign_a) in [(spring.0, 1.0), (spring.1, -1.0)] {
                for (b, sign_b) in [(spring.0, 1.0), (spring.1, -1.0)] {
                    for (p, entries) in block.iter().enumerate() {
                        for (q, entry) in entries.iter().enumerate() {
                            if let (Some(row), Some(column)) = (self.free[2 * a + p], self.free[2 * b + q]) {
                                k[row * n + column] += sign_a * sign_b * entry;
                            }
                        }
                    }
                }
            }
        }
        k
    }
}

/// Cholesky K = L Lᵀ of a positive semi-definite K (dense, row-major, n × n), a pivot at most
/// [`ZERO_PIVOT`] s taken as a zero-energy mode (its column of L left 0). Returns L, which
/// columns are zero, the largest dropped pivot and the smallest kept one, over s.
fn semidefinite_cholesky(k: &[f64], n: usize) -> (Vec<f64>, Vec<bool>, f64, f64) {
    let scale = (0..n).map(|i| k[i * n + i]).fold(0.0f64, f64::max);
    let mut l = vec![0.0; n * n];
    let mut zero = vec![false; n];
    let (mut dropped, mut kept) = (0.0f64, f64::INFINITY);
    for j in 0..n {
        let mut d = k[j * n + j];
        for p in 0..j {
            d -= l[j * n + p] * l[j * n + p];
        }
        if d <= ZERO_PIVOT * scale {
            zero[j] = true;
            dropped = dropped.max(d.abs() / scale);
            continue;
        }
        kept = kept.min(d / scale);
        let pivot = d.sqrt();
        l[j * n + j] = pivot;
        for i in j + 1..n {
            let mut sum = k[i * n + j];
            for p in 0..j {
                sum -= l[i * n + p] * l[j * n + p];
            }
            l[i * n + j] = sum / pivot;
        }
    }
    (l, zero, dropped, kept)
}

/// A basis of K's zero-energy motions from its factor: per zero pivot z, v_z = 1, the other
/// zero pivots' entries 0, and Lᵀv = 0 solved for the rest by back substitution (K v = L Lᵀ v = 0).
fn zero_modes(l: &[f64], zero: &[bool]) -> Vec<Vec<f64>> {
    let n = zero.len();
    let mut modes = Vec::new();
    for z in (0..n).filter(|&z| zero[z]) {
        let mut v = vec![0.0; n];
        v[z] = 1.0;
        for i in (0..n).rev().filter(|&i| !zero[i]) {
            let mut sum = 0.0;
            for p in i + 1..n {
                sum += l[p * n + i] * v[p];
            }
            v[i] = -sum / l[i * n + i];
        }
        modes.push(v);
    }
    modes
}

/// The part of `d` outside the span of `columns`, relative to ‖d‖, by modified Gram–Schmidt: a
/// column with at most [`MOVES`] of it left is in the span of the ones before.
fn outside_span(d: &[f64], columns: &[Vec<f64>]) -> f64 {
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for column in columns {
        let mut c = column.clone();
        for q in &basis {
            let along = dot(q, &c);
            c.iter_mut().zip(q).for_each(|(x, y)| *x -= along * y);
        }
        let left = dot(&c, &c).sqrt();
        if left > MOVES {
            basis.push(c.into_iter().map(|x| x / left).collect());
        }
    }
    let mut rest = d.to_vec();
    for q in &basis {
        let along = dot(q, &rest);
        rest.iter_mut().zip(q).for_each(|(x, y)| *x -= along * y);
    }
    (dot(&rest, &rest) / dot(d, d)).sqrt()
}

/// Whether the run of `spec` is a mechanism by the rank argument: (velocity drive, force load).
fn expected_mechanisms(spec: &RunSpec) -> (bool, bool) {
    let l = spec.lattice().unwrap();
    let along_y = l.load_case == LoadCase::Tensile;
    let top = l.layout(spec.spacing).edges.top;
    let network = Network::of(spec, &[], along_y);
    let (factor, zero, dropped, kept) = semidefinite_cholesky(&network.stiffness(&|_, _| 0.0), network.rows);
    assert!(dropped < 1e-13 && kept > 1e-6, "pivots: dropped up to {dropped:e} s, kept from {kept:e} s");
    let driven: Vec<usize> = top.iter().map(|&n| network.free[2 * n + usize::from(along_y)].unwrap()).collect();
    // Each zero mode's top-row motion per unit length of the mode.
    let top_motions: Vec<Vec<f64>> = zero_modes(&factor, &zero)
        .iter()
        .map(|v| {
            let length = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            driven.iter().map(|&row| v[row] / length).collect()
        })
        .collect();
    let d = vec![1.0; top.len()];
    let outside = outside_span(&d, &top_motions);
    assert!(!(1e-12..=0.1).contains(&outside), "the drive's part outside the span, {outside:e}, is neither");
    // A force load has no static answer when some zero mode moves the top row on average.
    let lifted = top_motions.iter().map(|m| m.iter().sum::<f64>().abs() / (top.len() as f64).sqrt());
    let force = lifted.fold(0.0f64, f64::max) > MOVES;
    (outside <= IN_SPAN, force)
}

fn label(r: &RunRecord) -> String {
    format!("{} {:?}", r.run_id, r.spec.varied)
}

#[test]
fn a_velocity_drive_is_a_mechanism_exactly_where_a_zero_energy_motion_takes_it() {
    let (driven, loaded) = (runs(&campaign(VELOCITY)), runs(&campaign(FORCE)));
    assert_eq!((driven.len(), loaded.len()), (16, 16));
    let mut floppy = 0;
    for (drive, load) in driven.iter().zip(&loaded) {
        assert_eq!(drive.varied, load.varied);
        let (by_drive, by_load) = expected_mechanisms(drive);
        // A zero mode that moves the top row as the drive does moves it on average too.
        assert!(!by_drive || by_load, "{:?}", drive.varied);
        for (spec, expected) in [(drive, by_drive), (load, by_load)] {
            let r = execute(spec);
            assert_eq!(
                r.status == RunStatus::Mechanism,
                expected,
                "{}: {} {}",
                label(&r),
                r.status.as_str(),
                r.message
            );
            if expected && spec.lattice().unwrap().control == Control::Velocity {
                assert!(r.message.contains("velocity drive is taken by a zero-stiffness motion"), "{}", r.message);
                let m = &r.metrics.lattice;
                assert!(m.youngs_modulus_linear.is_none() && m.shear_modulus_linear.is_none(), "{}", label(&r));
                floppy += 1;
            }
        }
    }
    // honeycomb: tensile on coursework, shear on both; kagome: shear on both.
    assert_eq!(floppy, 5);
}

/// Solves K u = b on the factor of [`semidefinite_cholesky`], a zero pivot's unknown set to 0
/// (b has no part along a zero mode of a driven network: the drive's force meets none).
fn semidefinite_solve(l: &[f64], zero: &[bool], b: &[f64]) -> Vec<f64> {
    let n = b.len();
    let mut y = vec![0.0; n];
    for i in (0..n).filter(|&i| !zero[i]) {
        let mut sum = b[i];
        for p in 0..i {
            sum -= l[i * n + p] * y[p];
        }
        y[i] = sum / l[i * n + i];
    }
    let mut u = vec![0.0; n];
    for i in (0..n).rev().filter(|&i| !zero[i]) {
        let mut sum = y[i];
        for p in i + 1..n {
            sum -= l[p * n + i] * u[p];
        }
        u[i] = sum / l[i * n + i];
    }
    u
}

/// Where a dense answer of a drive is linearised: at the rest geometry (the linear problem),
/// or at the driven state, the top row at its travel and the rest where it was, as the run took
/// it before 2026-12-07 (its tangent holding the driven bonds' tension as geometric stiffness).
#[derive(Clone, Copy, PartialEq)]
enum About {
    Rest,
    Driven,
}

/// E (Pa) of `spec`'s network with its top row held and moved up by `travel` (m), solved
/// densely here by one Newton step from the state `about`, u₀: K_ff(u₀) Δu_f = R_f(u₀) −
/// K_fp(u₀)(u_p − u₀_p), R the springs' forces at u₀ (none at rest), then the top row's reaction
/// F along y ([`top_reaction`]), E = (F/(d L_x))/(ΔL_y/L_y) with ΔL_y the top row's mean u_y less
/// the bottom row's. About the rest geometry this is the linear answer, K_ff u_f = −K_fp u_p.
fn driven_youngs_modulus(spec: &RunSpec, travel: f64, about: About) -> f64 {
    let l = spec.lattice().unwrap();
    let edges = l.layout(spec.spacing).edges;
    let network = Network::of(spec, &edges.top, true);
    let imposed = |node: usize, axis: usize| if axis == 1 && edges.top.contains(&node) { travel } else { 0.0 };
    let start = |node: usize, axis: usize| if about == About::Driven { imposed(node, axis) } else { 0.0 };
    let mut force = vec![0.0; network.rows];
    for spring in &network.springs {
        let (n, tension, block) = spring_state(spring, &start);
        let step = |node: usize, axis: usize| imposed(node, axis) - start(node, axis);
        let moved = [0, 1].map(|p| step(spring.0, p) - step(spring.1, p));
        let pull = [0, 1].map(|p| tension * n[p] + block[p][0] * moved[0] + block[p][1] * moved[1]);
        for (node, sign) in [(spring.0, 1.0), (spring.1, -1.0)] {
            for (axis, along) in pull.iter().enumerate() {
                if let Some(row) = network.free[2 * node + axis] {
                    force[row] -= sign * along;
                }
            }
        }
    }
    let (factor, zero, _, _) = semidefinite_cholesky(&network.stiffness(&start), network.rows);
    let free = semidefinite_solve(&factor, &zero, &force);
    let u = |node: usize, axis: usize| network.free[2 * node + axis].map_or(imposed(node, axis), |row| free[row]);
    let reaction = top_reaction(&network, &edges.top, about, &u);
    let mean = |nodes: &[usize]| nodes.iter().map(|&n| u(n, 1)).sum::<f64>() / nodes.len() as f64;
    let strain = (mean(&edges.top) - mean(&edges.bottom)) / edges.height;
    reaction / l.depth / edges.width / strain
}

/// The y force (N) the supports apply to the `top` row at displacements `u`: at first order
/// about the rest geometry, k n̂ (n̂·Δu) per spring (the linear problem's reaction), or the
/// springs' forces at u themselves, s n̂ (as the run took the reaction of its answer about the
/// driven state).
fn top_reaction(network: &Network, top: &[usize], about: About, u: &impl Fn(usize, usize) -> f64) -> f64 {
    let mut reaction = 0.0;
    for spring in &network.springs {
        let pull = match about {
            About::Rest => {
                let (_, _, block) = spring_state(spring, &|_, _| 0.0);
                let moved = [0, 1].map(|p| u(spring.0, p) - u(spring.1, p));
                block[1][0] * moved[0] + block[1][1] * moved[1]
            }
            About::Driven => {
                let (n, tension, _) = spring_state(spring, u);
                tension * n[1]
            }
        };
        reaction += [(spring.0, 1.0), (spring.1, -1.0)]
            .iter()
            .filter(|(n, _)| top.contains(n))
            .map(|(_, s)| s * pull)
            .sum::<f64>();
    }
    reaction
}

/// How far a linear modulus may lie from the same linear problem solved another way: round-off
/// of two factorisations of ~100 to ~300 unknowns, the refined sparse one's and the dense one's
/// (measured at most 7e-15 below).
const LINEAR_TOLERANCE: f64 = 1e-9;

/// The top row's travel (m) of a velocity-driven lattice: strain · L_y.
fn travel(spec: &RunSpec) -> f64 {
    let l = spec.lattice().unwrap();
    l.drive_strain * l.layout(spec.spacing).edges.height
}

/// E (Pa) of a run's linear static answer.
fn linear_youngs_modulus(spec: &RunSpec) -> f64 {
    let r = execute(spec);
    r.metrics.lattice.youngs_modulus_linear.unwrap_or_else(|| panic!("{}: no E_linear: {}", label(&r), r.message))
}

#[test]
fn a_driven_kagome_block_pulled_is_rigid_and_keeps_its_modulus() {
    // Under force control the kagome block on coursework supports pulled is a mechanism (zero
    // modes lift its top row unevenly); held level by the drive it is rigid. Its moduli against
    // the dense first-order answer of the same drive: the non-linear static answer (`*_fem`) to
    // 2e-3, of the order of the strain (1e-4) times the tenfold the marginal network's rotations
    // add (measured 9.9e-4); the linear one (`*_linear`) to round-off (measured 7e-15). Taken
    // about the driven state instead, as the run did before 2026-12-07, its tangent holding the
    // driven bonds' tension, ~k·travel, as geometric stiffness s/r ~ 1e-3 k on the modes the
    // drive holds, the linear E was 5.1e-3 off: 7.529278574652e10 Pa, which the dense solve
    // about that state reproduces (measured to 3e-13), so the dense solve stands for the old
    // answer where the tests below show the tolerance rejecting it.
    let yaml = campaign(VELOCITY).replace("[square, triangular, honeycomb, kagome]", "[kagome]");
    let pulled = |s: &RunSpec| {
        s.lattice().is_some_and(|l| l.supports == Supports::Coursework && l.load_case == LoadCase::Tensile)
    };
    let spec = runs(&yaml).into_iter().find(pulled).unwrap();
    let r = execute(&spec);
    assert_ne!(r.status, RunStatus::Mechanism, "{}", r.message);
    let dense = driven_youngs_modulus(&spec, travel(&spec), About::Rest);
    let m = &r.metrics.lattice;
    for (name, value, tolerance) in
        [("fem", m.youngs_modulus_fem, 2e-3), ("linear", m.youngs_modulus_linear, LINEAR_TOLERANCE)]
    {
        let value = value.unwrap_or_else(|| panic!("no E_{name}"));
        assert!((value / dense - 1.0).abs() < tolerance, "E_{name} {value:e} against the dense {dense:e}");
    }
    let driven = driven_youngs_modulus(&spec, travel(&spec), About::Driven);
    assert!((driven / 7.529278574652e10 - 1.0).abs() < LINEAR_TOLERANCE, "about the driven state: {driven:e}");
}

/// A small square lattice with both diagonals (k_d/k = 0.5) pulled on `supports`, as in the vk
/// campaign: (driven to a strain of 1e-4, loaded with 1 kN per top-row node).
fn square_pulled(supports: &str) -> (RunSpec, RunSpec) {
    let yaml = campaign("[]")
        .replace("lattice: {nx: 12, ny: 11}", "lattice: {nx: 6, ny: 5}")
        .replace("[square, triangular, honeycomb, kagome]", "[square]")
        .replace("[coursework, periodic-x]", &format!("[{supports}]"))
        .replace("[tensile, shear]", "[tensile]");
    let one = |load: &str| runs(&yaml.replace("load: []", &format!("load: {load}"))).pop().unwrap();
    (one(VELOCITY), one(FORCE))
}

#[test]
fn a_driven_periodic_strip_has_the_linear_modulus_of_the_same_strip_loaded() {
    // The premise: a translation by one spacing a maps the periodic strip on itself and every
    // top-row node on the next, and so the equal loads; the strip is rigid, so its linear answer
    // is unique and maps on itself too: the top row rises evenly, as the drive holds it (and the
    // mirror x → −x leaves u_x = 0). Both linear problems then have one answer and one E: the
    // continuum's (k + k_d)/d of a strip that cannot contract sideways, 3e11 Pa (a cell's
    // vertical bond and two diagonals, each k_d ε a/√2 along it, carry (k + k_d) ε a over a · d).
    // The dense linear solve here checks the premise on the network itself.
    let (driven, loaded) = square_pulled("periodic-x");
    let e = linear_youngs_modulus(&driven);
    let dense = driven_youngs_modulus(&driven, travel(&driven), About::Rest);
    let (k, k_d, depth) = (2e9, 1e9, 0.01);
    for (name, reference) in
        [("loaded", linear_youngs_modulus(&loaded)), ("dense", dense), ("continuum", (k + k_d) / depth)]
    {
        assert!((e / reference - 1.0).abs() < LINEAR_TOLERANCE, "E_linear {e:e} against the {name} {reference:e}");
    }
    // Where the claim fails: the answer about the driven state, the run's before 2026-12-07,
    // is off by the order of the strain and more (measured 1.7e-4 here, 1.8e-3 on the vk
    // campaign's 12 × 11, whose travel strains the driven bonds 2.5 times as much), 1e5 times
    // the tolerance.
    let about_driven = driven_youngs_modulus(&driven, travel(&driven), About::Driven);
    assert!((about_driven / dense - 1.0).abs() > 1e-5, "about the driven state {about_driven:e}");
}

#[test]
fn a_driven_free_block_has_the_linear_modulus_of_its_own_drive() {
    // On coursework supports the premise fails: the free block's top row does not rise evenly
    // under equal loads (its corners lag), so the drive, which holds it level, meets a stiffer
    // network (measured 8.1e-4 here, 2.0e-4 on the vk campaign's 12 × 11). The run's linear E is then the dense
    // first-order answer of the drive itself.
    let (driven, loaded) = square_pulled("coursework");
    let e = linear_youngs_modulus(&driven);
    let dense = driven_youngs_modulus(&driven, travel(&driven), About::Rest);
    assert!((e / dense - 1.0).abs() < LINEAR_TOLERANCE, "E_linear {e:e} against the dense {dense:e}");
    let e_loaded = linear_youngs_modulus(&loaded);
    assert!((e / e_loaded - 1.0).abs() > 1e-5, "E_linear {e:e} driven, {e_loaded:e} loaded");
}

#[test]
fn a_drive_and_a_load_superpose_on_one_factor_and_react_at_first_order() {
    // Two springs k along x, node 0 held, node 1 free along x under a load F, node 2 held and
    // moved by (δ, h). At first order about the rest geometry the sideways h meets no stiffness
    // (the springs carry no tension at rest), so u₁ = (F + k δ)/(2k), and the support holds
    // node 2 with k (δ − u₁) along x and nothing along y. The springs' forces at the displaced
    // state ([`Truss::reaction`]) add the second-order part: the bond, in tension k (δ − u₁) and
    // turned by h/(a + δ − u₁), pulls node 2 sideways by about k (δ − u₁) h/(a + δ − u₁)
    // (measured within 3.4e-5: the tension's change with h, ~h²/2a, is of higher order).
    let (k, force, (dx, dy)) = (3.0, -2.0, (0.5, 0.01));
    let mut bonds = Bonds::default();
    (0..2).for_each(|i| bonds.push(i, i + 1, 1.0, k));
    let (x, y) = ([0.0, 1.0, 2.0], [0.0; 3]);
    let loads = [Load { particle: 1, fx: force, fy: 0.0 }];
    let prescribed = [(2, dx, dy)];
    let truss = Truss {
        x: &x,
        y: &y,
        bonds: &bonds,
        held_x: &[0, 2],
        held_y: &[0, 1, 2],
        loads: &loads,
        prescribed: &prescribed,
    };
    let mut solver = truss.solver(&Analyses::default());
    let StaticSolution::Displacements { ux, uy } = solver.solve_linear() else { panic!("the chain carries") };
    // One factorisation serves the drive's part and the load's.
    assert_eq!(solver.convergence().factorisations, 1);
    let u1 = (force + k * dx) / (2.0 * k);
    assert!((ux[1] / u1 - 1.0).abs() < 1e-12, "u₁ = {} against {u1}", ux[1]);
    let (fx, fy) = truss.linear_reaction(&ux, &uy, &[2]);
    assert!((fx / (k * (dx - u1)) - 1.0).abs() < 1e-12 && fy == 0.0, "({fx}, {fy})");
    let (_, fy) = truss.reaction(&Linear, &ux, &uy, &[2]);
    let sideways = k * (dx - u1) * dy / (1.0 + dx - u1);
    assert!((fy / sideways - 1.0).abs() < 1e-2, "the springs' forces: {fy} against ~{sideways}");
}
