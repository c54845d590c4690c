//! gbXML space boundaries (docs/scene.md, "Importing a building model"): a space's faces are
//! its `SpaceBoundary` polygons (the interior face of each wall, floor and roof) where the
//! file gives them, not the surfaces' `PlanarGeometry`, which exporters place on the
//! construction's centre line; a surface's openings are moved into its boundary's plane.
//!
//! The reference is the L-shaped office of `examples/import/l-office.xml`, whose surfaces lie
//! on the room's interior faces. The same model with every surface and opening moved outward
//! by half a wall's thickness, and the interior faces given as space boundaries, must give
//! the same scene, patch for patch and bit for bit.

use std::path::{Path, PathBuf};

use eigenrad_precompute::scene::{load, Scene};

/// Half the thickness of the walls, floor and roof of the thick model, metres.
const HALF_THICKNESS: f64 = 0.1;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("eigenrad-boundaries-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The corners of every `CartesianPoint` in `text`, in order.
fn points(text: &str) -> Vec<[f64; 3]> {
    text.split("<CartesianPoint>")
        .skip(1)
        .map(|p| {
            let p = &p[..p.find("</CartesianPoint>").unwrap()];
            let c: Vec<f64> = p
                .split("<Coordinate>")
                .skip(1)
                .map(|c| {
                    c[..c.find("</Coordinate>").unwrap()]
                        .trim()
                        .parse()
                        .unwrap()
                })
                .collect();
            [c[0], c[1], c[2]]
        })
        .collect()
}

/// A PolyLoop of `corners`, as gbXML writes it.
fn poly_loop(corners: &[[f64; 3]]) -> String {
    let mut out = String::from("<PolyLoop>");
    for c in corners {
        out.push_str("<CartesianPoint>");
        for x in c {
            out.push_str(&format!("<Coordinate>{x}</Coordinate>"));
        }
        out.push_str("</CartesianPoint>");
    }
    out + "</PolyLoop>"
}

/// The unit normal of a polygon by Newell's method (outward for a gbXML exterior surface,
/// wound counter-clockwise seen from outside).
fn normal(corners: &[[f64; 3]]) -> [f64; 3] {
    let mut n = [0.0; 3];
    for (k, a) in corners.iter().enumerate() {
        let b = corners[(k + 1) % corners.len()];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    n.map(|x| x / length)
}

/// `l-office.xml` with thick constructions: each surface's PlanarGeometry (and its openings')
/// moved outward by [`HALF_THICKNESS`], the interior face kept as the space's boundary of that
/// surface when `boundaries` is set.
fn thick_model(boundaries: bool) -> String {
    let text = std::fs::read_to_string(root().join("examples/import/l-office.xml")).unwrap();
    let mut out = String::new();
    let mut space_boundaries = String::new();
    let mut rest = text.as_str();
    while let Some(start) = rest.find("<Surface ") {
        let end = start + rest[start..].find("</Surface>").unwrap();
        out.push_str(&rest[..start]);
        let surface = &rest[start..end];
        let id_start = surface.find("id=\"").unwrap() + 4;
        let id = &surface[id_start..id_start + surface[id_start..].find('"').unwrap()];
        // The surface's own loop comes before its openings'.
        let first = &surface[surface.find("<PolyLoop>").unwrap()..];
        let own = points(&first[..first.find("</PolyLoop>").unwrap()]);
        let n = normal(&own);
        space_boundaries.push_str(&format!(
            "<SpaceBoundary isSecondLevelBoundary=\"false\" surfaceIdRef=\"{id}\">\
             <PlanarGeometry>{}</PlanarGeometry></SpaceBoundary>\n",
            poly_loop(&own)
        ));
        // Every corner of the surface and its openings moved outward.
        let mut moved = String::new();
        let mut tail = surface;
        while let Some(p) = tail.find("<PolyLoop>") {
            let q = p + tail[p..].find("</PolyLoop>").unwrap() + "</PolyLoop>".len();
            moved.push_str(&tail[..p]);
            let corners: Vec<[f64; 3]> = points(&tail[p..q])
                .iter()
                .map(|c| [0, 1, 2].map(|k| c[k] + HALF_THICKNESS * n[k]))
                .collect();
            moved.push_str(&poly_loop(&corners));
            tail = &tail[q..];
        }
        moved.push_str(tail);
        out.push_str(&moved);
        rest = &rest[end..];
    }
    out.push_str(rest);
    if boundaries {
        out = out.replacen("</Space>", &format!("{space_boundaries}</Space>"), 1);
    }
    out
}

/// The L-office's example scene over `model`, at a coarse mesh.
fn scene_over(model: &Path, dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(root().join("examples/import/l-office-gbxml.toml"))
        .unwrap()
        .replace("max_edge = 0.6", "max_edge = 2.0")
        .replace(
            "file = \"l-office.xml\"",
            &format!("file = {:?}", model.display().to_string()),
        )
        .replace(
            "\"../photometry/",
            &format!("\"{}/examples/photometry/", root().display()),
        );
    let path = dir.join(format!(
        "{}.toml",
        model.file_stem().unwrap().to_string_lossy()
    ));
    std::fs::write(&path, text).unwrap();
    path
}

fn load_scene(path: &Path) -> Scene {
    load(path).unwrap_or_else(|e| panic!("{}: {e:#}", path.display()))
}

#[test]
fn space_boundaries_give_the_interior_faces_not_the_centre_lines() {
    let dir = scratch("thick");
    let interior = scene_over(&root().join("examples/import/l-office.xml"), &dir);
    let thick = dir.join("thick.xml");
    std::fs::write(&thick, thick_model(true)).unwrap();
    let (want, got) = (load_scene(&interior), load_scene(&scene_over(&thick, &dir)));
    assert_eq!(want.patches.len(), got.patches.len());
    for (k, (a, b)) in want.patches.iter().zip(&got.patches).enumerate() {
        assert_eq!(a, b, "patch {k}");
    }
    assert_eq!(want.reflectance, got.reflectance);
    assert_eq!(
        want.windows, got.windows,
        "the openings moved into the boundaries' planes"
    );
    assert_eq!(want.adjacency, got.adjacency);
    println!(
        "{} patches, {} windows: the same as the model on the interior faces",
        got.patches.len(),
        got.windows.len()
    );
}

/// The thick model's surfaces alone do not describe the room: their centre-line walls stop
/// short of the floor and the roof, which lie half a thickness further out. Without the
/// boundaries the import reads those surfaces, and says so, naming the face.
#[test]
fn without_its_boundaries_the_thick_model_is_refused_naming_a_wall() {
    let dir = scratch("centre-lines");
    let thick = dir.join("centre.xml");
    std::fs::write(&thick, thick_model(false)).unwrap();
    match load(&scene_over(&thick, &dir)) {
        Ok(_) => panic!("the centre-line surfaces imported as a room"),
        Err(e) => {
            let message = format!("{e:#}");
            assert!(
                message.contains("centre.xml:") && message.contains("does not run from the floor"),
                "{message}"
            );
        }
    }
}
