//! From a [`Model`] to the runtime's [`BasisTables`]: what the basis stores, table by table.

use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::{Precision, Quantity};

use crate::radiosity::eigen::Formulation;
use crate::radiosity::model::Model;
use crate::scene::{Bands, Scene};

/// Fills every table of the basis for the first `p` modes of `model`.
pub fn basis_tables(scene: &Scene, model: &Model, p: usize, precision: Precision) -> BasisTables {
    let n = model.patch_count();
    let bands = model.bands.len();
    let m = scene.channels.len();
    let outputs = model.output_rows.len();
    let split = model.formulation == Formulation::Split;
    let p = model
        .bands
        .iter()
        .map(|b| b.mode_count())
        .max()
        .unwrap_or(0)
        .min(p);

    let quantity = match scene.bands {
        Bands::Photopic => Quantity::Photometric,
        Bands::Rgb => Quantity::Radiometric,
    };
    let mut t = BasisTables {
        surface_names: scene.surfaces.iter().map(|s| s.name.clone()).collect(),
        channel_names: scene.channels.iter().map(|c| c.name.clone()).collect(),
        sensor_names: scene.sensors.iter().map(|s| s.name.clone()).collect(),
        zone_names: scene.zones.iter().map(|z| z.name.clone()).collect(),
        ..BasisTables::new(quantity, model.formulation, precision, bands, p)
    };

    // A band with fewer reflecting patches than p is padded with null modes: zero vectors
    // with μ = 0 (split, c = 0) or λ = 1 (seed, positive as the format requires).
    let pad = if split { 0.0 } else { 1.0 };
    for band in &model.bands {
        for k in 0..p {
            t.eigenvalues
                .push(band.modes.values.get(k).copied().unwrap_or(pad));
        }
    }
    let mode = |b: usize, i: usize, k: usize| {
        let v = &model.bands[b].modes.vectors;
        if k < v.ncols() {
            v[(i, k)]
        } else {
            0.0
        }
    };
    let truncate = |mut x: Vec<f64>| {
        x.resize(p, 0.0);
        x
    };

    for (i, patch) in scene.patches.iter().enumerate() {
        t.patch_area.push(patch.area);
        t.patch_centroid.push(patch.centroid.to_array());
        t.patch_surface.push(patch.surface as u16);
        t.patch_channel
            .push(scene.channel_of_patch[i].map(|c| c as u16));
        for b in 0..bands {
            t.patch_reflectance.push(model.bands[b].reflectance[i]);
            // The format gives a patch one channel: its emission is that channel's.
            t.patch_emission
                .push(scene.channel_of_patch[i].map_or(0.0, |c| model.emission(c, b)[i]));
        }
        for b in 0..bands {
            for k in 0..p {
                t.modes.push(mode(b, i, k));
            }
        }
    }
    for j in 0..n {
        if (0..bands).any(|b| model.bands[b].reflectance[j] == 0.0) {
            for b in 0..bands {
                t.black_projection
                    .extend(truncate(model.patch_projection(j, b)));
            }
        }
    }

    // Channels are stored exactly, from the exact solve the model did at build time: any
    // combination of levels is then exact to the storage precision, and the modes serve
    // exitance set patch by patch only.
    t.channel_response = vec![0.0; n * m * bands];
    for c in 0..m {
        for b in 0..bands {
            for (i, x) in model.channel_response(c, b).iter().enumerate() {
                t.channel_response[i * m * bands + c * bands + b] = *x;
            }
        }
    }

    for s in &scene.sensors {
        let half = s.half_angle.unwrap_or(std::f64::consts::PI);
        t.sensor_geometry.push([
            s.position.x,
            s.position.y,
            s.position.z,
            s.normal.x,
            s.normal.y,
            s.normal.z,
            half,
        ]);
    }
    for z in &scene.zones {
        t.zone_area
            .push(crate::formfactor::outputs::zone_area(scene, z));
    }
    for row in &model.output_rows {
        for b in 0..bands {
            for k in 0..p {
                t.output_modes
                    .push((0..n).map(|j| row[j] * mode(b, j, k)).sum());
            }
        }
    }
    // `O × B × m`: the exact readings of each channel alone at level 1.
    let readings: Vec<Vec<Vec<f64>>> = (0..m)
        .map(|c| (0..bands).map(|b| model.channel_readings(c, b)).collect())
        .collect();
    for o in 0..outputs {
        for b in 0..bands {
            for channel in &readings {
                t.output_channels.push(channel[b][o]);
            }
        }
    }
    t.output_view = vec![0.0; n * outputs];
    for (o, row) in model.output_rows.iter().enumerate() {
        for (j, &v) in row.iter().enumerate() {
            t.output_view[j * outputs + o] = v;
        }
    }
    t
}
