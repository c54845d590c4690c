//! The radiosity problem of a meshed room and its solutions: the room's system, its form-factor
//! operator ([`crate::formfactor::FormFactorOperator`]) with its exact solves (`system`, `exact`), the
//! eigenmodes (`eigen`), the truncated expansions of a system in one formulation (`model`),
//! and the iterative solvers the benchmarks compare with (`iterative`).

pub mod eigen;
pub mod exact;
pub mod iterative;
pub mod model;
pub mod system;

pub use model::Model;
pub use system::{LightResponse, System};
