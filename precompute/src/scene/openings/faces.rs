//! One room's faces: where each opening and footprint lies, checked against the face and
//! the others, and each face cut around them, on a grid of the openings' edges or by a
//! polygon difference ([`super::polygon`]).

use std::ops::Range;

use super::frame::{grid, snap, Frame};
use super::{polygon, Placed};
use crate::geometry::{Polygon, Vec3};
use crate::scene::context::RawSurface;
use crate::scene::error::{Location, SceneError};
use crate::scene::room::{FaceKind, Point2, Room as RoomShape};

/// One room's faces and where its `openings` list was written, for the messages.
pub(super) struct Room {
    pub(super) at: Location,
    pub(super) field: String,
    /// The room's surfaces in the raw surfaces.
    pub(super) faces: Range<usize>,
    /// The surfaces cut on a grid (indices into the raw surfaces): every face of a box, the
    /// walls of a plan room.
    pub(super) hosts: Vec<usize>,
    /// Their rectangles.
    pub(super) frames: Vec<Frame>,
    /// [`super::CONTACT_TOLERANCE`] of the room's diagonal, metres.
    pub(super) tol: f64,
}

impl Room {
    /// An error about the room's `openings`.
    pub(super) fn invalid(&self, message: String) -> SceneError {
        SceneError::Invalid {
            at: self.at.clone(),
            field: self.field.clone(),
            message,
        }
    }

    /// The face whose plane holds every corner of `quad` most nearly, and the farthest
    /// corner's distance from it (m).
    pub(super) fn nearest_face(&self, quad: &[Vec3]) -> (usize, f64) {
        let distance = |f: &Frame| {
            quad.iter()
                .map(|&p| (p - f.a).dot(f.normal).abs())
                .fold(0.0, f64::max)
        };
        self.frames
            .iter()
            .enumerate()
            .map(|(k, f)| (k, distance(f)))
            .fold(
                (0, f64::INFINITY),
                |best, x| if x.1 < best.1 { x } else { best },
            )
    }

    /// In a plan room, the opening `name` lying in the floor or the ceiling: which, and its
    /// corners in plan (m); `None` when it lies in neither (it must then be in a wall). The
    /// opening must be one convex quadrilateral facing into the room.
    pub(super) fn in_plan_face(
        &self,
        shape: &RoomShape,
        name: &str,
        raw: &[RawSurface],
        flip: &[bool],
        claimed: &mut [bool],
    ) -> Result<Option<(FaceKind, Vec<Point2>)>, SceneError> {
        let Some(index) = raw.iter().position(|s| s.name == name) else {
            return Ok(None); // `place` names the unknown surface
        };
        let [quad] = raw[index].faces.as_slice() else {
            return Ok(None);
        };
        let Some(face) = shape.face_holding(quad) else {
            return Ok(None);
        };
        if !matches!(
            face.kind,
            FaceKind::Floor | FaceKind::Ceiling | FaceKind::CeilingPlane { .. }
        ) {
            return Ok(None);
        }
        if self.faces.contains(&index) || claimed[index] {
            return Err(self.invalid(format!(
                "`{name}` cannot be an opening here: it is a face of a room or already an opening"
            )));
        }
        claimed[index] = true;
        let face_name = format!("{}.{}", shape.name, face.suffix);
        let mut winding = quad.clone();
        if flip[index] {
            winding.reverse();
        }
        if Polygon::new(winding).normal().dot(shape.inward(face)) <= 0.0 {
            return Err(self.invalid(format!(
                "opening `{name}` faces out of the room (its normal is opposite to the inward \
                 normal of face `{face_name}`): list its corners in the opposite order"
            )));
        }
        let tol = shape.tolerance();
        if let Some(problem) = polygon::problem(name, quad, tol) {
            return Err(self.invalid(problem));
        }
        if let Some(p) = quad.iter().find(|p| !shape.plan.holds([p.x, p.y], tol)) {
            return Err(self.invalid(format!(
                "opening `{name}` reaches outside face `{face_name}` (its corner {:?} is \
                 outside the plan)",
                p.to_array()
            )));
        }
        Ok(Some((face.kind, quad.iter().map(|p| [p.x, p.y]).collect())))
    }

