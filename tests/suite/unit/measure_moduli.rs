//! Unit tests of `src/measure/moduli.rs`, moved out of the library (one test binary).

use mdsolids::measure::{
    LatticeShape, anisotropic_moduli, homogeneity, network_constants, plane_wave_speeds, youngs_modulus_along,
};
use mdsolids::model::LatticeType;
use mdsolids::model::{Edges, Layout};

/// A 3 × 3 block's x displacements, row by row, with left and right columns `left`, `right`.
fn block(left: [f64; 3], right: [f64; 3]) -> (Edges, Vec<f64>) {
    let ux = (0..3).flat_map(|row| [left[row], 0.5 * (left[row] + right[row]), right[row]]).collect();
    (Layout::square(3, 3, 1.0, false).edges, ux)
}

/// Straight edges give 0, a bowed edge its deviation over the mean sideways displacement,
/// and edges that do not move sideways (ν = 0, round-off only) no number at all.
#[test]
fn homogeneity_is_defined_only_where_the_edges_move() {
    let shape = |edges| LatticeShape { edges, depth: 1.0 };
    let (edges, ux) = block([0.0, 0.0, 0.0], [-1e-3, -1e-3, -1e-3]);
    assert_eq!(homogeneity(&shape(&edges), &ux, 1e-2), Some(0.0));
    let (edges, ux) = block([0.0, 0.0, 0.0], [-1e-3, -2e-3, -1e-3]);
    // Line through (0, −1e-3), (1, −2e-3), (2, −1e-3): −4/3e-3, deviation 2/3e-3; mean |u| 2/3e-3.
    let h = homogeneity(&shape(&edges), &ux, 1e-2).unwrap();
    assert!((h - 1.0).abs() < 1e-12, "{h}");
    let (edges, ux) = block([1e-19, -2e-19, 0.0], [3e-19, 0.0, -1e-19]);
    assert_eq!(homogeneity(&shape(&edges), &ux, 1e-6), None);
}

/// A periodic cell of a lattice of unit springs (k = 1, m = 1, a = 1): its lattice vectors,
/// node positions and bonds (i, j, n₁, n₂): node i to node j of the cell n₁a₁ + n₂a₂ away.
struct Cell {
    vectors: [[f64; 2]; 2],
    nodes: Vec<[f64; 2]>,
    bonds: Vec<(usize, usize, i32, i32)>,
}

impl Cell {
    /// The cells as drawn by hand here, independently of `model::planar`.
    fn of(kind: LatticeType) -> Cell {
        let h = 3.0_f64.sqrt() / 2.0;
        match kind {
            LatticeType::Triangular => Cell {
                vectors: [[1.0, 0.0], [0.5, h]],
                nodes: vec![[0.0, 0.0]],
                bonds: vec![(0, 0, 1, 0), (0, 0, 0, 1), (0, 0, -1, 1)],
            },
            LatticeType::Kagome => Cell {
                vectors: [[2.0, 0.0], [1.0, 2.0 * h]],
                nodes: vec![[0.0, 0.0], [1.0, 0.0], [0.5, h]],
                bonds: vec![(0, 1, 0, 0), (1, 0, 1, 0), (0, 2, 0, 0), (1, 2, 0, 0), (2, 1, -1, 1), (2, 0, 0, 1)],
            },
            LatticeType::Honeycomb => Cell {
                vectors: [[2.0 * h, 0.0], [h, 1.5]],
                nodes: vec![[0.0, 0.0], [0.0, 1.0]],
                bonds: vec![(0, 1, 0, 0), (1, 0, 0, 1), (1, 0, -1, 1)],
            },
            LatticeType::Square => unreachable!("the square lattice is not a planar type"),
        }
    }

