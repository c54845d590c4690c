//! The radiosity system of a meshed scene and its solutions: the model (`G = A F`, `ρ`,
//! `b = A/ρ`) with its truncated expansions, the exact reference solve, and the eigenmodes.

pub mod eigen;
pub mod exact;
pub mod iterative;
pub mod model;

pub use model::Model;
