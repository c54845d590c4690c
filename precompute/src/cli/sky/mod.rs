//! `eigenrad sky`: the sky of a site, a time and a weather state ([`crate::daylight::sky`],
//! where it is computed) and its report as text (`format.rs`). The commands and their tests
//! reach the sky through the names re-exported here.

mod format;

pub use crate::daylight::sky::{sky, PatchReport, PerezReport, SkyInput, SkyReport, SkyRequest};
pub use format::format_sky;
