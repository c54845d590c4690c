//! eigenrad in the browser: `eigenrad-runtime` compiled to WebAssembly
//! (`wasm32-unknown-unknown`) behind plain `extern "C"` exports, for the commissioning page in
//! `www/` (`scripts/web.sh` builds and serves both; the README's "In the browser").
//!
//! The page hands the module a basis file's bytes, the very bytes a firmware reads from
//! flash, and asks for readings through the runtime's evaluators: no number shown is computed
//! twice. The calling convention stays within numbers: the page writes its inputs into
//! buffers the module lends (`input_bytes`, `input_numbers`), calls an export, and reads the
//! answer from the module's memory at `values_ptr` (`f64`), `colours_ptr` (RGB bytes) or
//! `text_ptr`/`text_len` (UTF-8: JSON, or the error message when an export returns a
//! negative status). Illuminance and exitance are in lux, positions in m, power in W.
//!
//! Exports use no `unsafe` code: Rust only hands out pointers to its own vectors, and reads
//! them back as the vectors they are. An opened basis stays in memory while the page is open
//! (its bytes are leaked so that the runtime's `Basis<'static>` can borrow them).

mod json;
mod plan;
mod session;
mod sun;

use std::cell::RefCell;

use eigenrad_runtime::target::Output;
use eigenrad_runtime::{dali, Error};

use session::Session;
use sun::{Moment, SkyInput};

/// The page's state: the opened basis, and the buffers of the calling convention.
#[derive(Default)]
struct Page {
    session: Option<Session>,
    input_bytes: Vec<u8>,
    input_numbers: Vec<f64>,
    values: Vec<f64>,
    colours: Vec<u8>,
    text: String,
}

thread_local! {
    static PAGE: RefCell<Page> = RefCell::new(Page::default());
}

/// Status of an export that failed: its message is in the text buffer.
const FAILED: i32 = -1;

fn with_page<T>(f: impl FnOnce(&mut Page) -> T) -> T {
    PAGE.with(|p| f(&mut p.borrow_mut()))
}

/// Runs `f` on the opened basis; its error (or the lack of a basis) becomes the text and
/// [`FAILED`].
fn with_session(
    f: impl FnOnce(&mut Session, &mut Vec<f64>, &mut Vec<u8>, &mut String) -> Result<i32, String>,
) -> i32 {
    with_page(|page| {
        let Page {
            session,
            values,
            colours,
            text,
            ..
        } = page;
        let result = match session.as_mut() {
            Some(s) => f(s, values, colours, text),
            None => Err("no basis is open".to_owned()),
        };
        result.unwrap_or_else(|message| {
            *text = message;
            FAILED
        })
    })
}

fn message(e: Error) -> String {
    e.to_string()
}

/// Lends `len` bytes for the page to write a basis file into; their address.
#[no_mangle]
pub extern "C" fn input_bytes(len: usize) -> *mut u8 {
    with_page(|p| {
        p.input_bytes = vec![0; len];
        p.input_bytes.as_mut_ptr()
    })
}

/// Lends `len` numbers for the page's inputs to [`solve`]; their address.
#[no_mangle]
pub extern "C" fn input_numbers(len: usize) -> *mut f64 {
    with_page(|p| {
        p.input_numbers = vec![0.0; len];
        p.input_numbers.as_mut_ptr()
    })
}

/// The numbers of the last answer.
#[no_mangle]
pub extern "C" fn values_ptr() -> *const f64 {
    with_page(|p| p.values.as_ptr())
}

/// The colours of the last [`plan`]: 8-bit RGB per grid point.
#[no_mangle]
pub extern "C" fn colours_ptr() -> *const u8 {
    with_page(|p| p.colours.as_ptr())
}

/// The text of the last answer (JSON, or an error message).
#[no_mangle]
pub extern "C" fn text_ptr() -> *const u8 {
    with_page(|p| p.text.as_ptr())
}

#[no_mangle]
pub extern "C" fn text_len() -> usize {
    with_page(|p| p.text.len())
}

/// Opens the basis in the input bytes: 0, and what it holds as JSON in the text buffer; or
/// [`FAILED`] with the runtime's reason (the previous basis stays open).
#[no_mangle]
pub extern "C" fn open() -> i32 {
    with_page(|page| {
        let bytes: &'static [u8] = Vec::leak(std::mem::take(&mut page.input_bytes));
        match Session::open(bytes).and_then(|s| json::info(&s).map(|info| (s, info))) {
            Ok((session, info)) => {
                page.session = Some(session);
                page.text = info;
                0
            }
            Err(e) => {
                page.text = format!("not a basis the page can show: {e}");
                FAILED
            }
        }
    })
}

