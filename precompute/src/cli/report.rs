//! The files and text `eigenrad build` and `eigenrad verify` leave: the build report's table
//! and verify's curves.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::atomic;
use super::figures::fixed;
use crate::error::{Error, Result};
use crate::pipeline::BuildReport;
use crate::verify::{self, VerifyReport};

/// The largest error between the sun grid's nodes a reading should have, relative to its
/// largest sun response: above it the report points to `--sun-first`.
const SUN_BETWEEN_NODES: f64 = 0.02;

/// Human-readable build report.
pub fn format_build_report(r: &BuildReport, output: &Path) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "scene {}: {} patches (aspect ratio median {:.2}, worst {:.2}), {} band(s) in {}",
        r.scene, r.patches, r.aspect.median, r.aspect.worst, r.bands, r.unit
    );
    s += &super::form_factors::format_health(&r.form_factors);
    let _ = writeln!(
        s,
        "form-factor operator: {}, {:.1} MB ({})",
        r.operator.storage,
        r.operator.bytes as f64 / 1e6,
        r.operator.reason
    );
    if let Some(c) = &r.operator.compression {
        let dense = 8.0 * (r.patches as f64).powi(2);
        let _ = writeln!(
            s,
            "  compression: {:.1} % of the dense f64 matrix ({:.1} MB); {} blocks whole, {} at low rank (ranks up to {}, mean {:.1}) covering {:.1} % of the entries; guard fallbacks {}, rank fallbacks {}; entries read {:.1} % of n²; measured error {:.1e} (largest relative error of {} rows read whole)",
            100.0 * r.operator.bytes as f64 / dense,
            dense / 1e6,
            c.near_blocks,
            c.low_rank_blocks,
            c.max_rank,
            c.mean_rank,
            100.0 * c.low_rank_share,
            c.guard_fallbacks,
            c.rank_fallbacks,
            100.0 * c.entries_read,
            c.row_error,
            crate::formfactor::hierarchical::ROWS_CHECKED
        );
        if c.shaded_blocks > 0 || c.shade_splits > 0 {
            let _ = writeln!(
                s,
                "  visibility between clusters (--visibility clusters): {} well-separated blocks a blocker may cut read without shadows, times one visible share per patch from rays; {} split further where their rays strayed from the shares by more than {:.0e} of a patch's output; the measured error above is against the exact shadows",
                c.shaded_blocks,
                c.shade_splits,
                c.shade_misfit
            );
        }
    }
    let _ = writeln!(
        s,
        "basis: {} modes, formulation {}, storage {}, {} bytes -> {}",
        r.modes,
        r.formulation,
        r.precision,
        r.bytes,
        output.display()
    );
    for (band, e) in r.eigensolve.iter().enumerate() {
        let band = if r.eigensolve.len() > 1 {
            format!(" of band {band}")
        } else {
            String::new()
        };
        let work = match (e.restarts, e.operator_columns) {
            (Some(restarts), Some(columns)) => {
                format!(", {restarts} restarts, the operator applied to {columns} vectors")
            }
            _ => String::new(),
        };
        let _ = writeln!(
            s,
            "  modes{band}: {}{work}, largest residual {:.1e}",
            e.method, e.max_residual
        );
    }
    let flash = crate::flash::FlashBudget {
        bytes: r.plan.flash_bytes,
    };
    if !flash.fits(r.bytes as u64) {
        let _ = writeln!(
            s,
            "  warning: {} bytes are more than the flash budget of {flash} (--flash); expected before the form factors: {:.0}",
            r.bytes,
            r.plan.basis.total()
        );
    }
    write_luminaires(&mut s, r);
    let _ = writeln!(
        s,
        "accuracy through the runtime against the exact solve (relative error):"
    );
    let _ = writeln!(
        s,
        "  {:<28} {:>10}  {:<34}  {:<30}",
        "case", "exitance", "worst patch", "worst sensor or zone"
    );
    for a in &r.accuracy {
        let patch = format!(
            "{:.1e} (patch {}, {})",
            a.worst_patch.error, a.worst_patch.index, a.worst_patch_surface
        );
        let reading = format!("{:.1e} ({})", a.worst_reading.error, a.worst_reading_name);
        let _ = writeln!(
            s,
            "  {:<28} {:>10.1e}  {:<34}  {:<30}",
            a.case, a.patch_error, patch, reading
        );
    }
    let _ = writeln!(
        s,
        "  (exitance: area-weighted RMS over the patches; a patch, sensor or zone against its own exact value, floored at {:.0e} of the largest)",
        crate::accuracy::metric::READING_FLOOR
    );
    if !r.grids.is_empty() {
        let _ = writeln!(
            s,
            "calculation grids, every channel at level 1, through the runtime (largest relative difference of a figure from the exact solve: {:.1e}):",
            r.grid_figure_error
        );
        super::readout::write_grids(&mut s, &r.grids, r.unit);
    }
    if let Some(d) = &r.daylight {
        let _ = writeln!(
            s,
            "daylight: {} nodes ({} sky patches ({}), the exterior, {} of the sun grid's {} × {} nodes, every {:.2}° of declination and {:.2}° of hour angle, that light the room): {} bytes",
            d.nodes,
            d.sky_patches,
            d.sky,
            d.sun_nodes,
            d.sun_grid[0],
            d.sun_grid[1],
            d.sun_step_deg[0],
            d.sun_step_deg[1],
            d.bytes
        );
        if let Some(e) = &d.sky_discretisation {
            // The node tables are as wide as the nodes; the direct sun's tables and the sun's
            // first reflection's are apart.
            let tables = d.bytes.saturating_sub(
                d.direct_sun
                    .as_ref()
                    .map_or(0, |t| t.bytes + t.candidate_bytes[0]),
            );
            let _ = writeln!(
                s,
                "  sky patches chosen for --sky-tolerance: Reinhart MF:{}, the direct daylight of {} readings under {} reference skies within {:.3} % of MF:{} (mean {:.3} %); the sky's columns take about {} of the {} bytes",
                e.subdivision,
                e.readings,
                e.skies,
                100.0 * e.max,
                e.reference,
                100.0 * e.mean,
                tables * d.sky_patches / d.nodes.max(1),
                d.bytes
            );
        }
        if let Some(direct) = &d.direct_sun {
            let _ = writeln!(
                s,
                "  direct sun on the controller: {} window faces, {} room and {} exterior occluders, {} bytes",
                direct.window_faces, direct.room_occluders, direct.exterior_occluders, direct.bytes
            );
            if direct.candidates > 0 {
                let _ = writeln!(
                    s,
                    "  the sun's first reflection on the controller: {} candidate patches of {}, every reading's response to each ({} bytes), {} zone polygons: {} bytes",
                    direct.candidates,
                    r.patches,
                    direct.candidate_bytes[1],
                    direct.zone_polygons,
                    direct.candidate_bytes[0]
                );
            }
        }
        if let Some(f) = &d.first_reflection {
            let _ = writeln!(
                s,
                "  first reflection for patch exitance: the sky's at rank {} (relative error {:.1e}, area-weighted, tolerance {:.1e}), the sun nodes' {} patches, {} bytes",
                f.rank, f.sky_error, f.tolerance, f.sun_entries, f.bytes
            );
        }
        let i = &d.sun_interpolation;
        let _ = writeln!(
            s,
            "  the sun between nodes, at the centres of {} cells, against the exact sun (relative to each reading's largest sun response; mean, 95th percentile, largest):",
            i.cells
        );
        // A kind of reading the scene does not have is left out, not shown as errors of 0.
        for (what, e) in [
            ("zones", &i.zones),
            ("sensors", &i.sensors),
            ("grid points", &i.grid_points),
            ("direct sun", &i.direct),
        ]
        .into_iter()
        .filter(|(_, e)| e.count > 0)
        {
            let _ = writeln!(
                s,
                "    {what:<12} {:.1e}  {:.1e}  {:.1e}",
                e.mean, e.p95, e.max
            );
        }
        s += &sun_parts(&i.parts);
        let worst = [&i.zones, &i.sensors, &i.grid_points]
            .iter()
            .map(|e| e.max)
            .fold(0.0, f64::max);
        let computed = d.direct_sun.as_ref().is_some_and(|x| x.candidates > 0);
        if !computed && worst > SUN_BETWEEN_NODES {
            let _ = writeln!(
                s,
                "  readings under the sun are interpolated between the nodes, {:.1} % off at the largest: `--sun-first` computes the sun patch and its first reflection on the controller at the sun's own direction (docs/accuracy.md, \"The sun's first reflection on the controller\")",
                100.0 * worst
            );
        }
        let _ = writeln!(
            s,
            "  through the runtime against the exact solve (CIE overcast sky, zenith 3000 cd/m², E_gh 10000 lux; then with the sun at a node, E_n 50000 lux): sensors, zones and grid points within {:.1e}; patch exitance {:.1e} overcast, {:.1e} with the sun (area-weighted RMS)",
            d.check.readings, d.check.patch_error_overcast, d.check.patch_error_sun
        );
    }
    s += &crate::accuracy::calibration::format_ratios(&r.sensor_ratios, &r.channels);
    let _ = writeln!(s, "time per stage:");
    for t in &r.timings {
        let _ = writeln!(s, "  {:<34} {:>8.3} s", t.stage, t.seconds);
    }
    s
}

