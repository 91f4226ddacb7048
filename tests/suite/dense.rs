//! An independent static answer of a loaded lattice for the tests: the run's own scene (bond
//! list, supports, loads) assembled into a dense tangent stiffness matrix and solved by
//! Newton–Raphson with a Cholesky factorisation that skips zero pivots, written here and not
//! taken from `fem.rs`. The moduli come from the loads' own sum, not from the spec's total.

use mdsolids::model::LawSpec;
use mdsolids::spec::{LoadCase, RunSpec};
use mdsolids::study::{Metrics, build_scene};

/// A spring (i, j, rest length (m), stiffness, x shift across a periodic side (m)).
type Spring = (usize, usize, f64, f64, f64);

/// The static problem of a scene.
struct Problem {
    x: Vec<f64>,
    y: Vec<f64>,
    springs: Vec<Spring>,
    /// Row of each degree of freedom (2i: x of node i, 2i + 1: y) in the free system, if free.
    free: Vec<Option<usize>>,
    /// The loads on the free degrees of freedom (N), at load factor 1.
    force: Vec<f64>,
    /// The loads' sum (N, x and y), at load factor 1.
    total: (f64, f64),
    law: LawSpec,
}

/// The dense answer of a loaded lattice.
pub struct Reference {
    /// E (tension) or G (shear) (Pa).
    pub modulus: f64,
    /// ν (tension), `None` in shear.
    pub poisson: Option<f64>,
    /// The modulus of the increment from load factor 1 to 1 + step (Pa).
    pub secant: Option<f64>,
    /// The tangent modulus d(load)/d(ΔL) at the answer (Pa).
    pub tangent: Option<f64>,
    /// Zero pivots of the tangent stiffness at the answer: floppy modes the load leaves alone.
    pub zero_pivots: usize,
    /// The smallest non-zero pivot² of the tangent stiffness at the answer over its largest
    /// diagonal entry: about 1/condition number.
    pub conditioning: f64,
}

impl Reference {
    /// The answer of `spec`'s scene; `None` when the load drives a mechanism.
    pub fn of(spec: &RunSpec, step: f64) -> Option<Reference> {
        let problem = Problem::of(spec);
        let (u, zero_pivots, conditioning) = problem.solve(1.0)?;
        let (modulus, poisson) = moduli(spec, &problem, 1.0, &u);
        let secant = problem.solve(1.0 + step).map(|(next, _, _)| {
            let increment: Vec<f64> = next.iter().zip(&u).map(|(b, a)| b - a).collect();
            moduli(spec, &problem, step, &increment).0
        });
        let (stiffness, _) = problem.assemble(&u, 1.0);
        let tangent = cholesky_solve(stiffness, problem.force.clone())
            .filter(|(_, zeros, _)| *zeros == 0)
            .map(|(du, _, _)| moduli(spec, &problem, 1.0, &problem.expand(&du)).0);
        Some(Reference { modulus, poisson, secant, tangent, zero_pivots, conditioning })
    }

    /// Whether the run's static answer (`*_fem`) agrees with this one to `agreement`: E or G
    /// always, ν and the tangent modulus where the stiffness is regular and conditioned to 1e6
    /// (a floppy mode leaves them to the regularisation; a nearly floppy one, a Hertz spring at
    /// δ ≈ 0 with no stiffness, to round-off times the condition number: 5e-9 of ν on a
    /// kagome block pulled along its rows).
    pub fn agrees_statically(&self, spec: &RunSpec, m: &Metrics, agreement: f64) -> Result<(), String> {
        let l = &m.lattice;
        let shear = spec.lattice().unwrap().load_case == LoadCase::Shear;
        let (fem, tangent) = if shear {
            (l.shear_modulus_fem, l.shear_modulus_tangent_fem)
        } else {
            (l.youngs_modulus_fem, l.youngs_modulus_tangent_fem)
        };
        let fem = fem.ok_or("no static modulus")?;
        let relative = |a: f64, b: f64| (a / b - 1.0).abs();
        if relative(fem, self.modulus) > agreement {
            return Err(format!("static modulus {fem} against the dense {}", self.modulus));
        }
        if self.zero_pivots > 0 || self.conditioning < 1e-6 {
            return Ok(());
        }
        // A Hertz spring near δ = 0 has s′ ∝ δ^(1/2) → 0 and s″ → ∞: Newton converges only
        // linearly there, and both answers stop about 1e-8 apart in ν (kagome pulled along x).
        let agreement = if spec.law.is_linear() { agreement } else { agreement.max(1e-7) };
        if let (Some(fem), Some(dense)) = (l.poisson_ratio_fem.filter(|_| !shear), self.poisson)
            && (fem - dense).abs() > agreement
        {
            return Err(format!("static ν {fem} against the dense {dense}"));
        }
        match (tangent, self.tangent) {
            (Some(fem), Some(dense)) if relative(fem, dense) > agreement => {
                Err(format!("static tangent modulus {fem} against the dense {dense}"))
            }
            _ => Ok(()),
        }
    }
}

