//! The faces of an OBJ room as one closed shell: corners welded within the tolerance, every
//! edge split where another face's corner lies on it (a long wall edge meeting two floor
//! faces), each edge then shared by exactly two faces running along it in opposite
//! directions, and every face wound to face into the room.
//!
//! Which way is "into the room" is decided for the whole shell at once: once the faces are
//! oriented consistently, the shell's signed volume (the divergence theorem over its faces)
//! is negative when their normals point inwards. A face wound against that orientation is
//! then named for what it is, a face facing out of the room, whatever its neighbours are.

use std::collections::BTreeMap;

use crate::geometry::Vec3;

/// One face of the OBJ file as read, with what names it in messages.
pub(super) struct InputFace {
    /// Its corners, metres, as the file winds them.
    pub corners: Vec<Vec3>,
    /// How a message names it, e.g. ``face `south #2` ``.
    pub label: String,
    /// The 1-based line of its `f` statement.
    pub line: Option<usize>,
}

/// A shell checked closed and wound into the room.
pub(super) struct Shell {
    /// The welded corners, metres.
    pub points: Vec<Vec3>,
    /// Each input face as a ring of indices into `points`, wound into the room, with every
    /// corner of another face lying on one of its edges inserted there.
    pub rings: Vec<Vec<usize>>,
}

/// Why the faces are not a closed room: the face at fault (index into the input) and what is
/// wrong.
pub(super) struct ShellError {
    pub face: usize,
    pub message: String,
}

/// Welds, splits and checks `faces` into a closed shell wound into the room; `tol` (m) is
/// how far apart two corners may be and still count as one, or a corner from an edge and
/// still lie on it.
pub(super) fn close(faces: &[InputFace], tol: f64) -> Result<Shell, ShellError> {
    let (points, rings) = weld(faces, tol)?;
    let rings = split_edges(&points, rings, tol);
    let edges = edge_users(&rings);
    for (&(a, b), users) in &edges {
        if users.len() != 2 {
            let face = users[0].0;
            let at = |i: usize| points[i].to_array();
            let message = if users.len() == 1 {
                format!(
                    "its edge from {:?} to {:?} (m) is not shared with another face: the room \
                     is not closed (a face is missing, or two faces' corners do not meet)",
                    at(a),
                    at(b)
                )
            } else {
                let others: Vec<String> = users[1..]
                    .iter()
                    .map(|&(f, _)| faces[f].label.clone())
                    .collect();
                format!(
                    "its edge from {:?} to {:?} (m) is shared with {}: a room is one closed \
                     surface, each edge between exactly two faces",
                    at(a),
                    at(b),
                    others.join(", ")
                )
            };
            return Err(ShellError { face, message });
        }
    }
    let keep = orient(faces, &rings, &edges)?;
    // With `keep` applied the faces are consistent; the sign of the volume they enclose says
    // whether they face in (negative) or out.
    let volume: f64 = rings
        .iter()
        .zip(&keep)
        .map(|(ring, &k)| if k { 1.0 } else { -1.0 } * signed_volume(&points, ring))
        .sum();
    // Faces wound as the file winds them face in when the consistent orientation does and
    // they keep it, or when it faces out and they do not.
    let inward: Vec<bool> = keep.iter().map(|&k| k == (volume < 0.0)).collect();
    let outward: Vec<usize> = (0..faces.len()).filter(|&f| !inward[f]).collect();
    if let Some(&first) = outward.first() {
        let message =
            if outward.len() == faces.len() {
                "every face of the room faces out of it (the file draws the room as a solid seen \
             from outside): reverse the winding of all its faces (in a modeller: flip the \
             normals)"
                    .to_string()
            } else {
                let named: Vec<&str> = outward
                    .iter()
                    .take(6)
                    .map(|&f| faces[f].label.as_str())
                    .collect();
                format!(
                "the face faces out of the room while its neighbours face into it; reverse its \
                 corners in the file ({} of {} faces do: {}{})",
                outward.len(),
                faces.len(),
                named.join(", "),
                if outward.len() > named.len() { ", ..." } else { "" }
            )
            };
        return Err(ShellError {
            face: first,
            message,
        });
    }
    Ok(Shell { points, rings })
}

