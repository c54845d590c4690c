//! What a basis stores for the controller to compute the sun's first reflection at the sun's
//! own direction (docs/format.md, "The sun's first reflection"; `eigenrad_runtime::sky::
//! sun_first`): the patches the sun can light directly, each as its polygon, every
//! reading's response to each, and the sun directions their shadows are culled with.

use eigenrad_runtime::sky::sun_first::MAX_CORNERS;
use eigenrad_runtime::sky::sun_grid::{direction_of, SunGrid};

use faer::Mat;

use rayon::prelude::*;

use super::nodes::room_sun;
use super::{sun_light, DaylightOptions};
use crate::formfactor::outputs::zone_area;
use crate::formfactor::Occluders;
use crate::geometry::{Patch, Vec3};
use crate::radiosity::eigen::EigenError;
use crate::radiosity::System;
use crate::scene::{Scene, Site, ZoneKind};

/// The candidates' tables, as [`eigenrad_runtime::writer::BasisTables`] holds them, and
/// points on them for the occluders' culling.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SunFirstTables {
    /// The candidate patches, ascending.
    pub patches: Vec<u32>,
    /// Each candidate's corners.
    pub sizes: Vec<u8>,
    /// Per candidate: unit normal, then its corners (m).
    pub points: Vec<f64>,
    /// Points of every candidate (its corners, its centroid and the centroids of the
    /// triangles the centroid fans it into), candidate by candidate.
    pub sample_points: Vec<Vec3>,
}

/// The candidates among `patches`: those `lit` says the sun lights at some stored node (a
/// non-zero initial exitance there) and that reflect, each stored as its polygon, whose
/// sunlit part the controller clips (`eigenrad_runtime::sky::sunlit`). A patch with more
/// corners than [`MAX_CORNERS`] (meshing makes triangles and quadrilaterals) is left out.
pub fn sun_first_tables(patches: &[Patch], lit: impl Fn(usize) -> bool) -> SunFirstTables {
    let mut t = SunFirstTables::default();
    for (i, p) in patches.iter().enumerate().filter(|&(i, _)| lit(i)) {
        let corners = &p.polygon.vertices;
        let n = corners.len();
        if !(3..=usize::from(MAX_CORNERS)).contains(&n) {
            continue;
        }
        t.patches.push(i as u32);
        t.sizes.push(n as u8);
        t.points.extend(p.normal.to_array());
        for c in corners {
            t.points.extend(c.to_array());
        }
        t.sample_points.extend(culling_points(p));
    }
    t
}

/// Points of a patch its occluders are culled with: its corners, its centroid and the
/// centroids of the triangles its centroid fans it into.
pub fn culling_points(p: &Patch) -> impl Iterator<Item = Vec3> + '_ {
    let corners = &p.polygon.vertices;
    let n = corners.len();
    corners
        .iter()
        .copied()
        .chain(std::iter::once(p.centroid))
        .chain((0..n).map(move |k| (p.centroid + corners[k] + corners[(k + 1) % n]) * (1.0 / 3.0)))
}

/// The sun directions (room frame) the candidates' occluders are culled with: every stored
/// node's and the centre of every cell with a stored corner, where the controller reads the
/// sun between nodes.
pub fn culling_suns(site: &Site, grid: &SunGrid, stored: &[u32]) -> Vec<Vec3> {
    let mut suns = Vec::new();
    for &node in stored {
        let node = node as usize;
        let Some((declination, hour)) = grid.angles(node) else {
            continue;
        };
        for (dd, dh) in [
            (0.0, 0.0),
            (0.5, 0.5),
            (-0.5, 0.5),
            (0.5, -0.5),
            (-0.5, -0.5),
        ] {
            let d = direction_of(
                grid.latitude,
                declination + dd * grid.declination_step,
                hour + dh * grid.hour_step,
            );
            suns.extend(room_sun(site, d));
        }
    }
    suns
}

