//! Contact duration and restitution from the timed δ = 0 crossings of a pair's bond.

use crate::sim::Crossing;

/// The first contact of a pair: from δ turning negative to δ returning to zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactTiming {
    /// Contact duration t_end − t_start (s).
    pub duration: f64,
    /// Restitution −δ̇(t_end)/δ̇(t_start): the relative normal speed after over before.
    pub restitution: f64,
}

/// Timing of the first closing crossing and the first opening after it; `None` if the contact
/// never closed and opened again within the run.
pub fn contact_timing(crossings: &[Crossing]) -> Option<ContactTiming> {
    let start = crossings.iter().position(|c| c.closing)?;
    let end = crossings[start..].iter().find(|c| !c.closing)?;
    let begin = crossings[start];
    Some(ContactTiming { duration: end.time - begin.time, restitution: -end.rate / begin.rate })
}
