//! A corpus of malformed scenes (`tests/scenes/`): each must be refused by
//! `eigenrad::precompute::scene::load` with a message naming the file and the field or line
//! at fault, so that the message alone is enough to find and fix the input.

use std::path::{Path, PathBuf};

use eigenrad::precompute::scene::load;

fn corpus(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/scenes")
        .join(name)
}

/// The message of loading `name`, which must fail.
fn message(name: &str) -> String {
    match load(&corpus(name)) {
        Ok(scene) => panic!("{name} was accepted ({} patches)", scene.patches.len()),
        Err(e) => e.to_string(),
    }
}

/// `:N:`, where N is the 1-based line of `file` (in the corpus) first holding `needle`.
fn line(file: &str, needle: &str) -> String {
    let text = std::fs::read_to_string(corpus(file)).expect("corpus file");
    let n = text
        .lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("`{needle}` not in {file}"));
    format!(":{}:", n + 1)
}

/// Loads `file`, expects an error naming `file` (or `names_file` when the fault is in a file
/// it references) and every one of `parts`.
fn expect(file: &str, names_file: &str, parts: &[&str]) {
    let m = message(file);
    eprintln!("{file}: {m}");
    assert!(m.contains(names_file), "`{names_file}` not named in: {m}");
    for p in parts {
        assert!(m.contains(p), "`{p}` missing from: {m}");
    }
}

#[test]
fn corpus_valid_scene_loads() {
    // The corpus files are this scene with one fault each.
    let scene = load(&corpus("valid.toml")).expect("the corpus's base scene is valid");
    assert!(!scene.patches.is_empty());
}

#[test]
fn missing_scene_file() {
    expect(
        "does_not_exist.toml",
        "does_not_exist.toml",
        &["cannot read file"],
    );
}

#[test]
fn toml_syntax_error() {
    // The parser stops where the missing `]` becomes certain: the next line.
    expect(
        "syntax_error.toml",
        "syntax_error.toml",
        &[
            &line("syntax_error.toml", "material = \"wall\""),
            "expected `,`",
        ],
    );
}

#[test]
fn unknown_field() {
    expect(
        "unknown_field.toml",
        "unknown_field.toml",
        &[
            &line("unknown_field.toml", "reflectivity"),
            "unknown field `reflectivity`",
        ],
    );
}

#[test]
fn wrong_type() {
    expect(
        "wrong_type.toml",
        "wrong_type.toml",
        &[&line("wrong_type.toml", "max_edge"), "expected f64"],
    );
}

#[test]
fn reflectance_of_one() {
    expect(
        "reflectance_one.toml",
        "reflectance_one.toml",
        &[
            &line("reflectance_one.toml", "wall ="),
            "materials.wall.reflectance",
            "[0, 1)",
        ],
    );
}

#[test]
fn negative_reflectance() {
    expect(
        "reflectance_negative.toml",
        "reflectance_negative.toml",
        &[
            &line("reflectance_negative.toml", "wall ="),
            "materials.wall.reflectance",
            "-0.2",
        ],
    );
}

#[test]
fn per_band_list_of_wrong_length() {
    expect(
        "band_count.toml",
        "band_count.toml",
        &["materials.wall.reflectance", "expected 3 value(s), found 2"],
    );
}

#[test]
fn negative_exitance() {
    expect(
        "negative_exitance.toml",
        "negative_exitance.toml",
        &[
            &line("negative_exitance.toml", "exitance"),
            "channel `lamp`.exitance",
            "non-negative",
        ],
    );
}

#[test]
fn negative_material_emission() {
    expect(
        "negative_emission.toml",
        "negative_emission.toml",
        &["materials.lamp.emission", "-1"],
    );
}

#[test]
fn infinite_flux() {
    expect(
        "infinite_flux.toml",
        "infinite_flux.toml",
        &[
            &line("infinite_flux.toml", "flux = inf"),
            "channel `lamp`.flux",
            "inf",
        ],
    );
}

#[test]
fn nan_coordinate() {
    expect(
        "nan_coordinate.toml",
        "nan_coordinate.toml",
        &[
            &line("nan_coordinate.toml", "nan"),
            "quad `lamp`.corners",
            "finite",
        ],
    );
}

#[test]
fn infinite_coordinate() {
    expect(
        "infinite_room.toml",
        "infinite_room.toml",
        &[
            &line("infinite_room.toml", "inf"),
            "room `room`.max",
            "finite",
        ],
    );
}

#[test]
fn room_inside_out() {
    expect(
        "room_inside_out.toml",
        "room_inside_out.toml",
        &[
            &line("room_inside_out.toml", "max ="),
            "room `room`.max",
            "must exceed",
        ],
    );
}

