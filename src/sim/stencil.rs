//! The force loop of a regular square (or triangular: staggered) lattice, row by row without
//! a bond list.
//!
//! Bonds between two rows (vertical and both diagonals) join element t of one row slice to
//! element t of another, so each loop writes distinct elements and vectorises (sqrt and
//! division four at a time). Bonds within a row join t and t+1; their forces go to a scratch
//! row first and are then added as `h[t] − h[t−1]`. Rows are grouped in fixed blocks: a block's
//! thread handles its rows and the bonds between them, and the bonds between blocks follow.
//! The blocking does not depend on the thread count, so neither do the results.
//!
//! Damped lattices keep the loops vectorised: a running sum of the dissipated power inside the
//! bond loop is a serial chain of additions the compiler may not reorder, and it kept sqrt and
//! division scalar (4× slower). Each bond's power goes into a scratch row instead (`loss[t]`,
//! one row per family of bonds: within the row, vertical, rising, falling), and the four rows
//! are summed afterwards, each in sixteen partial sums, which vectorise. On one thread the
//! background damping's power γ_g Σ v² is summed row by row beside them instead of in a pass of
//! its own, and its forces −γ_g v are subtracted
//! from each row as soon as the row's last bond is in, while it is in cache (after every bond,
//! as before).

use rayon::prelude::*;

use super::field::{ForceField, add_background_damping, subtract_background_damping};
use super::parallel::worth_splitting;
use crate::model::{Dashpot, ForceLaw, Spring, SquareLattice};

/// Rows per block.
const BLOCK_ROWS: usize = 16;

/// A block's index with its forces (x, y) and scratch (x, y, dissipated power), as the zipped
/// chunk iterators deliver them.
type BlockSlices<'a> = (usize, ((((&'a mut [f64], &'a mut [f64]), &'a mut [f64]), &'a mut [f64]), &'a mut [f64]));

/// A block's scratch: the forces of the bonds within a row (x, y), one row each, and the power
/// (W) each bond dissipates, four rows ([`Family`]), slot t for the bond whose first end is
/// node t of its row; slots a family lacks stay 0.
struct Scratch<'a> {
    hx: &'a mut [f64],
    hy: &'a mut [f64],
    loss: &'a mut [f64],
}

/// The families of bonds of a row, in the order their power was always summed: the row of
/// `loss` each writes.
#[derive(Clone, Copy)]
enum Family {
    Within = 0,
    Vertical = 1,
    Rising = 2,
    Falling = 3,
}

/// Rows of dissipated power per block, one per [`Family`].
const FAMILIES: usize = 4;

/// Positions and (dashpot) velocities of a run of particles.
#[derive(Clone, Copy)]
struct Nodes<'a> {
    x: &'a [f64],
    y: &'a [f64],
    vx: &'a [f64],
    vy: &'a [f64],
}

impl<'a> Nodes<'a> {
    fn range(&self, range: std::ops::Range<usize>) -> Nodes<'a> {
        Nodes { x: &self.x[range.clone()], y: &self.y[range.clone()], vx: &self.vx[range.clone()], vy: &self.vy[range] }
    }
}

/// A regular lattice of identical-law springs, with optional background damping.
#[derive(Clone, Debug)]
pub struct LatticeNetwork<L, D, const CONTACT: bool> {
    spring: Spring<L, D, CONTACT>,
    lattice: SquareLattice,
    background_gamma: f64,
    /// Forces of the bonds within a row and dissipated power: one row (power: [`FAMILIES`]
    /// rows) per block each, reused row after row so they stay in L1.
    scratch_x: Vec<f64>,
    scratch_y: Vec<f64>,
    scratch_loss: Vec<f64>,
}

impl<L: ForceLaw, D: Dashpot, const CONTACT: bool> LatticeNetwork<L, D, CONTACT> {
    /// The network of `lattice` with background damping `background_gamma` (N s/m, 0 for none).
    pub fn new(spring: Spring<L, D, CONTACT>, lattice: SquareLattice, background_gamma: f64) -> Self {
        let scratch = lattice.ny.div_ceil(BLOCK_ROWS) * lattice.nx;
        LatticeNetwork {
            spring,
            lattice,
            background_gamma,
            scratch_x: vec![0.0; scratch],
            scratch_y: vec![0.0; scratch],
            scratch_loss: vec![0.0; FAMILIES * scratch],
        }
    }

