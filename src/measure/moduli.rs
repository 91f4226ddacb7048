//! Elastic moduli of a loaded lattice from its node displacements (MD after relaxation, or the
//! static solution): the same function serves both, so they are compared like for like.
//!
//! Widths L_x = (N_x − 1) a, L_y = (N_y − 1) a, depth d; F is the total force on the top row.
//! ΔL are differences of mean displacements of rows or columns.

/// Size of a lattice: nodes per row and rows, spacing a (m), depth d (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LatticeShape {
    /// Nodes per row.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// Spacing a (m).
    pub spacing: f64,
    /// Depth d (m).
    pub depth: f64,
    /// Bonds wrap across the sides: the width carrying the load is the period nx · a.
    pub periodic_x: bool,
}

impl LatticeShape {
    /// L_x: (N_x − 1) a, or the period N_x a of a periodic lattice.
    fn width(&self) -> f64 {
        let columns = if self.periodic_x { self.nx } else { self.nx - 1 };
        columns as f64 * self.spacing
    }
    fn height(&self) -> f64 {
        (self.ny - 1) as f64 * self.spacing
    }
    /// Mean of `u` over row `iy`.
    fn row_mean(&self, u: &[f64], iy: usize) -> f64 {
        u[iy * self.nx..(iy + 1) * self.nx].iter().sum::<f64>() / self.nx as f64
    }
    /// Values of `u` down column `ix`.
    fn column(&self, u: &[f64], ix: usize) -> Vec<f64> {
        (0..self.ny).map(|iy| u[iy * self.nx + ix]).collect()
    }
}

/// ΔL (m) of a lattice's measured modulus: the mean of `u` (u_y in tension, u_x in shear)
/// over the top row minus its mean over the bottom row.
pub fn row_extension(shape: &LatticeShape, u: &[f64]) -> f64 {
    shape.row_mean(u, shape.ny - 1) - shape.row_mean(u, 0)
}

/// The bound on the relative error of a modulus M ∝ 1/ΔL (E in tension, G in shear) measured
/// at the extension `extension` = ΔL (m) from displacements within `error` (m, 2-norm over every
/// node) of the state of rest: ΔL weighs two rows by ±1/N_x, so |δΔL| ≤ √(2/N_x) ‖δu‖₂
/// (Cauchy–Schwarz), and with b = |δΔL|/|ΔL|, |δM/M| ≤ b/(1 − b) (∞ for b ≥ 1).
pub fn modulus_error_bound(shape: &LatticeShape, extension: f64, error: f64) -> f64 {
    let b = (2.0 / shape.nx as f64).sqrt() * error / extension.abs();
    if b < 1.0 { b / (1.0 - b) } else { f64::INFINITY }
}

/// The largest displacement error (m, 2-norm) for which [`modulus_error_bound`] at `extension`
/// is at most `tolerance`: b = tolerance/(1 + tolerance).
pub fn displacement_error_allowed(shape: &LatticeShape, extension: f64, tolerance: f64) -> f64 {
    tolerance / (1.0 + tolerance) * extension.abs() / (2.0 / shape.nx as f64).sqrt()
}

/// Young's modulus and Poisson ratios of a tensile test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TensileModuli {
    /// E = (F/d/L_x) / (ΔL_y/L_y) (Pa).
    pub youngs_modulus: f64,
    /// ν = −(ΔL_x/L_x) / (ΔL_y/L_y).
    pub poisson_ratio: f64,
    /// The coursework's ν = ΔL_x/ΔL_y (a ratio of lengths, not of strains).
    pub poisson_ratio_coursework: f64,
}

/// E and ν from a tensile test with total top-row force `force` (N) and node displacements
/// `(ux, uy)` (m): ΔL_y = mean u_y(top row) − mean u_y(bottom row),
/// ΔL_x = mean u_x(right column) − mean u_x(left column).
pub fn tensile_moduli(shape: &LatticeShape, force: f64, ux: &[f64], uy: &[f64]) -> TensileModuli {
    let stretch = shape.row_mean(uy, shape.ny - 1) - shape.row_mean(uy, 0);
    let mean = |column: Vec<f64>| column.iter().sum::<f64>() / column.len() as f64;
    let widening = mean(shape.column(ux, shape.nx - 1)) - mean(shape.column(ux, 0));
    let strain_y = stretch / shape.height();
    TensileModuli {
        youngs_modulus: force / shape.depth / shape.width() / strain_y,
        poisson_ratio: -(widening / shape.width()) / strain_y,
        poisson_ratio_coursework: widening / stretch,
    }
}

/// G = (F/d/L_x) / (ΔL_x,top / L_y) from a shear test, with ΔL_x,top the mean x displacement
/// of the top row relative to the bottom row (Pa).
pub fn shear_modulus(shape: &LatticeShape, force: f64, ux: &[f64]) -> f64 {
    let shift = shape.row_mean(ux, shape.ny - 1) - shape.row_mean(ux, 0);
    force / shape.depth / shape.width() / (shift / shape.height())
}

