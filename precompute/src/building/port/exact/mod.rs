//! Exact ports: the opening a real hole (docs/math.md, "Rooms seen through an exact port").
//!
//! Two rooms seen as one scene exchange light only between the patches that see the opening,
//! through it: the cross exchange areas `G_XY` between room X's patches that see the opening
//! (its *seen patches* `V_X`) and room Y's, occluded by both rooms. Each room's build answers
//! for its seen patches ([`respond`]): the exitance every channel and every daylight node
//! gives them, and, for unit irradiance arriving at each of them from outside, the exitance it
//! then gives them, every output's reading and every patch's exitance. The merge ([`couple`])
//! computes the cross terms from the rooms' scenes (the pair integrals through the opening,
//! the receivers' view of the other room's seen patches, the direct light of each room's
//! luminaires with photometry and clear windows in the other), for every port and for every
//! two rooms that see each other across a third through two openings, and solves the coupled
//! system over the seen patches of every room.

mod couple;
mod cross;
mod daylight;
mod direct;
mod tables;

pub use couple::couple;

use serde::{Deserialize, Serialize};

use crate::basis::BasisDaylight;
use crate::formfactor::FormFactorOptions;
use crate::radiosity::System;
use crate::scene::Scene;

/// The rules of the pair integrals a room was built with: the fields of [`FormFactorOptions`]
/// that enter them (progress, cache and the operator's storage do not). The merge computes an
/// exact port's cross terms with its rooms' rules, and refuses rooms built with different ones.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PairRules {
    /// [`FormFactorOptions::gauss_order`].
    pub gauss_order: usize,
    /// [`FormFactorOptions::touching_order`].
    pub touching_order: usize,
    /// [`FormFactorOptions::quadrature_tolerance`].
    pub quadrature_tolerance: f64,
    /// [`FormFactorOptions::visibility_depth`].
    pub visibility_depth: u32,
    /// [`FormFactorOptions::visibility_cell_share`].
    pub visibility_cell_share: f64,
    /// [`FormFactorOptions::occluded_order`].
    pub occluded_order: usize,
}

impl PairRules {
    /// The rules of `opts`.
    pub fn of(opts: &FormFactorOptions) -> Self {
        PairRules {
            gauss_order: opts.gauss_order,
            touching_order: opts.touching_order,
            quadrature_tolerance: opts.quadrature_tolerance,
            visibility_depth: opts.visibility_depth,
            visibility_cell_share: opts.visibility_cell_share,
            occluded_order: opts.occluded_order,
        }
    }

    /// Options computing the pair integrals by these rules (the others at their defaults).
    pub fn options(&self) -> FormFactorOptions {
        FormFactorOptions {
            gauss_order: self.gauss_order,
            touching_order: self.touching_order,
            quadrature_tolerance: self.quadrature_tolerance,
            visibility_depth: self.visibility_depth,
            visibility_cell_share: self.visibility_cell_share,
            occluded_order: self.occluded_order,
            ..FormFactorOptions::default()
        }
    }
}

impl Default for PairRules {
    fn default() -> Self {
        PairRules::of(&FormFactorOptions::default())
    }
}

/// One of a room's exact ports, as its build found it: the port and its opening's surface.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ExactOpening {
    /// The port's name in the manifest.
    pub port: String,
    /// The opening's surface in the room's scene.
    pub surface: String,
}

/// A room's exact responses at the patches that see its exact ports' openings, per band.
/// Exitance and readings in W/m² (lux in a photopic scene) per W/m² (lux) of irradiance.
/// Empty for a room without exact ports.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ExactPorts {
    /// The room's exact openings, in the manifest's order of ports.
    pub openings: Vec<ExactOpening>,
    /// The room's number of patches (the merge meshes its scene again and checks it).
    pub patches: usize,
    /// The rules of the room's pair integrals, for the merge's cross terms.
    pub rules: PairRules,
    /// The seen patches `V`: every patch (not an opening's) that exchanges light with a patch
    /// of an opening, ascending.
    pub seen: Vec<usize>,
    /// `channels[b][c][v]`: exitance of seen patch `v` with channel `c` alone at level 1.
    pub channels: Vec<Vec<Vec<f64>>>,
    /// `seen_exitance[b][i][v]`: exitance of seen patch `v` for irradiance 1 arriving at seen
    /// patch `i` from outside the room, nothing else lit.
    pub seen_exitance: Vec<Vec<Vec<f64>>>,
    /// `readings[b][i][o]`: reading of output `o` (sensors, zones, then grid points) for the
    /// same irradiance.
    pub readings: Vec<Vec<Vec<f64>>>,
    /// `exitance[b][i][k]`: exitance of every patch `k` for the same irradiance. Only the
    /// modes read it (exitance set patch by patch): empty when no controller of the room
    /// keeps them.
    pub exitance: Vec<Vec<Vec<f64>>>,
    /// `daylight[d][v]`: exitance (lux) of seen patch `v` with daylight node `d` of the
    /// room's daylight section alone at 1 (its sky's patches, the exterior, its sun nodes, in
    /// their order). Empty for a room without daylight; daylight is photopic, one band.
    pub daylight: Vec<Vec<f64>>,
}

