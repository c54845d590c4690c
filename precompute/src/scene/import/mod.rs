//! `[[import]]`: rooms from the engineer's building model (Honeybee HBJSON, gbXML).
//!
//! A reader per format turns the file into a [`model::Model`] (spaces, faces, openings,
//! materials, in metres); each space asked for is then read as a prism ([`prism`]) and laid
//! out as a typed [`Room`], exactly as a `[[room]]` with that plan would be, its windows and
//! doors becoming openings cut out of its faces. Faces take their material from the scene
//! when the model names one the scene defines, else from the model's own values, else from the
//! import's `materials` map; a face without any is an error, never a guess. The model's sensor
//! grids ([`sensor_grids`]) become zones of the scene.

mod gbxml;
mod hbjson;
pub(crate) mod model;
pub(crate) mod prism;
mod sensor_grids;
#[cfg(test)]
mod tests;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use toml::Spanned;

use super::context::{Ctx, MaterialInfo, RawSurface};
use super::error::{Location, SceneError};
use super::file::{ImportDef, SurfaceOverride};
use super::room::{Ends, FaceKind, Room};
use super::Adjacency;
use crate::geometry::{Polygon, Vec3};
use model::{Model, ModelMaterial, ModelOpening};
pub(crate) use sensor_grids::ImportedGrid;

/// What went wrong in a model file: the element and, when known, its line.
#[derive(Debug)]
pub(crate) struct ImportError {
    /// The 1-based line of the file.
    pub line: Option<usize>,
    /// The element at fault, e.g. ``space `Office`, face `Office_South` ``.
    pub element: String,
    pub message: String,
}

/// The rooms of one `[[import]]`.
pub(crate) struct Imported {
    pub rooms: Vec<ImportedRoom>,
    /// The sensor grids it asks for ([`sensor_grids::chosen`]).
    pub grids: Vec<ImportedGrid>,
    /// What the file holds and the import could not map, each naming the file.
    pub warnings: Vec<String>,
}

/// A room read from a model, with its openings.
pub(crate) struct ImportedRoom {
    pub room: Room,
    /// Its windows and doors as surfaces facing into the room, named `<room>.<opening>`.
    pub openings: Vec<RawSurface>,
    /// Where the `[[import]]` was written, for messages about the openings.
    pub at: Location,
    /// Its faces shared with another space of the model.
    pub adjacency: Vec<Adjacency>,
}

/// The model file formats.
enum Format {
    Hbjson,
    Gbxml,
}

/// Reads the model an `[[import]]` names and lays out the spaces it asks for. Materials the
/// model defines and faces use are added to `materials` (unless the scene defines a material
/// of that name: the scene's is used); `surfaces` are the scene's `[surfaces]` tables, which
/// may give a face its material.
pub(crate) fn read(
    ctx: &Ctx,
    def: &Spanned<ImportDef>,
    surfaces: &BTreeMap<String, Spanned<SurfaceOverride>>,
    materials: &mut BTreeMap<String, MaterialInfo>,
) -> Result<Imported, SceneError> {
    let d = def.get_ref();
    let at = ctx.at(def);
    let path = model_path(ctx.origin, d.file.get_ref());
    let format = match path.extension().and_then(|e| e.to_str()) {
        Some("hbjson" | "json") => Format::Hbjson,
        Some("xml" | "gbxml") => Format::Gbxml,
        _ => {
            return Err(SceneError::Invalid {
                at: ctx.at(&d.file),
                field: "import.file".into(),
                message: format!(
                    "`{}`: the format is taken from the extension: .hbjson or .json (Honeybee), \
                     .xml or .gbxml (gbXML)",
                    d.file.get_ref()
                ),
            })
        }
    };
    let text = std::fs::read(&path).map_err(|reason| match reason.kind() {
        std::io::ErrorKind::NotFound => SceneError::MissingFile {
            at: ctx.at(&d.file),
            field: "import.file".into(),
            path: path.clone(),
        },
        _ => SceneError::Read {
            path: path.clone(),
            reason,
        },
    })?;
    let located = |e: ImportError| SceneError::Import {
        at: Location {
            file: path.clone(),
            line: e.line,
        },
        element: e.element,
        message: e.message,
    };
    let text = String::from_utf8(text).map_err(|e| {
        located(ImportError {
            line: None,
            element: "file".into(),
            message: format!("not UTF-8 text: {e}"),
        })
    })?;
    let model = match format {
        Format::Hbjson => hbjson::read(&text),
        Format::Gbxml => gbxml::read(&text),
    }
    .map_err(located)?;
    let chosen = chosen_spaces(ctx, d, &model, &path)?;
    let mut importer = Importer {
        ctx,
        def: d,
        path: &path,
        surfaces,
        materials,
        model: &model,
    };
    let mut rooms = Vec::with_capacity(chosen.len());
    for &space in &chosen {
        rooms.push(importer.room(space, &at).map_err(located)?);
    }
    let mut warnings: Vec<String> = model
        .warnings
        .iter()
        .map(|w| format!("{}: {w}", path.display()))
        .collect();
    let grids = sensor_grids::chosen(
        ctx,
        d.sensor_grids.as_ref(),
        &model,
        &chosen,
        &path,
        &mut warnings,
    )?;
    Ok(Imported {
        rooms,
        grids,
        warnings,
    })
}

