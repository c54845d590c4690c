//! Two small rooms, `left` (3 m × 3 m) and `right` (2 m × 3 m), each 2.5 m high, joined by a
//! door (1 m × 2 m) in the wall x = 3 m, each lit by an emitting ceiling panel on a channel of
//! its own: their scenes, a building of them, and both rooms as one scene with the doorway
//! open (tests/ports.rs, tests/ports_exact.rs).

use std::path::{Path, PathBuf};

/// The door: x = 3 m, y from 1 to 2 m, z from 0 to 2 m; its corners counter-clockwise seen
/// from the left room (facing −x, into it).
pub const DOOR: [[f64; 3]; 4] = [
    [3.0, 1.0, 0.0],
    [3.0, 1.0, 2.0],
    [3.0, 2.0, 2.0],
    [3.0, 2.0, 0.0],
];

/// A rectangle in the plane x = 3 m over `y` and `z`, facing −x (`true`) or +x.
pub fn wall_quad(y: [f64; 2], z: [f64; 2], facing_left: bool) -> String {
    let mut c = vec![
        [3.0, y[0], z[0]],
        [3.0, y[0], z[1]],
        [3.0, y[1], z[1]],
        [3.0, y[1], z[0]],
    ];
    if !facing_left {
        c.reverse();
    }
    format!("{c:?}")
}

/// The corners as TOML.
pub fn corners(c: &[[f64; 3]; 4], facing_left: bool) -> String {
    let mut c = c.to_vec();
    if !facing_left {
        c.reverse();
    }
    format!("{c:?}")
}

pub const MATERIALS: &str = "[materials]\nfloor = { reflectance = 0.3 }\nwall = { reflectance = 0.6 }\nceiling = { reflectance = 0.8 }\nlamp = { reflectance = 0.0 }\ndoor = { reflectance = 0.0 }\n";

/// The left room's lamp, channel, sensors and zone.
pub const LEFT_LIGHT: &str = r#"
[[quad]]
name = "lamp_left"
material = "lamp"
corners = [[1, 1, 2.5], [1, 2, 2.5], [2, 2, 2.5], [2, 1, 2.5]]

[[channel]]
name = "left"
surfaces = ["lamp_left"]
flux = 1000

[[sensor]]
name = "desk_left"
position = [1.5, 1.5, 0.75]
normal = [0, 0, 1]

[[sensor]]
name = "facing_door_left"
position = [0.2, 1.5, 1.0]
normal = [1, 0, 0]

[[zone]]
name = "plane_left"
work_plane = { height = 0.75, area = { min = [0.25, 0.25], max = [2.75, 2.75] }, max_edge = 0.5 }
"#;

/// The right room's.
pub const RIGHT_LIGHT: &str = r#"
[[quad]]
name = "lamp_right"
material = "lamp"
corners = [[3.5, 1, 2.5], [3.5, 2, 2.5], [4.5, 2, 2.5], [4.5, 1, 2.5]]

[[channel]]
name = "right"
surfaces = ["lamp_right"]
flux = 600

[[sensor]]
name = "desk_right"
position = [4.0, 1.5, 0.75]
normal = [0, 0, 1]

[[sensor]]
name = "facing_door_right"
position = [4.8, 1.5, 1.0]
normal = [-1, 0, 0]

[[zone]]
name = "plane_right"
work_plane = { height = 0.75, area = { min = [3.25, 0.25], max = [4.75, 2.75] }, max_edge = 0.5 }
"#;

/// The left room's scene, its door's corners `door` (facing into it).
pub fn left_scene(door: &[[f64; 3]; 4]) -> String {
    format!(
        "[scene]\nname = \"left\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 0.5\n\n{MATERIALS}\n\
         [[room]]\nname = \"room\"\nmin = [0, 0, 0]\nmax = [3, 3, 2.5]\nmaterial = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\nopenings = [\"lamp_left\", \"door\"]\n\n\
         [[quad]]\nname = \"door\"\nmaterial = \"door\"\ncorners = {}\n{LEFT_LIGHT}",
        corners(door, true)
    )
}

/// The right room's scene, its door meshed at `door_edge` (m).
pub fn right_scene(door_edge: f64) -> String {
    format!(
        "[scene]\nname = \"right\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 0.5\n\n{MATERIALS}\n\
         [[room]]\nname = \"room\"\nmin = [3, 0, 0]\nmax = [5, 3, 2.5]\nmaterial = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\nopenings = [\"lamp_right\", \"door\"]\n\n\
         [[quad]]\nname = \"door\"\nmaterial = \"door\"\ncorners = {}\nmax_edge = {door_edge}\n{RIGHT_LIGHT}",
        corners(&DOOR, false)
    )
}

