//! The faces of a closed OBJ shell as the faces of a space: faces in one plane merged into
//! polygons along the edges they share (a floor drawn as two quads is one L-shaped floor, a
//! triangulated wall one rectangle), straight corners dropped, and each polygon told floor,
//! wall or ceiling by its plane and the way it faces.

use super::shell::{InputFace, Shell};
use crate::geometry::{Polygon, Vec3};
use crate::scene::import::model::{ModelFace, ModelFaceKind};

/// A face of the shell after merging: what the importers' prism reads, and what the room
/// takes from the file.
pub(super) struct Merged {
    pub face: ModelFace,
    /// The OBJ surface all its faces belong to, if one.
    pub surface: Option<usize>,
    /// The input faces it was made of.
    pub members: Vec<usize>,
}

/// What a merge refused: the input face at fault and why.
pub(super) struct MergeError {
    pub face: usize,
    pub message: String,
}

/// Merges the faces of `shell` (from `input`, each of OBJ surface `surface_of[f]` with
/// material `material_of[f]`) plane by plane; `tol` (m) as for the shell.
pub(super) fn merge(
    shell: &Shell,
    input: &[InputFace],
    surface_of: &[usize],
    material_of: &[&str],
    tol: f64,
) -> Result<Vec<Merged>, MergeError> {
    let polygon = |ring: &[usize]| -> Vec<Vec3> { ring.iter().map(|&i| shell.points[i]).collect() };
    let normals: Vec<Vec3> = shell
        .rings
        .iter()
        .map(|r| Polygon::new(polygon(r.as_slice())).normal())
        .collect();
    // Faces in one plane facing the same way, each group led by its first face.
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for f in 0..shell.rings.len() {
        let in_plane = |g: &Vec<usize>| {
            let (n, o) = (normals[g[0]], shell.points[shell.rings[g[0]][0]]);
            n.dot(normals[f]) > 0.0
                && shell.rings[f]
                    .iter()
                    .all(|&i| (shell.points[i] - o).dot(n).abs() <= tol)
        };
        match groups.iter().position(in_plane) {
            Some(g) => groups[g].push(f),
            None => groups.push(vec![f]),
        }
    }
    let lowest = shell
        .points
        .iter()
        .map(|p| p.z)
        .fold(f64::INFINITY, f64::min);
    let mut merged = Vec::new();
    for group in &groups {
        let lead = group[0];
        if let Some(&other) = group.iter().find(|&&f| material_of[f] != material_of[lead]) {
            return Err(MergeError {
                face: other,
                message: format!(
                    "its material `{}` differs from that of {} (`{}`) in the same plane: a face \
                     of the room has one material; a window or a door is not part of the \
                     room's shell: draw it apart and list it in the `[[obj]]`'s `openings`",
                    material_of[other], input[lead].label, material_of[lead]
                ),
            });
        }
        for members in connected(shell, group) {
            let first = members[0];
            let ring =
                outline(shell, &members, normals[lead], tol).map_err(|message| MergeError {
                    face: first,
                    message,
                })?;
            let corners = polygon(&ring);
            let kind =
                kind(&corners, normals[lead], lowest, tol).map_err(|message| MergeError {
                    face: first,
                    message,
                })?;
            let surface =
                Some(surface_of[first]).filter(|&s| members.iter().all(|&f| surface_of[f] == s));
            merged.push(Merged {
                face: ModelFace {
                    id: input[first].label.clone(),
                    name: String::new(),
                    line: input[first].line,
                    kind,
                    polygon: corners,
                    material: Some(material_of[first].to_owned()),
                    adjacent: None,
                    openings: Vec::new(),
                },
                surface,
                members,
            });
        }
    }
    Ok(merged)
}

/// The faces of `group` in sets joined by shared edges, each in input order, the sets in the
/// order of their first faces.
fn connected(shell: &Shell, group: &[usize]) -> Vec<Vec<usize>> {
    let edges = |f: usize| {
        let r = &shell.rings[f];
        (0..r.len()).map(move |k| (r[k], r[(k + 1) % r.len()]))
    };
    let mut set: Vec<Option<usize>> = vec![None; group.len()];
    let mut sets: Vec<Vec<usize>> = Vec::new();
    for start in 0..group.len() {
        if set[start].is_some() {
            continue;
        }
        set[start] = Some(sets.len());
        let mut members = vec![group[start]];
        let mut k = 0;
        while k < members.len() {
            let f = members[k];
            for (j, &g) in group.iter().enumerate() {
                if set[j].is_none() && edges(f).any(|(a, b)| edges(g).any(|e| e == (b, a))) {
                    set[j] = Some(sets.len());
                    members.push(g);
                }
            }
            k += 1;
        }
        members.sort_unstable();
        sets.push(members);
    }
    sets
}