/// Every file `eigenrad verify --out dir` may write for the scene named `scene`: the tables
/// and one SVG per metric.
pub fn verify_outputs(dir: &Path, scene: &str) -> Vec<PathBuf> {
    let mut out = vec![dir.join(format!("{scene}.md"))];
    out.extend(
        verify::Metric::ALL
            .iter()
            .map(|m| dir.join(format!("{scene}-{}.svg", m.label()))),
    );
    out
}

/// Writes `eigenrad verify`'s curves into `dir` (created if missing), one SVG per metric
/// ([`verify::svgs`]), each atomically. Returns the files written.
pub fn write_svgs(r: &VerifyReport, dir: &Path) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|reason| Error::Io {
        path: dir.to_path_buf(),
        reason,
    })?;
    let mut written = Vec::new();
    for (name, svg) in verify::svgs(r)? {
        let path = dir.join(name);
        atomic::write(&path, svg.as_bytes())?;
        written.push(path);
    }
    Ok(written)
}

/// The luminaires' flux table of the build report, and a warning for each file whose stated
/// flux its candela table does not carry.
fn write_luminaires(s: &mut String, r: &BuildReport) {
    if r.luminaires.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "luminaires (lm): {:<24} {:>10} {:>10} {:>6} {:>10} {:>10} {:>10}",
        "name", "stated", "integrated", "tilt", "emitted", "received", "escaping"
    );
    let lm = |x: Option<f64>| x.map_or("-".to_string(), |v| fixed(v, 1));
    for l in &r.luminaires {
        let _ = writeln!(
            s,
            "                 {:<24} {:>10} {:>10} {:>6} {:>10} {:>10} {:>10}",
            l.name,
            lm(l.stated),
            fixed(l.integrated, 1),
            fixed(l.tilt_factor, 3),
            fixed(l.emitted, 1),
            fixed(l.received, 1),
            fixed(l.escaping, 1)
        );
    }
    for w in r.luminaires.iter().filter_map(|l| l.warning.as_ref()) {
        let _ = writeln!(s, "warning: {w}");
    }
}