    /// Bonds of stiffness `k` and rest length `rest` joining `p[t]` to `q[t]`, for all t; their
    /// dissipated power into `loss[t]` (when damped).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)] // two sides, each positions, velocities and forces
    fn between(
        &self,
        k: f64,
        rest: f64,
        p: Nodes,
        q: Nodes,
        fpx: &mut [f64],
        fpy: &mut [f64],
        fqx: &mut [f64],
        fqy: &mut [f64],
        loss: &mut [f64],
    ) {
        let m = p.x.len();
        let (p, q) = (p.range(0..m), q.range(0..m));
        let (fpx, fpy, fqx, fqy, loss) = (&mut fpx[..m], &mut fpy[..m], &mut fqx[..m], &mut fqy[..m], &mut loss[..m]);
        for t in 0..m {
            let (dvx, dvy) = if D::ACTIVE { (p.vx[t] - q.vx[t], p.vy[t] - q.vy[t]) } else { (0.0, 0.0) };
            let f = self.spring.force_on_i(k, rest, p.x[t] - q.x[t], p.y[t] - q.y[t], dvx, dvy);
            fpx[t] += f.fx;
            fpy[t] += f.fy;
            fqx[t] -= f.fx;
            fqy[t] -= f.fy;
            if D::ACTIVE {
                loss[t] = f.dissipation;
            }
        }
    }

    /// Horizontal bonds of one row: forces into the scratch row `(hx, hy)`, then added as
    /// `f[t] += h[t] − h[t−1]`; dissipated power into the scratch's [`Family::Within`] row.
    #[inline(always)]
    fn within_row(&self, row: Nodes, scratch: &mut Scratch, fx: &mut [f64], fy: &mut [f64]) {
        let nx = row.x.len();
        if self.lattice.k_x == 0.0 || nx < 2 {
            return;
        }
        let (left, right) = (row.range(0..nx - 1), row.range(1..nx));
        let (hx, hy) = (&mut scratch.hx[..nx - 1], &mut scratch.hy[..nx - 1]);
        let loss = &mut family_row(scratch.loss, Family::Within, nx)[..nx - 1];
        let (k, rest) = (self.lattice.k_x, self.lattice.spacing);
        for t in 0..nx - 1 {
            let (dvx, dvy) = if D::ACTIVE { (left.vx[t] - right.vx[t], left.vy[t] - right.vy[t]) } else { (0.0, 0.0) };
            let f = self.spring.force_on_i(k, rest, left.x[t] - right.x[t], left.y[t] - right.y[t], dvx, dvy);
            hx[t] = f.fx;
            hy[t] = f.fy;
            if D::ACTIVE {
                loss[t] = f.dissipation;
            }
        }
        let (fx, fy) = (&mut fx[..nx], &mut fy[..nx]);
        fx[0] += hx[0];
        fy[0] += hy[0];
        for t in 1..nx - 1 {
            fx[t] += hx[t] - hx[t - 1];
            fy[t] += hy[t] - hy[t - 1];
        }
        fx[nx - 1] -= hx[nx - 2];
        fy[nx - 1] -= hy[nx - 2];
    }

    /// Vertical and diagonal bonds between row `a` (below, row number `lower`) and row `b`
    /// (above); their dissipated power into their families' rows of `loss`.
    #[inline(always)]
    fn between_rows(
        &self,
        lower: usize,
        a: Nodes,
        b: Nodes,
        fa: (&mut [f64], &mut [f64]),
        fb: (&mut [f64], &mut [f64]),
        loss: &mut [f64],
    ) {
        let l = &self.lattice;
        let nx = l.nx;
        let (fax, fay) = fa;
        let (fbx, fby) = fb;
        let (k_rising, k_falling) = l.diagonals_above(lower);
        if D::ACTIVE && l.staggered {
            // One diagonal family per pair of rows: the other one's row of `loss` still holds
            // the power of the pair below, and every row is summed.
            let absent = if k_rising == 0.0 { Family::Rising } else { Family::Falling };
            family_row(loss, absent, nx).fill(0.0);
        }
        if l.k_y != 0.0 {
            self.between(l.k_y, l.spacing, a, b, fax, fay, fbx, fby, family_row(loss, Family::Vertical, nx));
        }
        if nx > 1 && k_rising != 0.0 {
            let (p, q) = (a.range(0..nx - 1), b.range(1..nx));
            let (fbx, fby) = (&mut fbx[1..], &mut fby[1..]);
            let loss = family_row(loss, Family::Rising, nx);
            self.between(k_rising, l.diagonal_rest(), p, q, &mut fax[..nx - 1], &mut fay[..nx - 1], fbx, fby, loss);
        }
        if nx > 1 && k_falling != 0.0 {
            let (p, q) = (a.range(1..nx), b.range(0..nx - 1));
            let (fbx, fby) = (&mut fbx[..nx - 1], &mut fby[..nx - 1]);
            let loss = family_row(loss, Family::Falling, nx);
            self.between(k_falling, l.diagonal_rest(), p, q, &mut fax[1..], &mut fay[1..], fbx, fby, loss);
        }
    }

