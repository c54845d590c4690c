//! NREL's TMY3 CSV (S. Wilcox and W. Marion, "Users Manual for TMY3 Data Sets",
//! NREL/TP-581-43156, National Renewable Energy Laboratory, 2008).
//!
//! Line 1 is the site: `USAF,Name,State,TZ,latitude,longitude,elevation` (the time zone in
//! hours from UTC, the elevation in metres). Line 2 names the columns; each further line is
//! one hour, `MM/DD/YYYY,HH:MM,…`, the time `01:00` to `24:00` ending the hour in local
//! standard time. The columns are found by their names:
//!
//! | column | quantity | unit |
//! |---|---|---|
//! | `Date (MM/DD/YYYY)`, `Time (HH:MM)` | date and hour ending | |
//! | `GHI (W/m^2)`, `DNI (W/m^2)`, `DHI (W/m^2)` | global, direct normal and diffuse irradiance, the hour's mean (required) | W/m² |
//! | `GH illum (lx)`, `DN illum (lx)`, `DH illum (lx)` | illuminances (optional) | written as lx, in fact hundreds of lux ([`super::Illuminance`]) |
//! | `Dew-point (C)`, `Dry-bulb (C)` | temperatures (optional) | °C |
//!
//! Every value is taken as written. Each column has a source flag beside it, and NREL's
//! earlier data sets flag missing data `?` ("used mostly for missing data", the TMY2 and
//! NSRDB 1961–1990 manuals); the TMY3 manual's own flag tables could not be checked here, so
//! no flag makes a value missing. In Greensboro's file none of these columns is flagged `?`.

use std::collections::HashMap;
use std::path::Path;

use super::text::{self, File};
use super::{Format, Location, Record, Result, Weather};

/// The column names this reader looks for, as TMY3 files write them.
pub mod column {
    /// The record's date, `MM/DD/YYYY`.
    pub const DATE: &str = "Date (MM/DD/YYYY)";
    /// The hour the record ends, `HH:MM`, `01:00` to `24:00`.
    pub const TIME: &str = "Time (HH:MM)";
    /// Global horizontal irradiance, W/m².
    pub const GHI: &str = "GHI (W/m^2)";
    /// Direct normal irradiance, W/m².
    pub const DNI: &str = "DNI (W/m^2)";
    /// Diffuse horizontal irradiance, W/m².
    pub const DHI: &str = "DHI (W/m^2)";
    /// Global horizontal illuminance.
    pub const GH_ILLUM: &str = "GH illum (lx)";
    /// Direct normal illuminance.
    pub const DN_ILLUM: &str = "DN illum (lx)";
    /// Diffuse horizontal illuminance.
    pub const DH_ILLUM: &str = "DH illum (lx)";
    /// Dew-point temperature, °C.
    pub const DEW_POINT: &str = "Dew-point (C)";
    /// Dry-bulb temperature, °C.
    pub const DRY_BULB: &str = "Dry-bulb (C)";
}

/// A column's 0-based index and its name in messages.
struct Column {
    index: usize,
    name: String,
}

