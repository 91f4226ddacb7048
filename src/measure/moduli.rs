//! Elastic moduli of a loaded lattice from its node displacements (MD after relaxation, or the
//! static solution): the same function serves both, so they are compared like for like.
//!
//! Widths L_x, L_y of the block's [`Edges`] ((N_x − 1) a, (N_y − 1) a for the square
//! lattice), depth d; F is the total force on the top row. ΔL are differences of mean
//! displacements of rows or columns.

use crate::model::{Edges, LatticeType};

/// A loaded lattice's rows and columns by name, its size and depth d (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LatticeShape<'a> {
    /// The bottom and top rows, the side columns, L_x and L_y.
    pub edges: &'a Edges,
    /// Depth d (m).
    pub depth: f64,
}

/// Mean of `u` over `nodes`.
fn mean(u: &[f64], nodes: &[usize]) -> f64 {
    nodes.iter().map(|&n| u[n]).sum::<f64>() / nodes.len() as f64
}

/// Values of `u` at `nodes`, in their order.
fn values(u: &[f64], nodes: &[usize]) -> Vec<f64> {
    nodes.iter().map(|&n| u[n]).collect()
}

/// ΔL (m) of a lattice's measured modulus: the mean of `u` (u_y in tension, u_x in shear)
/// over the top row minus its mean over the bottom row.
pub fn row_extension(shape: &LatticeShape, u: &[f64]) -> f64 {
    mean(u, &shape.edges.top) - mean(u, &shape.edges.bottom)
}

/// The weights g of ΔL = gᵀu as (node, weight) pairs, the functional [`row_extension`]
/// computes: 1/N_top on each top-row node, −1/N_bottom on each bottom-row node (of `u`'s axis).
pub fn row_extension_weights(shape: &LatticeShape) -> Vec<(usize, f64)> {
    let (top, bottom) = (&shape.edges.top, &shape.edges.bottom);
    let top_weight = 1.0 / top.len() as f64;
    let bottom_weight = -1.0 / bottom.len() as f64;
    top.iter().map(|&n| (n, top_weight)).chain(bottom.iter().map(|&n| (n, bottom_weight))).collect()
}

/// The bound on the relative error |M/M* − 1| of a modulus M ∝ 1/ΔL (E in tension, G in shear,
/// under force control) measured at the extension `measured` = ΔL (m) when ΔL is within
/// `extension_error` (m) of its value at rest ΔL*: M/M* = ΔL*/ΔL, so |M/M* − 1| =
/// |ΔL* − ΔL|/|ΔL| ≤ `extension_error`/|ΔL| (∞ at ΔL = 0).
pub fn modulus_error_bound(measured: f64, extension_error: f64) -> f64 {
    extension_error / measured.abs()
}

/// The largest error of ΔL (m) allowed at the extension at rest `extension` = ΔL* (m) for
/// [`modulus_error_bound`] to be at most `tolerance`: tolerance/(1 + tolerance) |ΔL*|. Then
/// |ΔL| ≥ |ΔL*|/(1 + tolerance), and the bound at ΔL is at most the tolerance.
pub fn extension_error_allowed(extension: f64, tolerance: f64) -> f64 {
    tolerance / (1.0 + tolerance) * extension.abs()
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
    let e = shape.edges;
    let stretch = mean(uy, &e.top) - mean(uy, &e.bottom);
    let widening = mean(ux, &e.right) - mean(ux, &e.left);
    let strain_y = stretch / e.height;
    TensileModuli {
        youngs_modulus: force / shape.depth / e.width / strain_y,
        poisson_ratio: -(widening / e.width) / strain_y,
        poisson_ratio_coursework: widening / stretch,
    }
}

/// G = (F/d/L_x) / (ΔL_x,top / L_y) from a shear test, with ΔL_x,top the mean x displacement
/// of the top row relative to the bottom row (Pa).
pub fn shear_modulus(shape: &LatticeShape, force: f64, ux: &[f64]) -> f64 {
    let e = shape.edges;
    let shift = mean(ux, &e.top) - mean(ux, &e.bottom);
    force / shape.depth / e.width / (shift / e.height)
}

