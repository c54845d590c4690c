//! `eigenrad-bench simulate`: what a year of the controller costs on the host, part by part
//! (the weather file read, each hour's sun and sky, the controller's loop through the
//! runtime), the best of a few runs each.

use std::path::Path;
use std::time::Instant;

use anyhow::Result;
use eigenrad_precompute::simulate::{self, HourOptions, SkySource};
use eigenrad_precompute::weather;
use eigenrad_runtime::Basis;

/// Runs of each part; the best is reported (the least disturbed by other work).
const RUNS: usize = 3;

/// Prints the table's header and one row per basis, all on `weather` with `controllers`
/// (one controller file per basis, in order).
pub(crate) fn run(
    bases: &[std::path::PathBuf],
    weather_path: &Path,
    controllers: &[std::path::PathBuf],
) -> Result<()> {
    anyhow::ensure!(
        bases.len() == controllers.len(),
        "give one --controller per basis ({} bases, {} controllers)",
        bases.len(),
        controllers.len()
    );
    println!("| basis | hours | weather read s | skies s | controller loop s | year s |");
    println!("|---|---|---|---|---|---|");
    let mut all = 0.0;
    for (basis_path, controller_path) in bases.iter().zip(controllers) {
        let bytes = std::fs::read(basis_path)?;
        let basis = Basis::from_bytes(&bytes).map_err(|e| anyhow::anyhow!("{e}"))?;
        let controller = simulate::load_controller(controller_path, &basis)?;
        let (mut read_s, mut sky_s, mut loop_s) = (f64::MAX, f64::MAX, f64::MAX);
        let mut count = 0;
        for _ in 0..RUNS {
            let t = Instant::now();
            let w = weather::read(weather_path)?;
            read_s = read_s.min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let (hours, _, _) = simulate::hours(
                &w,
                &basis,
                &controller.occupancy,
                HourOptions {
                    year: None,
                    source: SkySource::Illuminance,
                },
            )?;
            sky_s = sky_s.min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let year = simulate::simulate(&bytes, &controller, &hours)?;
            loop_s = loop_s.min(t.elapsed().as_secs_f64());
            std::hint::black_box(&year);
            count = hours.len();
        }
        let total = read_s + sky_s + loop_s;
        all += total;
        println!(
            "| {} | {count} | {read_s:.3} | {sky_s:.3} | {loop_s:.3} | {total:.3} |",
            basis_path.display()
        );
    }
    if bases.len() > 1 {
        println!("| all | | | | | {all:.3} |");
    }
    Ok(())
}