/// The exact responses of a built room at the openings `openings` (`(port, surface)` in the
/// manifest's order of ports), from its meshed scene and its radiosity system, whose form
/// factors `opts` computed: one exact solve per band with a right-hand side per seen patch
/// (`M0 = ρ_i` on patch `i`, the first reflection of unit irradiance), as for the channels;
/// the seen patches' exitance under each node of the room's `daylight`, from its exact
/// responses. Every patch's exitance is kept only with `modes` (a controller of the room
/// keeps them).
pub fn respond(
    scene: &Scene,
    system: &System,
    daylight: Option<&BasisDaylight>,
    openings: &[ExactOpening],
    opts: &FormFactorOptions,
    modes: bool,
) -> Result<ExactPorts, crate::Error> {
    if openings.is_empty() {
        return Ok(ExactPorts::default());
    }
    let n = system.patch_count();
    let mut in_opening = vec![false; n];
    for o in openings {
        let range = opening_patches(scene, &o.port, &o.surface)?;
        for k in range {
            in_opening[k] = true;
        }
    }
    let mut sees = vec![false; n];
    let mut row = vec![0.0; n];
    for j in (0..n).filter(|&j| in_opening[j]) {
        system.operator().row(j, &mut row);
        for k in 0..n {
            if row[k] != 0.0 && !in_opening[k] {
                sees[k] = true;
            }
        }
    }
    let seen: Vec<usize> = (0..n).filter(|&k| sees[k]).collect();
    let responses = system.channel_responses()?;
    let m = system.channel_count();
    let mut ports = ExactPorts {
        openings: openings.to_vec(),
        patches: n,
        rules: PairRules::of(opts),
        seen: seen.clone(),
        ..ExactPorts::default()
    };
    let dark = vec![0.0; m];
    for b in 0..system.band_count() {
        ports.channels.push(
            (0..m)
                .map(|c| seen.iter().map(|&k| responses[c][b][k]).collect())
                .collect(),
        );
        let first: Vec<Vec<f64>> = seen
            .iter()
            .map(|&i| {
                let mut m0 = vec![0.0; n];
                m0[i] = system.reflectance[b][i];
                m0
            })
            .collect();
        let cases: Vec<(&[f64], &[f64])> = first
            .iter()
            .map(|m0| (dark.as_slice(), m0.as_slice()))
            .collect();
        let exitance = system.exact_many(b, &cases)?;
        ports.seen_exitance.push(
            exitance
                .iter()
                .map(|x| seen.iter().map(|&k| x[k]).collect())
                .collect(),
        );
        ports
            .readings
            .push(exitance.iter().map(|x| system.outputs(x)).collect());
        if modes {
            ports.exitance.push(exitance);
        }
    }
    if let Some(daylight) = daylight {
        ports.daylight = daylight
            .responses
            .iter()
            .map(|r| seen.iter().map(|&k| r.exitance[k]).collect())
            .collect();
    }
    Ok(ports)
}

/// The patches of the opening `surface` of port `port` in `scene`.
pub(crate) fn opening_patches(
    scene: &Scene,
    port: &str,
    surface: &str,
) -> Result<std::ops::Range<usize>, crate::Error> {
    // The manifest checked the quad against the scene file; a scene that meshed it into no
    // surface of this name is refused here rather than coupled wrongly.
    scene
        .surfaces
        .iter()
        .find(|s| s.name == surface)
        .map(|s| s.patch_range.clone())
        .filter(|r| !r.is_empty())
        .ok_or_else(|| crate::Error::PortOpening {
            port: port.to_string(),
            surface: surface.to_string(),
        })
}