/// E and ν (tension) or G (shear) from displacements `u` (dof 2i: x of node i) under the loads
/// times `factor`: E = (ΣF_y/d/L_x)/(ΔL_y/L_y), ν = −(ΔL_x/L_x)/(ΔL_y/L_y), G = (ΣF_x/d/L_x)/(ΔL_x,top/L_y),
/// ΔL the difference of the mean displacements of the opposite edges.
fn moduli(spec: &RunSpec, problem: &Problem, factor: f64, u: &[f64]) -> (f64, Option<f64>) {
    let l = spec.lattice().unwrap();
    let e = l.layout(spec.spacing).edges;
    let mean = |nodes: &[usize], axis: usize| nodes.iter().map(|&n| u[2 * n + axis]).sum::<f64>() / nodes.len() as f64;
    let (fx, fy) = problem.total;
    if l.load_case == LoadCase::Shear {
        let strain = (mean(&e.top, 0) - mean(&e.bottom, 0)) / e.height;
        return (factor * fx / l.depth / e.width / strain, None);
    }
    let strain = (mean(&e.top, 1) - mean(&e.bottom, 1)) / e.height;
    let lateral = (mean(&e.right, 0) - mean(&e.left, 0)) / e.width;
    (factor * fy / l.depth / e.width / strain, Some(-lateral / strain))
}

impl Problem {
    fn of(spec: &RunSpec) -> Problem {
        let scene = build_scene(spec);
        let p = &scene.particles;
        let mut springs = Vec::new();
        scene.network.for_each_bond(&scene.particles.x, &scene.particles.y, |i, j, rest, k, shift| {
            springs.push((i, j, rest, k, shift))
        });
        let mut free = vec![None; 2 * p.len()];
        let mut rows = 0;
        for (dof, slot) in free.iter_mut().enumerate() {
            let held = if dof % 2 == 0 { &p.held_x } else { &p.held_y };
            if !held.contains(&(dof / 2)) {
                *slot = Some(rows);
                rows += 1;
            }
        }
        let mut force = vec![0.0; rows];
        for load in &scene.loads {
            for (dof, value) in [(2 * load.particle, load.fx), (2 * load.particle + 1, load.fy)] {
                if let Some(row) = free[dof] {
                    force[row] += value;
                }
            }
        }
        let total = scene.loads.iter().fold((0.0, 0.0), |(x, y), load| (x + load.fx, y + load.fy));
        Problem { x: p.x.clone(), y: p.y.clone(), springs, free, force, total, law: spec.law }
    }

    /// Tension s(δ) and its derivative s′(δ) of a spring of stiffness k.
    fn law(&self, k: f64, delta: f64) -> (f64, f64) {
        match self.law {
            LawSpec::Linear => (k * delta, k),
            LawSpec::Power { beta } => {
                (k * delta.abs().powf(beta) * delta.signum(), beta * k * delta.abs().powf(beta - 1.0))
            }
        }
    }

    /// Displacements of every dof from the free ones (held ones stay at 0).
    fn expand(&self, free: &[f64]) -> Vec<f64> {
        self.free.iter().map(|row| row.map_or(0.0, |r| free[r])).collect()
    }