    /// Places the opening `name` (a surface of `raw`, marked in `claimed`) in the face it lies
    /// in, checked against the openings `placed` before it.
    pub(super) fn place(
        &self,
        name: &str,
        raw: &[RawSurface],
        flip: &[bool],
        claimed: &mut [bool],
        placed: &[Placed],
    ) -> Result<Placed, SceneError> {
        let Some(index) = raw.iter().position(|s| s.name == name) else {
            return Err(SceneError::Unknown {
                at: self.at.clone(),
                field: self.field.clone(),
                kind: "surface",
                name: name.to_owned(),
            });
        };
        if self.faces.contains(&index) || claimed[index] {
            return Err(self.invalid(format!(
                "`{name}` cannot be an opening here: it is a face of a room or already an opening"
            )));
        }
        claimed[index] = true;
        let quad = match raw[index].faces.as_slice() {
            [q] => q.clone(),
            _ => {
                return Err(self.invalid(format!(
                    "opening `{name}` must be one polygon (a [[quad]] or a [[polygon]]), found \
                     {} face(s)",
                    raw[index].faces.len()
                )))
            }
        };
        if let Some(problem) = polygon::problem(name, &quad, self.tol) {
            return Err(self.invalid(problem));
        }
        let (face, nearest) = self.nearest_face(&quad);
        let face_name = &raw[self.hosts[face]].name;
        let tol = self.tol;
        if nearest > tol {
            return Err(self.invalid(format!(
                "opening `{name}` is not in a face of the room: its corners are up to \
                 {nearest:.3e} m from the plane of the nearest face `{face_name}` (tolerance \
                 {tol:.1e} m)"
            )));
        }
        let frame = &self.frames[face];
        let mut opening = match self.rectangle(name, index, face, face_name, &quad)? {
            Some(rectangle) => rectangle,
            None => self.polygon(name, index, face, face_name, &quad)?,
        };
        let mut winding = quad.clone();
        if flip[index] {
            winding.reverse();
        }
        let facing = Polygon::new(winding).normal().dot(frame.normal);
        if facing <= 0.0 {
            return Err(self.invalid(format!(
                "opening `{name}` faces out of the room (its normal is opposite to the inward \
                 normal of face `{face_name}`): list its corners in the opposite order"
            )));
        }
        opening.s = [opening.s[0].max(0.0), opening.s[1].min(1.0)];
        opening.t = [opening.t[0].max(0.0), opening.t[1].min(1.0)];
        for other in placed.iter().filter(|o| o.face == face) {
            if opening.overlaps(other, frame, tol) {
                return Err(self.invalid(format!(
                    "openings `{}` and `{name}` overlap in face `{face_name}`",
                    other.surface.map_or("?", |o| raw[o].name.as_str())
                )));
            }
        }
        Ok(opening)
    }

