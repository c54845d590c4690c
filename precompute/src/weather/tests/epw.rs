//! The EPW reader: every field it takes, the missing codes, the illuminances' unit, and one
//! test per error, each naming the line and the field.

use super::*;

/// Line 9 is the first record; line 9 + 24 d + h − 1 is hour h of day d (0-based).
const FIRST: usize = 9;

/// Every field the reader takes, from the header and a sunlit record.
#[test]
fn fields() {
    let w = parse_epw(&path(), &epw(&[(1, 1)])).unwrap();
    assert_eq!(w.format, Format::Epw);
    assert_eq!(
        w.location,
        Location {
            name: "Vienna".into(),
            region: "W".into(),
            country: "AUT".into(),
            station: "110350".into(),
            latitude: 48.25,
            longitude: 16.36,
            elevation: 170.0,
            utc_offset_hours: 1.0,
        }
    );
    assert_eq!(w.records.len(), 24);
    assert_eq!(w.days(), 1);
    assert_eq!(w.illuminance, Illuminance::Lux);
    assert_eq!(
        w.records[11],
        Record {
            line: FIRST + 11,
            month: 1,
            day: 1,
            hour: 12,
            year: 2001,
            global_horizontal: 400.0,
            direct_normal: 500.0,
            diffuse_horizontal: 100.0,
            global_horizontal_lux: Some(44000.0),
            direct_normal_lux: Some(50000.0),
            diffuse_horizontal_lux: Some(12000.0),
            dew_point: Some(-1.5),
            dry_bulb: Some(5.5),
        }
    );
    // Decimals as EPW writers spell them: "9998.", ".5", "+1e2".
    let text = edit(&epw(&[(1, 1)]), FIRST + 11, |l| {
        set_field(&set_field(&set_field(l, 14, "1000."), 15, ".5"), 16, "+1e2")
    });
    let r = parse_epw(&path(), &text).unwrap().records[11];
    assert_eq!(
        [r.global_horizontal, r.direct_normal, r.diffuse_horizontal],
        [1000.0, 0.5, 100.0]
    );
}

/// Temperatures at 99.9 and illuminances at 999900 and above are missing; the rest of the
/// record reads.
#[test]
fn missing_codes() {
    let text = edit(&epw(&[(1, 1)]), FIRST + 11, |l| {
        let l = set_field(l, 7, "99.9");
        let l = set_field(&l, 8, "99.9");
        let l = set_field(&l, 17, "999999");
        let l = set_field(&l, 18, "999900");
        set_field(&l, 19, "999999.")
    });
    let w = parse_epw(&path(), &text).unwrap();
    let r = &w.records[11];
    assert_eq!((r.dry_bulb, r.dew_point), (None, None));
    assert_eq!(
        (
            r.global_horizontal_lux,
            r.direct_normal_lux,
            r.diffuse_horizontal_lux
        ),
        (None, None, None)
    );
    assert_eq!(r.global_horizontal, 400.0);
    assert_eq!(w.records[12].global_horizontal_lux, Some(44000.0));
    assert_eq!(w.illuminance, Illuminance::Lux);

    // Missing in every record: none.
    let text = epw(&[(1, 1)]).replace(",44000,50000,12000,", ",999999,999999,999999,");
    let text = text.replace(",0,0,0,0,180,", ",999999,999999,999999,0,180,");
    let w = parse_epw(&path(), &text).unwrap();
    assert_eq!(w.illuminance, Illuminance::Missing);
    assert!(!w.illuminance.available());
    assert!(w.records.iter().all(|r| r.global_horizontal_lux.is_none()));
}