    /// The tangent stiffness (dense, row-major over the free dofs) and the out-of-balance force
    /// loads × `factor` + spring forces at displacements `u` (every dof).
    fn assemble(&self, u: &[f64], factor: f64) -> (Vec<f64>, Vec<f64>) {
        let n = self.force.len();
        let mut stiffness = vec![0.0; n * n];
        let mut residual: Vec<f64> = self.force.iter().map(|f| factor * f).collect();
        for &(i, j, rest, k, shift) in &self.springs {
            let d = [
                self.x[i] + u[2 * i] - self.x[j] - u[2 * j] + shift,
                self.y[i] + u[2 * i + 1] - self.y[j] - u[2 * j + 1],
            ];
            let r = d[0].hypot(d[1]);
            let e = [d[0] / r, d[1] / r];
            let (s, ds) = self.law(k, r - rest);
            for (a, sign_a) in [(i, 1.0), (j, -1.0)] {
                for p in 0..2 {
                    let Some(row) = self.free[2 * a + p] else { continue };
                    residual[row] -= sign_a * s * e[p];
                    for (b, sign_b) in [(i, 1.0), (j, -1.0)] {
                        for q in 0..2 {
                            if let Some(column) = self.free[2 * b + q] {
                                let identity = if p == q { 1.0 } else { 0.0 };
                                let block = ds * e[p] * e[q] + s / r * (identity - e[p] * e[q]);
                                stiffness[row * n + column] += sign_a * sign_b * block;
                            }
                        }
                    }
                }
            }
        }
        (stiffness, residual)
    }

    /// Newton–Raphson to ‖R‖ ≤ 1e-12 ‖f‖ (or a step of 1e-14 of ‖u‖: round-off) under the loads × `factor`, from the answer of the
    /// springs linearised at the extension one node's load gives them (a power law has no
    /// stiffness at δ = 0); halves a step that raises ‖R‖. `None` when the load drives a
    /// mechanism or Newton does not converge. Returns every dof's displacement and the zero
    /// pivots of the tangent stiffness at the answer.
    fn solve(&self, factor: f64) -> Option<(Vec<f64>, usize, f64)> {
        let mut u = self.start(factor)?;
        let target = 1e-12 * norm(&self.force) * factor;
        let mut polish = 0;
        for _ in 0..60 {
            let (stiffness, residual) = self.assemble(&u, factor);
            let size = norm(&residual);
            let (step, zeros, conditioning) = cholesky_solve(stiffness, residual)?;
            let step = self.expand(&step);
            // Converged, and two more steps taken to reach round-off (a near-singular tangent
            // converges slowly: a residual of 1e-12 of the load can still hold 1e-8 of ν).
            if size <= target || norm(&step) <= 1e-14 * norm(&u) {
                polish += 1;
                if polish > 2 {
                    return Some((u, zeros, conditioning));
                }
            }
            let mut scale = 1.0;
            let mut next: Vec<f64> = u.iter().zip(&step).map(|(a, b)| a + b).collect();
            while norm(&self.assemble(&next, factor).1) > size && scale > 1e-3 {
                scale /= 2.0;
                next = u.iter().zip(&step).map(|(a, b)| a + scale * b).collect();
            }
            u = next;
        }
        None
    }

