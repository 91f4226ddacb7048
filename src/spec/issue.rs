//! A value a campaign may not have (an [`Issue`]: its field path, the value, what is
//! allowed instead) and the checks that make one, shared by every part of the resolution.

use std::fmt::Display;

/// A value the campaign may not have, with the field path (relative to the scene).
#[derive(Clone, Debug, PartialEq)]
pub struct Issue {
    /// Dotted field path, e.g. `damping.restitution`.
    pub path: String,
    /// The offending value as written.
    pub value: String,
    /// What is allowed instead.
    pub allowed: String,
}

pub(super) fn require(ok: bool, path: &str, value: impl Display, allowed: &str) -> Result<(), Issue> {
    if ok {
        Ok(())
    } else {
        Err(Issue { path: path.to_string(), value: value.to_string(), allowed: allowed.to_string() })
    }
}

/// A number shown in a message: in full when it is short that way, else in exponent form
/// (`1e-300`, not three hundred zeros).
pub(super) struct Num(pub(super) f64);

impl Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let size = self.0.abs();
        if size == 0.0 || (1e-4..1e15).contains(&size) || !size.is_finite() {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

pub(super) fn positive(value: f64, path: &str) -> Result<f64, Issue> {
    require(value.is_finite() && value > 0.0, path, Num(value), "must be a finite number > 0")?;
    Ok(value)
}

/// A required field that is absent.
pub(super) fn missing(path: &str, allowed: &str) -> Issue {
    Issue { path: path.into(), value: "(missing)".into(), allowed: allowed.into() }
}
