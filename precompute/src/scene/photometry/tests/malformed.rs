//! Malformed files: every fault is an error naming the file and the line, never a panic.

use std::path::Path;

use proptest::prelude::*;

use super::super::{eulumdat, ies, PhotometryError};
use super::data;

/// A test file with its 1-based line `line` replaced by `with` ("" deletes nothing: use
/// `edit` with `None` to delete).
fn edit(name: &str, line: usize, with: Option<&str>) -> Vec<u8> {
    let text = std::fs::read_to_string(data(name)).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    match with {
        Some(w) => lines[line - 1] = w,
        None => {
            lines.remove(line - 1);
        }
    }
    (lines.join("\r\n") + "\r\n").into_bytes()
}

fn ies_error(bytes: &[u8]) -> PhotometryError {
    match ies::parse(Path::new("bad.ies"), bytes) {
        Ok(_) => panic!("a malformed file was accepted"),
        Err(e) => e,
    }
}

fn ldt_error(bytes: &[u8]) -> PhotometryError {
    match eulumdat::parse(Path::new("bad.ldt"), bytes) {
        Ok(_) => panic!("a malformed file was accepted"),
        Err(e) => e,
    }
}

/// The error names the file and `line`, and its message says `says`.
#[track_caller]
fn assert_at(e: &PhotometryError, file: &str, line: usize, says: &str) {
    let message = e.to_string();
    assert_eq!(e.path(), Path::new(file), "{message}");
    assert_eq!(e.line(), Some(line), "{message}");
    assert!(
        message.starts_with(&format!("{file}:{line}: ")),
        "{message}"
    );
    assert!(message.contains(says), "{message:?} does not say {says:?}");
}

const HALF: &str = "lm63-2002-half.ies";

#[test]
fn lm63_counts_that_do_not_match() {
    // The header announces 20 vertical angles; lines 14–15 hold 19.
    let e = ies_error(&edit(HALF, 12, Some("1 -1 1 20 7 1 2 0.6 1.2 0")));
    assert_at(&e, "bad.ies", 15, "expected 20 vertical angles, found 19");
    // One vertical angle missing from line 15.
    let e = ies_error(&edit(HALF, 15, Some("100 110 120 130 140 150 160 170")));
    assert_at(&e, "bad.ies", 15, "expected 19 vertical angles, found 18");
    // One horizontal angle too many.
    let e = ies_error(&edit(HALF, 16, Some("0 30 60 90 120 150 180 210")));
    assert_at(&e, "bad.ies", 16, "expected 7 horizontal angles, found 8");
    // A candela value missing in the record of C = 0°.
    let e = ies_error(&edit(
        HALF,
        18,
        Some("76.71 69.64 63 57 51.83 47.63 44.53 42.64"),
    ));
    assert_at(
        &e,
        "bad.ies",
        18,
        "expected 19 candela values for horizontal angle 0°, found 18",
    );
    // A candela value too many in the record of C = 30°.
    let e = ies_error(&edit(
        HALF,
        20,
        Some("71.77 65.15 58.94 53.33 48.49 44.56 41.66 39.89 39.29 1"),
    ));
    assert_at(
        &e,
        "bad.ies",
        20,
        "expected 19 candela values for horizontal angle 30°, found 20",
    );
    // The last record cut short by the end of the file.
    let e = ies_error(&edit(HALF, 30, None));
    assert_at(
        &e,
        "bad.ies",
        29,
        "expected 19 candela values for horizontal angle 180°, found 10",
    );
    // Values after the last record.
    let mut extra = std::fs::read(data(HALF)).unwrap();
    extra.extend_from_slice(b"1 2 3\r\n");
    assert_at(
        &ies_error(&extra),
        "bad.ies",
        31,
        "3 values follow the last candela record",
    );
    // The ten-value record with a value missing.
    let e = ies_error(&edit(HALF, 12, Some("1 -1 1 19 7 1 2 0.6 1.2")));
    assert_at(&e, "bad.ies", 12, "expected 10 values");
    // A tilt table announcing 8 angles for 7.
    let e = ies_error(&edit("lm63-2002-tilt.ies", 13, Some("8")));
    assert_at(&e, "bad.ies", 15, "expected 8 tilt angles, found 7");
}

