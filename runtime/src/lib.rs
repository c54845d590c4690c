#![no_std]
#![doc = include_str!("../README.md")]

#[cfg(any(test, feature = "alloc"))]
extern crate alloc;

mod basis;
pub mod dali;
mod decode;
mod error;
mod eval;
pub mod format;
pub mod sky;
mod storage;
pub mod target;
#[cfg(any(test, feature = "alloc"))]
pub mod writer;

pub use basis::{Basis, GridPiece, PatchInfo, SensorInfo, Site, MIN_REFLECTANCE};
pub use error::{Error, Result};
pub use eval::{
    ChannelEvaluator, DaylightEvaluator, ElectricLight, Evaluator, Figures, Reading, Sun,
    MAX_EXITANCE, MAX_LEVEL,
};
pub use format::{Formulation, Precision, Quantity};
pub use target::{LevelProblem, Output};
