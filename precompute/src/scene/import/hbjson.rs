//! Honeybee's HBJSON (a `Model` of honeybee-schema, <https://github.com/ladybug-tools/honeybee-schema>):
//! rooms, their faces with apertures and doors, and the Radiance modifiers that give them
//! reflectance and transmittance.
//!
//! What is read: `units`, `tolerance`, `rooms[].faces[]` (`geometry.boundary`, `face_type`,
//! `boundary_condition`, `apertures[]`, `doors[]`, `properties.radiance.modifier`), the
//! rooms' `modifier_set`s, and `properties.radiance.modifiers` of type `Plastic`, `Metal` and
//! `Glass`, and `properties.radiance.sensor_grids` ([`super::sensor_grids`]). Shades, air
//! boundaries, orphaned objects, holes in faces, other modifier types and views are listed as
//! warnings.

use std::collections::{BTreeMap, HashMap};

use serde::Deserialize;
use serde_json::Value;

use super::model::{
    unit_metres, Model, ModelFace, ModelFaceKind, ModelMaterial, ModelOpening, OpeningKind, Space,
};
use super::ImportError;
use crate::geometry::Vec3;

/// honeybee-schema's default `Model.tolerance`, in the model's units.
const DEFAULT_TOLERANCE: f64 = 0.01;

/// Radiance's default refractive index of `glass` (Radiance reference manual, "Glass").
const GLASS_INDEX: f64 = 1.52;

#[derive(Deserialize)]
struct HbModel {
    #[serde(rename = "type")]
    kind: String,
    #[serde(default)]
    units: Option<String>,
    #[serde(default)]
    tolerance: Option<f64>,
    #[serde(default)]
    rooms: Vec<HbRoom>,
    #[serde(default)]
    properties: Option<HbModelProperties>,
    #[serde(default)]
    orphaned_faces: Vec<Value>,
    #[serde(default)]
    orphaned_apertures: Vec<Value>,
    #[serde(default)]
    orphaned_doors: Vec<Value>,
    #[serde(default)]
    orphaned_shades: Vec<Value>,
    #[serde(default)]
    shade_meshes: Vec<Value>,
}

#[derive(Deserialize, Default)]
struct HbModelProperties {
    #[serde(default)]
    radiance: Option<HbModelRadiance>,
}

#[derive(Deserialize, Default)]
struct HbModelRadiance {
    #[serde(default)]
    modifiers: Vec<Value>,
    #[serde(default)]
    modifier_sets: Vec<Value>,
    #[serde(default)]
    sensor_grids: Vec<Value>,
    #[serde(default)]
    views: Vec<Value>,
}

#[derive(Deserialize)]
struct HbRoom {
    identifier: String,
    #[serde(default)]
    display_name: Option<String>,
    faces: Vec<HbFace>,
    #[serde(default)]
    outdoor_shades: Vec<Value>,
    #[serde(default)]
    indoor_shades: Vec<Value>,
    #[serde(default)]
    properties: Option<HbObjectProperties>,
}

#[derive(Deserialize)]
struct HbFace {
    identifier: String,
    #[serde(default)]
    display_name: Option<String>,
    geometry: HbFace3D,
    face_type: String,
    #[serde(default)]
    boundary_condition: Option<HbBoundary>,
    #[serde(default)]
    apertures: Vec<HbSubFace>,
    #[serde(default)]
    doors: Vec<HbSubFace>,
    #[serde(default)]
    properties: Option<HbObjectProperties>,
}

#[derive(Deserialize)]
struct HbSubFace {
    identifier: String,
    #[serde(default)]
    display_name: Option<String>,
    geometry: HbFace3D,
    #[serde(default)]
    is_operable: bool,
    #[serde(default)]
    is_glass: bool,
    #[serde(default)]
    boundary_condition: Option<HbBoundary>,
    #[serde(default)]
    properties: Option<HbObjectProperties>,
}

#[derive(Deserialize)]
struct HbFace3D {
    boundary: Vec<Vec<f64>>,
    #[serde(default)]
    holes: Option<Vec<Value>>,
}

#[derive(Deserialize)]
struct HbBoundary {
    #[serde(rename = "type")]
    kind: String,
    /// For `Surface`: the adjacent face (or sub-face), then its parents up to the room.
    #[serde(default)]
    boundary_condition_objects: Vec<String>,
}