/// Both rooms as one scene, the doorway a real hole: one box 5 m × 3 m with the wall x = 3 m
/// between them made of two-sided quads around the doorway. Every face is meshed at 0.5 m,
/// so no patch straddles the wall (its edges fall on x = 3 m).
pub fn one_scene() -> String {
    let mut partition = String::new();
    for (k, (y, z)) in [
        ([0.0, 1.0], [0.0, 2.5]),
        ([2.0, 3.0], [0.0, 2.5]),
        ([1.0, 2.0], [2.0, 2.5]),
    ]
    .into_iter()
    .enumerate()
    {
        for (side, facing_left) in [("left", true), ("right", false)] {
            partition.push_str(&format!(
                "\n[[quad]]\nname = \"partition_{side}_{k}\"\nmaterial = \"wall\"\ncorners = {}\n",
                wall_quad(y, z, facing_left)
            ));
        }
    }
    format!(
        "[scene]\nname = \"both\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 0.5\n\n{MATERIALS}\n\
         [[room]]\nname = \"room\"\nmin = [0, 0, 0]\nmax = [5, 3, 2.5]\nmaterial = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\nopenings = [\"lamp_left\", \"lamp_right\"]\n\
         {partition}{LEFT_LIGHT}{RIGHT_LIGHT}"
    )
}

pub const CONTROLLERS: &str = "[[controller]]\nname = \"left\"\nroom = \"left\"\ndrives = [\"left\"]\nsensors = [\"desk_left\", \"facing_door_left\"]\ngrids = [\"plane_left\"]\n\n\
                           [[controller]]\nname = \"right\"\nroom = \"right\"\ndrives = [\"right\"]\nsensors = [\"desk_right\", \"facing_door_right\"]\ngrids = [\"plane_right\"]\n";

pub const PORT: &str = "[[port]]\nname = \"door\"\nrooms = [\"left\", \"right\"]\n";

/// Writes the two rooms' scenes and a manifest with `ports` (TOML) into `dir`.
pub fn two_rooms(dir: &Path, ports: &str) -> PathBuf {
    std::fs::write(dir.join("left.toml"), left_scene(&DOOR)).expect("scene");
    std::fs::write(dir.join("right.toml"), right_scene(0.5)).expect("scene");
    let text = format!(
        "[building]\nname = \"two rooms\"\n\n[[room]]\nname = \"left\"\nscene = \"left.toml\"\n\n\
         [[room]]\nname = \"right\"\nscene = \"right.toml\"\n\n{CONTROLLERS}\n{ports}"
    );
    let path = dir.join("building.toml");
    std::fs::write(&path, text).expect("manifest");
    path
}

/// Both rooms in one scene file, each box and each face as in its own room's scene (so meshed
/// into the same patches), the doorway the two black door quads `door_left` and `door_right`,
/// written last: leave out their patches (the last of the scene) and the doorway is a real
/// hole between two rooms meshed as they are built apart.
pub fn rooms_in_one_scene() -> String {
    format!(
        "[scene]\nname = \"both\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 0.5\n\n{MATERIALS}\n\
         [[room]]\nname = \"left\"\nmin = [0, 0, 0]\nmax = [3, 3, 2.5]\nmaterial = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\nopenings = [\"lamp_left\", \"door_left\"]\n\n\
         [[room]]\nname = \"right\"\nmin = [3, 0, 0]\nmax = [5, 3, 2.5]\nmaterial = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\nopenings = [\"lamp_right\", \"door_right\"]\n\
         {}{}\n\
         [[quad]]\nname = \"door_left\"\nmaterial = \"door\"\ncorners = {}\n\n\
         [[quad]]\nname = \"door_right\"\nmaterial = \"door\"\ncorners = {}\nmax_edge = 0.5\n",
        // Each work plane in its room (the scene has two).
        LEFT_LIGHT.replace("work_plane = {", "work_plane = { room = \"left\","),
        RIGHT_LIGHT.replace("work_plane = {", "work_plane = { room = \"right\","),
        corners(&DOOR, true),
        corners(&DOOR, false)
    )
}

/// A downlight with photometry in the left room near the door, aimed down at 45° towards it
/// (+x), on a channel of its own (`lum_left`): much of its light goes straight through the
/// door into the right room.
pub fn left_luminaire() -> String {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/photometry/downlight.ies");
    format!(
        "\n[[channel]]\nname = \"lum_left\"\n\n[[luminaire]]\nname = \"downlight\"\nfile = {:?}\nposition = [2.4, 1.5, 2.4]\naim = [1, 0, -1]\nchannel = \"lum_left\"\nmaintenance_factor = 0.8\n",
        file.to_str().expect("utf-8 path")
    )
}

