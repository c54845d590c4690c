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
use crate::picture::{Format, Net, NetInput, NetPatch, Plan};
use crate::scene::{self, Scene};

use super::levels::LevelArgs;
use super::readout::{self, DaylightArgs, Readout};
use super::units::{readout_in, Units};

mod plan;

use plan::{plan_picture, plan_zones};

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
    /// The work-plane zones of the plan, drawn together (several zones of one floor);
    /// empty: the scene's only one.
    pub zones: &'a [String],
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
    let zones = if request.plan {
        plan_zones(&scene, path, request.zones)?
    } else {
        Vec::new()
    };
    let native = native_readout(request, &scene)?;
    let readout = readout_in(native.clone(), request.units)?;
    let notes = notes(request, &readout);
    let plan = if zones.is_empty() {
        None
    } else {
        Some(plan_picture(&scene, path, &zones, &readout, notes.clone())?)
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
        Some((basis_path, bytes)) => {
            if request.daylight.is_some() && patches {
                refuse_daylight_through_modes_alone(path, basis_path, bytes)?;
            }
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

/// A basis that stores no first reflection of its daylight (a building's room, whose
/// daylight nodes its neighbours' join) holds its patches' daylight only through its modes,
/// too coarse for a picture of the surfaces: an error saying so. Other bases, and bases
/// that do not decode (the evaluation names their fault), pass.
fn refuse_daylight_through_modes_alone(
    scene: &Path,
    basis_path: &Path,
    bytes: &[u8],
) -> Result<()> {
    let Ok(basis) = eigenrad_runtime::Basis::from_bytes(bytes) else {
        return Ok(());
    };
    if !basis.has_daylight() || basis.daylight_reflection_rank().is_some() {
        return Ok(());
    }
    Err(render_error(
        scene,
        format!(
            "{} stores no first reflection of its daylight and holds its patches' daylight only through its modes, too coarse for a picture of the surfaces (docs/math.md, \"Daylight's first reflection\"); leave out --basis to draw them from the exact solve",
            basis_path.display()
        ),
    ))
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
        let sun = if d.sun_below_horizon {
            format!("sun {:.1}° below the horizon", -d.sun.altitude)
        } else {
            format!("sun {:.1}° up", d.sun.altitude)
        };
        notes.push(format!(
            "daylight: {} at {}, {sun}; diffuse horizontal {:.0} lux, direct normal {:.0} lux",
            d.model, d.time, d.diffuse_horizontal_lux, d.direct_normal_lux
        ));
    }
    notes.extend(rgb_note);
    notes
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
