//! A decoded, validated basis: views into the caller's bytes, nothing copied.

use crate::error::{Error, Result};
use crate::format::{Counts, Formulation, MatrixBytes, Payload, Precision, Quantity, NO_CHANNEL};
use crate::storage::{f32_at, u16_at, u32_at, Matrix};

/// Smallest non-zero reflectance: below it `A/ρ` could overflow; black is exactly 0.
pub const MIN_REFLECTANCE: f32 = 1.0e-6;

/// A radiosity eigenbasis read in place from a byte slice (e.g. flash).
///
/// Cheap to copy: it holds only slices into the original bytes. Build one with
/// [`Basis::from_bytes`], evaluate it with a [`ChannelEvaluator`](crate::ChannelEvaluator)
/// (channel levels only) or an [`Evaluator`](crate::Evaluator) (also exitance set patch by
/// patch).
#[derive(Clone, Copy, Debug)]
pub struct Basis<'a> {
    /// The payload's `quantity`, typed.
    pub(crate) quantity: Quantity,
    /// The payload's `formulation`, typed.
    pub(crate) formulation: Formulation,
    /// The payload's `precision`, typed.
    pub(crate) precision: Precision,
    /// `bands` and the payload's counts, as `usize`.
    pub(crate) counts: Counts,
    /// Header and payload, bytes.
    pub(crate) byte_len: usize,
    /// The payload, every table checked against the counts and its range.
    pub(crate) tables: Payload<'a>,
}

/// What the basis stores about one patch: its entries of the `patch_*` tables.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchInfo {
    /// Area (`patch_area`), m².
    pub area: f32,
    /// Centroid (`patch_centroid`), m.
    pub centroid: [f32; 3],
    /// Index of the named surface the patch belongs to (`patch_surface`).
    pub surface: usize,
    /// Channel that drives the patch's emission, if any (`patch_channel`).
    pub channel: Option<usize>,
    /// Reflectance per band (`patch_reflectance`; entries past [`Basis::bands`] are 0).
    pub reflectance: [f32; 3],
    /// Exitance emitted at channel level 1 per band (`patch_emission`), W/m² or lux
    /// (entries past [`Basis::bands`] are 0).
    pub emission: [f32; 3],
}

/// A point sensor's placement (its row of `sensor_geometry`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorInfo {
    /// Position, m.
    pub position: [f32; 3],
    /// Unit normal of the sensing surface.
    pub normal: [f32; 3],
    /// Field-of-view half-angle, rad (π/2 or more: the whole hemisphere).
    pub half_angle: f32,
}

/// One piece of a zone's calculation grid as stored (`grid_lattice`, `grid_layout`;
/// docs/format.md): a rectangular lattice of cells whose centres on the piece's area are
/// its points. A work plane has one piece, its band around a task area up to four, a
/// surface zone one per surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridPiece {
    /// Points the piece keeps: the cell centres on its area (at most the cells).
    pub points: usize,
    /// Cells along its first and second side.
    pub counts: [usize; 2],
    /// Largest spacing between points the layout used, m.
    pub spacing: f32,
    /// Cell sides along the first and second side, m (points sit at cell centres).
    pub cell: [f32; 2],
    /// Band left out at the walls, m.
    pub border: f32,
    /// Unit normal every point of the piece faces.
    pub normal: [f32; 3],
}

/// The site a basis' daylight was computed for (`daylight_site`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Site {
    /// Latitude, degrees north.
    pub latitude: f32,
    /// Longitude, degrees east.
    pub longitude: f32,
    /// Elevation, m.
    pub elevation: f32,
    /// Compass bearing of the scene's +y axis, degrees clockwise from true north.
    pub north: f32,
    /// The site's UTC offset, minutes (local time minus UTC).
    pub utc_offset_minutes: f32,
}

