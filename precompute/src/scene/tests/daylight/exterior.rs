//! Exterior surfaces: obstructions outside the room, not meshed, facing the way the file
//! says, and every rule broken with the message naming the field and line.

use super::*;

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
