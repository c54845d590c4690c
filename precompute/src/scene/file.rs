//! The TOML schema of a scene file, as written (lengths in the file's unit, angles in degrees).
//!
//! Every table denies unknown fields, so a typo is an error naming the line. Values that are
//! checked after parsing carry their span, so range errors name the line too.
//! `docs/scene.md` documents the schema for users.

use std::collections::BTreeMap;

use serde::{Deserialize, Deserializer};
use toml::Spanned;

use super::error::{Location, SceneError};

/// Three numbers (a point or a direction), exactly: an array of another length is an error
/// naming its line, where a fixed-size array would drop extra numbers silently.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Xyz(pub [f64; 3]);

impl<'de> Deserialize<'de> for Xyz {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Vec::<f64>::deserialize(d)?;
        <[f64; 3]>::try_from(v.as_slice())
            .map(Xyz)
            .map_err(|_| serde::de::Error::invalid_length(v.len(), &"3 numbers (x, y, z)"))
    }
}

impl std::ops::Deref for Xyz {
    type Target = [f64; 3];
    fn deref(&self) -> &[f64; 3] {
        &self.0
    }
}

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SceneFile {
    pub scene: Header,
    /// Where the room stands, for daylight.
    #[serde(default)]
    pub site: Option<Spanned<SiteDef>>,
    #[serde(default)]
    pub materials: BTreeMap<String, Spanned<MaterialDef>>,
    #[serde(default)]
    pub surfaces: BTreeMap<String, Spanned<SurfaceOverride>>,
    #[serde(default)]
    pub room: Vec<Spanned<RoomDef>>,
    #[serde(default)]
    pub import: Vec<Spanned<ImportDef>>,
    #[serde(default)]
    pub block: Vec<Spanned<BlockDef>>,
    #[serde(default)]
    pub quad: Vec<Spanned<QuadDef>>,
    #[serde(default)]
    pub polygon: Vec<Spanned<PolygonDef>>,
    #[serde(default)]
    pub obj: Vec<Spanned<ObjDef>>,
    #[serde(default)]
    pub channel: Vec<Spanned<ChannelDef>>,
    #[serde(default)]
    pub luminaire: Vec<Spanned<LuminaireDef>>,
    #[serde(default)]
    pub sensor: Vec<Spanned<SensorDef>>,
    #[serde(default)]
    pub zone: Vec<Spanned<ZoneDef>>,
}

impl SceneFile {
    /// Parses a scene file's text; `origin` is the file it came from, for messages.
    pub fn parse(text: &str, origin: &std::path::Path) -> Result<SceneFile, SceneError> {
        toml::from_str(text).map_err(|e| SceneError::Syntax {
            at: match e.span() {
                Some(span) => Location::at_offset(origin, text, span.start),
                None => Location::file(origin),
            },
            message: e.message().trim().to_string(),
        })
    }
}

/// `[scene]`: name, bands, unit and meshing defaults.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Header {
    pub name: String,
    pub bands: BandsDef,
    pub unit: Spanned<UnitDef>,
    /// Longest patch edge, in `unit`.
    pub max_edge: Spanned<f64>,
    /// Largest distance of a polygon's corner from its mean plane, as a fraction of the
    /// polygon's longest diagonal.
    #[serde(default)]
    pub planarity_tolerance: Option<Spanned<f64>>,
}

/// `scene.bands`.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum BandsDef {
    Photopic,
    Rgb,
}

/// `scene.unit`: the length unit of every coordinate and length in the file.
#[derive(Clone, Copy, Debug, Deserialize)]
pub(crate) enum UnitDef {
    #[serde(rename = "m")]
    Metre,
    #[serde(rename = "cm")]
    Centimetre,
    #[serde(rename = "mm")]
    Millimetre,
    #[serde(rename = "ft")]
    Foot,
    #[serde(rename = "in")]
    Inch,
}

impl UnitDef {
    /// Metres per unit (the foot and inch are the international ones).
    pub fn metres(self) -> f64 {
        match self {
            UnitDef::Metre => 1.0,
            UnitDef::Centimetre => 0.01,
            UnitDef::Millimetre => 0.001,
            UnitDef::Foot => 0.3048,
            UnitDef::Inch => 0.0254,
        }
    }
}

/// One number for every band, or one per band.
#[derive(Clone, Debug)]
pub(crate) enum PerBand {
    One(f64),
    Many(Vec<f64>),
}

