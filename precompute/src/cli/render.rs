//! `eigenrad render`: false-colour pictures of a scene, from its exact solve (as `solve`
//! computes it, through the form-factor cache) or from a basis built from it, evaluated
//! through the runtime (as `eval` reads it: what the controller would see).
//!
//! The scene is always read, for the geometry: a basis holds its patches' centroids and
//! areas and its grid points, but not the patches' outlines nor the room's, so the surfaces
//! and the room's outline come from the scene, and a basis must match it (the same patches
//! and grid points).

use std::path::Path;

use crate::error::{Error, Result};
use crate::formfactor::FormFactorOptions;
use crate::geometry::Vec3;
use crate::picture::{Format, Net, NetInput, NetPatch, Plan, PlanInput};
use crate::pipeline::GridReadout;
use crate::scene::{self, Scene, ZoneKind};

use super::levels::LevelArgs;
use super::readout::{self, DaylightArgs, Readout};
use super::units::{readout_in, Units};

/// What colours the surfaces.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SurfaceQuantity {
    /// Irradiance E arriving at each patch: lux (or fc), W/m² per band.
    #[default]
    Illuminance,
    /// Luminance L = M/π of each patch (diffuse): cd/m², or W/(m²·sr) per band.
    Luminance,
}

/// What `eigenrad render` is asked for.
#[derive(Clone, Debug)]
pub struct RenderRequest<'a> {
    /// The scene file.
    pub scene: &'a Path,
    /// A basis built from it (its path and bytes), to evaluate through the runtime instead
    /// of solving the scene.
    pub basis: Option<(&'a Path, &'a [u8])>,
    /// Channel levels, as `eval` and `solve` take them.
    pub levels: &'a LevelArgs,
    /// Unit of illuminance (luminance stays in cd/m²).
    pub units: Units,
    /// The work-plane zone of the plan; `None`: the scene's only one.
    pub zone: Option<&'a str>,
    /// Draw the plan.
    pub plan: bool,
    /// Draw the surfaces, coloured by this.
    pub surfaces: Option<SurfaceQuantity>,
    /// Form-factor settings, progress and cache of the exact solve.
    pub form_factors: &'a FormFactorOptions,
    /// Daylight at a time under a sky, as `solve --time` (or with a basis `eval --time`)
    /// takes it.
    pub daylight: Option<&'a DaylightArgs>,
}

/// The pictures, ready to be drawn as PNG or SVG.
#[derive(Clone, Debug)]
pub struct Pictures {
    /// The plan of the work plane, when asked for.
    pub plan: Option<Plan>,
    /// The surfaces, when asked for.
    pub surfaces: Option<Net>,
    /// The readings they were drawn from, in the units asked for.
    pub readout: Readout,
}

impl Pictures {
    /// The plan as the bytes of a `format` file; `None` when it was not asked for.
    pub fn plan_file(&self, format: Format) -> Option<std::result::Result<Vec<u8>, String>> {
        let plan = self.plan.as_ref()?;
        Some(match format {
            Format::Png => plan.png().map(|(b, _)| b),
            Format::Svg => plan.svg().map(|(s, _)| s.into_bytes()),
        })
    }

    /// The surfaces as the bytes of a `format` file; `None` when they were not asked for.
    pub fn surfaces_file(&self, format: Format) -> Option<std::result::Result<Vec<u8>, String>> {
        let net = self.surfaces.as_ref()?;
        Some(match format {
            Format::Png => net.png().map(|(b, _)| b),
            Format::Svg => net.svg().map(|(s, _)| s.into_bytes()),
        })
    }
}

fn render_error(scene: &Path, reason: String) -> Error {
    Error::Render {
        scene: scene.to_path_buf(),
        reason,
    }
}

