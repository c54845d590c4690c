//! Scene input: a TOML scene file (with OBJ/MTL geometry and built-in primitives) read into
//! meshed patches with reflectance, emission, channels, sensors and zones.
//!
//! The file format is documented in `docs/scene.md`. Everything here is in SI units: lengths
//! in metres, areas in m², angles in radians; exitance in lux (photopic scenes) or W/m² per
//! band (rgb scenes).

mod build;
mod channels;
mod contacts;
mod context;
mod daylight;
mod error;
pub(crate) mod file;
pub mod grid;
mod import;
mod inputs;
pub mod layout;
mod limits;
mod luminaires;
mod mesh;
mod obj;
mod obj_room;
mod observers;
mod openings;
pub mod photometry;
mod primitives;
pub mod receivers;
pub mod response;
mod room;
#[cfg(test)]
mod tests;
mod winding;

use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::geometry::{Face, Patch, Vec3};
use crate::scene::photometry::Photometry;

pub use error::{Location, SceneError};
pub use grid::Grid;
pub use inputs::{inputs, SceneInputs};
#[cfg(test)]
pub(crate) use luminaires::frame as luminaire_frame;
pub use receivers::{FieldOfView, Receiver};

/// The spectral bands a scene is computed in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bands {
    /// One band weighted by the photopic luminosity function: exitance and irradiance in lux
    /// (lm/m²), flux in lumens.
    Photopic,
    /// Three radiometric bands (red, green, blue): exitance and irradiance in W/m² per band,
    /// flux in W per band.
    Rgb,
}

impl Bands {
    /// Number of bands: 1 or 3.
    pub fn count(self) -> usize {
        match self {
            Bands::Photopic => 1,
            Bands::Rgb => 3,
        }
    }

    /// Unit of exitance and irradiance: `"lux"` or `"W/m²"`.
    pub fn unit(self) -> &'static str {
        match self {
            Bands::Photopic => "lux",
            Bands::Rgb => "W/m²",
        }
    }
}

/// A named surface: a room face, a block face, a quad or an OBJ group, cut into patches.
#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    /// Unique name (`room.floor`, `desk1.top`, an OBJ group or material name...).
    pub name: String,
    /// Name of its material.
    pub material: String,
    /// Diffuse reflectance per band, each in [0, 1).
    pub reflectance: Vec<f64>,
    /// Its patches in [`Scene::patches`].
    pub patch_range: Range<usize>,
}

/// A group of light sources dimmed together (a luminaire circuit, a window): emitting
/// surfaces, luminaires with photometry ([`Scene::luminaires`] naming it), or both.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    /// Unique name.
    pub name: String,
    /// Indices into [`Scene::surfaces`] of the surfaces it drives (none for a channel of
    /// luminaires only).
    pub surfaces: Vec<usize>,
    /// Area-weighted mean exitance of its surfaces at level 1, per band (lux or W/m²); zero
    /// when it drives no surface. Times the channel's area this is its surfaces' flux (lm or
    /// W).
    pub exitance: Vec<f64>,
}

/// A luminaire placed in the scene with its photometry: one element of a `[[luminaire]]`
/// entry (docs/scene.md, "Luminaires").
///
/// Its frame is right-handed as seen from behind: `c90 = −nadir × c0`, so C counts
/// counter-clockwise seen from above a downward luminaire, as type C photometry does.
#[derive(Clone, Debug, PartialEq)]
pub struct Luminaire {
    /// Unique name: the entry's name, or `name[row,column]` (1-based) for an array's element.
    pub name: String,
    /// The photometric file, as found from the scene's folder.
    pub file: PathBuf,
    /// Its photometry, shared by every luminaire of the same file.
    pub photometry: Arc<Photometry>,
    /// Photometric centre, metres.
    pub position: Vec3,
    /// Unit vector of γ = 0 (the nadir of the distribution).
    pub nadir: Vec3,
    /// Unit vector of C = 0°, γ = 90°: perpendicular to `nadir`.
    pub c0: Vec3,
    /// Unit vector of C = 90°, γ = 90°.
    pub c90: Vec3,
    /// Index into [`Scene::channels`] of the channel that dims it.
    pub channel: usize,
    /// Light-loss (maintenance) factor in (0, 1], multiplying every intensity.
    pub maintenance_factor: f64,
    /// The photometric file's tilt factor at this luminaire's orientation, multiplying every
    /// intensity ([`photometry::Photometry::tilt_factor`]; 1 without a tilt table).
    pub tilt_factor: f64,
}

