//! The static truss answer: the linear stiffness matrix of the same spring network with the
//! same supports and loads, solved directly (sparse Cholesky, faer). Pure: no I/O.
//!
//! Each spring of stiffness k along the unit vector n̂ between its nodes contributes
//! k n̂ n̂ᵀ to the 2 × 2 blocks (i, i) and (j, j) and −k n̂ n̂ᵀ to (i, j) and (j, i).
//! Held degrees of freedom are removed. A network with zero-energy motions (a square lattice
//! without diagonals under shear, a diluted network that lost rigidity) has a singular K; a
//! factorisation may then return garbage instead of failing, so the answer is accepted only if
//! it satisfies the unregularised equations: ‖K u − f‖ ≤ 1e-6 ‖f‖. Otherwise the load drives a
//! mechanism. Imposed displacements (a velocity drive) always leave the equations a solution;
//! they drive a mechanism when that solution stores no energy ([`Floppy::Drive`]).

mod answers;
mod kept;
mod ordering;
mod solver;
mod sparse;
mod triplets;

pub use self::answers::{Answers, Shared, StaticAnswer};
pub use self::solver::{Convergence, NEWTON_TOLERANCE, Solver, StiffnessPreconditioner};
pub use self::sparse::Analyses;
pub use self::triplets::{Entry, factor_and_solve};

use self::sparse::Analysis;
use crate::model::{Bonds, ForceLaw, Linear};
use crate::sim::{Load, euclidean_norm};

/// What the static solver found.
#[derive(Clone, Debug, PartialEq)]
pub enum StaticSolution {
    /// Node displacements (m).
    Displacements {
        /// x displacement of every node.
        ux: Vec<f64>,
        /// y displacement of every node.
        uy: Vec<f64>,
    },
    /// The load or the drive meets no stiffness: a zero-energy motion takes it.
    Mechanism(Floppy),
    /// The deadline passed before the iteration converged.
    PastDeadline,
}

/// What shows a network floppy under what moves it ([`StaticSolution::Mechanism`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Floppy {
    /// The load has a part along a zero-energy motion, so K u = f has no solution: the
    /// relative residual ‖K u − f‖/‖f‖ of the best attempt says by how much the equations fail.
    Load {
        /// ‖K u − f‖ / ‖f‖.
        residual: f64,
    },
    /// The imposed displacements u_p (a velocity drive, held where it stops) are taken by a
    /// zero-energy motion of the free nodes: K u = f always has a solution then (f = −K_fp u_p
    /// has no part along a zero mode of K_ff, which is one of the whole K and so meets no
    /// K_pf), but it stores no energy. `stiffness` is what the drive meets at first order,
    /// k_drive = 2E₁/‖u_p‖² (N/m), E₁ the energy at the rest geometry; it lies within
    /// `resolution` = εs (N/m), the shift of the factor ([`Solver`]), below which the factor
    /// tells no stiffness from none.
    Drive {
        /// k_drive (N/m).
        stiffness: f64,
        /// εs (N/m).
        resolution: f64,
    },
}

/// A spring network at rest: node positions, springs (linear, stiffness per bond), held axes
/// and loads.
pub struct Truss<'a> {
    /// Node x positions (m).
    pub x: &'a [f64],
    /// Node y positions (m).
    pub y: &'a [f64],
    /// Springs.
    pub bonds: &'a Bonds,
    /// Nodes held in x.
    pub held_x: &'a [usize],
    /// Nodes held in y.
    pub held_y: &'a [usize],
    /// External forces.
    pub loads: &'a [Load],
    /// Displacements (m) imposed on held axes, as (node, ux, uy); other held axes stay at 0.
    pub prescribed: &'a [(usize, f64, f64)],
}

