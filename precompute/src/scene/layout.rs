//! The scene seen from above, for its plan pictures: every room's floor plan and levels, the
//! blocks standing in the rooms, and which surfaces are openings cut in the rooms' faces.
//! Meshing and light never read it: the patches carry all of that for them.

use super::room::Room;
use crate::geometry::Vec3;

/// A room seen from above.
#[derive(Clone, Debug, PartialEq)]
pub struct RoomPlan {
    /// The room's name: its floor is the surface `<name>.floor`.
    pub name: String,
    /// Its floor plan's corners, counter-clockwise seen from above, m.
    pub corners: Vec<[f64; 2]>,
    /// The floor's z, m.
    pub floor: f64,
    /// The ceiling's z (a sloped ceiling's highest), m.
    pub ceiling: f64,
}

/// A block inside the rooms (a column, a desk, a cabinet).
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// Its name.
    pub name: String,
    /// Its lowest corner, m.
    pub min: Vec3,
    /// Its highest corner, m.
    pub max: Vec3,
}

/// What a plan of the scene draws besides the light.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Layout {
    /// The rooms, in file order.
    pub rooms: Vec<RoomPlan>,
    /// The blocks inside the rooms (exterior ones are obstructions), in file order.
    pub blocks: Vec<Block>,
    /// Indices into [`super::Scene::surfaces`] of the openings cut in the rooms' faces
    /// (windows, doors, flush luminaires), in surface order.
    pub openings: Vec<usize>,
}

impl Layout {
    /// The `rooms`, the `blocks` inside them (name and corners, m) and the surfaces
    /// `claimed` as openings, seen from above.
    pub(crate) fn of(rooms: &[Room], blocks: &[(String, Vec3, Vec3)], claimed: &[bool]) -> Self {
        Layout {
            rooms: rooms
                .iter()
                .map(|r| RoomPlan {
                    name: r.name.clone(),
                    corners: r.plan.corners.clone(),
                    floor: r.floor,
                    ceiling: r.ceiling,
                })
                .collect(),
            blocks: blocks
                .iter()
                .map(|(name, min, max)| Block {
                    name: name.clone(),
                    min: *min,
                    max: *max,
                })
                .collect(),
            openings: (0..claimed.len()).filter(|&i| claimed[i]).collect(),
        }
    }
}
