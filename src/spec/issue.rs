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

pub(super) fn require(ok: bool, path: &str, value: impl Shown, allowed: &str) -> Result<(), Issue> {
    if ok { Ok(()) } else { Err(Issue { path: path.to_string(), value: value.shown(), allowed: allowed.to_string() }) }
}

/// A value as a message shows it: a number as [`Num`] shows it (so that `1e300` is never
/// printed as 301 digits), anything else as it displays.
pub(super) trait Shown {
    fn shown(&self) -> String;
}

impl Shown for f64 {
    fn shown(&self) -> String {
        Num(*self).to_string()
    }
}

/// Values whose display is already short: words and whole numbers.
macro_rules! shown_as_displayed {
    ($($t:ty),*) => {$(
        impl Shown for $t {
            fn shown(&self) -> String {
                self.to_string()
            }
        }
    )*};
}
shown_as_displayed!(Num, str, String, bool, u32, u64, usize);

impl<T: Shown + ?Sized> Shown for &T {
    fn shown(&self) -> String {
        (**self).shown()
    }
}

/// A number shown in a message: in full when it is short that way, else in exponent form
/// (`1e-300`, not three hundred zeros). A precision (`{:.3}`) gives that many decimals, in
/// either form.
pub struct Num(pub f64);

impl Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let size = self.0.abs();
        let plain = size == 0.0 || (1e-4..1e15).contains(&size) || !size.is_finite();
        match (plain, f.precision()) {
            (true, None) => write!(f, "{}", self.0),
            (true, Some(digits)) => write!(f, "{:.*}", digits, self.0),
            (false, None) => write!(f, "{:e}", self.0),
            (false, Some(digits)) => write!(f, "{:.*e}", digits, self.0),
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
