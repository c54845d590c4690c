//! One test per validation error of a scene file: the message names the file and the field
//! or line.

use super::*;

#[test]
fn scene_error_unknown_field_names_line() {
    let extra =
        "\n[[sensor]]\nname = \"s\"\nposition = [0, 0, 1]\nnormal = [0, 0, 1]\nhalf_angel = 30\n";
    let m = error(extra);
    assert_names(
        &m,
        &[&format!(":{}:", line_of(extra, "half_angel")), "half_angel"],
    );
}

#[test]
fn scene_error_reflectance_out_of_range() {
    let m = error_in(&BASE.replace(
        "white = { reflectance = 0.5 }",
        "white = { reflectance = 1.0 }",
    ));
    assert_names(&m, &["materials.white.reflectance", ":8:"]);
    let m = error_in(&BASE.replace(
        "white = { reflectance = 0.5 }",
        "white = { reflectance = -0.1 }",
    ));
    assert_names(&m, &["materials.white.reflectance"]);
}

#[test]
fn scene_error_band_count() {
    let m = error_in(&BASE.replace("reflectance = 0.5", "reflectance = [0.5, 0.5, 0.5]"));
    assert_names(
        &m,
        &[
            "materials.white.reflectance",
            "expected 1 value(s), found 3",
        ],
    );
}

#[test]
fn scene_error_negative_or_nonfinite_exitance() {
    let m = error_in(&BASE.replace("emission = 100", "emission = -5"));
    assert_names(&m, &["materials.lamp.emission", ":9:"]);
    let extra = "\n[[channel]]\nname = \"c\"\nsurfaces = [\"a\"]\nexitance = nan\n";
    let m = error(extra);
    assert_names(
        &m,
        &[
            "channel `c`.exitance",
            &format!(":{}:", line_of(extra, "nan")),
        ],
    );
    let extra = "\n[[channel]]\nname = \"c\"\nsurfaces = [\"a\"]\nflux = -3\n";
    assert_names(&error(extra), &["channel `c`.flux"]);
}

#[test]
fn scene_error_nonfinite_coordinates() {
    let extra = "\n[[quad]]\nname = \"b\"\nmaterial = \"white\"\ncorners = [[0, 0, 0], [inf, 0, 0], [1, 1, 0], [0, 1, 0]]\n";
    let m = error(extra);
    assert_names(
        &m,
        &["quad `b`.corners", &format!(":{}:", line_of(extra, "inf"))],
    );
}

#[test]
fn scene_error_degenerate_face() {
    let extra = "\n[[quad]]\nname = \"b\"\nmaterial = \"white\"\ncorners = [[0, 0, 0], [1, 0, 0], [1, 0, 0], [0, 1, 0]]\n";
    let m = error(extra);
    assert_names(
        &m,
        &[
            "surface `b`",
            "degenerate",
            &format!(":{}:", line_of(extra, "corners")),
        ],
    );
    let extra = "\n[[quad]]\nname = \"b\"\nmaterial = \"white\"\ncorners = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]\n";
    assert_names(&error(extra), &["surface `b`", "degenerate"]);
}

#[test]
fn scene_error_nonplanar_quad() {
    let extra = "\n[[quad]]\nname = \"b\"\nmaterial = \"white\"\ncorners = [[0, 0, 0], [1, 0, 0], [1, 1, 0.1], [0, 1, 0]]\n";
    let m = error(extra);
    assert_names(
        &m,
        &[
            "surface `b`",
            "non-planar",
            &format!(":{}:", line_of(extra, "corners")),
        ],
    );
    // Within a looser tolerance, or triangulated, it is accepted.
    let loose = format!("{BASE}{extra}").replace(
        "max_edge = 0.5",
        "max_edge = 0.5\nplanarity_tolerance = 0.1",
    );
    assert!(parse(&loose, Path::new(FILE)).is_ok());
    let split = format!("{BASE}{extra}\n[surfaces.b]\ntriangulate = true\n");
    assert!(parse(&split, Path::new(FILE)).is_ok());
}

#[test]
fn scene_error_duplicate_names() {
    let extra = "\n[[quad]]\nname = \"a\"\nmaterial = \"white\"\ncorners = [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]\n";
    assert_names(
        &error(extra),
        &[
            "duplicate surface name `a`",
            &format!(":{}:", line_of(extra, "corners")),
        ],
    );
    let lamp = "\n[[quad]]\nname = \"l\"\nmaterial = \"lamp\"\ncorners = [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]]\n";
    let extra = format!("{lamp}\n[[channel]]\nname = \"c\"\nsurfaces = [\"l\"]\n\n[[channel]]\nname = \"c\"\nsurfaces = [\"l\"]\n");
    assert_names(&error(&extra), &["duplicate channel name `c`"]);
    let sensor = "\n[[sensor]]\nname = \"s\"\nposition = [0, 0, 1]\nnormal = [0, 0, 1]\n";
    assert_names(
        &error(&format!("{sensor}{sensor}")),
        &["duplicate sensor name `s`"],
    );
    let zone = "\n[[zone]]\nname = \"z\"\nsurfaces = [\"a\"]\n";
    assert_names(
        &error(&format!("{zone}{zone}")),
        &["duplicate zone name `z`"],
    );
    // A duplicate key in TOML itself: the parser names the line.
    let extra = "\n[materials.white]\nreflectance = 0.3\n";
    assert_names(
        &error(extra),
        &["duplicate key", &format!(":{}:", line_of(extra, "white"))],
    );
}