#[derive(Deserialize, Default)]
struct HbObjectProperties {
    #[serde(default)]
    radiance: Option<HbObjectRadiance>,
}

#[derive(Deserialize, Default)]
struct HbObjectRadiance {
    #[serde(default)]
    modifier: Option<String>,
    #[serde(default)]
    modifier_set: Option<String>,
}

impl HbObjectProperties {
    fn modifier(props: &Option<Self>) -> Option<String> {
        props.as_ref()?.radiance.as_ref()?.modifier.clone()
    }
}

/// Reads an HBJSON model from its text.
pub(crate) fn read(text: &str) -> Result<Model, ImportError> {
    let model: HbModel = serde_json::from_str(text).map_err(|e| ImportError {
        line: Some(e.line()),
        element: "Model".into(),
        message: format!("not a Honeybee model: {e}"),
    })?;
    if model.kind != "Model" {
        return Err(ImportError {
            line: Some(1),
            element: "Model".into(),
            message: format!(
                "the top-level object is of type `{}`; an HBJSON file holds a `Model`",
                model.kind
            ),
        });
    }
    let lines = identifier_lines(text);
    let line = |id: &str| lines.get(id).copied();
    let unit_name = model.units.as_deref().unwrap_or("Meters");
    let Some(unit) = unit_metres(unit_name) else {
        return Err(ImportError {
            line: Some(1),
            element: "Model.units".into(),
            message: format!(
                "units `{unit_name}` are not understood (Meters, Millimeters, Centimeters, \
                 Feet or Inches)"
            ),
        });
    };
    let tolerance = model.tolerance.unwrap_or(DEFAULT_TOLERANCE);
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(ImportError {
            line: Some(1),
            element: "Model.tolerance".into(),
            message: format!("must be a positive length, found {tolerance}"),
        });
    }
    let mut warnings = Vec::new();
    let radiance = model
        .properties
        .and_then(|p| p.radiance)
        .unwrap_or_default();
    let materials = modifiers(&radiance.modifiers, &mut warnings);
    let sets = modifier_sets(&radiance.modifier_sets);
    let grids = super::sensor_grids::read(&radiance.sensor_grids, unit, &line)?;
    for v in &radiance.views {
        let id = v.get("identifier").and_then(Value::as_str).unwrap_or("?");
        warnings.push(format!(
            "view `{id}` is not imported (a camera for pictures: eigenrad reads no views)"
        ));
    }
    for (what, list) in [
        ("orphaned face", &model.orphaned_faces),
        ("orphaned aperture", &model.orphaned_apertures),
        ("orphaned door", &model.orphaned_doors),
        ("orphaned shade", &model.orphaned_shades),
        ("shade mesh", &model.shade_meshes),
    ] {
        for v in list {
            let id = v.get("identifier").and_then(Value::as_str).unwrap_or("?");
            warnings.push(format!("{what} `{id}` belongs to no room: not imported"));
        }
    }
    let point = |element: &str, at: Option<usize>, c: &[f64]| -> Result<Vec3, ImportError> {
        match c {
            [x, y, z] if [x, y, z].iter().all(|v| v.is_finite()) => {
                Ok(Vec3::new(*x, *y, *z) * unit)
            }
            _ => Err(ImportError {
                line: at,
                element: element.into(),
                message: format!("a corner must be three finite numbers [x, y, z], found {c:?}"),
            }),
        }
    };
    let polygon = |element: &str, at: Option<usize>, g: &HbFace3D| {
        if g.holes.as_ref().is_some_and(|h| !h.is_empty()) {
            return Err(ImportError {
                line: at,
                element: element.into(),
                message: "faces with holes are not supported yet".into(),
            });
        }
        if g.boundary.len() < 3 {
            return Err(ImportError {
                line: at,
                element: element.into(),
                message: format!(
                    "missing geometry: its boundary has {} corners, at least 3 are needed",
                    g.boundary.len()
                ),
            });
        }
        g.boundary.iter().map(|c| point(element, at, c)).collect()
    };

    let mut spaces = Vec::with_capacity(model.rooms.len());
    for room in &model.rooms {
        let set = room
            .properties
            .as_ref()
            .and_then(|p| p.radiance.as_ref())
            .and_then(|r| r.modifier_set.as_ref())
            .and_then(|s| sets.get(s.as_str()));
        for shade in room.outdoor_shades.iter().chain(&room.indoor_shades) {
            let id = shade
                .get("identifier")
                .and_then(Value::as_str)
                .unwrap_or("?");
            warnings.push(format!(
                "room `{}`: shade `{id}` is not imported (shading devices are not mapped)",
                room.identifier
            ));
        }
        let mut faces = Vec::with_capacity(room.faces.len());
        for f in &room.faces {
            let kind = match f.face_type.as_str() {
                "Wall" => ModelFaceKind::Wall,
                "Floor" => ModelFaceKind::Floor,
                "RoofCeiling" => ModelFaceKind::Ceiling,
                other => {
                    warnings.push(format!(
                        "room `{}`: face `{}` of type `{other}` is not imported",
                        room.identifier, f.identifier
                    ));
                    continue;
                }
            };
            let at = line(&f.identifier);
            let element = format!("face `{}`", f.identifier);
            let bc = f.boundary_condition.as_ref();
            let interior = bc.is_some_and(|b| b.kind == "Surface");
            let adjacent = bc
                .filter(|b| b.kind == "Surface")
                .and_then(|b| b.boundary_condition_objects.last().cloned());
            let set_modifier = |group: &str, which: &str| {
                set.and_then(|s| s.get(group)?.get(which)?.as_str().map(str::to_owned))
            };
            let face_set = |group: &str| {
                set_modifier(
                    group,
                    if interior {
                        "interior_modifier"
                    } else {
                        "exterior_modifier"
                    },
                )
            };
            let group = match kind {
                ModelFaceKind::Wall => "wall_set",
                ModelFaceKind::Floor => "floor_set",
                ModelFaceKind::Ceiling => "roof_ceiling_set",
            };
            let mut openings = Vec::new();
            for (a, is_door) in f
                .apertures
                .iter()
                .map(|a| (a, false))
                .chain(f.doors.iter().map(|d| (d, true)))
            {
                let a_at = line(&a.identifier);
                let a_element = format!(
                    "{} `{}`",
                    ["aperture", "door"][is_door as usize],
                    a.identifier
                );
                let a_interior = a
                    .boundary_condition
                    .as_ref()
                    .is_some_and(|b| b.kind == "Surface");
                let from_set = if is_door {
                    let which = match (a.is_glass, a_interior) {
                        (true, true) => "interior_glass_modifier",
                        (true, false) => "exterior_glass_modifier",
                        (false, true) => "interior_modifier",
                        (false, false) => "exterior_modifier",
                    };
                    set_modifier("door_set", which)
                } else {
                    let which = if a_interior {
                        "interior_modifier"
                    } else if kind == ModelFaceKind::Ceiling {
                        "skylight_modifier"
                    } else if a.is_operable {
                        "operable_modifier"
                    } else {
                        "window_modifier"
                    };
                    set_modifier("aperture_set", which)
                };
                openings.push(ModelOpening {
                    id: a.identifier.clone(),
                    name: a
                        .display_name
                        .clone()
                        .unwrap_or_else(|| a.identifier.clone()),
                    line: a_at,
                    kind: if is_door {
                        OpeningKind::Door
                    } else {
                        OpeningKind::Window
                    },
                    polygon: polygon(&a_element, a_at, &a.geometry)?,
                    material: HbObjectProperties::modifier(&a.properties).or(from_set),
                });
            }
            faces.push(ModelFace {
                id: f.identifier.clone(),
                name: f
                    .display_name
                    .clone()
                    .unwrap_or_else(|| f.identifier.clone()),
                line: at,
                kind,
                polygon: polygon(&element, at, &f.geometry)?,
                material: HbObjectProperties::modifier(&f.properties).or_else(|| face_set(group)),
                adjacent,
                openings,
            });
        }
        spaces.push(Space {
            id: room.identifier.clone(),
            name: room
                .display_name
                .clone()
                .unwrap_or_else(|| room.identifier.clone()),
            line: line(&room.identifier),
            faces,
        });
    }
    Ok(Model {
        spaces,
        materials,
        tolerance: tolerance * unit,
        grids,
        warnings,
    })
}