/// Sets channel `channel`'s level (relative, 1 = as built).
#[no_mangle]
pub extern "C" fn set_level(channel: usize, level: f32) -> i32 {
    with_session(|s, _, _, _| s.set_level(channel, level).map(|()| 0).map_err(message))
}

/// Sets channel `channel` to DALI arc power level `arc` (0–254, IEC 62386-102).
#[no_mangle]
pub extern "C" fn set_arc(channel: usize, arc: u32) -> i32 {
    with_session(|s, _, _, _| {
        let arc = u8::try_from(arc).map_err(|_| format!("arc power level {arc} is above 254"))?;
        s.set_arc(channel, arc).map(|()| 0).map_err(message)
    })
}

/// Every channel's level and the lowest DALI arc power level giving at least it (−1 above
/// level 1) into the values: `[level, arc]` per channel; the channel count.
#[no_mangle]
pub extern "C" fn levels() -> i32 {
    with_session(|s, values, _, _| {
        values.clear();
        for c in 0..s.basis.channel_count() {
            values.push(f64::from(s.channels.channel_level(c).map_err(message)?));
            values.push(s.arc(c).map_err(message)?.map_or(-1.0, f64::from));
        }
        Ok(s.basis.channel_count() as i32)
    })
}

/// The DALI arc power level's relative level (IEC 62386-102), for the page's arc field;
/// NaN for 255 and above.
#[no_mangle]
pub extern "C" fn arc_level(arc: u32) -> f64 {
    u8::try_from(arc)
        .ok()
        .and_then(|a| dali::arc_power_to_level(a).ok())
        .map_or(f64::NAN, f64::from)
}

/// The map's colours, darkest (lowest value) first, one per bin, into the colours: the
/// colour bar's. Returns the count.
#[no_mangle]
pub extern "C" fn bin_colours() -> i32 {
    with_page(|p| {
        p.colours.clear();
        for k in 0..plan::colour::LEVELS {
            p.colours.extend(plan::colour::Scale::bin_colour(k));
        }
        plan::colour::LEVELS as i32
    })
}

/// Every sensor's and then every zone's reading into the values: `[total, electric,
/// daylight]` each, lux; the count of readings.
#[no_mangle]
pub extern "C" fn readings() -> i32 {
    with_session(|s, values, _, _| {
        values.clear();
        for k in 0..s.basis.sensor_count() {
            let r = s.sensor(k).map_err(message)?;
            values.extend([r.total, r.electric, r.daylight]);
        }
        for z in 0..s.basis.zone_count() {
            let r = s.zone(z).map_err(message)?;
            values.extend([r.total, r.electric, r.daylight]);
        }
        Ok((s.basis.sensor_count() + s.basis.zone_count()) as i32)
    })
}

/// Zone `zone`'s plan: the values get `E_avg, E_min, E_max, U_o` (daylight and electric
/// light together), the scale's `min, max, step, bin width`, then every point's value, then
/// the isolux lines as `count, (level, lines, (points, x, y, ...) ...) ...`; the colours get
/// every point's RGB. Returns the point count.
#[no_mangle]
pub extern "C" fn plan(zone: usize) -> i32 {
    with_session(|s, values, colours, _| {
        let grid = s.grid(zone).map_err(message)?;
        let figures = s.figures(zone).map_err(message)?;
        let grid_values = s.grid_values(zone).map_err(message)?;
        let xy: Vec<[f64; 2]> = grid.points.iter().map(|p| [p[0], p[1]]).collect();
        let counts = if grid.pieces == 1 {
            grid.counts
        } else {
            [0, 0]
        };
        let plan = plan::plan(&grid_values, &xy, counts, grid.cell);
        values.clear();
        values.extend([
            f64::from(figures.average),
            f64::from(figures.minimum),
            f64::from(figures.maximum),
            f64::from(figures.uniformity),
            plan.scale.min,
            plan.scale.max,
            plan.scale.step,
            plan.scale.bin_width(),
        ]);
        values.extend(&grid_values);
        values.push(plan.isolux.len() as f64);
        for (level, lines) in &plan.isolux {
            values.extend([*level, lines.len() as f64]);
            for line in lines {
                values.push(line.len() as f64);
                values.extend(line.iter().flatten());
            }
        }
        colours.clear();
        colours.extend(plan.colours.iter().flatten());
        Ok(grid_values.len() as i32)
    })
}

fn moment(s: &Session, year: i32, month: u32, day: u32, minute: u32) -> Moment {
    let offset = s
        .basis
        .site()
        .map_or(0, |site| site.utc_offset_minutes.round() as i32);
    Moment {
        year,
        month,
        day,
        minute,
        offset,
    }
}

