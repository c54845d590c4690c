//! Plan rooms under a sloped or pitched ceiling: their faces (the floor, one face per ceiling
//! plane, walls whose tops follow the ceiling), the check that they close, and the reading of
//! `ceiling_planes`.

use toml::Spanned;

use super::ceiling::{self, CeilingPlane};
use super::{Ends, FaceKind, Plan, Room, RoomBase, RoomFace};
use crate::geometry::Vec3;
use crate::scene::context::Ctx;
use crate::scene::error::{Location, SceneError};
use crate::scene::file::CeilingPlaneDef;
use crate::scene::openings::CONTACT_TOLERANCE;

impl RoomBase {
    /// The room on `plan` from `floor` (m) up to the lowest of `planes` over each point:
    /// floor, one ceiling face per plane, then one wall per plan edge as in
    /// [`RoomBase::prism`], each wall's top following the ceiling. Errors (as messages)
    /// name the plane or the corner at fault.
    pub(super) fn sloped(
        self,
        plan: Plan,
        floor: f64,
        mut planes: Vec<CeilingPlane>,
        ends: &Ends,
        label: impl Fn(&str, usize) -> (String, String, Location),
    ) -> Result<Room, String> {
        let (lo2, hi2) = plan.bounds();
        let size = (hi2[0] - lo2[0]).hypot(hi2[1] - lo2[1]);
        let top = plan
            .corners
            .iter()
            .map(|&c| ceiling::lowest(&planes, c))
            .fold(f64::NEG_INFINITY, f64::max);
        let tol = CONTACT_TOLERANCE * size.hypot(top - floor);
        // The roof may come down to the floor along an edge (an attic without knee walls),
        // not through it.
        for &c in &plan.corners {
            let z = ceiling::lowest(&planes, c);
            if z < floor - tol {
                return Err(format!(
                    "the ceiling is at z = {z} m over the plan corner {c:?} m, not above the \
                     floor (z = {floor} m)"
                ));
            }
        }
        ceiling::set_cells(
            &mut planes,
            [lo2[0] - size, lo2[1] - size],
            [hi2[0] + size, hi2[1] + size],
        );
        let mut faces = Vec::with_capacity(plan.len() + planes.len() + 1);
        let outline = plan.corners.iter().map(|c| Vec3::new(c[0], c[1], floor));
        faces.push(RoomFace::end(
            FaceKind::Floor,
            "floor",
            &ends.floor,
            outline.collect(),
        ));
        let mut all_pieces = Vec::new();
        for (index, plane) in planes.iter().enumerate() {
            let pieces = plan.convex_pieces_within(&plane.cell, &[], tol);
            let Some(first) = pieces.first() else {
                return Err(format!(
                    "ceiling plane `{}` is the ceiling nowhere: over every point of the plan \
                     another plane is lower (or the same)",
                    plane.suffix
                ));
            };
            let outline = first
                .iter()
                .rev()
                .map(|&c| Vec3::new(c[0], c[1], plane.z(c)))
                .collect();
            all_pieces.extend(pieces.iter().map(|p| {
                p.iter()
                    .rev()
                    .map(|&c| Vec3::new(c[0], c[1], plane.z(c)))
                    .collect::<Vec<_>>()
            }));
            faces.push(RoomFace::end(
                FaceKind::CeilingPlane { index },
                &plane.suffix,
                &ends.ceiling,
                outline,
            ));
        }
        for edge in 0..plan.len() {
            let (a, b) = plan.edge(edge);
            // Seen from the room: a low, up to the ceiling, along under it, b low; where the
            // ceiling meets the floor the wall has no side there (a triangle under a gable
            // that comes down to the floor), or no area at all (no wall).
            let top: Vec<Vec3> = ceiling::over_edge(&planes, a, b, tol)
                .into_iter()
                .map(|(p, z)| Vec3::new(p[0], p[1], z))
                .collect();
            if top.iter().all(|p| p.z <= floor + tol) {
                continue;
            }
            let (suffix, material, material_at) = label("", edge);
            let mut outline = vec![Vec3::new(a[0], a[1], floor)];
            let last = top.len() - 1;
            outline.extend(
                top.iter()
                    .enumerate()
                    .filter(|&(k, p)| (k != 0 && k != last) || p.z > floor + tol)
                    .map(|(_, &p)| p),
            );
            outline.push(Vec3::new(b[0], b[1], floor));
            faces.push(RoomFace {
                suffix,
                kind: FaceKind::Wall { edge },
                material,
                material_at,
                outline,
            });
        }
        // A closed shell wound one way has area vectors summing to zero.
        let vector_area = |p: &[Vec3]| {
            let polygon = crate::geometry::Polygon::new(p.to_vec());
            polygon.normal() * polygon.area()
        };
        let shells = faces
            .iter()
            .filter(|f| !matches!(f.kind, FaceKind::CeilingPlane { .. }))
            .map(|f| f.outline.as_slice())
            .chain(all_pieces.iter().map(Vec::as_slice));
        let (mut sum, mut total) = (Vec3::new(0.0, 0.0, 0.0), 0.0);
        for p in shells {
            sum += vector_area(p);
            total += crate::geometry::Polygon::new(p.to_vec()).area();
        }
        if sum.length() > 1e-9 * total {
            return Err(format!(
                "the floor, the walls and the ceiling planes do not close the room: their \
                 area vectors sum to {:?} m² (the planes may cross below a wall's top)",
                sum.to_array()
            ));
        }
        let high = faces
            .iter()
            .flat_map(|f| &f.outline)
            .chain(all_pieces.iter().flatten())
            .map(|p| p.z)
            .fold(top, f64::max);
        if high <= floor + tol {
            return Err(format!(
                "the ceiling is nowhere above the floor (z = {floor} m): the room has no volume"
            ));
        }
        Ok(Room {
            name: self.name,
            at: self.at,
            floor,
            ceiling: high,
            lo: Vec3::new(lo2[0], lo2[1], floor),
            hi: Vec3::new(hi2[0], hi2[1], high),
            plan,
            roof: planes,
            is_box: false,
            faces,
            max_edge: self.max_edge,
        })
    }
}

