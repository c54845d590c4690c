//! `eigenrad-bench shadows`: the luminaires' direct light with shadows cut out of the patches
//! as polygons (the default) against rays refined along the shadow edges
//! (`LuminaireOptions::polygon_shadows`). Each scene's light is computed both ways in this
//! process, one after the other, on the same patches and occluders as a build's: CPU and wall
//! seconds of each, and how far the direct illuminance of the patches and of the outputs
//! (sensors, zones, grid points) moves between them. On the patch and channel where the two
//! differ most, an independent reference: the midpoint rule on a fine grid of points over the
//! patch, each point's illuminance by rays from every piece of the opening (`Source::point`), no
//! cell refinement and no polygon; the opening split by the five-times rule, as the rays split
//! it, and four times finer, as the polygons split it in a shadowed cell.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context as _, Result};
use eigenrad_precompute::formfactor::{gauss_legendre, Occluders};
use eigenrad_precompute::geometry::Vec3;
use eigenrad_precompute::scene::{FieldOfView, Scene};
use eigenrad_precompute::sources::luminaires::{lights_and_flux, LuminaireOptions, Source};
use eigenrad_precompute::sources::ChannelLight;
use rayon::prelude::*;

use crate::scale::cpu_seconds;

/// One computation of the direct light: CPU and wall seconds, the light of every channel.
struct Run {
    cpu: f64,
    wall: f64,
    lights: Vec<ChannelLight>,
}

fn options(polygons: bool) -> LuminaireOptions {
    LuminaireOptions {
        polygon_shadows: polygons,
        ..LuminaireOptions::default()
    }
}

fn light(scene: &Scene, occluders: &Occluders, polygons: bool) -> Run {
    let (cpu, wall) = (cpu_seconds(), Instant::now());
    let (lights, _) = lights_and_flux(scene, occluders, &options(polygons));
    Run {
        cpu: cpu_seconds() - cpu,
        wall: wall.elapsed().as_secs_f64(),
        lights,
    }
}

/// How far one computation's values are from another's, relative to the other's largest
/// value over all channels (so that dim patches do not weigh as lit ones).
struct Differences {
    largest: f64,
    rms: f64,
    /// Where the largest is: channel and index.
    at: (usize, usize),
}

fn differences(a: &[&[f64]], b: &[&[f64]]) -> Differences {
    let scale = b
        .iter()
        .flat_map(|v| v.iter())
        .fold(0.0f64, |s, &x| s.max(x.abs()));
    let (mut largest, mut squares, mut count, mut at) = (0.0f64, 0.0, 0usize, (0, 0));
    for (c, (x, y)) in a.iter().zip(b).enumerate() {
        for (i, (&p, &q)) in x.iter().zip(y.iter()).enumerate() {
            let d = (p - q).abs() / scale;
            if d > largest {
                largest = d;
                at = (c, i);
            }
            squares += d * d;
            count += 1;
        }
    }
    Differences {
        largest,
        rms: (squares / count.max(1) as f64).sqrt(),
        at,
    }
}

/// Mean direct illuminance, lux, of channel `channel` over patch `k` of `scene` by the
/// midpoint rule on `side × side` points of its bilinear parameter square (quadrilaterals;
/// `None` for other patches), each point's opening split by `near_field_ratio`.
fn midpoint(
    scene: &Scene,
    occluders: &Occluders,
    channel: usize,
    k: usize,
    side: usize,
    near_field_ratio: f64,
) -> Option<f64> {
    let patch = &scene.patches[k];
    let &[a, b, c, d] = patch.polygon.vertices.as_slice() else {
        return None;
    };
    // One split at every point, shadowed or not.
    let opts = LuminaireOptions {
        near_field_ratio,
        shadow_ratio: near_field_ratio,
        ..LuminaireOptions::default()
    };
    let gl = gauss_legendre(opts.order);
    let sources: Vec<Source> = scene
        .luminaires
        .iter()
        .filter(|l| l.channel == channel)
        .map(|l| Source::new(l, occluders, &opts, &gl))
        .collect();
    let at = |u: f64, v: f64| {
        a * ((1.0 - u) * (1.0 - v)) + b * (u * (1.0 - v)) + c * (u * v) + d * ((1.0 - u) * v)
    };
    // Weighted by the bilinear map's Jacobian, so that the mean is over area.
    let rows: Vec<(f64, f64)> = (0..side)
        .into_par_iter()
        .map(|i| {
            let u = (i as f64 + 0.5) / side as f64;
            let (mut lumens, mut area) = (0.0, 0.0);
            for j in 0..side {
                let v = (j as f64 + 0.5) / side as f64;
                let du = (b - a) * (1.0 - v) + (c - d) * v;
                let dv = (d - a) * (1.0 - u) + (c - b) * u;
                let jacobian = du.cross(dv).length();
                let x: Vec3 = at(u, v);
                let e: f64 = sources
                    .iter()
                    .map(|s| s.point(x, patch.normal, FieldOfView::HEMISPHERE, &[k]))
                    .sum();
                lumens += e * jacobian;
                area += jacobian;
            }
            (lumens, area)
        })
        .collect();
    let (lumens, area) = rows
        .iter()
        .fold((0.0, 0.0), |(l, s), &(li, si)| (l + li, s + si));
    Some(lumens / area)
}

