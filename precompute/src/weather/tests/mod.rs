//! The weather readers' tests: each format's fields and errors ([`epw`], [`tmy3`]), what
//! they share (this file), and the shipped weather year against its source ([`shipped`]).

use std::path::{Path, PathBuf};

use super::*;

mod epw;
mod shipped;
mod tmy3;

/// The path the tests' texts are parsed as.
fn path() -> PathBuf {
    PathBuf::from("test.epw")
}

/// An EPW header for Vienna (WMO 110350, UTC+1).
const EPW_HEADER: &str = "LOCATION,Vienna,W,AUT,test,110350,48.25,16.36,1.0,170\n\
DESIGN CONDITIONS,0\n\
TYPICAL/EXTREME PERIODS,0\n\
GROUND TEMPERATURES,0\n\
HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\n\
COMMENTS 1,eigenrad test\n\
COMMENTS 2,\n\
DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";

/// One EPW record: the sun is up from hour 9 to hour 16 (400 W/m² global, 500 direct normal,
/// 100 diffuse; 44 000, 50 000 and 12 000 lx, 110 lm/W global), dry bulb 5.5 °C, dew point
/// −1.5 °C.
fn epw_record(month: u8, day: u8, hour: u8) -> String {
    let sun = (9..=16).contains(&hour);
    let [ghi, dni, dhi] = if sun { [400, 500, 100] } else { [0; 3] };
    let [ghl, dnl, dhl] = if sun { [44000, 50000, 12000] } else { [0; 3] };
    format!(
        "2001,{month},{day},{hour},60,?9?9?9?9E0?9?9?9,5.5,-1.5,62,99000,0,0,300,{ghi},{dni},\
         {dhi},{ghl},{dnl},{dhl},0,180,2.1,5,5,20,77777,9,999999999,10,0.1,0,88,0.2,0,1"
    )
}

/// An EPW of whole days.
fn epw(days: &[(u8, u8)]) -> String {
    let mut text = EPW_HEADER.to_owned();
    for &(month, day) in days {
        for hour in 1..=24 {
            text.push_str(&epw_record(month, day, hour));
            text.push('\n');
        }
    }
    text
}

