//! Host precompute for eigenrad: scene in; form factors, eigenbasis, serialized basis and an
//! accuracy report out. The `eigenrad` command is a thin layer over this library.
//!
//! The modules are the pipeline's stages, each using only the ones above it:
//!
//! | module | stage |
//! |---|---|
//! | [`geometry`] | points, polygons, patches |
//! | [`memory`] | what a build of n patches holds, the solvers' size thresholds, the machine's memory |
//! | [`scene`] | scene files, OBJ/MTL, meshing |
//! | [`formfactor`] | form factors with occlusion, sensor and zone rows, their health |
//! | [`cache`] | the patch form factors and sensor and zone rows kept on disk between runs, keyed by their content |
//! | [`sources`] | what emits light: per channel, its emission and direct irradiance |
//! | [`radiosity`] | the model (`G`, `ρ`, `b`), exact solves, eigenmodes |
//! | [`basis`] | a model and its modes as the runtime's tables |
//! | [`accuracy`] | test cases, the error figures, the truncation sweep, evaluation through the runtime |
//! | [`pipeline`] | scene to basis with its report (`eigenrad build`) |
//! | [`picture`] | false-colour pictures: a work plane's plan with isolux lines, the surfaces unfolded (`eigenrad render`) |
//! | [`verify`] | accuracy tables and curves against the mode count (`eigenrad verify`) |
//! | [`daylight`] | the sun's position from date, time and site; the site's and the room's frames (the sky models are the runtime's) |
//! | [`cli`] | what the commands compute and print, atomic file writes |
pub mod accuracy;
pub mod atomic;
pub mod basis;
pub mod cache;
pub mod cli;
pub mod daylight;
mod error;
pub mod formfactor;
pub mod geometry;
pub mod memory;
pub mod picture;
pub mod pipeline;
pub mod radiosity;
pub mod scene;
pub mod sources;
pub mod verify;

pub use error::{Error, Result};