/// Illuminances 0 in every record while the sun shines are no illuminances (many converters
/// write 0); 0 at night alone is not the rule's case.
#[test]
fn zeros_mean_missing() {
    let text = epw(&[(1, 1), (1, 2)]).replace(",44000,50000,12000,", ",0,0,0,");
    let w = parse_epw(&path(), &text).unwrap();
    assert_eq!(w.illuminance, Illuminance::AllZero);
    assert!(!w.illuminance.available());
    assert!(w.records.iter().all(|r| r.global_horizontal_lux.is_none()
        && r.direct_normal_lux.is_none()
        && r.diffuse_horizontal_lux.is_none()));

    // Light on some days keeps them all, the zeros of a dark day too.
    let mut text = epw(&[(1, 1), (1, 2), (1, 3)]);
    for n in FIRST + 8..FIRST + 16 {
        text = edit(&text, n, |l| l.replace(",44000,50000,12000,", ",0,0,0,"));
    }
    let w = parse_epw(&path(), &text).unwrap();
    assert_eq!(w.illuminance, Illuminance::Lux);
    assert_eq!(w.records[11].global_horizontal_lux, Some(0.0));
    assert_eq!(w.records[24 + 11].global_horizontal_lux, Some(44000.0));
    assert_eq!(w.records[0].global_horizontal_lux, Some(0.0));

    // No sun at all (a polar night): the zeros are what they say.
    let night = epw(&[(1, 1)]).replace(",400,500,100,44000,50000,12000,", ",0,0,0,0,0,0,");
    let w = parse_epw(&path(), &night).unwrap();
    assert_eq!(w.illuminance, Illuminance::Lux);
    assert_eq!(w.records[11].global_horizontal_lux, Some(0.0));
}

/// Illuminances written in hundreds of lux (440 for 44 000 lx, 1.1 "lm/W") are multiplied by
/// 100; a ratio that is neither daylight's in lux nor in hundreds leaves none.
#[test]
fn illuminance_unit() {
    let text = epw(&[(1, 1)]).replace(",44000,50000,12000,", ",440,500,120,");
    let w = parse_epw(&path(), &text).unwrap();
    assert_eq!(w.illuminance, Illuminance::HundredsOfLux { efficacy: 1.1 });
    let r = &w.records[11];
    assert_eq!(
        (
            r.global_horizontal_lux,
            r.direct_normal_lux,
            r.diffuse_horizontal_lux
        ),
        (Some(44000.0), Some(50000.0), Some(12000.0))
    );

    let text = epw(&[(1, 1)]).replace(",44000,50000,12000,", ",4400,5000,1200,");
    let w = parse_epw(&path(), &text).unwrap();
    assert_eq!(w.illuminance, Illuminance::Implausible { efficacy: 11.0 });
    assert!(w.records.iter().all(|r| r.global_horizontal_lux.is_none()));
}

/// A year, a leap year, whole days across month and year ends.
#[test]
fn whole_days() {
    let w = parse_epw(&path(), &epw(&year(28))).unwrap();
    assert_eq!((w.records.len(), w.days()), (8760, 365));
    let last = w.records.last().unwrap();
    assert_eq!(
        (last.month, last.day, last.hour, last.line),
        (12, 31, 24, 8768)
    );
    let w = parse_epw(&path(), &epw(&year(29))).unwrap();
    assert_eq!((w.records.len(), w.days()), (8784, 366));
    // Any whole number of days, across February's end and the year's.
    for days in [
        &[(2, 28), (3, 1)][..],
        &[(2, 28), (2, 29), (3, 1)],
        &[(12, 31), (1, 1)],
        &[(4, 30), (5, 1)],
    ] {
        let w = parse_epw(&path(), &epw(days)).unwrap();
        assert_eq!(w.days(), days.len());
    }
    // Blank lines at the end are fine.
    let w = parse_epw(&path(), &format!("{}\n\n \n", epw(&[(1, 1)]))).unwrap();
    assert_eq!(w.records.len(), 24);
}

/// A field that is not a number, and one that is not finite.
#[test]
fn error_not_a_number() {
    let text = edit(&epw(&[(1, 1)]), FIRST + 3, |l| set_field(l, 7, "warm"));
    let e = error_at(parse_epw, &text, 12, Some("dry bulb temperature (field 7)"));
    assert!(e.reason.contains("`warm` is not a number"), "{e}");
    let text = edit(&epw(&[(1, 1)]), FIRST + 11, |l| set_field(l, 15, "inf"));
    let e = error_at(
        parse_epw,
        &text,
        20,
        Some("direct normal radiation (field 15)"),
    );
    assert!(e.reason.contains("not a finite number"), "{e}");
}