#[test]
fn zero_max_edge() {
    expect(
        "zero_max_edge.toml",
        "zero_max_edge.toml",
        &[":5:", "scene.max_edge", "positive"],
    );
}

#[test]
fn degenerate_quad() {
    expect(
        "degenerate_quad.toml",
        "degenerate_quad.toml",
        &[
            &line("degenerate_quad.toml", "corners"),
            "surface `lamp`, face 1",
            "degenerate",
        ],
    );
}

#[test]
fn non_planar_quad() {
    expect(
        "nonplanar_quad.toml",
        "nonplanar_quad.toml",
        &[
            &line("nonplanar_quad.toml", "corners"),
            "surface `lamp`",
            "non-planar",
            "triangulate",
        ],
    );
}

#[test]
fn opening_facing_out_of_the_room() {
    expect(
        "opening_wrong_way.toml",
        "opening_wrong_way.toml",
        &[
            &line("opening_wrong_way.toml", "openings"),
            "room `room`.openings",
            "`lamp` faces out of the room",
        ],
    );
}

#[test]
fn opening_not_in_a_face() {
    expect(
        "opening_not_in_face.toml",
        "opening_not_in_face.toml",
        &[
            &line("opening_not_in_face.toml", "openings"),
            "room `room`.openings",
            "not in a face",
            "2.000e-2 m",
        ],
    );
}

#[test]
fn opening_self_intersecting() {
    expect(
        "opening_self_intersecting.toml",
        "opening_self_intersecting.toml",
        &[
            "room `room`.openings",
            "opening `lamp` is not a simple polygon: edges 1 and 3 cross",
        ],
    );
}

#[test]
fn opening_outside_its_face() {
    expect(
        "opening_outside_face.toml",
        "opening_outside_face.toml",
        &[
            "room `room`.openings",
            "reaches outside face `room.ceiling`",
        ],
    );
}

#[test]
fn overlapping_openings() {
    expect(
        "openings_overlap.toml",
        "openings_overlap.toml",
        &["room `room`.openings", "`lamp` and `lamp2` overlap"],
    );
}

#[test]
fn unknown_opening() {
    expect(
        "opening_unknown.toml",
        "opening_unknown.toml",
        &["room `room`.openings", "unknown surface `skylight`"],
    );
}

#[test]
fn obj_face_wound_inside_out() {
    expect(
        "obj_inverted_face.toml",
        "inverted_cube.obj",
        &["surface `cube`, face 2", "wound against its neighbours"],
    );
}

#[test]
fn duplicate_surface_name() {
    expect(
        "duplicate_surface.toml",
        "duplicate_surface.toml",
        &["duplicate surface name `lamp`"],
    );
}

#[test]
fn duplicate_channel_name() {
    expect(
        "duplicate_channel.toml",
        "duplicate_channel.toml",
        &["duplicate channel name `lamp`"],
    );
}

#[test]
fn duplicate_sensor_name() {
    expect(
        "duplicate_sensor.toml",
        "duplicate_sensor.toml",
        &["duplicate sensor name `floor`"],
    );
}

#[test]
fn channel_without_emitting_surface() {
    expect(
        "channel_without_emitter.toml",
        "channel_without_emitter.toml",
        &[
            &line("channel_without_emitter.toml", "[[channel]]"),
            "channel `lamp`",
            "none of its surfaces emits",
        ],
    );
}

#[test]
fn emitting_surface_in_no_channel() {
    expect(
        "emitter_without_channel.toml",
        "emitter_without_channel.toml",
        &["surface `panel`", "no channel drives it"],
    );
}

#[test]
fn unknown_surface_in_channel() {
    expect(
        "unknown_surface_in_channel.toml",
        "unknown_surface_in_channel.toml",
        &["channel `lamp`.surfaces", "unknown surface `lamp9`"],
    );
}

#[test]
fn unknown_material() {
    expect(
        "unknown_material.toml",
        "unknown_material.toml",
        &[
            &line("unknown_material.toml", "plaster"),
            "unknown material `plaster`",
        ],
    );
}

#[test]
fn sensor_zero_normal() {
    expect(
        "sensor_zero_normal.toml",
        "sensor_zero_normal.toml",
        &[
            &line("sensor_zero_normal.toml", "normal = [0, 0, 0]"),
            "sensor `floor`.normal",
            "non-zero",
        ],
    );
}

#[test]
fn sensor_half_angle_out_of_range() {
    expect(
        "sensor_half_angle.toml",
        "sensor_half_angle.toml",
        &["sensor `floor`.half_angle", "(0, 90]"],
    );
}