/// The corners of `faces` welded within `tol`, and each face as a ring of their indices
/// without repeated consecutive corners; a face left with fewer than three is an error.
fn weld(faces: &[InputFace], tol: f64) -> Result<(Vec<Vec3>, Vec<Vec<usize>>), ShellError> {
    let mut points: Vec<Vec3> = Vec::new();
    let mut rings = Vec::with_capacity(faces.len());
    for (f, face) in faces.iter().enumerate() {
        let mut ring: Vec<usize> = Vec::with_capacity(face.corners.len());
        for &c in &face.corners {
            let i = match points.iter().position(|&p| (p - c).length() <= tol) {
                Some(i) => i,
                None => {
                    points.push(c);
                    points.len() - 1
                }
            };
            if ring.last() != Some(&i) {
                ring.push(i);
            }
        }
        while ring.len() > 1 && ring.first() == ring.last() {
            ring.pop();
        }
        if ring.len() < 3 {
            return Err(ShellError {
                face: f,
                message: "the face has fewer than three distinct corners: it encloses no area"
                    .into(),
            });
        }
        rings.push(ring);
    }
    Ok((points, rings))
}

/// Each ring with the welded points lying on its edges (within `tol`, strictly between the
/// edge's ends) inserted in order along the edge.
fn split_edges(points: &[Vec3], rings: Vec<Vec<usize>>, tol: f64) -> Vec<Vec<usize>> {
    rings
        .into_iter()
        .map(|ring| {
            let n = ring.len();
            let mut out = Vec::with_capacity(n);
            for k in 0..n {
                let (a, b) = (ring[k], ring[(k + 1) % n]);
                out.push(a);
                let (pa, pb) = (points[a], points[b]);
                let along = pb - pa;
                let length = along.length();
                let mut on: Vec<(f64, usize)> = (0..points.len())
                    .filter(|&i| i != a && i != b)
                    .filter_map(|i| {
                        let s = (points[i] - pa).dot(along) / length;
                        let off = (points[i] - pa - along * (s / length)).length();
                        (s > tol && s < length - tol && off <= tol).then_some((s, i))
                    })
                    .collect();
                on.sort_by(|x, y| x.0.total_cmp(&y.0));
                out.extend(on.into_iter().map(|(_, i)| i));
            }
            out
        })
        .collect()
}

/// Per undirected edge (smaller index first), the faces running along it and whether each
/// runs from the smaller index to the larger; in a fixed order, for deterministic messages.
type Edges = BTreeMap<(usize, usize), Vec<(usize, bool)>>;

fn edge_users(rings: &[Vec<usize>]) -> Edges {
    let mut edges: Edges = BTreeMap::new();
    for (f, ring) in rings.iter().enumerate() {
        let n = ring.len();
        for k in 0..n {
            let (a, b) = (ring[k], ring[(k + 1) % n]);
            edges
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push((f, a < b));
        }
    }
    edges
}

/// Whether each face keeps its winding (`true`) or is reversed, for the faces to run along
/// every shared edge in opposite directions, starting from the first face as written. The
/// faces must form one connected shell that can be oriented (every edge has two users).
fn orient(
    faces: &[InputFace],
    rings: &[Vec<usize>],
    edges: &Edges,
) -> Result<Vec<bool>, ShellError> {
    // Per face, its neighbours across each edge and whether they run the same way.
    let mut across: Vec<Vec<(usize, bool)>> = vec![Vec::new(); rings.len()];
    for users in edges.values() {
        if let &[(f, df), (g, dg)] = users.as_slice() {
            across[f].push((g, df == dg));
            across[g].push((f, df == dg));
        }
    }
    let mut keep: Vec<Option<bool>> = vec![None; rings.len()];
    keep[0] = Some(true);
    let mut queue = vec![0usize];
    while let Some(f) = queue.pop() {
        let kf = keep[f].unwrap_or(true);
        for &(g, same) in &across[f] {
            // Running the same way as its neighbour, a face must be reversed relative to it.
            let want = if same { !kf } else { kf };
            match keep[g] {
                None => {
                    keep[g] = Some(want);
                    queue.push(g);
                }
                Some(k) if k != want => {
                    return Err(ShellError {
                        face: g,
                        message: format!(
                            "the faces around it cannot all be wound one way (the shell twists \
                             through it and {}): it is not the surface of one room",
                            faces[f].label
                        ),
                    })
                }
                Some(_) => {}
            }
        }
    }
    if let Some(g) = keep.iter().position(Option::is_none) {
        return Err(ShellError {
            face: g,
            message: format!(
                "the face is not connected to {} through shared edges: the file holds more than \
                 one closed surface; an OBJ room is one (put furniture in another `[[obj]]`)",
                faces[0].label
            ),
        });
    }
    Ok(keep.into_iter().map(|k| k.unwrap_or(true)).collect())
}

/// The signed volume (m³) of the cone from the shell's first corner over the face `ring`,
/// positive when the face's normal points away from that corner. Summed over a closed shell
/// it is the volume enclosed, negative when the normals point inwards.
fn signed_volume(points: &[Vec3], ring: &[usize]) -> f64 {
    let at = |k: usize| points[ring[k]] - points[0];
    (1..ring.len() - 1)
        .map(|k| at(0).dot(at(k).cross(at(k + 1))) / 6.0)
        .sum()
}