/// What bounds a relaxation's error, from the tangent stiffness K_t at the static answer
/// ([`Solver::error_bounds`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorBounds {
    /// k_min (N/m): a lower bound on the smallest eigenvalue of K_t, the softest stiffness
    /// (ω_min² = k_min/m sets critical damping and the critically damped bound); 0 when K_t
    /// is singular (a floppy network).
    pub stiffness_min: f64,
    /// ‖K_t⁻¹ g‖₂ (m/N) of the measured quantity gᵀu: its error is at most this × ‖r‖₂ for an
    /// out-of-balance force r; `None` when k_min = 0 or every measured dof is held.
    pub sensitivity: Option<f64>,
}

/// Numbering of the free degrees of freedom: dof 2i is x of node i, 2i + 1 its y;
/// `index[dof]` is its row in the reduced system, `usize::MAX` when held.
#[derive(Clone)]
struct Dofs {
    index: Vec<usize>,
    free: usize,
}

impl Dofs {
    /// Node values (x and y of every node) from the free ones (held ones are zero).
    fn expand(&self, u: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let nodes = self.index.len() / 2;
        let at = |dof: usize| if self.index[dof] == usize::MAX { 0.0 } else { u[self.index[dof]] };
        ((0..nodes).map(|i| at(2 * i)).collect(), (0..nodes).map(|i| at(2 * i + 1)).collect())
    }

    /// The free values of node values `vx`, `vy` (held ones dropped).
    fn gather(&self, vx: &[f64], vy: &[f64]) -> Vec<f64> {
        let mut free = vec![0.0; self.free];
        for (dof, &row) in self.index.iter().enumerate().filter(|(_, row)| **row != usize::MAX) {
            free[row] = if dof % 2 == 0 { vx[dof / 2] } else { vy[dof / 2] };
        }
        free
    }
}

impl<'a> Truss<'a> {
    /// The solver of this network's static problems, its symbolic analysis (the pattern of K
    /// and the elimination order) taken from `analyses` when a network of the same nodes,
    /// bonds and held axes was analysed before, and added to it otherwise.
    pub fn solver(&'a self, analyses: &Analyses) -> Solver<'a> {
        let dofs = self.dofs();
        let analysis = (dofs.free > 0).then(|| analyses.get(self.structure_key(), || self.analyse(&dofs)));
        Solver::new(self, dofs, analysis)
    }

    /// A blake3 hash of what the analysis depends on: the node count, the held axes and the
    /// bonds' ends (not their stiffness, rest length or the positions).
    fn structure_key(&self) -> [u8; 32] {
        let mut hasher = blake3::Hasher::new();
        for list in [&[self.x.len()][..], self.held_x, self.held_y, &self.bonds.i, &self.bonds.j] {
            hasher.update(&list.len().to_le_bytes());
            list.iter().for_each(|v| {
                hasher.update(&v.to_le_bytes());
            });
        }
        *hasher.finalize().as_bytes()
    }

    /// A blake3 hash of what the static answer depends on besides the force law, bit for bit:
    /// the structure ([`Truss::structure_key`]), the positions, every bond's rest length,
    /// stiffness and period shift, the loads and the imposed displacements; then `law`, the
    /// force law and whatever it is linearised at, in words.
    pub fn answer_key(&self, law: &str) -> [u8; 32] {
        let mut hasher = blake3::Hasher::new();
        hasher.update(&self.structure_key());
        let b = self.bonds;
        let loads: Vec<f64> = self.loads.iter().flat_map(|l| [l.particle as f64, l.fx, l.fy]).collect();
        let prescribed: Vec<f64> = self.prescribed.iter().flat_map(|&(node, ux, uy)| [node as f64, ux, uy]).collect();
        for list in [self.x, self.y, &b.rest, &b.stiffness, &b.shift_x, &loads, &prescribed] {
            let bytes: Vec<u8> = list.iter().flat_map(|v| v.to_le_bytes()).collect();
            hasher.update(&bytes.len().to_le_bytes());
            hasher.update(&bytes);
        }
        hasher.update(law.as_bytes());
        *hasher.finalize().as_bytes()
    }

    /// The pattern of K's lower triangle over the free dofs (a node's dofs couple with its own
    /// and its bonded neighbours') and its analysis.
    fn analyse(&self, dofs: &Dofs) -> Analysis {
        let nodes = self.x.len();
        let mut neighbours: Vec<Vec<usize>> = (0..nodes).map(|n| vec![n]).collect();
        for (&i, &j) in self.bonds.i.iter().zip(&self.bonds.j) {
            neighbours[i].push(j);
            neighbours[j].push(i);
        }
        let mut columns = vec![Vec::new(); dofs.free];
        let mut positions = vec![(0.0, 0.0); dofs.free];
        for (node, near) in neighbours.iter_mut().enumerate() {
            near.sort_unstable();
            near.dedup();
            for axis in 0..2 {
                let column = dofs.index[2 * node + axis];
                if column == usize::MAX {
                    continue;
                }
                positions[column] = (self.x[node], self.y[node]);
                let rows = near.iter().flat_map(|&other| [dofs.index[2 * other], dofs.index[2 * other + 1]]);
                columns[column] = rows.filter(|&row| row != usize::MAX && row >= column).collect();
            }
        }
        Analysis::of(columns, &positions)
    }

    /// The imposed displacements: zero everywhere but on the prescribed held axes.
    fn imposed(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut ux, mut uy) = (vec![0.0; self.x.len()], vec![0.0; self.x.len()]);
        for &(node, dx, dy) in self.prescribed {
            ux[node] = dx;
            uy[node] = dy;
        }
        (ux, uy)
    }

