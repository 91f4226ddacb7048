//! The force law of a spring: one function, [`Spring::force_on_i`], serves every bond.
//!
//! Sign conventions (DESIGN.md): n̂ = (x_i − x_j)/|x_i − x_j|, δ = |x_i − x_j| − x_e
//! (extension positive), δ̇ = n̂ · (v_i − v_j), and the force on i is
//! f_i = −(s(δ) + γ δ̇) n̂ with f_j = −f_i.
//!
//! The law, the dashpot and the contact switch are type parameters, so a run picks them once and
//! the compiler builds a bond loop without the parts the scene does not use (no `powf` for
//! linear springs, no velocity reads when γ = 0).

/// Elastic part s(δ) of a spring, with its stored energy e(δ), s = de/dδ.
pub trait ForceLaw: Copy + Send + Sync + 'static {
    /// Elastic force s(δ) (N) at extension `delta` (m) for stiffness constant `k`;
    /// positive in tension, so f_i = −s n̂ pulls i towards j.
    fn elastic_force(&self, k: f64, delta: f64) -> f64;
    /// Stored energy e(δ) (J), zero at δ = 0.
    fn energy(&self, k: f64, delta: f64) -> f64;
    /// Tangent stiffness ds/dδ (N/m), for static solvers and stability estimates.
    fn tangent_stiffness(&self, k: f64, delta: f64) -> f64;
}

/// Linear spring s = k δ, e = k δ²/2.
///
/// ```
/// use mdsolids::model::{ForceLaw, Linear};
/// assert_eq!(Linear.elastic_force(2.0, 0.5), 1.0);
/// assert_eq!(Linear.energy(2.0, 0.5), 0.25);
/// assert_eq!(Linear.tangent_stiffness(2.0, 0.5), 2.0);
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Linear;

impl ForceLaw for Linear {
    #[inline(always)]
    fn elastic_force(&self, k: f64, delta: f64) -> f64 {
        k * delta
    }
    #[inline(always)]
    fn energy(&self, k: f64, delta: f64) -> f64 {
        0.5 * k * delta * delta
    }
    fn tangent_stiffness(&self, k: f64, _delta: f64) -> f64 {
        k
    }
}

/// Power-law spring s = C |δ|^β sign δ, e = C |δ|^(β+1)/(β+1); Hertz is β = 3/2.
///
/// ```
/// use mdsolids::model::{ForceLaw, PowerLaw};
/// let hertz = PowerLaw { beta: 1.5 };
/// assert!((hertz.elastic_force(1.0, -0.04) + 0.008).abs() < 1e-15); // −0.04^1.5
/// assert!((hertz.energy(1.0, 0.04) - 0.04f64.powf(2.5) / 2.5).abs() < 1e-15);
/// assert!((hertz.tangent_stiffness(1.0, -0.04) - 1.5 * 0.2).abs() < 1e-15); // 1.5 · 0.04^0.5
/// ```
#[derive(Clone, Copy, Debug)]
pub struct PowerLaw {
    /// Exponent β (1 is linear, 3/2 is Hertz).
    pub beta: f64,
}

/// |δ|^e for `magnitude` = |δ| ≥ 0. Hertz's exponents (e = 1/2, 3/2, 5/2 for the tangent
/// stiffness, the force and the energy) through a square root: one vector instruction where
/// `powf` is a library call (~20 ns), and as accurate (√ is correctly rounded, so the result is
/// within 1–2 ulp, as `powf`'s). The test on e is the same for every bond of a run, so the
/// branch is always predicted.
#[inline(always)]
fn power(magnitude: f64, exponent: f64) -> f64 {
    if exponent == 1.5 {
        magnitude * magnitude.sqrt()
    } else if exponent == 0.5 {
        magnitude.sqrt()
    } else if exponent == 2.5 {
        magnitude * magnitude * magnitude.sqrt()
    } else {
        other_power(magnitude, exponent)
    }
}