#[test]
fn lm63_bad_values() {
    let candela = |v: &str| {
        edit(
            HALF,
            17,
            Some(&format!(
                "126 125.36 {v} 120.37 116.17 111 105 98.36 91.29 84"
            )),
        )
    };
    let e = ies_error(&candela("-5"));
    assert_at(
        &e,
        "bad.ies",
        17,
        "candela value -5 at horizontal angle 0°, vertical angle 20° is negative",
    );
    for v in ["NaN", "inf", "-infinity"] {
        assert_at(&ies_error(&candela(v)), "bad.ies", 17, "is not finite");
    }
    assert_at(
        &ies_error(&candela("12x")),
        "bad.ies",
        17,
        "candela value: `12x` is not a number",
    );
    // Angles not increasing.
    let e = ies_error(&edit(HALF, 14, Some("0 20 10 30 40 50 60 70 80 90")));
    assert_at(
        &e,
        "bad.ies",
        14,
        "vertical angle 3 is 10°, not above the one before (20°)",
    );
    let e = ies_error(&edit(HALF, 16, Some("0 30 60 60 120 150 180")));
    assert_at(&e, "bad.ies", 16, "horizontal angle 4 is 60°");
    let e = ies_error(&edit(HALF, 15, Some("100 110 120 130 140 150 160 170 190")));
    assert_at(
        &e,
        "bad.ies",
        15,
        "vertical angle 19 is 190°, outside 0°…180°",
    );
    // Horizontal angles that end at no symmetry plane.
    let e = ies_error(&edit(HALF, 16, Some("0 20 40 60 80 100 120")));
    assert_at(
        &e,
        "bad.ies",
        16,
        "horizontal angles 0°…120° match no LM-63 symmetry",
    );
    // Header fields out of range.
    let e = ies_error(&edit(HALF, 12, Some("1 0 1 19 7 1 2 0.6 1.2 0")));
    assert_at(&e, "bad.ies", 12, "lumens per lamp 0");
    let e = ies_error(&edit(HALF, 12, Some("1 -1 1 19 7 1 3 0.6 1.2 0")));
    assert_at(&e, "bad.ies", 12, "units type");
    let e = ies_error(&edit(HALF, 12, Some("1 -1 0 19 7 1 2 0.6 1.2 0")));
    assert_at(&e, "bad.ies", 12, "candela multiplier 0: must be positive");
    let e = ies_error(&edit(HALF, 12, Some("1 -1 1 19 7 1 2 0 0 -1")));
    assert_at(&e, "bad.ies", 12, "matches no LM-63 shape");
    let e = ies_error(&edit(HALF, 13, Some("0 1 40")));
    assert_at(&e, "bad.ies", 13, "ballast factor 0: must be positive");
}

