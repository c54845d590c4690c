//! Host precompute for eigenrad: scene in; form factors, eigenbasis, serialized basis and an
//! accuracy report out. The `eigenrad` command is a thin layer over this library.
//!
//! The modules are the pipeline's stages, each using only the ones above it (no module
//! imports one below it, and none imports another that imports it):
//!
//! | module | stage |
//! |---|---|
//! | [`geometry`] | points, polygons, patches |
//! | [`atomic`] | files written atomically: outputs and cache entries |
//! | [`memory`] | what a build of n patches holds, the solvers' size thresholds, the machine's memory |
//! | [`flash`] | a microcontroller's flash budget for a basis |
//! | [`daylight`] | the sun's position from date, time and site; a sky's illuminances and patch luminances for a site, a time and a weather state (the sky models are the runtime's); the site's and the room's frames |
//! | [`weather`] | weather years: EPW and TMY3 files read into hourly irradiances, illuminances and temperatures, and their site |
//! | [`scene`] | scene files, OBJ/MTL, meshing, the receivers every light path walks |
//! | [`formfactor`] | the form-factor operator, form factors with occlusion, sensor and zone rows, their health |
//! | [`cache`] | the patch form factors and sensor and zone rows kept on disk between runs, keyed by their content |
//! | [`sources`] | what emits light: per channel, its emission and direct irradiance |
//! | [`radiosity`] | the room's system (operator, `ρ`, receivers, lights) and its exact solves, eigenmodes, expansions |
//! | `error` | the umbrella [`Error`]: every stage's error, for the stages below and the commands |
//! | [`basis`] | a model and its modes as the runtime's tables |
//! | [`accuracy`] | test cases, the error figures, the truncation sweep, evaluation through the runtime |
//! | [`simulate`] | the controller's year: its loop through the runtime over a weather file, energy, targets, daylight metrics (`eigenrad simulate`) |
//! | [`pipeline`] | scene to basis with its report (`eigenrad build`) |
//! | [`building`] | rooms built apart (in parallel, or as shards on a cluster) and every controller's basis cut from them (`eigenrad building`, `eigenrad merge`) |
//! | [`picture`] | false-colour pictures: a work plane's plan with isolux lines, the surfaces unfolded (`eigenrad render`), a year hour by hour as a day × hour heat map (`eigenrad simulate --heatmap`, from plain values: it imports no stage) |
//! | [`verify`] | accuracy tables and curves against the mode count (`eigenrad verify`) |
//! | [`cli`] | what the commands compute and print |
pub mod accuracy;
pub mod atomic;
pub mod basis;
pub mod building;
pub mod cache;
pub mod cli;
pub mod daylight;
mod error;
pub mod flash;
pub mod formfactor;
pub mod geometry;
pub mod memory;
pub mod picture;
pub mod pipeline;
pub mod radiosity;
pub mod scene;
pub mod simulate;
pub mod sources;
pub mod verify;
pub mod weather;

pub use error::{Error, Result};