/// |δ|^e for the other exponents, kept out of line. Inlined, `powf` is a call the compiler
/// may evaluate ahead of the branch: in the vectorised bond loops it ran for every bond beside
/// the square root, the result thrown away (`pow(0, 1.5)`, 14 % of the pinned coursework
/// test's CPU). Out of line, its call is one the compiler cannot speculate.
#[inline(never)]
fn other_power(magnitude: f64, exponent: f64) -> f64 {
    magnitude.powf(exponent)
}

impl ForceLaw for PowerLaw {
    #[inline(always)]
    fn elastic_force(&self, k: f64, delta: f64) -> f64 {
        k * power(delta.abs(), self.beta).copysign(delta)
    }
    #[inline(always)]
    fn energy(&self, k: f64, delta: f64) -> f64 {
        k * power(delta.abs(), self.beta + 1.0) / (self.beta + 1.0)
    }
    /// β C |δ|^(β−1): zero at δ = 0 for β > 1 (an unloaded Hertz contact has no stiffness).
    fn tangent_stiffness(&self, k: f64, delta: f64) -> f64 {
        self.beta * k * power(delta.abs(), self.beta - 1.0)
    }
}

/// Dissipative part of a bond: a force γ δ̇ (N) along n̂ on the relative normal velocity.
pub trait Dashpot: Copy + Send + Sync + 'static {
    /// False for the undamped bond: the loop then never reads velocities.
    const ACTIVE: bool;
    /// Dashpot force γ δ̇ (N) for normal rate `rate` = δ̇ (m/s).
    fn force(&self, rate: f64) -> f64;
}

/// No bond damping (γ = 0).
#[derive(Clone, Copy, Debug, Default)]
pub struct NoDashpot;

impl Dashpot for NoDashpot {
    const ACTIVE: bool = false;
    #[inline(always)]
    fn force(&self, _rate: f64) -> f64 {
        0.0
    }
}

/// Linear dashpot with coefficient γ (N s/m).
#[derive(Clone, Copy, Debug)]
pub struct BondDashpot {
    /// γ (N s/m).
    pub gamma: f64,
}

impl Dashpot for BondDashpot {
    const ACTIVE: bool = true;
    #[inline(always)]
    fn force(&self, rate: f64) -> f64 {
        self.gamma * rate
    }
}

/// Force on i from j and the power the dashpot takes out of the pair.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BondForce {
    /// x component of f_i (N); f_j = −f_i.
    pub fx: f64,
    /// y component of f_i (N).
    pub fy: f64,
    /// Dissipated power γ δ̇² (W), ≥ 0.
    pub dissipation: f64,
}

/// A spring: force law `L`, dashpot `D`, and `CONTACT` = acts only in compression (δ < 0).
///
/// A damped contact's force jumps by γ δ̇ where it switches (δ = 0); the time loop splits a
/// step there and, at the switch, asks for the force of either side through `lookahead`.
///
/// The contact force is not clamped to stay repulsive: near the end of a damped contact the
/// dashpot pulls (s + γ δ̇ < 0). Clamping it would change the restitution of r = 0.5 into
/// 0.550 (`theory::clamped_restitution`), so the law is kept as the coursework writes it.
#[derive(Clone, Copy, Debug)]
pub struct Spring<L, D, const CONTACT: bool> {
    /// Elastic law.
    pub law: L,
    /// Bond dashpot.
    pub dashpot: D,
    /// When a damped contact is judged (s from now): it acts while δ + lookahead·δ̇ < 0, its
    /// extension that much later (linearly). 0 but at a contact switch, where δ ≈ 0: there the
    /// force of the sub-step of length h that ends at the switch is asked for with −h/2, that of
    /// the one that starts there with +h/2, each judged at its sub-step's middle. An undamped
    /// contact switches without a jump (s(0) = 0) and is judged by δ alone.
    pub lookahead: f64,
}