impl Luminaire {
    /// The photometric angles `(C, γ)`, degrees, of a direction (any non-zero length) leaving
    /// the luminaire: `γ` from `nadir` in [0, 180], `C` from `c0` towards `c90` in (−180, 180].
    pub fn angles(&self, direction: Vec3) -> (f64, f64) {
        let d = direction.normalized();
        let gamma = d.dot(self.nadir).clamp(-1.0, 1.0).acos().to_degrees();
        let c = d.dot(self.c90).atan2(d.dot(self.c0)).to_degrees();
        (c, gamma)
    }

    /// Luminous intensity, cd, towards `direction`, the maintenance and tilt factors included.
    pub fn intensity(&self, direction: Vec3) -> f64 {
        let distribution = &self.photometry.distribution;
        let (c, gamma) = if distribution.c_angles().len() == 1 {
            // Rotationally symmetric: C does not matter (and its atan2 is not computed).
            let d = direction.normalized();
            (0.0, d.dot(self.nadir).clamp(-1.0, 1.0).acos().to_degrees())
        } else {
            self.angles(direction)
        };
        self.maintenance_factor * self.tilt_factor * distribution.intensity(c, gamma)
    }
}

/// A point sensor (e.g. a ceiling photocell or a desk illuminance meter).
#[derive(Clone, Debug, PartialEq)]
pub struct Sensor {
    /// Unique name.
    pub name: String,
    /// Position, metres.
    pub position: Vec3,
    /// Unit normal of the sensing face.
    pub normal: Vec3,
    /// Field-of-view half-angle around the normal, radians; `None` is the full hemisphere.
    pub half_angle: Option<f64>,
    /// Angular response in place of the cosine (then `half_angle` is `None`); `None`: a
    /// cosine response within `half_angle`.
    pub response: Option<response::Response>,
}

/// A region whose area-averaged irradiance is reported.
#[derive(Clone, Debug, PartialEq)]
pub struct Zone {
    /// Unique name.
    pub name: String,
    /// What the zone is made of.
    pub kind: ZoneKind,
    /// Its calculation grid: always for a work plane and a sensor grid, when asked for a
    /// surface zone.
    pub grid: Option<Grid>,
}

/// What a zone averages over.
#[derive(Clone, Debug, PartialEq)]
pub enum ZoneKind {
    /// Patches of the scene (indices into [`Scene::patches`]).
    Surfaces(Vec<usize>),
    /// A horizontal work plane: upward-facing receivers that do not block light.
    WorkPlane {
        /// Height above the room's floor, metres.
        height: f64,
        /// Receiving patches covering the room's footprint (less the margin) at that height.
        /// Their `surface` is the index of the room's floor surface they lie above.
        receivers: Vec<Patch>,
    },
    /// A sensor grid imported from a building model: points each facing its own direction
    /// (also the zone's grid, which `--no-grids` drops), and the zone reads their mean
    /// (docs/scene.md, "Importing a building model").
    Points {
        /// Position (m) and unit normal of each point, in the grid's order.
        points: Vec<(Vec3, Vec3)>,
        /// The area the grid stands for, m²: a square cell of the grid's spacing per point
        /// (the model gives sensors, not the area they sample).
        area: f64,
    },
}

/// Where the room stands, for daylight: the scene's `[site]` (docs/scene.md, "Daylight").
#[derive(Clone, Debug, PartialEq)]
pub struct Site {
    /// Latitude (degrees north), longitude (degrees east) and elevation (m).
    pub location: crate::daylight::sun::Site,
    /// Compass bearing of the scene's +y axis, degrees clockwise from true north
    /// (`crate::daylight::room_direction`).
    pub north: f64,
    /// The site's UTC offset, seconds east of UTC, for times given without one; `None`: every
    /// time must carry its offset.
    pub utc_offset: Option<i32>,
    /// Diffuse reflectance of the ground outside, in [0, 1).
    pub ground_reflectance: f64,
}

/// A glazed surface through which daylight enters: a surface whose material has a
/// transmittance.
#[derive(Clone, Debug, PartialEq)]
pub struct Window {
    /// Index into [`Scene::surfaces`]; its patches face into the room.
    pub surface: usize,
    /// The glazing's angular transmittance (clear or diffusing).
    pub glazing: eigenrad_runtime::sky::glazing::Glazing,
}

