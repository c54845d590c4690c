//! From the parsed file to a validated, meshed [`Scene`]: units, materials, surfaces, meshing,
//! channels, sensors and zones.

use std::collections::{BTreeMap, HashSet};
use std::path::Path;

use toml::Spanned;

use super::error::{Location, SceneError};
use super::file::{BandsDef, PerBand, SceneFile, WorkPlaneDef};
use super::mesh::{check_face, mesh_face, triangulate};
use super::obj::{self, LUMINANCE};
use super::primitives;
use super::{Bands, Channel, Scene, Sensor, Surface, Zone, ZoneKind};
use crate::geometry::{Patch, Polygon, Vec3};

/// Default planarity tolerance: a corner may sit 0.1 % of the face's diagonal off its plane.
const PLANARITY: f64 = 1e-3;

/// Parsing context: where the text came from, its bands and its length unit.
pub(crate) struct Ctx<'a> {
    /// The scene file (for messages and relative paths).
    pub origin: &'a Path,
    text: &'a str,
    bands: usize,
    /// Metres per unit of length in the file.
    pub unit: f64,
}

/// A material's values in SI units.
#[derive(Clone, Debug)]
pub(crate) struct MaterialInfo {
    /// Per band, in [0, 1).
    pub reflectance: Vec<f64>,
    /// Exitance at level 1 per band (lux or W/m²).
    pub emission: Vec<f64>,
}

/// A surface before meshing: faces in metres, material by name.
#[derive(Clone, Debug)]
pub(crate) struct RawSurface {
    pub name: String,
    pub material: String,
    /// Where the material was named (for unknown-material errors).
    pub material_at: Location,
    /// Polygons, metres, counter-clockwise seen from the front.
    pub faces: Vec<Vec<Vec3>>,
    /// Longest patch edge, metres (`None`: the scene default).
    pub max_edge: Option<f64>,
    /// Where the surface was defined.
    pub at: Location,
}

impl Ctx<'_> {
    /// The location of a spanned value.
    pub fn at<T>(&self, s: &Spanned<T>) -> Location {
        Location::at_offset(self.origin, self.text, s.span().start)
    }

    /// A point or vector from the file, checked finite and converted to metres.
    pub fn point(&self, p: &Spanned<[f64; 3]>, field: &str) -> Result<Vec3, SceneError> {
        self.coordinates(*p.get_ref(), p, field)
    }

    /// Coordinates checked finite and converted to metres; `span` locates errors.
    pub fn coordinates<T>(
        &self,
        c: [f64; 3],
        span: &Spanned<T>,
        field: &str,
    ) -> Result<Vec3, SceneError> {
        if c.iter().any(|v| !v.is_finite()) {
            return Err(SceneError::OutOfRange {
                at: self.at(span),
                field: field.into(),
                message: format!("coordinates must be finite, found {c:?}"),
            });
        }
        Ok(Vec3::new(c[0], c[1], c[2]) * self.unit)
    }

    /// A positive finite length from the file, in metres.
    pub fn length(&self, l: &Spanned<f64>, field: &str) -> Result<f64, SceneError> {
        let v = *l.get_ref();
        if !(v.is_finite() && v > 0.0) {
            return Err(SceneError::OutOfRange {
                at: self.at(l),
                field: field.into(),
                message: format!("must be a positive finite length, found {v}"),
            });
        }
        Ok(v * self.unit)
    }

    /// An optional positive length, in metres.
    pub fn optional_length(
        &self,
        l: Option<&Spanned<f64>>,
        field: &str,
    ) -> Result<Option<f64>, SceneError> {
        l.map(|l| self.length(l, field)).transpose()
    }

    /// One value per band from an RGB triple (photopic: luminance-weighted sum).
    pub fn bands_of_rgb(&self, rgb: [f64; 3]) -> Vec<f64> {
        if self.bands == 1 {
            vec![rgb.iter().zip(LUMINANCE).map(|(c, w)| c * w).sum()]
        } else {
            rgb.to_vec()
        }
    }

    /// One value per band from `x = 0.5` or `x = [r, g, b]`.
    fn per_band(&self, v: &Spanned<PerBand>, field: &str) -> Result<Vec<f64>, SceneError> {
        match v.get_ref() {
            PerBand::One(x) => Ok(vec![*x; self.bands]),
            PerBand::Many(xs) if xs.len() == self.bands => Ok(xs.clone()),
            PerBand::Many(xs) => Err(SceneError::BandCount {
                at: self.at(v),
                field: field.into(),
                expected: self.bands,
                found: xs.len(),
            }),
        }
    }

    /// Checks reflectances are in [0, 1).
    pub fn check_reflectance(
        &self,
        r: Vec<f64>,
        at: &Location,
        field: &str,
    ) -> Result<Vec<f64>, SceneError> {
        if r.iter().all(|x| (0.0..1.0).contains(x)) {
            Ok(r)
        } else {
            Err(SceneError::OutOfRange {
                at: at.clone(),
                field: field.into(),
                message: format!("reflectance must be in [0, 1), found {r:?}"),
            })
        }
    }

    /// Checks exitances (or fluxes) are finite and non-negative.
    pub fn check_exitance(
        &self,
        e: Vec<f64>,
        at: &Location,
        field: &str,
    ) -> Result<Vec<f64>, SceneError> {
        if e.iter().all(|x| x.is_finite() && *x >= 0.0) {
            Ok(e)
        } else {
            Err(SceneError::OutOfRange {
                at: at.clone(),
                field: field.into(),
                message: format!("must be finite and non-negative, found {e:?}"),
            })
        }
    }
}

