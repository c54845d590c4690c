//! Rooms that share light through ports (docs/building.md, "Ports"; docs/math.md, "Rooms
//! coupled through ports").
//!
//! A port's opening is a black quad in each of its two rooms: light reaching it from inside
//! leaves the room. Each room's build answers for its ports' patches ([`respond`]): the flux
//! each of its channels and each of its daylight nodes sends onto every port patch, and, for
//! unit diffuse exitance entering through each port patch, what the room reads at every
//! output, its exitance on every patch and the flux it sends back onto every port patch. The
//! merge ([`couple`]) solves the small system of the exitances entering through every port
//! patch, per channel and daylight node of the building, and adds what they give to each
//! room's channel responses and daylight rows: the controllers' bases are cut from these
//! coupled tables, and the runtime reads them as any other.

mod couple;

pub use couple::{couple, foreign_channel, Coupled};

use serde::{Deserialize, Serialize};

use crate::basis::BasisDaylight;
use crate::formfactor::exchange;
use crate::radiosity::system::alone;
use crate::radiosity::System;
use crate::scene::Scene;
use crate::sources::ChannelLight;

/// One of a room's port openings, as the room's build meshed it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PortOpening {
    /// The port's name in the manifest.
    pub port: String,
    /// The opening's surface in the room's scene.
    pub surface: String,
    /// Area of each of its patches, m².
    pub area: Vec<f64>,
    /// Centroid of each of its patches, m.
    pub centroid: Vec<[f64; 3]>,
}

/// A room's exact responses at its ports' patches (all its openings' patches in order, the
/// room's *port patches*), per band. Flux in W (lm for a photopic scene), exitance and
/// readings in W/m² (lux). Empty for a room without ports.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RoomPorts {
    /// The room's openings, in the manifest's order of ports.
    pub openings: Vec<PortOpening>,
    /// `leaving[b][c][j]`: flux reaching port patch `j` from inside with channel `c` alone at
    /// level 1.
    pub leaving: Vec<Vec<Vec<f64>>>,
    /// `returned[b][i][j]`: flux reaching port patch `j` from inside for exitance 1 entering
    /// through port patch `i` (Lambertian), nothing else lit.
    pub returned: Vec<Vec<Vec<f64>>>,
    /// `readings[b][i][o]`: reading of output `o` (sensors, zones, then grid points) for
    /// exitance 1 entering through port patch `i`.
    pub readings: Vec<Vec<Vec<f64>>>,
    /// `exitance[b][i][k]`: exitance of patch `k` for exitance 1 entering through port patch
    /// `i` (1 on patch `i` itself, which is black).
    pub exitance: Vec<Vec<Vec<f64>>>,
    /// `daylight[d][j]`: flux reaching port patch `j` from inside with daylight node `d`
    /// alone at 1 (the nodes of the room's daylight section in their order: a sky patch per
    /// cd/m², the exterior per cd/m² of `E_gh/π`, a sun node per lux of direct normal
    /// illuminance), in lm. Empty for a room without daylight; daylight is photopic, one band.
    pub daylight: Vec<Vec<f64>>,
}

impl RoomPorts {
    /// Where opening `k`'s patches start among the room's port patches.
    fn first_patch(&self, k: usize) -> usize {
        self.openings[..k].iter().map(|o| o.area.len()).sum()
    }
}

/// The responses of a built room at the openings `openings` (`(port, surface)`, in the
/// manifest's order of ports), from its meshed scene, its radiosity system and the daylight
/// its basis carries.
pub fn respond(
    scene: &Scene,
    system: &System,
    daylight: Option<&BasisDaylight>,
    openings: &[(String, String)],
) -> Result<RoomPorts, crate::Error> {
    if openings.is_empty() {
        return Ok(RoomPorts::default());
    }
    let mut ports = RoomPorts::default();
    let mut patches = Vec::new();
    for (port, surface) in openings {
        // The manifest checked the quad against the scene file; a scene that meshed it into no
        // surface of this name is refused here rather than coupled wrongly.
        let range = scene
            .surfaces
            .iter()
            .find(|s| &s.name == surface)
            .map(|s| s.patch_range.clone())
            .filter(|r| !r.is_empty())
            .ok_or_else(|| crate::Error::PortOpening {
                port: port.clone(),
                surface: surface.clone(),
            })?;
        let own = &scene.patches[range.clone()];
        ports.openings.push(PortOpening {
            port: port.clone(),
            surface: surface.clone(),
            area: own.iter().map(|p| p.area).collect(),
            centroid: own
                .iter()
                .map(|p| [p.centroid.x, p.centroid.y, p.centroid.z])
                .collect(),
        });
        patches.extend(range);
    }
    let n = system.patch_count();
    let m = system.channel_count();
    let flux_on_ports = |irradiance: &[f64]| -> Vec<f64> {
        patches
            .iter()
            .map(|&j| system.area[j] * irradiance[j])
            .collect()
    };
    let responses = system.channel_responses()?;
    let entering: Vec<ChannelLight> = patches
        .iter()
        .map(|&i| {
            let unit: Vec<f64> = (0..n).map(|k| if k == i { 1.0 } else { 0.0 }).collect();
            let emission = vec![unit; system.band_count()];
            ChannelLight {
                patch_irradiance: emission
                    .iter()
                    .map(|e| exchange::patch_irradiance(system.operator(), &system.area, e))
                    .collect(),
                output_irradiance: emission
                    .iter()
                    .map(|e| exchange::output_irradiance(&system.output_rows, e))
                    .collect(),
                emission,
            }
        })
        .collect();
    for b in 0..system.band_count() {
        ports.leaving.push(
            (0..m)
                .map(|c| flux_on_ports(&system.patch_irradiance(b, &responses[c][b], &alone(m, c))))
                .collect(),
        );
        let mut returned = Vec::new();
        let mut readings = Vec::new();
        let mut exitance = Vec::new();
        for (response, irradiance) in system.light_responses_with_irradiance(b, &entering)? {
            returned.push(flux_on_ports(&irradiance));
            readings.push(response.readings);
            exitance.push(response.exitance);
        }
        ports.returned.push(returned);
        ports.readings.push(readings);
        ports.exitance.push(exitance);
    }
    if let Some(daylight) = daylight {
        ports.daylight = daylight
            .nodes
            .lights
            .iter()
            .zip(&daylight.responses)
            .map(|(light, response)| {
                let irradiance = system.light_irradiance_at(0, light, &response.exitance, &patches);
                patches
                    .iter()
                    .zip(irradiance)
                    .map(|(&j, e)| system.area[j] * e)
                    .collect()
            })
            .collect();
    }
    Ok(ports)
}
