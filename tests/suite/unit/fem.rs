//! Unit tests of `src/fem.rs`, moved out of the library (one test binary).

use mdsolids::fem::{Analyses, StaticSolution, Truss};
use mdsolids::model::{Bonds, Linear};
use mdsolids::sim::Load;

/// A chain of springs k between a held node and a pulled one: the pulled end moves F/k per
/// spring, u_end = n F / k (series springs).
#[test]
fn chain_in_series() {
    let mut bonds = Bonds::default();
    let k = 3.0;
    for i in 0..4 {
        bonds.push(i, i + 1, 1.0, k);
    }
    let x: Vec<f64> = (0..5).map(|i| i as f64).collect();
    let y = vec![0.0; 5];
    let held_y: Vec<usize> = (0..5).collect();
    let loads = [Load { particle: 4, fx: 2.0, fy: 0.0 }];
    let truss = Truss { x: &x, y: &y, bonds: &bonds, held_x: &[0], held_y: &held_y, loads: &loads, prescribed: &[] };
    match truss.solver(&Analyses::default()).solve_linear() {
        // Exact up to the 1e-12 regularisation and round-off.
        StaticSolution::Displacements { ux, .. } => assert!((ux[4] - 4.0 * 2.0 / k).abs() < 1e-9, "{ux:?}"),
        other => panic!("{other:?}"),
    }
}

/// The bounds of a relaxation on a fixed–free chain of n springs k along x (node 0 held): K is
/// tridiagonal with K⁻¹_ij = min(i, j)/k, so for the end's displacement Q = u_n the
/// sensitivity is ‖K⁻¹ e_n‖₂ = √(Σ i²)/k = √(n(n + 1)(2n + 1)/6)/k, and the lowest eigenvalue
/// is k_min = 2k(1 − cos(π/(2n + 1))). For any displacement error δu and its out-of-balance
/// force r = K δu the bound |δQ| ≤ ‖K⁻¹ e_n‖₂ ‖r‖₂ holds, and it is tighter than ‖r‖₂/k_min.
#[test]
fn error_bounds_of_a_fixed_free_chain() {
    let (n, k) = (12usize, 3.0);
    let mut bonds = Bonds::default();
    for i in 0..n {
        bonds.push(i, i + 1, 1.0, k);
    }
    let x: Vec<f64> = (0..=n).map(|i| i as f64).collect();
    let y = vec![0.0; n + 1];
    let held_y: Vec<usize> = (0..=n).collect();
    let truss = Truss { x: &x, y: &y, bonds: &bonds, held_x: &[0], held_y: &held_y, loads: &[], prescribed: &[] };
    let zero = vec![0.0; n + 1];
    let bounds = truss
        .solver(&Analyses::default())
        .error_bounds(&Linear, &zero, &zero, &[(2 * n, 1.0)])
        .expect("a chain held at one end factors");
    let sensitivity = bounds.sensitivity.expect("k_min > 0 and a free measured dof");
    let exact = ((n * (n + 1) * (2 * n + 1)) as f64 / 6.0).sqrt() / k;
    // 1e-9: the 1e-12 regularisation and round-off of the triangular solves.
    assert!((sensitivity / exact - 1.0).abs() < 1e-9, "{sensitivity} against {exact}");
    let k_min = 2.0 * k * (1.0 - (std::f64::consts::PI / (2.0 * n as f64 + 1.0)).cos());
    // k_min is a lower bound, within 1e-3 (the Rayleigh quotient settled to 1e-6, lowered by its
    // residual).
    assert!(bounds.stiffness_min <= k_min * (1.0 + 1e-12) && bounds.stiffness_min > k_min * (1.0 - 1e-3));
    assert!(sensitivity < 1.0 / bounds.stiffness_min, "tighter than ‖g‖₂/k_min with ‖g‖₂ = 1");
    // A few displacement errors, smooth and rough: r = K δu of the chain.
    for shape in [
        |i: f64| i.sin(),
        |i: f64| (0.3 * i).cos() - 1.0,
        |i: f64| if (i as usize).is_multiple_of(2) { 1.0 } else { -1.0 },
    ] {
        let du: Vec<f64> = (0..=n).map(|i| if i == 0 { 0.0 } else { shape(i as f64) }).collect();
        let r: Vec<f64> =
            (1..=n).map(|i| k * (2.0 * du[i] - du[i - 1] - if i < n { du[i + 1] } else { du[i] })).collect();
        let norm = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!(du[n].abs() <= sensitivity * norm * (1.0 + 1e-12), "{} above {}", du[n], sensitivity * norm);
    }
    // A quantity of held dofs alone has no error to bound.
    assert_eq!(
        truss.solver(&Analyses::default()).error_bounds(&Linear, &zero, &zero, &[(1, 1.0)]).unwrap().sensitivity,
        None
    );
}

