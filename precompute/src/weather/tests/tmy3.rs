//! The TMY3 reader, on the shipped excerpt of Greensboro's file and edits of it: every field
//! it takes, the columns found by name, and one test per error, each naming the line and the
//! field.

use super::*;

/// The shipped excerpt's text: the site, the column names and the first 72 hours.
fn excerpt() -> String {
    std::fs::read_to_string(shipped::excerpt()).unwrap()
}

/// Every field the reader takes: line 15 is 1 January 1988 13:00, `…,155,1,9,0,1,9,155,1,13,
/// 180,1,9,0,1,9,180,1,13,…,11.7,A,7,10.6,A,7,…` (GHI, DNI, DHI; illuminances in hundreds of
/// lux; dry bulb, dew point).
#[test]
fn fields() {
    let w = parse_tmy3(&path(), &excerpt()).unwrap();
    assert_eq!(w.format, Format::Tmy3);
    assert_eq!(
        w.location,
        Location {
            name: "GREENSBORO PIEDMONT TRIAD INT".into(),
            region: "NC".into(),
            country: String::new(),
            station: "723170".into(),
            latitude: 36.1,
            longitude: -79.95,
            elevation: 273.0,
            utc_offset_hours: -5.0,
        }
    );
    assert_eq!((w.records.len(), w.days()), (72, 3));
    assert_eq!(
        w.records[12],
        Record {
            line: 15,
            month: 1,
            day: 1,
            hour: 13,
            year: 1988,
            global_horizontal: 155.0,
            direct_normal: 0.0,
            diffuse_horizontal: 155.0,
            global_horizontal_lux: Some(18000.0),
            direct_normal_lux: Some(0.0),
            diffuse_horizontal_lux: Some(18000.0),
            dew_point: Some(10.6),
            dry_bulb: Some(11.7),
        }
    );
    // Hundreds of lux: the median ratio of GH illum to GHI as written is about 1.1.
    let Illuminance::HundredsOfLux { efficacy } = w.illuminance else {
        panic!("{:?}", w.illuminance);
    };
    assert!((1.0..1.2).contains(&efficacy), "{efficacy}");
    let last = w.records.last().unwrap();
    assert_eq!((last.month, last.day, last.hour, last.line), (1, 3, 24, 74));
}

/// Columns are found by name, wherever they are; the illuminance and temperature columns
/// may be absent.
#[test]
fn columns_by_name() {
    // Swap GHI (column 5) and DNI (column 8), names and values.
    let swap = |l: &str| {
        let mut f: Vec<&str> = l.split(',').collect();
        if f.len() > 8 {
            f.swap(4, 7);
        }
        f.join(",")
    };
    let text: String = excerpt()
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == 0 {
                format!("{l}\n")
            } else {
                format!("{}\n", swap(l))
            }
        })
        .collect();
    let swapped = parse_tmy3(&path(), &text).unwrap();
    assert_eq!(swapped, parse_tmy3(&path(), &excerpt()).unwrap());

    // Only the date, the time and the three irradiances.
    let keep = [0, 1, 4, 7, 10];
    let text: String = excerpt()
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == 0 {
                return format!("{l}\n");
            }
            let f: Vec<&str> = l.split(',').collect();
            let kept: Vec<&str> = keep.iter().map(|&k| f[k]).collect();
            format!("{}\n", kept.join(","))
        })
        .collect();
    let w = parse_tmy3(&path(), &text).unwrap();
    assert_eq!(w.illuminance, Illuminance::Missing);
    let r = &w.records[12];
    assert_eq!((r.global_horizontal, r.diffuse_horizontal), (155.0, 155.0));
    assert_eq!(
        (r.dew_point, r.dry_bulb, r.global_horizontal_lux),
        (None, None, None)
    );
}

/// A required column missing from line 2.
#[test]
fn error_missing_column() {
    let text = excerpt().replacen("DHI (W/m^2)", "DHI", 1);
    let e = error_at(parse_tmy3, &text, 2, Some("`DHI (W/m^2)`"));
    assert!(e.reason.contains("no such column"), "{e}");
}