    /// The opening `name` (surface `index` of the raw surfaces, corners `quad`) in face `face`
    /// (named `face_name`) as a rectangle with sides along the face's edges, before clamping
    /// to the face; `None` when it is no such rectangle, an error when it is one of zero
    /// width or reaching outside the face.
    fn rectangle(
        &self,
        name: &str,
        index: usize,
        face: usize,
        face_name: &str,
        quad: &[Vec3],
    ) -> Result<Option<Placed>, SceneError> {
        let frame = &self.frames[face];
        let st: Vec<(f64, f64)> = quad.iter().map(|&p| frame.params(p)).collect();
        let tol_s = self.tol / frame.ab.length();
        let tol_t = self.tol / frame.ad.length();
        let s = [
            st.iter().map(|p| p.0).fold(f64::INFINITY, f64::min),
            st.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max),
        ];
        let t = [
            st.iter().map(|p| p.1).fold(f64::INFINITY, f64::min),
            st.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max),
        ];
        if quad.len() != 4 {
            return Ok(None);
        }
        let mut upper = Vec::with_capacity(4);
        for &(cs, ct) in &st {
            let us = (cs - s[1]).abs() <= tol_s;
            let ut = (ct - t[1]).abs() <= tol_t;
            let on_s = us || (cs - s[0]).abs() <= tol_s;
            let on_t = ut || (ct - t[0]).abs() <= tol_t;
            if !(on_s && on_t) {
                return Ok(None);
            }
            upper.push((us, ut));
        }
        let mut kinds = upper.clone();
        kinds.sort_unstable();
        kinds.dedup();
        if kinds.len() != 4 {
            return Ok(None);
        }
        if s[1] - s[0] <= tol_s || t[1] - t[0] <= tol_t {
            return Err(self.invalid(format!(
                "opening `{name}` has zero width in face `{face_name}`"
            )));
        }
        let outside = s[0] < -tol_s || t[0] < -tol_t || s[1] > 1.0 + tol_s || t[1] > 1.0 + tol_t;
        if outside || quad.iter().any(|&p| !frame.holds(p, self.tol)) {
            return Err(self.invalid(format!(
                "opening `{name}` reaches outside face `{face_name}`"
            )));
        }
        Ok(Some(Placed {
            surface: Some(index),
            face,
            s,
            t,
            upper,
            outline: None,
        }))
    }

    /// The opening `name` (surface `index` of the raw surfaces, corners `corners`, a checked
    /// convex polygon) in face `face` (named `face_name`) as a polygon; an error when it
    /// reaches outside the face.
    fn polygon(
        &self,
        name: &str,
        index: usize,
        face: usize,
        face_name: &str,
        corners: &[Vec3],
    ) -> Result<Placed, SceneError> {
        let frame = &self.frames[face];
        if let Some(p) = corners.iter().find(|&&p| !frame.holds(p, self.tol)) {
            return Err(self.invalid(format!(
                "opening `{name}` reaches outside face `{face_name}` (its corner {:?})",
                p.to_array()
            )));
        }
        let st: Vec<(f64, f64)> = corners.iter().map(|&p| frame.params(p)).collect();
        let bounds = |along: fn(&(f64, f64)) -> f64| {
            [
                st.iter().map(along).fold(f64::INFINITY, f64::min),
                st.iter().map(along).fold(f64::NEG_INFINITY, f64::max),
            ]
        };
        Ok(Placed {
            surface: Some(index),
            face,
            s: bounds(|p| p.0),
            t: bounds(|p| p.1),
            upper: Vec::new(),
            outline: Some(corners.iter().map(|&p| frame.to_plane(p)).collect()),
        })
    }

    /// Blocks standing on the floor without a bottom face (`face` 0), or reaching the ceiling
    /// without a top face (`face` 1), hide the face under them: their footprints are cut out
    /// too (they may overlap each other, not an opening).
    pub(super) fn place_footprints(
        &self,
        standing: &[(String, Vec3, Vec3)],
        face: usize,
        raw: &[RawSurface],
        placed: &mut Vec<Placed>,
    ) -> Result<(), SceneError> {
        let tol = self.tol;
        let floor = &self.frames[face];
        for (name, lo, hi) in standing {
            let end = if face == 0 { lo.z } else { hi.z };
            if (end - floor.a.z).abs() > tol {
                continue;
            }
            let (s0, t0) = floor.params(*lo);
            let (s1, t1) = floor.params(*hi);
            let s = [s0.min(s1).max(0.0), s0.max(s1).min(1.0)];
            let t = [t0.min(t1).max(0.0), t0.max(t1).min(1.0)];
            if s[1] <= s[0] || t[1] <= t[0] {
                continue;
            }
            let footprint = Placed {
                surface: None,
                face,
                s,
                t,
                upper: Vec::new(),
                outline: None,
            };
            for other in placed.iter().filter(|o| o.face == face) {
                if let (Some(o), true) = (other.surface, footprint.overlaps(other, floor, tol)) {
                    return Err(self.invalid(format!(
                        "opening `{}` lies under block `{name}`, which stands on it",
                        raw[o].name
                    )));
                }
            }
            placed.push(footprint);
        }
        Ok(())
    }

    /// Cuts face `k` into the grid of its openings' edges, snaps the openings onto it and
    /// keeps the cells no opening covers as the face's new faces.
    pub(super) fn cut_face(
        &self,
        k: usize,
        raw: &mut [RawSurface],
        placed: &mut [Placed],
    ) -> Result<(), SceneError> {
        let frame = &self.frames[k];
        let mine: Vec<&mut Placed> = placed.iter_mut().filter(|p| p.face == k).collect();
        if mine.is_empty() {
            return Ok(());
        }
        let face = self.hosts[k];
        if mine.iter().any(|p| p.outline.is_some()) {
            return self.cut_around(k, raw, &mine);
        }
        let tol_s = self.tol / frame.ab.length();
        let tol_t = self.tol / frame.ad.length();
        let grid_s = grid(mine.iter().flat_map(|p| p.s), tol_s);
        let grid_t = grid(mine.iter().flat_map(|p| p.t), tol_t);
        let mut mine = mine;
        for p in mine.iter_mut() {
            p.s = p.s.map(|x| snap(&grid_s, x));
            p.t = p.t.map(|x| snap(&grid_t, x));
            if let Some(surface) = p.surface {
                let corners = p
                    .upper
                    .iter()
                    .map(|&(us, ut)| frame.point(p.s[us as usize], p.t[ut as usize]))
                    .collect();
                raw[surface].faces = vec![corners];
            }
        }
        let mut cells = Vec::new();
        for j in 0..grid_t.len() - 1 {
            for i in 0..grid_s.len() - 1 {
                let (s0, s1, t0, t1) = (grid_s[i], grid_s[i + 1], grid_t[j], grid_t[j + 1]);
                let (sm, tm) = (0.5 * (s0 + s1), 0.5 * (t0 + t1));
                let covered = mine
                    .iter()
                    .any(|p| p.s[0] < sm && sm < p.s[1] && p.t[0] < tm && tm < p.t[1]);
                if !covered {
                    let cell = frame.clip(
                        vec![
                            frame.point(s0, t0),
                            frame.point(s1, t0),
                            frame.point(s1, t1),
                            frame.point(s0, t1),
                        ],
                        self.tol,
                    );
                    if !cell.is_empty() {
                        cells.push(cell);
                    }
                }
            }
        }
        if cells.is_empty() {
            return Err(self.invalid(format!(
                "the openings (or blocks standing on it) cover the whole face `{}`; leave them \
                 out and give the face their material in [surfaces] instead",
                raw[face].name
            )));
        }
        raw[face].faces = cells;
        Ok(())
    }

    /// Cuts face `k`, which holds an opening that is not a rectangle along its edges, around
    /// its openings and footprints `mine` by a polygon difference ([`polygon::cut_around`]);
    /// sets each opening's corners into the face's plane exactly, as the cut sees them.
    fn cut_around(
        &self,
        k: usize,
        raw: &mut [RawSurface],
        mine: &[&mut Placed],
    ) -> Result<(), SceneError> {
        let frame = &self.frames[k];
        let face = self.hosts[k];
        let holes: Vec<Vec<Point2>> = mine.iter().map(|p| p.in_plane(frame)).collect();
        for (p, hole) in mine.iter().zip(&holes) {
            if let Some(surface) = p.surface {
                raw[surface].faces = vec![hole.iter().map(|&q| frame.point_in_plane(q)).collect()];
            }
        }
        let pieces = polygon::cut_around(frame, &holes, self.tol).map_err(|problem| {
            self.invalid(format!(
                "face `{}` cannot be cut around its openings: {problem}",
                raw[face].name
            ))
        })?;
        if pieces.is_empty() {
            return Err(self.invalid(format!(
                "the openings (or blocks standing on it) cover the whole face `{}`; leave them \
                 out and give the face their material in [surfaces] instead",
                raw[face].name
            )));
        }
        raw[face].faces = pieces;
        Ok(())
    }
}