/// One square with both diagonals, bottom edge pinned, top nodes pulled up by F each. By
/// symmetry the top nodes rise by u and move inwards by a (left node +a, right node −a).
/// The diagonal from the opposite bottom corner stretches by (u − a)/√2 and pulls with
/// k_d (u − a)/2 along each axis; the top spring shortens by 2a. Equilibrium of the top-left
/// node: x: k_d (u − a)/2 = 2 k a, so a = k_d u/(4k + k_d); y: F = k u + k_d (u − a)/2, so
/// F = u (k + 2 k k_d/(4k + k_d)).
#[test]
fn single_square_with_diagonals() {
    let (k, kd, force) = (2.0, 0.8, 0.5);
    let mut bonds = Bonds::default();
    bonds.push(0, 1, 1.0, k); // bottom
    bonds.push(2, 3, 1.0, k); // top
    bonds.push(0, 2, 1.0, k); // left
    bonds.push(1, 3, 1.0, k); // right
    bonds.push(0, 3, 2f64.sqrt(), kd);
    bonds.push(1, 2, 2f64.sqrt(), kd);
    let (x, y) = ([0.0, 1.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]);
    let loads = [Load { particle: 2, fx: 0.0, fy: force }, Load { particle: 3, fx: 0.0, fy: force }];
    let truss = Truss { x: &x, y: &y, bonds: &bonds, held_x: &[0, 1], held_y: &[0, 1], loads: &loads, prescribed: &[] };
    match truss.solver(&Analyses::default()).solve_linear() {
        StaticSolution::Displacements { ux, uy } => {
            let u = force / (k + 2.0 * k * kd / (4.0 * k + kd));
            let a = kd * u / (4.0 * k + kd);
            // 1e-11: the 1e-12 regularisation shifts the answer by ~1e-12 relative.
            assert!((uy[2] - u).abs() < 1e-11 && (uy[3] - u).abs() < 1e-11, "{uy:?} against {u}");
            assert!((ux[2] - a).abs() < 1e-11 && (ux[3] + a).abs() < 1e-11, "{ux:?} against ±{a}");
        }
        other => panic!("{other:?}"),
    }
}

/// A pre-stretched string of two springs (rest 0.9, length 1 each) between held ends,
/// pushed sideways at the middle by F: it stiffens as it deflects. Exact: 2 s(r) v/r = F
/// with r = √(1 + v²), s = k (r − 0.9). The linear answer (transverse stiffness 2 s₀/1 =
/// 0.2) overshoots by ~20 %; Newton–Raphson must find the exact v.
#[test]
fn newton_raphson_follows_geometric_stiffening() {
    let (k, force) = (1.0, 0.05);
    let mut bonds = Bonds::default();
    bonds.push(0, 1, 0.9, k);
    bonds.push(1, 2, 0.9, k);
    let (x, y) = ([0.0, 1.0, 2.0], [0.0, 0.0, 0.0]);
    let loads = [Load { particle: 1, fx: 0.0, fy: force }];
    let truss =
        Truss { x: &x, y: &y, bonds: &bonds, held_x: &[0, 1, 2], held_y: &[0, 2], loads: &loads, prescribed: &[] };
    let out_of_balance = |v: f64| {
        let r = (1.0 + v * v).sqrt();
        2.0 * k * (r - 0.9) * v / r - force
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if out_of_balance(mid) > 0.0 { hi = mid } else { lo = mid }
    }
    let exact = 0.5 * (lo + hi);
    let linear = match truss.solver(&Analyses::default()).solve_linear() {
        StaticSolution::Displacements { uy, .. } => uy[1],
        other => panic!("{other:?}"),
    };
    assert!((linear - force / 0.2).abs() < 1e-9 && (linear - exact).abs() > 0.01, "linear {linear}, exact {exact}");
    match truss.solver(&Analyses::default()).solve_nonlinear(&Linear, 0.0, None) {
        // Converged to ‖R‖ ≤ 1e-10 ‖f‖; the tangent ≈ 0.4 turns that into ~1e-11 in v.
        Some(StaticSolution::Displacements { uy, .. }) => {
            assert!((uy[1] - exact).abs() < 1e-9, "{} against {exact}", uy[1])
        }
        other => panic!("{other:?}"),
    }
}