#[test]
fn sensor_outside_the_room() {
    expect(
        "sensor_outside_room.toml",
        "sensor_outside_room.toml",
        &[
            &line("sensor_outside_room.toml", "-0.5"),
            "sensor `floor`.position",
            "outside every room",
        ],
    );
}

#[test]
fn sensor_facing_the_floor_it_lies_on() {
    expect(
        "sensor_facing_floor.toml",
        "sensor_facing_floor.toml",
        &[
            "sensor `floor`.normal",
            "lies on `room.floor` and faces into it",
        ],
    );
}

#[test]
fn sensor_inside_a_block() {
    expect(
        "sensor_in_block.toml",
        "sensor_in_block.toml",
        &[
            &line("sensor_in_block.toml", "[0.5, 0.5, 0.5]"),
            "sensor `hidden`.position",
            "inside block `cabinet`",
        ],
    );
}

#[test]
fn sensor_facing_into_a_block() {
    expect(
        "sensor_facing_into_block.toml",
        "sensor_facing_into_block.toml",
        &[
            "sensor `top`.normal",
            "lies on `cabinet.top` and faces into it",
        ],
    );
}

#[test]
fn block_through_a_wall() {
    expect(
        "block_through_wall.toml",
        "block_through_wall.toml",
        &["block `beam`", "not inside any room"],
    );
}

#[test]
fn work_plane_above_the_ceiling() {
    expect(
        "work_plane_above_ceiling.toml",
        "work_plane_above_ceiling.toml",
        &["zone `work_plane`.work_plane.height", "below the ceiling"],
    );
}

#[test]
fn work_plane_in_unknown_room() {
    expect(
        "work_plane_unknown_room.toml",
        "work_plane_unknown_room.toml",
        &["zone `work_plane`.work_plane.room", "unknown room `hall`"],
    );
}

#[test]
fn work_plane_margin_leaves_nothing() {
    expect(
        "work_plane_margin.toml",
        "work_plane_margin.toml",
        &["zone `work_plane`.work_plane.margin", "leaves nothing"],
    );
}

#[test]
fn missing_obj_file() {
    expect(
        "missing_obj.toml",
        "missing_obj.toml",
        &[":8:", "obj.file", "nowhere.obj", "not found"],
    );
}

#[test]
fn missing_mtl_file() {
    expect(
        "missing_mtl.toml",
        "missing_mtl.toml",
        &["missing_mtl.obj", "gone.mtl", "not found"],
    );
}

#[test]
fn malformed_obj_vertex() {
    expect(
        "malformed_obj.toml",
        "malformed.obj",
        &["malformed.obj:3:", "zero"],
    );
}

#[test]
fn obj_face_index_out_of_range() {
    expect(
        "obj_bad_index.toml",
        "bad_index.obj",
        &["bad_index.obj:7:", "7"],
    );
}

#[test]
fn malformed_mtl_value() {
    expect(
        "malformed_mtl.toml",
        "malformed.mtl",
        &["malformed.mtl:2:", "Kd"],
    );
}

#[test]
fn mtl_reflectance_above_one() {
    expect(
        "mtl_reflectance.toml",
        "bright.mtl",
        &["MTL material `snow` Kd", "[0, 1)"],
    );
}

#[test]
fn obj_zero_area_face() {
    expect(
        "obj_zero_area.toml",
        "zero_area.obj",
        &["surface `sliver`, face 1", "degenerate"],
    );
}

/// A scene whose mesh would not fit in memory (about 5e7 patches at max_edge = 1 mm) is
/// refused before meshing, with the estimate. (How fast: see the report; no timing here.)
#[test]
fn too_many_patches_refused_before_meshing_with_the_estimate() {
    let m = message("too_many_patches.toml");
    for p in [
        ":5:",
        "scene.max_edge",
        "patches",
        "bytes",
        "raise `max_edge`",
        "too_many_patches.toml",
    ] {
        assert!(m.contains(p), "`{p}` missing from: {m}");
    }
    // Room 6 m x 4 m x 2 m at 1 mm: 2 (6·4 + 6·2 + 4·2) m² / 1e-6 m² = 8.8e7 patches.
    assert!(m.contains("8.800e7 patches"), "estimate not in: {m}");
}

#[test]
fn reflectance_that_single_precision_rounds_to_one() {
    // 0.9999999999 < 1, but a basis stores reflectance in f32, where it is 1.
    expect(
        "reflectance_rounds_to_one.toml",
        "reflectance_rounds_to_one.toml",
        &[
            &line("reflectance_rounds_to_one.toml", "wall ="),
            "materials.wall.reflectance",
            "[0, 1)",
            "0.99999994",
        ],
    );
}