#[test]
fn scene_error_channel_without_emitter() {
    let extra = "\n[[channel]]\nname = \"c\"\nsurfaces = [\"a\"]\n";
    assert_names(
        &error(extra),
        &[
            "channel `c`",
            "none of its surfaces emits",
            &format!(":{}:", line_of(extra, "[[channel]]")),
        ],
    );
    let extra = "\n[[channel]]\nname = \"c\"\n";
    assert_names(&error(extra), &["channel `c`", "names no surface"]);
}

#[test]
fn scene_error_emitter_outside_channels() {
    let extra = "\n[[quad]]\nname = \"l\"\nmaterial = \"lamp\"\ncorners = [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]]\n";
    assert_names(
        &error(extra),
        &[
            "surface `l`",
            "no channel drives it",
            &format!(":{}:", line_of(extra, "\"lamp\"")),
        ],
    );
}

#[test]
fn scene_error_unknown_references() {
    let extra = "\n[[channel]]\nname = \"c\"\nsurfaces = [\"nope\"]\nexitance = 10\n";
    assert_names(
        &error(extra),
        &[
            "channel `c`.surfaces",
            "unknown surface `nope`",
            &format!(":{}:", line_of(extra, "nope")),
        ],
    );
    let extra = "\n[[quad]]\nname = \"b\"\nmaterial = \"whit\"\ncorners = [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]\n";
    assert_names(
        &error(extra),
        &[
            "unknown material `whit`",
            &format!(":{}:", line_of(extra, "whit")),
        ],
    );
    let extra = "\n[surfaces.nope]\nflip = true\n";
    assert_names(&error(extra), &["unknown surface `nope`"]);
    let extra = "\n[[zone]]\nname = \"z\"\nwork_plane = { room = \"hall\", height = 0.8 }\n";
    assert_names(
        &error(extra),
        &[
            "unknown room `hall`",
            &format!(":{}:", line_of(extra, "hall")),
        ],
    );
    let extra = "\n[[channel]]\nname = \"c\"\nmaterials = [\"neon\"]\n";
    assert_names(&error(extra), &["channel `c`.materials", "`neon`"]);
}

#[test]
fn scene_error_sensor_zero_normal() {
    let extra = "\n[[sensor]]\nname = \"s\"\nposition = [0, 0, 1]\nnormal = [0, 0, 0]\n";
    assert_names(
        &error(extra),
        &[
            "sensor `s`.normal",
            &format!(":{}:", line_of(extra, "normal")),
        ],
    );
    let extra =
        "\n[[sensor]]\nname = \"s\"\nposition = [0, 0, 1]\nnormal = [0, 0, 1]\nhalf_angle = 120\n";
    assert_names(&error(extra), &["sensor `s`.half_angle"]);
}

#[test]
fn scene_error_wrong_type_or_variant_names_line() {
    let m = error_in(&BASE.replace("reflectance = 0.5", "reflectance = \"high\""));
    assert_names(&m, &[":8:", "expected a number, or a list of numbers"]);
    let m = error_in(&BASE.replace("unit = \"m\"", "unit = \"yd\""));
    assert_names(&m, &[":4:", "unknown variant `yd`"]);
    let m = error("\n[[sensor]]\nname = \"s\"\nposition = [0, 0, 1]\n");
    assert_names(&m, &["missing field `normal`"]);
}

#[test]
fn scene_error_surface_in_two_channels() {
    let lamp = "\n[[quad]]\nname = \"l\"\nmaterial = \"lamp\"\ncorners = [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]]\n";
    let extra = format!(
        "{lamp}\n[[channel]]\nname = \"c1\"\nsurfaces = [\"l\"]\n\n[[channel]]\nname = \"c2\"\nmaterials = [\"lamp\"]\n"
    );
    assert_names(
        &error(&extra),
        &[
            "surface `l`",
            "`c1`",
            "`c2`",
            &format!(":{}:", line_of(&extra, "c2") - 1),
        ],
    );
}

#[test]
fn scene_error_missing_scene_file_names_path() {
    let path = scratch("missing-scene").join("nothing-here.toml");
    let m = match load(&path) {
        Ok(_) => panic!("missing scene accepted"),
        Err(e) => e.to_string(),
    };
    assert!(
        m.contains("nothing-here.toml") && m.contains("cannot read"),
        "{m}"
    );
}
