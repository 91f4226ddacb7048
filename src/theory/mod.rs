//! Analytical references: the two-body collision, damped collisions, the normal modes of a
//! chain and the plane waves of the square lattice.

pub use self::chain::{ChainModes, chain_mode_frequency};
pub use self::collision::{
    background_decay_rate, linear_pair_overlap, power_law_gamma_for_restitution, power_law_restitution,
};
pub use self::lattice::{branch_frequency, square_branch_stiffnesses};
pub use self::two_body::{
    Overdamped, clamped_restitution, critical_damping, full_mass_restitution, gamma_for_restitution,
    linear_contact_duration, linear_restitution, pair_omega, power_law_contact_duration, power_law_max_overlap,
};

mod chain;
mod collision;
mod lattice;
pub mod special;
mod two_body;
