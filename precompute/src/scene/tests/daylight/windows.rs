//! Glazed materials and their windows: the glazing's fields, the windows in surface order
//! facing into the room, and every rule broken with the message naming the field and line.

use super::*;

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
