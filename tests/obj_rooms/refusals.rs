//! Mistakes in an OBJ room, each refused naming the OBJ file, its `f` line, the room and the
//! face: a face missing, a wall wound out, the shell drawn as a solid, a window drawn in the
//! shell, a floor on two levels; sensors and windows out of its shape; `openings` without a
//! `room`.

use super::*;

/// The message of loading the OBJ L of `faces` with `extra` TOML after the `[[obj]]` entry,
/// which must fail.
fn refused(name: &str, faces: &[ObjFace], obj_fields: &str, extra: &str) -> String {
    let dir = scratch(name);
    write(&dir, "room.mtl", MTL);
    write(&dir, "room.obj", &obj(faces));
    let path = write(
        &dir,
        "scene.toml",
        &format!(
            "{}\n[[obj]]\nfile = \"room.obj\"\nroom = \"office\"\n{obj_fields}{extra}",
            header(0.5)
        ),
    );
    let message = match load(&path) {
        Ok(_) => panic!("{name} was accepted"),
        Err(e) => e.to_string(),
    };
    println!("{name}: {message}");
    std::fs::remove_dir_all(&dir).ok();
    message
}

fn has(message: &str, parts: &[&str]) {
    for p in parts {
        assert!(message.contains(p), "`{p}` missing from: {message}");
    }
}

/// The line of the `f` statement of face `k` (0-based) in [`obj`]'s file of `faces`.
fn face_line(faces: &[ObjFace], k: usize) -> usize {
    // mtllib, then per face: g, usemtl, its vertices, f.
    1 + faces[..=k].iter().map(|f| 3 + f.2.len()).sum::<usize>()
}

#[test]
fn an_obj_room_with_a_face_missing_is_not_closed() {
    let mut faces = l_faces();
    let east = faces.remove(5);
    assert_eq!(east.0, "east");
    let message = refused("open", &faces, "", "");
    // The first face along the gap: the first floor quad's edge x = 6.
    has(
        &message,
        &[
            &format!("room.obj:{}:", face_line(&faces, 0)),
            "OBJ room `office`, face 1 of `floor`",
            "is not shared with another face: the room is not closed",
        ],
    );
}

#[test]
fn a_wall_wound_out_of_an_obj_room_is_named() {
    let mut faces = l_faces();
    faces[7].2.reverse(); // notch_west
    let message = refused("outward-wall", &faces, "", "");
    has(
        &message,
        &[
            &format!("room.obj:{}:", face_line(&faces, 7)),
            "OBJ room `office`, face 1 of `notch_west`",
            "faces out of the room while its neighbours face into it",
            "1 of 10 faces",
        ],
    );
}

#[test]
fn an_obj_room_drawn_as_a_solid_is_refused() {
    let mut faces = l_faces();
    for f in &mut faces {
        f.2.reverse();
    }
    let message = refused("solid", &faces, "", "");
    has(
        &message,
        &[
            "OBJ room `office`",
            "every face of the room faces out of it",
        ],
    );
}

#[test]
fn a_window_drawn_in_the_shell_of_an_obj_room_is_refused() {
    // The south wall drawn as the window and the wall around it.
    let mut faces = l_faces();
    let h = HEIGHT;
    faces.remove(4);
    let south: Vec<ObjFace> = vec![
        (
            "south",
            "wall",
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 0.0, h],
                [1.0, 0.0, h],
                [1.0, 0.0, 0.0],
            ],
        ),
        (
            "south",
            "wall",
            vec![
                [1.0, 0.0, 0.0],
                [1.0, 0.0, 1.0],
                [6.0, 0.0, 1.0],
                [6.0, 0.0, 0.0],
            ],
        ),
        (
            "window",
            "glass",
            vec![
                [1.0, 0.0, 1.0],
                [1.0, 0.0, 2.0],
                [3.0, 0.0, 2.0],
                [3.0, 0.0, 1.0],
            ],
        ),
        (
            "south",
            "wall",
            vec![
                [1.0, 0.0, 2.0],
                [1.0, 0.0, h],
                [3.0, 0.0, h],
                [3.0, 0.0, 2.0],
            ],
        ),
        (
            "south",
            "wall",
            vec![
                [3.0, 0.0, 1.0],
                [3.0, 0.0, h],
                [6.0, 0.0, h],
                [6.0, 0.0, 1.0],
            ],
        ),
    ];
    faces.extend(south);
    let message = refused("window-in-shell", &faces, "", "");
    has(
        &message,
        &[
            "OBJ room `office`, face 1 of `window`",
            "its material `glass` differs from that of face 1 of `south`",
            "list it in the `[[obj]]`'s `openings`",
        ],
    );
}

