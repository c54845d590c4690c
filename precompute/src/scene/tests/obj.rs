//! OBJ/MTL geometry: missing files named, units and transform applied, RGB reduced to the
//! photopic band, bad values located in their file.

use super::*;

const OBJ_SCENE: &str = "[scene]\nname = \"o\"\nbands = \"rgb\"\nunit = \"cm\"\nmax_edge = 50\n\n[[obj]]\nfile = \"model.obj\"\n";

#[test]
fn scene_error_missing_obj_names_path() {
    let dir = scratch("missing-obj");
    let m = match parse(OBJ_SCENE, &dir.join("test-scene.toml")) {
        Ok(_) => panic!("missing OBJ accepted"),
        Err(e) => e.to_string(),
    };
    assert_names(&m, &["obj.file", "model.obj", ":8:", "not found"]);
}

#[test]
fn scene_error_missing_mtl_names_path() {
    let dir = scratch("missing-mtl");
    std::fs::write(
        dir.join("model.obj"),
        "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\ng t\nusemtl x\nf 1 2 3\n",
    )
    .expect("write obj");
    let m = match parse(OBJ_SCENE, &dir.join("test-scene.toml")) {
        Ok(_) => panic!("missing MTL accepted"),
        Err(e) => e.to_string(),
    };
    assert_names(&m, &["gone.mtl", "not found"]);
}

