//! `eigenrad-bench daylight`: what the room's response to the sky and the sun costs on the
//! host (`sources::daylight`), against the scene's form factors, in one run.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Result};
use eigenrad_precompute::formfactor::{FormFactorOptions, Occluders};
use eigenrad_precompute::geometry::Vec3;
use eigenrad_precompute::pipeline;
use eigenrad_precompute::sources::daylight::{sky_response, sun_light, DaylightOptions};
use eigenrad_runtime::sky::patches::SkyPatches;

/// Prints the table's header and one row per scene.
pub(crate) fn run(scenes: &[PathBuf]) -> Result<()> {
    println!(
        "| scene | patches | window patches | prepare s (form factors, rows, light sources) | Tregenza (145) s | Reinhart MF:2 (577) s | one sun direction ms | Tregenza / prepare |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for s in scenes {
        row(s)?;
    }
    Ok(())
}

/// One row: the scene prepared as `build` and `solve` do (form factors uncached, output rows,
/// the channels' light), then its sky responses and one sun.
fn row(path: &Path) -> Result<()> {
    let opts = FormFactorOptions {
        cache: None,
        ..FormFactorOptions::default()
    };
    let t = Instant::now();
    let prepared = pipeline::prepare(path, &opts)?;
    let prepare_s = t.elapsed().as_secs_f64();
    let scene = &prepared.scene;
    if scene.site.is_none() || scene.windows.is_empty() {
        bail!(
            "{}: daylight needs a [site] and a glazed window (docs/scene.md, \"Daylight\")",
            path.display()
        );
    }
    let occluders = Occluders::with_faces(&scene.patches, &scene.faces);
    let daylight = DaylightOptions::default();
    let t = Instant::now();
    let tregenza = sky_response(scene, &occluders, SkyPatches::TREGENZA, &daylight);
    let tregenza_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let mf2 = SkyPatches::reinhart(2).map_err(|e| anyhow::anyhow!("{e}"))?;
    let reinhart = sky_response(scene, &occluders, mf2, &daylight);
    let reinhart_s = t.elapsed().as_secs_f64();
    // A sun in front of the first window, 40° up: through it, whatever the room's orientation.
    let window = &scene.windows[0];
    let patch = &scene.patches[scene.surfaces[window.surface].patch_range.start];
    let inward = patch.normal;
    let horizontal = Vec3::new(-inward.x, -inward.y, 0.0).normalized();
    let (c, s) = (40f64.to_radians().cos(), 40f64.to_radians().sin());
    let toward_sun = Vec3::new(horizontal.x * c, horizontal.y * c, s).normalized();
    let t = Instant::now();
    let sun = sun_light(scene, &occluders, toward_sun, &daylight);
    let sun_ms = 1e3 * t.elapsed().as_secs_f64();
    std::hint::black_box((&tregenza, &reinhart, &sun));
    let window_patches: usize = scene
        .windows
        .iter()
        .map(|w| scene.surfaces[w.surface].patch_range.len())
        .sum();
    println!(
        "| {} | {} | {window_patches} | {prepare_s:.2} | {tregenza_s:.2} | {reinhart_s:.2} | {sun_ms:.1} | {:.2} |",
        path.display(),
        scene.patches.len(),
        tregenza_s / prepare_s,
    );
    Ok(())
}