#[test]
fn reflectance_too_small_to_weigh() {
    // Between 0 (black) and 1e-6 the weight A/ρ of the eigenproblem could overflow.
    expect(
        "reflectance_tiny.toml",
        "reflectance_tiny.toml",
        &[
            &line("reflectance_tiny.toml", "wall ="),
            "materials.wall.reflectance",
            "1e-6",
        ],
    );
}

#[test]
fn flux_giving_an_exitance_no_basis_stores() {
    expect(
        "enormous_flux.toml",
        "enormous_flux.toml",
        &[
            &line("enormous_flux.toml", "flux = 1e308"),
            "channel `lamp`.flux",
            "1e9",
        ],
    );
}

#[test]
fn quad_with_five_corners() {
    expect(
        "quad_five_corners.toml",
        "quad_five_corners.toml",
        &[
            &line("quad_five_corners.toml", "corners ="),
            "quad `lamp`.corners",
            "4 corners, found 5",
        ],
    );
}

#[test]
fn point_with_four_coordinates() {
    expect(
        "sensor_four_coordinates.toml",
        "sensor_four_coordinates.toml",
        &[
            &line("sensor_four_coordinates.toml", "position ="),
            "3 numbers",
        ],
    );
}

#[test]
fn channel_names_that_level_arguments_cannot_address() {
    for (file, problem) in [
        ("channel_name_with_equals.toml", "contains `=`"),
        ("channel_name_empty.toml", "is empty"),
    ] {
        expect(file, file, &[&line(file, "[[channel]]"), ".name", problem]);
    }
}

#[test]
fn zone_naming_no_surface() {
    expect(
        "zone_without_surfaces.toml",
        "zone_without_surfaces.toml",
        &[
            &line("zone_without_surfaces.toml", "surfaces = []"),
            "zone `nothing`.surfaces",
            "names no surface",
        ],
    );
}

#[test]
fn work_plane_meshed_too_finely_for_memory() {
    // Refused from an estimate, before meshing 4e10 receivers.
    expect(
        "work_plane_too_fine.toml",
        "work_plane_too_fine.toml",
        &[
            &line("work_plane_too_fine.toml", "max_edge = 0.00001"),
            "zone `desk`.work_plane.max_edge",
            "receivers",
        ],
    );
}

#[test]
fn obj_faults_name_their_file_line_and_cause() {
    // (scene, the file at fault, text of the line at fault, the cause).
    for (scene, file, at, cause) in [
        (
            "obj_undefined_usemtl.toml",
            "undefined_usemtl.obj",
            "usemtl nosuch",
            "names no material (its MTL files define grey)",
        ),
        (
            "obj_infinite_vertex.toml",
            "infinite_vertex.obj",
            "v 1 inf 1",
            "`inf` is not finite",
        ),
        (
            "obj_forward_vertex.toml",
            "forward_vertex.obj",
            "f 1 4 3 2",
            "defined further down",
        ),
        (
            "obj_huge_vertex.toml",
            "huge_vertex.obj",
            "v 1 1e300 1",
            "vertex coordinate y = `1e300` is 1.000e300 m from the origin",
        ),
    ] {
        let located = format!("{file}{}", line(file, at));
        expect(scene, file, &[&located, cause]);
    }
    expect(
        "obj_no_faces.toml",
        "no_faces.obj",
        &["no_faces.obj:1:", "no faces"],
    );
    // Its third line holds the bytes 0xFF 0xFE (so `line` cannot read it as text).
    expect(
        "obj_mtl_not_utf8.toml",
        "not_utf8.mtl",
        &["not_utf8.mtl:3:", "not UTF-8"],
    );
}

#[test]
fn a_coordinate_beyond_the_largest_a_scene_may_span_is_named() {
    expect(
        "huge_coordinate.toml",
        "huge_coordinate.toml",
        &[
            &line("huge_coordinate.toml", "2e9"),
            "sensor `floor`.position",
            "coordinate z = 2000000000 is 2.000e9 m from the origin",
        ],
    );
}

#[test]
fn a_sensor_outside_a_closed_obj_scene_is_refused_with_its_extent() {
    expect(
        "obj_sensor_outside.toml",
        "obj_sensor_outside.toml",
        &[
            &line("obj_sensor_outside.toml", "position = [7"),
            "sensor `far`.position",
            "outside the scene's closed geometry (faces enclosing [0.0, 0.0, 0.0] to [1.0, 1.0, 1.0])",
        ],
    );
}