/// Parses a TMY3 CSV's text; `path` is for messages.
pub fn parse_tmy3(path: &Path, text: &str) -> Result<Weather> {
    let file = File::new(path);
    let mut lines = text::lines(text);
    let Some((_, first)) = lines.next() else {
        return Err(file.error(Some(1), None, "the file is empty"));
    };
    let location = location(&file, first)?;
    let Some((_, second)) = lines.next() else {
        return Err(file.error(
            Some(1),
            None,
            "the file ends after its first line; line 2 names the columns",
        ));
    };
    let headers = text::fields(second);
    let positions: HashMap<&str, usize> = headers
        .iter()
        .enumerate()
        .map(|(i, h)| (h.as_ref(), i))
        .collect();
    let column = |name: &str| {
        positions.get(name).map(|&index| Column {
            index,
            name: format!("`{name}` (column {})", index + 1),
        })
    };
    let required = |name: &str| {
        column(name).ok_or_else(|| {
            file.at(
                2,
                &format!("`{name}`"),
                "no such column; a TMY3 file's second line names its columns",
            )
        })
    };
    let date = required(column::DATE)?;
    let time = required(column::TIME)?;
    let ghi = required(column::GHI)?;
    let dni = required(column::DNI)?;
    let dhi = required(column::DHI)?;
    let gh_illum = column(column::GH_ILLUM);
    let dn_illum = column(column::DN_ILLUM);
    let dh_illum = column(column::DH_ILLUM);
    let dew_point = column(column::DEW_POINT);
    let dry_bulb = column(column::DRY_BULB);

    let mut records = Vec::with_capacity(8784);
    let mut last_line = 2;
    let mut blank = None;
    for (n, line) in lines {
        if line.trim().is_empty() {
            blank.get_or_insert(n);
            last_line = n;
            continue;
        }
        if let Some(blank) = blank {
            return Err(file.error(Some(blank), None, "an empty line among the records"));
        }
        last_line = n;
        let f = text::fields(line);
        if f.len() != headers.len() {
            return Err(file.at(
                n,
                "record",
                format!(
                    "{} comma-separated fields expected (one a column named on line 2), found {}",
                    headers.len(),
                    f.len()
                ),
            ));
        }
        let (month, day, year) = parse_date(&file, n, &date.name, &f[date.index])?;
        let hour = parse_hour(&file, n, &time.name, &f[time.index])?;
        let irradiance = |c: &Column| file.irradiance(n, &c.name, &f[c.index]);
        let illuminance = |c: &Option<Column>| {
            c.as_ref()
                .map(|c| file.illuminance(n, &c.name, &f[c.index]))
                .transpose()
        };
        let temperature = |c: &Option<Column>| {
            c.as_ref()
                .map(|c| file.temperature(n, &c.name, &f[c.index]))
                .transpose()
        };
        records.push(Record {
            line: n,
            month,
            day,
            hour,
            year,
            global_horizontal: irradiance(&ghi)?,
            direct_normal: irradiance(&dni)?,
            diffuse_horizontal: irradiance(&dhi)?,
            global_horizontal_lux: illuminance(&gh_illum)?,
            direct_normal_lux: illuminance(&dn_illum)?,
            diffuse_horizontal_lux: illuminance(&dh_illum)?,
            dew_point: temperature(&dew_point)?,
            dry_bulb: temperature(&dry_bulb)?,
        });
    }
    file.finish(Format::Tmy3, location, records, last_line)
}

/// The site, from line 1: `USAF,Name,State,TZ,latitude,longitude,elevation`.
fn location(file: &File, line: &str) -> Result<Location> {
    let f = text::fields(line);
    if f.len() < 7 {
        return Err(file.at(
            1,
            "site",
            format!(
                "7 comma-separated fields expected (USAF, name, state, time zone, latitude, \
                 longitude, elevation), found {}",
                f.len()
            ),
        ));
    }
    Ok(Location {
        name: f[1].to_string(),
        region: f[2].to_string(),
        country: String::new(),
        station: f[0].to_string(),
        utc_offset_hours: file.number_in(1, "time zone (field 4)", &f[3], -12.0..=14.0, "h")?,
        latitude: file.number_in(1, "latitude (field 5)", &f[4], -90.0..=90.0, "°")?,
        longitude: file.number_in(1, "longitude (field 6)", &f[5], -180.0..=180.0, "°")?,
        elevation: file.number_in(1, "elevation (field 7)", &f[6], -1000.0..=9999.9, "m")?,
    })
}

/// `MM/DD/YYYY` as (month, day, year).
fn parse_date(file: &File, n: usize, field: &str, text: &str) -> Result<(u8, u8, i32)> {
    let parts: Vec<&str> = text.split('/').collect();
    let [month, day, year] = parts[..] else {
        return Err(file.at(n, field, format!("`{text}` is not a date MM/DD/YYYY")));
    };
    let month = file.integer(n, field, month, 1, 12)? as u8;
    let day = file.integer(n, field, day, 1, i64::from(text::max_days(month)))? as u8;
    let year = file.integer(n, field, year, -9999, 9999)? as i32;
    Ok((month, day, year))
}

/// `HH:MM`, `01:00` to `24:00`, as the hour ending (1 to 24).
fn parse_hour(file: &File, n: usize, field: &str, text: &str) -> Result<u8> {
    let Some((hour, minutes)) = text.split_once(':') else {
        return Err(file.at(n, field, format!("`{text}` is not a time HH:MM")));
    };
    let hour = file.integer(n, field, hour, 1, 24)? as u8;
    if minutes != "00" {
        return Err(file.at(
            n,
            field,
            format!("`{text}`: an hourly file's times are whole hours, `01:00` to `24:00`"),
        ));
    }
    Ok(hour)
}
