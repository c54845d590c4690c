//! `eigenrad-bench sight`: what the scene's solids (`formfactor::Solid`: its blocks as closed
//! boxes) save in the hierarchical form factors, and what they change. Each scene's operator
//! is built twice in this process, one after the other, on the same patches: with occluders
//! that know no solid, then with the scene's solids; the same settings otherwise
//! (`--operator hierarchical`'s).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context as _, Result};
use eigenrad_precompute::formfactor::hierarchical::{Compression, Settings};
use eigenrad_precompute::formfactor::{
    occluded_share, patch_form_factors_hierarchical, FormFactorOperator, FormFactorOptions,
    Hierarchical, Occluders,
};
use faer::{Mat, Par};

use crate::scale::cpu_seconds;

/// Columns of the products the two operators are compared on.
const PROBES: usize = 4;

/// One build of the operator: CPU and wall seconds, what the compression made.
struct Run {
    cpu: f64,
    wall: f64,
    compression: Compression,
    operator: Hierarchical,
}

fn build(patches: &[eigenrad_precompute::geometry::Patch], occluders: &Occluders) -> Result<Run> {
    let (cpu, wall) = (cpu_seconds(), Instant::now());
    let ff = patch_form_factors_hierarchical(
        patches,
        occluders,
        &FormFactorOptions::default(),
        &Settings::default(),
    )
    .map_err(|e| anyhow::anyhow!("non-finite entry between patches {:?}", e.patches))?;
    Ok(Run {
        cpu: cpu_seconds() - cpu,
        wall: wall.elapsed().as_secs_f64(),
        compression: ff.matrix.compression().clone(),
        operator: ff.matrix,
    })
}

/// Prints one row per build and, per scene, the largest difference between the two
/// operators' products (relative to the largest entry of the product without solids).
pub(crate) fn run(scenes: &[PathBuf]) -> Result<()> {
    println!("| scene | patches | solids | form factors CPU s | wall s | entries read | near blocks | low-rank blocks | rank fallbacks | guard fallbacks | measured row error |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for path in scenes {
        let scene = eigenrad_precompute::scene::load(path)
            .with_context(|| format!("{}", path.display()))?;
        let n = scene.patches.len();
        let plain = Occluders::with_faces(&scene.patches, &scene.faces);
        let solid = plain.clone().with_solids(&scene.solids);
        let mut runs = Vec::new();
        for (label, occluders) in [("none", &plain), ("blocks", &solid)] {
            let r = build(&scene.patches, occluders)?;
            let c = &r.compression;
            println!(
                "| {} | {n} | {label} ({}) | {:.1} | {:.1} | {:.3} | {} | {} | {} | {} | {:.1e} |",
                path.display(),
                if label == "none" {
                    0
                } else {
                    scene.solids.len()
                },
                r.cpu,
                r.wall,
                c.entries_read,
                c.near_blocks,
                c.low_rank_blocks,
                c.rank_fallbacks,
                c.guard_fallbacks,
                c.row_error
            );
            runs.push(r);
        }
        let x = Mat::<f64>::from_fn(n, PROBES, |i, k| {
            (((i * 7 + k * 13) % 17) as f64 - 8.0) / 8.0 + f64::from(k == 0)
        });
        let (mut a, mut b) = (Mat::<f64>::zeros(n, PROBES), Mat::<f64>::zeros(n, PROBES));
        runs[0]
            .operator
            .apply(a.as_mut(), x.as_ref(), Par::rayon(0));
        runs[1]
            .operator
            .apply(b.as_mut(), x.as_ref(), Par::rayon(0));
        let worst = (0..PROBES)
            .map(|k| {
                let scale = (0..n).fold(0.0f64, |s, i| s.max(a[(i, k)].abs()));
                (0..n).fold(0.0f64, |s, i| s.max((a[(i, k)] - b[(i, k)]).abs())) / scale
            })
            .fold(0.0, f64::max);
        println!(
            "\n{}: CPU time with the solids {:.2}× without; products differ by at most {worst:.1e} of their largest entry",
            path.display(),
            runs[1].cpu / runs[0].cpu
        );
        println!(
            "facing pairs with a blocker in their shaft (sampled, formfactor::occluded_share): {:.3}; with a blocker and not hidden whole by a solid: {:.3}\n",
            occluded_share(&scene.patches, &plain),
            occluded_share(&scene.patches, &solid)
        );
    }
    Ok(())
}