/// Reads and checks `room.ceiling_planes`: the planes (metres), named.
pub(super) fn read_ceiling_planes(
    ctx: &Ctx,
    what: &str,
    list: &Spanned<Vec<Spanned<CeilingPlaneDef>>>,
) -> Result<Vec<CeilingPlane>, SceneError> {
    let defs = list.get_ref();
    if defs.is_empty() {
        return Err(SceneError::Invalid {
            at: ctx.at(list),
            field: format!("{what}.ceiling_planes"),
            message: "lists no plane: give at least one, or `height` for a flat ceiling".into(),
        });
    }
    let mut planes: Vec<CeilingPlane> = Vec::with_capacity(defs.len());
    for (k, def) in defs.iter().enumerate() {
        let d = def.get_ref();
        let field = format!("{what}.ceiling_planes[{}]", k + 1);
        let suffix = d.name.clone().unwrap_or_else(|| {
            if defs.len() == 1 {
                "ceiling".into()
            } else {
                format!("ceiling_{}", k + 1)
            }
        });
        let invalid = |message: String| SceneError::Invalid {
            at: ctx.at(def),
            field: field.clone(),
            message,
        };
        if planes.iter().any(|p| p.suffix == suffix) {
            return Err(invalid(format!(
                "the name `{suffix}` is already another plane's"
            )));
        }
        let [a, b, c] = &d.through[..] else {
            return Err(invalid(format!(
                "`through` gives {} points; a plane is given by three",
                d.through.len()
            )));
        };
        let p = [
            ctx.point(a, &format!("{field}.through"))?,
            ctx.point(b, &format!("{field}.through"))?,
            ctx.point(c, &format!("{field}.through"))?,
        ];
        let plane = CeilingPlane::through(suffix, p).ok_or_else(|| {
            invalid(
                "its three points lie on one line or in a vertical plane: a ceiling plane \
                 needs three points not on one line, not all straight above each other"
                    .into(),
            )
        })?;
        planes.push(plane);
    }
    Ok(planes)
}
