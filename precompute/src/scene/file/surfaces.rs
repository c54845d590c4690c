//! The scene file's tables that make surfaces: quads, polygons, rooms (boxes, plans, sloped
//! ceilings), imports of building models, blocks and OBJ files.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use super::Xyz;

/// `[[quad]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct QuadDef {
    pub name: String,
    pub material: Spanned<String>,
    /// Counter-clockwise seen from the front.
    /// Four corners; a list of another length is an error naming it (not truncated).
    pub corners: Spanned<Vec<Xyz>>,
    #[serde(default)]
    pub max_edge: Option<Spanned<f64>>,
    /// Outside the room: an obstruction shading the windows, not meshed into patches.
    #[serde(default)]
    pub exterior: bool,
}

/// `[[polygon]]`: one planar convex face of any number of corners (a triangular window, a
/// trapezoid under a sloped ceiling).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PolygonDef {
    pub name: String,
    pub material: Spanned<String>,
    /// Counter-clockwise seen from the front; at least three.
    pub vertices: Spanned<Vec<Xyz>>,
    #[serde(default)]
    pub max_edge: Option<Spanned<f64>>,
    /// Outside the room: an obstruction shading the windows, not meshed into patches.
    #[serde(default)]
    pub exterior: bool,
}

/// `[[room]]`: a closed room seen from inside, either an axis-aligned box (`min`, `max`) or a
/// floor plan (`plan`, `height`, optional `level`) with one wall per edge.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RoomDef {
    pub name: String,
    /// The box's smallest corner.
    #[serde(default)]
    pub min: Option<Spanned<Xyz>>,
    /// The box's largest corner.
    #[serde(default)]
    pub max: Option<Spanned<Xyz>>,
    /// The floor polygon seen from above, `[x, y]` corners in the scene's unit, either way
    /// round; wall `k` stands on the edge from corner `k` to corner `k + 1` (1-based).
    #[serde(default)]
    pub plan: Option<Spanned<Vec<Vec<f64>>>>,
    /// Floor to ceiling, in the scene's unit (with `plan`).
    #[serde(default)]
    pub height: Option<Spanned<f64>>,
    /// The floor's z, in the scene's unit (with `plan`; default 0).
    #[serde(default)]
    pub level: Option<Spanned<f64>>,
    /// A sloped or pitched ceiling (with `plan`, instead of `height`): the lowest of these
    /// planes over each point of the plan.
    #[serde(default)]
    pub ceiling_planes: Option<Spanned<Vec<Spanned<CeilingPlaneDef>>>>,
    /// One name per plan edge, in edge order (with `plan`; default `wall_1`, `wall_2`, ...).
    #[serde(default)]
    pub wall_names: Option<Spanned<Vec<String>>>,
    /// One material per plan edge, in edge order (with `plan`; default `walls`/`material`).
    #[serde(default)]
    pub wall_materials: Option<Spanned<Vec<Spanned<String>>>>,
    pub material: Spanned<String>,
    #[serde(default)]
    pub floor: Option<Spanned<String>>,
    #[serde(default)]
    pub ceiling: Option<Spanned<String>>,
    #[serde(default)]
    pub walls: Option<Spanned<String>>,
    #[serde(default)]
    pub max_edge: Option<Spanned<f64>>,
    /// Quads set flush into the room's faces; the faces are meshed around them.
    #[serde(default)]
    pub openings: Option<Spanned<Vec<String>>>,
}

/// One plane of a `[[room]]`'s `ceiling_planes`: three points of the ceiling as a section
/// drawing gives them (two along the eaves, one on the ridge, say).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct CeilingPlaneDef {
    /// Its face's name after the room's (default `ceiling` for a single plane, `ceiling_k`
    /// for plane `k` of several).
    #[serde(default)]
    pub name: Option<String>,
    /// Three points of the plane, `[x, y, z]` in the scene's unit, not on one line.
    pub through: Vec<Spanned<Xyz>>,
}

