//! `eigenrad inspect`: what a basis holds (dimensions, names, sizes, leading eigenvalues).

use std::fmt::Write as _;
use std::path::Path;

use eigenrad_runtime::Basis;
use serde::Serialize;

use super::readout::{band_names, basis_error, unit};
use crate::error::Result;

/// What `inspect` shows.
#[derive(Clone, Debug, Serialize)]
pub struct BasisInfo {
    /// Format version.
    pub format_version: u16,
    /// Total bytes.
    pub bytes: usize,
    /// Unit.
    pub unit: &'static str,
    /// Band names.
    pub bands: Vec<&'static str>,
    /// `split` or `seed`.
    pub formulation: &'static str,
    /// `f32`, `f16` or `i16`.
    pub precision: &'static str,
    /// Number of patches.
    pub patches: usize,
    /// Modes per band.
    pub modes: usize,
    /// Surface names.
    pub surfaces: Vec<String>,
    /// Channel names.
    pub channels: Vec<String>,
    /// Sensor names.
    pub sensors: Vec<String>,
    /// Zone names with their areas (m²).
    pub zones: Vec<(String, f32)>,
    /// Each zone's calculation grid: its points over all pieces (0: none).
    pub grids: Vec<usize>,
    /// Eigenvalues of the first band.
    pub eigenvalues: Vec<f32>,
    /// The daylight the basis carries, `null` without.
    pub daylight: Option<DaylightInfo>,
}

/// What a basis' daylight holds.
#[derive(Clone, Debug, Serialize)]
pub struct DaylightInfo {
    /// Latitude (° north), longitude (° east), elevation (m).
    pub site: [f32; 3],
    /// Compass bearing of the scene's +y axis, degrees.
    pub north_deg: f32,
    /// The site's UTC offset, minutes.
    pub utc_offset_minutes: f32,
    /// Sky patches (145: Tregenza).
    pub sky_patches: usize,
    /// The sun grid: declinations and hour angles.
    pub sun_grid: [usize; 2],
    /// Degrees between declinations and between hour angles.
    pub sun_step_deg: [f32; 2],
    /// The grid's nodes that light the room.
    pub sun_nodes: usize,
    /// Every daylight node: sky patches, the exterior, the sun nodes.
    pub nodes: usize,
}

fn names<'a>(
    count: usize,
    f: impl Fn(usize) -> std::result::Result<&'a str, eigenrad_runtime::Error>,
) -> std::result::Result<Vec<String>, eigenrad_runtime::Error> {
    (0..count).map(|i| f(i).map(str::to_owned)).collect()
}

/// `eigenrad inspect`.
pub fn inspect(path: &Path, bytes: &[u8]) -> Result<BasisInfo> {
    let b = Basis::from_bytes(bytes).map_err(basis_error(path))?;
    let e = basis_error(path);
    // The daylight's site and sun grid are printed: their values are checked first.
    b.check_daylight().map_err(&e)?;
    let mut zones = Vec::new();
    let mut grids = Vec::new();
    for z in 0..b.zone_count() {
        grids.push(b.grid_points(z).map_err(&e)?);
        zones.push((
            b.zone_name(z).map_err(&e)?.to_owned(),
            b.zone_area(z).map_err(&e)?,
        ));
    }
    Ok(BasisInfo {
        format_version: eigenrad_runtime::format::FORMAT_VERSION,
        bytes: b.byte_len(),
        unit: unit(b.quantity()),
        bands: band_names(b.bands()),
        formulation: b.formulation().name(),
        precision: b.precision().name(),
        patches: b.patch_count(),
        modes: b.mode_count(),
        surfaces: names(b.surface_count(), |i| b.surface_name(i)).map_err(&e)?,
        channels: names(b.channel_count(), |i| b.channel_name(i)).map_err(&e)?,
        sensors: names(b.sensor_count(), |i| b.sensor_name(i)).map_err(&e)?,
        zones,
        grids,
        eigenvalues: (0..b.mode_count())
            .map(|k| b.eigenvalue(0, k))
            .collect::<std::result::Result<_, _>>()
            .map_err(&e)?,
        daylight: match (b.site(), b.sky_patches(), b.sun_grid()) {
            (Some(site), Some(sky), Some(grid)) => Some(DaylightInfo {
                site: [site.latitude, site.longitude, site.elevation],
                north_deg: site.north,
                utc_offset_minutes: site.utc_offset_minutes,
                sky_patches: sky.count(),
                sun_grid: [grid.rows, grid.columns],
                sun_step_deg: [grid.declination_step, grid.hour_step],
                sun_nodes: b.sun_node_count(),
                nodes: b.daylight_node_count(),
            }),
            _ => None,
        },
    })
}

/// Human-readable `inspect`.
pub fn format_inspect(i: &BasisInfo) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "format v{}, {} bytes", i.format_version, i.bytes);
    let _ = writeln!(
        s,
        "{} patches, {} modes per band, bands: {} ({})",
        i.patches,
        i.modes,
        i.bands.join(" "),
        i.unit
    );
    let _ = writeln!(s, "formulation {}, storage {}", i.formulation, i.precision);
    let _ = writeln!(
        s,
        "surfaces ({}): {}",
        i.surfaces.len(),
        i.surfaces.join(", ")
    );
    let _ = writeln!(
        s,
        "channels ({}): {}",
        i.channels.len(),
        i.channels.join(", ")
    );
    let _ = writeln!(s, "sensors ({}): {}", i.sensors.len(), i.sensors.join(", "));
    let zones: Vec<String> = i
        .zones
        .iter()
        .zip(&i.grids)
        .map(|((n, a), g)| match g {
            0 => format!("{n} ({a:.2} m²)"),
            g => format!("{n} ({a:.2} m², grid of {g} points)"),
        })
        .collect();
    let _ = writeln!(s, "zones ({}): {}", i.zones.len(), zones.join(", "));
    let head: Vec<String> = i
        .eigenvalues
        .iter()
        .take(8)
        .map(|e| format!("{e:.4}"))
        .collect();
    let _ = writeln!(s, "leading eigenvalues (band 1): {}", head.join(" "));
    match &i.daylight {
        None => {
            let _ = writeln!(s, "daylight: none");
        }
        Some(d) => {
            let _ = writeln!(
                s,
                "daylight: site {:.4}° N {:.4}° E {:.0} m, north {:.1}°, UTC offset {:+.0} min; {} nodes: {} sky patches, the exterior, {} of the sun grid's {} × {} nodes ({:.2}° of declination by {:.2}° of hour angle)",
                d.site[0],
                d.site[1],
                d.site[2],
                d.north_deg,
                d.utc_offset_minutes,
                d.nodes,
                d.sky_patches,
                d.sun_nodes,
                d.sun_grid[0],
                d.sun_grid[1],
                d.sun_step_deg[0],
                d.sun_step_deg[1]
            );
        }
    }
    s
}
