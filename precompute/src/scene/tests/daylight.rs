//! The daylight part of a scene file: the `[site]`, glazed materials and their windows, and
//! exterior surfaces (obstructions). Every rule has a test that breaks it and checks the
//! message names the file, the line and the field; the geometry of obstructions is checked
//! against the boxes and corners written in the file.

use eigenrad_runtime::sky::glazing::Glazing;

use super::*;

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

// ---- glazing and windows -------------------------------------------------------------------

#[test]
fn scene_glazing_fields_parse() {
    // Reference: the runtime's own constructors, which the transport will use.
    let glazing = |extra: &str| {
        let text = day(extra).replace("material = \"glass\"", "material = \"g\"");
        let scene = load_day(&text);
        assert_eq!(scene.windows.len(), 1);
        scene.windows[0].glazing
    };
    let two = Glazing::clear(0.70, 2).expect("valid");
    assert_eq!(
        glazing("\n[materials.g]\nreflectance = 0.08\ntransmittance = 0.70\n"),
        two
    );
    assert_eq!(
        glazing("\n[materials.g]\nreflectance = 0.08\ntransmittance = 0.70\nglazing = \"clear\"\npanes = 2\n"),
        two
    );
    assert_eq!(
        glazing("\n[materials.g]\nreflectance = 0.08\ntransmittance = 0.88\npanes = 1\n"),
        Glazing::clear(0.88, 1).expect("valid")
    );
    let frosted = glazing(
        "\n[materials.g]\nreflectance = 0.1\ntransmittance = 0.6\nglazing = \"diffusing\"\n",
    );
    assert!(frosted.is_diffusing());
    assert_eq!(frosted, Glazing::diffusing(0.6, 2).expect("valid"));
    assert_eq!(
        glazing("\n[materials.g]\nreflectance = 0.05\ntransmittance = 0.5\npanes = 3\n").panes(),
        3
    );
    // The window's surface keeps its reflectance: a patch of ρ = 0.08 to the radiosity.
    let scene = load_day(DAY);
    let w = surface(&scene, "window");
    assert_eq!(w.reflectance, vec![0.08]);
}

#[test]
fn scene_glazing_errors_name_the_field_and_line() {
    let material = |body: &str| day(&format!("\n[materials.g]\n{body}\n"));
    for (body, at, parts) in [
        (
            "reflectance = 0.1\ntransmittance = 0",
            "transmittance",
            &["materials.g.transmittance", "(0, 1)"][..],
        ),
        (
            "reflectance = 0.1\ntransmittance = 1",
            "transmittance",
            &["materials.g.transmittance", "(0, 1)"],
        ),
        (
            "reflectance = 0.1\ntransmittance = -0.2",
            "transmittance",
            &["materials.g.transmittance"],
        ),
        // Above non-absorbing double glazing (0.8491), below single (0.9183).
        (
            "reflectance = 0.05\ntransmittance = 0.9",
            "transmittance",
            &["materials.g.transmittance", "non-absorbing", "2 pane(s)"],
        ),
        (
            "reflectance = 0.05\ntransmittance = 0.85\npanes = 3",
            "transmittance",
            &["materials.g.transmittance", "3 pane(s)"],
        ),
        (
            "reflectance = 0.1\ntransmittance = 0.7\npanes = 0",
            "panes",
            &["materials.g.panes", "1 to 3"],
        ),
        (
            "reflectance = 0.1\ntransmittance = 0.7\npanes = 4",
            "panes",
            &["materials.g.panes", "1 to 3"],
        ),
        (
            "reflectance = 0.1\npanes = 2",
            "panes",
            &["materials.g.panes", "no `transmittance`"],
        ),
        (
            "reflectance = 0.1\nglazing = \"diffusing\"",
            "glazing",
            &["materials.g.glazing", "no `transmittance`"],
        ),
        (
            "reflectance = 0.1\ntransmittance = 0.7\nglazing = \"frosted\"",
            "glazing",
            &["unknown variant `frosted`"],
        ),
        (
            "reflectance = 0.4\ntransmittance = 0.7",
            "transmittance",
            &["materials.g.transmittance", "exceeds 1"],
        ),
        (
            "reflectance = 0.1\ntransmittance = 0.7\nemission = 50",
            "emission",
            &["materials.g.emission", "cannot emit"],
        ),
    ] {
        refused(&material(body), at, parts);
    }
    // 0.9 is fine for one pane.
    assert!(parse(
        &material("reflectance = 0.05\ntransmittance = 0.9\npanes = 1"),
        Path::new(FILE)
    )
    .is_ok());
    // rgb scenes: no glazing yet.
    let rgb = DAY
        .replace("bands = \"photopic\"", "bands = \"rgb\"")
        .replace(
            "glass = { reflectance = 0.08, transmittance = 0.70 }",
            "glass = { reflectance = [0.08, 0.08, 0.08], transmittance = 0.70 }",
        );
    refused(
        &rgb,
        "glass =",
        &["materials.glass.transmittance", "rgb", "photopic"],
    );
}