/// Checks that no two items share a name.
fn unique<'n>(
    kind: &'static str,
    names: impl IntoIterator<Item = (&'n str, Location)>,
) -> Result<(), SceneError> {
    let mut seen = HashSet::new();
    for (name, at) in names {
        if !seen.insert(name) {
            return Err(SceneError::Duplicate {
                at,
                kind,
                name: name.into(),
            });
        }
    }
    Ok(())
}

/// Surfaces matching a reference: an exact name, or a prefix followed by `*`.
fn matching(names: &[Surface], pattern: &str) -> Vec<usize> {
    match pattern.strip_suffix('*') {
        Some(prefix) => (0..names.len())
            .filter(|&i| names[i].name.starts_with(prefix))
            .collect(),
        None => names
            .iter()
            .position(|s| s.name == pattern)
            .into_iter()
            .collect(),
    }
}

/// Resolves a list of surface references to surface indices (in reference order, no repeats).
fn resolve_surfaces(
    ctx: &Ctx,
    surfaces: &[Surface],
    refs: &Spanned<Vec<String>>,
    field: &str,
) -> Result<Vec<usize>, SceneError> {
    let mut out = Vec::new();
    for r in refs.get_ref() {
        let found = matching(surfaces, r);
        if found.is_empty() {
            return Err(SceneError::Unknown {
                at: ctx.at(refs),
                field: field.into(),
                kind: "surface",
                name: r.clone(),
            });
        }
        for i in found {
            if !out.contains(&i) {
                out.push(i);
            }
        }
    }
    Ok(out)
}

