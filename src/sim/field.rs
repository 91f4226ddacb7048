//! Force fields: the bond-list loop for irregular networks (every bond once,
//! f_i = `Spring::force_on_i`, f_j = −f_i) and background damping f_i = −γ_g v_i.

use rayon::prelude::*;

use super::parallel::worth_splitting;
use crate::model::{Bonds, Dashpot, ForceLaw, Spring};

/// Something that adds forces to particles: the integrators know only this.
pub trait ForceField: Send + Sync {
    /// True when forces jump where a contact switches: a damped contact, whose dashpot force
    /// γ δ̇ appears and vanishes with it at δ = 0. The time loop then splits a step at every
    /// switch. An undamped contact switches without a jump (s(0) = 0) and bonded springs never
    /// switch: for them the split is compiled away.
    const SWITCH_JUMPS: bool = false;

    /// Judges damped contacts at δ + lookahead·δ̇ (`lookahead` in s; `Spring::lookahead`) in
    /// the evaluations from now on; nothing for a field without them.
    fn judge_contacts_ahead(&mut self, _lookahead: f64) {}

    /// True when forces depend on velocities (a dashpot or background damping), so the
    /// integrators must supply predicted velocities.
    fn uses_velocity(&self) -> bool;

    /// Adds the forces at positions `(x, y)` and velocities `(vx, vy)` to `(fx, fy)` and
    /// returns the power dissipated (W). Takes `&mut self` for scratch space.
    fn add_forces(&mut self, x: &[f64], y: &[f64], vx: &[f64], vy: &[f64], fx: &mut [f64], fy: &mut [f64]) -> f64;

    /// Potential energy (J) stored at positions `(x, y)`; not on the hot path.
    fn potential_energy(&self, x: &[f64], y: &[f64]) -> f64 {
        let mut energy = 0.0;
        self.for_each_bond(&mut |i, j, rest, k, shift| {
            energy += self.bond_energy(k, rest, x[i] - x[j] + shift, y[i] - y[j])
        });
        energy
    }

    /// Energy (J) of one bond of stiffness `k` and rest length `rest` at separation `(dx, dy)`.
    fn bond_energy(&self, k: f64, rest: f64, dx: f64, dy: f64) -> f64;

    /// Calls `visit(i, j, rest, k, shift_x)` for every bond, whose separation is
    /// x_i − x_j + shift_x; for checks and the prediction of contact switches, not for forces.
    fn for_each_bond(&self, visit: &mut dyn FnMut(usize, usize, f64, f64, f64));
}

/// Background damping f_i −= γ_g v_i on every particle; returns its power γ_g Σ v² (W), one
/// running sum over the particles in order.
pub fn add_background_damping(gamma: f64, vx: &[f64], vy: &[f64], fx: &mut [f64], fy: &mut [f64]) -> f64 {
    subtract_background_damping(gamma, vx, vy, fx, fy);
    let n = fx.len();
    (0..n).fold(0.0, |power, i| power + gamma * (vx[i] * vx[i] + vy[i] * vy[i]))
}

/// The forces of background damping alone, f_i −= γ_g v_i, for a caller that sums their power
/// itself: a loop without a running sum vectorises.
pub fn subtract_background_damping(gamma: f64, vx: &[f64], vy: &[f64], fx: &mut [f64], fy: &mut [f64]) {
    let n = fx.len();
    let (vx, vy, fy) = (&vx[..n], &vy[..n], &mut fy[..n]);
    for i in 0..n {
        fx[i] -= gamma * vx[i];
        fy[i] -= gamma * vy[i];
    }
}

/// Particles per block of a bond-list network: bonds with both ends in one block are
/// summed by that block's thread; the few that cross blocks are summed afterwards.
const BLOCK_PARTICLES: usize = 8192;

/// An irregular network of identical-law springs over a sorted bond list, with optional
/// background damping.
#[derive(Clone, Debug)]
pub struct BondNetwork<L, D, const CONTACT: bool> {
    spring: Spring<L, D, CONTACT>,
    /// Bonds inside each block of [`BLOCK_PARTICLES`] particles.
    blocks: Vec<Bonds>,
    /// Bonds between blocks.
    crossing: Bonds,
    /// Bonds that wrap across a periodic side (their separation carries a shift).
    wrapped: Bonds,
    background_gamma: f64,
}

