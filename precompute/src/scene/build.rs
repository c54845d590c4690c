//! From the parsed file to a validated, meshed [`Scene`]: units, materials, surfaces, meshing,
//! channels, sensors and zones (the scene's own, then the imported sensor grids).

use std::collections::BTreeMap;
use std::ops::Range;
use std::path::Path;

use super::channels::Emitters;
use super::contacts::{self, Footprint};
use super::context::{unique, Ctx, MaterialInfo, RawSurface};
use super::error::SceneError;
use super::file::{BandsDef, SceneFile};
use super::layout::Layout;
use super::mesh::{mesh_surfaces, Meshed};
use super::openings::CONTACT_TOLERANCE;
use super::room::Room;
use super::{
    channels, daylight, import, limits, luminaires, obj, obj_room, observers, openings, primitives,
    winding,
};
use super::{Adjacency, Bands, Luminaire, Scene, Window};
use crate::formfactor::Solid;
use crate::geometry::{Aabb, Face, Patch, Vec3};

/// Default planarity tolerance: a corner may sit 0.1 % of the face's diagonal off its plane.
const PLANARITY: f64 = 1e-3;

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
    let planarity = planarity(&ctx, &file)?;
    let mut materials = scene_materials(&ctx, &file)?;
    let mut geometry = geometry(&ctx, &file, &mut materials)?;
    let site = daylight::site(&ctx, file.site.as_ref())?;
    let (mut flip, mut split) = surface_settings(&ctx, &file, &mut geometry.raw)?;

    // Faces wound against their neighbours, exterior surfaces set apart, openings cut out of
    // room faces, and the patch count checked against memory: all before meshing.
    check_obj_windings(&geometry, &flip)?;
    let mut is_obj = obj_surfaces(&geometry);
    let outside = daylight::take_exterior(&mut geometry.raw, &mut flip, &mut split, &mut is_obj);
    daylight::check_references(&ctx, &file, &geometry.raw, &outside)?;
    let obstructions =
        daylight::obstructions(&ctx, &outside, &materials, &geometry.rooms, planarity)?;
    let claimed = cut_openings(&ctx, &file, &mut geometry, &flip)?;
    limits::check(
        &geometry.raw,
        ctx.bands,
        max_edge,
        &ctx.at(&file.scene.max_edge),
    )?;

    let raw = &geometry.raw;
    let footprints = obj_footprints(raw, &is_obj);
    let meshed = mesh_surfaces(
        raw,
        &materials,
        &flip,
        &split,
        &footprints,
        max_edge,
        planarity,
    )?;
    // Name and corners (m) of each block inside the rooms.
    let inside = inside_blocks(&file, &geometry);
    let luminaires = luminaires::place(&ctx, &file.luminaire, &file.channel)?;
    luminaires::check_placement(&ctx, &file.luminaire, &luminaires, &geometry.rooms, &inside)?;
    let emitters = resolve_channels(&ctx, &file, &luminaires, &meshed, raw)?;
    let (emission, channel_of_patch) = patch_emission(&meshed.patches, &emitters);
    let windows = glazed_windows(&ctx, &file, &geometry, &claimed, &materials, &emitters)?;
    let sensors = observers::sensors(
        &ctx,
        &file.sensor,
        &geometry.rooms,
        &inside,
        extent(raw),
        &enclosures(&geometry.rooms, &meshed.faces),
    )?;
    let mut zones = observers::zones(
        &ctx,
        &file.zone,
        &geometry.rooms,
        &inside,
        &meshed.surfaces,
        &meshed.patches,
        max_edge,
    )?;
    // The imported sensor grids follow the scene's own zones, under names of their own.
    unique(
        "zone",
        (file
            .zone
            .iter()
            .map(|z| (z.get_ref().name.as_str(), ctx.at(z))))
        .chain(
            geometry
                .grids
                .iter()
                .map(|g| (g.name.as_str(), g.at.clone())),
        ),
    )?;
    zones.extend(observers::imported_grids(
        &geometry.grids,
        &geometry.rooms,
        &inside,
    )?);

    let layout = Layout::of(&geometry.rooms, &inside, &claimed);
    let solids = inside_solids(&file, &geometry);
    Ok(Scene {
        name: file.scene.name,
        bands,
        surfaces: meshed.surfaces,
        patches: meshed.patches,
        faces: meshed.faces,
        reflectance: meshed.reflectance,
        emission,
        channel_of_patch,
        channels: emitters.channels,
        luminaires,
        sensors,
        zones,
        site,
        windows,
        obstructions,
        layout,
        solids,
        adjacency: geometry.adjacency,
        warnings: geometry.warnings,
    })
}