#[test]
fn scene_windows_in_surface_order_facing_into_the_room() {
    // Two windows: the wall's and a skylight, named in `openings` in the other order.
    let text = day("\n[[quad]]\nname = \"skylight\"\nmaterial = \"glass\"\n\
         corners = [[1, 0.5, 2.5], [1, 1.5, 2.5], [2, 1.5, 2.5], [2, 0.5, 2.5]]\n")
    .replace(
        "openings = [\"window\"]",
        "openings = [\"skylight\", \"window\"]",
    );
    let scene = load_day(&text);
    let names: Vec<&str> = scene
        .windows
        .iter()
        .map(|w| scene.surfaces[w.surface].name.as_str())
        .collect();
    assert_eq!(names, ["window", "skylight"]);
    assert!(scene.windows[0].surface < scene.windows[1].surface);
    for (name, inward) in [
        ("window", Vec3::new(0.0, 1.0, 0.0)),
        ("skylight", Vec3::new(0.0, 0.0, -1.0)),
    ] {
        let ps = patches(&scene, name);
        assert!(!ps.is_empty());
        assert!(
            ps.iter().all(|p| (p.normal - inward).length() < 1e-12),
            "{name}"
        );
        // Hand-checked areas: 1 m × 1.2 m and 1 m × 1 m.
        let expected = if name == "window" { 1.2 } else { 1.0 };
        assert!((area(&scene, name) - expected).abs() < 1e-12, "{name}");
    }
    // A room's own face glazed in [surfaces] (a glass wall) is a window facing in.
    let text = DAY
        .replace("openings = [\"window\"]\n", "")
        .replace("name = \"window\"", "name = \"panel\"")
        .replace("material = \"glass\"", "material = \"white\"")
        + "\n[surfaces.\"room.wall_xmax\"]\nmaterial = \"glass\"\n";
    let scene = load_day(&text);
    assert_eq!(scene.windows.len(), 1);
    assert_eq!(
        scene.surfaces[scene.windows[0].surface].name,
        "room.wall_xmax"
    );
    assert!(patches(&scene, "room.wall_xmax")
        .iter()
        .all(|p| (p.normal - Vec3::new(-1.0, 0.0, 0.0)).length() < 1e-12));
    // A surface of another material is no window; no glazed material, no windows.
    assert!(load_day(BASE).windows.is_empty());
}

#[test]
fn scene_window_errors_name_both_and_the_line() {
    // A window cannot also be a channel's emitting surface.
    let text =
        day("\n[[channel]]\nname = \"daylight\"\nsurfaces = [\"window\"]\nexitance = 3000\n");
    refused(
        &text,
        "[[channel]]",
        &["surface `window`", "channel `daylight`", "window"],
    );
    // A window in a wall's plane but not cut out of it: the wall would hide it.
    let text = DAY.replace("openings = [\"window\"]\n", "");
    refused(
        &text,
        "corners = [[1, 0, 0.8]",
        &["window `window`", "room.wall_ymin", "openings"],
    );
}