impl<'de> Deserialize<'de> for PerBand {
    // By hand rather than `untagged`, so that a wrong value says what was expected.
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = PerBand;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a number, or a list of numbers with one per band")
            }
            fn visit_f64<E>(self, v: f64) -> Result<PerBand, E> {
                Ok(PerBand::One(v))
            }
            fn visit_i64<E>(self, v: i64) -> Result<PerBand, E> {
                Ok(PerBand::One(v as f64))
            }
            fn visit_u64<E>(self, v: u64) -> Result<PerBand, E> {
                Ok(PerBand::One(v as f64))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<PerBand, A::Error> {
                let mut values = Vec::new();
                while let Some(v) = seq.next_element::<f64>()? {
                    values.push(v);
                }
                Ok(PerBand::Many(values))
            }
        }
        d.deserialize_any(Visitor)
    }
}

/// `[materials.<name>]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MaterialDef {
    /// Diffuse reflectance in [0, 1).
    pub reflectance: Spanned<PerBand>,
    /// Exitance at level 1 (lux or W/m² per band).
    #[serde(default)]
    pub emission: Option<Spanned<PerBand>>,
    /// Visible transmittance at normal incidence, in (0, 1): the material is glazing and
    /// its surfaces are windows.
    #[serde(default)]
    pub transmittance: Option<Spanned<f64>>,
    /// Panes of the glazing, 1 to 3 (default 2); only with `transmittance`.
    #[serde(default)]
    pub panes: Option<Spanned<i64>>,
    /// The glazing's angular model (default clear); only with `transmittance`.
    #[serde(default)]
    pub glazing: Option<Spanned<GlazingDef>>,
}

/// `materials.<name>.glazing`.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(crate) enum GlazingDef {
    /// Clear glass: transmitted light keeps its direction.
    Clear,
    /// Transmitted light leaves as a Lambertian emitter.
    Diffusing,
}

/// `[site]`: where the room stands and how it is turned (degrees, metres).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SiteDef {
    /// Degrees north, −90 to 90.
    pub latitude: Spanned<f64>,
    /// Degrees east, −180 to 180.
    pub longitude: Spanned<f64>,
    /// Metres above sea level (default 0); always metres, whatever `scene.unit`.
    #[serde(default)]
    pub elevation: Option<Spanned<f64>>,
    /// Compass bearing of the scene's +y axis, degrees clockwise from true north (default 0).
    #[serde(default)]
    pub north: Option<Spanned<f64>>,
    /// `"Z"`, `"+HH:MM"` or `"-HH:MM"`: the offset of times given without one.
    #[serde(default)]
    pub utc_offset: Option<Spanned<String>>,
    /// The ground's diffuse reflectance, in [0, 1) (default 0.2).
    #[serde(default)]
    pub ground_reflectance: Option<Spanned<f64>>,
}

/// `[surfaces.<name>]`: per-surface settings that apply whatever made the surface.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SurfaceOverride {
    #[serde(default)]
    pub material: Option<Spanned<String>>,
    #[serde(default)]
    pub max_edge: Option<Spanned<f64>>,
    /// Reverse the winding of every face (the file has them facing the wrong way).
    #[serde(default)]
    pub flip: bool,
    /// Cut every face into triangles before meshing (for slightly non-planar quads).
    #[serde(default)]
    pub triangulate: bool,
}

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

/// `[[channel]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ChannelDef {
    pub name: String,
    #[serde(default)]
    pub surfaces: Option<Spanned<Vec<String>>>,
    #[serde(default)]
    pub materials: Option<Spanned<Vec<String>>>,
    /// Exitance at level 1, lux or W/m² per band.
    #[serde(default)]
    pub exitance: Option<Spanned<PerBand>>,
    /// Flux at level 1, lm or W per band, spread uniformly over the channel's area.
    #[serde(default)]
    pub flux: Option<Spanned<PerBand>>,
}

