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