/// The model file an `[[import]]` names, relative to the scene file's folder.
pub(crate) fn model_path(scene: &Path, file: &str) -> PathBuf {
    scene.parent().unwrap_or(Path::new("")).join(file)
}

/// The spaces `import.spaces` names (by identifier or display name), in that order; all of
/// them, in file order, without the list.
fn chosen_spaces<'m>(
    ctx: &Ctx,
    d: &ImportDef,
    model: &'m Model,
    path: &Path,
) -> Result<Vec<&'m model::Space>, SceneError> {
    let Some(list) = &d.spaces else {
        return Ok(model.spaces.iter().collect());
    };
    list.get_ref()
        .iter()
        .map(|name| {
            model
                .spaces
                .iter()
                .find(|s| &s.id == name || &s.name == name)
                .ok_or_else(|| {
                    let known: Vec<&str> = model.spaces.iter().map(|s| s.id.as_str()).collect();
                    SceneError::Invalid {
                        at: ctx.at(list),
                        field: "import.spaces".into(),
                        message: format!(
                            "unknown space `{name}` in {} (its spaces: {})",
                            path.display(),
                            known.join(", ")
                        ),
                    }
                })
        })
        .collect()
}

/// Lays out the spaces of one model.
struct Importer<'a> {
    ctx: &'a Ctx<'a>,
    def: &'a ImportDef,
    path: &'a Path,
    surfaces: &'a BTreeMap<String, Spanned<SurfaceOverride>>,
    materials: &'a mut BTreeMap<String, MaterialInfo>,
    model: &'a Model,
}