/// The modifiers that give a diffuse reflectance (`Plastic`, `Metal`) or glazing (`Glass`),
/// by identifier; the others are listed in `warnings`.
fn modifiers(list: &[Value], warnings: &mut Vec<String>) -> BTreeMap<String, ModelMaterial> {
    let mut out = BTreeMap::new();
    for m in list {
        let id = m.get("identifier").and_then(Value::as_str).unwrap_or("?");
        let kind = m.get("type").and_then(Value::as_str).unwrap_or("?");
        let rgb = |prefix: &str| -> Option<[f64; 3]> {
            let c = |band: &str| m.get(format!("{band}_{prefix}"))?.as_f64();
            Some([c("r")?, c("g")?, c("b")?])
        };
        let number = |key: &str| m.get(key).and_then(Value::as_f64);
        let material = match kind {
            // Radiance plastic: a diffuse part of the colour and an uncoloured specular part;
            // their sum is what a diffuse model can carry.
            "Plastic" => rgb("reflectance").map(|c| {
                let s = number("specularity").unwrap_or(0.0);
                ModelMaterial {
                    reflectance: c.map(|x| x * (1.0 - s) + s),
                    transmittance: None,
                    panes: None,
                }
            }),
            // Radiance metal: its specular part takes the colour too.
            "Metal" => rgb("reflectance").map(|c| ModelMaterial {
                reflectance: c,
                transmittance: None,
                panes: None,
            }),
            "Glass" => rgb("transmissivity").map(|tn| {
                let n = number("refraction_index").unwrap_or(GLASS_INDEX);
                glass(tn, n)
            }),
            _ => {
                warnings.push(format!(
                    "modifier `{id}` of type `{kind}` is not mapped: faces using it need a \
                     material from the scene"
                ));
                continue;
            }
        };
        match material {
            Some(material) => {
                out.insert(id.to_owned(), material);
            }
            None => warnings.push(format!(
                "modifier `{id}` of type `{kind}` lacks its red, green and blue values: not mapped"
            )),
        }
    }
    out
}