/// How far the left and right columns are from straight lines: the largest deviation of a
/// column node's x displacement from the least-squares line through its column, relative to
/// the mean |x displacement| of the two columns. 0 for a homogeneous deformation. Not defined
/// (`None`) where the edges do not move sideways: a mean |x displacement| below 1e-9 of the
/// largest displacement `largest` (m) is round-off (a lattice without diagonals, ν = 0), and
/// a ratio of round-offs says nothing.
pub fn homogeneity(shape: &LatticeShape, ux: &[f64], largest: f64) -> Option<f64> {
    let columns = [values(ux, &shape.edges.left), values(ux, &shape.edges.right)];
    let nodes = columns.iter().map(Vec::len).sum::<usize>();
    let mean_lateral = columns.iter().flatten().map(|u| u.abs()).sum::<f64>() / nodes as f64;
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

/// The constrained shear modulus (Pa) that a periodic strip (`periodic-x`, bottom clamped) measures
/// under a shear load on its top row: its period holds ε_xx = 0 and its free top σ_yy = 0, so
/// ε_yy = −C26 γ/C22 and τ = (C66 − C26²/C22) γ, over the depth d (C66 = (k_r + k_f)/2; one
/// diagonal family couples shear and stretch through C26 = (k_r − k_f)/2, where 1/S66 would
/// let the strip stretch along x too). `None` without diagonals: no shear stiffness.
///
/// ```
/// use mdsolids::measure::constrained_shear_modulus;
/// // One family (k_r = 1, k_f = 0) on k = 2: C66 = 0.5, C26 = 0.5, C22 = 2.5: 0.5 − 0.1.
/// assert!((constrained_shear_modulus(2.0, 2.0, 1.0, 0.0, 1.0).unwrap() - 0.4).abs() < 1e-12);
/// ```
pub fn constrained_shear_modulus(k_x: f64, k_y: f64, k_rising: f64, k_falling: f64, depth: f64) -> Option<f64> {
    let c = lattice_constants(k_x, k_y, k_rising, k_falling);
    Some((c.c66 - c.c16 * c.c16 / c.c22) / depth).filter(|g| *g > 0.0)
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
    let Some(s) = compliance(&lattice_constants(k_x, k_y, k_rising, k_falling)) else {
        return ContinuumModuli {
            youngs_modulus_x: k_x / depth,
            youngs_modulus_y: k_y / depth,
            poisson_ratio_xy: 0.0,
            poisson_ratio_yx: 0.0,
            shear_modulus: None,
        };
    };
    ContinuumModuli {
        youngs_modulus_x: 1.0 / (s[0][0] * depth),
        youngs_modulus_y: 1.0 / (s[1][1] * depth),
        // 0 − S12, not −S12: S12 = 0 (one diagonal family) gives 0, not −0.
        poisson_ratio_xy: (0.0 - s[0][1]) / s[0][0],
        poisson_ratio_yx: (0.0 - s[0][1]) / s[1][1],
        shear_modulus: Some(1.0 / (s[2][2] * depth)),
    }
}

/// Poisson's ratio of the continuum of a square lattice of power-law springs s = C |δ|^β sign δ,
/// both diagonals (C_d = r C, r = `k_diag_ratio`), pulled along y with no stress along x.
///
/// Every node is a centre of inversion of its bonds, so the strain is affine (ε_xx = −ν ε,
/// ε_yy = ε): the horizontal spring's extension is −ν ε a, each diagonal's (1 − ν) ε a/√2. No
/// stress along x, σ_xx a² = f_h a + 2 f_d (a√2)(1/2) = 0, gives −f_h = √2 f_d, that is
/// ν^β = √2 r ((1 − ν)/√2)^β, so ν/(1 − ν) = q = (r 2^((1−β)/2))^(1/β) and ν = q/(1 + q). It
/// does not depend on the load (scaling the strain by λ scales every force by λ^β); β = 1 gives
/// the linear lattice's ν = k_d/(k + k_d).
///
/// ```
/// use mdsolids::measure::power_law_poisson_ratio;
/// assert!((power_law_poisson_ratio(0.5, 1.0) - 1.0 / 3.0).abs() < 1e-15);
/// // Hertz, r = 1/2: q = (2^(−5/4))^(2/3) = 2^(−5/6).
/// let q = 2f64.powf(-5.0 / 6.0);
/// assert!((power_law_poisson_ratio(0.5, 1.5) - q / (1.0 + q)).abs() < 1e-15);
/// ```
pub fn power_law_poisson_ratio(k_diag_ratio: f64, beta: f64) -> f64 {
    let q = (k_diag_ratio * 2f64.powf((1.0 - beta) / 2.0)).powf(1.0 / beta);
    q / (1.0 + q)
}

/// The compliance S = C⁻¹ (m/N per unit depth; Voigt order xx, yy, xy with the engineering
/// shear γ = 2ε_xy) of a square lattice's constants, by cofactors (C is symmetric); `None`
/// without diagonals (C66 = 0: no shear stiffness, C singular).
fn compliance(c: &ElasticConstants) -> Option<[[f64; 3]; 3]> {
    if c.c66 == 0.0 {
        return None;
    }
    let m = [[c.c11, c.c12, c.c16], [c.c12, c.c22, c.c16], [c.c16, c.c16, c.c66]];
    let cofactor = |i: usize, j: usize| {
        let (r, s) = ([(i + 1) % 3, (i + 2) % 3], [(j + 1) % 3, (j + 2) % 3]);
        m[r[0]][s[0]] * m[r[1]][s[1]] - m[r[0]][s[1]] * m[r[1]][s[0]]
    };
    let det = (0..3).map(|j| m[0][j] * cofactor(0, j)).sum::<f64>();
    Some(std::array::from_fn(|i| std::array::from_fn(|j| cofactor(j, i) / det)))
}

/// Young's modulus (Pa) of a square lattice's continuum pulled along the direction at `angle`
/// (radians from x): a uniaxial stress σ along n = (cos θ, sin θ) is σ v with
/// v = (cos²θ, sin²θ, cos θ sin θ) in Voigt order, and strains the continuum along n by
/// vᵀ S v σ, so E(θ) = 1/(vᵀ S v d). `None` without diagonals: off the axes such a network
/// has no stiffness.
pub fn youngs_modulus_along(k_x: f64, k_y: f64, k_rising: f64, k_falling: f64, depth: f64, angle: f64) -> Option<f64> {
    let s = compliance(&lattice_constants(k_x, k_y, k_rising, k_falling))?;
    let (sin, cos) = angle.sin_cos();
    let v = [cos * cos, sin * sin, cos * sin];
    let strain: f64 = (0..3).map(|i| (0..3).map(|j| v[i] * s[i][j] * v[j]).sum::<f64>()).sum();
    Some(1.0 / (strain * depth))
}

/// Lamé constants per unit depth (N/m) of an isotropic network of central springs k with
/// nearest-neighbour distance a, and its area per node A (m²): the continuum of the
/// triangular, kagome and honeycomb lattices (isotropic by their six-fold symmetry).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IsotropicConstants {
    /// λ (N/m).
    pub lambda: f64,
    /// μ = C66 (N/m).
    pub mu: f64,
    /// Area per node A (m²): the mass per unit area is m/A.
    pub area_per_node: f64,
}