impl Importer<'_> {
    /// The room of `space`, its openings and its adjacency; `at` is the `[[import]]`.
    fn room(&mut self, space: &model::Space, at: &Location) -> Result<ImportedRoom, ImportError> {
        let tol = self.model.tolerance;
        let p = prism::prism(space, tol)?;
        let surface = |suffix: &str| format!("{}.{suffix}", space.name);
        let floor = self.material(
            &p.floor_face.id,
            p.floor_face.line,
            p.floor_face.kind.key(),
            p.floor_face.material.as_deref(),
            &surface("floor"),
        )?;
        let first = p.ceiling_faces[0];
        let ceiling = self.material(
            &first.id,
            first.line,
            first.kind.key(),
            first.material.as_deref(),
            &surface("ceiling"),
        )?;
        if let Some(other) = p
            .ceiling_faces
            .iter()
            .find(|c| c.material != first.material)
        {
            return Err(ImportError {
                line: other.line,
                element: format!("space `{}`, face `{}`", space.id, other.id),
                message: format!(
                    "its material differs from that of ceiling face `{}`: one material per \
                     ceiling is supported yet",
                    first.id
                ),
            });
        }
        let mut walls = Vec::with_capacity(p.walls.len());
        for (k, w) in p.walls.iter().enumerate() {
            let Some(w) = w else {
                // No wall where the roof meets the floor: the room has no face there either.
                walls.push((
                    format!("wall_{}", k + 1),
                    ceiling.0.clone(),
                    ceiling.1.clone(),
                ));
                continue;
            };
            let (material, material_at) = self.material(
                &w.id,
                w.line,
                w.kind.key(),
                w.material.as_deref(),
                &surface(&w.name),
            )?;
            walls.push((w.name.clone(), material, material_at));
        }
        let ends = Ends { floor, ceiling };
        let room = if p.roof.is_empty() {
            Room::from_plan(
                space.name.clone(),
                self.location(space.line),
                p.plan.clone(),
                (p.floor, p.ceiling),
                &ends,
                |edge| walls[edge].clone(),
            )
        } else {
            Room::from_sloped_plan(
                space.name.clone(),
                self.location(space.line),
                p.plan.clone(),
                p.floor,
                p.roof.clone(),
                &ends,
                |edge| walls[edge].clone(),
            )
            .map_err(|message| ImportError {
                line: space.line,
                element: format!("space `{}`", space.id),
                message,
            })?
        };

        // Each host face of the model and the room face it became.
        let mut hosts: Vec<(&model::ModelFace, &super::room::RoomFace)> = Vec::new();
        for f in &room.faces {
            match f.kind {
                FaceKind::Floor => hosts.push((p.floor_face, f)),
                FaceKind::Ceiling => hosts.extend(p.ceiling_faces.iter().map(|&c| (c, f))),
                FaceKind::CeilingPlane { index } => hosts.extend(
                    (p.ceiling_faces.iter().zip(&p.plane_of))
                        .filter(|&(_, &k)| k == index)
                        .map(|(&c, _)| (c, f)),
                ),
                FaceKind::Wall { edge } => hosts.extend(p.walls[edge].map(|w| (w, f))),
            }
        }
        let mut openings = Vec::new();
        let mut adjacency = Vec::new();
        for (host, face) in hosts {
            if let Some(other) = &host.adjacent {
                let name = surface(&face.suffix);
                if !adjacency.iter().any(|a: &Adjacency| a.surface == name) {
                    adjacency.push(Adjacency {
                        surface: name,
                        space: other.clone(),
                    });
                }
            }
            for o in &host.openings {
                openings.push(self.opening(space, &room, face, o)?);
            }
        }
        Ok(ImportedRoom {
            room,
            openings,
            at: at.clone(),
            adjacency,
        })
    }

    /// The opening `o` of room face `face` as a surface: set into the face's plane (within the
    /// model's tolerance) and wound to face into the room.
    fn opening(
        &mut self,
        space: &model::Space,
        room: &Room,
        face: &super::room::RoomFace,
        o: &ModelOpening,
    ) -> Result<RawSurface, ImportError> {
        let tol = self.model.tolerance;
        let error = |message: String| ImportError {
            line: o.line,
            element: format!("space `{}`, opening `{}`", space.id, o.id),
            message,
        };
        let off = prism::off_plane(&o.polygon);
        if off > tol {
            return Err(error(format!(
                "the polygon is not planar: a corner lies {off:.3e} m off its plane"
            )));
        }
        let inward = room.inward(face);
        let origin = face.outline[0];
        let distance = o
            .polygon
            .iter()
            .map(|&c| (c - origin).dot(inward).abs())
            .fold(0.0, f64::max);
        if distance > tol {
            return Err(error(format!(
                "it does not lie in its face `{}.{}`: a corner is {distance:.3e} m from the \
                 face's plane (tolerance {tol:.1e} m)",
                room.name, face.suffix
            )));
        }
        // Set exactly into the face's plane, so that the opening cuts it.
        let mut corners: Vec<Vec3> = o
            .polygon
            .iter()
            .map(|&c| c - inward * (c - origin).dot(inward))
            .collect();
        if Polygon::new(corners.clone()).normal().dot(inward) < 0.0 {
            corners.reverse();
        }
        let first = first_corner(&corners, room, face, tol);
        corners.rotate_left(first);
        let name = format!("{}.{}", space.name, o.name);
        let (material, material_at) =
            self.material(&o.id, o.line, o.kind.key(), o.material.as_deref(), &name)?;
        Ok(RawSurface {
            name,
            material,
            material_at,
            faces: vec![corners],
            max_edge: None,
            at: self.location(o.line),
            exterior: false,
        })
    }

    /// A location in the model file.
    fn location(&self, line: Option<usize>) -> Location {
        Location {
            file: self.path.to_path_buf(),
            line,
        }
    }

    /// The material of the element `id` (at `line`) whose model material is `named`, its kind
    /// `key` and its surface `surface`: the import's `materials` entry for that name, the
    /// scene's material of that name, the model's, the import's entry for its kind, the
    /// scene's `[surfaces]` table for it; an error else.
    fn material(
        &mut self,
        id: &str,
        line: Option<usize>,
        key: &str,
        named: Option<&str>,
        surface: &str,
    ) -> Result<(String, Location), ImportError> {
        let here = self.location(line);
        let mapped = |k: &str| {
            self.def
                .materials
                .get(k)
                .map(|m| (m.get_ref().clone(), self.ctx.at(m)))
        };
        if let Some(name) = named {
            if let Some(m) = mapped(name) {
                return Ok(m);
            }
            if self.materials.contains_key(name) {
                return Ok((name.to_owned(), here));
            }
            if let Some(m) = self.model.materials.get(name) {
                let info = self.info(name, m, line)?;
                self.materials.insert(name.to_owned(), info);
                return Ok((name.to_owned(), here));
            }
        }
        if let Some(m) = mapped(key) {
            return Ok(m);
        }
        if let Some(m) = self
            .surfaces
            .get(surface)
            .and_then(|s| s.get_ref().material.as_ref())
        {
            return Ok((m.get_ref().clone(), self.ctx.at(m)));
        }
        let why = match named {
            Some(name) => format!("its material `{name}` gives no reflectance"),
            None => "the model gives it no material".into(),
        };
        Err(ImportError {
            line,
            element: format!("`{id}` (surface `{surface}`)"),
            message: format!(
                "{why}; map it to a scene material in the import's `materials` (e.g. \
                 materials = {{ {} = \"wall\" }}) or in [surfaces.\"{surface}\"]",
                named.map_or(key.to_owned(), |n| format!("\"{n}\""))
            ),
        })
    }

    /// The scene material of the model's material `name`.
    fn info(
        &self,
        name: &str,
        m: &ModelMaterial,
        line: Option<usize>,
    ) -> Result<MaterialInfo, ImportError> {
        let error = |message: String| ImportError {
            line,
            element: format!("material `{name}`"),
            message,
        };
        let ctx = self.ctx;
        let field = format!("material `{name}`.reflectance");
        let reflectance = ctx
            .check_reflectance(per_band(ctx, m.reflectance), &self.location(line), &field)
            .map_err(|e| error(e.to_string()))?;
        let glazing = match m.transmittance {
            None => None,
            Some(_) if ctx.bands != 1 => {
                return Err(error(
                    "glazing is not available in rgb scenes yet: daylight is computed in the \
                     photopic band only; use `bands = \"photopic\"`"
                        .into(),
                ))
            }
            Some(t) => {
                let tau = per_band(&Ctx { bands: 1, ..*ctx }, t)[0];
                if reflectance[0] + tau > 1.0 {
                    return Err(error(format!(
                        "reflectance {} plus transmittance {tau} exceeds 1",
                        reflectance[0]
                    )));
                }
                let panes = match m.panes {
                    None => super::daylight::PANES,
                    Some(n) => u8::try_from(n)
                        .ok()
                        .filter(|n| (1..=eigenrad_runtime::sky::glazing::MAX_PANES).contains(n))
                        .ok_or_else(|| error(format!("{n} panes: glazing has 1 to 3")))?,
                };
                let clear = eigenrad_runtime::sky::glazing::Glazing::clear(tau as f32, panes)
                    .map_err(|e| error(format!("transmittance {tau}: {e}")))?;
                Some(clear)
            }
        };
        Ok(MaterialInfo {
            reflectance,
            emission: vec![0.0; ctx.bands],
            glazing,
        })
    }
}