/// Builds the scene from the parsed file.
pub(crate) fn build(file: SceneFile, text: &str, origin: &Path) -> Result<Scene, SceneError> {
    let bands = match file.scene.bands {
        BandsDef::Photopic => Bands::Photopic,
        BandsDef::Rgb => Bands::Rgb,
    };
    let ctx = Ctx {
        origin,
        text,
        bands: bands.count(),
        unit: file.scene.unit.get_ref().metres(),
    };
    let max_edge = ctx.length(&file.scene.max_edge, "scene.max_edge")?;
    let planarity = match &file.scene.planarity_tolerance {
        Some(p) if !(p.get_ref().is_finite() && *p.get_ref() >= 0.0) => {
            return Err(SceneError::OutOfRange {
                at: ctx.at(p),
                field: "scene.planarity_tolerance".into(),
                message: format!("must be finite and non-negative, found {}", p.get_ref()),
            })
        }
        Some(p) => *p.get_ref(),
        None => PLANARITY,
    };

    // Materials: the scene's own first; an MTL material of the same name does not replace it.
    let mut materials: BTreeMap<String, MaterialInfo> = BTreeMap::new();
    for (name, def) in &file.materials {
        let m = def.get_ref();
        let field = format!("materials.{name}.reflectance");
        let reflectance = ctx.per_band(&m.reflectance, &field)?;
        let reflectance = ctx.check_reflectance(reflectance, &ctx.at(&m.reflectance), &field)?;
        let emission = match &m.emission {
            Some(e) => {
                let field = format!("materials.{name}.emission");
                ctx.check_exitance(ctx.per_band(e, &field)?, &ctx.at(e), &field)?
            }
            None => vec![0.0; ctx.bands],
        };
        materials.insert(
            name.clone(),
            MaterialInfo {
                reflectance,
                emission,
            },
        );
    }

    // Geometry, in file order by kind.
    let mut raw: Vec<RawSurface> = Vec::new();
    let mut rooms: Vec<(String, Vec3, Vec3)> = Vec::new();
    for r in &file.room {
        raw.extend(primitives::room(&ctx, r)?);
        let (lo, hi) = primitives::box_corners(&ctx, "room", &r.get_ref().min, &r.get_ref().max)?;
        rooms.push((r.get_ref().name.clone(), lo, hi));
    }
    for b in &file.block {
        raw.extend(primitives::block(&ctx, b)?);
    }
    for q in &file.quad {
        raw.push(primitives::quad(&ctx, q)?);
    }
    for o in &file.obj {
        let content = obj::load(&ctx, o)?;
        raw.extend(content.surfaces);
        for (name, info) in content.materials {
            materials.entry(name).or_insert(info);
        }
    }
    unique(
        "surface",
        raw.iter().map(|s| (s.name.as_str(), s.at.clone())),
    )?;

    // Per-surface settings.
    let mut flip = vec![false; raw.len()];
    let mut split = vec![false; raw.len()];
    for (name, o) in &file.surfaces {
        let Some(i) = raw.iter().position(|s| &s.name == name) else {
            return Err(SceneError::Unknown {
                at: ctx.at(o),
                field: format!("surfaces.{name}"),
                kind: "surface",
                name: name.clone(),
            });
        };
        let o = o.get_ref();
        if let Some(m) = &o.material {
            raw[i].material = m.get_ref().clone();
            raw[i].material_at = ctx.at(m);
        }
        if let Some(e) = &o.max_edge {
            raw[i].max_edge = Some(ctx.length(e, &format!("surfaces.{name}.max_edge"))?);
        }
        flip[i] = o.flip;
        split[i] = o.triangulate;
    }

    // Materials resolved, faces checked and meshed.
    let mut surfaces = Vec::with_capacity(raw.len());
    let mut patches = Vec::new();
    let mut reflectance = Vec::new();
    let mut material_emission = Vec::with_capacity(raw.len());
    for (index, s) in raw.iter().enumerate() {
        let Some(material) = materials.get(&s.material) else {
            return Err(SceneError::Unknown {
                at: s.material_at.clone(),
                field: format!("surface `{}`.material", s.name),
                kind: "material",
                name: s.material.clone(),
            });
        };
        if s.faces.is_empty() {
            return Err(SceneError::BadFace {
                at: s.at.clone(),
                surface: s.name.clone(),
                face: 0,
                message: "surface has no faces".into(),
            });
        }
        let start = patches.len();
        let edge = s.max_edge.unwrap_or(max_edge);
        let mut polygons = Vec::new();
        for (f, face) in s.faces.iter().enumerate() {
            let mut face = face.clone();
            if flip[index] {
                face.reverse();
            }
            let bad = |p: super::mesh::FaceProblem| SceneError::BadFace {
                at: s.at.clone(),
                surface: s.name.clone(),
                face: f + 1,
                message: p.to_string(),
            };
            let pieces = if split[index] {
                triangulate(&face)
            } else {
                vec![face]
            };
            for piece in pieces {
                check_face(&piece, planarity).map_err(bad)?;
                mesh_face(&piece, edge, &mut polygons);
            }
        }
        for polygon in polygons {
            patches.push(Patch::new(polygon, index));
            reflectance.push(material.reflectance.clone());
        }
        surfaces.push(Surface {
            name: s.name.clone(),
            material: s.material.clone(),
            reflectance: material.reflectance.clone(),
            patch_range: start..patches.len(),
        });
        material_emission.push(material.emission.clone());
    }
    let area_of = |i: usize| -> f64 {
        patches[surfaces[i].patch_range.clone()]
            .iter()
            .map(|p| p.area)
            .sum()
    };

    // Channels.
    unique(
        "channel",
        file.channel
            .iter()
            .map(|c| (c.get_ref().name.as_str(), ctx.at(c))),
    )?;
    let mut channel_of_surface: Vec<Option<usize>> = vec![None; surfaces.len()];
    let mut surface_emission = vec![vec![0.0; ctx.bands]; surfaces.len()];
    let mut channels = Vec::with_capacity(file.channel.len());
    for (k, def) in file.channel.iter().enumerate() {
        let c = def.get_ref();
        let what = format!("channel `{}`", c.name);
        let mut members = match &c.surfaces {
            Some(refs) => resolve_surfaces(&ctx, &surfaces, refs, &format!("{what}.surfaces"))?,
            None => Vec::new(),
        };
        if let Some(mats) = &c.materials {
            for m in mats.get_ref() {
                let found: Vec<usize> = (0..surfaces.len())
                    .filter(|&i| &surfaces[i].material == m)
                    .collect();
                if found.is_empty() {
                    return Err(SceneError::Unknown {
                        at: ctx.at(mats),
                        field: format!("{what}.materials"),
                        kind: "material (on any surface)",
                        name: m.clone(),
                    });
                }
                for i in found {
                    if !members.contains(&i) {
                        members.push(i);
                    }
                }
            }
        }
        if members.is_empty() {
            return Err(SceneError::EmptyChannel {
                at: ctx.at(def),
                channel: c.name.clone(),
                message: "names no surface: give `surfaces` or `materials`".into(),
            });
        }
        let exitance = match (&c.exitance, &c.flux) {
            (Some(e), Some(_)) => {
                return Err(SceneError::Invalid {
                    at: ctx.at(e),
                    field: format!("{what}.exitance"),
                    message: "give `exitance` or `flux`, not both".into(),
                })
            }
            (Some(e), None) => {
                let field = format!("{what}.exitance");
                Some(ctx.check_exitance(ctx.per_band(e, &field)?, &ctx.at(e), &field)?)
            }
            (None, Some(f)) => {
                let field = format!("{what}.flux");
                let flux = ctx.check_exitance(ctx.per_band(f, &field)?, &ctx.at(f), &field)?;
                let area: f64 = members.iter().map(|&i| area_of(i)).sum();
                Some(flux.iter().map(|f| f / area).collect())
            }
            (None, None) => None,
        };
        for &i in &members {
            if let Some(previous) = channel_of_surface[i] {
                return Err(SceneError::Emitter {
                    at: ctx.at(def),
                    surface: surfaces[i].name.clone(),
                    message: format!(
                        "is in channel `{}` and in channel `{}`; a surface can be in one only",
                        channels_name(&file, previous),
                        c.name
                    ),
                });
            }
            channel_of_surface[i] = Some(k);
            surface_emission[i] = exitance
                .clone()
                .unwrap_or_else(|| material_emission[i].clone());
        }
        let area: f64 = members.iter().map(|&i| area_of(i)).sum();
        let mean: Vec<f64> = (0..ctx.bands)
            .map(|b| {
                members
                    .iter()
                    .map(|&i| surface_emission[i][b] * area_of(i))
                    .sum::<f64>()
                    / area
            })
            .collect();
        if mean.iter().all(|&x| x == 0.0) {
            return Err(SceneError::EmptyChannel {
                at: ctx.at(def),
                channel: c.name.clone(),
                message: "none of its surfaces emits: give `exitance` or `flux`, or use an \
                          emitting material"
                    .into(),
            });
        }
        channels.push(Channel {
            name: c.name.clone(),
            surfaces: members,
            exitance: mean,
        });
    }
    for (i, s) in surfaces.iter().enumerate() {
        if channel_of_surface[i].is_none() && material_emission[i].iter().any(|&x| x > 0.0) {
            return Err(SceneError::Emitter {
                at: raw[i].material_at.clone(),
                surface: s.name.clone(),
                message: format!(
                    "its material `{}` emits but no channel drives it; add it to a [[channel]]",
                    s.material
                ),
            });
        }
    }
    let mut emission = Vec::with_capacity(patches.len());
    let mut channel_of_patch = Vec::with_capacity(patches.len());
    for p in &patches {
        emission.push(surface_emission[p.surface].clone());
        channel_of_patch.push(channel_of_surface[p.surface]);
    }

    // Sensors.
    unique(
        "sensor",
        file.sensor
            .iter()
            .map(|s| (s.get_ref().name.as_str(), ctx.at(s))),
    )?;
    let mut sensors = Vec::with_capacity(file.sensor.len());
    for def in &file.sensor {
        let s = def.get_ref();
        let what = format!("sensor `{}`", s.name);
        let position = ctx.point(&s.position, &format!("{what}.position"))?;
        let n = s.normal.get_ref();
        let normal = Vec3::new(n[0], n[1], n[2]);
        if !(normal.is_finite() && normal.length() > 0.0) {
            return Err(SceneError::Invalid {
                at: ctx.at(&s.normal),
                field: format!("{what}.normal"),
                message: format!("must be a finite, non-zero vector, found {n:?}"),
            });
        }
        let half_angle = match &s.half_angle {
            Some(a) if !(*a.get_ref() > 0.0 && *a.get_ref() <= 90.0) => {
                return Err(SceneError::OutOfRange {
                    at: ctx.at(a),
                    field: format!("{what}.half_angle"),
                    message: format!("must be in (0, 90] degrees, found {}", a.get_ref()),
                })
            }
            Some(a) => Some(a.get_ref().to_radians()),
            None => None,
        };
        sensors.push(Sensor {
            name: s.name.clone(),
            position,
            normal: normal.normalized(),
            half_angle,
        });
    }

    // Zones.
    unique(
        "zone",
        file.zone
            .iter()
            .map(|z| (z.get_ref().name.as_str(), ctx.at(z))),
    )?;
    let mut zones = Vec::with_capacity(file.zone.len());
    for def in &file.zone {
        let z = def.get_ref();
        let what = format!("zone `{}`", z.name);
        let kind = match (&z.surfaces, &z.work_plane) {
            (Some(refs), None) => {
                let members = resolve_surfaces(&ctx, &surfaces, refs, &format!("{what}.surfaces"))?;
                ZoneKind::Surfaces(
                    members
                        .iter()
                        .flat_map(|&i| surfaces[i].patch_range.clone())
                        .collect(),
                )
            }
            (None, Some(wp)) => work_plane(&ctx, &what, wp, &rooms, &surfaces, max_edge)?,
            _ => {
                return Err(SceneError::Invalid {
                    at: ctx.at(def),
                    field: what,
                    message: "give exactly one of `surfaces` and `work_plane`".into(),
                })
            }
        };
        zones.push(Zone {
            name: z.name.clone(),
            kind,
        });
    }

    Ok(Scene {
        name: file.scene.name,
        bands,
        surfaces,
        patches,
        reflectance,
        emission,
        channel_of_patch,
        channels,
        sensors,
        zones,
    })
}

