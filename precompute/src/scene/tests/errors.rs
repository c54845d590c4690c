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

/// A room for the work-plane tests, then a zone whose `work_plane` is `wp`.
fn work_plane_zone(wp: &str) -> String {
    format!(
        "\n[[room]]\nname = \"r\"\nmin = [0, 0, 0]\nmax = [4, 3, 2.5]\nmaterial = \"white\"\n\
         \n[[zone]]\nname = \"z\"\nwork_plane = {{ height = 0.8, {wp} }}\n"
    )
}

#[test]
fn scene_error_grid_fields() {
    for (wp, parts) in [
        (
            "grid = { spacing = -0.2 }",
            &["zone `z`.work_plane.grid.spacing", "positive"][..],
        ),
        (
            "grid = { spacing = 12 }",
            &["zone `z`.work_plane.grid.spacing", "at most 10 m"][..],
        ),
        (
            "grid = { spacing = 0.0001 }",
            &["zone `z`.work_plane.grid.spacing", "more than 10000"][..],
        ),
        ("grid = { spacng = 0.3 }", &["spacng"][..]),
        (
            "area = { min = [1, 1], max = [5, 2] }",
            &["zone `z`.work_plane.area", "inside room `r`"][..],
        ),
        (
            "area = { min = [2, 1], max = [1, 2] }",
            &["zone `z`.work_plane.area", "min below max"][..],
        ),
        (
            "area = { min = [1, 1, 0], max = [2, 2] }",
            &[
                "zone `z`.work_plane.area.min",
                "expected 2 value(s), found 3",
            ][..],
        ),
        ("area = { min = [1, 1] }", &["max"][..]),
        (
            "band = 0.5",
            &["zone `z`.work_plane.band", "give `area` too"][..],
        ),
        (
            "area = { min = [1, 1], max = [2, 2] }, band = [1, 0.5]",
            &["zone `z`.work_plane.band", "0 ≤ from < to"][..],
        ),
        (
            "area = { min = [1, 1], max = [2, 2] }, band = -0.5",
            &["zone `z`.work_plane.band", "0 ≤ from < to"][..],
        ),
        (
            "area = { min = [1, 1], max = [2, 2] }, band = [0, 1, 2]",
            &["zone `z`.work_plane.band", "expected 2 value(s), found 3"][..],
        ),
        (
            "area = { min = [0, 0], max = [4, 3] }, band = 0.5",
            &["zone `z`.work_plane.band", "leaves nothing inside room `r`"][..],
        ),
    ] {
        let extra = work_plane_zone(wp);
        let m = error(&extra);
        assert_names(&m, parts);
        assert_names(&m, &[&format!(":{}:", line_of(&extra, "work_plane"))]);
    }
}

#[test]
fn work_plane_grid_follows_the_rule_and_the_scene() {
    let grid = |wp: &str| {
        let scene = parse(&format!("{BASE}{}", work_plane_zone(wp)), Path::new(FILE)).unwrap();
        scene.zones[0]
            .grid
            .clone()
            .expect("a work plane has a grid")
    };
    let zone = |wp: &str| {
        let g = grid(wp);
        assert_eq!(g.pieces.len(), 1, "{wp}");
        g.pieces[0].clone()
    };
    // 4 m × 3 m less the default 0.5 m border: 3 m × 2 m, p = 0.2 × 5^(log10 3) = 0.4310 m,
    // 3/0.4310 = 6.96 → 7, 2/0.4310 = 4.64 → 5.
    let g = zone("max_edge = 0.5");
    assert_eq!((g.counts, g.border, g.explicit), ([7, 5], 0.5, false));
    assert!((g.spacing - 0.43105).abs() < 1e-4, "{}", g.spacing);
    assert!(g
        .points
        .iter()
        .all(|p| p.x > 0.5 && p.x < 3.5 && p.y > 0.5 && p.y < 2.5));
    let g = zone("margin = 1.0, grid = { spacing = 0.5 }");
    assert_eq!((g.counts, g.border, g.explicit), ([4, 2], 1.0, true));
    // A 1 m × 0.5 m task area, no border: d = 1 m gives p = 0.2 m, 5 × 3 points (0.5/0.2 =
    // 2.5 → 3), cells 0.2 m × 1/6 m, the first at (1.1, 1 + 1/12).
    let g = zone("area = { min = [1, 1], max = [2, 1.5] }");
    assert_eq!((g.counts, g.border), ([5, 3], 0.0));
    assert!(
        (g.points[0].x - 1.1).abs() < 1e-12 && (g.points[0].y - (1.0 + 1.0 / 12.0)).abs() < 1e-12
    );
    // Its 0.5 m surrounding, by hand: the strips below and above, 2 m × 0.5 m each
    // (p = 0.3247 m: 2/0.3247 = 6.16 → 7, 0.5/0.3247 = 1.54 → 2), and left and right of the
    // task area, 0.5 m × 0.5 m each (p = 0.2 × 5^(log10 0.5) = 0.1232 m: 4.06 → 5 × 5).
    let band = grid("area = { min = [1, 1], max = [2, 1.5] }, band = 0.5");
    let counts: Vec<[usize; 2]> = band.pieces.iter().map(|p| p.counts).collect();
    assert_eq!(counts, [[7, 2], [7, 2], [5, 5], [5, 5]]);
    assert_eq!(band.len(), 78);
    let inside =
        |p: &Vec3, [x0, y0, x1, y1]: [f64; 4]| p.x > x0 && p.x < x1 && p.y > y0 && p.y < y1;
    for (p, normal) in band.points() {
        assert!(inside(&p, [0.5, 0.5, 2.5, 2.0]), "{p:?} outside the band");
        assert!(!inside(&p, [1.0, 1.0, 2.0, 1.5]), "{p:?} in the task area");
        assert_eq!((p.z, normal), (0.8, Vec3::new(0.0, 0.0, 1.0)));
    }
    // At the walls the band stops: a task area in the corner keeps the strips above and to
    // its right; between 0.5 and 1 m from its edges, the background band, also four strips.
    let corner = grid("area = { min = [0, 0], max = [1, 1] }, band = 0.5");
    assert_eq!(corner.pieces.len(), 2);
    assert!(corner
        .points()
        .all(|(p, _)| inside(&p, [0.0, 0.0, 1.5, 1.5]) && !inside(&p, [0.0, 0.0, 1.0, 1.0])));
    let background = grid("area = { min = [1.5, 1], max = [2.5, 2] }, band = [0.5, 1.0]");
    assert_eq!(background.pieces.len(), 4);
    assert!(background
        .points()
        .all(|(p, _)| inside(&p, [0.5, 0.0, 3.5, 3.0]) && !inside(&p, [1.0, 0.5, 3.0, 2.5])));
}