    /// The linear answer of the springs at their tangent stiffness at δ = (F/k)^(1/β).
    fn start(&self, factor: f64) -> Option<Vec<f64>> {
        let largest = self.force.iter().fold(0.0f64, |m, f| m.max(f.abs())) * factor;
        let linearised = Problem {
            springs: self
                .springs
                .iter()
                .map(|&(i, j, rest, k, shift)| {
                    let delta = match self.law {
                        LawSpec::Linear => 0.0,
                        LawSpec::Power { beta } => (largest / k).powf(1.0 / beta),
                    };
                    (i, j, rest, self.law(k, delta).1, shift)
                })
                .collect(),
            law: LawSpec::Linear,
            x: self.x.clone(),
            y: self.y.clone(),
            free: self.free.clone(),
            force: self.force.clone(),
            total: self.total,
        };
        let zero = vec![0.0; self.free.len()];
        let (stiffness, _) = linearised.assemble(&zero, factor);
        let load: Vec<f64> = self.force.iter().map(|f| factor * f).collect();
        let (u, _, _) = cholesky_solve(stiffness, load)?;
        Some(self.expand(&u))
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Solves K u = b for a symmetric positive semi-definite K (dense, row-major, n × n) by
/// Cholesky, a pivot below 1e-10 of the largest diagonal entry taken as a zero-energy mode
/// (its unknown set to 0); `None` when the answer leaves ‖K u − b‖ > 1e-6 ‖b‖ (b drives a
/// mechanism). Returns u, the number of zero pivots and the smallest other pivot² over the
/// largest diagonal entry.
fn cholesky_solve(k: Vec<f64>, b: Vec<f64>) -> Option<(Vec<f64>, usize, f64)> {
    let n = b.len();
    let scale = (0..n).map(|i| k[i * n + i]).fold(0.0f64, f64::max);
    let mut l = vec![0.0; n * n];
    let mut zero = vec![false; n];
    let mut smallest = f64::INFINITY;
    for j in 0..n {
        let d = k[j * n + j] - (0..j).map(|p| l[j * n + p] * l[j * n + p]).sum::<f64>();
        if d <= 1e-10 * scale {
            zero[j] = true;
            continue;
        }
        smallest = smallest.min(d / scale);
        l[j * n + j] = d.sqrt();
        for i in j + 1..n {
            let sum = k[i * n + j] - (0..j).map(|p| l[i * n + p] * l[j * n + p]).sum::<f64>();
            l[i * n + j] = sum / l[j * n + j];
        }
    }
    let mut y = vec![0.0; n];
    for i in 0..n {
        if !zero[i] {
            y[i] = (b[i] - (0..i).map(|p| l[i * n + p] * y[p]).sum::<f64>()) / l[i * n + i];
        }
    }
    let mut u = vec![0.0; n];
    for i in (0..n).rev() {
        if !zero[i] {
            u[i] = (y[i] - (i + 1..n).map(|p| l[p * n + i] * u[p]).sum::<f64>()) / l[i * n + i];
        }
    }
    let residual: Vec<f64> = (0..n).map(|i| (0..n).map(|j| k[i * n + j] * u[j]).sum::<f64>() - b[i]).collect();
    (norm(&residual) <= 1e-6 * norm(&b)).then_some((u, zero.iter().filter(|z| **z).count(), smallest))
}

/// The bounds on E of the spread network of `spread` from the linear answer of `uniform`, the
/// same lattice with every spring at its stiffness before the spread, solved densely here:
/// with e_b the uniform answer's bond extensions, E0 its modulus, E0 Σ k0 e² / Σ (k0 e)²/k
/// (Reuss) and E0 Σ k e² / Σ k0 e² (Voigt), each spread bond found by its two nodes.
pub fn spread_bounds(spread: &RunSpec, uniform: &RunSpec) -> (f64, f64) {
    let problem = Problem::of(uniform);
    let (stiffness, force) = problem.assemble(&vec![0.0; 2 * problem.x.len()], 1.0);
    let (free, zeros, _) = cholesky_solve(stiffness, force).expect("a rigid uniform network");
    assert_eq!(zeros, 0);
    let u = problem.expand(&free);
    let (modulus, _) = moduli(uniform, &problem, 1.0, &u);
    let spread_k: std::collections::HashMap<(usize, usize), f64> =
        Problem::of(spread).springs.iter().map(|&(i, j, _, k, _)| ((i.min(j), i.max(j)), k)).collect();
    let (mut energy, mut stiffened, mut softened) = (0.0, 0.0, 0.0);
    for &(i, j, _, k0, shift) in &problem.springs {
        let d = [problem.x[i] - problem.x[j] + shift, problem.y[i] - problem.y[j]];
        let e = ((u[2 * i] - u[2 * j]) * d[0] + (u[2 * i + 1] - u[2 * j + 1]) * d[1]) / d[0].hypot(d[1]);
        let k = spread_k[&(i.min(j), i.max(j))];
        energy += k0 * e * e;
        stiffened += k * e * e;
        softened += k0 * k0 * e * e / k;
    }
    (modulus * energy / softened, modulus * stiffened / energy)
}