    /// All bonds of the rows starting at row `first` whose forces are `(fx, fy)` (these rows
    /// only): within each row, and between each row and the one below it in the block, row
    /// after row so both rows are still in cache. Returns the power dissipated, summed
    /// row by row: within, then with the row below. With `background`, the running sum of the
    /// background power over the particles so far, adds these rows' γ_g v² to it and, unless
    /// bonds wrap around (they come last), subtracts γ_g v from each row once it is complete.
    fn block(
        &self,
        first: usize,
        nodes: Nodes,
        fx: &mut [f64],
        fy: &mut [f64],
        scratch: &mut Scratch,
        background: Option<&mut f64>,
    ) -> f64 {
        let nx = self.lattice.nx;
        let rows = fx.len() / nx;
        let row = |r: usize| nodes.range((first + r) * nx..(first + r + 1) * nx);
        let mut spare = 0.0;
        let (gamma, running) = match background {
            Some(sum) => (self.background_gamma, sum),
            None => (0.0, &mut spare),
        };
        let fold = gamma > 0.0 && !self.lattice.periodic_x;
        let mut power = 0.0;
        for r in 0..rows {
            let span = r * nx..(r + 1) * nx;
            self.within_row(row(r), scratch, &mut fx[span.clone()], &mut fy[span]);
            if r > 0 {
                self.rows_pair(first + r - 1, row(r - 1), row(r), r * nx, fx, fy, scratch.loss);
                if fold && !self.joins_blocks(first + r - 1) {
                    self.damp_row(nodes, first + r - 1, first, fx, fy);
                }
            }
            if D::ACTIVE || gamma > 0.0 {
                let [within, vertical, rising, falling] = family_sums(scratch.loss, row(r), gamma, running);
                if D::ACTIVE {
                    power += within;
                    if r > 0 {
                        power += (vertical + rising) + falling;
                    }
                }
            }
        }
        if fold && !self.joins_blocks(first + rows - 1) {
            self.damp_row(nodes, first + rows - 1, first, fx, fy);
        }
        power
    }

    /// True when row `r`'s last bond is added after the blocks, by the bonds between blocks:
    /// the first row of every block but the first, the last row of every block but the last.
    fn joins_blocks(&self, r: usize) -> bool {
        (r > 0 && r.is_multiple_of(BLOCK_ROWS)) || (r % BLOCK_ROWS == BLOCK_ROWS - 1 && r + 1 < self.lattice.ny)
    }

    /// Background damping f −= γ_g v on row `r`, whose forces are complete; `(fx, fy)` hold
    /// the rows from row `first` on.
    fn damp_row(&self, nodes: Nodes, r: usize, first: usize, fx: &mut [f64], fy: &mut [f64]) {
        let nx = self.lattice.nx;
        let (row, span) = (nodes.range(r * nx..(r + 1) * nx), (r - first) * nx..(r - first + 1) * nx);
        subtract_background_damping(self.background_gamma, row.vx, row.vy, &mut fx[span.clone()], &mut fy[span]);
    }

    /// The bonds that wrap across the sides of a periodic lattice: from the last node of each
    /// row to the first node of the same row and of the row above, one period on, and from the
    /// first node (one period on) to the last node of the row above. A few per row, so plain
    /// scalar code after the vectorised rows.
    fn wrapped(&self, nodes: Nodes, fx: &mut [f64], fy: &mut [f64]) -> f64 {
        let l = &self.lattice;
        let (last, period, diagonal) = (l.nx - 1, l.period(), l.diagonal_rest());
        let mut power = 0.0;
        let mut bond = |i: usize, j: usize, k: f64, rest: f64, shift: f64| {
            let (dvx, dvy) =
                if D::ACTIVE { (nodes.vx[i] - nodes.vx[j], nodes.vy[i] - nodes.vy[j]) } else { (0.0, 0.0) };
            let f = self.spring.force_on_i(k, rest, nodes.x[i] - nodes.x[j] + shift, nodes.y[i] - nodes.y[j], dvx, dvy);
            fx[i] += f.fx;
            fy[i] += f.fy;
            fx[j] -= f.fx;
            fy[j] -= f.fy;
            power += f.dissipation;
        };
        for iy in 0..l.ny {
            let (k_rising, k_falling) = l.diagonals_above(iy);
            if l.k_x != 0.0 {
                bond(l.node(last, iy), l.node(0, iy), l.k_x, l.spacing, -period);
            }
            if iy + 1 < l.ny && k_rising != 0.0 {
                bond(l.node(last, iy), l.node(0, iy + 1), k_rising, diagonal, -period);
            }
            if iy + 1 < l.ny && k_falling != 0.0 {
                bond(l.node(0, iy), l.node(last, iy + 1), k_falling, diagonal, period);
            }
        }
        power
    }

