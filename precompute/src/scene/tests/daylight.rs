//! The daylight part of a scene file: the `[site]`, glazed materials and their windows, and
//! exterior surfaces (obstructions). Every rule has a test that breaks it and checks the
//! message names the file, the line and the field; the geometry of obstructions is checked
//! against the boxes and corners written in the file. Here the room, the site and the
//! examples; the windows in `windows`, the obstructions in `exterior`.

use eigenrad_runtime::sky::glazing::Glazing;

use super::*;

mod exterior;
mod windows;

/// A 3 m × 2 m × 2.5 m room with a 1 m × 1.2 m glazed window flush in its wall y = 0.
const DAY: &str = r#"[scene]
name = "d"
bands = "photopic"
unit = "m"
max_edge = 0.5

[materials]
white = { reflectance = 0.5 }
lamp = { reflectance = 0.0, emission = 100 }
glass = { reflectance = 0.08, transmittance = 0.70 }
facade = { reflectance = 0.3 }

[[room]]
name = "room"
min = [0, 0, 0]
max = [3, 2, 2.5]
material = "white"
openings = ["window"]

[[quad]]
name = "window"
material = "glass"
corners = [[1, 0, 0.8], [1, 0, 2], [2, 0, 2], [2, 0, 0.8]]
"#;

/// Vienna, every field given.
const SITE: &str = r#"
[site]
latitude = 48.21
longitude = 16.37
elevation = 170
north = 30
utc_offset = "+01:00"
ground_reflectance = 0.15
"#;

/// An overhang above the window, facing down, outside the room.
const OVERHANG: &str = r#"
[[quad]]
name = "overhang"
material = "facade"
corners = [[0.8, 0, 2.2], [2.2, 0, 2.2], [2.2, -0.6, 2.2], [0.8, -0.6, 2.2]]
exterior = true
"#;

/// A building across the street, 5 m to 8 m south of the room.
const OPPOSITE: &str = r#"
[[block]]
name = "opposite"
min = [-2, -8, 0]
max = [5, -5, 6]
material = "facade"
exterior = true
"#;

fn day(extra: &str) -> String {
    format!("{DAY}{extra}")
}

