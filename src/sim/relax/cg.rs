//! Non-linear conjugate gradients on Π(x) = U(x) − Σ F·(x − x₀), Polak–Ribière+
//! (β = max(0, r·(r − r_prev)/(r_prev·r_prev)), r = −∇Π the static force), as LAMMPS's
//! `min_style cg`. The line search along d finds a zero of φ′(α) = −r(x + α d)·d by secant
//! steps from the trial step of the previous line: exact in one secant step where Π is
//! quadratic along the line (linear springs, small rotations), so an iteration costs two force
//! evaluations there; a power law's takes a few more.

use super::{Gradient, Minimiser, dot, largest};
use crate::sim::field::ForceField;
use crate::sim::state::State;

/// The line search ends when |φ′(α)| ≤ this fraction of |φ′(0)| (the strong Wolfe curvature
/// condition; 0.1 is the usual choice for CG) ...
const CURVATURE: f64 = 0.1;
/// ... or after this many evaluations on the line.
const LINE_EVALUATIONS: u64 = 10;
/// No step moves a particle farther than this fraction of the shortest bond (LAMMPS's `dmax`
/// 0.1 in lattice units): a line search stays inside the region where its secant model holds.
const MAX_MOVE: f64 = 0.1;
/// The first trial step moves the particle farthest along d by this fraction of the shortest
/// bond; later ones start from the previous line's step.
const FIRST_TRIAL: f64 = 1e-6;

/// CG's state between iterations: the search direction, the previous force and step.
pub(super) struct ConjugateGradients {
    dx: Vec<f64>,
    dy: Vec<f64>,
    previous_x: Vec<f64>,
    previous_y: Vec<f64>,
    /// Positions at the start of the line.
    line_x: Vec<f64>,
    line_y: Vec<f64>,
    /// The previous line's accepted step (s/m of d's units), the next trial; 0 at the start.
    step: f64,
    /// The shortest bond (m), for the step limits.
    shortest_bond: f64,
}

impl ConjugateGradients {
    /// Conjugate gradients on `field`'s network (its bonds set the step limits).
    pub(super) fn new<F: ForceField>(field: &F) -> ConjugateGradients {
        let mut shortest_bond = f64::INFINITY;
        field.for_each_bond(&mut |_, _, rest, _, _| shortest_bond = shortest_bond.min(rest));
        ConjugateGradients {
            dx: Vec::new(),
            dy: Vec::new(),
            previous_x: Vec::new(),
            previous_y: Vec::new(),
            line_x: Vec::new(),
            line_y: Vec::new(),
            step: 0.0,
            shortest_bond: if shortest_bond.is_finite() { shortest_bond } else { 1.0 },
        }
    }

    /// The new direction d = r + β d with Polak–Ribière+ β, restarted along r when that is no
    /// descent direction (r·d ≤ 0).
    fn update_direction(&mut self, force: &Gradient) {
        if self.dx.len() != force.fx.len() {
            self.dx.clone_from(&force.fx);
            self.dy.clone_from(&force.fy);
        } else {
            let previous = dot(&self.previous_x, &self.previous_y, &self.previous_x, &self.previous_y);
            let overlap = dot(&force.fx, &force.fy, &self.previous_x, &self.previous_y);
            let now = dot(&force.fx, &force.fy, &force.fx, &force.fy);
            let beta = if previous > 0.0 { ((now - overlap) / previous).max(0.0) } else { 0.0 };
            for i in 0..self.dx.len() {
                self.dx[i] = force.fx[i] + beta * self.dx[i];
                self.dy[i] = force.fy[i] + beta * self.dy[i];
            }
            if dot(&force.fx, &force.fy, &self.dx, &self.dy) <= 0.0 {
                self.dx.clone_from(&force.fx);
                self.dy.clone_from(&force.fy);
            }
        }
        self.previous_x.clone_from(&force.fx);
        self.previous_y.clone_from(&force.fy);
    }

    /// Puts the particles at the line's start plus `alpha` d.
    fn move_to(&self, state: &mut State, alpha: f64) {
        let p = &mut state.particles;
        for i in 0..p.len() {
            p.x[i] = self.line_x[i] + alpha * self.dx[i];
            p.y[i] = self.line_y[i] + alpha * self.dy[i];
        }
    }
}

impl Minimiser for ConjugateGradients {
    fn iterate<F: ForceField>(
        &mut self,
        state: &mut State,
        field: &mut F,
        force: &mut Gradient,
    ) -> Result<u64, String> {
        self.update_direction(force);
        let slope_0 = -dot(&force.fx, &force.fy, &self.dx, &self.dy);
        let longest = largest(&self.dx, &self.dy);
        if longest == 0.0 {
            return Err("CG found a zero search direction".into());
        }
        let most = MAX_MOVE * self.shortest_bond / longest;
        let trial = if self.step > 0.0 { self.step } else { FIRST_TRIAL * self.shortest_bond / longest };
        self.line_x.clone_from(&state.particles.x);
        self.line_y.clone_from(&state.particles.y);
        // Secant on φ′ from (0, φ′(0)) and (α, φ′(α)); where φ′ does not grow (no curvature
        // seen yet), the step doubles.
        let (mut alpha_last, mut slope_last) = (0.0, slope_0);
        let mut alpha = trial.min(most);
        let mut evaluations = 0;
        loop {
            self.move_to(state, alpha);
            force.evaluate(state, field);
            evaluations += 1;
            let slope = -dot(&force.fx, &force.fy, &self.dx, &self.dy);
            if slope.abs() <= CURVATURE * slope_0.abs() || evaluations == LINE_EVALUATIONS {
                self.step = alpha;
                return Ok(evaluations);
            }
            let next = if slope > slope_last {
                alpha - slope * (alpha - alpha_last) / (slope - slope_last)
            } else {
                2.0 * alpha
            };
            (alpha_last, slope_last) = (alpha, slope);
            alpha = if next > 0.0 { next.min(most) } else { 0.5 * alpha };
        }
    }
}