/// Checks each OBJ file's faces for one wound against its neighbours ([`winding::check`]),
/// with the `flip` of the `[surfaces]` tables applied.
fn check_obj_windings(geometry: &Geometry, flip: &[bool]) -> Result<(), SceneError> {
    for range in &geometry.obj_surfaces {
        winding::check(&geometry.raw[range.clone()], &flip[range.clone()])?;
    }
    Ok(())
}

/// Which of the surfaces come from OBJ files, by index into `geometry.raw`.
fn obj_surfaces(geometry: &Geometry) -> Vec<bool> {
    let mut is_obj = vec![false; geometry.raw.len()];
    for i in geometry.obj_surfaces.iter().flat_map(|r| r.clone()) {
        is_obj[i] = true;
    }
    is_obj
}

/// Cuts every room's openings, and the footprints of the blocks standing on its floor, out of
/// its faces ([`openings::cut`]); returns which surfaces became an opening.
fn cut_openings(
    ctx: &Ctx,
    file: &SceneFile,
    geometry: &mut Geometry,
    flip: &[bool],
) -> Result<Vec<bool>, SceneError> {
    let mut claimed = vec![false; geometry.raw.len()];
    let open_at = |end: fn(&super::file::BlockDef) -> bool| -> Vec<(String, Vec3, Vec3)> {
        geometry
            .blocks
            .iter()
            .zip(&file.block)
            .filter(|(_, def)| !end(def.get_ref()) && !def.get_ref().exterior)
            .map(|(b, _)| b.clone())
            .collect()
    };
    // Blocks without a bottom stand on the floor; without a top they reach the ceiling.
    let standing = open_at(|b| b.bottom);
    let hanging = open_at(|b| b.top);
    for ((r, room), faces) in file
        .room
        .iter()
        .zip(&geometry.rooms)
        .zip(geometry.room_faces.clone())
    {
        openings::cut(
            &openings::OpeningList::of(ctx, r),
            room,
            faces,
            &mut geometry.raw,
            flip,
            &mut claimed,
            &openings::OpenBlocks {
                standing: &standing,
                hanging: &hanging,
            },
        )?;
    }
    // The imported rooms and the OBJ rooms follow the scene's own, in `rooms` and
    // `room_faces`.
    let first = file.room.len();
    for (k, (names, at, kind)) in geometry.more_openings.iter().enumerate() {
        let room = &geometry.rooms[first + k];
        openings::cut(
            &openings::OpeningList {
                names,
                at: at.clone(),
                field: format!("{kind} room `{}`.openings", room.name),
            },
            room,
            geometry.room_faces[first + k].clone(),
            &mut geometry.raw,
            flip,
            &mut claimed,
            &openings::OpenBlocks {
                standing: &standing,
                hanging: &hanging,
            },
        )?;
    }
    Ok(claimed)
}

/// The footprints of the OBJ objects (`is_obj`) on the faces they stand on, within
/// [`contact_tolerance`].
fn obj_footprints(raw: &[RawSurface], is_obj: &[bool]) -> Vec<Footprint> {
    let objects: Vec<usize> = (0..raw.len()).filter(|&i| is_obj[i]).collect();
    contacts::footprints(raw, &objects, contact_tolerance(raw))
}

