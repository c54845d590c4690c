//! Light through two openings in turn: three rooms in a row joined by two exact ports whose
//! doors are in line ([`crate::common::three_rooms`]), built apart and merged, against the
//! three rooms as one scene with both doorways open. The left room's lamp lights the far
//! room's floor straight through both doors, and each end room's door-facing sensor sees the
//! other end room through them: the merge adds what passes across the middle room.

use eigenrad_precompute::building::{self, Manifest};

use crate::common;
use crate::common::one_scene::with_the_hole;
use crate::common::three_rooms::{three_rooms, three_rooms_in_one_scene};
use crate::{build, merged_error, read_in, readings};

#[test]
fn light_through_two_doors_in_turn_reads_as_in_one_scene() {
    let dir = common::scratch("ports-exact-three");
    let manifest = Manifest::load(&three_rooms(&dir)).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    build(&manifest, &[vec![0, 1, 2]], &out);
    let one =
        with_the_hole("ports-exact-three-hole", &three_rooms_in_one_scene()).channel_readings();
    // Each controller's channels as its basis names them: its own, then the others'.
    let channels = [
        ["left", "right/right", "far/far"],
        ["left/left", "right", "far/far"],
        ["left/left", "right/right", "far"],
    ];
    let mut worst: (f64, String) = (0.0, String::new());
    let mut count = 0;
    for (controller, names) in manifest.controllers.iter().zip(channels) {
        let basis = std::fs::read(building::basis_path(&out, &controller.name)).expect("basis");
        for channel in names {
            for (name, got) in readings(&basis, channel) {
                let want = read_in(&one, &name, channel);
                let error = merged_error(&controller.name, &name, channel, got, want);
                if error > worst.0 {
                    worst = (error, format!("{}: {name} of {channel}", controller.name));
                }
                count += 1;
            }
        }
    }
    eprintln!(
        "three rooms through two exact ports against one scene, {count} readings: largest relative difference {:.2e} ({})",
        worst.0, worst.1
    );
}