    /// The displacements (m, x and y of every node) of the free values `free`, the imposed ones
    /// on the held axes.
    fn displaced(&self, dofs: &Dofs, free: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (mut ux, mut uy) = self.imposed();
        let (dx, dy) = dofs.expand(free);
        for i in 0..ux.len() {
            ux[i] += dx[i];
            uy[i] += dy[i];
        }
        (ux, uy)
    }

    /// The force (N, x and y) the supports apply to `nodes` to hold them at displacements
    /// `(ux, uy)`: minus the sum of the spring forces on them.
    pub fn reaction<L: ForceLaw>(&self, law: &L, ux: &[f64], uy: &[f64], nodes: &[usize]) -> (f64, f64) {
        self.support_force(nodes, |b| {
            let (n, _, tension, _) = self.bond_state(law, b, ux, uy);
            [tension * n[0], tension * n[1]]
        })
    }

    /// The force (N, x and y) the supports apply to `nodes` in the linear problem, at first
    /// order about the rest geometry, at displacements `(ux, uy)`: (K u)_p = K_pp u_p + K_pf u_f
    /// plus any pre-stress's force at rest, each bond pulling i by s₀ n̂ + A_b Δu_b (A_b its
    /// block at rest of linear springs of the bonds' k, s₀ its tension there, Δu_b = uᵢ − uⱼ).
    /// It is the reaction of [`Solver::solve_linear`]'s answer; [`Truss::reaction`] at the same
    /// displacements adds the second-order part of the springs' forces (their stretch |t|²/2r
    /// from a sideways move t, and their rotation t/r times the tension).
    pub fn linear_reaction(&self, ux: &[f64], uy: &[f64], nodes: &[usize]) -> (f64, f64) {
        let rest = vec![0.0; self.x.len()];
        self.support_force(nodes, |b| {
            let (i, j) = (self.bonds.i[b], self.bonds.j[b]);
            let moved = [ux[i] - ux[j], uy[i] - uy[j]];
            let (block, n, tension) = self.tangent_block(&Linear, b, &rest, &rest);
            [0, 1].map(|p| tension * n[p] + block[p][0] * moved[0] + block[p][1] * moved[1])
        })
    }

    /// The force (N, x and y) the supports apply to `nodes` against the springs: `pull(b)` (N)
    /// at bond b's node i and −`pull(b)` at its node j, s n̂ for a spring in tension s along n̂
    /// (from j to i), which pulls i by −s n̂ and j by +s n̂.
    fn support_force(&self, nodes: &[usize], pull: impl Fn(usize) -> [f64; 2]) -> (f64, f64) {
        let mut held = vec![false; self.x.len()];
        nodes.iter().for_each(|&node| held[node] = true);
        let mut total = (0.0, 0.0);
        for b in (0..self.bonds.len()).filter(|&b| held[self.bonds.i[b]] || held[self.bonds.j[b]]) {
            let force = pull(b);
            for (node, sign) in [(self.bonds.i[b], 1.0), (self.bonds.j[b], -1.0)] {
                if held[node] {
                    total.0 += sign * force[0];
                    total.1 += sign * force[1];
                }
            }
        }
        total
    }

