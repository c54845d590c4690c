//! Sensor grids imported from a building model as zones: every sensor a grid point read as
//! illuminance on the plane facing its own direction (a cosine receiver over the front
//! hemisphere, like a work-plane grid's point), the zone reading their mean (docs/scene.md,
//! "Sensor grids").
//!
//! A sensor outside its room (or outside every room, for a grid the model ties to none) is
//! an error naming the model file, the grid and the sensor: the grid belongs to another
//! room, or the model and the scene disagree. A sensor inside an obstacle of the scene (a
//! block) is left out and counted, as a work-plane grid's points are.

use super::work_plane::inside_obstacle;
use crate::geometry::Vec3;
use crate::scene::error::SceneError;
use crate::scene::grid::{self, Grid, GridPiece};
use crate::scene::import::ImportedGrid;
use crate::scene::room::Room;
use crate::scene::{Zone, ZoneKind};

/// The nominal spacing (m) of a grid whose sensors are all at one place: its layout needs a
/// positive cell, and one sensor has no neighbour to measure it from.
const LONE_SPACING: f64 = 1.0;

/// The zones of the imported sensor grids, in order; `rooms` are the scene's rooms (the
/// grids name theirs), `obstacles` the blocks inside them (name, min, max in metres).
pub(crate) fn imported_grids(
    grids: &[ImportedGrid],
    rooms: &[Room],
    obstacles: &[(String, Vec3, Vec3)],
) -> Result<Vec<Zone>, SceneError> {
    grids
        .iter()
        .map(|g| imported_grid(g, rooms, obstacles))
        .collect()
}

/// The zone of one imported grid.
fn imported_grid(
    g: &ImportedGrid,
    rooms: &[Room],
    obstacles: &[(String, Vec3, Vec3)],
) -> Result<Zone, SceneError> {
    let error = |element: String, message: String| SceneError::Import {
        at: g.at.clone(),
        element,
        message,
    };
    let what = format!("sensor grid `{}`", g.id);
    if g.sensors.len() > grid::MAX_POINTS {
        return Err(error(
            what,
            format!(
                "has {} sensors, more than the {} a zone's grid may have",
                g.sensors.len(),
                grid::MAX_POINTS
            ),
        ));
    }
    let room = match &g.room {
        Some(name) => rooms.iter().find(|r| &r.name == name),
        None => None,
    };
    let mut kept: Vec<(Vec3, Vec3)> = Vec::with_capacity(g.sensors.len());
    let mut obstructed = 0;
    for (i, &(p, n)) in g.sensors.iter().enumerate() {
        let inside = match room {
            Some(r) => r.contains(p),
            None => rooms.iter().any(|r| r.contains(p)),
        };
        if !inside {
            let whose = match room {
                Some(r) => format!("its room ({})", r.describe(1.0)),
                None => format!(
                    "every room ({})",
                    rooms
                        .iter()
                        .map(|r| r.describe(1.0))
                        .collect::<Vec<_>>()
                        .join("; ")
                ),
            };
            return Err(error(
                format!("{what}, sensor {i}"),
                format!(
                    "its position {:?} m is outside {whose}: a sensor there would read \
                     nothing of the room",
                    p.to_array()
                ),
            ));
        }
        if inside_obstacle(p, obstacles) {
            obstructed += 1;
        } else {
            kept.push((p, n));
        }
    }
    if kept.is_empty() {
        return Err(error(
            what,
            format!("all its {} sensors lie inside obstacles", g.sensors.len()),
        ));
    }
    let spacing = spacing(&kept);
    Ok(Zone {
        name: g.name.clone(),
        kind: ZoneKind::Points {
            area: kept.len() as f64 * spacing * spacing,
            points: kept.clone(),
        },
        grid: Some(Grid {
            pieces: pieces(&kept, spacing),
            obstructed,
        }),
    })
}

/// The grid's spacing (m): the largest distance from a sensor to its nearest neighbour (the
/// spacing a regular grid is laid out at), [`LONE_SPACING`] when no two sensors are apart.
fn spacing(points: &[(Vec3, Vec3)]) -> f64 {
    let mut largest: f64 = 0.0;
    for (i, &(p, _)) in points.iter().enumerate() {
        let nearest = points
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, &(q, _))| (q - p).length())
            .filter(|&d| d > 0.0)
            .fold(f64::INFINITY, f64::min);
        if nearest.is_finite() {
            largest = largest.max(nearest);
        }
    }
    if largest > 0.0 {
        largest
    } else {
        LONE_SPACING
    }
}

/// The grid's pieces: one per run of consecutive sensors facing the same direction, each a
/// row of its points (`counts` [points, 1], square cells of `spacing`), so that the points
/// keep the file's order and each piece its one normal.
fn pieces(points: &[(Vec3, Vec3)], spacing: f64) -> Vec<GridPiece> {
    let mut pieces: Vec<GridPiece> = Vec::new();
    for &(p, n) in points {
        match pieces.last_mut() {
            Some(piece) if piece.normal == n => {
                piece.points.push(p);
                piece.counts[0] += 1;
            }
            _ => pieces.push(GridPiece {
                spacing,
                explicit: true,
                border: 0.0,
                counts: [1, 1],
                cell: [spacing, spacing],
                normal: n,
                points: vec![p],
            }),
        }
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs of equal directions become pieces in file order; the spacing is the largest
    /// nearest-neighbour distance (a 0.5 m row and a point 2 m past its end: 2 m).
    #[test]
    fn pieces_follow_the_directions_in_file_order() {
        let up = Vec3::new(0.0, 0.0, 1.0);
        let south = Vec3::new(0.0, -1.0, 0.0);
        let at = |x: f64| Vec3::new(x, 0.0, 1.0);
        let points = [
            (at(0.0), up),
            (at(0.5), up),
            (at(1.0), south),
            (at(3.0), up),
        ];
        assert_eq!(spacing(&points), 2.0);
        let p = pieces(&points, 0.5);
        let shape: Vec<(usize, Vec3)> = p.iter().map(|q| (q.points.len(), q.normal)).collect();
        assert_eq!(shape, [(2, up), (1, south), (1, up)]);
        assert!(p.iter().all(|q| q.counts == [q.points.len(), 1]));
        assert_eq!(spacing(&[(at(1.0), up), (at(1.0), up)]), LONE_SPACING);
    }
}