/// Four Hertz springs (s = C δ^{3/2}) in series pulled by F: each stretches by
/// δ = (F/C)^{2/3}, and the tangent compliance is 4/s′(δ) with s′ = 1.5 C δ^{1/2}.
#[test]
fn hertz_chain_in_series_and_its_tangent() {
    let (c, force) = (3.0, 0.02);
    let hertz = mdsolids::model::PowerLaw { beta: 1.5 };
    let mut bonds = Bonds::default();
    for i in 0..4 {
        bonds.push(i, i + 1, 1.0, c);
    }
    let x: Vec<f64> = (0..5).map(|i| i as f64).collect();
    let (y, held_y) = (vec![0.0; 5], (0..5).collect::<Vec<usize>>());
    let loads = [Load { particle: 4, fx: force, fy: 0.0 }];
    let truss = Truss { x: &x, y: &y, bonds: &bonds, held_x: &[0], held_y: &held_y, loads: &loads, prescribed: &[] };
    let delta = (force / c).powf(1.0 / 1.5);
    // Start deliberately off (at 3 δ): Newton must still converge.
    let Some(StaticSolution::Displacements { ux, uy }) =
        truss.solver(&Analyses::default()).solve_nonlinear(&hertz, 3.0 * delta, None)
    else {
        panic!("no static answer")
    };
    // Newton stops at ‖R‖ ≤ 1e-10 ‖f‖: relative 1e-9 on δ is ample.
    assert!((ux[4] - 4.0 * delta).abs() < 1e-9 * delta, "{} against {}", ux[4], 4.0 * delta);
    let (dx, _) =
        truss.solver(&Analyses::default()).tangent_response(&hertz, &ux, &uy).expect("a stretched chain has stiffness");
    let compliance = 4.0 / (1.5 * c * delta.sqrt());
    assert!((dx[4] / force - compliance).abs() < 1e-9 * compliance, "{} against {compliance}", dx[4] / force);
}

/// The same square without diagonals, pushed sideways at the top: it folds (a mechanism).
#[test]
fn square_without_diagonals_shears_freely() {
    let mut bonds = Bonds::default();
    for (i, j) in [(0, 1), (2, 3), (0, 2), (1, 3)] {
        bonds.push(i, j, 1.0, 1.0);
    }
    let (x, y) = ([0.0, 1.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]);
    let loads = [Load { particle: 2, fx: 1.0, fy: 0.0 }];
    let truss = Truss { x: &x, y: &y, bonds: &bonds, held_x: &[0, 1], held_y: &[0, 1], loads: &loads, prescribed: &[] };
    assert!(matches!(truss.solver(&Analyses::default()).solve_linear(), StaticSolution::Mechanism { .. }));
}

