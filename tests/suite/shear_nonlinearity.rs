//! `static_nonlinearity` of a periodic strip in shear, under force and velocity control: the
//! relative distance of the static answer's non-linear G from its linear G, and nothing else,
//! against an independent answer. Every row of a `periodic-x` strip moves rigidly (the period
//! holds ε_xx = 0 and the strip is the same at every column), and every interlayer carries the
//! same force, so the strip is one interlayer of bonds from a node to the row above, solved here
//! exactly by Newton's method on its two unknowns: the row's shift s and lift t (m).

use crate::common::{execute_all, log_slope};
use mdsolids::runner::RunRecord;
use mdsolids::sim::RunStatus;
use mdsolids::spec::{Control, Diagonals};

/// The strips' spacing a (m).
const A: f64 = 0.1;
/// Their axial springs' stiffness k (N/m).
const K: f64 = 2.0e9;
/// Their diagonal springs' stiffness k_d (N/m), k_d/k = 1/2.
const K_DIAG: f64 = 1.0e9;

/// A steel-like periodic 6 × 5 strip (k_d/k = 1/2) in shear with diagonals `both` and `rising`:
/// loaded by 1e4 and 1e5 N per node (static answer only), and driven to strains 1e-4 and 1e-3.
fn strips() -> String {
    "version: 1\nname: t\ndefaults:\n  material: {mass: 0.785, k: 2.0e9}\n  geometry: {spacing: 0.1, depth: 0.01}\n  \
     lattice: {nx: 6, ny: 5, k_diag_ratio: 0.5}\n  supports: periodic-x\nscenes:\n  - name: force\n    \
     kind: lattice\n    load: {case: shear}\n    relax: {method: static}\n    grid:\n      \
     lattice.diagonals: [both, rising]\n      load.per_node: [1.0e4, 1.0e5]\n  - name: drive\n    \
     kind: lattice\n    damping: {restitution: 0.5, background: 12000.0}\n    time: {integrator: velocity-verlet}\n    \
     load: {case: shear, control: velocity}\n    relax: {max_tc: 3000}\n    grid:\n      \
     lattice.diagonals: [both, rising]\n      load.strain: [1.0e-4, 1.0e-3]\n"
        .to_string()
}

/// The bonds from a node to the row above, as rest vectors (m) with their stiffnesses (N/m):
/// the vertical spring k, and k_d along (a, a) (rising) and (−a, a) (falling). The horizontal
/// springs stay at rest length (a row moves rigidly).
fn interlayer(diagonals: Diagonals) -> Vec<([f64; 2], f64)> {
    let mut bonds = vec![([0.0, A], K)];
    if matches!(diagonals, Diagonals::Both | Diagonals::Rising) {
        bonds.push(([A, A], K_DIAG));
    }
    if matches!(diagonals, Diagonals::Both | Diagonals::Falling) {
        bonds.push(([-A, A], K_DIAG));
    }
    bonds
}

/// The force (N, x and y) the `bonds` carry onto the row above when it moves by `u` (m), with
/// its Jacobian (N/m): Σ T n and Σ k [n nᵀ + (1 − L₀/L)(I − n nᵀ)], tension T = k (L − L₀).
/// L − L₀ = (2 r₀·u + u·u)/(L + L₀), free of the cancellation of L − L₀ at strains of 1e-4,
/// which would leave 1e-12 of T where the non-linear part sought is 1e-9 of it.
fn bond_forces(bonds: &[([f64; 2], f64)], u: [f64; 2]) -> ([f64; 2], [[f64; 2]; 2]) {
    let (mut f, mut j) = ([0.0; 2], [[0.0; 2]; 2]);
    for &(r0, k) in bonds {
        let r = [r0[0] + u[0], r0[1] + u[1]];
        let (rest, length) = (r0[0].hypot(r0[1]), r[0].hypot(r[1]));
        let stretch = (2.0 * (r0[0] * u[0] + r0[1] * u[1]) + u[0] * u[0] + u[1] * u[1]) / (length + rest);
        let n = [r[0] / length, r[1] / length];
        for p in 0..2 {
            f[p] += k * stretch * n[p];
            for q in 0..2 {
                let identity = if p == q { 1.0 } else { 0.0 };
                j[p][q] += k * (n[p] * n[q] + stretch / length * (identity - n[p] * n[q]));
            }
        }
    }
    (f, j)
}

