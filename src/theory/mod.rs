//! Analytical references: the two-body collision and the normal modes of a chain.

pub use self::chain::{ChainModes, chain_mode_frequency};
pub use self::two_body::{
    Overdamped, gamma_for_restitution, linear_contact_duration, linear_restitution, pair_omega,
    power_law_contact_duration, power_law_max_overlap,
};

mod chain;
pub mod special;
mod two_body;
