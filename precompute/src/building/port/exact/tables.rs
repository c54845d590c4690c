//! What the coupled solve of exact ports adds to a room's tables: the channels of every room
//! joined to it, each reading and patch response with what comes through the openings
//! (docs/math.md, "Rooms seen through an exact port").

use eigenrad_runtime::writer::BasisTables;

use crate::building::controller::{cut, Selection};

/// A room's tables `t` with the channels `kept` (`(source, name)`, the room's own first),
/// where source `g` adds `reading(b, g, o)` at output `o` and `patch(b, g, k)` to the
/// exitance of patch `k` in band `b` to the room's own response (0 for another room's
/// channel). Without `patch` (no controller of the room keeps the modes) the tables hold no
/// patch response.
pub(super) fn coupled_tables(
    t: &BasisTables,
    kept: &[(usize, String)],
    reading: &dyn Fn(usize, usize, usize) -> f64,
    patch: Option<&dyn Fn(usize, usize, usize) -> f64>,
) -> BasisTables {
    let bands = t.bands;
    let own = t.channel_names.len();
    let outputs = t.sensor_names.len() + t.zone_names.len();
    let points = t.grid_position.len();
    let n = t.patch_area.len();
    let table = |rows: usize, offset: usize, old: &[f64]| -> Vec<f64> {
        let mut out = Vec::with_capacity(rows * bands * kept.len());
        for o in 0..rows {
            for b in 0..bands {
                for (kc, (g, _)) in kept.iter().enumerate() {
                    let own_value = if kc < own {
                        old[(o * bands + b) * own + kc]
                    } else {
                        0.0
                    };
                    out.push(own_value + reading(b, *g, offset + o));
                }
            }
        }
        out
    };
    let mut tables = t.clone();
    tables.output_channels = table(outputs, 0, &t.output_channels);
    tables.grid_channels = table(points, outputs, &t.grid_channels);
    if let Some(patch) = patch.filter(|_| !t.channel_response.is_empty()) {
        let mut response = Vec::with_capacity(n * kept.len() * bands);
        for k in 0..n {
            for (kc, (g, _)) in kept.iter().enumerate() {
                for b in 0..bands {
                    let own_value = if kc < own {
                        t.channel_response[k * own * bands + kc * bands + b]
                    } else {
                        0.0
                    };
                    response.push(own_value + patch(b, *g, k));
                }
            }
        }
        tables.channel_response = response;
    }
    tables.channel_names = kept.iter().map(|(_, name)| name.clone()).collect();
    tables
}

/// A room's coupled `tables`, without its patches and modes unless `patches` (a controller
/// of the room keeps the modes): the patches' exitance for light entering through an exact
/// port is kept only then, and without it the room's basis keeps no patch, as its
/// controllers' do.
pub(super) fn without_patches_unless(patches: bool, tables: BasisTables) -> BasisTables {
    if patches || tables.patch_area.is_empty() {
        return tables;
    }
    let everything = Selection {
        channels: (0..tables.channel_names.len()).collect(),
        sensors: (0..tables.sensor_names.len()).collect(),
        zones: (0..tables.zone_names.len()).map(|z| (z, true)).collect(),
        modes: false,
    };
    cut(&tables, &everything)
}