/// Prints one row per scene: the two computations' times, their ratio, and the differences on
/// patches and outputs (relative to the largest value of the rays' computation); then, on the
/// patch where they differ most, both against the midpoint rule on `side × side` points.
pub(crate) fn run(scenes: &[PathBuf], side: usize) -> Result<()> {
    println!("| scene | patches | luminaires | rays CPU s | wall s | polygons CPU s | wall s | CPU ratio | patches largest / RMS | outputs largest / RMS |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let mut worst = Vec::new();
    for path in scenes {
        let scene = eigenrad_precompute::scene::load(path)
            .with_context(|| format!("{}", path.display()))?;
        let occluders = Occluders::with_faces(&scene.patches, &scene.faces);
        let rays = light(&scene, &occluders, false);
        let polygons = light(&scene, &occluders, true);
        let compare = |patches: bool| {
            let values = |run: &Run| -> Vec<Vec<f64>> {
                run.lights
                    .iter()
                    .map(|l| {
                        if patches {
                            l.patch_irradiance[0].clone()
                        } else {
                            l.output_irradiance[0].clone()
                        }
                    })
                    .collect()
            };
            let (a, b) = (values(&polygons), values(&rays));
            let a: Vec<&[f64]> = a.iter().map(Vec::as_slice).collect();
            let b: Vec<&[f64]> = b.iter().map(Vec::as_slice).collect();
            differences(&a, &b)
        };
        let (on_patches, on_outputs) = (compare(true), compare(false));
        println!(
            "| {} | {} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.3} | {:.1e} / {:.1e} | {:.1e} / {:.1e} |",
            path.display(),
            scene.patches.len(),
            scene.luminaires.len(),
            rays.cpu,
            rays.wall,
            polygons.cpu,
            polygons.wall,
            polygons.cpu / rays.cpu,
            on_patches.largest,
            on_patches.rms,
            on_outputs.largest,
            on_outputs.rms
        );
        let (c, k) = on_patches.at;
        let value = |run: &Run| run.lights.get(c).map_or(0.0, |l| l.patch_irradiance[0][k]);
        let surface = scene.surfaces[scene.patches[k].surface].name.clone();
        let build_ratio = LuminaireOptions::default().near_field_ratio;
        let same = midpoint(&scene, &occluders, c, k, side, build_ratio);
        // Closer to the extended opening: as the polygons split it in a shadowed cell.
        let finer_ratio = LuminaireOptions::default().shadow_ratio;
        let finer = midpoint(&scene, &occluders, c, k, side, finer_ratio);
        worst.push((
            path.clone(),
            c,
            k,
            surface,
            value(&polygons),
            value(&rays),
            same,
            finer,
        ));
    }
    println!("\nOn the patch where the two differ most, against the midpoint rule on {side} × {side} points, rays from every piece of the opening at each point, the opening split by the five-times rule (pieces at most 1/5 of their distance, as the rays split it) and as the polygons split it in a shadowed cell (1/{}):\n", LuminaireOptions::default().shadow_ratio);
    println!("| scene | channel | patch | polygons lux | rays lux | midpoint lux | polygons off | rays off | midpoint, finer pieces, lux | polygons off | rays off |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for (path, c, k, surface, polygons, rays, same, finer) in worst {
        let value = |r: Option<f64>| r.map_or("–".to_string(), |r| format!("{r:.4}"));
        let off = |x: f64, r: Option<f64>| {
            r.map_or("–".to_string(), |r| format!("{:.1e}", (x - r).abs() / r))
        };
        println!(
            "| {} | {c} | {k} ({surface}) | {polygons:.4} | {rays:.4} | {} | {} | {} | {} | {} | {} |",
            path.display(),
            value(same),
            off(polygons, same),
            off(rays, same),
            value(finer),
            off(polygons, finer),
            off(rays, finer)
        );
    }
    Ok(())
}
