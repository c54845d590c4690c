//! `eigenrad form-factors`: the surface-to-surface form factors of a scene.

use std::path::PathBuf;

use clap::Args;

use super::groups::{help, CacheArgs, JsonFlag};
use crate::cli;

/// The arguments of `eigenrad form-factors`.
#[derive(Args)]
#[command(mut_arg(
    "json",
    help("Print `{factors: [{from, to, value}], health: {...}}` as JSON on stdout")
))]
pub(super) struct FormFactorsArgs {
    /// Scene file (TOML).
    scene: PathBuf,
    #[command(flatten)]
    json: JsonFlag,
    #[command(flatten)]
    cache: CacheArgs,
}

impl FormFactorsArgs {
    /// Computes the scene's form factors and prints them by surface.
    pub(super) fn run(self) -> anyhow::Result<()> {
        let table = cli::form_factor_table(&self.scene, &self.cache.form_factors())?;
        self.json.print(&table, cli::format_surface_form_factors)
    }
}