    /// Bond `b`'s tangent block at `(ux, uy)`, A = s′ n̂ n̂ᵀ + (s/r)(I − n̂ n̂ᵀ) (N/m: the force on
    /// i is −A (uᵢ − uⱼ) to first order, on j +A (uᵢ − uⱼ)), and the n̂ and tension s (N) there.
    fn tangent_block<L: ForceLaw>(&self, law: &L, b: usize, ux: &[f64], uy: &[f64]) -> ([[f64; 2]; 2], [f64; 2], f64) {
        let (n, r, tension, tangent) = self.bond_state(law, b, ux, uy);
        let entry = |p: usize, q: usize| {
            let identity = if p == q { 1.0 } else { 0.0 };
            tangent * n[p] * n[q] + tension / r * (identity - n[p] * n[q])
        };
        ([[entry(0, 0), entry(0, 1)], [entry(1, 0), entry(1, 1)]], n, tension)
    }

    /// The force (N) the imposed displacements u_p put on the free degrees of freedom at first
    /// order about the rest geometry, −K_fp u_p: −A_b Δu_b on node i, +A_b Δu_b on j for the
    /// relative displacement Δu_b = uᵢ − uⱼ of bond b, A_b its block at rest of linear springs of
    /// the bonds' k (pre-stretched ones with their tension).
    fn imposed_force(&self, dofs: &Dofs) -> Vec<f64> {
        let (ux, uy) = self.imposed();
        let rest = vec![0.0; self.x.len()];
        let mut force = vec![0.0; dofs.free];
        for b in 0..self.bonds.len() {
            let (i, j) = (self.bonds.i[b], self.bonds.j[b]);
            let moved = [ux[i] - ux[j], uy[i] - uy[j]];
            if moved == [0.0, 0.0] {
                continue;
            }
            let (block, _, _) = self.tangent_block(&Linear, b, &rest, &rest);
            for (node, sign) in [(i, 1.0), (j, -1.0)] {
                for (axis, row) in block.iter().enumerate() {
                    if let Some(&free) = dofs.index.get(2 * node + axis).filter(|free| **free != usize::MAX) {
                        force[free] -= sign * (row[0] * moved[0] + row[1] * moved[1]);
                    }
                }
            }
        }
        force
    }

    /// The energy (J) of displacements `(ux, uy)` at first order about the rest geometry,
    /// E₁ = ½ uᵀK u over every degree of freedom, held ones included: ½ Σ_b (s′ e_b² + (s/r) t_b²)
    /// with e_b = n̂·Δu_b the bond's extension and t_b = n̂ × Δu_b its sideways move. Summed so,
    /// not as Δuᵀ A Δu, a zero-energy motion's E₁ is ~ε² of its scale, not ε: a rotating bond's
    /// e_b carries the round-off ε|Δu_b|, and the expanded form cancels to ε k |Δu_b|².
    fn first_order_energy(&self, ux: &[f64], uy: &[f64]) -> f64 {
        let rest = vec![0.0; self.x.len()];
        (0..self.bonds.len())
            .map(|b| {
                let (i, j) = (self.bonds.i[b], self.bonds.j[b]);
                let moved = [ux[i] - ux[j], uy[i] - uy[j]];
                let (n, r, tension, tangent) = self.bond_state(&Linear, b, &rest, &rest);
                let (extension, sideways) = (n[0] * moved[0] + n[1] * moved[1], n[0] * moved[1] - n[1] * moved[0]);
                0.5 * (tangent * extension * extension + tension / r * sideways * sideways)
            })
            .sum()
    }

