//! `[[obj]]` with `room`: an OBJ file whose faces are one closed room seen from inside.
//!
//! The faces are checked to be one closed shell wound into the room ([`shell`]), faces in
//! one plane are merged into the room's faces ([`faces`]), and the result is read as a space
//! of a building model is ([`prism`]): a floor polygon, a wall standing on each of its edges
//! and a flat or sloped ceiling over it. The room is then laid out exactly as a `[[room]]`
//! with that `plan` (and `height` or `ceiling_planes`), so that openings, blocks, sensors,
//! luminaires, work planes and plans treat it as any other room, and the same room drawn in
//! OBJ or written as a plan gives the same patches.

mod faces;
mod shell;

use toml::Spanned;

use super::context::Ctx;
use super::error::{Location, SceneError};
use super::file::ObjDef;
use super::import::model::{ModelFace, Space};
use super::import::prism;
use super::obj::ObjContent;
use super::openings::CONTACT_TOLERANCE;
use super::room::{Ends, Room};
use crate::geometry::Aabb;
use faces::Merged;
use shell::InputFace;

/// An OBJ room and the openings its `[[obj]]` lists.
pub(crate) struct ObjRoom {
    pub room: Room,
    /// The surfaces set flush into its faces.
    pub openings: Vec<String>,
    /// Where the list (else the `[[obj]]` entry) was written.
    pub at: Location,
}

/// Reads the room of the `[[obj]]` entry `def` named `name` from its `content`.
pub(crate) fn read(
    ctx: &Ctx,
    def: &Spanned<ObjDef>,
    name: &Spanned<String>,
    content: &ObjContent,
) -> Result<ObjRoom, SceneError> {
    let o = def.get_ref();
    let room_name = name.get_ref();
    let refuse = |field: &str, message: &str| SceneError::Invalid {
        at: ctx.at(def),
        field: format!("obj.{field}"),
        message: message.to_owned(),
    };
    if o.prefix.is_some() {
        return Err(refuse(
            "prefix",
            "an OBJ room's faces are named after the room (`<room>.floor`, ...): drop `prefix`",
        ));
    }
    if o.exterior {
        return Err(refuse(
            "exterior",
            "a room is the inside: an OBJ room cannot be exterior",
        ));
    }
    let file = content
        .surfaces
        .first()
        .map_or_else(|| ctx.at(&o.file), |s| s.at.clone());
    let mut input = Vec::new();
    let mut surface_of = Vec::new();
    let mut material_of = Vec::new();
    for (s, surface) in content.surfaces.iter().enumerate() {
        for (k, corners) in surface.faces.iter().enumerate() {
            input.push(InputFace {
                corners: corners.clone(),
                label: format!("face {} of `{}`", k + 1, surface.name),
                line: content.lines[s].get(k).copied().flatten(),
            });
            surface_of.push(s);
            material_of.push(surface.material.as_str());
        }
    }
    let mut bounds = Aabb::EMPTY;
    for p in input.iter().flat_map(|f| &f.corners) {
        bounds.grow(*p);
    }
    let tol = CONTACT_TOLERANCE * (bounds.max - bounds.min).length();
    let error = |face: usize, message: String| SceneError::Import {
        at: Location {
            file: file.file.clone(),
            line: input[face].line,
        },
        element: format!("OBJ room `{room_name}`, {}", input[face].label),
        message,
    };
    let shell = shell::close(&input, tol).map_err(|e| error(e.face, e.message))?;
    let merged = faces::merge(&shell, &input, &surface_of, &material_of, tol)
        .map_err(|e| error(e.face, e.message))?;
    let space = Space {
        id: room_name.clone(),
        name: room_name.clone(),
        line: None,
        faces: merged.iter().map(|m| m.face.clone()).collect(),
    };
    let p = prism::prism(&space, tol).map_err(|e| {
        // The prism names faces as a model's (``space `R`, face `ID` ``): name them as above.
        let mut element = e.element.replacen("space `", "OBJ room `", 1);
        for m in &merged {
            element = element.replace(&format!("face `{}`", m.face.id), &m.face.id);
        }
        SceneError::Import {
            at: Location {
                file: file.file.clone(),
                line: e.line,
            },
            element,
            message: e.message,
        }
    })?;
    // The merged face a face of the prism is (each input face is in exactly one).
    let of = |f: &ModelFace| merged.iter().position(|m| m.face.id == f.id).unwrap_or(0);
    let material = |m: &Merged| {
        let s = &content.surfaces[surface_of[m.members[0]]];
        (s.material.clone(), s.material_at.clone())
    };
    let floor = material(&merged[of(p.floor_face)]);
    let ceiling = material(&merged[of(p.ceiling_faces[0])]);
    if let Some(other) = p
        .ceiling_faces
        .iter()
        .map(|&c| &merged[of(c)])
        .find(|m| material(m).0 != ceiling.0)
    {
        return Err(error(
            other.members[0],
            format!(
                "its material `{}` differs from the rest of the ceiling's (`{}`): a room's \
                 ceiling has one material",
                material(other).0,
                ceiling.0
            ),
        ));
    }
    // A wall is named after its OBJ surface when that surface makes it and no other wall.
    let surface_name = |m: &Merged| m.surface.map(|s| content.surfaces[s].name.clone());
    let wall_surfaces: Vec<Option<String>> = p
        .walls
        .iter()
        .map(|&w| w.and_then(|w| surface_name(&merged[of(w)])))
        .collect();
    let walls: Vec<(String, String, Location)> = p
        .walls
        .iter()
        .enumerate()
        .map(|(k, &w)| {
            let own = wall_surfaces[k].clone().filter(|s| {
                wall_surfaces
                    .iter()
                    .filter(|t| t.as_ref() == Some(s))
                    .count()
                    == 1
                    && s != "floor"
                    && !s.starts_with("ceiling")
            });
            let suffix = own.unwrap_or_else(|| format!("wall_{}", k + 1));
            let (material, at) = match w {
                Some(w) => material(&merged[of(w)]),
                // No wall where the roof meets the floor: the room has no face there either.
                None => ceiling.clone(),
            };
            (suffix, material, at)
        })
        .collect();
    let ends = Ends { floor, ceiling };
    let at = ctx.at(def);
    let mut room = if p.roof.is_empty() {
        Room::from_plan(
            room_name.clone(),
            at.clone(),
            p.plan.clone(),
            (p.floor, p.ceiling),
            &ends,
            |edge| walls[edge].clone(),
        )
    } else {
        // Named as a `[[room]]`'s `ceiling_planes` without names are.
        let mut roof = p.roof.clone();
        let count = roof.len();
        for (k, plane) in roof.iter_mut().enumerate() {
            plane.suffix = match count {
                1 => "ceiling".into(),
                _ => format!("ceiling_{}", k + 1),
            };
        }
        Room::from_sloped_plan(
            room_name.clone(),
            at.clone(),
            p.plan.clone(),
            p.floor,
            roof,
            &ends,
            |edge| walls[edge].clone(),
        )
        .map_err(|message| SceneError::Invalid {
            at: at.clone(),
            field: format!("obj room `{room_name}`"),
            message,
        })?
    };
    room.max_edge = ctx.optional_length(o.max_edge.as_ref(), "obj.max_edge")?;
    Ok(ObjRoom {
        room,
        openings: o
            .openings
            .as_ref()
            .map_or_else(Vec::new, |l| l.get_ref().clone()),
        at: o.openings.as_ref().map_or(at, |l| ctx.at(l)),
    })
}
