//! A decoded, validated basis: views into the caller's bytes, nothing copied.

use crate::error::{Error, Result};
use crate::format::{self, Formulation, MatrixBytes, Precision, Quantity, NO_CHANNEL};
use crate::storage::{f32_at, f32s, u16_at, u32_at, Matrix};

/// Largest magnitude accepted for any stored number. Keeps every sum the evaluator forms
/// far from `f32` overflow, while leaving room for any physical scene (10⁹ lux is 10⁴ suns).
const VALUE_LIMIT: f32 = 1.0e9;
/// Smallest non-zero reflectance: below it `A/ρ` could overflow; black is exactly 0.
pub const MIN_REFLECTANCE: f32 = 1.0e-6;
/// Largest `|μ|` for the split formulation: `c = μ/(1−μ)` stays below 10⁶.
const MAX_MU: f32 = 1.0 - 1.0e-6;

/// A radiosity eigenbasis read in place from a byte slice (e.g. flash).
///
/// Cheap to copy: it holds only slices into the original bytes. Build one with
/// [`Basis::from_bytes`], evaluate it with an [`Evaluator`](crate::Evaluator).
#[derive(Clone, Copy, Debug)]
pub struct Basis<'a> {
    pub(crate) bands: usize,
    pub(crate) quantity: Quantity,
    pub(crate) formulation: Formulation,
    pub(crate) precision: Precision,
    pub(crate) patches: usize,
    pub(crate) modes: usize,
    pub(crate) surfaces: usize,
    pub(crate) channels: usize,
    pub(crate) sensors: usize,
    pub(crate) zones: usize,
    pub(crate) byte_len: usize,
    pub(crate) names: &'a [u8],
    pub(crate) eigenvalues: &'a [u8],
    pub(crate) area: &'a [u8],
    pub(crate) centroid: &'a [u8],
    pub(crate) surface: &'a [u8],
    pub(crate) channel: &'a [u8],
    pub(crate) reflectance: &'a [u8],
    pub(crate) emission: &'a [u8],
    pub(crate) mode_vectors: Matrix<'a>,
    pub(crate) black_patches: &'a [u8],
    pub(crate) black_projection: &'a [u8],
    pub(crate) channel_projection: &'a [u8],
    pub(crate) channel_bounce: Matrix<'a>,
    pub(crate) sensor_geometry: &'a [u8],
    pub(crate) zone_area: &'a [u8],
    pub(crate) output_modes: &'a [u8],
    pub(crate) output_channels: &'a [u8],
    pub(crate) output_view: Matrix<'a>,
}

/// What the basis stores about one patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchInfo {
    /// Area, m².
    pub area: f32,
    /// Centroid, m.
    pub centroid: [f32; 3],
    /// Index of the named surface the patch belongs to.
    pub surface: usize,
    /// Channel that drives the patch's emission, if any.
    pub channel: Option<usize>,
    /// Reflectance per band (entries past [`Basis::bands`] are 0).
    pub reflectance: [f32; 3],
    /// Exitance emitted at channel level 1 per band, W/m² or lux (entries past
    /// [`Basis::bands`] are 0).
    pub emission: [f32; 3],
}

/// A point sensor's placement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorInfo {
    /// Position, m.
    pub position: [f32; 3],
    /// Unit normal of the sensing surface.
    pub normal: [f32; 3],
    /// Field-of-view half-angle, rad (π/2 or more: the whole hemisphere).
    pub half_angle: f32,
}

fn field_value(field: &'static str, value: u8) -> Error {
    Error::DecodeField {
        field,
        value: u32::from(value),
    }
}

fn mul(a: usize, b: usize) -> Result<usize> {
    a.checked_mul(b).ok_or(Error::DecodeField {
        field: "dimensions",
        value: u32::MAX,
    })
}

/// Checks that `bytes` holds exactly `count` values of `width` bytes.
fn check_len(field: &'static str, bytes: &[u8], count: usize, width: usize) -> Result<()> {
    let expected = mul(count, width)?;
    if bytes.len() == expected {
        Ok(())
    } else {
        Err(Error::DecodeLength {
            field,
            expected,
            found: bytes.len(),
        })
    }
}