impl<L: ForceLaw, D: Dashpot, const CONTACT: bool> Spring<L, D, CONTACT> {
    /// A spring of law `law` and dashpot `dashpot`, its contacts judged by their extension now.
    pub const fn new(law: L, dashpot: D) -> Self {
        Spring { law, dashpot, lookahead: 0.0 }
    }

    /// Force on particle i for separation `(dx, dy)` = x_i − x_j (m), relative velocity
    /// `(dvx, dvy)` = v_i − v_j (m/s), rest length `rest` (m) and stiffness constant `k`:
    /// f_i = −(s(δ) + γ δ̇) n̂; zero for a contact spring in tension (δ ≥ 0; damped: δ +
    /// lookahead·δ̇ ≥ 0).
    ///
    /// A damped contact's force is computed and then chosen away when open, not skipped by a
    /// branch: whether a moving packing's near pair touches is a coin toss the processor cannot
    /// predict, and the wrong guesses cost more than the arithmetic (the packing bench's force
    /// pass: 33 ns a disc with the branch, 19 ns without, at 10⁴ discs; docs/performance.md).
    /// An undamped contact keeps its branch before the division: it serves the minimisers,
    /// whose contacts settle, and there the skipped work wins (`jamming.yaml` 10 % faster).
    #[inline(always)]
    pub fn force_on_i(&self, k: f64, rest: f64, dx: f64, dy: f64, dvx: f64, dvy: f64) -> BondForce {
        let r = (dx * dx + dy * dy).sqrt();
        let delta = r - rest;
        if CONTACT && !D::ACTIVE && delta >= 0.0 {
            return BondForce::default();
        }
        let inverse_r = 1.0 / r; // one division per bond: the loop is bound by sqrt and division
        let (nx, ny) = (dx * inverse_r, dy * inverse_r);
        let rate = if D::ACTIVE { nx * dvx + ny * dvy } else { 0.0 };
        let damping = self.dashpot.force(rate);
        let magnitude = self.law.elastic_force(k, delta) + damping;
        let open = CONTACT && D::ACTIVE && delta + self.lookahead * rate >= 0.0;
        BondForce {
            fx: if open { 0.0 } else { -magnitude * nx },
            fy: if open { 0.0 } else { -magnitude * ny },
            dissipation: if open { 0.0 } else { damping * rate },
        }
    }

    /// Stored energy (J) of a bond at separation `(dx, dy)`; zero for an open contact.
    #[inline(always)]
    pub fn energy(&self, k: f64, rest: f64, dx: f64, dy: f64) -> f64 {
        let delta = (dx * dx + dy * dy).sqrt() - rest;
        if CONTACT && delta >= 0.0 { 0.0 } else { self.law.energy(k, delta) }
    }
}

/// Which law every bond of a run follows, as a value: what a campaign asks for, a run
/// records and a scene carries. [`LawSpec::dispatch`] turns it into the concrete
/// [`ForceLaw`] type, once per run, for the bond loop and the static solver alike.
///
/// Serialised as the two keys `law` (`linear`, `power`) and `beta` (1 for linear springs), the
/// shape records and run ids have always had.
///
/// ```
/// use mdsolids::model::LawSpec;
/// let hertz = LawSpec::Power { beta: 1.5 };
/// assert!(!hertz.is_linear() && hertz.beta() == 1.5 && hertz.name() == "power");
/// assert_eq!(LawSpec::Linear.elastic_force(2.0, 0.5), 1.0);
/// assert_eq!(serde_json::to_string(&LawSpec::Linear).unwrap(), r#"{"law":"linear","beta":1.0}"#);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(into = "LawFields", from = "LawFields")]
pub enum LawSpec {
    /// s = k δ ([`Linear`]).
    Linear,
    /// s = C |δ|^β sign δ ([`PowerLaw`]).
    Power {
        /// Exponent β.
        beta: f64,
    },
}

