//! The rooms of [`super::two_rooms`] (or [`super::three_rooms`]) as one scene whose doorways
//! are real holes, meshed as the rooms are built apart
//! ([`super::two_rooms::rooms_in_one_scene`] without its door quads, the last surfaces): the reference an exact port is measured against (tests/ports_exact.rs). Its form
//! factors are the dense matrix of every pair of its patches with occlusion by all of them,
//! its solves the exact ones of the whole system (one dense LU).

use std::sync::Arc;

use eigenrad_precompute::formfactor::{self, exchange, outputs, FormFactorOptions, Occluders};
use eigenrad_precompute::radiosity::System;
use eigenrad_precompute::scene::{self, Scene};
use eigenrad_precompute::sources;

/// The one scene, solved.
pub struct WithTheHole {
    /// The scene, its door quads cut off.
    pub scene: Scene,
    /// Its occluders (every patch).
    pub occluders: Occluders,
    /// Its radiosity system, a light per channel (luminaires with photometry included).
    pub system: System,
    /// Its outputs' names: `sensor S`, `zone Z`, then `zone Z point g`.
    pub names: Vec<String>,
    /// The luminaires' direct light alone: (output, `direct <channel>`, lux).
    direct_part: Vec<(usize, String, f64)>,
}

/// The one scene `text` ([`super::two_rooms::rooms_in_one_scene`] with more in it) written
/// and solved in `scratch`, luminaires with photometry lighting it with the build's rules
/// (`sources::luminaires`).
pub fn with_the_hole(scratch: &str, text: &str) -> WithTheHole {
    let dir = super::scratch(scratch);
    let path = dir.join("both.toml");
    std::fs::write(&path, text).expect("scene");
    let mut scene: Scene = scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    // The door quads are the last surfaces, their patches the last patches: cut them off.
    let doors = scene
        .surfaces
        .iter()
        .rev()
        .take_while(|s| s.name.starts_with("door_"))
        .count();
    assert!(doors >= 2 && doors % 2 == 0, "{doors} door quads last");
    let surfaces = scene.surfaces.len();
    let first = scene.surfaces[surfaces - doors].patch_range.start;
    assert_eq!(
        scene.surfaces[surfaces - 1].patch_range.end,
        scene.patches.len()
    );
    scene.patches.truncate(first);
    scene.reflectance.truncate(first);
    scene.emission.truncate(first);
    scene.channel_of_patch.truncate(first);
    scene.surfaces.truncate(surfaces - doors);
    scene.faces.retain(|f| f.patches.end <= first);
    let opts = FormFactorOptions::default();
    let occluders = Occluders::with_faces(&scene.patches, &scene.faces);
    let ff = formfactor::patch_form_factors_with(&scene.patches, &occluders, &opts);
    let area: Vec<f64> = scene.patches.iter().map(|p| p.area).collect();
    let g = exchange::exchange_areas(ff.matrix, &area);
    let rows = outputs::output_rows(&scene, &g, &area, &occluders, &opts);
    let mut lights = sources::surfaces::channel_lights(&scene, &g, &area, &rows);
    // The luminaires' direct light alone, by output, as the channel `direct <channel>`.
    let mut direct_part = Vec::new();
    if !scene.luminaires.is_empty() {
        let options = sources::luminaires::LuminaireOptions::default();
        let direct = sources::luminaires::channel_lights(&scene, &occluders, &options);
        for (channel, light) in scene.channels.iter().zip(&direct) {
            for (o, e) in light.output_irradiance[0].iter().enumerate() {
                direct_part.push((o, format!("direct {}", channel.name), *e));
            }
        }
        lights = lights.iter().zip(&direct).map(|(s, l)| s.plus(l)).collect();
    }
    let reflectance = vec![scene.reflectance.iter().map(|r| r[0]).collect()];
    let system = System::new(Arc::new(g), area, reflectance, rows, lights);
    let mut names: Vec<String> = scene
        .sensors
        .iter()
        .map(|s| format!("sensor {}", s.name))
        .chain(scene.zones.iter().map(|z| format!("zone {}", z.name)))
        .collect();
    let mut per_zone = vec![0; scene.zones.len()];
    for (z, _, _) in outputs::grid_points(&scene) {
        names.push(format!(
            "zone {} point {}",
            scene.zones[z].name, per_zone[z]
        ));
        per_zone[z] += 1;
    }
    WithTheHole {
        scene,
        occluders,
        system,
        names,
        direct_part,
    }
}

impl WithTheHole {
    /// Its exact readings of each channel alone at level 1: (output name, channel name,
    /// lux), then each luminaire channel's direct light alone as channel `direct <channel>`.
    pub fn channel_readings(&self) -> Vec<(String, String, f64)> {
        let system = &self.system;
        let responses = system.channel_responses().unwrap_or_else(|e| panic!("{e}"));
        let m = system.channel_count();
        let mut out = Vec::new();
        for (c, channel) in self.scene.channels.iter().enumerate() {
            let levels: Vec<f64> = (0..m).map(|d| if d == c { 1.0 } else { 0.0 }).collect();
            let read = system.readings(0, &responses[c][0], &levels);
            assert_eq!(read.len(), self.names.len());
            for (name, value) in self.names.iter().zip(read) {
                out.push((name.clone(), channel.name.clone(), value));
            }
        }
        for (o, channel, e) in &self.direct_part {
            out.push((self.names[*o].clone(), channel.clone(), *e));
        }
        out
    }
}