/// A value that is not a number, a negative irradiance, one above any hour's sunlight, a
/// temperature out of range.
#[test]
fn error_values() {
    let text = edit(&excerpt(), 15, |l| set_field(l, 5, "n/a"));
    let e = error_at(parse_tmy3, &text, 15, Some("`GHI (W/m^2)` (column 5)"));
    assert!(e.reason.contains("`n/a` is not a number"), "{e}");
    let text = edit(&excerpt(), 15, |l| set_field(l, 11, "-9900"));
    let e = error_at(parse_tmy3, &text, 15, Some("`DHI (W/m^2)` (column 11)"));
    assert!(e.reason.contains("negative"), "{e}");
    let text = edit(&excerpt(), 15, |l| set_field(l, 8, "5400"));
    error_at(parse_tmy3, &text, 15, Some("`DNI (W/m^2)` (column 8)"));
    let text = edit(&excerpt(), 15, |l| set_field(l, 14, "-1"));
    error_at(parse_tmy3, &text, 15, Some("`GH illum (lx)` (column 14)"));
    let text = edit(&excerpt(), 15, |l| set_field(l, 35, "-9900"));
    let e = error_at(parse_tmy3, &text, 15, Some("`Dew-point (C)` (column 35)"));
    assert!(e.reason.contains("outside -70 to 70 °C"), "{e}");
}

/// Dates and times that are not `MM/DD/YYYY` and `01:00` to `24:00`.
#[test]
fn error_date_and_time() {
    let field = Some("`Date (MM/DD/YYYY)` (column 1)");
    let text = edit(&excerpt(), 3, |l| set_field(l, 1, "13/01/1988"));
    let e = error_at(parse_tmy3, &text, 3, field);
    assert!(e.reason.contains("13 is outside 1 to 12"), "{e}");
    let text = edit(&excerpt(), 3, |l| set_field(l, 1, "1988-01-01"));
    let e = error_at(parse_tmy3, &text, 3, field);
    assert!(e.reason.contains("not a date MM/DD/YYYY"), "{e}");
    let field = Some("`Time (HH:MM)` (column 2)");
    for time in ["00:00", "25:00"] {
        let text = edit(&excerpt(), 3, |l| set_field(l, 2, time));
        let e = error_at(parse_tmy3, &text, 3, field);
        assert!(e.reason.contains("outside 1 to 24"), "{e}");
    }
    let text = edit(&excerpt(), 3, |l| set_field(l, 2, "01:30"));
    let e = error_at(parse_tmy3, &text, 3, field);
    assert!(e.reason.contains("whole hours"), "{e}");
    let text = edit(&excerpt(), 3, |l| set_field(l, 2, "0100"));
    error_at(parse_tmy3, &text, 3, field);
    // The hours must follow one another here too.
    let text = edit(&excerpt(), 4, |l| set_field(l, 2, "03:00"));
    error_at(parse_tmy3, &text, 4, Some("date and hour"));
}

/// A record with more or fewer fields than line 2 names.
#[test]
fn error_field_count() {
    let text = edit(&excerpt(), 40, |l| format!("{l},extra"));
    let e = error_at(parse_tmy3, &text, 40, Some("record"));
    assert!(
        e.reason.contains("71 comma-separated fields expected"),
        "{e}"
    );
    assert!(e.reason.ends_with("found 72"), "{e}");
}

/// A site line too short, or with a latitude that is not one.
#[test]
fn error_site() {
    let text = edit(&excerpt(), 1, |_| "723170,GREENSBORO,NC".to_owned());
    let e = error_at(parse_tmy3, &text, 1, Some("site"));
    assert!(e.reason.ends_with("found 3"), "{e}");
    let text = edit(&excerpt(), 1, |l| l.replace("36.100", "N36"));
    error_at(parse_tmy3, &text, 1, Some("latitude (field 5)"));
    // A quoted name may hold a comma.
    let text = edit(&excerpt(), 1, |l| {
        l.replace("\"GREENSBORO ", "\"GREENSBORO, ")
    });
    let w = parse_tmy3(&path(), &text).unwrap();
    assert_eq!(w.location.name, "GREENSBORO, PIEDMONT TRIAD INT");
}

/// A site line alone, and the column names without records.
#[test]
fn error_no_records() {
    let site = excerpt().lines().next().unwrap().to_owned();
    let e = error_at(parse_tmy3, &site, 1, None);
    assert!(e.reason.contains("line 2 names the columns"), "{e}");
    let names: String = excerpt()
        .lines()
        .take(2)
        .map(|l| format!("{l}\n"))
        .collect();
    let e = error_at(parse_tmy3, &names, 2, None);
    assert!(e.reason.contains("without records"), "{e}");
}