impl IsotropicConstants {
    /// Young's modulus under uniaxial stress, E = 4μ(λ + μ)/(λ + 2μ) / d (Pa).
    pub fn youngs_modulus(&self, depth: f64) -> f64 {
        4.0 * self.mu * (self.lambda + self.mu) / (self.lambda + 2.0 * self.mu) / depth
    }

    /// Poisson's ratio ν = λ/(λ + 2μ) (plane stress of a sheet: the 2D ratio).
    pub fn poisson_ratio(&self) -> f64 {
        self.lambda / (self.lambda + 2.0 * self.mu)
    }

    /// The constrained modulus (λ + 2μ)/d (Pa): what a periodic strip measures in tension.
    pub fn constrained_modulus(&self, depth: f64) -> f64 {
        (self.lambda + 2.0 * self.mu) / depth
    }

    /// Shear modulus μ/d (Pa).
    pub fn shear_modulus(&self, depth: f64) -> f64 {
        self.mu / depth
    }

    /// Longitudinal and transverse sound speeds (m/s), c² = C A/m with C = λ + 2μ or μ.
    pub fn sound_speeds(&self, mass: f64) -> (f64, f64) {
        let c = |modulus: f64| (modulus * self.area_per_node / mass).sqrt();
        (c(self.lambda + 2.0 * self.mu), c(self.mu))
    }
}

