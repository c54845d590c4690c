//! Openings cut out of room faces: every area accounted for, no patch left behind an opening.

use super::*;

/// A closed 3 m × 2 m × 2.5 m room with four openings: one in the ceiling, two sharing an edge
/// in the wall y = 0 (one touching the floor), one covering a corner of the wall x = 3.
const OPENINGS: &str = r#"[scene]
name = "openings"
bands = "photopic"
unit = "m"
max_edge = 0.4

[materials]
white = { reflectance = 0.5 }
black = { reflectance = 0.0 }

[[room]]
name = "room"
min = [0, 0, 0]
max = [3, 2, 2.5]
material = "white"
openings = ["lamp", "left", "right", "corner"]

[[quad]]
name = "lamp"
material = "black"
corners = [[1.0, 0.7, 2.5], [1.0, 1.3, 2.5], [1.6, 1.3, 2.5], [1.6, 0.7, 2.5]]

[[quad]]
name = "left"
material = "black"
corners = [[0.5, 0, 0], [0.5, 0, 1.2], [1.5, 0, 1.2], [1.5, 0, 0]]

[[quad]]
name = "right"
material = "black"
corners = [[1.5, 0, 0.3], [1.5, 0, 1.0], [2.25, 0, 1.0], [2.25, 0, 0.3]]

[[quad]]
name = "corner"
material = "black"
corners = [[3, 1.5, 2.0], [3, 1.5, 2.5], [3, 2, 2.5], [3, 2, 2.0]]
"#;

/// The part of a patch's bounding box shared with an opening's, in the plane they share
/// (m²); zero when they only touch along an edge.
fn shared_area(a: &Patch, b: &Patch) -> f64 {
    let bounds = |p: &Patch, k: usize| {
        let v = p.polygon.vertices.iter().map(|c| c.axis(k));
        (
            v.clone().fold(f64::INFINITY, f64::min),
            v.fold(f64::NEG_INFINITY, f64::max),
        )
    };
    let mut area = 1.0;
    for k in 0..3 {
        let (a0, a1) = bounds(a, k);
        let (b0, b1) = bounds(b, k);
        if a1 - a0 < 1e-12 && b1 - b0 < 1e-12 {
            // The axis normal to both: they must share the plane.
            if (a0 - b0).abs() > 1e-12 {
                return 0.0;
            }
            continue;
        }
        area *= (a1.min(b1) - a0.max(b0)).max(0.0);
    }
    area
}

#[test]
fn scene_openings_account_for_every_area_and_leave_no_patch_behind() {
    let scene = parse(OPENINGS, Path::new(FILE)).expect("room with openings loads");
    // Every patch is a room face or an opening: the box's surface area exactly (to rounding).
    let total: f64 = scene.patches.iter().map(|p| p.area).sum();
    let box_area = 2.0 * (3.0 * 2.0 + 3.0 * 2.5 + 2.0 * 2.5);
    assert!(
        (total - box_area).abs() < 1e-12 * box_area,
        "{total} m² vs {box_area} m²"
    );
    assert!((area(&scene, "room.ceiling") - (6.0 - 0.36)).abs() < 1e-12);
    assert!((area(&scene, "room.wall_ymin") - (7.5 - 1.2 - 0.525)).abs() < 1e-12);
    assert!((area(&scene, "room.wall_xmax") - (5.0 - 0.25)).abs() < 1e-12);
    // No room patch overlaps an opening's patch, and every opening faces into the room.
    let centre = Vec3::new(1.5, 1.0, 1.25);
    for opening in ["lamp", "left", "right", "corner"] {
        for o in patches(&scene, opening) {
            assert!(
                o.normal.dot(centre - o.centroid) > 0.0,
                "{opening} faces out"
            );
            for face in [
                "floor",
                "ceiling",
                "wall_xmin",
                "wall_xmax",
                "wall_ymin",
                "wall_ymax",
            ] {
                for p in patches(&scene, &format!("room.{face}")) {
                    let shared = shared_area(p, o);
                    assert!(
                        shared < 1e-12,
                        "room.{face} overlaps {opening} by {shared} m²"
                    );
                }
            }
        }
    }
    // Patches keep within max_edge (cells are meshed at the face's max_edge).
    for p in &scene.patches {
        let v = &p.polygon.vertices;
        for i in 0..v.len() {
            assert!((v[(i + 1) % v.len()] - v[i]).length() <= 0.4 + 1e-12);
        }
    }
    let again = parse(OPENINGS, Path::new(FILE)).expect("loads again");
    assert_eq!(scene.patches, again.patches);
}
