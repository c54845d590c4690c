//! The EnergyPlus weather file (EPW), as its data dictionary defines it (EnergyPlus
//! Auxiliary Programs, "Weather Converter Program": "EnergyPlus Weather File (EPW) Data
//! Dictionary").
//!
//! Eight header lines (`LOCATION`, `DESIGN CONDITIONS`, `TYPICAL/EXTREME PERIODS`, `GROUND
//! TEMPERATURES`, `HOLIDAYS/DAYLIGHT SAVINGS`, `COMMENTS 1`, `COMMENTS 2`, `DATA PERIODS`),
//! then one record a line of 35 comma-separated fields. Of the header this reader takes the
//! site from `LOCATION` (city, state, country, source, WMO, latitude, longitude, time zone,
//! elevation) and checks that `DATA PERIODS` announces one record per hour. Of a record it
//! takes the fields below, numbered by their place in the line; the dictionary says a value
//! at or above its missing code is missing.
//!
//! | field | quantity | unit | missing |
//! |---|---|---|---|
//! | 1–4 | year, month, day, hour (1–24, hour 1 is 00:01–01:00) | | never |
//! | 5 | minute (read, not used: hourly files write 0 or 60) | | |
//! | 7 | dry bulb temperature | °C | 99.9 |
//! | 8 | dew point temperature | °C | 99.9 |
//! | 14 | global horizontal radiation | Wh/m² | 9999 (an error here) |
//! | 15 | direct normal radiation | Wh/m² | 9999 (an error here) |
//! | 16 | diffuse horizontal radiation | Wh/m² | 9999 (an error here) |
//! | 17 | global horizontal illuminance | lux | 999900 and above |
//! | 18 | direct normal illuminance | lux | 999900 and above |
//! | 19 | diffuse horizontal illuminance | lux | 999900 and above |
//!
//! The radiation fields are energies over the hour ending at the record's hour, so their
//! Wh/m² are the hour's mean W/m².

use std::path::Path;

use super::text::{self, File};
use super::{Format, Location, Record, Result, Weather};

/// The fields of a record: the data dictionary's N1–N34 and A1.
pub const FIELDS: usize = 35;

/// The irradiance fields' missing code, Wh/m²: at or above it a value is missing.
pub const MISSING_IRRADIANCE: f64 = 9999.0;
/// The illuminance fields' missing code, lux: at or above it a value is missing (the
/// dictionary writes 999999 and counts 999900 and above as missing).
pub const MISSING_ILLUMINANCE: f64 = 999_900.0;
/// The temperature fields' missing code, °C.
pub const MISSING_TEMPERATURE: f64 = 99.9;

/// The header lines before the first record.
pub const HEADER_LINES: usize = 8;

/// A record field's 0-based index and its name in messages.
struct Field(usize, &'static str);

const YEAR: Field = Field(0, "year (field 1)");
const MONTH: Field = Field(1, "month (field 2)");
const DAY: Field = Field(2, "day (field 3)");
const HOUR: Field = Field(3, "hour (field 4)");
const MINUTE: Field = Field(4, "minute (field 5)");
const DRY_BULB: Field = Field(6, "dry bulb temperature (field 7)");
const DEW_POINT: Field = Field(7, "dew point temperature (field 8)");
const GLOBAL: Field = Field(13, "global horizontal radiation (field 14)");
const DIRECT: Field = Field(14, "direct normal radiation (field 15)");
const DIFFUSE: Field = Field(15, "diffuse horizontal radiation (field 16)");
const GLOBAL_LUX: Field = Field(16, "global horizontal illuminance (field 17)");
const DIRECT_LUX: Field = Field(17, "direct normal illuminance (field 18)");
const DIFFUSE_LUX: Field = Field(18, "diffuse horizontal illuminance (field 19)");

/// Parses an EPW's text; `path` is for messages.
pub fn parse_epw(path: &Path, text: &str) -> Result<Weather> {
    let file = File::new(path);
    let mut lines = text::lines(text);
    let mut header = Vec::with_capacity(HEADER_LINES);
    let mut last_line = 0;
    for (n, line) in lines.by_ref().take(HEADER_LINES) {
        header.push(line);
        last_line = n;
    }
    if header.len() < HEADER_LINES {
        return Err(file.error(
            Some(last_line.max(1)),
            None,
            format!(
                "the file ends inside the header: an EPW has {HEADER_LINES} header lines \
                 (LOCATION to DATA PERIODS) before its records"
            ),
        ));
    }
    let location = location(&file, header[0])?;
    data_periods(&file, header[HEADER_LINES - 1])?;

    let mut records = Vec::with_capacity(8784);
    // Blank lines at the end of a file are common; among the records, an error.
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
        records.push(record(&file, n, line)?);
        last_line = n;
    }
    file.finish(Format::Epw, location, records, last_line)
}