/// The work-plane zone the plan is of: `asked`, or the scene's only zone with a grid.
fn plan_zone<'s>(scene: &'s Scene, path: &Path, asked: Option<&str>) -> Result<&'s scene::Zone> {
    let grids: Vec<&scene::Zone> = scene.zones.iter().filter(|z| z.grid.is_some()).collect();
    let names = || {
        grids
            .iter()
            .map(|z| z.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    match asked {
        Some(name) => match scene.zones.iter().find(|z| z.name == name) {
            Some(z) if z.grid.is_some() => Ok(z),
            Some(_) => Err(render_error(
                path,
                format!(
                    "--zone {name}: zone `{name}` is a surface zone, without a calculation grid; a plan needs a work-plane zone ({})",
                    if grids.is_empty() { "the scene has none".into() } else { names() }
                ),
            )),
            None => Err(render_error(
                path,
                format!("--zone {name}: no zone named `{name}` (zones with a grid: {})", if grids.is_empty() { "none".into() } else { names() }),
            )),
        },
        None => match grids.as_slice() {
            [one] => Ok(one),
            [] => Err(render_error(
                path,
                "no work-plane zone: a plan needs a zone with `work_plane = { ... }` and its calculation grid (docs/scene.md, \"Zones\"); leave out --plan to draw the surfaces only".into(),
            )),
            _ => Err(render_error(
                path,
                format!("{} work-plane zones ({}): name the plan's with --zone", grids.len(), names()),
            )),
        },
    }
}

/// Checks that the basis at `path` was built from `scene`: the same patches (count and
/// centroids, to the basis' single precision) and the same grid points.
fn check_basis_matches(
    scene: &Scene,
    scene_path: &Path,
    basis_path: &Path,
    r: &Readout,
) -> Result<()> {
    let bad = |what: String| {
        render_error(
            scene_path,
            format!(
                "the basis {} was not built from this scene ({what}); rebuild it with `eigenrad build`",
                basis_path.display()
            ),
        )
    };
    // f32 holds a coordinate to 6e-8 of its size: 1e-5 m in a 100 m scene.
    let close = |a: [f64; 3], b: [f64; 3]| {
        a.iter()
            .zip(&b)
            .all(|(x, y)| (x - y).abs() <= 1e-6 * (1.0 + x.abs()) + 1e-5)
    };
    if let Some(patches) = &r.patches {
        if patches.len() != scene.patches.len() {
            return Err(bad(format!(
                "{} patches, the scene meshes into {}",
                patches.len(),
                scene.patches.len()
            )));
        }
        for (i, (p, q)) in patches.iter().zip(&scene.patches).enumerate() {
            if !close(p.centroid, q.centroid.to_array()) {
                return Err(bad(format!(
                    "patch {i} is centred at {:?} m, the scene's at {:?} m",
                    p.centroid,
                    q.centroid.to_array()
                )));
            }
        }
    }
    let scene_grids: Vec<&scene::Zone> = scene.zones.iter().filter(|z| z.grid.is_some()).collect();
    if scene_grids.len() != r.grids.len() {
        return Err(bad(format!(
            "{} calculation grids, the scene has {}",
            r.grids.len(),
            scene_grids.len()
        )));
    }
    for (z, g) in scene_grids.iter().zip(&r.grids) {
        let grid: Vec<Vec3> = z
            .grid
            .as_ref()
            .map_or_else(Vec::new, |g| g.points().map(|(p, _)| p).collect());
        if z.name != g.zone
            || grid.len() != g.points.len()
            || !grid
                .iter()
                .zip(&g.points)
                .all(|(a, b)| close(a.to_array(), b.position_m))
        {
            return Err(bad(format!("the grid of zone `{}` differs", z.name)));
        }
    }
    Ok(())
}

/// Bands summed: the one band of a photopic readout, the total over red, green and blue of a
/// radiometric one.
fn total(v: &[f64]) -> f64 {
    v.iter().sum()
}

/// `eigenrad render`: the readings of the scene (exact solve) or of the basis (runtime), and
/// the pictures asked for.
pub fn render(request: &RenderRequest<'_>) -> Result<Pictures> {
    let path = request.scene;
    let scene = scene::load(path)?;
    let zone = if request.plan {
        Some(plan_zone(&scene, path, request.zone)?)
    } else {
        None
    };
    let native = native_readout(request, &scene)?;
    let readout = readout_in(native.clone(), request.units)?;
    let notes = notes(request, &readout);
    let plan = match zone {
        None => None,
        Some(zone) => Some(plan_picture(&scene, path, zone, &readout, notes.clone())?),
    };
    let surfaces = request
        .surfaces
        .map(|quantity| surfaces_picture(&scene, quantity, &readout, &native, notes));
    Ok(Pictures {
        plan,
        surfaces,
        readout,
    })
}

/// The readings in the scene's or the basis' own units (lux or W/m²), with the patches when
/// the surfaces are drawn: the basis through the runtime, checked against the scene, or the
/// scene's exact solve.
fn native_readout(request: &RenderRequest<'_>, scene: &Scene) -> Result<Readout> {
    let path = request.scene;
    let patches = request.surfaces.is_some();
    match request.basis {
        Some((basis_path, _)) if request.daylight.is_some() && patches => {
            Err(render_error(
                path,
                format!(
                    "{} holds the daylight of its patches only through its modes, too coarse for a picture of the surfaces (docs/math.md, \"Daylight in the basis\"); leave out --basis to draw them from the exact solve",
                    basis_path.display()
                ),
            ))
        }
        Some((basis_path, bytes)) => {
            let r = readout::eval_with_daylight(
                basis_path,
                bytes,
                request.levels,
                request.daylight,
                patches,
            )?;
            check_basis_matches(scene, path, basis_path, &r)?;
            Ok(r)
        }
        None => readout::solve_with_daylight(
            path,
            request.levels,
            request.daylight,
            patches,
            request.form_factors,
        ),
    }
}

/// The lines under every picture's title: where the readings come from, the channels'
/// levels, the daylight's sky and, for several bands, how they were summed.
fn notes(request: &RenderRequest<'_>, readout: &Readout) -> Vec<String> {
    let rgb_note = (readout.bands.len() > 1)
        .then(|| "values: the sum of the red, green and blue bands".to_owned());
    let levels = format!(
        "levels: {}",
        readout
            .levels
            .iter()
            .map(|l| match l.arc {
                Some(arc) => format!("{}={} (arc {arc})", l.name, format_level(l.level)),
                None => format!("{}={}", l.name, format_level(l.level)),
            })
            .collect::<Vec<_>>()
            .join(", ")
    );
    let source = match request.basis {
        Some((b, _)) => format!(
            "the basis {} through the runtime, as `eval` (what the controller reads)",
            b.display()
        ),
        None => format!("the exact solve of {}, as `solve`", request.scene.display()),
    };
    let mut notes = vec![format!("from {source}"), levels];
    if let Some(d) = &readout.daylight {
        notes.push(format!(
            "daylight: {} at {}, sun {:.1}° up; diffuse horizontal {:.0} lux, direct normal {:.0} lux",
            d.model, d.time, d.sun.altitude, d.diffuse_horizontal_lux, d.direct_normal_lux
        ));
    }
    notes.extend(rgb_note);
    notes
}

/// The plan of `zone`'s work plane from the readings of its calculation grid (one piece),
/// with the room's outline and the luminaires seen from above.
fn plan_picture(
    scene: &Scene,
    path: &Path,
    zone: &scene::Zone,
    readout: &Readout,
    notes: Vec<String>,
) -> Result<Plan> {
    let grid = readout
        .grids
        .iter()
        .find(|g| g.zone == zone.name)
        .ok_or_else(|| render_error(path, format!("zone `{}` has no grid readings", zone.name)))?;
    let [piece] = grid.pieces[..] else {
        return Err(render_error(
            path,
            format!(
                "zone `{}`'s grid has {} pieces (the band around a task area): a plan \
                 draws a grid of one piece, a work plane or a task area",
                zone.name,
                grid.pieces.len()
            ),
        ));
    };
    let values: Vec<f64> = grid.points.iter().map(|p| total(&p.irradiance)).collect();
    let figures = plan_figures(grid, &values, readout.bands.len());
    let (height, floor) = match &zone.kind {
        ZoneKind::WorkPlane { height, receivers } => {
            (*height, receivers.first().map(|r| r.surface))
        }
        ZoneKind::Surfaces(_) => (f64::NAN, None),
    };
    Ok(Plan::new(PlanInput {
        title: format!(
            "{}: {} at {:.2} m above the floor, illuminance ({})",
            scene.name, zone.name, height, readout.unit
        ),
        notes,
        unit: readout.unit,
        counts: piece.counts,
        cell: piece.cell_m,
        border: piece.border_m,
        points: grid
            .points
            .iter()
            .map(|p| [p.position_m[0], p.position_m[1]])
            .collect(),
        values,
        room: room_outline(scene, floor, grid),
        floor: floor_patches(scene, floor),
        figures,
        luminaires: luminaire_outlines(scene),
        luminaire_points: scene
            .luminaires
            .iter()
            .map(|l| [l.position.x, l.position.y])
            .collect(),
    }))
}

/// `E_avg`, `E_min`, `E_max` and `U_o` of a plan's `values`: the grid's own for one band, of
/// the bands' sums for several.
fn plan_figures(grid: &GridReadout, values: &[f64], bands: usize) -> [f64; 4] {
    if bands == 1 {
        [
            grid.average[0],
            grid.minimum[0],
            grid.maximum[0],
            grid.uniformity[0],
        ]
    } else {
        match eigenrad_runtime::Figures::of(values.iter().copied()) {
            Some(f) => [f.average, f.minimum, f.maximum, f.uniformity],
            None => [f64::NAN; 4],
        }
    }
}

/// A rectangle in plan, `[[x_min, y_min], [x_max, y_max]]` (m); empty while `x_min > x_max`.
type Extent = [[f64; 2]; 2];

/// No rectangle yet: any point grows it.
const EMPTY: Extent = [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]];