/// An n × n square lattice with both diagonals (k = 1, k_d = 0.5, spacing 1), bottom row
/// clamped, `force` up on each top node: positions, bonds, held nodes and loads.
fn pulled_lattice(n: usize, force: f64) -> (Vec<f64>, Vec<f64>, Bonds, Vec<usize>, Vec<Load>) {
    let node = |i: usize, j: usize| j * n + i;
    let x: Vec<f64> = (0..n * n).map(|k| (k % n) as f64).collect();
    let y: Vec<f64> = (0..n * n).map(|k| (k / n) as f64).collect();
    let mut bonds = Bonds::default();
    for j in 0..n {
        for i in 0..n {
            let (right, up) = (i + 1 < n, j + 1 < n);
            if right {
                bonds.push(node(i, j), node(i + 1, j), 1.0, 1.0);
            }
            if up {
                bonds.push(node(i, j), node(i, j + 1), 1.0, 1.0);
            }
            if right && up {
                bonds.push(node(i, j), node(i + 1, j + 1), 2f64.sqrt(), 0.5);
                bonds.push(node(i + 1, j), node(i, j + 1), 2f64.sqrt(), 0.5);
            }
        }
    }
    let loads = (0..n).map(|i| Load { particle: node(i, n - 1), fx: 0.0, fy: force }).collect();
    (x, y, bonds, (0..n).collect(), loads)
}

/// Newton–Raphson on a lattice stretched by ~4 % converges on the network's one symbolic
/// analysis and its one numeric factorisation, the linear answer's: every correction is solved
/// by conjugate gradients preconditioned with it (the tangent differs from K by terms of the
/// strain's order, so each solve gains ~log₁₀(1/0.04) ≈ 1.4 digits: at most 16 solves for the
/// linear answer's refinement and three or four corrections, where a fresh factor each took
/// four factorisations), and the out-of-balance force it ends at is recorded, at most 1e-12 of
/// the load. The answer satisfies the non-linear equations to that residual (checked by
/// `Truss::reaction`: the supports carry the whole load).
#[test]
fn newton_converges_quadratically_and_records_its_residual() {
    let (n, force) = (12, 0.05);
    let (x, y, bonds, held, loads) = pulled_lattice(n, force);
    let truss = Truss { x: &x, y: &y, bonds: &bonds, held_x: &held, held_y: &held, loads: &loads, prescribed: &[] };
    let mut solver = truss.solver(&Analyses::default());
    let StaticSolution::Displacements { ux, uy } = solver.solve_linear() else { panic!("a clamped block carries") };
    let Some(StaticSolution::Displacements { ux, uy }) = solver.solve_nonlinear_from(&Linear, ux, uy, None) else {
        panic!("Newton converges")
    };
    let convergence = solver.convergence();
    assert_eq!(convergence.factorisations, 1, "{convergence:?}");
    assert!(convergence.residual <= 1e-12, "{convergence:?}");
    assert!(convergence.solves <= 16, "{convergence:?}");
    let (_, carried) = truss.reaction(&Linear, &ux, &uy, &held);
    // The supports hold −(total load); 1e-10: the 1e-12 residual summed over 2n² dofs.
    assert!((carried + force * n as f64).abs() <= 1e-10, "{carried}");
}

/// An answer a deadline cut short is not kept (`fem::Answers`): the run that asks next solves
/// again, while a finished answer is handed out without solving.
#[test]
fn an_answer_cut_short_by_a_deadline_is_solved_again() {
    use mdsolids::fem::{Answers, StaticAnswer};
    let answers = Answers::default();
    let answer = |nonlinear| StaticAnswer {
        linear: StaticSolution::Displacements { ux: vec![0.0], uy: vec![1.0] },
        nonlinear: Some(nonlinear),
        residual: 1e-13,
        descents: 0,
    };
    let mut solved = 0;
    let key = [7; 32];
    let cut = answers.get(key, || {
        solved += 1;
        answer(StaticSolution::PastDeadline)
    });
    assert_eq!(
        (cut.nonlinear, solved, answers.len()),
        (Some(StaticSolution::PastDeadline), 1, 0),
        "solved once by the run it cut, not kept"
    );
    let done = StaticSolution::Displacements { ux: vec![0.5], uy: vec![1.5] };
    let first = answers.get(key, || answer(done.clone()));
    let second = answers.get(key, || unreachable!("kept"));
    assert_eq!((first.clone(), answers.len()), (second, 1));
    assert_eq!(first.nonlinear, Some(done));
}
