//! The TOML schema of a scene file, as written (lengths in the file's unit, angles in degrees).
//!
//! Every table denies unknown fields, so a typo is an error naming the line. Values that are
//! checked after parsing carry their span, so range errors name the line too.
//! `docs/scene.md` documents the schema for users.

use std::collections::BTreeMap;

use serde::{Deserialize, Deserializer};
use toml::Spanned;

use super::error::{Location, SceneError};

mod surfaces;
pub(crate) use surfaces::*;

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