/// `extent` grown to hold `p` seen from above.
fn grow(p: Vec3, extent: &mut Extent) {
    extent[0] = [extent[0][0].min(p.x), extent[0][1].min(p.y)];
    extent[1] = [extent[1][0].max(p.x), extent[1][1].max(p.y)];
}

/// The room's outline: its floor's extent (the work plane's receivers lie above it), or the
/// grid's when the work plane names no floor.
fn room_outline(scene: &Scene, floor: Option<usize>, grid: &GridReadout) -> Extent {
    let mut room = EMPTY;
    if let Some(f) = floor {
        for p in &scene.patches[scene.surfaces[f].patch_range.clone()] {
            for &v in &p.polygon.vertices {
                grow(v, &mut room);
            }
        }
    }
    if room[0][0] > room[1][0] || room[0][0].is_nan() {
        for p in &grid.points {
            grow(Vec3::new(p.position_m[0], p.position_m[1], 0.0), &mut room);
        }
    }
    room
}

/// The patches of the floor surface `floor` seen from above, m.
fn floor_patches(scene: &Scene, floor: Option<usize>) -> Vec<Vec<[f64; 2]>> {
    floor.map_or_else(Vec::new, |f| {
        scene.patches[scene.surfaces[f].patch_range.clone()]
            .iter()
            .map(|p| p.polygon.vertices.iter().map(|v| [v.x, v.y]).collect())
            .collect()
    })
}