/// K₀ = Σ k n₀ n₀ᵀ (N/m): the linear problem's stiffness of the `bonds`.
fn linear_stiffness(bonds: &[([f64; 2], f64)]) -> [[f64; 2]; 2] {
    bond_forces(bonds, [0.0, 0.0]).1
}

/// x = m⁻¹ b for a 2 × 2 matrix m.
fn solve(m: [[f64; 2]; 2], b: [f64; 2]) -> [f64; 2] {
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    [(m[1][1] * b[0] - m[0][1] * b[1]) / det, (m[0][0] * b[1] - m[1][0] * b[0]) / det]
}

/// G/G_lin − 1 of the interlayer `bonds` under the force `force` (N, along x; nothing along y:
/// the top row is free to lift): G ∝ 1/s at equal force, so s_lin/s − 1. Newton's method from
/// the linear answer, to a correction below 1e-15 of the shift.
fn under_force(bonds: &[([f64; 2], f64)], force: f64) -> f64 {
    let linear = solve(linear_stiffness(bonds), [force, 0.0]);
    let mut u = linear;
    for _ in 0..50 {
        let (f, j) = bond_forces(bonds, u);
        let step = solve(j, [force - f[0], -f[1]]);
        u = [u[0] + step[0], u[1] + step[1]];
        if step[0].abs().max(step[1].abs()) < 1e-15 * u[0].abs() {
            return linear[0] / u[0] - 1.0;
        }
    }
    panic!("Newton's method did not converge on the interlayer")
}

/// G/G_lin − 1 of the interlayer `bonds` sheared by `shift` (m; the drive holds x only, the row
/// lifts freely): G ∝ the force F_x the shift takes at F_y = 0, so F_x/F_x,lin − 1.
fn under_drive(bonds: &[([f64; 2], f64)], shift: f64) -> f64 {
    let k0 = linear_stiffness(bonds);
    let linear = k0[0][0] * shift - k0[0][1] * k0[1][0] / k0[1][1] * shift;
    let mut lift = -k0[1][0] / k0[1][1] * shift;
    for _ in 0..50 {
        let (f, j) = bond_forces(bonds, [shift, lift]);
        let step = -f[1] / j[1][1];
        lift += step;
        if step.abs() < 1e-15 * shift.abs() {
            return bond_forces(bonds, [shift, lift]).0[0] / linear - 1.0;
        }
    }
    panic!("Newton's method did not converge on the interlayer")
}

/// The independent expectation of `static_nonlinearity` for run `r`: |G/G_lin − 1| of its
/// interlayer, under the load per node or the drive's shift per interlayer, strain · a.
fn expected(r: &RunRecord) -> f64 {
    let l = r.spec.lattice().expect("a lattice run");
    let bonds = interlayer(l.diagonals);
    let relative = match l.control {
        Control::Force => under_force(&bonds, l.load_per_node),
        Control::Velocity => under_drive(&bonds, l.drive_strain * A),
    };
    relative.abs()
}

