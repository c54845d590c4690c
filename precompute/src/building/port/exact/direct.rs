//! The direct light of one room's luminaires with photometry through an exact port's opening:
//! the illuminance each of its channels puts, at level 1, on the other room's seen patches and
//! at the other room's outputs, straight from the luminaires through the hole, occluded by
//! both rooms' surfaces (docs/math.md, "Rooms seen through an exact port"). It is what the
//! one-scene build's luminaire code gives those patches and outputs
//! ([`crate::sources::luminaires`]), with the same rules, from the two rooms' patches as one
//! scene; the light the luminaires put in their own room is in that room's part already.

use rayon::prelude::*;

use super::cross::Side;
use crate::formfactor::{gauss_legendre, Occluders};
use crate::geometry::Patch;
use crate::scene::receivers::{receivers, Receiver};
use crate::scene::Scene;
use crate::sources::luminaires::{direct_at_receivers, LuminaireOptions, Source};

/// What the luminaires of one room put directly on the other room of a port, per channel of
/// the lit-from room at level 1, lux.
pub(super) struct Direct {
    /// `seen[c][a]`: on the other room's seen patch `a` (its mean over the patch).
    pub seen: Vec<Vec<f64>>,
    /// `outputs[c][o]`: at the other room's output `o` (sensors, zones, then grid points).
    pub outputs: Vec<Vec<f64>>,
}

/// The direct light of `from`'s luminaires on the side `to` of a port, through its opening.
/// `patches` and `occluders` are both rooms' patches as one scene (the openings left out),
/// `index[k]` patch `k` of `to`'s scene in them. `None` when `from` has no luminaires.
pub(super) fn through(
    from: &Scene,
    to: &Side,
    index: &[Option<usize>],
    patches: &[Patch],
    occluders: &Occluders,
) -> Option<Direct> {
    if from.luminaires.is_empty() {
        return None;
    }
    // The build's rules (`pipeline`), so that the merge integrates as the one scene would.
    let opts = LuminaireOptions::default();
    let gl = gauss_legendre(opts.order.max(1));
    let all: Vec<Receiver> = receivers(to.scene).take(to.outputs).collect();
    // The patches whose illuminance is needed: the seen patches and the surface zones'.
    let mut needed = vec![false; to.scene.patches.len()];
    for &k in to.seen {
        needed[k] = true;
    }
    for receiver in &all {
        if let Receiver::Surfaces(members) = *receiver {
            for &k in members {
                needed[k] = true;
            }
        }
    }
    let m = from.channels.len();
    let mut on_patches = vec![vec![0.0; to.scene.patches.len()]; m];
    let mut outputs = vec![vec![0.0; all.len()]; m];
    for lum in &from.luminaires {
        let source = Source::new(lum, occluders, &opts, &gl);
        let c = lum.channel;
        // An opening's patch is no receiver: it is the hole the light passes through.
        let lit: Vec<f64> = (0..to.scene.patches.len())
            .into_par_iter()
            .map(|k| match index[k] {
                Some(at) if needed[k] => source.patch(&patches[at], &[at]),
                _ => 0.0,
            })
            .collect();
        for (sum, e) in on_patches[c].iter_mut().zip(lit) {
            *sum += e;
        }
        let direct = direct_at_receivers(&source, &all);
        for (sum, e) in outputs[c].iter_mut().zip(direct) {
            *sum += e;
        }
    }
    for c in 0..m {
        for (out, receiver) in outputs[c].iter_mut().zip(&all) {
            if let Receiver::Surfaces(members) = *receiver {
                let area: f64 = members.iter().map(|&k| to.scene.patches[k].area).sum();
                let lumens: f64 = members
                    .iter()
                    .map(|&k| to.scene.patches[k].area * on_patches[c][k])
                    .sum();
                *out = lumens / area;
            }
        }
    }
    Some(Direct {
        seen: on_patches
            .iter()
            .map(|e| to.seen.iter().map(|&k| e[k]).collect())
            .collect(),
        outputs,
    })
}
