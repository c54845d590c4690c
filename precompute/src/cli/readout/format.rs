//! A readout as text: the table `solve` and `eval` print, and the grid points as CSV.

use std::fmt::Write as _;

use super::{Reading, Readout};
use crate::cli::figures::fixed;
use crate::pipeline::{GridReadout, PieceLayout};

/// Every grid point of `r` as CSV: a header naming the units, then one line per point, zones
/// in basis order and points first side fastest, positions to 0.1 mm. Names are quoted
/// (doubling any quote).
pub fn grids_csv(r: &Readout) -> String {
    let unit = match r.unit {
        "lux" => "lux",
        "fc" => "fc",
        _ => "W_per_m2",
    };
    // With daylight, each point's daylight part follows its total, band by band.
    let daylight = r.daylight.as_ref().map(|d| &d.grids);
    let mut s = String::from("zone,point,x_m,y_m,z_m");
    for b in &r.bands {
        let _ = write!(s, ",{b}_{unit}");
    }
    if daylight.is_some() {
        for b in &r.bands {
            let _ = write!(s, ",daylight_{b}_{unit}");
        }
    }
    s.push('\n');
    for (k, g) in r.grids.iter().enumerate() {
        let zone = g.zone.replace('"', "\"\"");
        let day = daylight.and_then(|d| d.get(k));
        for (i, p) in g.points.iter().enumerate() {
            let [x, y, z] = p.position_m;
            let _ = write!(s, "\"{zone}\",{i},{x:.4},{y:.4},{z:.4}");
            let day_point = day.and_then(|d| d.points.get(i));
            let parts = day_point.map(|d| d.irradiance.as_slice()).unwrap_or(&[]);
            // `+ 0.0` turns a `-0.0` into `0`; every other value prints unchanged.
            for v in p.irradiance.iter().chain(parts) {
                let _ = write!(s, ",{}", v + 0.0);
            }
            s.push('\n');
        }
    }
    s
}

/// Two lines per grid: its layout (the standard's for a work plane or task area, the file's
/// for an imported grid, so not labelled), then its EN 12464-1 figures (`unit`: lux or W/m²).
pub(in crate::cli) fn write_grids(s: &mut String, grids: &[GridReadout], unit: &str) {
    let fmt = |v: &[f64]| v.iter().map(|&x| fixed(x, 4)).collect::<Vec<_>>().join(" ");
    let layout = |p: &PieceLayout| {
        let kept = if p.points < p.counts[0] * p.counts[1] {
            format!(" ({} on the area)", p.points)
        } else {
            String::new()
        };
        format!(
            "{} × {} points{kept}, spacing ≤ {:.3} m, cells {:.3} × {:.3} m, border {:.2} m",
            p.counts[0], p.counts[1], p.spacing_m, p.cell_m[0], p.cell_m[1], p.border_m
        )
    };
    for g in grids {
        match &g.pieces[..] {
            [one] => {
                let _ = writeln!(s, "grid   {:<20} {}", g.zone, layout(one));
            }
            pieces => {
                let _ = writeln!(
                    s,
                    "grid   {:<20} {} points in {} pieces",
                    g.zone,
                    g.points.len(),
                    pieces.len()
                );
                for (k, p) in pieces.iter().enumerate() {
                    let _ = writeln!(s, "       piece {:<14} {}", k + 1, layout(p));
                }
            }
        }
        if g.obstructed > 0 {
            let _ = writeln!(
                s,
                "       {} points inside obstacles left out",
                g.obstructed
            );
        }
        let _ = writeln!(
            s,
            "       E_avg {} {unit}, E_min {} {unit}, E_max {} {unit}, U_o {} (EN 12464-1)",
            fmt(&g.average),
            fmt(&g.minimum),
            fmt(&g.maximum),
            fmt(&g.uniformity),
        );
    }
}

/// A readout as a table, one line per sensor and zone (and per patch when it has them).
pub fn format_readout(r: &Readout) -> String {
    let fmt = |v: &[f64]| v.iter().map(|&x| fixed(x, 4)).collect::<Vec<_>>().join(" ");
    let mut s = String::new();
    let _ = writeln!(
        s,
        "levels: {}",
        r.levels
            .iter()
            .map(|l| match l.arc {
                Some(arc) => format!("{}={} (arc {arc})", l.name, l.level),
                None => format!("{}={}", l.name, l.level),
            })
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(s, "bands: {} ({})", r.bands.join(" "), r.unit);
    if let Some(d) = &r.daylight {
        let _ = writeln!(
            s,
            "daylight: {} at {}; sun altitude {:.2}°, azimuth {:.2}°; diffuse horizontal {:.1} lux, direct normal {:.1} lux, global horizontal {:.1} lux; {} sky patches ({}); through {}",
            d.model,
            d.time,
            d.sun.altitude,
            d.sun.azimuth,
            d.diffuse_horizontal_lux,
            d.direct_normal_lux,
            d.global_horizontal_lux,
            d.patch_count,
            d.patch_set,
            if d.windows.is_empty() {
                // A basis does not name its windows.
                "the windows".to_owned()
            } else {
                d.windows.join(", ")
            }
        );
        if d.sun_below_horizon {
            let _ = writeln!(
                s,
                "daylight: the sun is below the horizon: the sky's light alone, no direct sun"
            );
        }
        for note in &d.notes {
            let _ = writeln!(s, "daylight: note: {note}");
        }
    }
    // With daylight, each reading is followed by its two parts.
    let parts = |x: &Reading| match (&x.daylight, &x.electric) {
        (Some(d), Some(e)) => format!(" = daylight {} + electric {}", fmt(d), fmt(e)),
        _ => String::new(),
    };
    for x in &r.sensors {
        let _ = writeln!(
            s,
            "sensor {:<20} {} {}{}",
            x.name,
            fmt(&x.irradiance),
            r.unit,
            parts(x)
        );
    }
    for z in &r.zones {
        let _ = writeln!(
            s,
            "zone   {:<20} {} {} (average){}",
            z.name,
            fmt(&z.irradiance),
            r.unit,
            parts(z)
        );
    }
    write_grids(&mut s, &r.grids, r.unit);
    if let Some(d) = &r.daylight {
        if !d.grids.is_empty() {
            let _ = writeln!(s, "under daylight alone:");
            write_grids(&mut s, &d.grids, r.unit);
        }
    }
    if let Some(patches) = &r.patches {
        let _ = writeln!(
            s,
            "{:>6} {:<20} {:>10} {:>28} {:>28}",
            "patch", "surface", "area m²", "exitance", "irradiance"
        );
        for p in patches {
            let e = p.irradiance.as_deref().map_or("-".into(), fmt);
            let _ = writeln!(
                s,
                "{:>6} {:<20} {:>10.5} {:>28} {:>28}",
                p.id,
                p.surface,
                p.area,
                fmt(&p.exitance),
                e
            );
        }
    }
    s
}