/// How far the left and right columns are from straight lines: the largest deviation of a
/// column node's x displacement from the least-squares line through its column, relative to
/// the mean |x displacement| of the two columns. 0 for a homogeneous deformation. Not defined
/// (`None`) where the edges do not move sideways: a mean |x displacement| below 1e-9 of the
/// largest displacement `largest` (m) is round-off (a lattice without diagonals, ν = 0), and
/// a ratio of round-offs says nothing.
pub fn homogeneity(shape: &LatticeShape, ux: &[f64], largest: f64) -> Option<f64> {
    let columns = [shape.column(ux, 0), shape.column(ux, shape.nx - 1)];
    let mean_lateral = columns.iter().flatten().map(|u| u.abs()).sum::<f64>() / (2 * shape.ny) as f64;
    let deviation = columns.iter().map(|c| line_deviation(c)).fold(0.0, f64::max);
    (mean_lateral > 1e-9 * largest).then(|| deviation / mean_lateral)
}

/// Largest |u_i − (p + q i)| for the least-squares line through (i, u_i).
fn line_deviation(u: &[f64]) -> f64 {
    let n = u.len() as f64;
    let (mean_i, mean_u) = ((n - 1.0) / 2.0, u.iter().sum::<f64>() / n);
    let (sxy, sxx) = u.iter().enumerate().fold((0.0, 0.0), |(a, b), (i, v)| {
        let di = i as f64 - mean_i;
        (a + di * (v - mean_u), b + di * di)
    });
    let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    u.iter().enumerate().map(|(i, v)| (v - mean_u - slope * (i as f64 - mean_i)).abs()).fold(0.0, f64::max)
}

/// Elastic constants (Voigt notation, engineering shear strain) of a square lattice per unit
/// depth (N/m), from C_ijkl = (1/a²) Σ k L² n_i n_j n_k n_l over the four bonds of a node:
/// horizontal k_x, vertical k_y, rising diagonal k_r along (1, 1)/√2 and falling k_f along
/// (1, −1)/√2 (length a√2, so each adds k/2 to every entry, with the sign of n₁³n₂ in C16).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElasticConstants {
    /// C11 = k_x + (k_r + k_f)/2.
    pub c11: f64,
    /// C22 = k_y + (k_r + k_f)/2.
    pub c22: f64,
    /// C12 = (k_r + k_f)/2.
    pub c12: f64,
    /// C66 = (k_r + k_f)/2.
    pub c66: f64,
    /// C16 = C26 = (k_r − k_f)/2: one diagonal family couples stretch and shear.
    pub c16: f64,
}

/// The elastic constants of a square lattice with springs k_x, k_y, k_rising, k_falling (N/m).
pub fn lattice_constants(k_x: f64, k_y: f64, k_rising: f64, k_falling: f64) -> ElasticConstants {
    let half = 0.5 * (k_rising + k_falling);
    ElasticConstants { c11: k_x + half, c22: k_y + half, c12: half, c66: half, c16: 0.5 * (k_rising - k_falling) }
}

/// Continuum moduli in both directions (Pa) of an anisotropic lattice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContinuumModuli {
    /// E_x = 1/(S11 d).
    pub youngs_modulus_x: f64,
    /// E_y = 1/(S22 d).
    pub youngs_modulus_y: f64,
    /// ν_xy = −S12/S11 (contraction along y under a pull along x).
    pub poisson_ratio_xy: f64,
    /// ν_yx = −S12/S22.
    pub poisson_ratio_yx: f64,
    /// G = 1/(S66 d); `None` without diagonals (no shear stiffness).
    pub shear_modulus: Option<f64>,
}

/// The constrained modulus along y (Pa): σ_yy/ε_yy with no lateral strain (ε_xx = 0) and no
/// shear stress, what a periodic strip (`periodic-x`, bottom clamped) measures in tension:
/// C22 − C26²/C66 over the depth d (C22 = k_y + (k_r + k_f)/2 without the C26 coupling of
/// one diagonal family; k_y with no diagonals).
///
/// ```
/// use mdsolids::measure::constrained_modulus_y;
/// // Both diagonals: (k + k_d)/d.
/// assert!((constrained_modulus_y(2.0, 2.0, 1.0, 1.0, 0.5) - 6.0).abs() < 1e-12);
/// ```
pub fn constrained_modulus_y(k_x: f64, k_y: f64, k_rising: f64, k_falling: f64, depth: f64) -> f64 {
    let c = lattice_constants(k_x, k_y, k_rising, k_falling);
    let coupling = if c.c66 > 0.0 { c.c16 * c.c16 / c.c66 } else { 0.0 };
    (c.c22 - coupling) / depth
}

