//! What both readers share: numbered lines, comma-separated fields, numbers that must be
//! finite and in range, errors that carry the file, line and field, and the checks on a
//! year's records (consecutive hours, whole days, the illuminances' unit).

use std::borrow::Cow;
use std::path::Path;

use super::{Format, Illuminance, Location, Record, Result, Weather, WeatherError};

/// The most an hour's mean irradiance can be at the ground, W/m²: above the solar constant
/// (1361 W/m², G. Kopp and J. L. Lean, Geophysical Research Letters 38, L01706, 2011), so a
/// larger value is another unit (J/m², kJ/m²) or a fault.
pub(super) const IRRADIANCE_MAX: f64 = 1500.0;

/// The range of air temperatures the EPW data dictionary allows (dry bulb and dew point,
/// −70 °C to 70 °C); TMY3's are held to the same.
pub(super) const TEMPERATURE_RANGE: std::ops::RangeInclusive<f64> = -70.0..=70.0;

/// The file being read, for error messages.
#[derive(Clone, Copy)]
pub(super) struct File<'a> {
    pub path: &'a Path,
}

impl<'a> File<'a> {
    pub fn new(path: &'a Path) -> Self {
        File { path }
    }

    /// An error at `line` (if any) in `field` (if any).
    pub fn error(
        &self,
        line: Option<usize>,
        field: Option<&str>,
        reason: impl Into<String>,
    ) -> WeatherError {
        WeatherError {
            path: self.path.to_path_buf(),
            line,
            field: field.map(str::to_owned),
            reason: reason.into(),
        }
    }

    /// An error in `field` at `line`.
    pub fn at(&self, line: usize, field: &str, reason: impl Into<String>) -> WeatherError {
        self.error(Some(line), Some(field), reason)
    }

    /// A finite number.
    pub fn number(&self, line: usize, field: &str, text: &str) -> Result<f64> {
        let value: f64 = text
            .parse()
            .map_err(|_| self.at(line, field, format!("`{text}` is not a number")))?;
        if value.is_finite() {
            Ok(value)
        } else {
            // `f64::from_str` reads "inf" and "NaN"; neither is a measurement.
            Err(self.at(line, field, format!("`{text}` is not a finite number")))
        }
    }

    /// A number in `range`, `unit` its unit in the message (`°`, `h`, `m`, `°C`).
    pub fn number_in(
        &self,
        line: usize,
        field: &str,
        text: &str,
        range: std::ops::RangeInclusive<f64>,
        unit: &str,
    ) -> Result<f64> {
        let value = self.number(line, field, text)?;
        if range.contains(&value) {
            Ok(value)
        } else {
            Err(self.at(
                line,
                field,
                format!(
                    "{value} {unit} is outside {} to {} {unit}",
                    range.start(),
                    range.end()
                ),
            ))
        }
    }

    /// A whole number written without a decimal point, in `min..=max`.
    pub fn integer(&self, line: usize, field: &str, text: &str, min: i64, max: i64) -> Result<i64> {
        let value: i64 = text
            .parse()
            .map_err(|_| self.at(line, field, format!("`{text}` is not a whole number")))?;
        if (min..=max).contains(&value) {
            Ok(value)
        } else {
            Err(self.at(line, field, format!("{value} is outside {min} to {max}")))
        }
    }

    /// An hour's mean irradiance, W/m²: not negative, not above [`IRRADIANCE_MAX`].
    pub fn irradiance(&self, line: usize, field: &str, text: &str) -> Result<f64> {
        let value = self.number(line, field, text)?;
        if value < 0.0 {
            Err(self.at(line, field, format!("{value} W/m² is negative")))
        } else if value > IRRADIANCE_MAX {
            Err(self.at(
                line,
                field,
                format!(
                    "{value} W/m² is more than any hour's sunlight at the ground \
                     ({IRRADIANCE_MAX} W/m²); is the file in another unit?"
                ),
            ))
        } else {
            Ok(value)
        }
    }

    /// An illuminance, lux as written: not negative.
    pub fn illuminance(&self, line: usize, field: &str, text: &str) -> Result<f64> {
        let value = self.number(line, field, text)?;
        if value < 0.0 {
            Err(self.at(line, field, format!("{value} lx is negative")))
        } else {
            Ok(value)
        }
    }

    /// An air temperature, °C, in [`TEMPERATURE_RANGE`].
    pub fn temperature(&self, line: usize, field: &str, text: &str) -> Result<f64> {
        self.number_in(line, field, text, TEMPERATURE_RANGE, "°C")
    }