// ---- exterior surfaces ---------------------------------------------------------------------

#[test]
fn scene_exterior_surfaces_are_not_meshed_and_change_nothing_inside() {
    // Reference: the same scene without them. The room's surfaces, patches, faces (the
    // occluders of its form factors), reflectances and emission are identical.
    let plain = load_day(&day(""));
    let shaded = load_day(&day(&format!("{OVERHANG}{OPPOSITE}")));
    assert_eq!(plain.surfaces, shaded.surfaces);
    assert_eq!(plain.patches, shaded.patches);
    assert_eq!(plain.faces, shaded.faces);
    assert_eq!(plain.reflectance, shaded.reflectance);
    assert_eq!(plain.emission, shaded.emission);
    assert_eq!(plain.windows, shaded.windows);
    assert!(plain.obstructions.is_empty());
    let names: Vec<&str> = shaded
        .obstructions
        .iter()
        .map(|o| o.name.as_str())
        .collect();
    assert_eq!(
        names,
        [
            "opposite.bottom",
            "opposite.top",
            "opposite.side_xmin",
            "opposite.side_xmax",
            "opposite.side_ymin",
            "opposite.side_ymax",
            "overhang",
        ],
        "blocks before quads, as surfaces are ordered"
    );
    assert!(shaded.obstructions.iter().all(|o| o.reflectance == 0.3));
    assert!(shaded
        .obstructions
        .iter()
        .flat_map(|o| &o.faces)
        .all(|f| f.patches.is_empty()));
    // Determinism: the same file, the same scene.
    assert_eq!(shaded, load_day(&day(&format!("{OVERHANG}{OPPOSITE}"))));
}

#[test]
fn scene_exterior_block_faces_face_out() {
    // Reference: the box from (−2, −8, 0) to (5, −5, 6) by hand: each face's outward normal,
    // the plane it lies in and its area.
    let (lo, hi) = (Vec3::new(-2.0, -8.0, 0.0), Vec3::new(5.0, -5.0, 6.0));
    let expected = [
        ("bottom", Vec3::new(0.0, 0.0, -1.0), lo.z, 7.0 * 3.0),
        ("top", Vec3::new(0.0, 0.0, 1.0), hi.z, 7.0 * 3.0),
        ("side_xmin", Vec3::new(-1.0, 0.0, 0.0), lo.x, 3.0 * 6.0),
        ("side_xmax", Vec3::new(1.0, 0.0, 0.0), hi.x, 3.0 * 6.0),
        ("side_ymin", Vec3::new(0.0, -1.0, 0.0), lo.y, 7.0 * 6.0),
        ("side_ymax", Vec3::new(0.0, 1.0, 0.0), hi.y, 7.0 * 6.0),
    ];
    for bottom in [true, false] {
        let block = if bottom {
            OPPOSITE.to_owned()
        } else {
            OPPOSITE.replace("exterior = true", "exterior = true\nbottom = false")
        };
        let scene = load_day(&day(&block));
        let wanted: Vec<_> = expected
            .iter()
            .filter(|e| bottom || e.0 != "bottom")
            .collect();
        assert_eq!(scene.obstructions.len(), wanted.len());
        for (o, (suffix, normal, plane, face_area)) in scene.obstructions.iter().zip(wanted) {
            assert_eq!(o.name, format!("opposite.{suffix}"));
            assert_eq!(o.faces.len(), 1);
            let polygon = &o.faces[0].polygon;
            assert!((polygon.normal() - *normal).length() < 1e-12, "{suffix}");
            assert!((polygon.area() - face_area).abs() < 1e-12, "{suffix}");
            let axis = [0, 1, 2]
                .into_iter()
                .find(|&k| normal.axis(k) != 0.0)
                .unwrap_or(0);
            assert!(polygon.vertices.iter().all(|v| v.axis(axis) == *plane));
            assert!(polygon
                .vertices
                .iter()
                .all(|v| (0..3).all(|k| v.axis(k) >= lo.axis(k) && v.axis(k) <= hi.axis(k))));
        }
    }
}

