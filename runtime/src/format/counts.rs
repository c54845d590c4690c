//! The dimensions of a basis (`docs/format.md`, notation) and the column counts of its
//! matrices, one rule for the reader and the writer.

/// The dimensions every table's length follows from (`docs/format.md`, notation): the reader
/// takes them from the payload's settings and counts, the writer from its tables' lengths.
///
/// The rules for the matrices' columns live here, once, for both. They return `None` when a
/// product overflows `usize`, which only the untrusted counts of a corrupt basis can make
/// happen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Counts {
    /// `B`: the payload's `bands`.
    pub bands: usize,
    /// `n`: `patch_count`.
    pub patch_count: usize,
    /// `p`: `mode_count`.
    pub mode_count: usize,
    /// `surface_count`.
    pub surface_count: usize,
    /// `m`: `channel_count`.
    pub channel_count: usize,
    /// `S`: `sensor_count`.
    pub sensor_count: usize,
    /// `Z`: `zone_count`.
    pub zone_count: usize,
    /// `Q`: grid pieces, the sum of `grid_pieces`.
    pub grid_piece_count: usize,
    /// `G`: grid points, the sum of the pieces' kept points.
    pub grid_point_count: usize,
    /// `D`: daylight nodes (sky patches, the exterior, the sun nodes); 0 without daylight.
    pub daylight_node_count: usize,
    /// The sun nodes among the daylight nodes (`sun_nodes`).
    pub sun_node_count: usize,
    /// `r`, the rank of the sky's stored first reflection; `None` when the basis stores no
    /// first reflection (patch exitance under daylight through the modes alone).
    pub reflection_rank: Option<usize>,
}

impl Counts {
    /// `O = S + Z`: outputs, sensors first.
    pub fn output_count(&self) -> Option<usize> {
        self.sensor_count.checked_add(self.zone_count)
    }

    /// Columns of `modes`: `B·p`.
    pub fn modes_cols(&self) -> Option<usize> {
        self.bands.checked_mul(self.mode_count)
    }

    /// Columns of `channel_response`: `m·B`.
    pub fn channel_response_cols(&self) -> Option<usize> {
        self.channel_count.checked_mul(self.bands)
    }

    /// Columns of `output_view`: `O`.
    pub fn output_view_cols(&self) -> Option<usize> {
        self.output_count()
    }

    /// Columns of `grid_view`: `n`.
    pub fn grid_view_cols(&self) -> Option<usize> {
        Some(self.patch_count)
    }

    /// Columns of `daylight_grid`: `D`.
    pub fn daylight_grid_cols(&self) -> Option<usize> {
        Some(self.daylight_node_count)
    }

    /// Columns of `daylight_modes`: `D` without a stored first reflection; with one, the
    /// `r` coefficients of the sky's and the sun nodes (docs/format.md, "First reflection").
    pub fn daylight_modes_cols(&self) -> Option<usize> {
        match self.reflection_rank {
            None => Some(self.daylight_node_count),
            Some(r) => r.checked_add(self.sun_node_count),
        }
    }

    /// Columns of `sky_reflection_weights`: the sky's patches and the exterior,
    /// `D − sun nodes`.
    pub fn sky_reflection_cols(&self) -> Option<usize> {
        self.daylight_node_count.checked_sub(self.sun_node_count)
    }
}

/// `D`, the daylight nodes of a basis whose sky is `sky_subdivision` and whose sun has
/// `sun_nodes` nodes: the sky's patches, the exterior and the sun nodes (0 without
/// daylight, `None` for a subdivision the sky patches do not have or an overflow).
pub(crate) fn daylight_nodes(sky_subdivision: u8, sun_nodes: usize) -> Option<usize> {
    if sky_subdivision == 0 {
        return Some(0);
    }
    let sky = crate::sky::patches::SkyPatches::reinhart(sky_subdivision).ok()?;
    sky.count().checked_add(1)?.checked_add(sun_nodes)
}