/// The outline of the union of the faces `members` (in one plane facing `normal`, joined by
/// shared edges): the edges of theirs that no other member shares, chained into a ring wound
/// as the faces are, without straight corners. Any further ring is a hole: an error.
fn outline(shell: &Shell, members: &[usize], normal: Vec3, tol: f64) -> Result<Vec<usize>, String> {
    let mut half: Vec<(usize, usize)> = Vec::new();
    for &f in members {
        let r = &shell.rings[f];
        half.extend((0..r.len()).map(|k| (r[k], r[(k + 1) % r.len()])));
    }
    let mut boundary: Vec<(usize, usize)> = half
        .iter()
        .copied()
        .filter(|&(a, b)| !half.contains(&(b, a)))
        .collect();
    boundary.sort_unstable();
    let mut used = vec![false; boundary.len()];
    let mut rings: Vec<Vec<usize>> = Vec::new();
    while let Some(start) = used.iter().position(|u| !u) {
        let mut ring = Vec::new();
        let mut at = start;
        loop {
            used[at] = true;
            let (a, b) = boundary[at];
            ring.push(a);
            if b == boundary[start].0 {
                break;
            }
            match (0..boundary.len()).find(|&k| !used[k] && boundary[k].0 == b) {
                Some(next) => at = next,
                // A closed shell's outlines in a plane always close; stop rather than loop.
                None => break,
            }
        }
        let ring = without_straight_corners(&shell.points, ring, tol);
        if ring.len() >= 3 {
            rings.push(ring);
        }
    }
    // The outer ring encloses the most area facing `normal`; any other is a hole.
    let area = |r: &Vec<usize>| {
        let corners: Vec<Vec3> = r.iter().map(|&i| shell.points[i]).collect();
        area_vector(&corners).dot(normal)
    };
    rings.sort_by(|a, b| area(b).total_cmp(&area(a)));
    match rings.len() {
        0 => Err("the faces in its plane enclose no area".into()),
        1 => Ok(rings.swap_remove(0)),
        _ => Err(format!(
            "the faces in its plane leave a hole around {:?} (m): a face of a room has no \
             holes (a column through the room is a `[[block]]` with `top = false` and \
             `bottom = false`)",
            shell.points[rings[1][0]].to_array()
        )),
    }
}

/// Twice the area vector of a polygon (Newell), m².
fn area_vector(corners: &[Vec3]) -> Vec3 {
    let n = corners.len();
    (0..n).fold(Vec3::ZERO, |s, k| {
        s + corners[k].cross(corners[(k + 1) % n])
    })
}

/// `ring` without the corners lying within `tol` (m) of the line between their neighbours.
fn without_straight_corners(points: &[Vec3], mut ring: Vec<usize>, tol: f64) -> Vec<usize> {
    let mut k = 0;
    while ring.len() > 3 && k < ring.len() {
        let n = ring.len();
        let (a, b, c) = (
            points[ring[(k + n - 1) % n]],
            points[ring[k]],
            points[ring[(k + 1) % n]],
        );
        let along = c - a;
        let s = (b - a).dot(along) / along.dot(along);
        let off = (b - a - along * s).length();
        if off <= tol && (0.0..=1.0).contains(&s) {
            ring.remove(k);
            k = k.saturating_sub(1);
        } else {
            k += 1;
        }
    }
    ring
}

/// What a face of a room's shell is, from its plane and the way it faces (`normal`, into
/// the room): level and facing up at the shell's lowest z (`lowest`, m), the floor; level
/// and facing down, the ceiling; standing or sloping down into the room, a wall (the prism
/// reads a sloping one as a roof face). Facing up anywhere else is refused.
fn kind(corners: &[Vec3], normal: Vec3, lowest: f64, tol: f64) -> Result<ModelFaceKind, String> {
    let z = corners[0].z;
    let level = corners.iter().all(|p| (p.z - z).abs() <= tol);
    if level {
        if normal.z < 0.0 {
            return Ok(ModelFaceKind::Ceiling);
        }
        if (z - lowest).abs() <= tol {
            return Ok(ModelFaceKind::Floor);
        }
        return Err(format!(
            "the face is level and faces up at z = {z} m, above the room's floor at z = \
             {lowest} m: a room's floor is on one level (a step or a platform is a \
             `[[block]]`)"
        ));
    }
    let across = Vec3::new(normal.x, normal.y, 0.0);
    let standing = across.length() > 0.0 && {
        let h = across.normalized();
        corners
            .iter()
            .all(|&p| (p - corners[0]).dot(h).abs() <= tol)
    };
    if !standing && normal.z > 0.0 {
        return Err(
            "the face slopes and faces up: a room's floor is level (sloped floors are not \
             supported yet)"
                .into(),
        );
    }
    Ok(if standing {
        ModelFaceKind::Wall
    } else {
        ModelFaceKind::Ceiling
    })
}
