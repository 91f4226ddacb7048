//! The chain's own fields (particles, excited node, walls, relaxation, timed wave) and its
//! part of the resolution and of what a run spec tells: its v0 rule, its relaxing walls, its
//! default length, its particles and bonds.

use serde_json::Value;

use crate::spec::issue::{Issue, Num, missing, positive, require};
use crate::spec::raw::{Control, RawScene};
use crate::spec::shared::{Deformation, RelaxSpec, WaveSpec, bonded, kick_speed, resolve_relax, wave_threshold};

/// What only a chain has.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainRun {
    /// Moving particles.
    pub n: usize,
    /// Excited particle, 1..n.
    pub node: usize,
    /// Distance between the walls (m).
    pub wall_distance: f64,
    /// A relaxing chain: when the relaxation stops, and the tangent step.
    pub relax: Option<RelaxSpec>,
    /// The wave timed from the excited particle to a receiver, if asked for.
    pub wave: Option<WaveSpec>,
}

impl ChainRun {
    /// Particles, excited node, walls, timed wave and relaxation of a chain scene.
    pub(super) fn resolve(raw: &RawScene, spacing: f64) -> Result<ChainRun, Issue> {
        let chain = resolve_chain(raw, spacing)?;
        let relax = raw.relax.is_some().then(|| resolve_relax(raw, Control::Force, None)).transpose()?;
        Ok(ChainRun { relax, ..chain })
    }

    /// A hit chain's v0 is required, > 0; a relaxing chain's may be 0 (its walls may be what
    /// moves it), and its springs are bonded.
    pub(super) fn resolve_v0(raw: &RawScene, contact: bool) -> Result<f64, Issue> {
        if raw.relax.is_none() {
            return kick_speed(raw);
        }
        let v0 = raw.v0.unwrap_or(0.0);
        require(v0.is_finite() && v0 >= 0.0, "v0", v0, "must be a finite number ≥ 0 (m/s)")?;
        bonded(contact)?;
        Ok(v0)
    }

    /// How far the walls are moved from the rest length (n + 1) a, ΔW (m), for springs of rest
    /// length `spacing` (m).
    pub fn wall_extension(&self, spacing: f64) -> f64 {
        self.wall_distance - (self.n + 1) as f64 * spacing
    }

    /// A hit chain is a collision: its contact time is the two-body one.
    pub(super) fn is_collision(&self) -> bool {
        self.relax.is_none()
    }

    /// The run's default length (t_c): 20 for a hit chain; a relaxing one's is `relax.max_tc`.
    pub(super) fn default_duration_tc(&self) -> Option<f64> {
        self.relax.is_none().then_some(20.0)
    }

    /// The moving particles and the two walls.
    pub(super) fn particles(&self) -> usize {
        self.n + 2
    }

    /// n + 1 springs.
    pub(super) fn bonds(&self) -> usize {
        self.n + 1
    }

    /// A relaxing chain between moved walls: its springs' equilibrium extension ΔW/(n + 1),
    /// where it ends; a hit chain between moved walls: the kick at v0 (m/s) on springs held at
    /// ΔW/(n + 1), where it starts evenly spaced; otherwise the kick at v0.
    pub(super) fn deformation(&self, spacing: f64, v0: f64) -> Deformation {
        let extension = self.wall_extension(spacing) / (self.n + 1) as f64;
        match (extension != 0.0, self.relax.is_some()) {
            (true, true) => Deformation::Extension(extension),
            (true, false) => Deformation::PreStressed { extension, speed: v0 },
            (false, _) => Deformation::Collision(v0),
        }
    }

    /// A relaxing chain's walls: far enough apart that its last spring (of rest length
    /// `spacing`, m) does not collapse, and moved (or the chain kicked at `v0`, m/s), so that
    /// there is something to relax. Nothing to check for a hit chain.
    pub(super) fn check(&self, spacing: f64, v0: f64) -> Result<(), Issue> {
        if self.relax.is_none() {
            return Ok(());
        }
        let walls = self.wall_distance;
        let least = (self.n as f64 + 0.1) * spacing;
        require(
            walls > least,
            "wall_distance",
            walls,
            &format!(
                "must be more than (n + 0.1) · spacing = {}: a relaxing chain starts at rest spacing from the left \
                 wall, so the last spring takes the whole wall displacement at first and must not collapse",
                Num(least)
            ),
        )?;
        let extension = self.wall_extension(spacing);
        require(
            v0 > 0.0 || extension.abs() > 1e-12 * walls,
            "wall_distance",
            walls,
            "a relaxing chain needs its walls moved from (n + 1) · spacing, or a v0",
        )?;
        // The residual-force criterion is relative to the equilibrium wall force: none when
        // the walls are not moved, and the run could never count as relaxed.
        require(
            self.relax.is_none_or(|r| r.residual_force.is_none()) || extension != 0.0,
            "relax.residual_force",
            "(set)",
            "needs walls moved from (n + 1) · spacing (it is a fraction of the wall force); use relax.kinetic_ratio",
        )
    }
}

/// Number of particles, excited node (1..n), wall distance and timed wave of a chain scene
/// (its relaxation still unset).
fn resolve_chain(raw: &RawScene, spacing: f64) -> Result<ChainRun, Issue> {
    let n = raw.n.ok_or_else(|| missing("n", "the number of moving particles, 1..=100000"))?;
    require((1..=100_000).contains(&n), "n", n, "must be in 1..=100000")?;
    let node = particle(raw.node.as_ref(), n, n.div_ceil(2), "node")?;
    let walls = positive(raw.wall_distance.unwrap_or((n + 1) as f64 * spacing), "wall_distance")?;
    let wave = match &raw.wave {
        None => None,
        Some(w) => {
            let far_end = if node <= n / 2 { n } else { 1 };
            let receiver = particle(w.receiver.as_ref(), n, far_end, "wave.receiver")?;
            require(receiver != node, "wave.receiver", receiver, "a particle other than the excited one")?;
            let springs = receiver.abs_diff(node);
            Some(WaveSpec {
                source: node,
                receivers: vec![receiver],
                distance: springs as f64 * spacing,
                springs,
                threshold: wave_threshold(w)?,
            })
        }
    };
    Ok(ChainRun { n, node, wall_distance: walls, relax: None, wave })
}

/// A chain particle named `first`, `last`, `centre` or by its number 1..=n; `default` when absent.
fn particle(value: Option<&Value>, n: usize, default: usize, path: &str) -> Result<usize, Issue> {
    let allowed = || format!("centre, first, last or a particle number 1..={n}");
    match value {
        None => Ok(default),
        Some(Value::String(s)) if s == "centre" || s == "center" => Ok(n.div_ceil(2)),
        Some(Value::String(s)) if s == "first" => Ok(1),
        Some(Value::String(s)) if s == "last" => Ok(n),
        Some(Value::Number(number)) => match number.as_u64() {
            Some(i) if (1..=n as u64).contains(&i) => Ok(i as usize),
            _ => Err(Issue { path: path.into(), value: number.to_string(), allowed: allowed() }),
        },
        Some(other) => Err(Issue { path: path.into(), value: other.to_string(), allowed: allowed() }),
    }
}