// The accessors trust the tables: `Basis::from_bytes`, in `decode/`, checked them (the
// daylight's values: `check_daylight`, before any daylight reader). It lives there so that
// decoding builds on this type and this module imports nothing of it.
impl<'a> Basis<'a> {
    /// Spectral bands: 1 (photopic) or 3 (RGB).
    pub fn bands(&self) -> usize {
        self.counts.bands
    }
    /// Whether values are W/m² (radiometric) or lux (photometric).
    pub fn quantity(&self) -> Quantity {
        self.quantity
    }
    /// The expansion the basis was built with.
    pub fn formulation(&self) -> Formulation {
        self.formulation
    }
    /// Storage precision of the large tables.
    pub fn precision(&self) -> Precision {
        self.precision
    }
    /// Number of patches `n`.
    pub fn patch_count(&self) -> usize {
        self.counts.patch_count
    }
    /// Number of modes `p` per band.
    pub fn mode_count(&self) -> usize {
        self.counts.mode_count
    }
    /// Number of named surfaces.
    pub fn surface_count(&self) -> usize {
        self.counts.surface_count
    }
    /// Number of channels `m`.
    pub fn channel_count(&self) -> usize {
        self.counts.channel_count
    }
    /// Number of sensors.
    pub fn sensor_count(&self) -> usize {
        self.counts.sensor_count
    }
    /// Number of zones.
    pub fn zone_count(&self) -> usize {
        self.counts.zone_count
    }
    /// Encoded size of the basis in bytes (header and payload).
    pub fn byte_len(&self) -> usize {
        self.byte_len
    }

    /// Mode `k`'s eigenvalue in `band`: `μ_k` (split) or `λ_k` (seed).
    pub fn eigenvalue(&self, band: usize, k: usize) -> Result<f32> {
        let c = &self.counts;
        check_index("band", band, c.bands)?;
        check_index("mode", k, c.mode_count)?;
        Ok(f32_at(self.tables.eigenvalues, band * c.mode_count + k))
    }