/// Negative radiation or illuminance.
#[test]
fn error_negative() {
    let text = edit(&epw(&[(1, 1)]), FIRST + 11, |l| set_field(l, 14, "-3"));
    let e = error_at(
        parse_epw,
        &text,
        20,
        Some("global horizontal radiation (field 14)"),
    );
    assert!(e.reason.contains("-3 W/m² is negative"), "{e}");
    let text = edit(&epw(&[(1, 1)]), FIRST + 11, |l| set_field(l, 19, "-1"));
    let e = error_at(
        parse_epw,
        &text,
        20,
        Some("diffuse horizontal illuminance (field 19)"),
    );
    assert!(e.reason.contains("negative"), "{e}");
}

/// Radiation above any hour's sunlight: another unit.
#[test]
fn error_radiation_too_large() {
    let text = edit(&epw(&[(1, 1)]), FIRST + 11, |l| set_field(l, 16, "3600"));
    let e = error_at(
        parse_epw,
        &text,
        20,
        Some("diffuse horizontal radiation (field 16)"),
    );
    assert!(e.reason.contains("another unit"), "{e}");
}

/// Missing radiation (9999) cannot be simulated.
#[test]
fn error_missing_radiation() {
    let text = edit(&epw(&[(1, 1)]), FIRST + 11, |l| set_field(l, 15, "9999"));
    let e = error_at(
        parse_epw,
        &text,
        20,
        Some("direct normal radiation (field 15)"),
    );
    assert!(e.reason.contains("9999 marks it missing"), "{e}");
}

/// A temperature outside the dictionary's range that is not its missing code.
#[test]
fn error_temperature() {
    let text = edit(&epw(&[(1, 1)]), FIRST, |l| set_field(l, 8, "-80"));
    let e = error_at(parse_epw, &text, 9, Some("dew point temperature (field 8)"));
    assert!(e.reason.contains("-80 °C is outside -70 to 70 °C"), "{e}");
}

/// Month 13, day 30 of February, hour 0 and hour 25, a minute past 60, a year in decimals.
#[test]
fn error_date_and_hour() {
    let day = epw(&[(1, 1)]);
    let text = edit(&day, FIRST, |l| set_field(l, 2, "13"));
    let e = error_at(parse_epw, &text, 9, Some("month (field 2)"));
    assert!(e.reason.contains("13 is outside 1 to 12"), "{e}");
    let text = edit(&epw(&[(2, 1)]), FIRST, |l| set_field(l, 3, "30"));
    let e = error_at(parse_epw, &text, 9, Some("day (field 3)"));
    assert!(e.reason.contains("30 is outside 1 to 29"), "{e}");
    for hour in ["0", "25"] {
        let text = edit(&day, FIRST + 5, |l| set_field(l, 4, hour));
        let e = error_at(parse_epw, &text, 14, Some("hour (field 4)"));
        assert!(e.reason.contains("outside 1 to 24"), "{e}");
    }
    let text = edit(&day, FIRST, |l| set_field(l, 5, "61"));
    error_at(parse_epw, &text, 9, Some("minute (field 5)"));
    let text = edit(&day, FIRST, |l| set_field(l, 1, "2001.5"));
    let e = error_at(parse_epw, &text, 9, Some("year (field 1)"));
    assert!(e.reason.contains("not a whole number"), "{e}");
}

/// Fewer than 35 fields in a record.
#[test]
fn error_field_count() {
    let text = edit(&epw(&[(1, 1)]), FIRST + 2, |l| {
        l.rsplit_once(',').unwrap().0.to_owned()
    });
    let e = error_at(parse_epw, &text, 11, Some("record"));
    assert!(
        e.reason.contains("35 comma-separated fields expected"),
        "{e}"
    );
    assert!(e.reason.ends_with("found 34"), "{e}");
}

/// Records that are not consecutive hours: a gap, a repeat, a day skipped.
#[test]
fn error_not_consecutive() {
    let day = epw(&[(1, 1)]);
    let gap: String = day
        .lines()
        .enumerate()
        .filter(|&(i, _)| i + 1 != FIRST + 4)
        .map(|(_, l)| format!("{l}\n"))
        .collect();
    let e = error_at(parse_epw, &gap, 13, Some("date and hour"));
    assert!(
        e.reason
            .contains("1/1 hour 6 does not follow 1/1 hour 4 (line 12)"),
        "{e}"
    );
    let repeat = edit(&day, FIRST + 4, |l| set_field(l, 4, "4"));
    error_at(parse_epw, &repeat, 13, Some("date and hour"));
    let e = error_at(
        parse_epw,
        &epw(&[(1, 1), (1, 3)]),
        FIRST + 24,
        Some("date and hour"),
    );
    assert!(
        e.reason.contains("1/3 hour 1 does not follow 1/1 hour 24"),
        "{e}"
    );
    // February's 28th may be followed by the 29th or March; the 29th by March only.
    error_at(
        parse_epw,
        &epw(&[(2, 29), (2, 30)]),
        FIRST + 24,
        Some("day (field 3)"),
    );
    error_at(
        parse_epw,
        &epw(&[(3, 30), (4, 1)]),
        FIRST + 24,
        Some("date and hour"),
    );
}