/// Checks every `f32` of a table against `ok`.
fn check_f32(field: &'static str, bytes: &[u8], ok: impl Fn(f32) -> bool) -> Result<()> {
    match f32s(bytes).position(|v| !ok(v)) {
        Some(index) => Err(Error::DecodeValue { field, index }),
        None => Ok(()),
    }
}

fn bounded(v: f32) -> bool {
    v.is_finite() && v.abs() <= VALUE_LIMIT
}

fn matrix<'a>(
    field: &'static str,
    scales_field: &'static str,
    raw: MatrixBytes<'a>,
    precision: Precision,
    rows: usize,
    cols: usize,
) -> Result<Matrix<'a>> {
    check_len(field, raw.data, mul(rows, cols)?, precision.bytes())?;
    match precision {
        Precision::F32 => {
            check_len(scales_field, raw.scales, 0, 4)?;
            check_f32(field, raw.data, bounded)?;
        }
        Precision::F16 => {
            check_len(scales_field, raw.scales, cols, 4)?;
            check_f32(scales_field, raw.scales, |s| bounded(s) && s >= 0.0)?;
            // Exponent 31 is infinity or NaN.
            if let Some(index) = raw
                .data
                .chunks_exact(2)
                .position(|c| matches!(*c, [_, hi] if hi & 0x7C == 0x7C))
            {
                return Err(Error::DecodeValue { field, index });
            }
        }
        Precision::I16 => {
            check_len(scales_field, raw.scales, cols, 4)?;
            check_f32(scales_field, raw.scales, |s| bounded(s) && s >= 0.0)?;
        }
    }
    Ok(Matrix {
        precision,
        cols,
        scales: raw.scales,
        data: raw.data,
    })
}

