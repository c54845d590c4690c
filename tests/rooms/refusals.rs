//! Mistakes in rooms, each refused naming the item, the room and the line: opening polygons
//! off their plane, crossing themselves, concave, out of their face or overlapping; ceiling
//! planes that are nowhere the ceiling, vertical or below the floor; plan corners and edges;
//! sensors, luminaires, blocks and windows out of a plan room's shape.

use super::*;

/// The message of loading `text` (a scene whose file is `name`), which must fail; and the
/// `:N:` of the first line holding `needle`.
fn refused(name: &str, text: &str, needle: &str) -> (String, String) {
    let dir = scratch(name);
    let path = write(&dir, &format!("{name}.toml"), text);
    let message = match load(&path) {
        Ok(_) => panic!("{name} was accepted"),
        Err(e) => e.to_string(),
    };
    std::fs::remove_dir_all(&dir).ok();
    let line = text
        .lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("`{needle}` not in the scene"));
    println!("{name}: {message}");
    (message, format!("{name}.toml:{}:", line + 1))
}

fn expect(name: &str, text: &str, needle: &str, parts: &[&str]) {
    let (message, at) = refused(name, text, needle);
    assert!(message.contains(&at), "`{at}` not in: {message}");
    for p in parts {
        assert!(message.contains(p), "`{p}` missing from: {message}");
    }
}

const L_PLAN: &str = "plan = [[0, 0], [6, 0], [6, 2], [3.5, 2], [3.5, 4], [0, 4]]";

fn with_plan(plan: &str) -> String {
    l_room(0.5, 1000.0).replace(L_PLAN, plan)
}

#[test]
fn a_self_intersecting_plan_is_refused_naming_its_edges() {
    expect(
        "bowtie",
        &with_plan("plan = [[0, 0], [4, 4], [4, 0], [0, 4]]"),
        "plan =",
        &["room `room`.plan", "edges 1 and 3 cross"],
    );
}

#[test]
fn a_plan_with_a_repeated_corner_is_refused_naming_the_corners() {
    expect(
        "repeated",
        &with_plan("plan = [[0, 0], [6, 0], [6, 2], [3.5, 2], [6, 2], [0, 4]]"),
        "plan =",
        &["room `room`.plan", "corners 3 and 5 are the same point"],
    );
}

#[test]
fn a_plan_with_a_zero_length_edge_is_refused_naming_the_edge() {
    expect(
        "zero-edge",
        &with_plan("plan = [[0, 0], [6, 0], [6, 0], [6, 2], [0, 4]]"),
        "plan =",
        &["room `room`.plan", "edge 2", "zero length"],
    );
}

#[test]
fn a_plan_corner_of_three_numbers_is_refused() {
    expect(
        "corner-xyz",
        &with_plan("plan = [[0, 0, 0], [6, 0], [6, 4], [0, 4]]"),
        "plan =",
        &["room `room`.plan", "corner 1 has 3 numbers"],
    );
}

#[test]
fn a_plan_without_height_is_refused() {
    expect(
        "no-height",
        &l_room(0.5, 1000.0).replace("height = 2.5\n", ""),
        "[[room]]",
        &["room `room`.height", "needs its `height`"],
    );
}

#[test]
fn wall_names_must_give_one_per_edge() {
    expect(
        "wall-names",
        &l_room(0.5, 1000.0).replace(
            "height = 2.5\n",
            "height = 2.5\nwall_names = [\"a\", \"b\"]\n",
        ),
        "wall_names",
        &["room `room`.wall_names", "2 entries for the plan's 6 edges"],
    );
}

/// The L room with one more table appended.
fn l_with(extra: &str) -> String {
    format!(
        "{}\n[materials.lum]\nreflectance = 0.5\n{extra}",
        l_room(0.5, 1000.0)
    )
}

#[test]
fn a_sensor_in_the_notch_is_outside_the_room() {
    // (5, 3) lies inside the L's bounding box but in its notch.
    expect(
        "sensor-notch",
        &l_with("[[sensor]]\nname = \"s\"\nposition = [5, 3, 1]\nnormal = [0, 0, 1]\n"),
        "position = [5, 3, 1]",
        &[
            "sensor `s`.position",
            "outside every room",
            "`room` has the plan",
        ],
    );
}

const LUMINAIRE: &str = r#"[[channel]]
name = "lights"

[[luminaire]]
name = "lum"
file = "PHOTOMETRY"
position = POSITION
channel = "lights"
"#;

fn luminaire_at(position: &str) -> String {
    let photometry =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/photometry/downlight.ies");
    l_with(
        &LUMINAIRE
            .replace("PHOTOMETRY", &photometry.display().to_string())
            .replace("POSITION", position),
    )
}

