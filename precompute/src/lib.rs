//! Host precompute for eigenrad: scene in; form factors, eigenbasis, serialized basis and an
//! accuracy report out. The `eigenrad` command is a thin layer over this library.
pub mod accuracy;
pub mod atomic;
pub mod build;
pub mod cli;
pub mod eigen;
mod error;
pub mod formfactor;
pub mod geometry;
pub mod host_eval;
pub mod model;
pub mod outputs;
pub mod scene;
pub mod solve;
pub mod tables;
pub mod verify;

pub use error::{Error, Result};