#[test]
fn an_obj_room_with_its_floor_on_two_levels_is_refused() {
    // The notch side's floor quad raised 0.3 m, with a riser closing the step.
    let mut faces = l_faces();
    faces[1].2.iter_mut().for_each(|c| c[2] = 0.3);
    for k in [7, 8] {
        for c in faces[k].2.iter_mut().filter(|c| c[2] == 0.0 && c[1] >= 2.0) {
            c[2] = 0.3;
        }
    }
    // The west wall: a pentagon down to 0 on y < 2, 0.3 on y > 2.
    faces[9].2 = vec![
        [0.0, 4.0, 0.3],
        [0.0, 4.0, HEIGHT],
        [0.0, 0.0, HEIGHT],
        [0.0, 0.0, 0.0],
        [0.0, 2.0, 0.0],
        [0.0, 2.0, 0.3],
    ];
    faces.push((
        "riser",
        "floor",
        vec![
            [0.0, 2.0, 0.0],
            [3.5, 2.0, 0.0],
            [3.5, 2.0, 0.3],
            [0.0, 2.0, 0.3],
        ],
    ));
    let message = refused("step", &faces, "", "");
    has(
        &message,
        &[
            "OBJ room `office`, face 2 of `floor`",
            "faces up at z = 0.3 m, above the room's floor at z = 0 m",
        ],
    );
}

#[test]
fn a_sensor_in_the_notch_of_an_obj_room_is_refused() {
    let message = refused(
        "sensor-notch",
        &l_faces(),
        "",
        "\n[[sensor]]\nname = \"s\"\nposition = [5, 3, 1]\nnormal = [0, 0, 1]\n",
    );
    has(
        &message,
        &[
            "sensor `s`.position",
            "outside every room",
            "`office` has the plan",
        ],
    );
}

#[test]
fn a_window_facing_out_of_an_obj_room_is_refused() {
    let out = WINDOW.replace(
        "[[3, 0, 1], [1, 0, 1], [1, 0, 2], [3, 0, 2]]",
        "[[1, 0, 1], [3, 0, 1], [3, 0, 2], [1, 0, 2]]",
    );
    let message = refused("window-out", &l_faces(), "openings = [\"window\"]\n", &out);
    has(
        &message,
        &[
            "OBJ room `office`.openings",
            "faces out of the room",
            "office.south",
        ],
    );
}

#[test]
fn a_window_over_an_uncut_obj_wall_is_refused() {
    let message = refused("window-uncut", &l_faces(), "", WINDOW);
    has(&message, &["window", "office.south", "openings"]);
}

#[test]
fn openings_without_a_room_are_refused() {
    let dir = scratch("openings-alone");
    write(&dir, "room.mtl", MTL);
    write(&dir, "room.obj", &obj(&l_faces()));
    let text = format!(
        "{}\n[[obj]]\nfile = \"room.obj\"\nopenings = [\"window\"]\n{WINDOW}",
        header(0.5)
    );
    let line = 1 + text
        .lines()
        .position(|l| l.starts_with("openings"))
        .unwrap();
    let path = write(&dir, "scene.toml", &text);
    let message = match load(&path) {
        Ok(_) => panic!("openings without a room were accepted"),
        Err(e) => e.to_string(),
    };
    println!("{message}");
    has(
        &message,
        &[&format!("scene.toml:{line}:"), "obj.openings", "room = "],
    );
    std::fs::remove_dir_all(&dir).ok();
}
