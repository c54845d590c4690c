//! The surfaces of a scene meshed into patches: each surface's material resolved, its faces
//! checked and cut into patches, and the patches cut along the footprints of OBJ objects
//! standing on them.

use std::collections::BTreeMap;

use super::{check_face, mesh_face, triangulate, FaceProblem};
use crate::geometry::{Face, Patch, Polygon};
use crate::scene::contacts::{self, Footprint};
use crate::scene::context::{MaterialInfo, RawSurface};
use crate::scene::error::SceneError;
use crate::scene::Surface;

/// The surfaces meshed into patches, with what each patch takes from its material.
pub(crate) struct Meshed {
    pub surfaces: Vec<Surface>,
    pub patches: Vec<Patch>,
    pub faces: Vec<Face>,
    /// Per patch, per band.
    pub reflectance: Vec<Vec<f64>>,
    /// Per surface, its material's exitance per band (lux or W/m²).
    pub material_emission: Vec<Vec<f64>>,
}

/// Resolves each surface's material, checks its faces (flat within `planarity`) and meshes
/// them into patches no longer than `max_edge` (m) or the surface's own, cut along the
/// `footprints` of OBJ objects standing on them.
pub(crate) fn mesh_surfaces(
    raw: &[RawSurface],
    materials: &BTreeMap<String, MaterialInfo>,
    flip: &[bool],
    split: &[bool],
    footprints: &[Footprint],
    max_edge: f64,
    planarity: f64,
) -> Result<Meshed, SceneError> {
    let mut surfaces = Vec::with_capacity(raw.len());
    let mut patches = Vec::new();
    let mut faces = Vec::new();
    let mut reflectance = Vec::new();
    let mut material_emission = Vec::with_capacity(raw.len());
    for (index, s) in raw.iter().enumerate() {
        let material = s.material_in(materials)?;
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
            let bad = |p: FaceProblem| SceneError::BadFace {
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
            let standing: Vec<&Footprint> = footprints
                .iter()
                .filter(|fp| fp.surface == index && fp.face == f)
                .collect();
            for piece in pieces {
                check_face(&piece, planarity).map_err(bad)?;
                let first = patches.len() + polygons.len();
                let mut grid = Vec::new();
                mesh_face(&piece, edge, &mut grid);
                for footprint in &standing {
                    grid = grid
                        .into_iter()
                        .flat_map(|p| {
                            let normal = p.normal();
                            contacts::cut(&p.vertices, footprint, normal)
                        })
                        .map(Polygon::new)
                        .collect();
                }
                polygons.extend(grid);
                faces.push(Face {
                    polygon: Polygon::new(piece),
                    patches: first..patches.len() + polygons.len(),
                });
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
    Ok(Meshed {
        surfaces,
        patches,
        faces,
        reflectance,
        material_emission,
    })
}
