//! The shipped weather year (`data/weather/`) against its source: Greensboro's EPW, made by
//! `scripts/tmy3-to-epw.py` from NREL's TMY3 file, and the excerpt of that file read by the
//! other reader.

use super::*;

/// `data/weather/` in the repository.
fn folder() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/weather")
}

/// The shipped EPW.
pub(super) fn epw() -> PathBuf {
    folder().join("greensboro-723170-tmy3.epw")
}

/// The shipped excerpt of the TMY3 CSV: its 2 header lines and its first 72 records.
pub(super) fn excerpt() -> PathBuf {
    folder().join("greensboro-723170-tmy3-excerpt.csv")
}

/// The EPW and the TMY3 excerpt read to the same first 72 records, at the same site.
#[test]
fn epw_matches_tmy3() {
    let epw = read(&epw()).unwrap();
    let tmy3 = read(&excerpt()).unwrap();
    assert_eq!((epw.format, tmy3.format), (Format::Epw, Format::Tmy3));
    assert_eq!((epw.records.len(), epw.days()), (8760, 365));
    assert_eq!(tmy3.records.len(), 72);
    // The EPW holds lux, the TMY3 hundreds of lux: both read to lux.
    assert_eq!(epw.illuminance, Illuminance::Lux);
    assert!(matches!(
        tmy3.illuminance,
        Illuminance::HundredsOfLux { .. }
    ));

    let (a, b) = (&epw.location, &tmy3.location);
    let d = a.distance_km(b.latitude, b.longitude);
    assert!(d < 1.0, "the EPW's site is {d} km from the TMY3's");
    assert_eq!(
        (a.name.as_str(), a.region.as_str()),
        (b.name.as_str(), b.region.as_str())
    );
    assert_eq!((a.station.as_str(), a.country.as_str()), ("723170", "USA"));
    assert_eq!(
        (a.elevation, a.utc_offset_hours),
        (b.elevation, b.utc_offset_hours)
    );

    for (e, t) in epw.records.iter().zip(&tmy3.records) {
        let line = t.line;
        assert_eq!(
            e.line,
            line - 2 + 8,
            "the EPW's line for the TMY3's line {line}"
        );
        assert_eq!(
            (e.month, e.day, e.hour, e.year),
            (t.month, t.day, t.hour, t.year),
            "TMY3 line {line}"
        );
        let irradiances = |r: &Record| [r.global_horizontal, r.direct_normal, r.diffuse_horizontal];
        assert_eq!(irradiances(e), irradiances(t), "TMY3 line {line}");
        let lux = |r: &Record| {
            [
                r.global_horizontal_lux,
                r.direct_normal_lux,
                r.diffuse_horizontal_lux,
            ]
        };
        assert_eq!(lux(e), lux(t), "TMY3 line {line}");
        assert_eq!(
            (e.dew_point, e.dry_bulb),
            (t.dew_point, t.dry_bulb),
            "TMY3 line {line}"
        );
    }
    // The excerpt holds daylight, so the comparison above compared some.
    assert!(tmy3
        .records
        .iter()
        .any(|r| r.global_horizontal_lux > Some(10_000.0)));
}

/// The EPW's annual sums of global, direct normal and diffuse irradiation, kWh/m², as
/// computed from NREL's CSV itself (`pvlib/data/723170TYA.CSV` in the pvlib 0.16.1 wheel,
/// sha256 1e96f846…10c6c9):
///
/// ```text
/// python3 -c "import csv; r=list(csv.reader(open('723170TYA.CSV'))); h=r[1]; \
///   [print(c, sum(float(x[h.index(c)]) for x in r[2:])/1000) \
///    for c in ('GHI (W/m^2)','DNI (W/m^2)','DHI (W/m^2)')]"
/// ```
///
/// prints 1566.203, 1476.549 and 682.223; within 1e-9 relative.
#[test]
fn annual_sums() {
    let epw = read(&epw()).unwrap();
    let sum = |f: fn(&Record) -> f64| epw.records.iter().map(f).sum::<f64>() / 1000.0;
    for (name, sum, expected) in [
        ("global", sum(|r| r.global_horizontal), 1566.203),
        ("direct normal", sum(|r| r.direct_normal), 1476.549),
        ("diffuse", sum(|r| r.diffuse_horizontal), 682.223),
    ] {
        assert!(
            ((sum - expected) / expected).abs() < 1e-9,
            "{name}: {sum} kWh/m², expected {expected}"
        );
    }
    // Every record has its illuminances and temperatures; none was missing in the source.
    assert!(epw.records.iter().all(|r| r.global_horizontal_lux.is_some()
        && r.dew_point.is_some()
        && r.dry_bulb.is_some()));
}