/// Luminaires: each emitting surface's patches that face down, seen from above.
fn luminaire_outlines(scene: &Scene) -> Vec<Extent> {
    let mut luminaires = Vec::new();
    for channel in &scene.channels {
        for &s in &channel.surfaces {
            let mut r = EMPTY;
            for p in &scene.patches[scene.surfaces[s].patch_range.clone()] {
                if p.normal.z < -0.5 {
                    for &v in &p.polygon.vertices {
                        grow(v, &mut r);
                    }
                }
            }
            if r[0][0] <= r[1][0] {
                luminaires.push(r);
            }
        }
    }
    luminaires
}

/// The room's surfaces unfolded, each patch coloured by `quantity`: its irradiance in the
/// units asked for (`readout`), or its luminance from the exitance in the readings' own
/// units (`native`).
fn surfaces_picture(
    scene: &Scene,
    quantity: SurfaceQuantity,
    readout: &Readout,
    native: &Readout,
    notes: Vec<String>,
) -> Net {
    let converted = readout.patches.as_deref().unwrap_or_default();
    let raw = native.patches.as_deref().unwrap_or_default();
    let photometric = native.unit == "lux";
    let (unit, label) = match quantity {
        SurfaceQuantity::Illuminance => (readout.unit, "illuminance E"),
        SurfaceQuantity::Luminance if photometric => ("cd/m²", "luminance L = M/π"),
        SurfaceQuantity::Luminance => ("W/(m²·sr)", "radiance L = M/π"),
    };
    let patches = scene
        .patches
        .iter()
        .enumerate()
        .map(|(i, p)| NetPatch {
            vertices: p.polygon.vertices.iter().map(|v| v.to_array()).collect(),
            normal: p.normal.to_array(),
            value: match quantity {
                SurfaceQuantity::Illuminance => converted
                    .get(i)
                    .and_then(|r| r.irradiance.as_deref())
                    .map(total),
                SurfaceQuantity::Luminance => raw
                    .get(i)
                    .map(|r| total(&r.exitance) / std::f64::consts::PI),
            },
            emits: scene.emission[i].iter().any(|&e| e > 0.0),
        })
        .collect();
    Net::new(NetInput {
        title: format!(
            "{}: the room's surfaces unfolded, {label} ({unit})",
            scene.name
        ),
        notes,
        unit,
        quantity: label,
        patches,
    })
}

/// A level as given: `1`, `0.5`, `0.2007` (arc levels are not round).
fn format_level(level: f64) -> String {
    let s = format!("{level:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_owned()
}