/// Moduli under uniaxial stress (the lattice free to shear, as on coursework supports) from
/// the compliance S = C⁻¹ of [`lattice_constants`], divided by the depth d (m). Without
/// diagonals C is diagonal in the normal block and singular in shear: E_x = k_x/d,
/// E_y = k_y/d, ν = 0, no G.
///
/// ```
/// use mdsolids::measure::anisotropic_moduli;
/// // Both diagonals k_d = 1, k = 2, d = 0.5: the isotropic E = (C11² − C12²)/C11/d, ν = 1/3.
/// let m = anisotropic_moduli(2.0, 2.0, 1.0, 1.0, 0.5);
/// assert!((m.youngs_modulus_y - (9.0 - 1.0) / 3.0 / 0.5).abs() < 1e-12);
/// assert!((m.poisson_ratio_xy - 1.0 / 3.0).abs() < 1e-12 && m.shear_modulus == Some(2.0));
/// // One diagonal: the block shears freely, so it pulls like its axial springs alone.
/// let one = anisotropic_moduli(2.0, 3.0, 1.0, 0.0, 1.0);
/// assert!((one.youngs_modulus_y - 3.0).abs() < 1e-12 && one.poisson_ratio_yx.abs() < 1e-12);
/// // S12 = 0 exactly there: ν is +0, never printed as -0.0.
/// assert!(one.poisson_ratio_yx.is_sign_positive() && one.poisson_ratio_xy.is_sign_positive());
/// ```
pub fn anisotropic_moduli(k_x: f64, k_y: f64, k_rising: f64, k_falling: f64, depth: f64) -> ContinuumModuli {
    let c = lattice_constants(k_x, k_y, k_rising, k_falling);
    if c.c66 == 0.0 {
        return ContinuumModuli {
            youngs_modulus_x: k_x / depth,
            youngs_modulus_y: k_y / depth,
            poisson_ratio_xy: 0.0,
            poisson_ratio_yx: 0.0,
            shear_modulus: None,
        };
    }
    let m = [[c.c11, c.c12, c.c16], [c.c12, c.c22, c.c16], [c.c16, c.c16, c.c66]];
    // S = C⁻¹ by cofactors: S_ij = cof_ji / det (C is symmetric).
    let cofactor = |i: usize, j: usize| {
        let (r, s) = ([(i + 1) % 3, (i + 2) % 3], [(j + 1) % 3, (j + 2) % 3]);
        m[r[0]][s[0]] * m[r[1]][s[1]] - m[r[0]][s[1]] * m[r[1]][s[0]]
    };
    let det = (0..3).map(|j| m[0][j] * cofactor(0, j)).sum::<f64>();
    let s = |i: usize, j: usize| cofactor(j, i) / det;
    ContinuumModuli {
        youngs_modulus_x: 1.0 / (s(0, 0) * depth),
        youngs_modulus_y: 1.0 / (s(1, 1) * depth),
        // 0 − S12, not −S12: S12 = 0 (one diagonal family) gives 0, not −0.
        poisson_ratio_xy: (0.0 - s(0, 1)) / s(0, 0),
        poisson_ratio_yx: (0.0 - s(0, 1)) / s(1, 1),
        shear_modulus: Some(1.0 / (s(2, 2) * depth)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 × 3 block's x displacements, row by row, with left and right columns `left`, `right`.
    fn block(left: [f64; 3], right: [f64; 3]) -> (LatticeShape, Vec<f64>) {
        let shape = LatticeShape { nx: 3, ny: 3, spacing: 1.0, depth: 1.0, periodic_x: false };
        let ux = (0..3).flat_map(|row| [left[row], 0.5 * (left[row] + right[row]), right[row]]).collect();
        (shape, ux)
    }

    /// Straight edges give 0, a bowed edge its deviation over the mean sideways displacement,
    /// and edges that do not move sideways (ν = 0, round-off only) no number at all.
    #[test]
    fn homogeneity_is_defined_only_where_the_edges_move() {
        let (shape, ux) = block([0.0, 0.0, 0.0], [-1e-3, -1e-3, -1e-3]);
        assert_eq!(homogeneity(&shape, &ux, 1e-2), Some(0.0));
        let (shape, ux) = block([0.0, 0.0, 0.0], [-1e-3, -2e-3, -1e-3]);
        // Line through (0, −1e-3), (1, −2e-3), (2, −1e-3): −4/3e-3, deviation 2/3e-3; mean |u| 2/3e-3.
        let h = homogeneity(&shape, &ux, 1e-2).unwrap();
        assert!((h - 1.0).abs() < 1e-12, "{h}");
        let (shape, ux) = block([1e-19, -2e-19, 0.0], [3e-19, 0.0, -1e-19]);
        assert_eq!(homogeneity(&shape, &ux, 1e-6), None);
    }
}