fn channels_name(file: &SceneFile, k: usize) -> &str {
    file.channel
        .get(k)
        .map_or("?", |c| c.get_ref().name.as_str())
}

/// Receivers of a work plane: upward quads over the room's footprint less the margin.
fn work_plane(
    ctx: &Ctx,
    what: &str,
    def: &Spanned<WorkPlaneDef>,
    rooms: &[(String, Vec3, Vec3)],
    surfaces: &[Surface],
    default_edge: f64,
) -> Result<ZoneKind, SceneError> {
    let wp = def.get_ref();
    let field = format!("{what}.work_plane.room");
    let room = match &wp.room {
        Some(name) => rooms
            .iter()
            .find(|r| &r.0 == name.get_ref())
            .ok_or_else(|| SceneError::Unknown {
                at: ctx.at(name),
                field: field.clone(),
                kind: "room",
                name: name.get_ref().clone(),
            })?,
        None if rooms.len() == 1 => &rooms[0],
        None => {
            return Err(SceneError::Invalid {
                at: ctx.at(def),
                field,
                message: format!("name the room (the scene has {} rooms)", rooms.len()),
            })
        }
    };
    let (name, lo, hi) = room;
    let height = ctx.length(&wp.height, &format!("{what}.work_plane.height"))?;
    if height >= hi.z - lo.z {
        return Err(SceneError::OutOfRange {
            at: ctx.at(&wp.height),
            field: format!("{what}.work_plane.height"),
            message: format!("must be below the ceiling of room `{name}`"),
        });
    }
    let margin = match &wp.margin {
        Some(m) if !(m.get_ref().is_finite() && *m.get_ref() >= 0.0) => {
            return Err(SceneError::OutOfRange {
                at: ctx.at(m),
                field: format!("{what}.work_plane.margin"),
                message: format!("must be finite and non-negative, found {}", m.get_ref()),
            })
        }
        Some(m) => *m.get_ref() * ctx.unit,
        None => 0.0,
    };
    if 2.0 * margin >= (hi.x - lo.x).min(hi.y - lo.y) {
        return Err(SceneError::OutOfRange {
            at: wp
                .margin
                .as_ref()
                .map_or_else(|| ctx.at(def), |m| ctx.at(m)),
            field: format!("{what}.work_plane.margin"),
            message: format!("leaves nothing of room `{name}`"),
        });
    }
    let edge = ctx.optional_length(wp.max_edge.as_ref(), &format!("{what}.work_plane.max_edge"))?;
    let floor = surfaces
        .iter()
        .position(|s| s.name == format!("{name}.floor"))
        .unwrap_or(0);
    let z = lo.z + height;
    let (x0, y0, x1, y1) = (lo.x + margin, lo.y + margin, hi.x - margin, hi.y - margin);
    let corners = [
        Vec3::new(x0, y0, z),
        Vec3::new(x1, y0, z),
        Vec3::new(x1, y1, z),
        Vec3::new(x0, y1, z),
    ];
    let mut polygons: Vec<Polygon> = Vec::new();
    mesh_face(&corners, edge.unwrap_or(default_edge), &mut polygons);
    Ok(ZoneKind::WorkPlane {
        height,
        receivers: polygons.into_iter().map(|p| Patch::new(p, floor)).collect(),
    })
}