#[test]
fn lm63_unsupported_and_missing() {
    let e = ies_error(&edit(HALF, 12, Some("1 -1 1 19 7 2 2 0.6 1.2 0")));
    assert!(matches!(e, PhotometryError::Unsupported { .. }));
    assert_at(
        &e,
        "bad.ies",
        12,
        "type B photometry (type 2) is not supported",
    );
    let e = ies_error(&edit(HALF, 12, Some("1 -1 1 19 7 3 2 0.6 1.2 0")));
    assert_at(
        &e,
        "bad.ies",
        12,
        "type A photometry (type 3) is not supported",
    );
    // A tilt table in a file of its own: missing, or not named; LM-63-2019 allows none.
    let e = ies_error(&edit(HALF, 11, Some("TILT=lamp.tlt")));
    assert_at(
        &e,
        "bad.ies",
        11,
        "`TILT=lamp.tlt`: cannot read the tilt table's file lamp.tlt",
    );
    let e = ies_error(&edit(HALF, 11, Some("TILT=")));
    assert_at(&e, "bad.ies", 11, "`TILT=` names no tilt table");
    let e = ies_error(&edit("lm63-2019-none.ies", 11, Some("TILT=lamp.tlt")));
    assert_at(
        &e,
        "bad.ies",
        11,
        "`TILT=lamp.tlt` (a tilt table in a separate file, which LM-63-2019 no longer allows) \
         is not supported",
    );
    let e = ies_error(&edit(HALF, 1, Some("IESNA:LM-63-2030")));
    assert_at(
        &e,
        "bad.ies",
        1,
        "LM-63 version line `IESNA:LM-63-2030` is not supported",
    );
    let e = ies_error(&edit(HALF, 11, Some("[KEYWORD] no tilt line")));
    assert_at(&e, "bad.ies", 30, "no `TILT=` line");
    assert_at(&ies_error(b""), "bad.ies", 1, "no `TILT=` line");
    // Nothing after TILT=.
    let e = ies_error(b"IESNA:LM-63-2002\nTILT=NONE\n");
    assert_at(&e, "bad.ies", 2, "expected 10 values");
}

const ISYM2: &str = "eulumdat-isym2.ldt";

#[test]
fn eulumdat_faults() {
    let e = ldt_error(&edit(ISYM2, 3, Some("5")));
    assert_at(
        &e,
        "bad.ldt",
        3,
        "symmetry indicator Isym (0 to 4): 5 is not a whole number from 0 to 4",
    );
    // One intensity line missing: 7 planes × 19 angles announced.
    let e = ldt_error(&edit(ISYM2, 100, None));
    assert_at(
        &e,
        "bad.ldt",
        205,
        "expected 133 luminous intensities, found 132",
    );
    let mut extra = std::fs::read(data(ISYM2)).unwrap();
    extra.extend_from_slice(b"12\r\n\r\n");
    assert_at(
        &ldt_error(&extra),
        "bad.ldt",
        207,
        "1 lines follow the last luminous intensity",
    );
    let e = ldt_error(&edit(ISYM2, 100, Some("-3")));
    assert_at(
        &e,
        "bad.ldt",
        100,
        "luminous intensity -3 cd/klm at C 30°, γ 70° is negative",
    );
    assert_at(
        &ldt_error(&edit(ISYM2, 100, Some("NaN"))),
        "bad.ldt",
        100,
        "is not finite",
    );
    // C angles not increasing, and a plane where the symmetry needs 180°.
    let e = ldt_error(&edit(ISYM2, 45, Some("20")));
    assert_at(
        &e,
        "bad.ldt",
        45,
        "C angle 3 is 20°, not above the one before (30°)",
    );
    let e = ldt_error(&edit(ISYM2, 49, Some("185")));
    assert_at(
        &e,
        "bad.ldt",
        49,
        "Isym 2 (line 3) needs C angle 7 to be 180°, found 185°",
    );
    let e = ldt_error(&edit("eulumdat-isym4.ldt", 4, Some("10")));
    assert_at(
        &e,
        "bad.ldt",
        4,
        "Isym 4 (line 3) needs Mc divisible by 4, found 10",
    );
    let e = ldt_error(&edit(ISYM2, 57, Some("5")));
    assert_at(&e, "bad.ldt", 57, "γ angle 3 is 5°");
    let e = ldt_error(&edit(ISYM2, 29, Some("0")));
    assert_at(
        &e,
        "bad.ldt",
        29,
        "total luminous flux of the lamps 0 lm: must be positive",
    );
    let e = ldt_error(&edit(ISYM2, 22, Some("six")));
    assert_at(
        &e,
        "bad.ldt",
        22,
        "downward flux fraction DFF: `six` is not a number",
    );
    assert_at(
        &ldt_error(b""),
        "bad.ldt",
        1,
        "the file ends before the company identification",
    );
    let e = ldt_error(&edit(ISYM2, 24, Some("0")));
    assert_at(
        &e,
        "bad.ldt",
        24,
        "conversion factor for luminous intensities 0",
    );
}