    /// The checks on a whole year, and the year itself: at least one record; consecutive
    /// hours from hour 1 of the first day to hour 24 of the last; the illuminances' unit.
    /// `last_line` is the file's last line, for a file without records.
    pub fn finish(
        &self,
        format: Format,
        location: Location,
        mut records: Vec<Record>,
        last_line: usize,
    ) -> Result<Weather> {
        let Some(first) = records.first() else {
            return Err(self.error(
                Some(last_line),
                None,
                "the file ends without records (one a line, after the header)",
            ));
        };
        if first.hour != 1 {
            return Err(self.at(
                first.line,
                "hour",
                format!(
                    "the first record is hour {}; a weather file starts at hour 1 (the hour \
                     ending at 01:00) so that it holds whole days",
                    first.hour
                ),
            ));
        }
        for pair in records.windows(2) {
            let (previous, record) = (&pair[0], &pair[1]);
            if !follows(previous, record) {
                return Err(self.at(
                    record.line,
                    "date and hour",
                    format!(
                        "{}/{} hour {} does not follow {}/{} hour {} (line {}): the records \
                         must be consecutive hours",
                        record.month,
                        record.day,
                        record.hour,
                        previous.month,
                        previous.day,
                        previous.hour,
                        previous.line
                    ),
                ));
            }
        }
        // Consecutive from hour 1, so whole days exactly when the last is hour 24.
        if let Some(last) = records.last().filter(|r| r.hour != 24) {
            return Err(self.at(
                last.line,
                "hour",
                format!(
                    "the file ends at hour {} of {}/{} after {} records; a weather file holds \
                     whole days (24 records each: 8760 a year, 8784 a leap year)",
                    last.hour,
                    last.month,
                    last.day,
                    records.len()
                ),
            ));
        }
        let illuminance = illuminance_unit(&mut records);
        Ok(Weather {
            path: self.path.to_path_buf(),
            format,
            location,
            records,
            illuminance,
        })
    }
}

/// The text's lines with their 1-based numbers, without a UTF-8 byte-order mark and without
/// their line ends (LF or CR LF).
pub(super) fn lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.strip_prefix('\u{feff}')
        .unwrap_or(text)
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l))
}

/// The comma-separated fields of a line, trimmed; a field in double quotes loses them (and
/// `""` inside is one quote), so that a quoted name may hold commas.
pub(super) fn fields(line: &str) -> Vec<Cow<'_, str>> {
    if !line.contains('"') {
        return line.split(',').map(|f| Cow::Borrowed(f.trim())).collect();
    }
    let mut fields = Vec::new();
    let mut field = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            '"' => quoted = !quoted,
            ',' if !quoted => fields.push(Cow::Owned(std::mem::take(&mut field).trim().to_owned())),
            c => field.push(c),
        }
    }
    fields.push(Cow::Owned(field.trim().to_owned()));
    fields
}

/// Days in `month` (1 to 12) at most: February may have 29 (typical years take February from
/// any year; a leap year's file has its 29th).
pub(super) fn max_days(month: u8) -> u8 {
    match month {
        2 => 29,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

/// Whether `record` is the hour after `previous`: the next hour of the day, or hour 1 of the
/// next day after hour 24 (December 31 is followed by January 1, whatever the years).
fn follows(previous: &Record, record: &Record) -> bool {
    if previous.hour < 24 {
        return (record.month, record.day, record.hour)
            == (previous.month, previous.day, previous.hour + 1);
    }
    if record.hour != 1 {
        return false;
    }
    // The month's last day: February's is the 28th or the 29th.
    let last_day = match previous.month {
        2 => previous.day >= 28,
        m => previous.day == max_days(m),
    };
    let same_month = record.month == previous.month && record.day == previous.day + 1;
    let next_month = last_day && record.month == previous.month % 12 + 1 && record.day == 1;
    same_month || next_month
}

/// Reads the unit of the records' illuminances and puts them in lux, or clears them when the
/// file has none ([`Illuminance`]).
fn illuminance_unit(records: &mut [Record]) -> Illuminance {
    let clear = |records: &mut [Record]| {
        for r in records.iter_mut() {
            r.global_horizontal_lux = None;
            r.direct_normal_lux = None;
            r.diffuse_horizontal_lux = None;
        }
    };
    if records.iter().all(|r| r.global_horizontal_lux.is_none()) {
        clear(records);
        return Illuminance::Missing;
    }
    let sun = records.iter().any(|r| r.global_horizontal > 0.0);
    let light = records
        .iter()
        .any(|r| r.global_horizontal_lux.is_some_and(|e| e > 0.0));
    if sun && !light {
        clear(records);
        return Illuminance::AllZero;
    }
    let mut efficacies: Vec<f64> = records
        .iter()
        .filter(|r| r.global_horizontal >= Illuminance::SUNLIT_W_M2)
        .filter_map(|r| r.global_horizontal_lux.map(|e| e / r.global_horizontal))
        .collect();
    if efficacies.is_empty() {
        return Illuminance::Lux;
    }
    efficacies.sort_by(f64::total_cmp);
    let n = efficacies.len();
    let efficacy = if n % 2 == 1 {
        efficacies[n / 2]
    } else {
        (efficacies[n / 2 - 1] + efficacies[n / 2]) / 2.0
    };
    let hundreds =
        Illuminance::LUX_EFFICACY.start() / 100.0..=Illuminance::LUX_EFFICACY.end() / 100.0;
    if Illuminance::LUX_EFFICACY.contains(&efficacy) {
        Illuminance::Lux
    } else if hundreds.contains(&efficacy) {
        for r in records.iter_mut() {
            for e in [
                &mut r.global_horizontal_lux,
                &mut r.direct_normal_lux,
                &mut r.diffuse_horizontal_lux,
            ] {
                *e = e.map(|e| e * 100.0);
            }
        }
        Illuminance::HundredsOfLux { efficacy }
    } else {
        clear(records);
        Illuminance::Implausible { efficacy }
    }
}