/// The reflectance and transmittance at normal incidence of Radiance `glass` of
/// transmissivity `tn` (per band) and refractive index `n`: one pane, reflecting
/// `r = ((n − 1)/(n + 1))²` at each side, light passing back and forth inside it
/// (Radiance reference manual, "Glass": T = tn (1 − r)² / (1 − r² tn²),
/// R = r + r (1 − r)² tn² / (1 − r² tn²)). For n = 1.52, tn = 0.96 gives T = 0.88.
fn glass(tn: [f64; 3], n: f64) -> ModelMaterial {
    let r = ((n - 1.0) / (n + 1.0)).powi(2);
    let denominator = tn.map(|t| 1.0 - r * r * t * t);
    let mut reflectance = [0.0; 3];
    let mut transmittance = [0.0; 3];
    for k in 0..3 {
        transmittance[k] = tn[k] * (1.0 - r).powi(2) / denominator[k];
        reflectance[k] = r + r * (1.0 - r).powi(2) * tn[k] * tn[k] / denominator[k];
    }
    ModelMaterial {
        reflectance,
        transmittance: Some(transmittance),
        panes: Some(1),
    }
}

/// The model's modifier sets by identifier, as JSON (`wall_set.interior_modifier`, ...).
fn modifier_sets(list: &[Value]) -> HashMap<&str, &Value> {
    list.iter()
        .filter_map(|s| Some((s.get("identifier")?.as_str()?, s)))
        .collect()
}

/// The 1-based line of every `"identifier": "..."` in the text: identifiers are unique in a
/// Honeybee model, so this finds where each object is defined.
fn identifier_lines(text: &str) -> HashMap<String, usize> {
    const KEY: &str = "\"identifier\"";
    let mut out = HashMap::new();
    let mut line = 1;
    let mut counted = 0;
    for (at, _) in text.match_indices(KEY) {
        line += text[counted..at].bytes().filter(|&b| b == b'\n').count();
        counted = at;
        let rest = text[at + KEY.len()..].trim_start();
        let Some(rest) = rest.strip_prefix(':') else {
            continue;
        };
        let mut value = serde_json::Deserializer::from_str(rest.trim_start()).into_iter::<String>();
        if let Some(Ok(id)) = value.next() {
            out.entry(id).or_insert(line);
        }
    }
    out
}
