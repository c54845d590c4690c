//! Rooms that share light through ports (docs/building.md, "Ports"; docs/math.md, "Rooms
//! coupled through ports").
//!
//! A port's opening is a black quad in each of its two rooms: light reaching it from inside
//! leaves the room. Each room's build answers for its ports' patches ([`respond`]), each
//! resolved into its port's direction bins ([`directions`]; one bin, diffuse, by default): the
//! flux each of its channels and each of its daylight nodes sends onto every port patch in
//! every bin, and, for unit exitance entering through each port patch in each bin, what the
//! room reads at every output, its exitance on every patch and the flux it sends back onto
//! every port patch in every bin. The
//! merge ([`couple`]) solves the small system of the exitances entering through every port
//! patch, per channel and daylight node of the building, and adds what they give to each
//! room's channel responses and daylight rows: the controllers' bases are cut from these
//! coupled tables, and the runtime reads them as any other.
//!
//! An exact port ([`exact`]) is the opening as a real hole: the rooms' responses are kept at
//! the patches that see it, and the merge couples those through the opening.

mod couple;
pub mod directions;
pub mod exact;

pub use couple::{couple, foreign_channel, Coupled};
pub use directions::{DEFAULT_DIRECTIONS, MAX_DIRECTIONS};

use serde::{Deserialize, Serialize};

use crate::basis::BasisDaylight;
use crate::formfactor::{exchange, gauss_legendre, Occluders};
use crate::geometry::Vec3;
use crate::radiosity::system::alone;
use crate::radiosity::System;
use crate::scene::receivers::{receivers, Receiver};
use crate::scene::Scene;
use crate::sources::luminaires::{LuminaireOptions, Source};
use crate::sources::ChannelLight;
use directions::{samples, shares, shares_at_points, Bins};

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
    /// Number of direction bins of the light crossing each of its patches (1: diffuse;
    /// [`directions`]).
    pub directions: usize,
}

/// An opening a room's build answers for.
#[derive(Clone, Debug, PartialEq)]
pub struct PortAsked {
    /// The port's name in the manifest.
    pub port: String,
    /// The opening's surface in the room's scene.
    pub surface: String,
    /// The port's number of direction bins.
    pub directions: usize,
}

/// A room's exact responses at its ports' patches (all its openings' patches in order, the
/// room's *port patches*), each patch resolved into its port's direction bins: the room's
/// *slots*, `(patch, bin)` in that order, one per patch for a diffuse port. Per band. Flux in W (lm for a photopic scene), exitance and
/// readings in W/m² (lux). Empty for a room without ports.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RoomPorts {
    /// The room's openings, in the manifest's order of ports.
    pub openings: Vec<PortOpening>,
    /// `leaving[b][c][j]`: flux reaching slot `j` (its patch, travelling in its bin) from inside
    /// with channel `c` alone at level 1.
    pub leaving: Vec<Vec<Vec<f64>>>,
    /// `returned[b][i][j]`: flux reaching slot `j` from inside for exitance 1 entering through
    /// slot `i` (Lambertian within its bin), nothing else lit.
    pub returned: Vec<Vec<Vec<f64>>>,
    /// `readings[b][i][o]`: reading of output `o` (sensors, zones, then grid points) for
    /// exitance 1 entering through slot `i`.
    pub readings: Vec<Vec<Vec<f64>>>,
    /// `exitance[b][i][k]`: exitance of patch `k` for exitance 1 entering through slot `i` (1
    /// on its patch itself, which is black).
    pub exitance: Vec<Vec<Vec<f64>>>,
    /// `daylight[d][j]`: flux reaching slot `j` from inside with daylight node `d`
    /// alone at 1 (the nodes of the room's daylight section in their order: a sky patch per
    /// cd/m², the exterior per cd/m² of `E_gh/π`, a sun node per lux of direct normal
    /// illuminance), in lm. Empty for a room without daylight; daylight is photopic, one band.
    pub daylight: Vec<Vec<f64>>,
}