/// The channels resolved against the meshed surfaces ([`channels::resolve`]), each knowing
/// whether luminaires are in it.
fn resolve_channels(
    ctx: &Ctx,
    file: &SceneFile,
    luminaires: &[Luminaire],
    meshed: &Meshed,
    raw: &[RawSurface],
) -> Result<Emitters, SceneError> {
    let lit: Vec<bool> = (0..file.channel.len())
        .map(|k| luminaires.iter().any(|l| l.channel == k))
        .collect();
    channels::resolve(
        ctx,
        &file.channel,
        &lit,
        &meshed.surfaces,
        &meshed.patches,
        raw,
        &meshed.material_emission,
    )
}

/// Each patch's emission per band at level 1 and the channel driving it: its surface's.
fn patch_emission(patches: &[Patch], emitters: &Emitters) -> (Vec<Vec<f64>>, Vec<Option<usize>>) {
    let mut emission = Vec::with_capacity(patches.len());
    let mut channel_of_patch = Vec::with_capacity(patches.len());
    for p in patches {
        emission.push(emitters.surface_emission[p.surface].clone());
        channel_of_patch.push(emitters.channel_of_surface[p.surface]);
    }
    (emission, channel_of_patch)
}

/// The glazed surfaces ([`daylight::windows`]); `claimed` marks the surfaces that became an
/// opening.
fn glazed_windows(
    ctx: &Ctx,
    file: &SceneFile,
    geometry: &Geometry,
    claimed: &[bool],
    materials: &BTreeMap<String, MaterialInfo>,
    emitters: &Emitters,
) -> Result<Vec<Window>, SceneError> {
    // A room's own face may be glazed; any other window in a room face must be an opening.
    let mut in_place = claimed.to_vec();
    for i in geometry.room_faces.iter().flat_map(|r| r.clone()) {
        in_place[i] = true;
    }
    daylight::windows(
        ctx,
        file,
        &geometry.raw,
        materials,
        &emitters.channel_of_surface,
        &geometry.rooms,
        &in_place,
    )
}

/// The blocks inside the rooms (all but exterior ones): name and corners, m.
fn inside_blocks(file: &SceneFile, geometry: &Geometry) -> Vec<(String, Vec3, Vec3)> {
    geometry
        .blocks
        .iter()
        .zip(&file.block)
        .filter(|(_, def)| !def.get_ref().exterior)
        .map(|(b, _)| b.clone())
        .collect()
}

/// The blocks inside the rooms as solids: every face of a block is a patch of the scene but
/// the bottom or top it leaves out.
fn inside_solids(file: &SceneFile, geometry: &Geometry) -> Vec<Solid> {
    geometry
        .blocks
        .iter()
        .zip(&file.block)
        .filter(|(_, def)| !def.get_ref().exterior)
        .map(|((_, lo, hi), def)| Solid {
            bounds: Aabb { min: *lo, max: *hi },
            open_below: !def.get_ref().bottom,
            open_above: !def.get_ref().top,
        })
        .collect()
}

/// The scene's planarity tolerance (a share of each face's diagonal), [`PLANARITY`] unless
/// the file sets one.
fn planarity(ctx: &Ctx, file: &SceneFile) -> Result<f64, SceneError> {
    Ok(match &file.scene.planarity_tolerance {
        Some(p) if !(p.get_ref().is_finite() && *p.get_ref() >= 0.0) => {
            return Err(SceneError::OutOfRange {
                at: ctx.at(p),
                field: "scene.planarity_tolerance".into(),
                message: format!("must be finite and non-negative, found {}", p.get_ref()),
            })
        }
        Some(p) => *p.get_ref(),
        None => PLANARITY,
    })
}

