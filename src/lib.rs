//! eigenrad: real-time radiosity for lighting controllers.
//!
//! This facade re-exports the two halves of the project so that the end-to-end tests in
//! `tests/` and the host examples in `examples/` can use both:
//!
//! - [`runtime`]: the `no_std` evaluator that firmware links (`eigenrad-runtime`);
//! - [`precompute`]: the host library behind the `eigenrad` command (`eigenrad-precompute`).
pub use eigenrad_precompute as precompute;
pub use eigenrad_runtime as runtime;