/// The site, from the `LOCATION` line.
fn location(file: &File, line: &str) -> Result<Location> {
    let f = text::fields(line);
    if f[0] != "LOCATION" {
        return Err(file.error(
            Some(1),
            None,
            format!("an EPW starts with a `LOCATION,` line, not `{line}`"),
        ));
    }
    if f.len() < 10 {
        return Err(file.at(
            1,
            "LOCATION",
            format!(
                "10 comma-separated fields expected (LOCATION, city, state, country, source, \
                 WMO, latitude, longitude, time zone, elevation), found {}",
                f.len()
            ),
        ));
    }
    Ok(Location {
        name: f[1].to_string(),
        region: f[2].to_string(),
        country: f[3].to_string(),
        station: f[5].to_string(),
        latitude: file.number_in(1, "latitude (LOCATION field 7)", &f[6], -90.0..=90.0, "°")?,
        longitude: file.number_in(
            1,
            "longitude (LOCATION field 8)",
            &f[7],
            -180.0..=180.0,
            "°",
        )?,
        // The dictionary says −12 to +12; the Line Islands keep +14.
        utc_offset_hours: file.number_in(
            1,
            "time zone (LOCATION field 9)",
            &f[8],
            -12.0..=14.0,
            "h",
        )?,
        elevation: file.number_in(
            1,
            "elevation (LOCATION field 10)",
            &f[9],
            -1000.0..=9999.9,
            "m",
        )?,
    })
}

/// Checks the `DATA PERIODS` line: one record per hour.
fn data_periods(file: &File, line: &str) -> Result<()> {
    let f = text::fields(line);
    if f[0] != "DATA PERIODS" {
        return Err(file.error(
            Some(HEADER_LINES),
            None,
            format!(
                "line {HEADER_LINES} of an EPW is its DATA PERIODS header, not `{}`",
                truncate(line)
            ),
        ));
    }
    if f.len() < 3 {
        return Err(file.at(
            HEADER_LINES,
            "DATA PERIODS",
            "the number of data periods and of records per hour are missing",
        ));
    }
    file.integer(
        HEADER_LINES,
        "number of data periods (DATA PERIODS field 2)",
        &f[1],
        1,
        366,
    )?;
    let per_hour = file.integer(
        HEADER_LINES,
        "records per hour (DATA PERIODS field 3)",
        &f[2],
        1,
        60,
    )?;
    if per_hour != 1 {
        return Err(file.at(
            HEADER_LINES,
            "records per hour (DATA PERIODS field 3)",
            format!(
                "{per_hour} records per hour; eigenrad reads hourly weather (1 record per hour)"
            ),
        ));
    }
    Ok(())
}

/// The first 60 characters of a line, for messages.
fn truncate(line: &str) -> String {
    match line.char_indices().nth(60) {
        Some((i, _)) => format!("{}…", &line[..i]),
        None => line.to_owned(),
    }
}

/// One record.
fn record(file: &File, n: usize, line: &str) -> Result<Record> {
    let f = text::fields(line);
    if f.len() < FIELDS {
        return Err(file.at(
            n,
            "record",
            format!(
                "{FIELDS} comma-separated fields expected (year, month, day, hour, minute, data \
                 source, dry bulb, … liquid precipitation quantity), found {}",
                f.len()
            ),
        ));
    }
    let get = |field: &Field| -> &str { &f[field.0] };
    let month = file.integer(n, MONTH.1, get(&MONTH), 1, 12)? as u8;
    let day = file.integer(n, DAY.1, get(&DAY), 1, i64::from(text::max_days(month)))? as u8;
    let hour = file.integer(n, HOUR.1, get(&HOUR), 1, 24)? as u8;
    let year = file.integer(n, YEAR.1, get(&YEAR), -9999, 9999)? as i32;
    file.integer(n, MINUTE.1, get(&MINUTE), 0, 60)?;
    let irradiance = |field: &Field| -> Result<f64> {
        let value = file.number(n, field.1, get(field))?;
        if value >= MISSING_IRRADIANCE {
            return Err(file.at(
                n,
                field.1,
                format!(
                    "{value} marks it missing; the simulation needs every hour's global, \
                     direct and diffuse radiation (fill the gap, as EnergyPlus's Weather \
                     Converter does, before using the file)"
                ),
            ));
        }
        file.irradiance(n, field.1, get(field))
    };
    let illuminance = |field: &Field| -> Result<Option<f64>> {
        let value = file.number(n, field.1, get(field))?;
        if value >= MISSING_ILLUMINANCE {
            return Ok(None);
        }
        file.illuminance(n, field.1, get(field)).map(Some)
    };
    let temperature = |field: &Field| -> Result<Option<f64>> {
        let value = file.number(n, field.1, get(field))?;
        if value >= MISSING_TEMPERATURE {
            return Ok(None);
        }
        file.temperature(n, field.1, get(field)).map(Some)
    };
    Ok(Record {
        line: n,
        month,
        day,
        hour,
        year,
        dry_bulb: temperature(&DRY_BULB)?,
        dew_point: temperature(&DEW_POINT)?,
        global_horizontal: irradiance(&GLOBAL)?,
        direct_normal: irradiance(&DIRECT)?,
        diffuse_horizontal: irradiance(&DIFFUSE)?,
        global_horizontal_lux: illuminance(&GLOBAL_LUX)?,
        direct_normal_lux: illuminance(&DIRECT_LUX)?,
        diffuse_horizontal_lux: illuminance(&DIFFUSE_LUX)?,
    })
}