/// A file that does not start at hour 1 or does not end at hour 24: not whole days.
#[test]
fn error_not_whole_days() {
    let day = epw(&[(1, 1)]);
    let late: String = day
        .lines()
        .enumerate()
        .filter(|&(i, _)| i + 1 != FIRST)
        .map(|(_, l)| format!("{l}\n"))
        .collect();
    let e = error_at(parse_epw, &late, FIRST, Some("hour"));
    assert!(e.reason.contains("the first record is hour 2"), "{e}");
    let short: String = day
        .lines()
        .take(FIRST + 11)
        .map(|l| format!("{l}\n"))
        .collect();
    let e = error_at(parse_epw, &short, FIRST + 11, Some("hour"));
    assert!(
        e.reason.contains("ends at hour 12 of 1/1 after 12 records"),
        "{e}"
    );
}

/// A header alone, a header cut short, an empty line among the records.
#[test]
fn error_no_records() {
    let e = error_at(parse_epw, EPW_HEADER, 8, None);
    assert!(e.reason.contains("without records"), "{e}");
    let e = error_at(
        parse_epw,
        "LOCATION,a,b,c,d,1,0,0,0,0\nDESIGN CONDITIONS,0\n",
        2,
        None,
    );
    assert!(e.reason.contains("ends inside the header"), "{e}");
    let text = edit(&epw(&[(1, 1)]), FIRST + 6, |_| String::new());
    let e = error_at(parse_epw, &text, FIRST + 6, None);
    assert!(e.reason.contains("empty line among the records"), "{e}");
}

/// A DATA PERIODS header that is not hourly, or not on line 8.
#[test]
fn error_data_periods() {
    let text = epw(&[(1, 1)]).replace("DATA PERIODS,1,1,", "DATA PERIODS,1,4,");
    let e = error_at(
        parse_epw,
        &text,
        8,
        Some("records per hour (DATA PERIODS field 3)"),
    );
    assert!(e.reason.contains("4 records per hour"), "{e}");
    let text = epw(&[(1, 1)]).replace("DATA PERIODS,1,1,", "DATA PERIODS,one,1,");
    error_at(
        parse_epw,
        &text,
        8,
        Some("number of data periods (DATA PERIODS field 2)"),
    );
    let text = edit(&epw(&[(1, 1)]), 8, |_| "COMMENTS 3,extra".to_owned());
    let e = error_at(parse_epw, &text, 8, None);
    assert!(e.reason.contains("DATA PERIODS header"), "{e}");
}

/// A LOCATION line with a latitude out of range, a longitude that is not a number, too few
/// fields.
#[test]
fn error_location() {
    let text = epw(&[(1, 1)]).replace(",48.25,16.36,", ",95,16.36,");
    let e = error_at(parse_epw, &text, 1, Some("latitude (LOCATION field 7)"));
    assert!(e.reason.contains("95 ° is outside -90 to 90 °"), "{e}");
    let text = epw(&[(1, 1)]).replace(",48.25,16.36,", ",48.25,east,");
    error_at(parse_epw, &text, 1, Some("longitude (LOCATION field 8)"));
    let text = epw(&[(1, 1)]).replace(",1.0,170\n", ",15,170\n");
    error_at(parse_epw, &text, 1, Some("time zone (LOCATION field 9)"));
    let text = edit(&epw(&[(1, 1)]), 1, |_| "LOCATION,Vienna,W,AUT".to_owned());
    let e = error_at(parse_epw, &text, 1, Some("LOCATION"));
    assert!(e.reason.ends_with("found 4"), "{e}");
}