/// Code generic over the force law, called by [`LawSpec::dispatch`] with the concrete type:
/// the one place a law value becomes monomorphised code.
pub trait LawVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with the law `law`.
    fn visit<L: ForceLaw>(self, law: L) -> Self::Output;
}

impl LawSpec {
    /// Calls `visitor` with the concrete law.
    pub fn dispatch<V: LawVisitor>(self, visitor: V) -> V::Output {
        match self {
            LawSpec::Linear => visitor.visit(Linear),
            LawSpec::Power { beta } => visitor.visit(PowerLaw { beta }),
        }
    }

    /// The name written in campaigns, records and tables.
    pub fn name(self) -> &'static str {
        LawFields::from(self).law.name()
    }

    /// The exponent β: 1 for linear springs.
    pub fn beta(self) -> f64 {
        LawFields::from(self).beta
    }

    /// Linear springs (s = k δ), for which the analytical references and the linear continuum hold.
    pub fn is_linear(self) -> bool {
        self == LawSpec::Linear
    }

    /// Elastic force s(δ) (N) of a bond with constant `k` at extension `delta` (m), for the
    /// scalar uses outside the bond loop (references, wall forces).
    pub fn elastic_force(self, k: f64, delta: f64) -> f64 {
        self.dispatch(Evaluate { k, delta, quantity: Quantity::Force })
    }

    /// Tangent stiffness ds/dδ (N/m) of a bond with constant `k` at extension `delta` (m), for
    /// the scalar uses outside the bond loop (t_c, damping, stability estimates).
    pub fn tangent_stiffness(self, k: f64, delta: f64) -> f64 {
        self.dispatch(Evaluate { k, delta, quantity: Quantity::Tangent })
    }

    /// Stored energy e(δ) (J) of a bond with constant `k` at extension `delta` (m), for the
    /// scalar uses outside the bond loop (a packing's contact energy).
    pub fn energy(self, k: f64, delta: f64) -> f64 {
        self.dispatch(Evaluate { k, delta, quantity: Quantity::Energy })
    }
}

/// Which of a law's functions [`Evaluate`] asks for.
#[derive(Clone, Copy)]
enum Quantity {
    Force,
    Tangent,
    Energy,
}

/// A [`Quantity`] at stiffness constant `k` and extension `delta` (m).
struct Evaluate {
    k: f64,
    delta: f64,
    quantity: Quantity,
}

impl LawVisitor for Evaluate {
    type Output = f64;
    fn visit<L: ForceLaw>(self, law: L) -> f64 {
        match self.quantity {
            Quantity::Force => law.elastic_force(self.k, self.delta),
            Quantity::Tangent => law.tangent_stiffness(self.k, self.delta),
            Quantity::Energy => law.energy(self.k, self.delta),
        }
    }
}

/// The name of a law family, as campaigns and records write it (`material.law`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LawName {
    /// f = k δ.
    Linear,
    /// f = C |δ|^β (`hertz` is accepted and means β = 3/2 unless `beta` says otherwise).
    #[serde(alias = "hertz")]
    Power,
}

impl LawName {
    /// The name used in tables.
    pub fn name(self) -> &'static str {
        match self {
            LawName::Linear => "linear",
            LawName::Power => "power",
        }
    }
}

/// The serialised shape of a [`LawSpec`]: `law` and `beta`.
#[derive(serde::Serialize, serde::Deserialize)]
struct LawFields {
    law: LawName,
    beta: f64,
}

impl From<LawSpec> for LawFields {
    fn from(law: LawSpec) -> LawFields {
        match law {
            LawSpec::Linear => LawFields { law: LawName::Linear, beta: 1.0 },
            LawSpec::Power { beta } => LawFields { law: LawName::Power, beta },
        }
    }
}

impl From<LawFields> for LawSpec {
    fn from(fields: LawFields) -> LawSpec {
        match fields.law {
            LawName::Linear => LawSpec::Linear,
            LawName::Power => LawSpec::Power { beta: fields.beta },
        }
    }
}