    /// The `index`-th entry of the name table, as stored: a postcard byte string (a varint
    /// length and the bytes; postcard writes a `&str` the same way). Stepping over entries as
    /// bytes reads no UTF-8: only the name returned is checked ([`Basis::named`]), so that a
    /// controller that finds channels by name links no UTF-8 validation.
    fn name_bytes(&self, index: usize) -> Option<&'a [u8]> {
        let mut rest = self.tables.names;
        for _ in 0..index {
            rest = postcard::take_from_bytes::<&[u8]>(rest).ok()?.1;
        }
        postcard::take_from_bytes::<&[u8]>(rest)
            .ok()
            .map(|(s, _)| s)
    }

    /// Name `index` of the names from `base` on (`count` of them): checked against the count,
    /// then as UTF-8, the one check of the name table `from_bytes` leaves to the reader.
    fn named(
        &self,
        what: &'static str,
        base: usize,
        index: usize,
        count: usize,
    ) -> Result<&'a str> {
        check_index(what, index, count)?;
        let bytes = self.name_bytes(base + index).ok_or(Error::DecodePayload)?;
        core::str::from_utf8(bytes).map_err(|_| Error::DecodeValue {
            field: "names",
            index: base + index,
        })
    }

    /// Index among the names from `base` on (`count` of them) of the one whose bytes are
    /// `name`'s: a name that is not UTF-8 equals no `&str`.
    fn find(&self, base: usize, count: usize, name: &str) -> Option<usize> {
        let mut rest = self.tables.names;
        for i in 0..base + count {
            let (s, tail) = postcard::take_from_bytes::<&[u8]>(rest).ok()?;
            if i >= base && same_bytes(s, name.as_bytes()) {
                return Some(i - base);
            }
            rest = tail;
        }
        None
    }

    /// Where the channels' names start in the name table (after the surfaces').
    fn channel_names(&self) -> usize {
        self.counts.surface_count
    }
    /// Where the sensors' names start in the name table.
    fn sensor_names(&self) -> usize {
        self.channel_names() + self.counts.channel_count
    }
    /// Where the zones' names start in the name table.
    fn zone_names(&self) -> usize {
        self.sensor_names() + self.counts.sensor_count
    }

    /// Name of surface `index`.
    pub fn surface_name(&self, index: usize) -> Result<&'a str> {
        self.named("surface", 0, index, self.counts.surface_count)
    }
    /// Name of channel `index`.
    pub fn channel_name(&self, index: usize) -> Result<&'a str> {
        let count = self.counts.channel_count;
        self.named("channel", self.channel_names(), index, count)
    }
    /// Name of sensor `index`.
    pub fn sensor_name(&self, index: usize) -> Result<&'a str> {
        let count = self.counts.sensor_count;
        self.named("sensor", self.sensor_names(), index, count)
    }
    /// Name of zone `index`.
    pub fn zone_name(&self, index: usize) -> Result<&'a str> {
        self.named("zone", self.zone_names(), index, self.counts.zone_count)
    }
    /// Index of the channel called `name`.
    pub fn find_channel(&self, name: &str) -> Option<usize> {
        self.find(self.channel_names(), self.counts.channel_count, name)
    }
    /// Index of the sensor called `name`.
    pub fn find_sensor(&self, name: &str) -> Option<usize> {
        self.find(self.sensor_names(), self.counts.sensor_count, name)
    }
    /// Index of the zone called `name`.
    pub fn find_zone(&self, name: &str) -> Option<usize> {
        self.find(self.zone_names(), self.counts.zone_count, name)
    }

    /// What the basis stores about patch `index`.
    pub fn patch(&self, index: usize) -> Result<PatchInfo> {
        check_index("patch", index, self.counts.patch_count)?;
        let t = &self.tables;
        let bands = self.counts.bands;
        let mut reflectance = [0.0; 3];
        let mut emission = [0.0; 3];
        for b in 0..bands.min(3) {
            if let (Some(r), Some(e)) = (reflectance.get_mut(b), emission.get_mut(b)) {
                *r = f32_at(t.patch_reflectance, index * bands + b);
                *e = f32_at(t.patch_emission, index * bands + b);
            }
        }
        let channel = u16_at(t.patch_channel, index);
        Ok(PatchInfo {
            area: f32_at(t.patch_area, index),
            centroid: [
                f32_at(t.patch_centroid, index * 3),
                f32_at(t.patch_centroid, index * 3 + 1),
                f32_at(t.patch_centroid, index * 3 + 2),
            ],
            surface: usize::from(u16_at(t.patch_surface, index)),
            channel: (channel != NO_CHANNEL).then_some(usize::from(channel)),
            reflectance,
            emission,
        })
    }

    /// Placement of sensor `index`.
    pub fn sensor(&self, index: usize) -> Result<SensorInfo> {
        check_index("sensor", index, self.counts.sensor_count)?;
        let g = |k: usize| f32_at(self.tables.sensor_geometry, index * 7 + k);
        Ok(SensorInfo {
            position: [g(0), g(1), g(2)],
            normal: [g(3), g(4), g(5)],
            half_angle: g(6),
        })
    }

    /// Area of zone `index`, m².
    pub fn zone_area(&self, index: usize) -> Result<f32> {
        check_index("zone", index, self.counts.zone_count)?;
        Ok(f32_at(self.tables.zone_area, index))
    }

    /// Number of grid points over all zones.
    pub fn grid_point_count(&self) -> usize {
        self.counts.grid_point_count
    }

    /// Number of pieces of zone `zone`'s calculation grid (0: the zone has none).
    pub fn grid_piece_count(&self, zone: usize) -> Result<usize> {
        Ok(self.piece_range(zone)?.1)
    }

    /// Piece `piece` of zone `zone`'s calculation grid.
    pub fn grid_piece(&self, zone: usize, piece: usize) -> Result<GridPiece> {
        let (first, len) = self.piece_range(zone)?;
        check_index("grid piece", piece, len)?;
        let q = first + piece;
        let t = &self.tables;
        let g = |k: usize| f32_at(t.grid_layout, q * 7 + k);
        let n = |k: usize| u32_at(t.grid_lattice, q * 3 + k) as usize;
        Ok(GridPiece {
            points: n(2),
            counts: [n(0), n(1)],
            spacing: g(0),
            cell: [g(1), g(2)],
            border: g(3),
            normal: [g(4), g(5), g(6)],
        })
    }

    /// Number of points of zone `zone`'s calculation grid, over all its pieces.
    pub fn grid_points(&self, zone: usize) -> Result<usize> {
        Ok(self.grid_range(zone)?.1)
    }

    /// Position (m) of point `point` of zone `zone`'s grid (first side fastest).
    pub fn grid_point(&self, zone: usize, point: usize) -> Result<[f32; 3]> {
        let g = self.grid_index(zone, point)?;
        let p = |k: usize| f32_at(self.tables.grid_position, g * 3 + k);
        Ok([p(0), p(1), p(2)])
    }

    /// Position (m) and unit normal of grid point `g` among all grid points (zone by zone),
    /// `None` out of range: the normal is its piece's.
    pub(crate) fn grid_point_placement(&self, g: usize) -> Option<([f32; 3], [f32; 3])> {
        let t = &self.tables;
        let mut start = 0usize;
        for q in 0..self.counts.grid_piece_count {
            start = start.saturating_add(u32_at(t.grid_lattice, 3 * q + 2) as usize);
            if g < start {
                let at = |table: &[u8], k: usize| f32_at(table, k);
                let position = [0, 1, 2].map(|k| at(t.grid_position, 3 * g + k));
                let normal = [4, 5, 6].map(|k| at(t.grid_layout, 7 * q + k));
                return Some((position, normal));
            }
        }
        None
    }

    /// Where zone `zone`'s pieces start among all grid pieces, and how many it has.
    fn piece_range(&self, zone: usize) -> Result<(usize, usize)> {
        check_index("zone", zone, self.counts.zone_count)?;
        let pieces = |z: usize| u32_at(self.tables.grid_pieces, z) as usize;
        let start = (0..zone).map(pieces).fold(0usize, usize::saturating_add);
        Ok((start, pieces(zone)))
    }

    /// Where zone `zone`'s points start among all grid points, and how many it has.
    pub(crate) fn grid_range(&self, zone: usize) -> Result<(usize, usize)> {
        let (first, len) = self.piece_range(zone)?;
        let kept = |q: usize| u32_at(self.tables.grid_lattice, 3 * q + 2) as usize;
        let sum = |r: core::ops::Range<usize>| r.map(kept).fold(0usize, usize::saturating_add);
        Ok((sum(0..first), sum(first..first + len)))
    }

    /// Index among all grid points of point `point` of zone `zone`, checked.
    pub(crate) fn grid_index(&self, zone: usize, point: usize) -> Result<usize> {
        let (start, len) = self.grid_range(zone)?;
        check_index("grid point", point, len)?;
        Ok(start + point)
    }

    /// The `grid_view` matrix: `G × n`.
    pub(crate) fn grid_view(&self) -> Matrix<'a> {
        self.matrix(self.tables.grid_view, self.counts.grid_view_cols())
    }

    /// Whether the basis carries daylight (its scene had a site and glazed windows).
    pub fn has_daylight(&self) -> bool {
        self.tables.sky_subdivision != 0
    }

    /// Checks the values of the basis' daylight section (docs/format.md, "Daylight" and
    /// "Direct sun"): the site, the sun grid and its nodes in range, every node table finite
    /// and bounded, the direct sun's geometry. `Ok` without daylight.
    ///
    /// [`Basis::from_bytes`] checks only the section's shape (which tables, how long), so that
    /// a firmware that reads no daylight links none of this; every daylight reader calls it:
    /// [`DirectSun::new`](crate::sky::direct::DirectSun::new) and so
    /// [`DaylightEvaluator::new`](crate::DaylightEvaluator::new). A tool that reads
    /// [`site`](Self::site) or [`sun_grid`](Self::sun_grid) alone calls it first: until it
    /// has, those are the stored values as they are. A corrupt value is the decoder's error
    /// naming its table.
    pub fn check_daylight(&self) -> Result<()> {
        crate::decode::check_daylight(&self.tables, &self.counts, self.precision)
    }

    /// The sky patches of the basis' daylight, `None` without daylight. A
    /// [`DaylightEvaluator`](crate::DaylightEvaluator) takes one luminance per patch, in
    /// their order.
    pub fn sky_patches(&self) -> Option<crate::sky::patches::SkyPatches> {
        crate::sky::patches::SkyPatches::reinhart(self.tables.sky_subdivision).ok()
    }

    /// The site of the basis' daylight, `None` without daylight: as stored, within the
    /// ranges of docs/format.md once [`check_daylight`](Self::check_daylight) has passed.
    pub fn site(&self) -> Option<Site> {
        if !self.has_daylight() {
            return None;
        }
        let at = |k: usize| f32_at(self.tables.daylight_site, k);
        Some(Site {
            latitude: at(0),
            longitude: at(1),
            elevation: at(2),
            north: at(3),
            utc_offset_minutes: at(4),
        })
    }

    /// The grid of sun directions the basis' daylight stores the sun at, `None` without
    /// daylight: as stored, within the ranges of docs/format.md once
    /// [`check_daylight`](Self::check_daylight) has passed.
    // Inlined: a sky update reads the grid on every call, and a returned `Option` of it
    // was copied through `memcpy`.
    #[inline]
    pub fn sun_grid(&self) -> Option<crate::sky::sun_grid::SunGrid> {
        let site = self.site()?;
        let t = &self.tables;
        Some(crate::sky::sun_grid::SunGrid {
            latitude: site.latitude,
            declination_first: f32_at(t.sun_spacing, 0),
            declination_step: f32_at(t.sun_spacing, 1),
            rows: u32_at(t.sun_lattice, 0) as usize,
            hour_first: f32_at(t.sun_spacing, 2),
            hour_step: f32_at(t.sun_spacing, 3),
            columns: u32_at(t.sun_lattice, 1) as usize,
        })
    }

    /// Number of sun-grid nodes that light the room (stored ones).
    pub fn sun_node_count(&self) -> usize {
        self.tables.sun_nodes.len() / 4
    }

    /// Number of daylight nodes `D`: sky patches, the exterior, the stored sun nodes (0
    /// without daylight).
    pub fn daylight_node_count(&self) -> usize {
        self.counts.daylight_node_count
    }

    /// Where sun-grid node `node` is among the stored sun nodes, if it lights the room.
    pub(crate) fn sun_node_position(&self, node: usize) -> Option<usize> {
        search_u32(self.tables.sun_nodes, node)
    }

    /// The `daylight_grid` matrix: `G × D`.
    pub(crate) fn daylight_grid(&self) -> Matrix<'a> {
        self.matrix(self.tables.daylight_grid, self.counts.daylight_grid_cols())
    }

    /// The `sky_reflection` matrix: `n × r` (empty without a first reflection).
    pub(crate) fn sky_reflection(&self) -> Matrix<'a> {
        self.matrix(
            self.tables.sky_reflection,
            Some(self.counts.reflection_rank.unwrap_or(0)),
        )
    }

    /// The rank `r` of the sky's stored first reflection under daylight, `None` when the
    /// basis stores none (its patches' daylight then comes through the modes alone:
    /// docs/math.md, "Daylight's first reflection").
    pub fn daylight_reflection_rank(&self) -> Option<usize> {
        self.counts.reflection_rank
    }

    /// The values a [`DaylightEvaluator`](crate::DaylightEvaluator) keeps to read patch
    /// exitance: the `p` mode amplitudes and the `r` coefficients of the first reflection.
    /// Its capacity `EXITANCE` must hold them.
    pub fn daylight_exitance_state(&self) -> usize {
        self.counts
            .mode_count
            .saturating_add(self.counts.reflection_rank.unwrap_or(0))
    }

    /// Position of patch `patch` in the black-patch list, if it is black in some band.
    pub(crate) fn black_index(&self, patch: usize) -> Option<usize> {
        search_u32(self.tables.black_patches, patch)
    }

    /// The `modes` matrix: `n × (B·p)`, column `b·p + k` is mode `k` of band `b`.
    pub(crate) fn modes(&self) -> Matrix<'a> {
        self.matrix(self.tables.modes, self.counts.modes_cols())
    }

    /// The `channel_response` matrix: `n × (m·B)`, column `c·B + b`.
    pub(crate) fn channel_response(&self) -> Matrix<'a> {
        self.matrix(
            self.tables.channel_response,
            self.counts.channel_response_cols(),
        )
    }

    /// The `output_view` matrix: `n × O`.
    pub(crate) fn output_view(&self) -> Matrix<'a> {
        self.matrix(self.tables.output_view, self.counts.output_view_cols())
    }

    /// A view of a matrix table with `cols` columns; decoding checked that `cols` exists
    /// and fits the table.
    fn matrix(&self, raw: MatrixBytes<'a>, cols: Option<usize>) -> Matrix<'a> {
        Matrix {
            precision: self.precision,
            cols: cols.unwrap_or(0),
            scales: raw.scales,
            data: raw.data,
        }
    }
}

/// Whether `a` and `b` hold the same bytes, compared one by one: `==` on slices calls
/// `memcmp`, which a controller finding names would link for this alone.
fn same_bytes(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x == y)
}

/// Position of `value` in an ascending table of little-endian `u32`, by bisection.
fn search_u32(table: &[u8], value: usize) -> Option<usize> {
    let (mut lo, mut hi) = (0usize, table.len() / 4);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        let v = u32_at(table, mid) as usize;
        if v == value {
            return Some(mid);
        }
        if v < value {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    None
}

pub(crate) fn check_index(what: &'static str, index: usize, count: usize) -> Result<()> {
    if index < count {
        Ok(())
    } else {
        Err(Error::IndexOutOfRange { what, index, count })
    }
}