/// Every reading's response to a unit of each candidate's first reflection, candidate by
/// candidate (`readings` values each: the sensors, zones and grid points of `system`'s first
/// output rows), lux per lux: `T_oj`, the reading's whole response to exitance `M0_j` on
/// patch `j` alone, `[R_o (I − R F)⁻¹]_j` (its view of the patch and everything the room
/// reflects after it), plus, for a zone made of surfaces, `j`'s own irradiance in its
/// area-weighted mean, `A_j / (A_zone ρ_j)` per unit of `M0_j = ρ_j E_j`.
///
/// One solve per reading rather than one per candidate: with `B = A R⁻¹` (the candidates
/// reflect), `B (I − R F) = B − G` is symmetric, so `(I − R F)⁻ᵀ = B (I − R F)⁻¹ B⁻¹` and the
/// row `R_o (I − R F)⁻¹` is `B (I − R F)⁻¹ B⁻¹ R_oᵀ`: the exact solver of band 0 (daylight is
/// photopic) applied to `ρ_j R_oj / A_j`, then scaled by `A_j / ρ_j` (docs/math.md, "The
/// sun between the grid's nodes, part by part"). A black patch's row of `I − R F` is the
/// identity, and its entry of that right-hand side is 0, as the transpose needs.
pub fn sun_first_responses(
    scene: &Scene,
    system: &System,
    candidates: &[u32],
    readings: usize,
) -> Result<Vec<f64>, EigenError> {
    let rows = &system.output_rows;
    let (area, rho) = (&system.area, &system.reflectance[0]);
    let n = area.len();
    if candidates.is_empty() || rows.len() < readings {
        return Ok(Vec::new());
    }
    let rhs = Mat::<f64>::from_fn(n, readings, |j, o| rho[j] * rows[o][j] / area[j]);
    let x = system.solver(0)?.solve_many(rhs.as_ref());
    let width = readings;
    let mut response = Vec::with_capacity(candidates.len() * width);
    for &j in candidates {
        let j = j as usize;
        response.extend((0..width).map(|o| area[j] * x[(j, o)] / rho[j]));
    }
    let sensors = scene.sensors.len();
    for (z, zone) in scene.zones.iter().enumerate() {
        let ZoneKind::Surfaces(members) = &zone.kind else {
            continue;
        };
        let zone_area = zone_area(scene, zone);
        for (k, &j) in candidates.iter().enumerate() {
            let j = j as usize;
            if zone_area > 0.0 && members.contains(&j) {
                response[k * width + sensors + z] += area[j] / (zone_area * rho[j]);
            }
        }
    }
    Ok(response)
}

/// The patches the sun lights directly at the centre of some cell of `grid` (every cell
/// whose centre is above the horizon), by the exact sun (`sun_light`): with the nodes' own,
/// the candidates. A patch lit between the nodes alone (the sun peeping over an
/// obstruction's roof where every corner of the cell is hidden) is then computed at the sun
/// like the others rather than missed.
pub fn lit_between_nodes(
    scene: &Scene,
    occluders: &Occluders,
    site: &Site,
    grid: &SunGrid,
    opts: &DaylightOptions,
) -> Vec<bool> {
    let cells: Vec<Vec3> = (0..grid.rows.saturating_sub(1))
        .flat_map(|row| (0..grid.columns.saturating_sub(1)).map(move |column| (row, column)))
        .filter_map(|(row, column)| {
            let (declination, hour) = grid.angles(row * grid.columns + column)?;
            let centre = direction_of(
                grid.latitude,
                declination + 0.5 * grid.declination_step,
                hour + 0.5 * grid.hour_step,
            );
            room_sun(site, centre)
        })
        .collect();
    let lit: Vec<Vec<bool>> = cells
        .par_iter()
        .map(|&sun| {
            let light = sun_light(scene, occluders, sun, opts);
            let band = light.patch_irradiance.first();
            (0..scene.patches.len())
                .map(|i| band.is_some_and(|b| b[i] > 0.0))
                .collect()
        })
        .collect();
    (0..scene.patches.len())
        .map(|i| lit.iter().any(|l| l[i]))
        .collect()
}

/// Per zone, the polygons the controller computes its direct sun on: a work plane's
/// receivers (each of at most [`MAX_CORNERS`] corners), none for other zones (a zone of
/// surfaces has its direct sun in its candidates' responses, an imported grid's is
/// interpolated).
pub fn zone_sun_tables(scene: &Scene) -> ZoneSunTables {
    let mut t = ZoneSunTables::default();
    for zone in &scene.zones {
        let ZoneKind::WorkPlane { receivers, .. } = &zone.kind else {
            t.counts.push(0);
            continue;
        };
        let kept: Vec<&Patch> = receivers
            .iter()
            .filter(|r| (3..=usize::from(MAX_CORNERS)).contains(&r.polygon.vertices.len()))
            .collect();
        t.counts.push(kept.len() as u32);
        for r in kept {
            t.sizes.push(r.polygon.vertices.len() as u8);
            t.polygons.extend(r.normal.to_array());
            for c in &r.polygon.vertices {
                t.polygons.extend(c.to_array());
            }
            t.sample_points.extend(culling_points(r));
        }
    }
    t
}

/// The zones' polygons, as [`eigenrad_runtime::writer::BasisTables`] holds them
/// (`zone_sun_counts`, `zone_sun_sizes`, `zone_sun_polygons`), and points on them for the
/// occluders' culling.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ZoneSunTables {
    /// Polygons per zone.
    pub counts: Vec<u32>,
    /// Each polygon's corners.
    pub sizes: Vec<u8>,
    /// Per polygon: unit normal, then its corners (m).
    pub polygons: Vec<f64>,
    /// Points of every polygon.
    pub sample_points: Vec<Vec3>,
}
