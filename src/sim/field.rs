//! The force loop: every bond once, f_i = `Spring::force_on_i`, f_j = −f_i, plus background
//! damping f_i = −γ_g v_i.

use crate::model::{Bonds, Dashpot, ForceLaw, Spring};

/// Something that adds forces to particles: the integrators know only this.
pub trait ForceField: Sync {
    /// True when forces depend on velocities (a dashpot or background damping), so the
    /// integrators must supply predicted velocities.
    fn uses_velocity(&self) -> bool;

    /// Adds the forces at positions `(x, y)` and velocities `(vx, vy)` to `(fx, fy)` and
    /// returns the power dissipated (W).
    fn add_forces(&self, x: &[f64], y: &[f64], vx: &[f64], vy: &[f64], fx: &mut [f64], fy: &mut [f64]) -> f64;

    /// Potential energy (J) stored at positions `(x, y)`.
    fn potential_energy(&self, x: &[f64], y: &[f64]) -> f64;
}

/// A network of identical-law springs over a bond list, with optional background damping.
#[derive(Clone, Debug)]
pub struct BondNetwork<L, D, const CONTACT: bool> {
    /// The law every bond obeys (stiffness per bond lives in `bonds`).
    pub spring: Spring<L, D, CONTACT>,
    /// Connectivity, rest lengths and stiffness constants.
    pub bonds: Bonds,
    /// Background damping γ_g (N s/m) against the particle velocity; 0 for none.
    pub background_gamma: f64,
}

impl<L: ForceLaw, D: Dashpot, const CONTACT: bool> ForceField for BondNetwork<L, D, CONTACT> {
    fn uses_velocity(&self) -> bool {
        D::ACTIVE || self.background_gamma > 0.0
    }

    fn add_forces(&self, x: &[f64], y: &[f64], vx: &[f64], vy: &[f64], fx: &mut [f64], fy: &mut [f64]) -> f64 {
        let b = &self.bonds;
        let mut power = 0.0;
        for n in 0..b.len() {
            let (i, j) = (b.i[n], b.j[n]);
            let (dvx, dvy) = if D::ACTIVE { (vx[i] - vx[j], vy[i] - vy[j]) } else { (0.0, 0.0) };
            let f = self.spring.force_on_i(b.stiffness[n], b.rest[n], x[i] - x[j], y[i] - y[j], dvx, dvy);
            fx[i] += f.fx;
            fy[i] += f.fy;
            fx[j] -= f.fx;
            fy[j] -= f.fy;
            power += f.dissipation;
        }
        let g = self.background_gamma;
        if g > 0.0 {
            for i in 0..fx.len() {
                fx[i] -= g * vx[i];
                fy[i] -= g * vy[i];
                power += g * (vx[i] * vx[i] + vy[i] * vy[i]);
            }
        }
        power
    }

    fn potential_energy(&self, x: &[f64], y: &[f64]) -> f64 {
        let b = &self.bonds;
        (0..b.len())
            .map(|n| {
                let (i, j) = (b.i[n], b.j[n]);
                self.spring.energy(b.stiffness[n], b.rest[n], x[i] - x[j], y[i] - y[j])
            })
            .sum()
    }
}