    /// The squared frequencies ω² (ascending) of the Bloch waves of wavevector `q`: the
    /// eigenvalues of the dynamical matrix D(q) = Σ_bonds k n nᵀ (the blocks ii, jj; −e^{iq·R}
    /// in ij, its conjugate in ji), found as those of the real symmetric [[Re D, −Im D],
    /// [Im D, Re D]], where each appears twice.
    fn frequencies_squared(&self, q: [f64; 2]) -> Vec<f64> {
        let n = 2 * self.nodes.len();
        let (mut re, mut im) = (vec![vec![0.0; n]; n], vec![vec![0.0; n]; n]);
        for &(i, j, n1, n2) in &self.bonds {
            let [a1, a2] = self.vectors;
            let r = [n1 as f64 * a1[0] + n2 as f64 * a2[0], n1 as f64 * a1[1] + n2 as f64 * a2[1]];
            let d = [self.nodes[j][0] + r[0] - self.nodes[i][0], self.nodes[j][1] + r[1] - self.nodes[i][1]];
            let length = d[0].hypot(d[1]);
            assert!((length - 1.0).abs() < 1e-12, "bond {i}-{j} is {length} long");
            let e = [d[0] / length, d[1] / length];
            let phase = q[0] * r[0] + q[1] * r[1];
            for (s, t) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                let k = e[s] * e[t];
                re[2 * i + s][2 * i + t] += k;
                re[2 * j + s][2 * j + t] += k;
                re[2 * i + s][2 * j + t] -= k * phase.cos();
                im[2 * i + s][2 * j + t] -= k * phase.sin();
                re[2 * j + s][2 * i + t] -= k * phase.cos();
                im[2 * j + s][2 * i + t] += k * phase.sin();
            }
        }
        let mut real = vec![vec![0.0; 2 * n]; 2 * n];
        for r in 0..n {
            for c in 0..n {
                real[r][c] = re[r][c];
                real[n + r][n + c] = re[r][c];
                real[r][n + c] = -im[r][c];
                real[n + r][c] = im[r][c];
            }
        }
        let mut w2 = jacobi_eigenvalues(real);
        w2.sort_by(f64::total_cmp);
        w2.into_iter().step_by(2).collect()
    }
}

/// Eigenvalues of a real symmetric matrix by cyclic Jacobi rotations, to round-off.
fn jacobi_eigenvalues(mut a: Vec<Vec<f64>>) -> Vec<f64> {
    let n = a.len();
    for _sweep in 0..100 {
        let off: f64 = (0..n)
            .flat_map(|r| (0..n).filter(move |&c| c != r).map(move |c| (r, c)))
            .map(|(r, c)| a[r][c].powi(2))
            .sum();
        if off < 1e-30 {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                if a[p][q].abs() < 1e-300 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let (c, s) = (1.0 / (t * t + 1.0).sqrt(), t / (t * t + 1.0).sqrt());
                // A ← Jᵀ A J: columns p and q, then rows p and q.
                for row in a.iter_mut() {
                    let (arp, arq) = (row[p], row[q]);
                    row[p] = c * arp - s * arq;
                    row[q] = s * arp + c * arq;
                }
                let (upper, lower) = a.split_at_mut(q);
                for (apr, aqr) in upper[p].iter_mut().zip(lower[0].iter_mut()) {
                    let (x, y) = (*apr, *aqr);
                    *apr = c * x - s * y;
                    *aqr = s * x + c * y;
                }
            }
        }
    }
    (0..n).map(|i| a[i][i]).collect()
}

