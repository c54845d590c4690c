//! Zones: the surfaces or the work plane each one averages over, and the calculation grids
//! of surface zones.

use toml::Spanned;

use super::work_plane::work_plane;
use crate::geometry::{Patch, Vec3};
use crate::scene::context::{resolve_surfaces, unique, Ctx};
use crate::scene::error::SceneError;
use crate::scene::file::{GridDef, ZoneDef};
use crate::scene::grid::{self, Grid};
use crate::scene::room::Room;
use crate::scene::{Surface, Zone, ZoneKind};

/// Reads and checks the zones; `obstacles` are the blocks inside the rooms (name, min, max in
/// metres), `patch_list` the scene's patches (the surfaces' `patch_range`s index it),
/// `max_edge` (m) the scene's default.
pub(crate) fn zones(
    ctx: &Ctx,
    defs: &[Spanned<ZoneDef>],
    rooms: &[Room],
    obstacles: &[(String, Vec3, Vec3)],
    surfaces: &[Surface],
    patch_list: &[Patch],
    max_edge: f64,
) -> Result<Vec<Zone>, SceneError> {
    unique(
        "zone",
        defs.iter().map(|z| (z.get_ref().name.as_str(), ctx.at(z))),
    )?;
    let mut zones = Vec::with_capacity(defs.len());
    for def in defs {
        let z = def.get_ref();
        let what = format!("zone `{}`", z.name);
        let (kind, grid) = match (&z.surfaces, &z.work_plane) {
            (Some(refs), None) => {
                let members = resolve_surfaces(ctx, surfaces, refs, &format!("{what}.surfaces"))?;
                if members.is_empty() {
                    return Err(SceneError::Invalid {
                        at: ctx.at(refs),
                        field: format!("{what}.surfaces"),
                        message: "names no surface: a zone averages over at least one".into(),
                    });
                }
                let patches: Vec<usize> = members
                    .iter()
                    .flat_map(|&i| surfaces[i].patch_range.clone())
                    .collect();
                let grid = match &z.grid {
                    Some(g) => Some(surface_grid(ctx, &what, g, &patches, patch_list)?),
                    None => None,
                };
                (ZoneKind::Surfaces(patches), grid)
            }
            (None, Some(wp)) => {
                if let Some(g) = &z.grid {
                    return Err(SceneError::Invalid {
                        at: ctx.at(g),
                        field: format!("{what}.grid"),
                        message: "a work plane's grid is set as `work_plane.grid`".into(),
                    });
                }
                let (kind, grid) =
                    work_plane(ctx, &what, wp, rooms, obstacles, surfaces, max_edge)?;
                (kind, Some(grid))
            }
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
            grid,
        });
    }

    Ok(zones)
}

/// The spacing a grid's settings `grid` give (`field` under the zone), m, checked; `None`
/// for the rule.
pub(super) fn explicit_spacing(
    ctx: &Ctx,
    what: &str,
    field: &str,
    grid: Option<&Spanned<GridDef>>,
) -> Result<Option<f64>, SceneError> {
    let Some(s) = grid.and_then(|g| g.get_ref().spacing.as_ref()) else {
        return Ok(None);
    };
    let field = format!("{what}.{field}.spacing");
    let value = ctx.length(s, &field)?;
    if !(value > 0.0 && value <= grid::MAX_SPACING) {
        return Err(SceneError::OutOfRange {
            at: ctx.at(s),
            field,
            message: format!(
                "must be positive and at most {} m, found {}",
                grid::MAX_SPACING,
                s.get_ref()
            ),
        });
    }
    Ok(Some(value))
}

/// The error for a grid of more than [`grid::MAX_POINTS`] cells (`field` under the zone: its
/// settings `grid`), at its spacing if the scene gave one, else at the settings or `fallback`.
pub(super) fn too_many_points(
    ctx: &Ctx,
    what: &str,
    field: &str,
    grid: Option<&Spanned<GridDef>>,
    fallback: crate::scene::error::Location,
    cells: usize,
) -> SceneError {
    let spacing = grid.and_then(|g| g.get_ref().spacing.as_ref());
    let (at, field) = match (spacing, grid) {
        (Some(s), _) => (ctx.at(s), format!("{what}.{field}.spacing")),
        (None, Some(g)) => (ctx.at(g), format!("{what}.{field}")),
        (None, None) => (fallback, format!("{what}.{field}")),
    };
    SceneError::OutOfRange {
        at,
        field,
        message: format!(
            "gives {cells} points, more than {} a zone may have",
            grid::MAX_POINTS
        ),
    }
}

/// A surface zone's grid (`zone.grid`): one piece per plane of its `patches` (indices into
/// `patch_list`), no border.
fn surface_grid(
    ctx: &Ctx,
    what: &str,
    def: &Spanned<GridDef>,
    patches: &[usize],
    patch_list: &[Patch],
) -> Result<Grid, SceneError> {
    let spacing = explicit_spacing(ctx, what, "grid", Some(def))?;
    let members: Vec<&Patch> = patches.iter().map(|&i| &patch_list[i]).collect();
    let pieces = grid::on_patches(&members, spacing, grid::MAX_POINTS)
        .map_err(|cells| too_many_points(ctx, what, "grid", Some(def), ctx.at(def), cells))?;
    if pieces.is_empty() {
        return Err(SceneError::Invalid {
            at: ctx.at(def),
            field: format!("{what}.grid"),
            message: "no cell centre of the grid lies on the zone's surfaces".into(),
        });
    }
    Ok(Grid {
        pieces,
        obstructed: 0,
    })
}
