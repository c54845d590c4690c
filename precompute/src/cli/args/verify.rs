//! `eigenrad verify`: the accuracy report of a scene against the mode count.

use std::io::IsTerminal;
use std::path::PathBuf;

use clap::Args;

use super::groups::{help, CacheArgs, JsonFlag};
use super::note_written;
use crate::cli::{self, atomic, guard};
use crate::{scene, verify};

/// The arguments of `eigenrad verify`.
#[derive(Args)]
#[command(mut_arg(
    "json",
    help("Print the report as one JSON document on stdout instead of the tables")
))]
pub(super) struct VerifyArgs {
    /// Scene file (TOML).
    scene: PathBuf,
    /// Write `<scene>.md` and `<scene>-{patches,zones,sensors}.svg` into this folder.
    #[arg(long)]
    out: Option<PathBuf>,
    #[command(flatten)]
    json: JsonFlag,
    #[command(flatten)]
    cache: CacheArgs,
}

impl VerifyArgs {
    /// Computes the report, writes its files with `--out` and prints its tables.
    pub(super) fn run(self) -> anyhow::Result<()> {
        if let Some(dir) = &self.out {
            let inputs = scene::inputs(&self.scene)?;
            guard::check_outputs(&cli::verify_outputs(dir, &inputs.name), &inputs.files)?;
        }
        let opts = verify::VerifyOptions {
            form_factors: self.cache.form_factors(),
            progress: std::io::stderr().is_terminal(),
            ..verify::VerifyOptions::default()
        };
        let report = verify::verify(&self.scene, &opts)?;
        let tables = verify::markdown(&report);
        if let Some(dir) = &self.out {
            for path in cli::write_svgs(&report, dir)? {
                note_written(&path);
            }
            let path = dir.join(format!("{}.md", report.scene));
            atomic::write(&path, tables.as_bytes())?;
            note_written(&path);
        }
        self.json.print(&report, |_| tables)
    }
}