/// One value per band of a red, green and blue triple: the value itself when the three are
/// equal (a grey the file gives as one number stays that number), else
/// [`Ctx::bands_of_rgb`].
fn per_band(ctx: &Ctx, rgb: [f64; 3]) -> Vec<f64> {
    if rgb.iter().all(|&x| x == rgb[0]) {
        vec![rgb[0]; ctx.bands]
    } else {
        ctx.bands_of_rgb(rgb)
    }
}

/// Where an opening's corners (wound into the room) start, so that the same opening meshes
/// into the same patches however the file lists it: in a wall, the lowest corner nearest the
/// wall's start (the wall's own order: up its first side, then along); in a floor or a
/// ceiling, the south-west-most corner, as a plan. Coordinates within `tol` (m) count as
/// equal.
fn first_corner(corners: &[Vec3], room: &Room, face: &super::room::RoomFace, tol: f64) -> usize {
    let key = |p: &Vec3| match face.kind {
        FaceKind::Wall { edge } => {
            let (a, b) = room.plan.edge(edge);
            (
                p.z,
                (p.x - a[0]) * (b[0] - a[0]) + (p.y - a[1]) * (b[1] - a[1]),
            )
        }
        _ => (p.y, p.x),
    };
    let keys: Vec<(f64, f64)> = corners.iter().map(key).collect();
    let low = keys.iter().map(|k| k.0).fold(f64::INFINITY, f64::min);
    (0..keys.len())
        .filter(|&k| keys[k].0 <= low + tol)
        .min_by(|&i, &j| keys[i].1.total_cmp(&keys[j].1))
        .unwrap_or(0)
}