impl<L: ForceLaw, D: Dashpot, const CONTACT: bool> BondNetwork<L, D, CONTACT> {
    /// A network of `particles` particles over `bonds` (any order: they are sorted here) with
    /// background damping `background_gamma` (N s/m, 0 for none).
    pub fn new(spring: Spring<L, D, CONTACT>, bonds: &Bonds, particles: usize, background_gamma: f64) -> Self {
        assert!(bonds.particles_needed() <= particles, "a bond names a particle that does not exist");
        let sorted = bonds.sorted();
        let block_count = particles.div_ceil(BLOCK_PARTICLES).max(1);
        let mut blocks = vec![Bonds::default(); block_count];
        let (mut crossing, mut wrapped) = (Bonds::default(), Bonds::default());
        for b in 0..sorted.len() {
            let (i, j) = (sorted.i[b], sorted.j[b]);
            let target = if sorted.shift_x[b] != 0.0 {
                &mut wrapped
            } else if i / BLOCK_PARTICLES == j / BLOCK_PARTICLES {
                &mut blocks[i / BLOCK_PARTICLES]
            } else {
                &mut crossing
            };
            sorted.copy_to(b, target);
        }
        BondNetwork { spring, blocks, crossing, wrapped, background_gamma }
    }

    /// Adds the forces of `bonds` to `(fx, fy)`, which hold particles `offset..`; `SHIFTED`
    /// bonds add their periodic shift to the x separation.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)] // the structure of arrays, one slice per component
    fn accumulate<const SHIFTED: bool>(
        &self,
        bonds: &Bonds,
        offset: usize,
        x: &[f64],
        y: &[f64],
        vx: &[f64],
        vy: &[f64],
        fx: &mut [f64],
        fy: &mut [f64],
    ) -> f64 {
        let mut power = 0.0;
        let m = bonds.len();
        let (bi, bj, rest, stiffness) = (&bonds.i[..m], &bonds.j[..m], &bonds.rest[..m], &bonds.stiffness[..m]);
        for b in 0..m {
            let (i, j) = (bi[b], bj[b]);
            let (dvx, dvy) = if D::ACTIVE { (vx[i] - vx[j], vy[i] - vy[j]) } else { (0.0, 0.0) };
            let dx = if SHIFTED { x[i] - x[j] + bonds.shift_x[b] } else { x[i] - x[j] };
            let f = self.spring.force_on_i(stiffness[b], rest[b], dx, y[i] - y[j], dvx, dvy);
            fx[i - offset] += f.fx;
            fy[i - offset] += f.fy;
            fx[j - offset] -= f.fx;
            fy[j - offset] -= f.fy;
            power += f.dissipation;
        }
        power
    }
}

impl<L: ForceLaw, D: Dashpot, const CONTACT: bool> ForceField for BondNetwork<L, D, CONTACT> {
    const SWITCH_JUMPS: bool = CONTACT && D::ACTIVE;

    fn judge_contacts_ahead(&mut self, lookahead: f64) {
        self.spring.lookahead = lookahead;
    }

    fn uses_velocity(&self) -> bool {
        D::ACTIVE || self.background_gamma > 0.0
    }

    fn add_forces(&mut self, x: &[f64], y: &[f64], vx: &[f64], vy: &[f64], fx: &mut [f64], fy: &mut [f64]) -> f64 {
        let this = &*self;
        let block = |(index, (fx, fy)): (usize, (&mut [f64], &mut [f64]))| {
            this.accumulate::<false>(&this.blocks[index], index * BLOCK_PARTICLES, x, y, vx, vy, fx, fy)
        };
        let mut power: f64 = if worth_splitting(x.len()) {
            fx.par_chunks_mut(BLOCK_PARTICLES).zip(fy.par_chunks_mut(BLOCK_PARTICLES)).enumerate().map(block).sum()
        } else {
            fx.chunks_mut(BLOCK_PARTICLES).zip(fy.chunks_mut(BLOCK_PARTICLES)).enumerate().map(block).sum()
        };
        power += self.accumulate::<false>(&self.crossing, 0, x, y, vx, vy, fx, fy);
        power += self.accumulate::<true>(&self.wrapped, 0, x, y, vx, vy, fx, fy);
        if self.background_gamma > 0.0 {
            power += add_background_damping(self.background_gamma, vx, vy, fx, fy);
        }
        power
    }

    fn bond_energy(&self, k: f64, rest: f64, dx: f64, dy: f64) -> f64 {
        self.spring.energy(k, rest, dx, dy)
    }

    fn for_each_bond(&self, visit: &mut dyn FnMut(usize, usize, f64, f64, f64)) {
        for bonds in self.blocks.iter().chain([&self.crossing, &self.wrapped]) {
            bonds.for_each(&mut *visit);
        }
    }
}
