//! Rooms under a flat ceiling: the box (a rectangular plan, faces in the box's order with
//! the box's corners) and the prism on any other plan.

use super::{Ends, FaceKind, Plan, Room, RoomBase, RoomFace};
use crate::geometry::Vec3;
use crate::scene::error::Location;
use crate::scene::primitives::box_faces;

impl RoomBase {
    /// The room on `plan`: as a box when the plan is an axis-aligned rectangle, as a prism
    /// else.
    pub(super) fn laid_out(
        self,
        plan: Plan,
        floor: f64,
        ceiling: f64,
        ends: &Ends,
        label: impl Fn(&str, usize) -> (String, String, Location),
    ) -> Room {
        if plan.is_rectangle() {
            self.boxed(plan, floor, ceiling, ends, label)
        } else {
            self.prism(plan, floor, ceiling, ends, label)
        }
    }

    /// The room on a rectangular `plan` from `floor` to `ceiling` (m), laid out as the box:
    /// `label(box suffix, plan edge)` names a wall and gives its material.
    pub(super) fn boxed(
        self,
        plan: Plan,
        floor: f64,
        ceiling: f64,
        ends: &Ends,
        label: impl Fn(&str, usize) -> (String, String, Location),
    ) -> Room {
        let (lo2, hi2) = plan.bounds();
        let (lo, hi) = (
            Vec3::new(lo2[0], lo2[1], floor),
            Vec3::new(hi2[0], hi2[1], ceiling),
        );
        // The plan edge each box wall stands on: its two ends share that wall's coordinate.
        let edge_at = |axis: usize, value: f64| {
            (0..plan.len())
                .find(|&i| {
                    let (a, b) = plan.edge(i);
                    a[axis] == value && b[axis] == value
                })
                .unwrap_or(0)
        };
        let faces = box_faces(lo, hi)
            .into_iter()
            .map(|(suffix, _, corners)| {
                let outline = corners.to_vec();
                let edge = match suffix {
                    "floor" => return RoomFace::end(FaceKind::Floor, suffix, &ends.floor, outline),
                    "ceiling" => {
                        return RoomFace::end(FaceKind::Ceiling, suffix, &ends.ceiling, outline)
                    }
                    "wall_xmin" => edge_at(0, lo.x),
                    "wall_xmax" => edge_at(0, hi.x),
                    "wall_ymin" => edge_at(1, lo.y),
                    _ => edge_at(1, hi.y),
                };
                let (suffix, material, material_at) = label(suffix, edge);
                RoomFace {
                    suffix,
                    kind: FaceKind::Wall { edge },
                    material,
                    material_at,
                    outline,
                }
            })
            .collect();
        Room {
            name: self.name,
            at: self.at,
            plan,
            floor,
            ceiling,
            lo,
            hi,
            roof: Vec::new(),
            is_box: true,
            faces,
            max_edge: self.max_edge,
        }
    }

    /// The prism on `plan` from `floor` to `ceiling` (m): floor, ceiling, then one wall per
    /// plan edge in counter-clockwise order, `label("", edge)` naming each.
    pub(super) fn prism(
        self,
        plan: Plan,
        floor: f64,
        ceiling: f64,
        ends: &Ends,
        label: impl Fn(&str, usize) -> (String, String, Location),
    ) -> Room {
        let at = |z: f64| -> Vec<Vec3> {
            plan.corners
                .iter()
                .map(|c| Vec3::new(c[0], c[1], z))
                .collect()
        };
        let mut faces = Vec::with_capacity(plan.len() + 2);
        faces.push(RoomFace::end(
            FaceKind::Floor,
            "floor",
            &ends.floor,
            at(floor),
        ));
        let mut down = at(ceiling);
        down.reverse();
        faces.push(RoomFace::end(
            FaceKind::Ceiling,
            "ceiling",
            &ends.ceiling,
            down,
        ));
        for edge in 0..plan.len() {
            let (a, b) = plan.edge(edge);
            let (suffix, material, material_at) = label("", edge);
            // Seen from the room (to the left of a → b): a low, a high, b high, b low.
            faces.push(RoomFace {
                suffix,
                kind: FaceKind::Wall { edge },
                material,
                material_at,
                outline: vec![
                    Vec3::new(a[0], a[1], floor),
                    Vec3::new(a[0], a[1], ceiling),
                    Vec3::new(b[0], b[1], ceiling),
                    Vec3::new(b[0], b[1], floor),
                ],
            });
        }
        let (lo2, hi2) = plan.bounds();
        Room {
            name: self.name,
            at: self.at,
            plan,
            floor,
            ceiling,
            lo: Vec3::new(lo2[0], lo2[1], floor),
            hi: Vec3::new(hi2[0], hi2[1], ceiling),
            roof: Vec::new(),
            is_box: false,
            faces,
            max_edge: self.max_edge,
        }
    }
}