/// `[[import]]`: rooms from a building model (HBJSON or gbXML), each space a room.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ImportDef {
    /// The model file, relative to the scene file: `.hbjson`/`.json` (Honeybee) or
    /// `.xml`/`.gbxml` (gbXML).
    pub file: Spanned<String>,
    /// The spaces to import, by identifier or display name (default: all, in file order).
    #[serde(default)]
    pub spaces: Option<Spanned<Vec<String>>>,
    /// Scene materials for the model's materials (by the model's name), or for faces the
    /// model gives none (by kind: `Floor`, `Wall`, `RoofCeiling`, `Aperture`, `Door`).
    #[serde(default)]
    pub materials: BTreeMap<String, Spanned<String>>,
    /// The model's sensor grids to import as zones: `true` (the default) for all of them,
    /// `false` for none, or a list of names (identifier or display name).
    #[serde(default)]
    pub sensor_grids: Option<Spanned<SensorGridsDef>>,
}

/// `[[import]].sensor_grids`: all, none, or those named.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(crate) enum SensorGridsDef {
    All(bool),
    Names(Vec<String>),
}

/// `[[block]]`: axis-aligned box seen from outside.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BlockDef {
    pub name: String,
    pub min: Spanned<Xyz>,
    pub max: Spanned<Xyz>,
    pub material: Spanned<String>,
    /// Whether to make the bottom face (leave it out when the block stands on the floor).
    #[serde(default = "yes")]
    pub bottom: bool,
    /// Whether to make the top face (leave it out when the block reaches the ceiling).
    #[serde(default = "yes")]
    pub top: bool,
    #[serde(default)]
    pub max_edge: Option<Spanned<f64>>,
    /// Outside the room: an obstruction shading the windows, not meshed into patches.
    #[serde(default)]
    pub exterior: bool,
}

fn yes() -> bool {
    true
}

/// `[[obj]]`: geometry and materials from an OBJ/MTL pair.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ObjDef {
    /// Relative to the scene file.
    pub file: Spanned<String>,
    #[serde(default)]
    pub name_by: NameBy,
    #[serde(default)]
    pub prefix: Option<String>,
    #[serde(default)]
    pub up: UpAxis,
    #[serde(default)]
    pub scale: Option<Spanned<f64>>,
    /// In the scene's unit, applied after `up` and `scale`.
    #[serde(default)]
    pub translate: Option<Spanned<Xyz>>,
    #[serde(default)]
    pub max_edge: Option<Spanned<f64>>,
    /// Drop a face whose corners are those of an earlier face of the same surface.
    #[serde(default)]
    pub drop_duplicate_faces: bool,
    /// What the MTL `Ke` values are.
    #[serde(default)]
    pub ke: KeMeaning,
    /// Outside the room: every surface of the file is an obstruction shading the windows,
    /// not meshed into patches.
    #[serde(default)]
    pub exterior: bool,
    /// The file's faces are one closed room of this name (the room's shell, seen from
    /// inside), laid out as a `[[room]]` with that plan would be.
    #[serde(default)]
    pub room: Option<Spanned<String>>,
    /// The surfaces set flush into the room's faces (an OBJ room only).
    #[serde(default)]
    pub openings: Option<Spanned<Vec<String>>>,
}

/// `obj.ke`: what an MTL file's `Ke` gives.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(crate) enum KeMeaning {
    /// Emitted radiance (W/(m²·sr) per band, or cd/m²), as renderers read it: a Lambertian
    /// emitter's exitance is π times it.
    #[default]
    Radiance,
    /// The exitance itself (W/m² per band, or lux).
    Exitance,
}

impl KeMeaning {
    /// Exitance (W/m² or lux) per unit of `Ke`.
    pub fn exitance_per_ke(self) -> f64 {
        match self {
            KeMeaning::Radiance => std::f64::consts::PI,
            KeMeaning::Exitance => 1.0,
        }
    }
}

/// `obj.name_by`: what names the surfaces of an OBJ file.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(crate) enum NameBy {
    #[default]
    Group,
    Material,
}

/// `obj.up`: which axis of the OBJ file points up.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(crate) enum UpAxis {
    Y,
    #[default]
    Z,
}