#[test]
fn a_luminaire_in_the_notch_is_outside_the_room() {
    expect(
        "luminaire-notch",
        &luminaire_at("[5, 3, 2.5]"),
        "position = [5, 3, 2.5]",
        &["luminaire `lum`.position", "outside every room", "`room`"],
    );
}

#[test]
fn a_luminaire_inside_a_column_is_refused_naming_both() {
    let column = "[[block]]\nname = \"column\"\nmin = [1, 1, 0]\nmax = [1.4, 1.4, 2.5]\n\
                  material = \"surface\"\nbottom = false\ntop = false\n";
    expect(
        "luminaire-column",
        &format!("{}\n{column}", luminaire_at("[1.2, 1.2, 2]")),
        "position = [1.2, 1.2, 2]",
        &[
            "luminaire `lum`.position",
            "inside block `column` in room `room`",
        ],
    );
}

#[test]
fn a_block_reaching_into_the_notch_is_refused() {
    expect(
        "block-notch",
        &l_with(
            "[[block]]\nname = \"cabinet\"\nmin = [3, 2.5, 0]\nmax = [4, 3, 1]\n\
             material = \"surface\"\nbottom = false\n",
        ),
        "max = [4, 3, 1]",
        &["block `cabinet`.min/max", "not inside any room"],
    );
}

#[test]
fn a_block_open_at_the_top_must_reach_the_ceiling() {
    expect(
        "open-top",
        &l_with(
            "[[block]]\nname = \"column\"\nmin = [1, 1, 0]\nmax = [1.4, 1.4, 2]\n\
             material = \"surface\"\ntop = false\n",
        ),
        "max = [1.4, 1.4, 2]",
        &["block `column`.top", "below the ceiling of room `room`"],
    );
}

#[test]
fn a_window_facing_out_of_a_plan_wall_is_refused() {
    // In the wall x = 3.5 (edge 4, facing −x into the room) but wound to face +x.
    let text = l_with(
        "[[quad]]\nname = \"window\"\nmaterial = \"lum\"\n\
         corners = [[3.5, 2.5, 1], [3.5, 3.5, 1], [3.5, 3.5, 2], [3.5, 2.5, 2]]\n",
    )
    .replace(
        "material = \"surface\"\n\n[[channel]]",
        "material = \"surface\"\nopenings = [\"window\"]\n\n[[channel]]",
    );
    expect(
        "window-out",
        &text,
        "openings =",
        &[
            "room `room`.openings",
            "faces out of the room",
            "room.wall_4",
        ],
    );
}

/// The gabled room of [`gable_with_polygon_openings`] with the triangle's line `from`
/// replaced by `to`.
fn gable_with_triangle(from: &str, to: &str) -> String {
    let text = gable_with_polygon_openings();
    assert!(text.contains(from), "`{from}` not in the scene");
    text.replacen(from, to, 1)
}

const TRIANGLE: &str = "vertices = [[0, 1, 1.5], [0, 3, 1.5], [0, 2, 3.2]]";

#[test]
fn a_polygon_opening_off_its_plane_is_refused_naming_it() {
    expect(
        "bent-opening",
        &gable_with_triangle(
            TRIANGLE,
            "vertices = [[0, 1, 1.5], [0, 3, 1.5], [0.1, 3, 2.5], [0, 2, 3.2]]",
        ),
        "openings = [",
        &["room `room`.openings", "opening `triangle` is not planar"],
    );
}

#[test]
fn a_self_intersecting_opening_is_refused_naming_its_edges() {
    expect(
        "bowtie-opening",
        &gable_with_triangle(
            TRIANGLE,
            "vertices = [[0, 1, 1.5], [0, 3, 2.5], [0, 3, 1.5], [0, 1, 2.5]]",
        ),
        "openings = [",
        &[
            "room `room`.openings",
            "opening `triangle` is not a simple polygon: edges 1 and 3 cross",
        ],
    );
}

#[test]
fn a_concave_opening_is_refused_naming_it() {
    expect(
        "concave-opening",
        &gable_with_triangle(
            TRIANGLE,
            "vertices = [[0, 1, 1.5], [0, 3, 1.5], [0, 2, 2], [0, 2, 3.2]]",
        ),
        "openings = [",
        &["room `room`.openings", "opening `triangle` is not convex"],
    );
}

#[test]
fn a_polygon_opening_reaching_out_of_its_face_is_refused_naming_both() {
    // The apex above the gable's roof line (3.7 m at the ridge).
    expect(
        "opening-out-of-face",
        &gable_with_triangle(
            TRIANGLE,
            "vertices = [[0, 1, 1.5], [0, 3, 1.5], [0, 2, 3.9]]",
        ),
        "openings = [",
        &[
            "room `room`.openings",
            "opening `triangle` reaches outside face `room.wall_4`",
        ],
    );
}