/// The build report's lines on where the error between nodes comes from
/// ([`crate::accuracy::sun_parts`]).
fn sun_parts(parts: &crate::accuracy::sun_parts::SunParts) -> String {
    let mut s = String::new();
    let kinds: Vec<_> = parts.kinds.iter().filter(|k| k.rest.count > 0).collect();
    if kinds.is_empty() {
        return s;
    }
    let _ = writeln!(
        s,
        "  its parts (direct sun, the sun patch's first reflection, the rest; largest each) and the reading with the largest error:"
    );
    for k in kinds {
        let _ = write!(
            s,
            "    {:<12} {:.1e}  {:.1e}  {:.1e}",
            k.kind, k.direct.max, k.first.max, k.rest.max
        );
        if let Some(w) = &k.worst {
            let _ = write!(
                s,
                "; {} at δ {:.1}° h {:.1}°: {:+.1e} = {:+.1e} {:+.1e} {:+.1e} of {:.3} lux per lux (the first reflection's power {:.2} times the corners' mean)",
                w.reading,
                w.declination_hour[0],
                w.declination_hour[1],
                w.error,
                w.direct,
                w.first,
                w.rest,
                w.peak,
                w.power_ratio
            );
        }
        s.push('\n');
    }
    let _ = writeln!(
        s,
        "  with the direct sun and the first reflection of the {} patches the sun nodes light at the sun's direction, the rest interpolated, then the rest per unit of the first reflection's power (mean, 95th percentile, largest):",
        parts.sunlit_patches
    );
    for k in parts.kinds.iter().filter(|k| k.rest.count > 0) {
        let (q, n) = (&k.rest, &k.rest_per_power);
        let _ = writeln!(
            s,
            "    {:<12} {:.1e}  {:.1e}  {:.1e};  {:.1e}  {:.1e}  {:.1e}",
            k.kind, q.mean, q.p95, q.max, n.mean, n.p95, n.max
        );
    }
    for w in parts
        .kinds
        .iter()
        .filter_map(|k| k.worst_per_power.as_ref())
    {
        let _ = writeln!(
            s,
            "    largest per unit of power: {} at δ {:.1}° h {:.1}°: {:+.1e} of {:.3} lux per lux (the first reflection's power {:.2} times the corners' mean)",
            w.reading, w.declination_hour[0], w.declination_hour[1], w.error, w.peak, w.power_ratio
        );
    }
    s
}
