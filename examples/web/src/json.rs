//! What the module tells the page as JSON text: what a basis holds, a sky state, an unmet
//! target. Numbers print as Rust prints `f64` (the shortest text that reads back to the same
//! number), so an `f32` from the runtime reaches the page unchanged; non-finite ones as null.

use std::fmt::Write;

use eigenrad_runtime::target::Output;
use eigenrad_runtime::{Basis, ChannelEvaluator, Error};

use crate::session::{Session, CHANNELS};
use crate::sun::SkyState;

/// A JSON string literal of `s`.
fn string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if u32::from(c) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A JSON number, or null when not finite.
fn number(x: f64) -> String {
    if x.is_finite() {
        format!("{x}")
    } else {
        "null".to_owned()
    }
}

fn numbers(xs: impl IntoIterator<Item = f64>) -> String {
    let list: Vec<String> = xs.into_iter().map(number).collect();
    format!("[{}]", list.join(","))
}

fn wide(xs: [f32; 3]) -> String {
    numbers(xs.map(f64::from))
}

/// What `session`'s basis holds: counts, names, sensors' placement, zones and their grids,
/// each channel's emitting patches and where on each grid it lights most, the daylight's site.
pub fn info(session: &Session) -> Result<String, Error> {
    let b = &session.basis;
    let mut out = String::new();
    let _ = write!(
        out,
        "{{\"bytes\":{},\"bands\":{},\"quantity\":{},\"formulation\":{},\"precision\":{},\
         \"patches\":{},\"modes\":{},\"surfaces\":{},",
        b.byte_len(),
        b.bands(),
        string(&format!("{:?}", b.quantity())),
        string(&format!("{:?}", b.formulation())),
        string(&format!("{:?}", b.precision())),
        b.patch_count(),
        b.mode_count(),
        b.surface_count()
    );
    // The room seen from above: the extent of the patches' centroids, m.
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in 0..b.patch_count() {
        let c = b.patch(p)?.centroid;
        for k in 0..2 {
            lo[k] = lo[k].min(f64::from(c[k]));
            hi[k] = hi[k].max(f64::from(c[k]));
        }
    }
    let _ = write!(out, "\"extent\":[{},{}],", numbers(lo), numbers(hi));
    // Each channel's emitting patches, and the grid point of each zone it lights most with
    // the others off: where a luminaire with photometry (a point source, not a patch) sits
    // on the plan.
    let mut alone = ChannelEvaluator::<1, CHANNELS>::new(*b)?;
    let zeros = vec![0.0f32; b.channel_count()];
    let mut channels = Vec::new();
    for c in 0..b.channel_count() {
        let mut emitters = Vec::new();
        for p in 0..b.patch_count() {
            let info = b.patch(p)?;
            if info.channel == Some(c) {
                emitters.push(wide(info.centroid));
            }
        }
        alone.set_channel_levels(&zeros)?;
        alone.set_channel_level(c, 1.0)?;
        let mut brightest = Vec::new();
        for z in 0..b.zone_count() {
            let mut best: Option<(usize, f32)> = None;
            for i in 0..b.grid_points(z)? {
                let [e] = alone.grid_point_irradiance(z, i)?;
                if best.is_none_or(|(_, v)| e > v) {
                    best = Some((i, e));
                }
            }
            brightest.push(best.map_or("null".to_owned(), |(i, _)| i.to_string()));
        }
        channels.push(format!(
            "{{\"name\":{},\"emitters\":[{}],\"brightest_point\":[{}]}}",
            string(b.channel_name(c)?),
            emitters.join(","),
            brightest.join(",")
        ));
    }
    let _ = write!(out, "\"channels\":[{}],", channels.join(","));
    let mut sensors = Vec::new();
    for s in 0..b.sensor_count() {
        let info = b.sensor(s)?;
        sensors.push(format!(
            "{{\"name\":{},\"position\":{},\"normal\":{},\"half_angle_deg\":{}}}",
            string(b.sensor_name(s)?),
            wide(info.position),
            wide(info.normal),
            number(f64::from(info.half_angle).to_degrees())
        ));
    }
    let _ = write!(out, "\"sensors\":[{}],", sensors.join(","));
    let mut zones = Vec::new();
    for z in 0..b.zone_count() {
        let grid = if b.grid_points(z)? > 0 {
            let g = session.grid(z)?;
            let points: Vec<String> = g.points.iter().map(|p| numbers(*p)).collect();
            format!(
                "{{\"pieces\":{},\"counts\":[{},{}],\"cell\":{},\"points\":[{}]}}",
                g.pieces,
                g.counts[0],
                g.counts[1],
                numbers(g.cell),
                points.join(",")
            )
        } else {
            "null".to_owned()
        };
        zones.push(format!(
            "{{\"name\":{},\"area\":{},\"grid\":{}}}",
            string(b.zone_name(z)?),
            number(f64::from(b.zone_area(z)?)),
            grid
        ));
    }
    let _ = write!(out, "\"zones\":[{}],", zones.join(","));
    let daylight = match (b.site(), b.sky_patches()) {
        (Some(site), Some(patches)) => format!(
            "{{\"latitude\":{},\"longitude\":{},\"elevation\":{},\"north\":{},\
             \"utc_offset_minutes\":{},\"sky_patches\":{},\"sun_nodes\":{}}}",
            number(f64::from(site.latitude)),
            number(f64::from(site.longitude)),
            number(f64::from(site.elevation)),
            number(f64::from(site.north)),
            number(f64::from(site.utc_offset_minutes)),
            patches.count(),
            b.sun_node_count()
        ),
        _ => "null".to_owned(),
    };
    let _ = write!(out, "\"daylight\":{daylight}}}");
    Ok(out)
}

/// A sky state's sun and illuminances (degrees, lux).
pub fn sky(state: &SkyState) -> String {
    format!(
        "{{\"altitude\":{},\"azimuth\":{},\"diffuse_horizontal\":{},\"direct_normal\":{},\
         \"global_horizontal\":{}}}",
        number(state.altitude),
        number(state.azimuth),
        number(state.diffuse_horizontal),
        number(state.direct_normal),
        number(state.global_horizontal)
    )
}

/// The solver's verdict on an unmet target, naming the bound's reading.
pub fn unmet(basis: &Basis<'_>, bounds: &[(Output, f32, f32)], e: Error) -> String {
    if let Error::BoundUnmet { bound, upper, by } = e {
        let name = match bounds.get(bound).map(|b| b.0) {
            Some(Output::Sensor(s)) => basis.sensor_name(s).unwrap_or("?"),
            Some(Output::Zone(z)) => basis.zone_name(z).unwrap_or("?"),
            None => "?",
        };
        let side = if upper { "over" } else { "short" };
        format!("{name}: {by:.1} lux {side} at the least violation")
    } else {
        e.to_string()
    }
}