#[test]
fn scene_exterior_quad_keeps_its_winding() {
    let scene = load_day(&day(OVERHANG));
    let given = [
        Vec3::new(0.8, 0.0, 2.2),
        Vec3::new(2.2, 0.0, 2.2),
        Vec3::new(2.2, -0.6, 2.2),
        Vec3::new(0.8, -0.6, 2.2),
    ];
    let o = &scene.obstructions[0];
    assert_eq!(o.faces.len(), 1);
    assert_eq!(o.faces[0].polygon.vertices, given);
    assert!((o.faces[0].polygon.normal() - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
    // `flip` in [surfaces] reverses it; `material` there applies; `max_edge` is harmless.
    let text = day(&format!(
        "{OVERHANG}\n[surfaces.overhang]\nflip = true\nmaterial = \"white\"\nmax_edge = 0.1\n"
    ));
    let o = &load_day(&text).obstructions[0];
    let mut reversed = given.to_vec();
    reversed.reverse();
    assert_eq!(o.faces[0].polygon.vertices, reversed);
    assert_eq!(o.reflectance, 0.5);
    // In centimetres, converted to metres.
    let cm = format!(
        "{BASE}\n[[quad]]\nname = \"fin\"\nmaterial = \"white\"\nexterior = true\n\
         corners = [[0, 0, 100], [0, 0, 200], [0, 100, 200], [0, 100, 100]]\n"
    )
    .replace("unit = \"m\"", "unit = \"cm\"")
    .replace("max_edge = 0.5", "max_edge = 50")
    .replace(
        "[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]",
        "[[0, 0, 0], [100, 0, 0], [100, 100, 0], [0, 100, 0]]",
    );
    let o = &load_day(&cm).obstructions[0];
    assert_eq!(o.faces[0].polygon.vertices[1], Vec3::new(0.0, 0.0, 2.0));
}

#[test]
fn scene_exterior_obj_is_an_obstruction_and_an_input() {
    let dir = scratch("exterior-obj");
    std::fs::write(
        dir.join("fins.obj"),
        "mtllib fins.mtl\nv -0.5 0 0\nv -0.5 -1 0\nv -0.5 -1 2\nv -0.5 0 2\n\
         v 3.5 0 0\nv 3.5 0 2\nv 3.5 -1 2\nv 3.5 -1 0\n\
         g west\nusemtl grey\nf 1 2 3 4\ng east\nusemtl grey\nf 5 6 7 8\n",
    )
    .expect("write obj");
    std::fs::write(dir.join("fins.mtl"), "newmtl grey\nKd 0.3 0.3 0.3\n").expect("write mtl");
    let text = day("\n[[obj]]\nfile = \"fins.obj\"\nexterior = true\n");
    let path = dir.join("test-scene.toml");
    std::fs::write(&path, &text).expect("write scene");
    let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<&str> = scene.obstructions.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["west", "east"]);
    // Kd 0.3 grey in the photopic band: 0.3 (the BT.709 weights add up to 1).
    for o in &scene.obstructions {
        assert!((o.reflectance - 0.3).abs() < 1e-12);
        assert_eq!(o.faces.len(), 1);
    }
    assert!(!scene
        .surfaces
        .iter()
        .any(|s| s.name == "west" || s.name == "east"));
    // `inputs` lists the exterior OBJ file and its MTL, as for any OBJ file.
    let inputs = inputs(&path).expect("inputs");
    assert_eq!(
        inputs.files,
        vec![path.clone(), dir.join("fins.obj"), dir.join("fins.mtl")]
    );
}

#[test]
fn scene_exterior_errors_name_the_field_and_line() {
    // Not in a channel, a zone or a room's openings.
    let text = day(&format!(
        "{OVERHANG}\n[[channel]]\nname = \"c\"\nsurfaces = [\"overhang\"]\nexitance = 10\n"
    ));
    refused(
        &text,
        "surfaces = [\"overhang\"]",
        &["channel `c`.surfaces", "`overhang`", "exterior"],
    );
    let text = day(&format!(
        "{OVERHANG}\n[[channel]]\nname = \"c\"\nmaterials = [\"facade\"]\nexitance = 10\n"
    ));
    refused(
        &text,
        "materials = [\"facade\"]",
        &["channel `c`.materials", "`facade`", "exterior"],
    );
    let text = day(&format!(
        "{OPPOSITE}\n[[zone]]\nname = \"z\"\nsurfaces = [\"opposite.*\"]\n"
    ));
    refused(
        &text,
        "surfaces = [\"opposite.*\"]",
        &["zone `z`.surfaces", "exterior"],
    );
    let text = day(OVERHANG).replace(
        "openings = [\"window\"]",
        "openings = [\"window\", \"overhang\"]",
    );
    refused(
        &text,
        "openings =",
        &["room `room`.openings", "`overhang`", "exterior"],
    );
    // A pattern matching the room's surfaces as well takes only those.
    let text = day(&format!(
        "{OVERHANG}\n[[zone]]\nname = \"z\"\nsurfaces = [\"*\"]\n"
    ));
    let scene = load_day(&text);
    assert!(
        matches!(&scene.zones[0].kind, ZoneKind::Surfaces(p) if p.len() == scene.patches.len())
    );

    // Not emitting, not glazed, not in rgb scenes.
    let text = day(&OVERHANG.replace("material = \"facade\"", "material = \"lamp\""));
    refused(
        &text,
        "material = \"lamp\"",
        &["surface `overhang`.exterior", "emits"],
    );
    let text = day(&OVERHANG.replace("material = \"facade\"", "material = \"glass\""));
    refused(
        &text,
        "material = \"glass\"",
        &["surface `overhang`.exterior", "glazed"],
    );
    let rgb = format!("{BASE}{OVERHANG}")
        .replace("bands = \"photopic\"", "bands = \"rgb\"")
        .replace("material = \"facade\"", "material = \"white\"");
    refused(
        &rgb,
        "corners = [[0.8",
        &["surface `overhang`.exterior", "rgb"],
    );

    // Outside every room: a quad through the wall, a block overlapping the room.
    let through = OVERHANG
        .replace(
            "[2.2, -0.6, 2.2], [0.8, -0.6, 2.2]",
            "[2.2, 0.5, 2.2], [0.8, 0.5, 2.2]",
        )
        .replace(
            "[[0.8, 0, 2.2], [2.2, 0, 2.2],",
            "[[0.8, -0.6, 2.2], [2.2, -0.6, 2.2],",
        );
    let text = day(&through);
    refused(
        &text,
        "corners = [[0.8",
        &["surface `overhang`.exterior", "reaches into room `room`"],
    );
    let text = day(&OPPOSITE.replace("max = [5, -5, 6]", "max = [5, 0.5, 6]"));
    refused(
        &text,
        "[[block]]",
        &["opposite.", "reaches into room `room`"],
    );
    // Touching the room's faces is fine: a block flush against the wall y = 0 and the
    // overhang's edge on it.
    let flush = OPPOSITE.replace("max = [5, -5, 6]", "max = [5, 0, 6]");
    assert_eq!(
        load_day(&day(&format!("{flush}{OVERHANG}")))
            .obstructions
            .len(),
        7
    );

    // A room is the inside: `exterior` is not one of its fields.
    let text = DAY.replace(
        "openings = [\"window\"]",
        "openings = [\"window\"]\nexterior = true",
    );
    refused(&text, "exterior = true", &["unknown field `exterior`"]);
    // A bad face is reported as for any surface.
    let text = day(&OVERHANG.replace("[2.2, -0.6, 2.2]", "[2.2, -0.6, 2.9]"));
    refused(
        &text,
        "corners = [[0.8",
        &["surface `overhang`", "non-planar"],
    );
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
