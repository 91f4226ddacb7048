//! Unit tests of `src/theory/collision.rs` and `src/theory/lattice.rs`: the damped collisions
//! and the square lattice's branches, each against a closed form or an independent computation.

use mdsolids::theory::special::beta;
use mdsolids::theory::{
    branch_frequency, linear_pair_overlap, linear_restitution, power_law_gamma_for_restitution, power_law_max_overlap,
    power_law_restitution, square_branch_stiffnesses,
};

#[test]
fn a_linear_contact_integrated_gives_the_closed_form_restitution() {
    // β = 1 is the linear pair: r = exp(−γ t_c/m) exactly; RK4 at 20 000 steps per contact
    // (error ∝ h⁴ ≈ 1e-16) and the crossing found by Newton's method leave round-off: 1e-11.
    for gamma in [0.0, 0.1, 0.5, 1.0] {
        let r = power_law_restitution(2.0, 1.0, 1.5, gamma, 0.3).unwrap();
        assert!((r - linear_restitution(2.0, 1.5, gamma).unwrap()).abs() < 1e-11, "γ = {gamma}: {r}");
    }
}

#[test]
fn a_weakly_damped_hertz_contact_loses_the_first_order_energy() {
    // To first order in γ the dashpot takes γ ∫ δ̇² dt = 2γ v δ_max J of the energy μv²/2,
    // J = ∫₀¹ √(1 − x^(β+1)) dx = B(1/(β+1), 3/2)/(β+1): 1 − r = 4γ δ_max J/(m v). At γ = 1e-4
    // the second-order term is ~1e-4 of the first: tolerance 1e-3 relative.
    let (c, b, m, v, gamma) = (1.0, 1.5, 1.0, 0.2, 1e-4);
    let j = beta(1.0 / (b + 1.0), 1.5) / (b + 1.0);
    let first_order = 4.0 * gamma * power_law_max_overlap(c, b, m, v) * j / (m * v);
    let loss = 1.0 - power_law_restitution(c, b, m, gamma, v).unwrap();
    assert!((loss / first_order - 1.0).abs() < 1e-3, "{loss} against {first_order}");
}

#[test]
fn the_dashpot_for_a_target_gives_that_target() {
    // Bisection to 60 halvings: the restitution it gives is the target to 1e-9.
    for target in [0.3, 0.5, 0.9] {
        let gamma = power_law_gamma_for_restitution(target, 1.0, 1.5, 1.0, 1.0).unwrap();
        assert!((power_law_restitution(1.0, 1.5, 1.0, gamma, 1.0).unwrap() - target).abs() < 1e-9);
    }
}

#[test]
fn the_overlap_solves_the_damped_pair_equation() {
    // (m/2) δ̈ + γ δ̇ + k δ = 0 with δ(0) = 0, δ̇(0) = v, checked by central differences
    // (h = 1e-4 s: truncation h² ≈ 1e-8 of the terms, round-off 1e-16/h² ≈ 1e-8).
    let (k, m, gamma, v, h) = (3.0, 2.0, 0.7, 0.4, 1e-4);
    let d = |t: f64| linear_pair_overlap(k, m, gamma, v, t).unwrap();
    assert_eq!(d(0.0), 0.0);
    assert!(((d(h) - d(-h)) / (2.0 * h) - v).abs() < 1e-7);
    for t in [0.3, 1.1, 2.9] {
        let acceleration = (d(t + h) - 2.0 * d(t) + d(t - h)) / (h * h);
        let velocity = (d(t + h) - d(t - h)) / (2.0 * h);
        assert!((0.5 * m * acceleration + gamma * velocity + k * d(t)).abs() < 1e-6, "t = {t}");
    }
}

#[test]
fn the_branches_are_the_eigenvalues_of_the_dynamical_matrix() {
    // The dynamical matrix of a square lattice summed over its eight neighbours for a wave
    // q = (0, q) along y, D = Σ_b k_b n̂n̂ (1 − cos q·r_b), independently of the closed form;
    // its eigenvalues are m ω², which 2√(k_eff/m)|sin(qa/2)| must give to 1e-12.
    let (k_x, k_y, k_r, k_f, m, a, q) = (1.3, 0.8, 0.45, 0.2, 1.7, 0.5, 2.1);
    let neighbours = [((1.0, 0.0), k_x), ((0.0, 1.0), k_y), ((1.0, 1.0), k_r), ((1.0, -1.0), k_f)];
    let mut d = [[0.0; 2]; 2];
    for ((x, y), k) in neighbours {
        let length = f64::hypot(x, y);
        let n = [x / length, y / length];
        // Both neighbours ±r of the family: 2 k n̂n̂ (1 − cos(q·r)).
        let weight = 2.0 * k * (1.0 - (q * y * a).cos());
        for i in 0..2 {
            for j in 0..2 {
                d[i][j] += weight * n[i] * n[j];
            }
        }
    }
    let (trace, det) = (d[0][0] + d[1][1], d[0][0] * d[1][1] - d[0][1] * d[1][0]);
    let root = (0.25 * trace * trace - det).sqrt();
    let expected = [0.5 * trace - root, 0.5 * trace + root].map(|mw2| (mw2 / m).sqrt());
    let measured = square_branch_stiffnesses(k_y, k_r, k_f).map(|k_eff| branch_frequency(k_eff, m, q, a));
    for (e, w) in expected.iter().zip(measured) {
        assert!((e - w).abs() < 1e-12, "{expected:?} against {measured:?}");
    }
    // No diagonals: a transverse wave has no stiffness.
    assert_eq!(square_branch_stiffnesses(1.0, 0.0, 0.0), [0.0, 1.0]);
}