fn set_sky(year: i32, month: u32, day: u32, minute: u32, input: SkyInput) -> i32 {
    with_session(|s, _, _, text| {
        let m = moment(s, year, month, day, minute);
        let state = s.set_sky(m, input).map_err(|e| e.to_string())?;
        *text = json::sky(state);
        Ok(0)
    })
}

/// The CIE sky `sky_type` (1–15; 0 the traditional overcast sky) of `diffuse_horizontal` lux
/// with a sun of `direct_normal` lux, at `minute` after midnight of the date, the site's
/// standard time: `eval --time ... --cie TYPE --dhi-lux ... --dni-lux ...`. The sun's
/// position and the sky's figures as JSON into the text.
#[no_mangle]
pub extern "C" fn set_sky_cie(
    sky_type: u32,
    year: i32,
    month: u32,
    day: u32,
    minute: u32,
    diffuse_horizontal: f64,
    direct_normal: f64,
) -> i32 {
    let Ok(sky_type) = u8::try_from(sky_type) else {
        return with_page(|p| {
            p.text = format!("CIE sky type {sky_type} is not 0 to 15");
            FAILED
        });
    };
    set_sky(
        year,
        month,
        day,
        minute,
        SkyInput::Cie {
            sky_type,
            diffuse_horizontal,
            direct_normal,
        },
    )
}

/// The Perez sky from a direct normal and a diffuse horizontal irradiance (W/m²), or with
/// `illuminance` 1 illuminance (lux), and `water` cm of precipitable water: `eval --time ...
/// --dni --dhi` or `--dni-lux --dhi-lux`.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn set_sky_perez(
    illuminance: u32,
    year: i32,
    month: u32,
    day: u32,
    minute: u32,
    direct_normal: f64,
    diffuse_horizontal: f64,
    water: f64,
) -> i32 {
    let input = if illuminance == 1 {
        SkyInput::PerezIlluminance {
            direct_normal,
            diffuse_horizontal,
            water,
        }
    } else {
        SkyInput::PerezIrradiance {
            direct_normal,
            diffuse_horizontal,
            water,
        }
    };
    set_sky(year, month, day, minute, input)
}

/// Dark outside: no sky, no sun.
#[no_mangle]
pub extern "C" fn clear_sky() -> i32 {
    with_session(|s, _, _, _| s.clear_sky().map(|()| 0).map_err(message))
}

/// Patch `patch`'s exitance into the values: `[total, electric, daylight]`, lux.
#[no_mangle]
pub extern "C" fn patch_exitance(patch: usize) -> i32 {
    with_session(|s, values, _, _| {
        let r = s.patch_exitance(patch).map_err(message)?;
        values.clear();
        values.extend([r.total, r.electric, r.daylight]);
        Ok(0)
    })
}

/// The least-power levels for a target. The input numbers hold `controlled` channel indices,
/// their `controlled` weights (W at level 1), then `bounds` bounds of four numbers each:
/// kind (0 sensor, 1 zone), index, lower and upper bound (lux; upper may be +∞). Sets the
/// levels found; the values get `[power W, met (1 or 0)]`, and when a bound is unmet the text
/// says which. Returns 0, or [`FAILED`] for input the solver refuses.
#[no_mangle]
pub extern "C" fn solve(controlled: usize, bounds: usize) -> i32 {
    with_page(|page| {
        let input = std::mem::take(&mut page.input_numbers);
        let Page {
            session,
            values,
            text,
            ..
        } = page;
        let result = (|| {
            let s = session.as_mut().ok_or("no basis is open")?;
            let needed = 2 * controlled + 4 * bounds;
            let input = input
                .get(..needed)
                .ok_or(format!("the solver needs {needed} input numbers"))?;
            let (channels, rest) = input.split_at(controlled);
            let (weights, rest) = rest.split_at(controlled);
            let channels: Vec<usize> = channels.iter().map(|&c| c as usize).collect();
            let weights: Vec<f32> = weights.iter().map(|&w| w as f32).collect();
            let mut list = Vec::with_capacity(bounds);
            for b in rest.chunks_exact(4) {
                let output = match b[0] as u32 {
                    0 => Output::Sensor(b[1] as usize),
                    _ => Output::Zone(b[1] as usize),
                };
                list.push((output, b[2] as f32, b[3] as f32));
            }
            let (power, verdict) = s.solve(&channels, &weights, &list).map_err(message)?;
            values.clear();
            values.extend([f64::from(power), f64::from(u8::from(verdict.is_ok()))]);
            *text = match verdict {
                Ok(()) => String::new(),
                Err(e) => json::unmet(&s.basis, &list, e),
            };
            Ok::<i32, String>(0)
        })();
        result.unwrap_or_else(|m| {
            *text = m;
            FAILED
        })
    })
}
