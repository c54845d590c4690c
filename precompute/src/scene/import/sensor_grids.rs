//! Honeybee sensor grids (`properties.radiance.sensor_grids`, honeybee-radiance's
//! `SensorGrid`): each a list of sensors, a position and the direction its plane faces, read
//! into [`ModelGrid`]s; then the grids an `[[import]]` asks for (`sensor_grids`), each tied to
//! the room of its `room_identifier`.
//!
//! A grid's `mesh` and `base_geometry` only say where its sensors came from (each sensor a
//! mesh face's centre): the sensors themselves are what is read.

use serde::Deserialize;
use serde_json::Value;
use toml::Spanned;

use super::model::{Model, ModelGrid, Space};
use super::ImportError;
use crate::geometry::Vec3;
use crate::scene::context::Ctx;
use crate::scene::error::{Location, SceneError};
use crate::scene::file::SensorGridsDef;

#[derive(Deserialize)]
struct HbSensorGrid {
    identifier: String,
    #[serde(default)]
    display_name: Option<String>,
    sensors: Vec<HbSensor>,
    #[serde(default)]
    room_identifier: Option<String>,
}

#[derive(Deserialize)]
struct HbSensor {
    pos: Vec<f64>,
    dir: Vec<f64>,
}

/// Reads the model's sensor grids (`list`, as JSON) in metres (`unit`: metres per model
/// unit); `line` finds an identifier's line. A grid without sensors, a position or direction
/// that is not three finite numbers, or a zero direction is an error naming the grid and the
/// sensor (0-based, in file order).
pub(super) fn read(
    list: &[Value],
    unit: f64,
    line: &dyn Fn(&str) -> Option<usize>,
) -> Result<Vec<ModelGrid>, ImportError> {
    let mut grids = Vec::with_capacity(list.len());
    for (k, value) in list.iter().enumerate() {
        let id = value.get("identifier").and_then(Value::as_str);
        let at = id.and_then(line);
        let element = match id {
            Some(id) => format!("sensor grid `{id}`"),
            None => format!("sensor grid {k}"),
        };
        let g = HbSensorGrid::deserialize(value).map_err(|e| ImportError {
            line: at,
            element: element.clone(),
            message: format!("not a Honeybee sensor grid: {e}"),
        })?;
        if g.sensors.is_empty() {
            return Err(ImportError {
                line: at,
                element,
                message: "has no sensors".into(),
            });
        }
        let mut sensors = Vec::with_capacity(g.sensors.len());
        for (i, s) in g.sensors.iter().enumerate() {
            let error = |message: String| ImportError {
                line: at,
                element: format!("{element}, sensor {i}"),
                message,
            };
            let vector = |name: &str, c: &[f64]| match c {
                [x, y, z] if [x, y, z].iter().all(|v| v.is_finite()) => Ok(Vec3::new(*x, *y, *z)),
                _ => Err(error(format!(
                    "`{name}` must be three finite numbers [x, y, z], found {c:?}"
                ))),
            };
            let position = vector("pos", &s.pos)? * unit;
            let direction = vector("dir", &s.dir)?;
            let length = direction.length();
            if !(length.is_finite() && length > 0.0) {
                return Err(error(format!(
                    "`dir` must be a finite, non-zero vector, found {:?}",
                    s.dir
                )));
            }
            sensors.push((position, direction.normalized()));
        }
        grids.push(ModelGrid {
            name: g.display_name.unwrap_or_else(|| g.identifier.clone()),
            id: g.identifier,
            line: at,
            space: g.room_identifier,
            sensors,
        });
    }
    Ok(grids)
}

/// A sensor grid an `[[import]]` brings into the scene.
pub(crate) struct ImportedGrid {
    /// Its zone name (the grid's display name, else its identifier).
    pub name: String,
    /// Its identifier in the model.
    pub id: String,
    /// The scene name of the room it lies in, when the model says.
    pub room: Option<String>,
    /// Its sensors: position (m) and unit direction, in file order.
    pub sensors: Vec<(Vec3, Vec3)>,
    /// Where the model defines it.
    pub at: Location,
}

/// The grids `[[import]].sensor_grids` asks for (`def`, at `field`): all of them (the
/// default, or `true`), none (`false`), or those named by identifier or display name, in
/// that order. `spaces` are the spaces imported; `path` is the model file. A named grid that
/// is not in the model, a grid whose `room_identifier` is no space of the model, and a named
/// grid whose space is not imported are errors; a grid the default takes whose space is not
/// imported is left out with a warning.
pub(super) fn chosen(
    ctx: &Ctx,
    def: Option<&Spanned<SensorGridsDef>>,
    model: &Model,
    spaces: &[&Space],
    path: &std::path::Path,
    warnings: &mut Vec<String>,
) -> Result<Vec<ImportedGrid>, SceneError> {
    let (list, named): (Vec<&ModelGrid>, bool) = match def.map(Spanned::get_ref) {
        None | Some(SensorGridsDef::All(true)) => (model.grids.iter().collect(), false),
        Some(SensorGridsDef::All(false)) => return Ok(Vec::new()),
        Some(SensorGridsDef::Names(names)) => {
            let mut list = Vec::with_capacity(names.len());
            for name in names {
                let Some(g) = model
                    .grids
                    .iter()
                    .find(|g| &g.id == name || &g.name == name)
                else {
                    let known: Vec<&str> = model.grids.iter().map(|g| g.id.as_str()).collect();
                    return Err(SceneError::Invalid {
                        at: def.map_or_else(|| Location::file(ctx.origin), |d| ctx.at(d)),
                        field: "import.sensor_grids".into(),
                        message: format!(
                            "unknown sensor grid `{name}` in {} (its sensor grids: {})",
                            path.display(),
                            if known.is_empty() {
                                "none".into()
                            } else {
                                known.join(", ")
                            }
                        ),
                    });
                };
                list.push(g);
            }
            (list, true)
        }
    };
    let mut out = Vec::with_capacity(list.len());
    for g in list {
        let at = Location {
            file: path.to_path_buf(),
            line: g.line,
        };
        let room = match &g.space {
            None => None,
            Some(id) => {
                if !model.spaces.iter().any(|s| &s.id == id) {
                    return Err(SceneError::Import {
                        at,
                        element: format!("sensor grid `{}`", g.id),
                        message: format!(
                            "its room_identifier `{id}` is no room of the model (its rooms: {})",
                            model
                                .spaces
                                .iter()
                                .map(|s| s.id.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    });
                }
                match spaces.iter().find(|s| &s.id == id) {
                    Some(s) => Some(s.name.clone()),
                    None if named => {
                        return Err(SceneError::Import {
                            at,
                            element: format!("sensor grid `{}`", g.id),
                            message: format!(
                                "it lies in room `{id}`, which the import's `spaces` leaves \
                                 out: import that room too, or leave the grid out of \
                                 `sensor_grids`"
                            ),
                        })
                    }
                    None => {
                        warnings.push(format!(
                            "{}: sensor grid `{}` lies in room `{id}`, which is not imported: \
                             the grid is left out",
                            path.display(),
                            g.id
                        ));
                        continue;
                    }
                }
            }
        };
        out.push(ImportedGrid {
            name: g.name.clone(),
            id: g.id.clone(),
            room,
            sensors: g.sensors.clone(),
            at,
        });
    }
    Ok(out)
}
