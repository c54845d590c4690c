//! Three rooms in a row: the two rooms of [`super::two_rooms`] (`left`, 3 m × 3 m, and
//! `right`, 2 m × 3 m) and a third, `far` (3 m × 3 m, x from 5 to 8 m), joined to `right` by
//! a second door in the wall x = 5 m in line with the first: light passes from `left` to
//! `far` through both doors in turn (tests/ports_exact.rs).

use std::path::{Path, PathBuf};

use super::two_rooms::{corners, left_scene, DOOR, LEFT_LIGHT, MATERIALS, RIGHT_LIGHT};

/// The second door: x = 5 m, y from 1 to 2 m, z from 0 to 2 m; its corners counter-clockwise
/// seen from the right room (facing −x, into it).
pub const DOOR_EAST: [[f64; 3]; 4] = [
    [5.0, 1.0, 0.0],
    [5.0, 1.0, 2.0],
    [5.0, 2.0, 2.0],
    [5.0, 2.0, 0.0],
];

/// The far room's lamp, channel, sensors (one looking back through both doors) and zone.
pub const FAR_LIGHT: &str = r#"
[[quad]]
name = "lamp_far"
material = "lamp"
corners = [[6, 1, 2.5], [6, 2, 2.5], [7, 2, 2.5], [7, 1, 2.5]]

[[channel]]
name = "far"
surfaces = ["lamp_far"]
flux = 800

[[sensor]]
name = "desk_far"
position = [6.5, 1.5, 0.75]
normal = [0, 0, 1]

[[sensor]]
name = "facing_doors_far"
position = [7.8, 1.5, 1.0]
normal = [-1, 0, 0]

[[zone]]
name = "plane_far"
work_plane = { height = 0.75, area = { min = [5.25, 0.25], max = [7.75, 2.75] }, max_edge = 0.5 }
"#;

/// The right room's scene with both doors: `door` (to the left room) and `door_east`.
pub fn middle_scene() -> String {
    format!(
        "[scene]\nname = \"right\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 0.5\n\n{MATERIALS}\n\
         [[room]]\nname = \"room\"\nmin = [3, 0, 0]\nmax = [5, 3, 2.5]\nmaterial = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\nopenings = [\"lamp_right\", \"door\", \"door_east\"]\n\n\
         [[quad]]\nname = \"door\"\nmaterial = \"door\"\ncorners = {}\n\n\
         [[quad]]\nname = \"door_east\"\nmaterial = \"door\"\ncorners = {}\n{RIGHT_LIGHT}",
        corners(&DOOR, false),
        corners(&DOOR_EAST, true)
    )
}

/// The far room's scene, its door facing into it (+x).
pub fn far_scene() -> String {
    format!(
        "[scene]\nname = \"far\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 0.5\n\n{MATERIALS}\n\
         [[room]]\nname = \"room\"\nmin = [5, 0, 0]\nmax = [8, 3, 2.5]\nmaterial = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\nopenings = [\"lamp_far\", \"door\"]\n\n\
         [[quad]]\nname = \"door\"\nmaterial = \"door\"\ncorners = {}\n{FAR_LIGHT}",
        corners(&DOOR_EAST, false)
    )
}

/// Writes the three rooms' scenes and a manifest joining them by two exact ports into `dir`.
pub fn three_rooms(dir: &Path) -> PathBuf {
    std::fs::write(dir.join("left.toml"), left_scene(&DOOR)).expect("scene");
    std::fs::write(dir.join("right.toml"), middle_scene()).expect("scene");
    std::fs::write(dir.join("far.toml"), far_scene()).expect("scene");
    let text = format!(
        "[building]\nname = \"three rooms\"\n\n\
         [[room]]\nname = \"left\"\nscene = \"left.toml\"\n\n\
         [[room]]\nname = \"right\"\nscene = \"right.toml\"\n\n\
         [[room]]\nname = \"far\"\nscene = \"far.toml\"\n\n{}\n\
         [[controller]]\nname = \"far\"\nroom = \"far\"\ndrives = [\"far\"]\nsensors = [\"desk_far\", \"facing_doors_far\"]\ngrids = [\"plane_far\"]\n\n\
         [[port]]\nname = \"door\"\nrooms = [\"left\", \"right\"]\nmodel = \"exact\"\n\n\
         [[port]]\nname = \"door2\"\nrooms = [\"right\", \"far\"]\nopenings = [\"door_east\", \"door\"]\nmodel = \"exact\"\n",
        super::two_rooms::CONTROLLERS
    );
    let path = dir.join("building.toml");
    std::fs::write(&path, text).expect("manifest");
    path
}

/// The three rooms in one scene file, each box and face as in its own room's scene, the four
/// door quads written last (leave them out and the doorways are real holes).
pub fn three_rooms_in_one_scene() -> String {
    format!(
        "[scene]\nname = \"three\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 0.5\n\n{MATERIALS}\n\
         [[room]]\nname = \"left\"\nmin = [0, 0, 0]\nmax = [3, 3, 2.5]\nmaterial = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\nopenings = [\"lamp_left\", \"door_left\"]\n\n\
         [[room]]\nname = \"right\"\nmin = [3, 0, 0]\nmax = [5, 3, 2.5]\nmaterial = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\nopenings = [\"lamp_right\", \"door_right\", \"door_east\"]\n\n\
         [[room]]\nname = \"far\"\nmin = [5, 0, 0]\nmax = [8, 3, 2.5]\nmaterial = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\nopenings = [\"lamp_far\", \"door_far\"]\n\
         {}{}{}\n\
         [[quad]]\nname = \"door_left\"\nmaterial = \"door\"\ncorners = {}\n\n\
         [[quad]]\nname = \"door_right\"\nmaterial = \"door\"\ncorners = {}\n\n\
         [[quad]]\nname = \"door_east\"\nmaterial = \"door\"\ncorners = {}\n\n\
         [[quad]]\nname = \"door_far\"\nmaterial = \"door\"\ncorners = {}\n",
        LEFT_LIGHT.replace("work_plane = {", "work_plane = { room = \"left\","),
        RIGHT_LIGHT.replace("work_plane = {", "work_plane = { room = \"right\","),
        FAR_LIGHT.replace("work_plane = {", "work_plane = { room = \"far\","),
        corners(&DOOR, true),
        corners(&DOOR, false),
        corners(&DOOR_EAST, true),
        corners(&DOOR_EAST, false)
    )
}