impl<'a> Basis<'a> {
    /// Decodes and validates a basis in place.
    ///
    /// Checks the magic, the format version, the CRC-32 of the payload, every table length
    /// against the dimensions, and that every stored number is finite and in range. Vector
    /// data stays where it is (flash): only slice headers are kept. Any byte string gives
    /// `Ok` or an `Err`; none panics.
    pub fn from_bytes(bytes: &'a [u8]) -> Result<Self> {
        let raw = format::decode(bytes)?;
        let bands = match raw.bands {
            1 | 3 => usize::from(raw.bands),
            other => return Err(field_value("bands", other)),
        };
        let quantity = match raw.quantity {
            0 => Quantity::Radiometric,
            1 => Quantity::Photometric,
            other => return Err(field_value("quantity", other)),
        };
        if quantity == Quantity::Photometric && bands != 1 {
            return Err(field_value("quantity", raw.quantity));
        }
        let formulation = match raw.formulation {
            0 => Formulation::Split,
            1 => Formulation::Seed,
            other => return Err(field_value("formulation", other)),
        };
        let precision = match raw.precision {
            0 => Precision::F32,
            1 => Precision::F16,
            2 => Precision::I16,
            other => return Err(field_value("precision", other)),
        };
        let n = raw.patch_count as usize;
        let p = raw.mode_count as usize;
        let surfaces = raw.surface_count as usize;
        let m = raw.channel_count as usize;
        let sensors = raw.sensor_count as usize;
        let zones = raw.zone_count as usize;
        if surfaces > usize::from(u16::MAX) || m >= usize::from(NO_CHANNEL) {
            return Err(Error::DecodeField {
                field: "surface_count or channel_count",
                value: u32::MAX,
            });
        }
        let outputs = sensors.checked_add(zones).ok_or(Error::DecodeField {
            field: "zone_count",
            value: raw.zone_count,
        })?;
        let bp = mul(bands, p)?;
        let header_len = format::HEADER_LEN;
        let payload_len = bytes.get(12..16).map_or(0, |b| u32_at(b, 0) as usize);

        // Names: surfaces, channels, sensors, zones, as consecutive postcard strings.
        let name_count = surfaces
            .checked_add(m)
            .and_then(|x| x.checked_add(outputs))
            .ok_or(Error::DecodeField {
                field: "names",
                value: u32::MAX,
            })?;
        let mut rest = raw.names;
        for _ in 0..name_count {
            let (_, tail) =
                postcard::take_from_bytes::<&str>(rest).map_err(|_| Error::DecodePayload)?;
            rest = tail;
        }
        if !rest.is_empty() {
            return Err(Error::DecodeLength {
                field: "names",
                expected: raw.names.len() - rest.len(),
                found: raw.names.len(),
            });
        }

        check_len("eigenvalues", raw.eigenvalues, bp, 4)?;
        match formulation {
            Formulation::Split => {
                check_f32("eigenvalues", raw.eigenvalues, |mu| mu.abs() <= MAX_MU)?
            }
            Formulation::Seed => check_f32("eigenvalues", raw.eigenvalues, |l| {
                bounded(l) && l >= 1.0e-30
            })?,
        }
        check_len("patch_area", raw.patch_area, n, 4)?;
        check_f32("patch_area", raw.patch_area, |a| bounded(a) && a > 0.0)?;
        check_len("patch_centroid", raw.patch_centroid, mul(n, 3)?, 4)?;
        check_f32("patch_centroid", raw.patch_centroid, bounded)?;
        check_len("patch_surface", raw.patch_surface, n, 2)?;
        if let Some(index) =
            (0..n).position(|i| usize::from(u16_at(raw.patch_surface, i)) >= surfaces)
        {
            return Err(Error::DecodeValue {
                field: "patch_surface",
                index,
            });
        }
        check_len("patch_channel", raw.patch_channel, n, 2)?;
        if let Some(index) = (0..n).position(|i| {
            let c = u16_at(raw.patch_channel, i);
            c != NO_CHANNEL && usize::from(c) >= m
        }) {
            return Err(Error::DecodeValue {
                field: "patch_channel",
                index,
            });
        }
        let nb = mul(n, bands)?;
        check_len("patch_reflectance", raw.patch_reflectance, nb, 4)?;
        check_f32("patch_reflectance", raw.patch_reflectance, |r| {
            r == 0.0 || (MIN_REFLECTANCE..1.0).contains(&r)
        })?;
        check_len("patch_emission", raw.patch_emission, nb, 4)?;
        check_f32("patch_emission", raw.patch_emission, |e| {
            bounded(e) && e >= 0.0
        })?;
        // Emission belongs to a channel: a patch outside every channel emits nothing.
        if let Some(index) = (0..nb).position(|k| {
            f32_at(raw.patch_emission, k) != 0.0
                && u16_at(raw.patch_channel, k / bands) == NO_CHANNEL
        }) {
            return Err(Error::DecodeValue {
                field: "patch_emission",
                index,
            });
        }

        let mode_vectors = matrix("modes.data", "modes.scales", raw.modes, precision, n, bp)?;

        // Black patches: ascending, in range, and every patch with a zero reflectance listed.
        if raw.black_patches.len() % 4 != 0 {
            return Err(Error::DecodeLength {
                field: "black_patches",
                expected: raw.black_patches.len() / 4 * 4,
                found: raw.black_patches.len(),
            });
        }
        let black = raw.black_patches.len() / 4;
        let mut next = 0usize;
        for i in 0..n {
            let is_black = (0..bands).any(|b| f32_at(raw.patch_reflectance, i * bands + b) == 0.0);
            let listed = next < black && u32_at(raw.black_patches, next) as usize == i;
            if is_black != listed {
                return Err(Error::DecodeValue {
                    field: "black_patches",
                    index: next,
                });
            }
            if listed {
                next += 1;
            }
        }
        if next != black {
            return Err(Error::DecodeValue {
                field: "black_patches",
                index: next,
            });
        }
        check_len("black_projection", raw.black_projection, mul(black, bp)?, 4)?;
        check_f32("black_projection", raw.black_projection, bounded)?;

        check_len("channel_projection", raw.channel_projection, mul(m, bp)?, 4)?;
        check_f32("channel_projection", raw.channel_projection, bounded)?;
        let bounce_cols = match formulation {
            Formulation::Split => mul(m, bands)?,
            Formulation::Seed => 0,
        };
        let channel_bounce = matrix(
            "channel_bounce.data",
            "channel_bounce.scales",
            raw.channel_bounce,
            precision,
            n,
            bounce_cols,
        )?;

        check_len("sensor_geometry", raw.sensor_geometry, mul(sensors, 7)?, 4)?;
        check_f32("sensor_geometry", raw.sensor_geometry, bounded)?;
        check_len("zone_area", raw.zone_area, zones, 4)?;
        check_f32("zone_area", raw.zone_area, |a| bounded(a) && a > 0.0)?;
        check_len("output_modes", raw.output_modes, mul(outputs, bp)?, 4)?;
        check_f32("output_modes", raw.output_modes, bounded)?;
        check_len(
            "output_channels",
            raw.output_channels,
            mul(mul(outputs, bands)?, m)?,
            4,
        )?;
        check_f32("output_channels", raw.output_channels, bounded)?;
        let output_view = matrix(
            "output_view.data",
            "output_view.scales",
            raw.output_view,
            precision,
            n,
            outputs,
        )?;

        Ok(Basis {
            bands,
            quantity,
            formulation,
            precision,
            patches: n,
            modes: p,
            surfaces,
            channels: m,
            sensors,
            zones,
            byte_len: header_len + payload_len,
            names: raw.names,
            eigenvalues: raw.eigenvalues,
            area: raw.patch_area,
            centroid: raw.patch_centroid,
            surface: raw.patch_surface,
            channel: raw.patch_channel,
            reflectance: raw.patch_reflectance,
            emission: raw.patch_emission,
            mode_vectors,
            black_patches: raw.black_patches,
            black_projection: raw.black_projection,
            channel_projection: raw.channel_projection,
            channel_bounce,
            sensor_geometry: raw.sensor_geometry,
            zone_area: raw.zone_area,
            output_modes: raw.output_modes,
            output_channels: raw.output_channels,
            output_view,
        })
    }