/// A sensor over the base quad with `response` written after `response = `.
fn responding(response: &str) -> String {
    format!(
        "\n[[sensor]]\nname = \"s\"\nposition = [0.5, 0.5, 1]\nnormal = [0, 0, -1]\nresponse = {response}\n"
    )
}

#[test]
fn scene_sensor_responses_are_read() {
    let read = |response: &str| {
        let text = format!("{BASE}{}", responding(response));
        parse(&text, Path::new(FILE))
            .expect("valid response")
            .sensors
            .remove(0)
    };
    let cosine = read("{ preset = \"cosine\" }");
    assert_eq!((cosine.half_angle, cosine.response), (None, None));
    let cone = read("{ preset = \"cone\", half_angle = 30 }");
    assert!((cone.half_angle.unwrap_or(0.0) - 30f64.to_radians()).abs() < 1e-15);
    let shielded = read("{ preset = \"shielded\" }").response.expect("a table");
    assert!((shielded.view_edge() - 60f64.to_radians()).abs() < 1e-12);
    let inline = read("{ polar = [0, 45, 90], sensitivity = [1, 0.5, 0] }")
        .response
        .expect("a table");
    assert!((inline.at_angle(22.5f64.to_radians()) - 0.75).abs() < 1e-12);
}

#[test]
fn scene_error_bad_sensor_responses_name_the_field() {
    let cases: [(&str, &[&str]); 6] = [
        (
            "{ preset = \"fisheye\" }",
            &["sensor `s`.response.preset", "fisheye"],
        ),
        ("{ preset = \"cone\" }", &["sensor `s`.response.half_angle"]),
        (
            "{ preset = \"shielded\", cutoff = 90 }",
            &["sensor `s`.response.cutoff", "(0, 90)"],
        ),
        (
            "{ polar = [0, 45], sensitivity = [1] }",
            &["sensor `s`.response.sensitivity", "expected 2"],
        ),
        (
            "{ polar = [0, 45, 30], sensitivity = [1, 1, 1] }",
            &["sensor `s`.response.polar", "row 3", "increase"],
        ),
        (
            "{ preset = \"cosine\", file = \"s.dat\" }",
            &["sensor `s`.response", "exactly one"],
        ),
    ];
    for (response, parts) in cases {
        let extra = responding(response);
        let m = error(&extra);
        assert_names(&m, parts);
        assert_names(&m, &[&format!(":{}:", line_of(&extra, "response"))]);
    }
    let both = format!("{}half_angle = 30\n", responding("{ preset = \"cosine\" }"));
    assert_names(&error(&both), &["either `half_angle` or `response`"]);
}

#[test]
fn scene_error_bad_rsensor_file_names_its_file_and_line() {
    let dir = scratch("rsensor");
    let table = dir.join("cell.dat");
    std::fs::write(&table, "degrees\t0\t90\n0\t1\t1\n30\t0.5\t0.4\n60\t0\t0\n").expect("write");
    let scene = dir.join("test-scene.toml");
    let text = format!("{BASE}{}", responding("{ file = \"cell.dat\" }"));
    let m = match parse(&text, &scene) {
        Ok(_) => panic!("an azimuthal table is refused"),
        Err(e) => e.to_string(),
    };
    assert!(m.contains("cell.dat:3:") && m.contains("azimuth"), "{m}");
    std::fs::write(&table, "degrees\t0\t90\n0\t1\t1\n30\t0.5\t0.5\n60\t0\t0\n").expect("write");
    let read = parse(&text, &scene).expect("an axisymmetric table is read");
    // The table is one of the scene's inputs: no output may replace it.
    std::fs::write(&scene, &text).expect("write scene");
    let listed = crate::scene::inputs(&scene).expect("inputs");
    assert!(listed.files.contains(&table), "{:?}", listed.files);
    let r = read.sensors[0].response.as_ref().expect("a table");
    assert!((r.at_angle(15f64.to_radians()) - 0.75).abs() < 1e-12);
    let missing = format!("{BASE}{}", responding("{ file = \"none.dat\" }"));
    let m = match parse(&missing, &scene) {
        Ok(_) => panic!("a missing table is refused"),
        Err(e) => e.to_string(),
    };
    assert!(
        m.contains("file not found") && m.contains("none.dat"),
        "{m}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