/// A surface outside the room (`exterior = true`): it shades the windows and is not meshed
/// into the room's patches.
#[derive(Clone, Debug, PartialEq)]
pub struct Obstruction {
    /// The surface's name.
    pub name: String,
    /// Its convex faces, in metres (their `patches` ranges are empty).
    pub faces: Vec<Face>,
    /// Diffuse reflectance of the faces seen from the windows, in [0, 1) (photopic).
    pub reflectance: f64,
}

/// A face of a room imported from a building model that the model shares with another space
/// (HBJSON `boundary_condition: Surface`, gbXML `AdjacentSpaceId` pairs), kept for the
/// building manifest.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Adjacency {
    /// The room's surface (`<room>.<face>`).
    pub surface: String,
    /// The identifier, in the model, of the space on the other side.
    pub space: String,
}

/// A loaded, validated and meshed scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The scene's name (`scene.name`).
    pub name: String,
    /// Spectral bands; every per-band vector has `bands.count()` entries.
    pub bands: Bands,
    /// Named surfaces, in file order (rooms, blocks, quads, then OBJ files); exterior ones are
    /// not among them but in [`Scene::obstructions`].
    pub surfaces: Vec<Surface>,
    /// Patches; `patch.surface` indexes [`Scene::surfaces`].
    pub patches: Vec<Patch>,
    /// The convex faces the patches were cut from, in patch order (used for occlusion).
    pub faces: Vec<Face>,
    /// Reflectance per patch and band, each in [0, 1).
    pub reflectance: Vec<Vec<f64>>,
    /// Exitance emitted per patch and band at level 1 of its channel (lux or W/m²); zero for
    /// patches that do not emit.
    pub emission: Vec<Vec<f64>>,
    /// The channel driving each patch's emission. Every emitting patch is in exactly one
    /// channel (an emitting surface outside every channel is an error).
    pub channel_of_patch: Vec<Option<usize>>,
    /// Channels, in file order.
    pub channels: Vec<Channel>,
    /// Luminaires with photometry, in file order (an array's elements row by row); their
    /// light is not patch emission (`sources::luminaires`).
    pub luminaires: Vec<Luminaire>,
    /// Sensors, in file order.
    pub sensors: Vec<Sensor>,
    /// Zones, in file order.
    pub zones: Vec<Zone>,
    /// The site, for daylight; `None` without `[site]`.
    pub site: Option<Site>,
    /// Glazed surfaces (those whose material has a transmittance), in surface order.
    pub windows: Vec<Window>,
    /// Surfaces outside the room that shade the windows (`exterior = true`), one per surface,
    /// in surface order (blocks, quads, then OBJ files).
    pub obstructions: Vec<Obstruction>,
    /// The rooms, their blocks and openings seen from above, for plans.
    pub layout: layout::Layout,
    /// The blocks inside the rooms as closed boxes of blockers, for occlusion
    /// ([`crate::formfactor::Occluders::with_solids`]), in file order.
    pub solids: Vec<crate::formfactor::Solid>,
    /// The faces of imported rooms shared with another space of their model.
    pub adjacency: Vec<Adjacency>,
    /// What the `[[import]]`s' models hold and could not be mapped (shades, air boundaries,
    /// unknown face types, sensor grids of rooms not imported), each naming its file:
    /// reported, not guessed.
    pub warnings: Vec<String>,
}

impl Scene {
    /// The area (m²) of the surface named `name`, summed over its patches; `None` when the
    /// scene has no surface of that name.
    pub fn surface_area(&self, name: &str) -> Option<f64> {
        let surface = self.surfaces.iter().find(|s| s.name == name)?;
        Some(
            self.patches[surface.patch_range.clone()]
                .iter()
                .map(|p| p.area)
                .sum(),
        )
    }
}

/// Reads, validates and meshes the scene file at `path`.
///
/// OBJ files it names are found relative to its folder.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|reason| SceneError::Read {
        path: path.to_path_buf(),
        reason,
    })?;
    parse(&text, path)
}

/// Validates and meshes a scene from its text; `origin` is the file it came from, used to find
/// OBJ files (relative to its folder) and to name the file in errors.
pub fn parse(text: &str, origin: &Path) -> Result<Scene, SceneError> {
    build::build(file::SceneFile::parse(text, origin)?, text, origin)
}