impl RoomPorts {
    /// Where opening `k`'s slots start among the room's slots.
    fn first_slot(&self, k: usize) -> usize {
        self.openings[..k]
            .iter()
            .map(|o| o.area.len() * o.directions)
            .sum()
    }
}

/// One port patch of a room as [`respond`] resolves it.
struct PortPatch {
    /// Its index among the scene's patches.
    patch: usize,
    /// Its opening's direction bins, for the light entering this room and for the light
    /// leaving it (the other room's bins); `None` for a diffuse port.
    bins: Option<[Bins; 2]>,
    /// `(k, G_jk, shares)` for every patch `k` this one exchanges light with: `G_jk` (m²) and
    /// the shares of that exchange in each bin, entering then leaving (empty for a diffuse
    /// port).
    exchange: Vec<(usize, f64, [Vec<f64>; 2])>,
    /// Per channel, the shares of its luminaires' direct light on this patch in each bin of
    /// the light leaving (`None` where none reaches it, and for a diffuse port).
    luminaires: Vec<Option<Vec<f64>>>,
}

impl PortPatch {
    /// The flux reaching this patch from inside in each of its slots (W, or lm), where the
    /// room's exitance is `m` and the irradiance it gets is `irradiance` (W/m² or lux, all
    /// of it: `F M` plus the direct light from beyond the patches). The light from the
    /// patches goes into the bins of its directions; the direct light from beyond them into
    /// the bins `beyond_shares` gives (a channel's luminaires), or, where its directions are
    /// not known, into every bin alike, as a diffuse port would take it (docs/math.md,
    /// "Directional ports").
    fn flux(
        &self,
        area: f64,
        m: &[f64],
        irradiance: f64,
        beyond_shares: Option<&[f64]>,
        out: &mut Vec<f64>,
    ) {
        let Some([_, leaving]) = &self.bins else {
            out.push(area * irradiance);
            return;
        };
        let passed: f64 = self.exchange.iter().map(|(k, g, _)| g * m[*k]).sum();
        let beyond = area * irradiance - passed;
        for bin in 0..leaving.count() {
            let from_patches: f64 = self
                .exchange
                .iter()
                .map(|(k, g, s)| g * s[1][bin] * m[*k])
                .sum();
            let share = beyond_shares.map_or(leaving.weight(), |s| s[bin]);
            out.push(from_patches + beyond * share);
        }
    }
}