    /// Spectral bands: 1 (photopic) or 3 (RGB).
    pub fn bands(&self) -> usize {
        self.bands
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
        self.patches
    }
    /// Number of modes `p` per band.
    pub fn mode_count(&self) -> usize {
        self.modes
    }
    /// Number of named surfaces.
    pub fn surface_count(&self) -> usize {
        self.surfaces
    }
    /// Number of channels `m`.
    pub fn channel_count(&self) -> usize {
        self.channels
    }
    /// Number of sensors.
    pub fn sensor_count(&self) -> usize {
        self.sensors
    }
    /// Number of zones.
    pub fn zone_count(&self) -> usize {
        self.zones
    }
    /// Encoded size of the basis in bytes (header and payload).
    pub fn byte_len(&self) -> usize {
        self.byte_len
    }

    /// Mode `k`'s eigenvalue in `band`: `μ_k` (split) or `λ_k` (seed).
    pub fn eigenvalue(&self, band: usize, k: usize) -> Result<f32> {
        check_index("band", band, self.bands)?;
        check_index("mode", k, self.modes)?;
        Ok(f32_at(self.eigenvalues, band * self.modes + k))
    }

    /// The `index`-th string of the name table.
    fn name(&self, index: usize) -> Option<&'a str> {
        let mut rest = self.names;
        for _ in 0..index {
            rest = postcard::take_from_bytes::<&str>(rest).ok()?.1;
        }
        postcard::take_from_bytes::<&str>(rest).ok().map(|(s, _)| s)
    }

    fn named(
        &self,
        what: &'static str,
        base: usize,
        index: usize,
        count: usize,
    ) -> Result<&'a str> {
        check_index(what, index, count)?;
        self.name(base + index).ok_or(Error::DecodePayload)
    }

    fn find(&self, base: usize, count: usize, name: &str) -> Option<usize> {
        let mut rest = self.names;
        for i in 0..base + count {
            let (s, tail) = postcard::take_from_bytes::<&str>(rest).ok()?;
            if i >= base && s == name {
                return Some(i - base);
            }
            rest = tail;
        }
        None
    }

    /// Name of surface `index`.
    pub fn surface_name(&self, index: usize) -> Result<&'a str> {
        self.named("surface", 0, index, self.surfaces)
    }
    /// Name of channel `index`.
    pub fn channel_name(&self, index: usize) -> Result<&'a str> {
        self.named("channel", self.surfaces, index, self.channels)
    }
    /// Name of sensor `index`.
    pub fn sensor_name(&self, index: usize) -> Result<&'a str> {
        self.named("sensor", self.surfaces + self.channels, index, self.sensors)
    }
    /// Name of zone `index`.
    pub fn zone_name(&self, index: usize) -> Result<&'a str> {
        self.named(
            "zone",
            self.surfaces + self.channels + self.sensors,
            index,
            self.zones,
        )
    }
    /// Index of the channel called `name`.
    pub fn find_channel(&self, name: &str) -> Option<usize> {
        self.find(self.surfaces, self.channels, name)
    }
    /// Index of the sensor called `name`.
    pub fn find_sensor(&self, name: &str) -> Option<usize> {
        self.find(self.surfaces + self.channels, self.sensors, name)
    }
    /// Index of the zone called `name`.
    pub fn find_zone(&self, name: &str) -> Option<usize> {
        self.find(
            self.surfaces + self.channels + self.sensors,
            self.zones,
            name,
        )
    }

    /// What the basis stores about patch `index`.
    pub fn patch(&self, index: usize) -> Result<PatchInfo> {
        check_index("patch", index, self.patches)?;
        let mut reflectance = [0.0; 3];
        let mut emission = [0.0; 3];
        for b in 0..self.bands.min(3) {
            if let (Some(r), Some(e)) = (reflectance.get_mut(b), emission.get_mut(b)) {
                *r = f32_at(self.reflectance, index * self.bands + b);
                *e = f32_at(self.emission, index * self.bands + b);
            }
        }
        let channel = u16_at(self.channel, index);
        Ok(PatchInfo {
            area: f32_at(self.area, index),
            centroid: [
                f32_at(self.centroid, index * 3),
                f32_at(self.centroid, index * 3 + 1),
                f32_at(self.centroid, index * 3 + 2),
            ],
            surface: usize::from(u16_at(self.surface, index)),
            channel: (channel != NO_CHANNEL).then_some(usize::from(channel)),
            reflectance,
            emission,
        })
    }

    /// Placement of sensor `index`.
    pub fn sensor(&self, index: usize) -> Result<SensorInfo> {
        check_index("sensor", index, self.sensors)?;
        let g = |k: usize| f32_at(self.sensor_geometry, index * 7 + k);
        Ok(SensorInfo {
            position: [g(0), g(1), g(2)],
            normal: [g(3), g(4), g(5)],
            half_angle: g(6),
        })
    }

    /// Area of zone `index`, m².
    pub fn zone_area(&self, index: usize) -> Result<f32> {
        check_index("zone", index, self.zones)?;
        Ok(f32_at(self.zone_area, index))
    }

    /// Position of patch `patch` in the black-patch list, if it is black in some band.
    pub(crate) fn black_index(&self, patch: usize) -> Option<usize> {
        let count = self.black_patches.len() / 4;
        let (mut lo, mut hi) = (0usize, count);
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            let v = u32_at(self.black_patches, mid) as usize;
            if v == patch {
                return Some(mid);
            }
            if v < patch {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        None
    }
}

pub(crate) fn check_index(what: &'static str, index: usize, count: usize) -> Result<()> {
    if index < count {
        Ok(())
    } else {
        Err(Error::IndexOutOfRange { what, index, count })
    }
}
