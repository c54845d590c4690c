//! Faces wound against their neighbours in an OBJ file.
//!
//! Two faces of one consistently oriented surface run along a shared edge in opposite
//! directions. If a face runs the same way as its neighbours along most of the edges it shares
//! (each shared by exactly two faces), that face faces the wrong way: inside a closed object,
//! or out of a room. This is what can be detected without guessing which side is "out": a
//! whole object wound inside-out is consistent and is not reported (set `flip` for it).

use std::collections::HashMap;

use super::context::RawSurface;
use super::error::SceneError;
use crate::geometry::Vec3;

type Key = [u64; 3];

fn key(p: Vec3) -> Key {
    // +0.0 and −0.0 are the same corner.
    [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits)
}

/// Checks the faces of `surfaces` (one OBJ file's, `flip` already known per surface) for a
/// face wound against its neighbours.
pub(crate) fn check(surfaces: &[RawSurface], flip: &[bool]) -> Result<(), SceneError> {
    // (surface, face) of every face, and per undirected edge the faces using it with their
    // direction (true: from the smaller key to the larger).
    let mut faces: Vec<(usize, usize)> = Vec::new();
    let mut edges: HashMap<(Key, Key), Vec<(usize, bool)>> = HashMap::new();
    for (s, surface) in surfaces.iter().enumerate() {
        for (f, corners) in surface.faces.iter().enumerate() {
            let id = faces.len();
            faces.push((s, f));
            let n = corners.len();
            for i in 0..n {
                let (a, b) = (key(corners[i]), key(corners[(i + 1) % n]));
                if a == b {
                    continue;
                }
                let forward = (a < b) != flip[s];
                edges
                    .entry((a.min(b), a.max(b)))
                    .or_default()
                    .push((id, forward));
            }
        }
    }
    // Per face: shared edges run against the neighbour (good) and along it (bad).
    let mut good = vec![0usize; faces.len()];
    let mut bad = vec![0usize; faces.len()];
    for users in edges.values() {
        if let [(f, df), (g, dg)] = users.as_slice() {
            if f == g {
                continue;
            }
            let counts = if df == dg { &mut bad } else { &mut good };
            counts[*f] += 1;
            counts[*g] += 1;
        }
    }
    for (id, &(s, f)) in faces.iter().enumerate() {
        if bad[id] >= 2 && bad[id] > good[id] {
            let surface = &surfaces[s];
            return Err(SceneError::BadFace {
                at: surface.at.clone(),
                surface: surface.name.clone(),
                face: f + 1,
                message: format!(
                    "the face is wound against its neighbours ({} of its shared edges run the \
                     same way as the neighbouring face's, {} the opposite way): it faces the \
                     wrong way (inside its object, or out of its room); reverse its corners in \
                     the file",
                    bad[id], good[id]
                ),
            });
        }
    }
    Ok(())
}