/// The scene's own materials, checked, by name. They come first: an MTL material of the same
/// name does not replace them.
fn scene_materials(
    ctx: &Ctx,
    file: &SceneFile,
) -> Result<BTreeMap<String, MaterialInfo>, SceneError> {
    let mut materials: BTreeMap<String, MaterialInfo> = BTreeMap::new();
    for (name, def) in &file.materials {
        let m = def.get_ref();
        let field = format!("materials.{name}.reflectance");
        let reflectance = ctx.per_band(&m.reflectance, &field)?;
        let reflectance = ctx.check_reflectance(reflectance, &ctx.at(&m.reflectance), &field)?;
        let glazing = daylight::glazing(ctx, name, m, &reflectance)?;
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
                glazing,
            },
        );
    }
    Ok(materials)
}

/// Every surface of the file before meshing, with the boxes the later checks need.
struct Geometry {
    /// Rooms, imported rooms (each followed by its openings), OBJ rooms, blocks, quads and
    /// the other OBJ files' groups, in that order.
    raw: Vec<RawSurface>,
    /// The rooms: the scene's `[[room]]`s in file order, then the imported ones, then the
    /// OBJ rooms.
    rooms: Vec<Room>,
    /// Each room's faces in `raw`.
    room_faces: Vec<Range<usize>>,
    /// Each imported or OBJ room's openings (surface names), where the list (or its
    /// `[[import]]`) was written, and what made the room (`imported`, `OBJ`).
    more_openings: Vec<(Vec<String>, super::error::Location, &'static str)>,
    /// The imported rooms' faces shared with other spaces of their models.
    adjacency: Vec<Adjacency>,
    /// The imports' sensor grids.
    grids: Vec<import::ImportedGrid>,
    /// What the imports could not map.
    warnings: Vec<String>,
    /// Each block's name and corners (m).
    blocks: Vec<(String, Vec3, Vec3)>,
    /// Each OBJ file's surfaces in `raw`.
    obj_surfaces: Vec<Range<usize>>,
}

/// The surfaces of the file, in file order by kind, with unique names; the OBJ files'
/// materials are added to `materials` where the scene does not name them.
fn geometry(
    ctx: &Ctx,
    file: &SceneFile,
    materials: &mut BTreeMap<String, MaterialInfo>,
) -> Result<Geometry, SceneError> {
    let mut raw: Vec<RawSurface> = Vec::new();
    let mut rooms: Vec<Room> = Vec::new();
    let mut room_faces = Vec::new();
    for r in &file.room {
        let room = Room::read(ctx, r)?;
        let start = raw.len();
        raw.extend(room.surfaces());
        room_faces.push(start..raw.len());
        rooms.push(room);
    }
    let mut more_openings = Vec::new();
    let mut adjacency = Vec::new();
    let mut warnings = Vec::new();
    let mut grids = Vec::new();
    for i in &file.import {
        let imported = import::read(ctx, i, &file.surfaces, materials)?;
        for r in imported.rooms {
            let start = raw.len();
            raw.extend(r.room.surfaces());
            room_faces.push(start..raw.len());
            rooms.push(r.room);
            more_openings.push((
                r.openings.iter().map(|o| o.name.clone()).collect(),
                r.at,
                "imported",
            ));
            raw.extend(r.openings);
            adjacency.extend(r.adjacency);
        }
        warnings.extend(imported.warnings);
        grids.extend(imported.grids);
    }
    // OBJ rooms before the blocks, which must stand inside a room.
    let mut obj_rooms = vec![false; file.obj.len()];
    for (k, o) in file.obj.iter().enumerate() {
        let Some(name) = &o.get_ref().room else {
            if let Some(list) = &o.get_ref().openings {
                return Err(SceneError::Invalid {
                    at: ctx.at(list),
                    field: "obj.openings".into(),
                    message: "openings are cut out of a room's faces: name the room the OBJ \
                              file's faces form with `room = \"...\"`"
                        .into(),
                });
            }
            continue;
        };
        obj_rooms[k] = true;
        let content = obj::load(ctx, o)?;
        for (name, info) in content.materials.iter().cloned() {
            materials.entry(name).or_insert(info);
        }
        let r = obj_room::read(ctx, o, name, &content)?;
        let start = raw.len();
        raw.extend(r.room.surfaces());
        room_faces.push(start..raw.len());
        rooms.push(r.room);
        more_openings.push((r.openings, r.at, "OBJ"));
    }
    let mut blocks: Vec<(String, Vec3, Vec3)> = Vec::new();
    for b in &file.block {
        raw.extend(primitives::block(ctx, b)?);
        let (lo, hi) = primitives::box_corners(ctx, "block", &b.get_ref().min, &b.get_ref().max)?;
        if !b.get_ref().exterior {
            primitives::check_inside_rooms(ctx, b, lo, hi, &rooms)?;
        }
        blocks.push((b.get_ref().name.clone(), lo, hi));
    }
    for q in &file.quad {
        raw.push(primitives::quad(ctx, q)?);
    }
    for p in &file.polygon {
        raw.push(primitives::polygon(ctx, p)?);
    }
    let mut obj_surfaces = Vec::new();
    for o in file
        .obj
        .iter()
        .zip(&obj_rooms)
        .filter(|(_, &r)| !r)
        .map(|(o, _)| o)
    {
        let content = obj::load(ctx, o)?;
        let start = raw.len();
        raw.extend(content.surfaces);
        obj_surfaces.push(start..raw.len());
        for (name, info) in content.materials {
            materials.entry(name).or_insert(info);
        }
    }
    unique(
        "surface",
        raw.iter().map(|s| (s.name.as_str(), s.at.clone())),
    )?;
    Ok(Geometry {
        raw,
        rooms,
        room_faces,
        more_openings,
        adjacency,
        grids,
        warnings,
        blocks,
        obj_surfaces,
    })
}

/// Applies the `[surfaces.NAME]` tables to `raw` (material, `max_edge`); returns which
/// surfaces to flip and which to triangulate.
fn surface_settings(
    ctx: &Ctx,
    file: &SceneFile,
    raw: &mut [RawSurface],
) -> Result<(Vec<bool>, Vec<bool>), SceneError> {
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
    Ok((flip, split))
}

/// The box around every face of the scene (m), `None` for a scene without faces.
fn extent(raw: &[RawSurface]) -> Option<(Vec3, Vec3)> {
    let mut b = Aabb::EMPTY;
    for p in raw.iter().flat_map(|s| s.faces.iter().flatten()) {
        b.grow(*p);
    }
    (b.min.x <= b.max.x).then_some((b.min, b.max))
}

/// In a scene without rooms, the box (m) around each closed cavity its faces form
/// ([`crate::formfactor::cavities`]); none in a scene with rooms (their sensors are checked
/// against the rooms) or without a closed cavity.
fn enclosures(rooms: &[Room], faces: &[Face]) -> Vec<(Vec3, Vec3)> {
    if !rooms.is_empty() {
        return Vec::new();
    }
    crate::formfactor::cavities(faces)
        .iter()
        .map(|cavity| {
            let mut b = Aabb::EMPTY;
            for &f in cavity {
                for p in &faces[f].polygon.vertices {
                    b.grow(*p);
                }
            }
            (b.min, b.max)
        })
        .collect()
}

/// [`CONTACT_TOLERANCE`] of the diagonal of everything in the scene, metres: how far an OBJ
/// object's edge may be from a face and still stand on it.
fn contact_tolerance(raw: &[RawSurface]) -> f64 {
    // A non-finite coordinate is refused when its face is checked; until then, no contacts.
    extent(raw)
        .map(|(lo, hi)| CONTACT_TOLERANCE * (hi - lo).length())
        .filter(|t| t.is_finite())
        .unwrap_or(0.0)
}
