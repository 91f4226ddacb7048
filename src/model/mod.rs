//! What a solid is made of: particles, which pairs are bonded, and the force law of a bond.
//!
//! Connectivity ([`Bonds`]) knows nothing of forces, the force law ([`Spring`]) knows nothing
//! of which particles it joins, and neither knows how time is integrated (`crate::sim`).

pub use self::bonds::Bonds;
pub use self::lattice::SquareLattice;
pub use self::law::{
    BondDashpot, Dashpot, ForceLaw, LawName, LawSpec, LawVisitor, Linear, NoDashpot, PowerLaw, Spring,
};
pub use self::packing::{
    ContactSearch, Contacts, NearPairs, PeriodicBox, bidisperse_box, contacts_within, random_bidisperse,
};
pub use self::particles::{Axes, Particles};
pub use self::planar::{Edges, LatticeType, Layout, PlanarLattice};

mod bonds;
mod lattice;
mod law;
mod packing;
mod particles;
mod planar;