fn load_day(text: &str) -> Scene {
    parse(text, Path::new(FILE)).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The 1-based line of `text`'s last line holding `needle` (the extra text comes last).
fn line(text: &str, needle: &str) -> usize {
    let lines: Vec<&str> = text.lines().collect();
    lines
        .iter()
        .rposition(|l| l.contains(needle))
        .map_or_else(|| panic!("no `{needle}` in the text"), |i| i + 1)
}

/// `text` must be refused with a message naming the file, the line of `at` and `parts`.
fn refused(text: &str, at: &str, parts: &[&str]) {
    let m = error_in(text);
    assert_names(&m, parts);
    let l = format!(":{}:", line(text, at));
    assert!(m.contains(&l), "line {l} missing from: {m}");
}

// ---- [site] --------------------------------------------------------------------------------

#[test]
fn scene_site_fields_parse() {
    let scene = load_day(&day(SITE));
    let site = scene.site.expect("a site");
    assert_eq!(site.location.latitude, 48.21);
    assert_eq!(site.location.longitude, 16.37);
    assert_eq!(site.location.elevation, 170.0);
    assert_eq!(site.north, 30.0);
    assert_eq!(site.utc_offset, Some(3600));
    assert_eq!(site.ground_reflectance, 0.15);

    // The defaults: elevation 0 m, north 0°, no offset, ground 0.2.
    let scene = load_day(&day("\n[site]\nlatitude = -33.9\nlongitude = 151.2\n"));
    let site = scene.site.expect("a site");
    assert_eq!(
        (site.location.latitude, site.location.longitude),
        (-33.9, 151.2)
    );
    assert_eq!(site.location.elevation, 0.0);
    assert_eq!(site.north, 0.0);
    assert_eq!(site.utc_offset, None);
    assert_eq!(site.ground_reflectance, 0.2);

    // No [site]: fine, with or without windows; a site without windows is fine too.
    assert_eq!(load_day(DAY).site, None);
    let no_window = BASE.to_owned() + SITE;
    let scene = load_day(&no_window);
    assert!(scene.site.is_some() && scene.windows.is_empty());
    // Elevation is in metres whatever the scene's unit.
    let cm = day(SITE)
        .replace("unit = \"m\"", "unit = \"cm\"")
        .replace("max_edge = 0.5", "max_edge = 50")
        .replace("max = [3, 2, 2.5]", "max = [300, 200, 250]")
        .replace(
            "[[1, 0, 0.8], [1, 0, 2], [2, 0, 2], [2, 0, 0.8]]",
            "[[100, 0, 80], [100, 0, 200], [200, 0, 200], [200, 0, 80]]",
        );
    let site = load_day(&cm).site.expect("a site");
    assert_eq!(site.location.elevation, 170.0);
}

#[test]
fn scene_site_utc_offset_forms() {
    let offset = crate::scene::daylight::utc_offset;
    // Seconds east of UTC, by hand.
    for (text, seconds) in [
        ("Z", 0),
        ("+00:00", 0),
        ("-00:00", 0),
        ("+01:00", 3600),
        ("+05:45", 5 * 3600 + 45 * 60),
        ("-03:30", -(3 * 3600 + 30 * 60)),
        ("\u{2212}08:00", -8 * 3600),
        ("+14:00", 14 * 3600),
        ("-12:00", -12 * 3600),
    ] {
        assert_eq!(offset(text), Some(seconds), "{text}");
    }
    for text in [
        "",
        "z",
        "UTC",
        "01:00",
        "+1:00",
        "+0100",
        "+01",
        "+01:0",
        "+01:60",
        "+14:01",
        "-12:30",
        "+15:00",
        "+01:00:00",
        " +01:00",
        "+a1:00",
    ] {
        assert_eq!(offset(text), None, "{text:?}");
    }
    // In a scene, a bad one names the field and its line.
    let text = day(&SITE.replace("\"+01:00\"", "\"+1:00\""));
    refused(
        &text,
        "utc_offset",
        &["site.utc_offset", "`+1:00`", "+HH:MM"],
    );
    let text = day(&SITE.replace("\"+01:00\"", "\"\u{2212}05:00\""));
    assert_eq!(
        load_day(&text).site.and_then(|s| s.utc_offset),
        Some(-5 * 3600)
    );
}

#[test]
fn scene_site_errors_name_the_field_and_line() {
    for (from, to, field) in [
        ("latitude = 48.21", "latitude = 91", "site.latitude"),
        ("latitude = 48.21", "latitude = nan", "site.latitude"),
        ("longitude = 16.37", "longitude = -180.5", "site.longitude"),
        ("elevation = 170", "elevation = 9500", "site.elevation"),
        ("north = 30", "north = 400", "site.north"),
        (
            "ground_reflectance = 0.15",
            "ground_reflectance = 1",
            "site.ground_reflectance",
        ),
        (
            "ground_reflectance = 0.15",
            "ground_reflectance = -0.1",
            "site.ground_reflectance",
        ),
    ] {
        let text = day(&SITE.replace(from, to));
        refused(&text, to, &[field]);
    }
    // The schema: a missing latitude, an unknown field.
    let text = day(&SITE.replace("latitude = 48.21\n", ""));
    refused(&text, "[site]", &["missing field `latitude`"]);
    let text = day(&SITE.replace("north = 30", "timezone = \"Europe/Vienna\""));
    refused(&text, "timezone", &["unknown field `timezone`"]);
}

// ---- the examples --------------------------------------------------------------------------

#[test]
fn scene_docs_daylight_example_loads() {
    // The block of docs/scene.md, "Daylight", with a [scene] header before it and a room with
    // a window of each glazing after it.
    let docs = include_str!("../../../../docs/scene.md");
    let section = docs.find("## Daylight").expect("a Daylight section");
    let start = docs[section..].find("```toml\n").expect("its example") + section + 8;
    let end = docs[start..].find("```").expect("its end") + start;
    let text = format!(
        "[scene]\nname = \"docs\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 1\n\n{}\n\
         [[room]]\nname = \"room\"\nmin = [0, 0, 0]\nmax = [6, 4, 3]\nmaterial = \"facade\"\n\
         openings = [\"a\", \"b\", \"c\"]\n\
         [[quad]]\nname = \"a\"\nmaterial = \"glass\"\n\
         corners = [[1, 0, 1], [1, 0, 2], [2, 0, 2], [2, 0, 1]]\n\
         [[quad]]\nname = \"b\"\nmaterial = \"single\"\n\
         corners = [[3, 0, 1], [3, 0, 2], [4, 0, 2], [4, 0, 1]]\n\
         [[quad]]\nname = \"c\"\nmaterial = \"frosted\"\n\
         corners = [[1, 1, 3], [1, 2, 3], [2, 2, 3], [2, 1, 3]]\n",
        &docs[start..end]
    );
    let scene = load_day(&text);
    let site = scene.site.as_ref().expect("a site");
    assert_eq!(site.utc_offset, Some(3600));
    let glazing: Vec<Glazing> = scene.windows.iter().map(|w| w.glazing).collect();
    let expected = [
        Glazing::clear(0.70, 2),
        Glazing::clear(0.88, 1),
        Glazing::diffusing(0.6, 2),
    ]
    .map(|g| g.expect("valid"));
    assert_eq!(glazing, expected);
    // The block has all six faces.
    assert_eq!(scene.obstructions.len(), 6);
}

#[test]
fn scene_office_daylight_example() {
    let scene = load(&example("office-daylight")).unwrap_or_else(|e| panic!("{e}"));
    let site = scene.site.as_ref().expect("a site");
    assert_eq!(
        (site.location.latitude, site.location.longitude),
        (48.21, 16.37)
    );
    assert_eq!(site.utc_offset, Some(3600));
    // One window, clear double glazing of τ_n 0.70, and no window channel.
    assert_eq!(scene.windows.len(), 1);
    let window = &scene.windows[0];
    assert_eq!(scene.surfaces[window.surface].name, "window");
    assert_eq!(window.glazing, Glazing::clear(0.70, 2).expect("valid"));
    let channels: Vec<&str> = scene.channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(channels, ["lum1", "lum2", "lum3", "lum4"]);
    assert_eq!((scene.sensors.len(), scene.zones.len()), (2, 2));
    // The window looks due south: its outward normal (against its patches') is the
    // horizontal direction of azimuth 180° in the room's frame (`daylight::room_direction`).
    let south = crate::daylight::room_direction(0.0, 180.0, site.north);
    for p in patches(&scene, "window") {
        let out = -p.normal;
        assert!((Vec3::new(south[0], south[1], south[2]) - out).length() < 1e-12);
    }
    // Outside: the overhang and the five faces of the building across the street.
    assert_eq!(scene.obstructions.len(), 6);
    // The same office as `examples/office` inside, but for the glass's reflectance.
    let office = load(&example("office")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(office.patches, scene.patches);
    assert_eq!(office.faces, scene.faces);
}