/// [`two_rooms`] with [`left_luminaire`] in the left room, driven by the left controller.
pub fn two_rooms_with_luminaire(dir: &Path, ports: &str) -> PathBuf {
    let path = two_rooms(dir, ports);
    let left = left_scene(&DOOR) + &left_luminaire();
    std::fs::write(dir.join("left.toml"), left).expect("scene");
    let text = std::fs::read_to_string(&path).expect("manifest");
    let drives = "drives = [\"left\"]";
    assert!(text.contains(drives));
    std::fs::write(
        &path,
        text.replace(drives, "drives = [\"left\", \"lum_left\"]"),
    )
    .expect("manifest");
    path
}

/// The left room's scene with a glazed window in its south wall (y = 0) and a site: the
/// room has daylight, the right room none of its own.
pub fn daylit_left_scene() -> String {
    left_scene(&DOOR)
        .replacen(
            "[materials]\n",
            &format!("{}\n\n[materials]\nglass = {{ reflectance = 0.0, transmittance = 0.7 }}\n", super::VIENNA),
            1,
        )
        .replace(
            "openings = [\"lamp_left\", \"door\"]",
            "openings = [\"lamp_left\", \"door\", \"window\"]",
        )
        + "\n[[quad]]\nname = \"window\"\nmaterial = \"glass\"\ncorners = [[0.5, 0, 0.9], [0.5, 0, 2.0], [2.5, 0, 2.0], [2.5, 0, 0.9]]\n"
}

/// The right room's window, in its wall y = 3 m facing into it (−y, north with the site's
/// north 0): sunlit only by summer mornings' and evenings' suns.
pub const RIGHT_WINDOW: &str = "\n[[quad]]\nname = \"window_right\"\nmaterial = \"glass\"\ncorners = [[4.5, 3, 0.9], [4.5, 3, 2.0], [3.5, 3, 2.0], [3.5, 3, 0.9]]\n";

/// [`right_scene`] with [`RIGHT_WINDOW`] and the site of [`daylit_left_scene`].
pub fn daylit_right_scene() -> String {
    right_scene(0.5)
        .replacen(
            "[materials]\n",
            &format!(
                "{}\n\n[materials]\nglass = {{ reflectance = 0.0, transmittance = 0.7 }}\n",
                super::VIENNA
            ),
            1,
        )
        .replace(
            "openings = [\"lamp_right\", \"door\"]",
            "openings = [\"lamp_right\", \"door\", \"window_right\"]",
        )
        + RIGHT_WINDOW
}

/// [`rooms_in_one_scene`] with the left room's window and site of [`daylit_left_scene`] (and
/// with `right_window`, [`RIGHT_WINDOW`]): the two rooms as one scene lit by daylight through
/// the windows, the door quads still last.
pub fn daylit_rooms_in_one_scene(right_window: bool) -> String {
    let door = "\n[[quad]]\nname = \"door_left\"";
    let one = rooms_in_one_scene();
    assert!(one.contains(door));
    let mut windows = "\n[[quad]]\nname = \"window\"\nmaterial = \"glass\"\ncorners = [[0.5, 0, 0.9], [0.5, 0, 2.0], [2.5, 0, 2.0], [2.5, 0, 0.9]]\n".to_string();
    let mut one = one.replace(
        "openings = [\"lamp_left\", \"door_left\"]",
        "openings = [\"lamp_left\", \"door_left\", \"window\"]",
    );
    if right_window {
        windows.push_str(RIGHT_WINDOW);
        one = one.replace(
            "openings = [\"lamp_right\", \"door_right\"]",
            "openings = [\"lamp_right\", \"door_right\", \"window_right\"]",
        );
    }
    one.replacen(
        "[materials]\n",
        &format!(
            "{}\n\n[materials]\nglass = {{ reflectance = 0.0, transmittance = 0.7 }}\n",
            super::VIENNA
        ),
        1,
    )
    .replace(door, &format!("{windows}{door}"))
}

/// Rewrites the manifest at `path` ([`two_rooms`]) so that both controllers keep the modes,
/// with 8 MiB of flash for them.
pub fn both_keep_the_modes(path: &Path) {
    let text = std::fs::read_to_string(path)
        .expect("manifest")
        .replace("[building]\n", "[building]\nflash = \"8MiB\"\n")
        .replace(
            "grids = [\"plane_left\"]\n",
            "grids = [\"plane_left\"]\nmodes = true\n",
        )
        .replace(
            "grids = [\"plane_right\"]\n",
            "grids = [\"plane_right\"]\nmodes = true\n",
        );
    std::fs::write(path, text).expect("manifest");
}