/// The plane-wave speeds along y of every planar type against the slopes of its acoustic
/// Bloch branches, ω/q at q = 1e-4/a along y from a cell drawn here by hand: the triangular
/// lattice's c_L and c_T, the kagome's c_L and √2 c_T beside a branch flat at 0 (its line of
/// zero modes), the honeycomb's c_L beside a flat transverse branch. Tolerance 1e-6: the
/// slope at qa = 1e-4 differs from its limit by O(q²a²) = 1e-8, and ω² near 0 is found to
/// about 1e-15 (√ of it, over q: 3e-4 a√(k/m) on a zero branch, whence the 1e-3 there).
#[test]
fn plane_wave_speeds_are_the_slopes_of_the_bloch_branches() {
    let (k, a, m): (f64, f64, f64) = (2.0e9, 0.1, 0.785);
    let unit = a * (k / m).sqrt();
    let q = 1e-4;
    for (kind, zero_branches) in [(LatticeType::Triangular, 0), (LatticeType::Kagome, 1), (LatticeType::Honeycomb, 1)] {
        let slopes: Vec<f64> =
            Cell::of(kind).frequencies_squared([0.0, q]).iter().map(|w2| w2.max(0.0).sqrt() / q).collect();
        let (c_l, c_t) = plane_wave_speeds(kind, k, a, m).unwrap();
        let expected: Vec<f64> = c_t.into_iter().chain([c_l]).map(|c| c / unit).collect();
        for zero in &slopes[..zero_branches] {
            assert!(*zero < 1e-3, "{kind:?}: a zero branch has slope {zero}");
        }
        for (slope, want) in slopes[zero_branches..].iter().zip(&expected) {
            assert!((slope - want).abs() < 1e-6, "{kind:?}: slopes {slopes:?}, expected {expected:?}");
        }
        // Any further branch is optical (finite ω at q → 0): no acoustic branch is left out.
        assert!(slopes[zero_branches + expected.len()..].iter().all(|&s| s > 1e2), "{kind:?}: slopes {slopes:?}");
    }
    // The triangular lattice's are its continuum's; the kagome's transverse is not.
    let (c_l, c_t) = network_constants(LatticeType::Kagome, k, a).unwrap().sound_speeds(m);
    let (kagome_l, kagome_t) = plane_wave_speeds(LatticeType::Kagome, k, a, m).unwrap();
    assert_eq!(kagome_l, c_l);
    assert!((kagome_t.unwrap() / c_t - 2.0_f64.sqrt()).abs() < 1e-15);
}

/// Young's modulus along any direction of a square lattice's continuum, against closed forms
/// solved by hand from C (per unit depth, k = d = 1) for a uniaxial stress σ along n:
/// - one rising family k_r (C11 = C22 = k + h, C12 = C66 = C16 = C26 = h = k_r/2): along the
///   family (45°) e_xx = e_yy = 0 and γ = σ/(2h), so E = 2k_r, the springs alone; along the
///   missing diagonal (135°) e_xx = e_yy = σ/k and γ = −σ/(2h) − 2σ/k, so
///   E = 1/(2/k + 1/(2k_r));
/// - both families k_d = k/2: isotropic, E = C11 − C12²/C11 = 4/3 in every direction;
/// - along x and y, what `anisotropic_moduli` gives (k_y = 2k, one family).
///
/// Round-off only: tolerance 1e-12. Without diagonals there is no answer off the axes.
#[test]
fn youngs_modulus_along_any_direction_meets_the_hand_solved_cases() {
    let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-12;
    let along = |k_y: f64, rising: f64, falling: f64, degrees: f64| {
        youngs_modulus_along(1.0, k_y, rising, falling, 1.0, f64::to_radians(degrees)).unwrap()
    };
    let k_r = 0.5;
    assert!(close(along(1.0, k_r, 0.0, 45.0), 2.0 * k_r));
    assert!(close(along(1.0, k_r, 0.0, 135.0), 1.0 / (2.0 + 1.0 / (2.0 * k_r))));
    for degrees in [0.0, 17.0, 45.0, 90.0, 133.0] {
        assert!(close(along(1.0, 0.5, 0.5, degrees), 4.0 / 3.0), "{degrees}°");
    }
    let turned = anisotropic_moduli(1.0, 2.0, k_r, 0.0, 1.0);
    assert!(close(along(2.0, k_r, 0.0, 0.0), turned.youngs_modulus_x));
    assert!(close(along(2.0, k_r, 0.0, 90.0), turned.youngs_modulus_y));
    assert!(youngs_modulus_along(1.0, 1.0, 0.0, 0.0, 1.0, 0.3).is_none());
}