    /// Bonds between two consecutive rows, `lower` and the one above, whose forces are
    /// `fx[..split]` (last row of the lower part) and `fx[split..]` (first row of the upper
    /// part); dissipated power into the families' rows of `loss`.
    #[allow(clippy::too_many_arguments)] // the row number, both rows, the split and the outputs
    fn rows_pair(
        &self,
        lower: usize,
        a: Nodes,
        b: Nodes,
        split: usize,
        fx: &mut [f64],
        fy: &mut [f64],
        loss: &mut [f64],
    ) {
        let nx = self.lattice.nx;
        let (below_x, above_x) = fx.split_at_mut(split);
        let (below_y, above_y) = fy.split_at_mut(split);
        let below = split - nx..split;
        self.between_rows(
            lower,
            a,
            b,
            (&mut below_x[below.clone()], &mut below_y[below]),
            (&mut above_x[..nx], &mut above_y[..nx]),
            loss,
        );
    }

    /// The bonds between the last row of one block and the first row of the next, their power
    /// added to `power` pair after pair; `loss` is one block's scratch. With `fold`, both rows'
    /// background damping forces follow (their last bond is in).
    #[allow(clippy::too_many_arguments)] // the forces, the scratch, the sum and the switch
    fn between_blocks(
        &self,
        nodes: Nodes,
        fx: &mut [f64],
        fy: &mut [f64],
        loss: &mut [f64],
        power: &mut f64,
        fold: bool,
    ) {
        let nx = self.lattice.nx;
        for upper in (BLOCK_ROWS..self.lattice.ny).step_by(BLOCK_ROWS) {
            let (a, b) = (nodes.range((upper - 1) * nx..upper * nx), nodes.range(upper * nx..(upper + 1) * nx));
            self.rows_pair(upper - 1, a, b, upper * nx, fx, fy, loss);
            if fold {
                self.damp_row(nodes, upper - 1, 0, fx, fy);
                self.damp_row(nodes, upper, 0, fx, fy);
            }
            if D::ACTIVE {
                let [_, vertical, rising, falling] = family_sums(loss, a, 0.0, &mut 0.0);
                *power += (vertical + rising) + falling;
            }
        }
    }
}

/// The row of `loss` (rows of `nx`) that `family` writes.
#[inline(always)]
fn family_row(loss: &mut [f64], family: Family, nx: usize) -> &mut [f64] {
    &mut loss[family as usize * nx..(family as usize + 1) * nx]
}

/// Partial sums in [`lane_sum`]: enough independent chains to fill the vector adders (four
/// AVX2 registers, two AVX-512), so the sum runs at the adders' throughput, not their latency.
const LANES: usize = 16;

/// Σ `term(a[t], b[t])` over t, in [`LANES`] partial sums (t into lane t mod 16) folded pairwise
/// at the end: the order the adders want, not the order of t. Chunks of known length, so no
/// bounds checks stop the compiler from vectorising.
#[inline(always)]
fn lane_sum(a: &[f64], b: &[f64], term: impl Fn(f64, f64) -> f64) -> f64 {
    let mut lanes = [0.0; LANES];
    let (chunks_a, chunks_b) = (a.chunks_exact(LANES), b.chunks_exact(LANES));
    let (rest_a, rest_b) = (chunks_a.remainder(), chunks_b.remainder());
    for (ca, cb) in chunks_a.zip(chunks_b) {
        for lane in 0..LANES {
            lanes[lane] += term(ca[lane], cb[lane]);
        }
    }
    for (lane, (&x, &y)) in rest_a.iter().zip(rest_b).enumerate() {
        lanes[lane] += term(x, y);
    }
    let mut width = LANES;
    while width > 1 {
        width /= 2;
        for lane in 0..width {
            lanes[lane] += lanes[lane + width];
        }
    }
    lanes[0]
}