/// The continuum of a triangular, kagome or honeycomb lattice of central springs k (N/m),
/// spacing a (m); `None` for the square lattice (anisotropic, [`anisotropic_moduli`]).
///
/// Derivation: every node of both lattices is a centre of inversion of its bonds (it sits on
/// straight lines of bonds), so a uniform strain is in equilibrium node by node and the elastic
/// constants are the affine sums C_ijkl = (1/A_cell) Σ_cell k a² n_i n_j n_k n_l. Over bonds at
/// 0°, 60°, 120°: Σ n_x⁴ = 1 + 2/16 = 9/8 and Σ n_x² n_y² = 2 · (1/4)(3/4) = 3/8. The triangular
/// cell (area √3a²/2) holds one bond of each direction: C11 = (9/8) k a²/(√3a²/2) = 3√3k/4,
/// C12 = C66 = (3/8) k a²/(√3a²/2) = √3k/4, so λ = μ = √3k/4 (per unit depth: √3k/(4d)),
/// E = 8μ/3 = 2k/(√3 d), ν = 1/3, and with m/A the mass per area, c_L = a√(9k/(8m)),
/// c_T = a√(3k/(8m)). The kagome cell (2a × a√3, area 2√3a², three nodes) holds two bonds of
/// each direction: half the bond density, λ = μ = √3k/8, c_L = a√(3k/(4m)), c_T = a√(k/(4m)).
/// The honeycomb's nodes are not centres of inversion: under shear its three bonds at 120°
/// turn at no cost (z = 3 < 4), so μ = 0; a dilation ε stretches every bond by εa (by the
/// three-fold symmetry, in equilibrium), 3/2 bonds of energy ½k(εa)² per node of area
/// 3√3a²/4, which is 2(λ + μ)ε²: λ = k/(2√3), c_L = a√(3k/(8m)), no E, G or c_T.
///
/// ```
/// use mdsolids::measure::network_constants;
/// use mdsolids::model::LatticeType;
/// let t = network_constants(LatticeType::Triangular, 2.0, 0.1).unwrap();
/// assert!((t.youngs_modulus(0.5) - 2.0 * 2.0 / (3.0_f64.sqrt() * 0.5)).abs() < 1e-12);
/// assert!((t.poisson_ratio() - 1.0 / 3.0).abs() < 1e-15);
/// let (c_l, c_t) = t.sound_speeds(3.0);
/// assert!((c_l - 0.1 * (9.0 * 2.0 / 24.0_f64).sqrt()).abs() < 1e-12);
/// assert!((c_t - 0.1 * (3.0 * 2.0 / 24.0_f64).sqrt()).abs() < 1e-12);
/// let h = network_constants(LatticeType::Honeycomb, 2.0, 0.1).unwrap();
/// assert!(h.mu == 0.0 && (h.lambda - 1.0 / 3.0_f64.sqrt()).abs() < 1e-15);
/// assert!((h.sound_speeds(3.0).0 - 0.1 * (3.0 * 2.0 / 24.0_f64).sqrt()).abs() < 1e-12);
/// ```
pub fn network_constants(kind: LatticeType, k: f64, spacing: f64) -> Option<IsotropicConstants> {
    let s3 = 3.0_f64.sqrt();
    let (lambda, mu) = match kind {
        LatticeType::Triangular => (s3 * k / 4.0, s3 * k / 4.0),
        LatticeType::Kagome => (s3 * k / 8.0, s3 * k / 8.0),
        LatticeType::Honeycomb => (k / (2.0 * s3), 0.0),
        LatticeType::Square => return None,
    };
    Some(IsotropicConstants { lambda, mu, area_per_node: kind.area_per_node(spacing) })
}

/// Speeds (m/s) of the plane waves that run down a lattice of another type than square, along
/// y (the normal of its rows, as from a force step on the whole top row): the slopes ω/q of
/// its acoustic Bloch branches as q → 0, longitudinal and, where there is one, transverse.
/// `None` for the square lattice (its c² = C A/m from `lattice_constants`).
///
/// The triangular lattice has one node per cell, so its branches are its continuum's:
/// c_L = a√(9k/(8m)), c_T = a√(3k/(8m)) ([`IsotropicConstants::sound_speeds`]). The
/// honeycomb's transverse branch along y is flat at zero (μ = 0): no transverse wave, c_L =
/// a√(3k/(8m)). The kagome (z = 2d) has a third zero mode at q = 0 beside the two
/// translations, its triangles twisting in turn, and at q ≠ 0 that twist joins the transverse
/// motion at the order of the strain: along y its two x-polarised branches have the slopes 0
/// (a line of zero modes: a periodic strip shears as a mechanism) and a√(k/(2m)) = √2 c_T, not
/// the affine c_T = a√(k/(4m)) (its transverse slope along x); c_L = a√(3k/(4m)) holds.
/// These slopes come from the cell's 6 × 6 dynamical matrix, which the test suite
/// diagonalises for every type (`unit::measure_moduli`).
pub fn plane_wave_speeds(kind: LatticeType, k: f64, spacing: f64, mass: f64) -> Option<(f64, Option<f64>)> {
    let (c_l, c_t) = network_constants(kind, k, spacing)?.sound_speeds(mass);
    let transverse = match kind {
        LatticeType::Kagome => spacing * (k / (2.0 * mass)).sqrt(),
        _ => c_t,
    };
    Some((c_l, Some(transverse).filter(|&c| c > 0.0)))
}
