//! `eigenrad-bench partition`: how the hierarchical operator's block partition divides each
//! scene's `n²` entries before any is read (`formfactor::hierarchical::Census`): the share
//! read whole because the clusters are close, the share read whole because a blocker may cut
//! an admissible pair (sight splits it down to leaves), and the shares left to the cross
//! approximation and to dark blocks. Only the tree and the sight tests run, so the sizes a
//! build cannot reach in reasonable time are counted too.

use std::path::PathBuf;

use anyhow::{Context as _, Result};
use eigenrad_precompute::formfactor::hierarchical::Settings;
use eigenrad_precompute::formfactor::{partition_census, Occluders};

/// Prints the table's header and one row per scene.
pub(crate) fn run(scenes: &[PathBuf]) -> Result<()> {
    println!("| scene | patches | blocks | near | mixed, read whole | mixed, compressed after the split | far | dark | mixed pairs | their blocks read whole | entries read whole | partition s |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for path in scenes {
        let scene = eigenrad_precompute::scene::load(path)
            .with_context(|| format!("{}", path.display()))?;
        let occluders = Occluders::with_faces(&scene.patches, &scene.faces);
        let c = partition_census(&scene.patches, &occluders, &Settings::default());
        let whole = (c.near + c.mixed_whole) * (c.patches as f64).powi(2);
        println!(
            "| {} | {} | {} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {} | {} | {:.3e} | {:.1} |",
            path.display(),
            c.patches,
            c.blocks,
            c.near,
            c.mixed_whole,
            c.mixed_compressed,
            c.far,
            c.dark,
            c.mixed_pairs,
            c.mixed_blocks_whole,
            whole,
            c.seconds
        );
    }
    Ok(())
}