/// The responses of a built room at the openings `openings` (in the manifest's order of
/// ports), from its meshed scene, its occluders, its radiosity system and the daylight its
/// basis carries.
pub fn respond(
    scene: &Scene,
    occluders: &Occluders,
    system: &System,
    daylight: Option<&BasisDaylight>,
    openings: &[PortAsked],
) -> Result<RoomPorts, crate::Error> {
    if openings.is_empty() {
        return Ok(RoomPorts::default());
    }
    let mut ports = RoomPorts::default();
    let mut patches: Vec<PortPatch> = Vec::new();
    let n = system.patch_count();
    let directional = openings.iter().any(|o| o.directions > 1);
    let points: Vec<Vec<(Vec3, f64)>> = if directional {
        scene.patches.iter().map(samples).collect()
    } else {
        Vec::new()
    };
    let mut row = vec![0.0; n];
    let m = system.channel_count();
    // The luminaires as the build lit the patches (its options), for the directions of their
    // direct light onto the port patches.
    let luminaire_options = LuminaireOptions::default();
    let gl = gauss_legendre(luminaire_options.order.max(1));
    let luminaires: Vec<Source> = if directional {
        scene
            .luminaires
            .iter()
            .map(|l| Source::new(l, occluders, &luminaire_options, &gl))
            .collect()
    } else {
        Vec::new()
    };
    for asked in openings {
        let (port, surface) = (&asked.port, &asked.surface);
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
            directions: asked.directions,
        });
        for j in range {
            if asked.directions <= 1 {
                patches.push(PortPatch {
                    patch: j,
                    bins: None,
                    exchange: Vec::new(),
                    luminaires: vec![None; m],
                });
                continue;
            }
            let normal = scene.patches[j].normal;
            let bins = [
                Bins::new(asked.directions, normal),
                Bins::new(asked.directions, -normal),
            ];
            system.operator().row(j, &mut row);
            let exchange = (0..n)
                .filter(|&k| row[k] != 0.0)
                .map(|k| {
                    let receiver = (points[k].as_slice(), Some(scene.patches[k].normal));
                    let port = (points[j].as_slice(), normal);
                    let split = [
                        shares(&bins[0], port, receiver, false),
                        shares(&bins[1], port, receiver, true),
                    ];
                    (k, row[k], split)
                })
                .collect();
            // Each luminaire's direct light on the patch, in the bin of its direction of
            // travel from the luminaire's photometric centre to the patch's centroid.
            let patch = &scene.patches[j];
            let mut direct = vec![vec![0.0; asked.directions]; m];
            for (lum, source) in scene.luminaires.iter().zip(&luminaires) {
                let lux = source.patch(patch, &[j]);
                if lux > 0.0 {
                    direct[lum.channel][bins[1].of(patch.centroid - lum.position)] += lux;
                }
            }
            let luminaires = direct
                .into_iter()
                .map(|bins| {
                    let total: f64 = bins.iter().sum();
                    (total > 0.0).then(|| bins.iter().map(|x| x / total).collect())
                })
                .collect();
            patches.push(PortPatch {
                patch: j,
                bins: Some(bins),
                exchange,
                luminaires,
            });
        }
    }
    // The flux onto every slot for exitance `m`, irradiance(port patch's place, its index in
    // the scene) and the light from beyond the patches of channel `channel` (`None`: not a
    // channel's).
    let flux_on_ports =
        |m: &[f64], irradiance: &dyn Fn(usize, usize) -> f64, channel: Option<usize>| -> Vec<f64> {
            let mut out = Vec::new();
            for (place, p) in patches.iter().enumerate() {
                let beyond = channel.and_then(|c| p.luminaires[c].as_deref());
                p.flux(
                    system.area[p.patch],
                    m,
                    irradiance(place, p.patch),
                    beyond,
                    &mut out,
                );
            }
            out
        };
    let responses = system.channel_responses()?;
    let entering: Vec<ChannelLight> = patches
        .iter()
        .flat_map(|p| entering_lights(scene, system, p, &points))
        .collect();
    for b in 0..system.band_count() {
        ports.leaving.push(
            (0..m)
                .map(|c| {
                    let irradiance = system.patch_irradiance(b, &responses[c][b], &alone(m, c));
                    flux_on_ports(&responses[c][b], &|_, j| irradiance[j], Some(c))
                })
                .collect(),
        );
        let mut returned = Vec::new();
        let mut readings = Vec::new();
        let mut exitance = Vec::new();
        let slots = patches
            .iter()
            .flat_map(|p| (0..p.bins.map_or(1, |b| b[0].count())).map(move |_| p));
        for ((response, irradiance), p) in system
            .light_responses_with_irradiance(b, &entering)?
            .into_iter()
            .zip(slots)
        {
            returned.push(flux_on_ports(
                &response.exitance,
                &|_, j| irradiance[j],
                None,
            ));
            readings.push(response.readings);
            let mut exitance_of = response.exitance;
            if p.bins.is_some() {
                // The light entering leaves the black port patch into the room: its exitance
                // there, as the diffuse port's emission is.
                exitance_of[p.patch] += 1.0;
            }
            exitance.push(exitance_of);
        }
        ports.returned.push(returned);
        ports.readings.push(readings);
        ports.exitance.push(exitance);
    }
    if let Some(daylight) = daylight {
        let on: Vec<usize> = patches.iter().map(|p| p.patch).collect();
        ports.daylight = daylight
            .nodes
            .lights
            .iter()
            .zip(&daylight.responses)
            .map(|(light, response)| {
                let irradiance = system.light_irradiance_at(0, light, &response.exitance, &on);
                flux_on_ports(&response.exitance, &|place, _| irradiance[place], None)
            })
            .collect();
    }
    Ok(ports)
}

