//! A building model as the importers read it, whatever its format: spaces made of faces
//! (metres, each wound as the file winds it), the openings in those faces, the materials the
//! file defines, and what the reader could not map.

use std::collections::BTreeMap;

use crate::geometry::Vec3;

/// A building model read from an HBJSON or gbXML file.
#[derive(Clone, Debug, Default)]
pub(crate) struct Model {
    /// Its spaces (Honeybee rooms, gbXML `Space`s), in file order.
    pub spaces: Vec<Space>,
    /// The materials it defines, by the name its faces use.
    pub materials: BTreeMap<String, ModelMaterial>,
    /// How far apart two points may be and still count as one, metres (the file's own
    /// tolerance where it states one).
    pub tolerance: f64,
    /// Its sensor grids (Honeybee `sensor_grids`), in file order.
    pub grids: Vec<ModelGrid>,
    /// What the reader met and could not map (shades, air boundaries, unknown face types):
    /// reported, never guessed.
    pub warnings: Vec<String>,
}

/// A grid of sensors the model defines (a Honeybee `SensorGrid`): points where illuminance
/// is read, each on the plane facing its own direction.
#[derive(Clone, Debug)]
pub(crate) struct ModelGrid {
    /// Its identifier in the file.
    pub id: String,
    /// The zone name it is given in the scene (its display name, else its identifier).
    pub name: String,
    pub line: Option<usize>,
    /// The identifier of the space it lies in, when the file says.
    pub space: Option<String>,
    /// Its sensors in file order: position (m) and unit direction each faces.
    pub sensors: Vec<(Vec3, Vec3)>,
}

/// A material the model defines, with what the file says of it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ModelMaterial {
    /// Diffuse reflectance, red, green and blue, each in [0, 1].
    pub reflectance: [f64; 3],
    /// Visible transmittance at normal incidence, red, green and blue (glazing only).
    pub transmittance: Option<[f64; 3]>,
    /// The glazing's panes, when the file says (default: a scene material's default).
    pub panes: Option<usize>,
}

/// What a face of a space is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ModelFaceKind {
    Floor,
    Wall,
    /// A ceiling or a roof: the top of the space.
    Ceiling,
}

impl ModelFaceKind {
    /// The key of `[[import]].materials` that gives faces of this kind a material when the
    /// model gives them none.
    pub fn key(self) -> &'static str {
        match self {
            ModelFaceKind::Floor => "Floor",
            ModelFaceKind::Wall => "Wall",
            ModelFaceKind::Ceiling => "RoofCeiling",
        }
    }
}

/// A face of a space.
#[derive(Clone, Debug)]
pub(crate) struct ModelFace {
    /// Its identifier in the file.
    pub id: String,
    /// The name it is given in the scene (its display name, else its identifier).
    pub name: String,
    /// The 1-based line of the file where it is defined, when known.
    pub line: Option<usize>,
    pub kind: ModelFaceKind,
    /// Its corners, metres, wound either way.
    pub polygon: Vec<Vec3>,
    /// The name of its material in the file, if it names one.
    pub material: Option<String>,
    /// The identifier of the space on its other side, for a face shared with another space.
    pub adjacent: Option<String>,
    /// Windows and doors set in it.
    pub openings: Vec<ModelOpening>,
}

/// What an opening is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum OpeningKind {
    /// A window or a skylight (Honeybee `Aperture`, gbXML fixed or operable windows and
    /// skylights).
    Window,
    /// A door (glazed or not).
    Door,
}

impl OpeningKind {
    /// The key of `[[import]].materials` for openings of this kind without a material.
    pub fn key(self) -> &'static str {
        match self {
            OpeningKind::Window => "Aperture",
            OpeningKind::Door => "Door",
        }
    }
}

/// A window or a door in a face.
#[derive(Clone, Debug)]
pub(crate) struct ModelOpening {
    pub id: String,
    /// The name it is given in the scene (after its space's).
    pub name: String,
    pub line: Option<usize>,
    pub kind: OpeningKind,
    /// Its corners, metres, wound either way.
    pub polygon: Vec<Vec3>,
    pub material: Option<String>,
}

/// A space (a Honeybee room, a gbXML `Space`).
#[derive(Clone, Debug)]
pub(crate) struct Space {
    /// Its identifier in the file.
    pub id: String,
    /// The room name it is given in the scene (its display name, else its identifier).
    pub name: String,
    pub line: Option<usize>,
    pub faces: Vec<ModelFace>,
}

/// The length of a unit named in a model file, metres: the units Honeybee and gbXML name.
pub(crate) fn unit_metres(name: &str) -> Option<f64> {
    Some(match name {
        "Meters" | "Meter" => 1.0,
        "Centimeters" | "Centimeter" => 0.01,
        "Millimeters" | "Millimeter" => 0.001,
        "Kilometers" => 1000.0,
        "Feet" | "Foot" => 0.3048,
        "Inches" | "Inch" => 0.0254,
        "Yards" => 0.9144,
        "Miles" => 1609.344,
        _ => return None,
    })
}
