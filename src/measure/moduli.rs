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
/// the mean |x displacement| of the two columns. 0 for a homogeneous deformation.
pub fn homogeneity(shape: &LatticeShape, ux: &[f64]) -> Option<f64> {
    let columns = [shape.column(ux, 0), shape.column(ux, shape.nx - 1)];
    let mean_lateral = columns.iter().flatten().map(|u| u.abs()).sum::<f64>() / (2 * shape.ny) as f64;
    let deviation = columns.iter().map(|c| line_deviation(c)).fold(0.0, f64::max);
    (mean_lateral > 0.0).then(|| deviation / mean_lateral)
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

/// Continuum moduli of a square lattice with springs k and diagonals k_d (N/m) and depth d
/// (m): C11 = k + k_d, C12 = C44 = k_d per unit depth, so E = (C11 − C12²/C11)/d,
/// ν = C12/C11, G = C44/d.
///
/// ```
/// let (e, nu, g) = mdsolids::measure::continuum_moduli(2.0, 1.0, 0.5);
/// assert!((e - (3.0 - 1.0 / 3.0) / 0.5).abs() < 1e-12 && (nu - 1.0 / 3.0).abs() < 1e-15 && g == 2.0);
/// ```
pub fn continuum_moduli(k: f64, k_diag: f64, depth: f64) -> (f64, f64, f64) {
    let (c11, c12) = (k + k_diag, k_diag);
    ((c11 - c12 * c12 / c11) / depth, c12 / c11, k_diag / depth)
}