#[test]
fn a_polygon_opening_in_no_face_is_refused_naming_it() {
    expect(
        "opening-in-no-face",
        &gable_with_triangle(
            TRIANGLE,
            "vertices = [[0.5, 1, 1.5], [0.5, 3, 1.5], [0.5, 2, 3.2]]",
        ),
        "openings = [",
        &[
            "room `room`.openings",
            "opening `triangle` is not in a face",
        ],
    );
}

#[test]
fn overlapping_polygon_openings_are_refused_naming_both() {
    // Over the trapezoid in the south wall, and two skylights over each other in the roof.
    let text = gable_with_triangle(
        "vertices = [[1, 0, 0.9], [1.5, 0, 2.1], [2.5, 0, 2.1], [3, 0, 0.9]]",
        "vertices = [[1, 0, 0.9], [1.5, 0, 2.1], [2.5, 0, 2.1], [3, 0, 0.9]]\n\n\
         [[polygon]]\nname = \"over\"\nmaterial = \"surface\"\n\
         vertices = [[2, 0, 1.5], [2, 0, 2.4], [4, 0, 2.4], [4, 0, 1.5]]",
    )
    .replace("\"skylight\"]", "\"skylight\", \"over\"]");
    expect(
        "openings-overlap",
        &text,
        "openings = [",
        &[
            "room `room`.openings",
            "openings `trapezoid` and `over` overlap in face `room.wall_1`",
        ],
    );
    let text = gable_with_triangle(
        "vertices = [[2, 3, 3.1], [4, 3, 3.1], [3, 2.5, 3.4]]",
        "vertices = [[2, 3, 3.1], [4, 3, 3.1], [3, 2.5, 3.4]]\n\n\
         [[polygon]]\nname = \"over\"\nmaterial = \"surface\"\n\
         vertices = [[2.5, 3.5, 2.8], [3.5, 3.5, 2.8], [3, 2.8, 3.22]]",
    )
    .replace("\"skylight\"]", "\"skylight\", \"over\"]");
    expect(
        "skylights-overlap",
        &text,
        "openings = [",
        &[
            "room `room`.openings",
            "openings `skylight` and `over` overlap in face `room.north`",
        ],
    );
}

#[test]
fn a_ceiling_plane_that_is_nowhere_the_ceiling_is_refused_naming_it() {
    let ceiling = "ceiling_planes = [
        { name = \"low\", through = [[0, 0, 2.5], [1, 0, 2.5], [0, 1, 2.5]] },
        { name = \"high\", through = [[0, 0, 3], [1, 0, 3], [0, 1, 3]] },
]";
    let text = sloped_room("[[0, 0], [6, 0], [6, 4], [0, 4]]", ceiling, 0.5, 1000.0, "");
    expect(
        "plane-nowhere",
        &text,
        "ceiling_planes = [",
        &[
            "room `room`.ceiling_planes",
            "`high` is the ceiling nowhere",
        ],
    );
}

#[test]
fn a_vertical_ceiling_plane_is_refused_naming_it() {
    let ceiling = "ceiling_planes = [{ through = [[0, 0, 0], [1, 0, 0], [0, 0, 3]] }]";
    let text = sloped_room("[[0, 0], [6, 0], [6, 4], [0, 4]]", ceiling, 0.5, 1000.0, "");
    expect(
        "plane-vertical",
        &text,
        "{ through",
        &["room `room`.ceiling_planes[1]", "vertical plane"],
    );
}

#[test]
fn a_ceiling_plane_below_the_floor_is_refused_naming_the_corner() {
    // Falls from 2 m at x = 0 through the floor before x = 6.
    let ceiling = "ceiling_planes = [{ through = [[0, 0, 2], [0, 4, 2], [4, 0, 0.5]] }]";
    let text = sloped_room("[[0, 0], [6, 0], [6, 4], [0, 4]]", ceiling, 0.5, 1000.0, "");
    expect(
        "plane-low",
        &text,
        "ceiling_planes = [",
        &[
            "room `room`.ceiling_planes",
            "not above the floor",
            "[6.0, 0.0]",
        ],
    );
}

#[test]
fn height_and_ceiling_planes_together_are_refused() {
    let text = sloped_room(
        "[[0, 0], [6, 0], [6, 4], [0, 4]]",
        &format!("height = 3\n{MONO_PITCH}"),
        0.5,
        1000.0,
        "",
    );
    expect(
        "height-and-planes",
        &text,
        "height = 3",
        &["room `room`.height", "not both"],
    );
}