/// `[[luminaire]]`: a luminaire (or an array of them) placed with its photometric file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LuminaireDef {
    pub name: String,
    /// An `.ies` or `.ldt` file, relative to the scene file.
    pub file: Spanned<String>,
    /// Photometric centre, in the scene's unit (of the first element of an array).
    pub position: Spanned<Xyz>,
    /// The nadir direction (γ = 0), any non-zero length; default straight down.
    #[serde(default)]
    pub aim: Option<Spanned<Xyz>>,
    /// Rotation of the C0 plane about the nadir axis, degrees.
    #[serde(default)]
    pub spin: Option<Spanned<f64>>,
    #[serde(default)]
    pub array: Option<Spanned<ArrayDef>>,
    /// The `[[channel]]` that dims it.
    pub channel: Spanned<String>,
    /// Light-loss factor in (0, 1]; default 1.
    #[serde(default)]
    pub maintenance_factor: Option<Spanned<f64>>,
}

/// `luminaire.array`: copies in rows along y and columns along x of the scene.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ArrayDef {
    pub rows: usize,
    pub columns: usize,
    /// `[dx, dy]` between neighbouring columns and rows, in the scene's unit.
    pub spacing: Vec<f64>,
}

/// `[[sensor]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SensorDef {
    pub name: String,
    pub position: Spanned<Xyz>,
    pub normal: Spanned<Xyz>,
    /// Degrees.
    #[serde(default)]
    pub half_angle: Option<Spanned<f64>>,
    /// The angular response in place of a cosine within `half_angle`.
    #[serde(default)]
    pub response: Option<Spanned<ResponseDef>>,
}

/// `[sensor].response`: a preset, an `rsensor` file or an inline table (one of them).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ResponseDef {
    /// `cosine`, `cone` or `shielded`.
    #[serde(default)]
    pub preset: Option<Spanned<String>>,
    /// Degrees: the cone preset's half-angle.
    #[serde(default)]
    pub half_angle: Option<Spanned<f64>>,
    /// Degrees: the shielded preset's cut-off.
    #[serde(default)]
    pub cutoff: Option<Spanned<f64>>,
    /// A table in Radiance's `rsensor` layout, relative to the scene file.
    #[serde(default)]
    pub file: Option<Spanned<String>>,
    /// Degrees: the inline table's polar angles.
    #[serde(default)]
    pub polar: Option<Spanned<Vec<f64>>>,
    /// The inline table's relative sensitivities, one per polar angle.
    #[serde(default)]
    pub sensitivity: Option<Spanned<Vec<f64>>>,
}

/// `[[zone]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ZoneDef {
    pub name: String,
    #[serde(default)]
    pub surfaces: Option<Spanned<Vec<String>>>,
    #[serde(default)]
    pub work_plane: Option<Spanned<WorkPlaneDef>>,
    /// A surface zone's calculation grid (none unless given; `grid = {}` for the rule).
    #[serde(default)]
    pub grid: Option<Spanned<GridDef>>,
}

/// `zone.work_plane`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct WorkPlaneDef {
    /// The room whose footprint it covers; may be left out when there is one room.
    #[serde(default)]
    pub room: Option<Spanned<String>>,
    /// Above the room's floor, in the scene's unit.
    pub height: Spanned<f64>,
    /// Distance kept from the walls, in the scene's unit.
    #[serde(default)]
    pub margin: Option<Spanned<f64>>,
    /// Longest receiver edge, in the scene's unit (default: `scene.max_edge`).
    #[serde(default)]
    pub max_edge: Option<Spanned<f64>>,
    /// A task area: the plane restricted to this rectangle of the room's footprint.
    #[serde(default)]
    pub area: Option<Spanned<AreaDef>>,
    /// With `area`: the band around the task area instead (its surrounding), in the scene's
    /// unit.
    #[serde(default)]
    pub band: Option<Spanned<BandDef>>,
    /// The calculation grid's settings (default: the EN 12464-1 rule).
    #[serde(default)]
    pub grid: Option<Spanned<GridDef>>,
}

/// `zone.work_plane.area`: a rectangle of the floor plan, in the scene's unit.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct AreaDef {
    /// Smallest x and y (two numbers).
    pub min: Spanned<Vec<f64>>,
    /// Largest x and y (two numbers).
    pub max: Spanned<Vec<f64>>,
}

/// `zone.work_plane.band`: a width from the task area's edges, or two distances from them.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(crate) enum BandDef {
    /// The band from the area's edges out to this distance.
    Width(f64),
    /// The band between these two distances from the area's edges.
    Between(Vec<f64>),
}

/// `zone.work_plane.grid` and `zone.grid`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct GridDef {
    /// Largest spacing between points, in the scene's unit (default: the EN 12464-1 rule).
    #[serde(default)]
    pub spacing: Option<Spanned<f64>>,
}