/// The hand expansion of the interlayer with both diagonals, ρ = k/k_d, to O(γ³): at t = 0
/// F_x/(k_d a) = γ − 3γ³/8 + ργ³/2 and F_y/(k_d a) = (ρ/2 − 1/4)γ² + (1 + ρ) t/a, so the free
/// row lifts by t/a = −(ρ/2 − 1/4)γ²/(1 + ρ), which takes 2(ρ/2 − 1/4)²γ³/(1 + ρ) off F_x:
/// G/G_lin − 1 = c γ², c = −3/8 + ρ/2 − 2(ρ/2 − 1/4)²/(1 + ρ) = 1/4 at ρ = 2. Even in γ: the
/// mirror x → −x maps the strip onto itself sheared the other way, so no O(γ) term. The model
/// must meet it to O(γ²) relative: 1e-5 at γ = 1e-3 (the next term, ~γ², is 1e-6 of c).
#[test]
fn the_interlayer_model_meets_the_hand_expansion_of_a_mirror_symmetric_strip() {
    let rho = K / K_DIAG;
    let c = -3.0 / 8.0 + rho / 2.0 - 2.0 * (rho / 2.0 - 0.25).powi(2) / (1.0 + rho);
    assert_eq!(c, 0.25, "the coefficient at k_d/k = 1/2");
    let gamma = 1e-3;
    let bonds = interlayer(Diagonals::Both);
    let drive = under_drive(&bonds, gamma * A);
    assert!((drive / (c * gamma * gamma) - 1.0).abs() < 1e-5, "driven: {drive:e}");
    let force = under_force(&bonds, K_DIAG * A * gamma);
    assert!((force / (c * gamma * gamma) - 1.0).abs() < 1e-5, "loaded: {force:e}");
}

/// The column is the relative distance of the non-linear from the linear G, the one modulus a
/// shear measures (no E or ν enters: they are not measured), and equals the interlayer's to
/// 1e-5 relative: the smallest value is 2.5e-9 (γ = 1e-4, both diagonals), a difference of two
/// G's each solved to ‖R‖ ≤ 1e-12 ‖f‖, whose round-off (~1e-15 of G, measured 1e-7 of the
/// column at worst) the tolerance leaves a margin over. It scales as the load for the strip
/// with one diagonal family (O(γ)) and as the load squared for the mirror-symmetric one
/// (O(γ²), see the hand expansion): log-log slopes 1 and 2 to 1e-3 over a decade (the next
/// order's relative part is at most ~γ, 2.5e-3 at the larger load of the rising strip, whose
/// slope it moves by its change over the decade divided by ln 10).
#[test]
fn a_periodic_strip_in_shear_reads_the_relative_distance_of_its_static_shear_modulus() {
    let records = execute_all(&strips());
    assert_eq!(records.len(), 8);
    for r in &records {
        assert_eq!(r.status, RunStatus::Ok, "{:?}: {}", r.spec.varied, r.message);
        let m = &r.metrics.lattice;
        assert!(m.youngs_modulus_fem.is_none() && m.poisson_ratio_fem.is_none(), "{:?}", r.spec.varied);
        let column = m.static_nonlinearity.expect("linear springs have a linear answer beside");
        let (fem, linear) = (m.shear_modulus_fem.unwrap(), m.shear_modulus_linear.unwrap());
        assert_eq!(column, ((fem - linear) / linear).abs(), "G's alone: {:?}", r.spec.varied);
        let want = expected(r);
        assert!((column / want - 1.0).abs() < 1e-5, "{:?}: {column:e} against {want:e}", r.spec.varied);
    }
    let orders = [(Diagonals::Both, 2.0), (Diagonals::Rising, 1.0)];
    for (scene, (diagonals, order)) in ["force", "drive"].into_iter().flat_map(|s| orders.map(|o| (s, o))) {
        let points: Vec<(f64, f64)> = records
            .iter()
            .filter(|r| r.spec.scene == scene && r.spec.lattice().unwrap().diagonals == diagonals)
            .map(|r| (load_of(r), r.metrics.lattice.static_nonlinearity.unwrap()))
            .collect();
        let slope = log_slope(&points);
        assert!((slope - order).abs() < 1e-3, "{scene} {diagonals:?}: slope {slope} against {order}");
    }
}

/// The run's load: its load per node (N) or its drive's strain.
fn load_of(r: &RunRecord) -> f64 {
    let l = r.spec.lattice().unwrap();
    if l.control == Control::Force { l.load_per_node } else { l.drive_strain }
}