#[test]
fn scene_obj_units_transform_and_photopic_reduction() {
    let dir = scratch("obj-ok");
    std::fs::write(
        dir.join("model.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 100 0 0\nv 100 100 0\nv 0 100 0\ng sheet\nusemtl grey\nf 1 2 3 4\n",
    )
    .expect("write obj");
    std::fs::write(dir.join("m.mtl"), "newmtl grey\nKd 0.2 0.4 0.6\nKe 0 0 0\n")
        .expect("write mtl");
    let text = format!("{OBJ_SCENE}translate = [0, 0, 250]\n").replace("\"rgb\"", "\"photopic\"");
    let scene = parse(&text, &dir.join("test-scene.toml")).expect("OBJ scene loads");
    assert_eq!(scene.surfaces[0].name, "sheet");
    assert_eq!(scene.patches.len(), 4); // 1 m square at 0.5 m edges
    let total: f64 = scene.patches.iter().map(|p| p.area).sum();
    assert!((total - 1.0).abs() < 1e-12);
    assert!(scene
        .patches
        .iter()
        .all(|p| (p.centroid.z - 2.5).abs() < 1e-12));
    let y = 0.2126 * 0.2 + 0.7152 * 0.4 + 0.0722 * 0.6;
    assert!((scene.reflectance[0][0] - y).abs() < 1e-15);

    // A bad Kd names the MTL file and the material.
    std::fs::write(dir.join("m.mtl"), "newmtl grey\nKd 1.2 0.4 0.6\n").expect("write mtl");
    let m = match parse(&text, &dir.join("test-scene.toml")) {
        Ok(_) => panic!("Kd above 1 accepted"),
        Err(e) => e.to_string(),
    };
    assert!(m.contains("m.mtl") && m.contains("`grey` Kd"), "{m}");
    std::fs::write(dir.join("m.mtl"), "newmtl grey\nKd 0.2 0.4 0.6\n").expect("write mtl");

    // A bad face in the OBJ names the OBJ file and the surface.
    std::fs::write(
        dir.join("model.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 2 0 0\ng line\nusemtl grey\nf 1 2 3\n",
    )
    .expect("write obj");
    let m = match parse(&text, &dir.join("test-scene.toml")) {
        Ok(_) => panic!("degenerate OBJ face accepted"),
        Err(e) => e.to_string(),
    };
    assert!(
        m.contains("model.obj") && m.contains("surface `line`") && m.contains("face 1"),
        "{m}"
    );
}

/// MTL `Ke` is an emitted radiance by default, as renderers read it (exitance = π·Ke for a
/// Lambertian emitter); `ke = "exitance"` takes it as the exitance itself. And `up = "y"` turns
/// the file by +90° about x: OBJ (x, y, z) is scene (x, −z, y).
#[test]
fn scene_obj_ke_meaning_and_y_up_axes() {
    let dir = scratch("obj-ke");
    // A 1 m square in the OBJ's x–z plane at y = 2, facing +y (up, in a y-up file).
    std::fs::write(
        dir.join("model.obj"),
        "mtllib m.mtl\nv 0 2 0\nv 0 2 -1\nv 1 2 -1\nv 1 2 0\ng lamp\nusemtl glow\nf 1 4 3 2\n",
    )
    .expect("write obj");
    std::fs::write(dir.join("m.mtl"), "newmtl glow\nKd 0.5 0.5 0.5\nKe 1 2 3\n")
        .expect("write mtl");
    let base = "[scene]\nname = \"o\"\nbands = \"rgb\"\nunit = \"m\"\nmax_edge = 2\n\n\
                [[obj]]\nfile = \"model.obj\"\nup = \"y\"\n";
    let channel = "\n[[channel]]\nname = \"lamp\"\nsurfaces = [\"lamp\"]\n";
    let radiance = parse(&format!("{base}{channel}"), &dir.join("s.toml")).expect("loads");
    let pi = std::f64::consts::PI;
    for (b, ke) in [1.0, 2.0, 3.0].into_iter().enumerate() {
        assert!((radiance.emission[0][b] - pi * ke).abs() < 1e-12);
    }
    let exitance = parse(
        &format!("{base}ke = \"exitance\"\n{channel}"),
        &dir.join("s.toml"),
    )
    .expect("loads");
    assert_eq!(exitance.emission[0], vec![1.0, 2.0, 3.0]);
    // OBJ y = 2 is scene z = 2; OBJ z in [−1, 0] is scene y in [0, 1]; the normal +y is +z.
    let p = &radiance.patches[0];
    assert!((p.centroid.z - 2.0).abs() < 1e-12, "{:?}", p.centroid);
    assert!((p.centroid.y - 0.5).abs() < 1e-12 && (p.centroid.x - 0.5).abs() < 1e-12);
    assert!((p.normal.z - 1.0).abs() < 1e-12, "{:?}", p.normal);
    // An exitance beyond what a basis stores names the convention.
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl glow\nKd 0.5 0.5 0.5\nKe 4e8 0 0\n",
    )
    .expect("write mtl");
    let m = match parse(&format!("{base}{channel}"), &dir.join("s.toml")) {
        Ok(_) => panic!("π·Ke above the largest exitance accepted"),
        Err(e) => e.to_string(),
    };
    assert!(m.contains("m.mtl") && m.contains("Ke (radiance"), "{m}");
}

/// In a scene without rooms a sensor may lie a few sizes of the scene away (looking at it),
/// but one 100 m from a 1 m box (a `translate` or unit slip) is an error naming it, its line
/// and the scene's extent.
#[test]
fn scene_error_sensor_outside_an_obj_scene() {
    let dir = scratch("obj-sensor");
    std::fs::write(
        dir.join("model.obj"),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
         g box\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n",
    )
    .expect("write obj");
    let base = "[scene]\nname = \"o\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 1\n\n\
                [materials.default]\nreflectance = 0.5\n\n\
                [[obj]]\nfile = \"model.obj\"\n\n[surfaces.box]\nmaterial = \"default\"\n\n";
    let sensor =
        |at: &str| format!("[[sensor]]\nname = \"s\"\nposition = {at}\nnormal = [0, 0, 1]\n");
    parse(
        &format!("{base}{}", sensor("[0.5, 0.5, -5.0]")),
        &dir.join("test-scene.toml"),
    )
    .expect("a sensor inside the box loads");
    let m = match parse(
        &format!("{base}{}", sensor("[0.5, 100.5, 0.2]")),
        &dir.join("test-scene.toml"),
    ) {
        Ok(_) => panic!("a sensor 100 m outside accepted"),
        Err(e) => e.to_string(),
    };
    assert_names(
        &m,
        &[
            "sensor `s`.position",
            ":18:",
            "from the scene",
            "[0.0, 0.0, 0.0]",
        ],
    );
}

/// A colour given as one grey value is that grey in every band (the MTL format allows it; the
/// OBJ reader takes exactly three and once panicked on one: found by the `obj_mtl` fuzz
/// target), a comment after a colour is no value, and two values are an error at their line.
#[test]
fn scene_mtl_grey_colours_and_comments() {
    let dir = scratch("mtl-grey");
    std::fs::write(
        dir.join("model.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 100 0 0\nv 100 100 0\nv 0 100 0\ng sheet\nusemtl grey\nf 1 2 3 4\n",
    )
    .expect("write obj");
    let origin = dir.join("test-scene.toml");
    let reflectance = |mtl: &str| {
        std::fs::write(dir.join("m.mtl"), mtl).expect("write mtl");
        parse(OBJ_SCENE, &origin).map(|scene| scene.reflectance[0].clone())
    };
    let three = reflectance("newmtl grey\nKd 0.4 0.4 0.4\nKe 0 0 0\n").expect("three values");
    assert_eq!(three, vec![0.4; 3]);
    let grey = reflectance("newmtl grey\nKd 0.4\nKe 0\n").expect("one grey value");
    assert_eq!(grey, three);
    let commented = reflectance("newmtl grey\nKd 0.4 # grey\nKe 0 0 0 # dark\n")
        .expect("comments after the values");
    assert_eq!(commented, three);
    let m = match reflectance("newmtl grey\nKd 0.4 0.4\n") {
        Ok(_) => panic!("a colour of two values accepted"),
        Err(e) => e.to_string(),
    };
    for part in ["m.mtl:2", "`Kd` takes 1 or 3 number(s), found 2"] {
        assert!(m.contains(part), "`{part}` missing from: {m}");
    }
}