    /// Unit vector n̂ from j to i, length r, tension s and tangent s′ of bond `b` at `(ux, uy)`.
    ///
    /// The extension is taken from the displacements, not from the displaced positions: with
    /// d₀ = xᵢ − xⱼ the bond at rest and Δu = uᵢ − uⱼ, δ = |d₀ + Δu| − |d₀| + δ₀ is computed as
    /// (2 d₀·Δu + |Δu|²)/(|d₀ + Δu| + |d₀|) + δ₀, exact to ε of δ. Summing x + u first would
    /// round u to ε·|x| (7e-15 m at 32 m), and the spring would carry that ulp times k: a
    /// steel block (k = 2e9 N/m) at 10 N per node then never met Newton's 1e-10 of the load.
    /// δ₀ = |d₀| − rest is a spring's pre-stretch ([`pre_stretch`]).
    fn bond_state<L: ForceLaw>(&self, law: &L, b: usize, ux: &[f64], uy: &[f64]) -> ([f64; 2], f64, f64, f64) {
        let k = self.bonds.stiffness[b];
        let ([dx, dy], r, extension) = self.bond_geometry(b, ux, uy);
        ([dx / r, dy / r], r, law.elastic_force(k, extension), law.tangent_stiffness(k, extension))
    }

    /// Vector d from j to i, length r and extension δ of bond `b` at `(ux, uy)`, as
    /// [`Truss::bond_state`] explains.
    fn bond_geometry(&self, b: usize, ux: &[f64], uy: &[f64]) -> ([f64; 2], f64, f64) {
        let (i, j, rest) = (self.bonds.i[b], self.bonds.j[b], self.bonds.rest[b]);
        let (rest_x, rest_y) = (self.x[i] - self.x[j] + self.bonds.shift_x[b], self.y[i] - self.y[j]);
        let (move_x, move_y) = (ux[i] - ux[j], uy[i] - uy[j]);
        let (dx, dy) = (rest_x + move_x, rest_y + move_y);
        let (r, r0) = (dx.hypot(dy), rest_x.hypot(rest_y));
        let stretch = (2.0 * (rest_x * move_x + rest_y * move_y) + move_x * move_x + move_y * move_y) / (r + r0);
        let resolution = f64::EPSILON * (self.x[i].abs() + self.x[j].abs() + self.y[i].abs() + self.y[j].abs());
        ([dx, dy], r, stretch + pre_stretch(r0, rest, resolution))
    }

    /// The total potential energy Π = Σ U(δ_b) − f·u (J) at displacements `(ux, uy)`: the
    /// springs' energy less the loads' work on the free degrees of freedom (a held one does not
    /// move under its load), and the largest |δ|/rest over the bonds (how far the state is from
    /// small strains), in one pass over them. The static answer is a stationary point of Π,
    /// stable where Π is least.
    fn potential<L: ForceLaw>(&self, law: &L, ux: &[f64], uy: &[f64], dofs: &Dofs) -> (f64, f64) {
        let (mut stored, mut largest_strain) = (0.0, 0.0f64);
        for b in 0..self.bonds.len() {
            let extension = self.bond_geometry(b, ux, uy).2;
            stored += law.energy(self.bonds.stiffness[b], extension);
            largest_strain = largest_strain.max((extension / self.bonds.rest[b]).abs());
        }
        let work: f64 = self.load_vector(dofs).iter().zip(dofs.gather(ux, uy)).map(|(f, u)| f * u).sum();
        (stored - work, largest_strain)
    }

    fn dofs(&self) -> Dofs {
        let mut index = vec![usize::MAX; 2 * self.x.len()];
        let mut free = 0;
        for (dof, slot) in index.iter_mut().enumerate() {
            let held = if dof % 2 == 0 { self.held_x } else { self.held_y };
            if held.binary_search(&(dof / 2)).is_err() {
                *slot = free;
                free += 1;
            }
        }
        Dofs { index, free }
    }