/// The light entering the room through port patch `p`, one per slot: unit exitance leaving
/// the patch into the room, Lambertian (a diffuse port: the patch's emission) or within one
/// bin (its form factors toward the room restricted to the bin's directions, over the bin's
/// share of the projected solid angle).
fn entering_lights(
    scene: &Scene,
    system: &System,
    p: &PortPatch,
    points: &[Vec<(Vec3, f64)>],
) -> Vec<ChannelLight> {
    let n = system.patch_count();
    let bands = system.band_count();
    let Some([bins, _]) = &p.bins else {
        let unit: Vec<f64> = (0..n)
            .map(|k| if k == p.patch { 1.0 } else { 0.0 })
            .collect();
        let emission = vec![unit; bands];
        return vec![ChannelLight {
            patch_irradiance: emission
                .iter()
                .map(|e| exchange::patch_irradiance(system.operator(), &system.area, e))
                .collect(),
            output_irradiance: emission
                .iter()
                .map(|e| exchange::output_irradiance(&system.output_rows, e))
                .collect(),
            emission,
        }];
    };
    let i = p.patch;
    let normal = scene.patches[i].normal;
    let own = points[i].as_slice();
    // Each output's row entry for this patch, split over the bins by the directions from the
    // patch to what the output sees.
    let output_shares: Vec<Vec<f64>> = receivers(scene)
        .zip(&system.output_rows)
        .map(|(receiver, r)| {
            let r_oi = r[i];
            if r_oi == 0.0 {
                return vec![0.0; bins.count()];
            }
            match receiver {
                Receiver::Point {
                    position,
                    normal: n_o,
                    ..
                } => shares(bins, (own, normal), (&[(position, 1.0)], Some(n_o)), false)
                    .into_iter()
                    .map(|s| r_oi * s)
                    .collect(),
                Receiver::Surfaces(zone) => {
                    // `R_oi = Σ_k G_ik / Σ_k A_k` over the zone's patches: each term split.
                    let total: f64 = zone.iter().map(|&k| system.area[k]).sum();
                    let mut split = vec![0.0; bins.count()];
                    for (k, g, s) in &p.exchange {
                        if zone.contains(k) {
                            for (x, share) in split.iter_mut().zip(&s[0]) {
                                *x += g * share / total;
                            }
                        }
                    }
                    split
                }
                Receiver::Points(points) => shares_at_points(bins, (own, normal), points, false)
                    .into_iter()
                    .map(|s| r_oi * s)
                    .collect(),
                Receiver::Plane(cells) => {
                    // The cells of a work plane face one way: their samples together, each
                    // pair weighted by its kernel as the cells' form factors weigh them.
                    let all: Vec<(Vec3, f64)> = cells.iter().flat_map(samples).collect();
                    let facing = cells.first().map(|c| c.normal);
                    shares(bins, (own, normal), (&all, facing), false)
                        .into_iter()
                        .map(|s| r_oi * s)
                        .collect()
                }
            }
        })
        .collect();
    let w = bins.weight();
    (0..bins.count())
        .map(|bin| {
            let mut irradiance = vec![0.0; n];
            for (k, g, s) in &p.exchange {
                irradiance[*k] = g * s[0][bin] / (system.area[*k] * w);
            }
            let outputs: Vec<f64> = output_shares.iter().map(|s| s[bin] / w).collect();
            ChannelLight {
                emission: vec![vec![0.0; n]; bands],
                patch_irradiance: vec![irradiance; bands],
                output_irradiance: vec![outputs; bands],
            }
        })
        .collect()
}

/// Rooms joined through `links` (pairs of rooms), directly or through others: `group[r]` is
/// the lowest room of room r's group, of `rooms` rooms.
fn groups(rooms: usize, links: impl Iterator<Item = [usize; 2]> + Clone) -> Vec<usize> {
    let mut group: Vec<usize> = (0..rooms).collect();
    loop {
        let mut changed = false;
        for [a, b] in links.clone() {
            let low = group[a].min(group[b]);
            for r in [a, b] {
                if group[r] != low {
                    group[r] = low;
                    changed = true;
                }
            }
        }
        if !changed {
            return group;
        }
    }
}