/// The power of each family of bonds of a row, its row of `loss` summed by [`lane_sum`], and
/// the row's background power γ_g Σ (v_x² + v_y²) added to `background` (`gamma` 0 when the
/// caller keeps it elsewhere). Only the bookkeeping of dissipated energy reads these sums; their
/// order moves `energy_error` in its last digits and nothing else (one running sum per row,
/// kept until 2026-12-04 for bit-identical bookkeeping, was a sixth of the damped step).
fn family_sums(loss: &[f64], row: Nodes, gamma: f64, background: &mut f64) -> [f64; FAMILIES] {
    let nx = row.x.len();
    let (vx, vy) = (&row.vx[..nx], &row.vy[..nx]);
    if gamma > 0.0 {
        *background += gamma * lane_sum(vx, vy, |vx, vy| vx * vx + vy * vy);
    }
    std::array::from_fn(|family| {
        let row = &loss[family * nx..(family + 1) * nx];
        lane_sum(row, row, |power, _| power)
    })
}

impl<L: ForceLaw, D: Dashpot, const CONTACT: bool> ForceField for LatticeNetwork<L, D, CONTACT> {
    const SWITCH_JUMPS: bool = CONTACT && D::ACTIVE;

    fn judge_contacts_ahead(&mut self, lookahead: f64) {
        self.spring.lookahead = lookahead;
    }

    fn uses_velocity(&self) -> bool {
        D::ACTIVE || self.background_gamma > 0.0
    }

    fn add_forces(&mut self, x: &[f64], y: &[f64], vx: &[f64], vy: &[f64], fx: &mut [f64], fy: &mut [f64]) -> f64 {
        let nx = self.lattice.nx;
        // The scratch rows are moved out while `self` is shared with the block closures.
        let (mut hx, mut hy, mut loss) = (
            std::mem::take(&mut self.scratch_x),
            std::mem::take(&mut self.scratch_y),
            std::mem::take(&mut self.scratch_loss),
        );
        let nodes = Nodes { x, y, vx, vy };
        let block_len = BLOCK_ROWS * nx;
        let this = &*self;
        let block = |(index, ((((fx, fy), hx), hy), loss)): BlockSlices, background: Option<&mut f64>| {
            this.block(index * BLOCK_ROWS, nodes, fx, fy, &mut Scratch { hx, hy, loss }, background)
        };
        // One thread visits the rows in order and can carry the background power's running sum.
        let parallel = worth_splitting(x.len());
        let mut background = 0.0;
        let mut power: f64 = if parallel {
            fx.par_chunks_mut(block_len)
                .zip(fy.par_chunks_mut(block_len))
                .zip(hx.par_chunks_mut(nx))
                .zip(hy.par_chunks_mut(nx))
                .zip(loss.par_chunks_mut(FAMILIES * nx))
                .enumerate()
                .map(|slices| block(slices, None))
                .sum()
        } else {
            fx.chunks_mut(block_len)
                .zip(fy.chunks_mut(block_len))
                .zip(hx.chunks_mut(nx))
                .zip(hy.chunks_mut(nx))
                .zip(loss.chunks_mut(FAMILIES * nx))
                .enumerate()
                .map(|slices| block(slices, Some(&mut background)))
                .sum()
        };
        // Bonds between the last row of one block and the first row of the next.
        let fold = !parallel && self.background_gamma > 0.0 && !self.lattice.periodic_x;
        self.between_blocks(nodes, fx, fy, &mut loss[..FAMILIES * nx], &mut power, fold);
        if self.lattice.periodic_x {
            power += self.wrapped(nodes, fx, fy);
        }
        if self.background_gamma > 0.0 && parallel {
            power += add_background_damping(self.background_gamma, vx, vy, fx, fy);
        } else if self.background_gamma > 0.0 {
            if !fold {
                subtract_background_damping(self.background_gamma, vx, vy, fx, fy);
            }
            power += background;
        }
        (self.scratch_x, self.scratch_y, self.scratch_loss) = (hx, hy, loss);
        power
    }

    fn bond_energy(&self, k: f64, rest: f64, dx: f64, dy: f64) -> f64 {
        self.spring.energy(k, rest, dx, dy)
    }

    fn for_each_bond(&self, visit: &mut dyn FnMut(usize, usize, f64, f64, f64)) {
        self.lattice.for_each_bond(visit);
    }
}