/// Every day of a year of `february` days in February.
fn year(february: u8) -> Vec<(u8, u8)> {
    let lengths = [31, february, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
    (1..=12u8)
        .flat_map(|m| (1..=lengths[usize::from(m - 1)]).map(move |d| (m, d)))
        .collect()
}

/// `text` with line `n` (1-based) replaced by `replace(line)`.
fn edit(text: &str, n: usize, replace: impl Fn(&str) -> String) -> String {
    text.lines()
        .enumerate()
        .map(|(i, l)| if i + 1 == n { replace(l) } else { l.to_owned() })
        .collect::<Vec<_>>()
        .join("\n")
}

/// `line` with its comma-separated field `field` (1-based) set to `value`.
fn set_field(line: &str, field: usize, value: &str) -> String {
    let mut f: Vec<&str> = line.split(',').collect();
    f[field - 1] = value;
    f.join(",")
}

/// The error of parsing `text`, asserting its line and field and that the message names
/// them as `"test.epw:{line}: {field}: "`.
#[track_caller]
fn error_at(
    parse: fn(&Path, &str) -> Result<Weather>,
    text: &str,
    line: usize,
    field: Option<&str>,
) -> WeatherError {
    let e = match parse(&path(), text) {
        Ok(w) => panic!(
            "expected an error at line {line}, read {} records",
            w.records.len()
        ),
        Err(e) => e,
    };
    let message = e.to_string();
    assert_eq!(e.line, Some(line), "{message}");
    assert_eq!(e.field.as_deref(), field, "{message}");
    let place = match field {
        Some(field) => format!("test.epw:{line}: {field}: "),
        None => format!("test.epw:{line}: "),
    };
    assert!(message.starts_with(&place), "{message}");
    e
}

/// A file of neither format is an error naming its first line; a file is recognised by its
/// content, not its name.
#[test]
fn format_by_content() {
    let e = parse(&path(), "hello\nworld\n").unwrap_err();
    assert_eq!(e.line, Some(1));
    assert!(e.to_string().contains("neither an EPW"), "{e}");
    let w = parse(Path::new("weather.csv"), &epw(&[(1, 1)])).unwrap();
    assert_eq!(w.format, Format::Epw);
    let tmy3 = std::fs::read_to_string(shipped::excerpt()).unwrap();
    let w = parse(Path::new("weather.epw"), &tmy3).unwrap();
    assert_eq!(w.format, Format::Tmy3);
}

/// A byte-order mark and CR LF line ends read the same records, in both formats.
#[test]
fn byte_order_mark_and_crlf() {
    let plain = epw(&[(1, 1), (1, 2)]);
    let windows = format!("\u{feff}{}", plain.replace('\n', "\r\n"));
    let (a, b) = (
        parse(&path(), &plain).unwrap(),
        parse(&path(), &windows).unwrap(),
    );
    assert_eq!(a, b);
    assert_eq!(b.location.name, "Vienna");
    assert_eq!(b.records.len(), 48);

    let plain = std::fs::read_to_string(shipped::excerpt()).unwrap();
    let windows = format!("\u{feff}{}", plain.replace('\n', "\r\n"));
    let (a, b) = (
        parse(&path(), &plain).unwrap(),
        parse(&path(), &windows).unwrap(),
    );
    assert_eq!(a, b);
    assert_eq!(b.location.station, "723170");
}

/// Hour h holds the hour ending at h:00, local standard time: the sky is computed at
/// (h − 0.5) h after midnight. Hour 1 at 00:30, hour 13 at 12:30, hour 24 at 23:30.
#[test]
fn hour_convention() {
    let w = parse(&path(), &epw(&[(3, 21)])).unwrap();
    let minutes: Vec<f64> = w.records.iter().map(Record::mid_hour_minutes).collect();
    assert_eq!(minutes[0], 30.0);
    assert_eq!(minutes[12], 12.0 * 60.0 + 30.0);
    assert_eq!(minutes[23], 23.0 * 60.0 + 30.0);
    // The sun of the test file is up in hours 9 to 16: 08:00 to 16:00.
    let sunlit: Vec<u8> = w
        .records
        .iter()
        .filter(|r| r.global_horizontal > 0.0)
        .map(|r| r.hour)
        .collect();
    assert_eq!(sunlit, (9..=16).collect::<Vec<_>>());
    // TMY3's 13:00 is hour 13, the hour from 12:00 to 13:00.
    let excerpt = read(&shipped::excerpt()).unwrap();
    let r = &excerpt.records[12];
    assert_eq!((r.month, r.day, r.hour, r.line), (1, 1, 13, 15));
    assert_eq!(r.mid_hour_minutes(), 750.0);
}

/// Great-circle distances against values computed apart.
///
/// Vienna (St. Stephen's, 48°12′30″ N 16°22′21″ E) to Greensboro's TMY3 site (36.100° N
/// 79.950° W): 7524.215 km by the spherical law of cosines on the same 6371 km sphere
/// (`python3 -c "import math; p,q=math.radians(48+12/60+30/3600),math.radians(36.1);
/// l=math.radians(-79.95-(16+22/60+21/3600)); print(6371*math.acos(math.sin(p)*math.sin(q)+
/// math.cos(p)*math.cos(q)*math.cos(l)))"` prints 7524.21509906244), within 1 m. A quarter
/// meridian is π/2 × 6371 km and one degree of the equator 2π × 6371 / 360 km, within 1 mm.
#[test]
fn distance_km() {
    let greensboro = Location {
        name: "GREENSBORO PIEDMONT TRIAD INT".into(),
        region: "NC".into(),
        country: String::new(),
        station: "723170".into(),
        latitude: 36.1,
        longitude: -79.95,
        elevation: 273.0,
        utc_offset_hours: -5.0,
    };
    let vienna = (
        48.0 + 12.0 / 60.0 + 30.0 / 3600.0,
        16.0 + 22.0 / 60.0 + 21.0 / 3600.0,
    );
    let d = greensboro.distance_km(vienna.0, vienna.1);
    assert!((d - 7524.215099).abs() < 1e-3, "{d} km");
    assert_eq!(greensboro.distance_km(36.1, -79.95), 0.0);

    let null_island = Location {
        latitude: 0.0,
        longitude: 0.0,
        ..greensboro.clone()
    };
    let quarter = null_island.distance_km(90.0, 0.0);
    assert!(
        (quarter - std::f64::consts::FRAC_PI_2 * 6371.0).abs() < 1e-6,
        "{quarter} km"
    );
    let degree = null_island.distance_km(0.0, 1.0);
    assert!(
        (degree - std::f64::consts::TAU * 6371.0 / 360.0).abs() < 1e-6,
        "{degree} km"
    );
    // Across the antimeridian, and to the antipode (half the circumference).
    let d = null_island.distance_km(0.0, 180.0);
    assert!((d - std::f64::consts::PI * 6371.0).abs() < 1e-6, "{d} km");
    let fiji = Location {
        latitude: 0.0,
        longitude: 179.5,
        ..greensboro
    };
    let d = fiji.distance_km(0.0, -179.5);
    assert!((d - degree).abs() < 1e-6, "{d} km");
}

/// The message names what it has: no line for a file that cannot be read.
#[test]
fn unreadable_file() {
    let missing = Path::new("no/such/weather.epw");
    let e = read(missing).unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (None, None));
    assert!(
        e.to_string()
            .starts_with("no/such/weather.epw: cannot read file: "),
        "{e}"
    );
    // The umbrella error shows it unchanged.
    let umbrella = crate::Error::from(e.clone());
    assert_eq!(umbrella.to_string(), e.to_string());
}

/// A file that is not UTF-8 is read as Latin-1: a name keeps its letters.
#[test]
fn latin_1_names() {
    let dir = std::env::temp_dir().join(format!("eigenrad-weather-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("zurich.epw");
    let text = epw(&[(1, 1)]).replace("Vienna", "Z\u{fc}rich");
    let latin1: Vec<u8> = text.chars().map(|c| c as u8).collect();
    std::fs::write(&file, latin1).unwrap();
    let w = read(&file).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(w.location.name, "Zürich");
    assert_eq!(w.path, file);
}