#[test]
fn unknown_extensions_and_missing_files_are_named() {
    let e = super::super::read(Path::new("luminaire.txt")).unwrap_err();
    assert!(matches!(e, PhotometryError::UnknownFormat { .. }));
    assert!(e
        .to_string()
        .starts_with("luminaire.txt: unknown photometric format"));
    let e = super::super::read(Path::new("/nonexistent/luminaire.IES")).unwrap_err();
    assert!(matches!(e, PhotometryError::Read { .. }), "{e}");
    assert_eq!(e.line(), None);
}

/// Every test file, and the reader for it.
fn test_files() -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<_> = std::fs::read_dir(data(""))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| matches!(p.extension().and_then(|e| e.to_str()), Some("ies" | "ldt")))
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read(&p).unwrap(),
            )
        })
        .collect();
    files.sort();
    assert!(files.len() >= 18);
    files
}

fn parse(name: &str, bytes: &[u8]) -> Result<super::super::Photometry, PhotometryError> {
    if name.ends_with(".ies") {
        ies::parse(Path::new(name), bytes)
    } else {
        eulumdat::parse(Path::new(name), bytes)
    }
}

/// An error must name the file and a line of it.
fn check_error(name: &str, bytes: &[u8], e: &PhotometryError) {
    let lines = bytes.split(|b| *b == b'\n').count().max(1);
    assert_eq!(e.path(), Path::new(name));
    let line = e.line().expect("content errors name a line");
    assert!(
        (1..=lines).contains(&line),
        "{e} (the text has {lines} lines)"
    );
}

#[test]
fn every_truncation_of_every_test_file_is_an_error_naming_file_and_line() {
    for (name, bytes) in test_files() {
        parse(&name, &bytes).unwrap_or_else(|e| panic!("{e}"));
        // A cut inside the last value leaves a valid file with a shorter number: only cuts
        // before the last line must fail.
        let text = bytes.trim_ascii_end();
        let last_line = text.iter().rposition(|b| *b == b'\n').map_or(0, |i| i + 1);
        for cut in 0..bytes.len() {
            let head = &bytes[..cut];
            match parse(&name, head) {
                Err(e) => check_error(&name, head, &e),
                Ok(_) => assert!(cut > last_line, "{name} cut at byte {cut} was accepted"),
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        for name in ["random.ies", "random.ldt"] {
            if let Err(e) = parse(name, &bytes) {
                check_error(name, &bytes, &e);
            }
        }
    }

    #[test]
    fn random_edits_of_valid_files_never_panic(
        file in 0usize..18,
        edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..4),
    ) {
        let files = test_files();
        let (name, mut bytes) = files[file % files.len()].clone();
        for (at, byte) in edits {
            let i = at.index(bytes.len());
            bytes[i] = byte;
        }
        if let Err(e) = parse(&name, &bytes) {
            check_error(&name, &bytes, &e);
        }
    }

    #[test]
    fn random_tokens_in_valid_files_never_panic(
        file in 0usize..18,
        line in any::<prop::sample::Index>(),
        token in prop_oneof![
            Just("-1".to_string()), Just("0".to_string()), Just("1e308".to_string()),
            Just("99999999999".to_string()), Just("nan".to_string()), Just(",".to_string()),
            Just("TILT=INCLUDE".to_string()), Just("[MORE] x".to_string()), Just(String::new()),
            "[0-9 .,-]{0,12}",
        ],
    ) {
        let files = test_files();
        let (name, bytes) = &files[file % files.len()];
        let text = String::from_utf8_lossy(bytes).into_owned();
        let mut lines: Vec<&str> = text.lines().collect();
        let i = line.index(lines.len());
        lines[i] = &token;
        let edited = lines.join("\n");
        if let Err(e) = parse(name, edited.as_bytes()) {
            check_error(name, edited.as_bytes(), &e);
        }
    }
}