    /// The loads on the free degrees of freedom.
    fn load_vector(&self, dofs: &Dofs) -> Vec<f64> {
        let mut force = vec![0.0; dofs.free];
        for load in self.loads {
            for (dof, value) in [(2 * load.particle, load.fx), (2 * load.particle + 1, load.fy)] {
                if dofs.index[dof] != usize::MAX {
                    force[dofs.index[dof]] += value;
                }
            }
        }
        force
    }

    /// The tangent stiffness over the free degrees of freedom, written into `stiffness` (its
    /// lower triangle on `analysis`'s pattern), and the out-of-balance force R = loads + spring
    /// forces, at displacements `(ux, uy)`.
    fn tangent_and_residual<L: ForceLaw>(
        &self,
        law: &L,
        (ux, uy): (&[f64], &[f64]),
        dofs: &Dofs,
        analysis: &Analysis,
        stiffness: &mut [f64],
    ) -> Vec<f64> {
        stiffness.fill(0.0);
        let mut residual = self.load_vector(dofs);
        for b in 0..self.bonds.len() {
            let (i, j) = (self.bonds.i[b], self.bonds.j[b]);
            // The force on i is −s n̂, on j +s n̂.
            let (block, n, tension) = self.tangent_block(law, b, ux, uy);
            for (a, sign_a) in [(i, 1.0), (j, -1.0)] {
                for (p, n_p) in n.iter().enumerate() {
                    let row = dofs.index[2 * a + p];
                    if row == usize::MAX {
                        continue;
                    }
                    residual[row] -= sign_a * tension * n_p;
                    for (c, sign_c) in [(i, 1.0), (j, -1.0)] {
                        for (q, entry) in block[p].iter().enumerate() {
                            let column = dofs.index[2 * c + q];
                            if column != usize::MAX && row >= column {
                                stiffness[analysis.slot(row, column)] += sign_a * sign_c * entry;
                            }
                        }
                    }
                }
            }
        }
        residual
    }
}

/// A spring's stretch at the reference positions, |d₀| − rest (m), or 0 where that is below
/// the resolution of the positions, `resolution` = ε(|xᵢ| + |xⱼ| + |yᵢ| + |yⱼ|) (m): a lattice's
/// springs are at rest there by construction, and what differs is the rounding of the
/// positions, which taken literally would pre-stress every spring by k·ε·|x| (1e14 N for
/// k = 1e30 N/m at 1 m, against a load of 1 kN).
fn pre_stretch(length: f64, rest: f64, resolution: f64) -> f64 {
    let stretch = length - rest;
    if stretch.abs() <= 4.0 * (resolution + f64::EPSILON * rest) { 0.0 } else { stretch }
}

/// Iterative refinements of a solve with a fresh factor of the shifted K, at most (each one
/// more solve with the same factor; two are usually all the shift needs).
const REFINEMENTS: usize = 3;

/// K u = `force` by a factor of the shifted K + εI (`solve`), refined against the unshifted K
/// (`out_of_balance`: u ↦ f − K u): u ← u + (K + εI)⁻¹(f − K u), while the residual falls at
/// least twofold, at most [`REFINEMENTS`] times (a load on a mechanism's zero mode never lets it
/// fall). The shift alone leaves u off by about ε‖K⁻¹‖ (6e-11 of E on a 10 × 10 steel block).
/// `None` when a solve fails.
fn refined_solve(
    force: &[f64],
    mut solve: impl FnMut(&[f64]) -> Option<Vec<f64>>,
    out_of_balance: impl Fn(&[f64]) -> Vec<f64>,
) -> Option<Vec<f64>> {
    let mut u = solve(force)?;
    let mut residual = out_of_balance(&u);
    for _ in 0..REFINEMENTS {
        let correction = solve(&residual)?;
        let refined: Vec<f64> = u.iter().zip(&correction).map(|(a, b)| a + b).collect();
        let left = out_of_balance(&refined);
        if euclidean_norm(left.iter()) >= 0.5 * euclidean_norm(residual.iter()) {
            break;
        }
        (u, residual) = (refined, left);
    }
    Some(u)
}
