//! Writing a basis from owned tables (feature `alloc`; host tools and tests).
//!
//! The precompute fills a [`BasisTables`] in `f64` and calls [`BasisTables::to_bytes`]; the
//! quantisation to the storage precision and the byte layout live here, next to the reader,
//! so the two cannot drift apart.

use alloc::string::String;
use alloc::vec;
use alloc::vec::Vec;

use crate::error::{Error, Result};
use crate::format::{
    self, f32_to_f16, Formulation, MatrixBytes, Payload, Precision, Quantity, NO_CHANNEL,
};

/// Every table of a basis, owned, in `f64`, with the counts implied by the lengths.
///
/// Fields carry the names of `docs/format.md`'s payload. Notation as there: `n` patches, `p`
/// modes, `B` bands, `m` channels, `O` outputs (sensors, then zones). Matrices are row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct BasisTables {
    /// What the numbers measure: W/m² or lux.
    pub quantity: Quantity,
    /// Expansion used.
    pub formulation: Formulation,
    /// Storage of the three matrices (`modes`, `channel_bounce`, `output_view`).
    pub precision: Precision,
    /// `B`: 1 or 3.
    pub bands: usize,
    /// `p`: modes per band.
    pub mode_count: usize,
    /// Surface names.
    pub surface_names: Vec<String>,
    /// Channel names (`m`).
    pub channel_names: Vec<String>,
    /// Sensor names.
    pub sensor_names: Vec<String>,
    /// Zone names.
    pub zone_names: Vec<String>,
    /// `B × p`: `μ` (split) or `λ` (seed).
    pub eigenvalues: Vec<f64>,
    /// `n`, m².
    pub patch_area: Vec<f64>,
    /// `n`, m.
    pub patch_centroid: Vec<[f64; 3]>,
    /// `n` surface indices.
    pub patch_surface: Vec<u16>,
    /// `n` channel indices.
    pub patch_channel: Vec<Option<u16>>,
    /// `n × B`.
    pub patch_reflectance: Vec<f64>,
    /// `n × B`, exitance at level 1.
    pub patch_emission: Vec<f64>,
    /// `n × (B·p)`: mode vectors, patch-major.
    pub modes: Vec<f64>,
    /// `black × B × p`, black patches in ascending order (those with ρ = 0 in some band).
    pub black_projection: Vec<f64>,
    /// `m × B × p`.
    pub channel_projection: Vec<f64>,
    /// `n × (m·B)` (split) or empty (seed).
    pub channel_bounce: Vec<f64>,
    /// Per sensor: position (m), unit normal, half-angle (rad).
    pub sensor_geometry: Vec<[f64; 7]>,
    /// Per zone, m².
    pub zone_area: Vec<f64>,
    /// `O × B × p`.
    pub output_modes: Vec<f64>,
    /// `O × B × m`.
    pub output_channels: Vec<f64>,
    /// `n × O`.
    pub output_view: Vec<f64>,
}

fn f32_bytes(values: &[f64]) -> Vec<u8> {
    values
        .iter()
        .flat_map(|&v| (v as f32).to_le_bytes())
        .collect()
}

/// A row-major `rows × cols` matrix in `precision`: `(scales, data)`.
fn quantise(values: &[f64], cols: usize, precision: Precision) -> (Vec<u8>, Vec<u8>) {
    if precision == Precision::F32 || cols == 0 {
        return (Vec::new(), f32_bytes(values));
    }
    let mut max = vec![0.0f64; cols];
    for (i, &v) in values.iter().enumerate() {
        if let Some(slot) = max.get_mut(i % cols) {
            *slot = slot.max(v.abs());
        }
    }
    // f16 keeps its largest value at 2^14, well inside its range (65504) yet far above its
    // subnormals, so small entries of a column keep their 11-bit precision.
    let top = match precision {
        Precision::I16 => 32767.0,
        _ => 16384.0,
    };
    let scales: Vec<f64> = max
        .iter()
        .map(|&m| if m > 0.0 { m / top } else { 0.0 })
        .collect();
    let mut data = Vec::with_capacity(values.len() * 2);
    for (i, &v) in values.iter().enumerate() {
        let s = scales.get(i % cols).copied().unwrap_or(0.0);
        let x = if s > 0.0 {
            v / f64::from(s as f32)
        } else {
            0.0
        };
        let bits = match precision {
            Precision::I16 => (libm::round(x).clamp(-32767.0, 32767.0) as i16).to_le_bytes(),
            _ => f32_to_f16(x as f32).to_le_bytes(),
        };
        data.extend_from_slice(&bits);
    }
    (f32_bytes(&scales), data)
}

impl BasisTables {
    /// Tables for a basis of `bands` bands and `mode_count` modes with the given settings,
    /// every table and name list empty; fill them in before [`to_bytes`](Self::to_bytes).
    pub fn new(
        quantity: Quantity,
        formulation: Formulation,
        precision: Precision,
        bands: usize,
        mode_count: usize,
    ) -> Self {
        BasisTables {
            quantity,
            formulation,
            precision,
            bands,
            mode_count,
            surface_names: Vec::new(),
            channel_names: Vec::new(),
            sensor_names: Vec::new(),
            zone_names: Vec::new(),
            eigenvalues: Vec::new(),
            patch_area: Vec::new(),
            patch_centroid: Vec::new(),
            patch_surface: Vec::new(),
            patch_channel: Vec::new(),
            patch_reflectance: Vec::new(),
            patch_emission: Vec::new(),
            modes: Vec::new(),
            black_projection: Vec::new(),
            channel_projection: Vec::new(),
            channel_bounce: Vec::new(),
            sensor_geometry: Vec::new(),
            zone_area: Vec::new(),
            output_modes: Vec::new(),
            output_channels: Vec::new(),
            output_view: Vec::new(),
        }
    }

    /// Encodes the tables as a basis (header, checksum, payload).
    ///
    /// Fails with [`Error::EncodeOverflow`] when a count does not fit the format; it does
    /// not check the tables' lengths against each other: the reader does.
    pub fn to_bytes(&self) -> Result<Vec<u8>> {
        let (quantity, formulation, precision) = (self.quantity, self.formulation, self.precision);
        let bands = self.bands;
        let n = self.patch_area.len();
        let m = self.channel_names.len();
        let outputs = self.sensor_names.len() + self.zone_names.len();
        let count = |field: &'static str, v: usize| {
            u32::try_from(v).map_err(|_| Error::EncodeOverflow { field })
        };

        let mut names = Vec::new();
        for name in self
            .surface_names
            .iter()
            .chain(&self.channel_names)
            .chain(&self.sensor_names)
            .chain(&self.zone_names)
        {
            let mut buf = vec![0u8; name.len() + 8];
            let used = postcard::to_slice(name.as_str(), &mut buf)
                .map_err(|_| Error::EncodePayload)?
                .len();
            names.extend_from_slice(buf.get(..used).unwrap_or(&[]));
        }
        let centroid: Vec<f64> = self.patch_centroid.iter().flatten().copied().collect();
        let surface: Vec<u8> = self
            .patch_surface
            .iter()
            .flat_map(|s| s.to_le_bytes())
            .collect();
        let channel: Vec<u8> = self
            .patch_channel
            .iter()
            .flat_map(|c| c.unwrap_or(NO_CHANNEL).to_le_bytes())
            .collect();
        let black: Vec<u8> = (0..n)
            .filter(|&i| {
                (0..bands).any(|b| self.patch_reflectance.get(i * bands + b) == Some(&0.0))
            })
            .flat_map(|i| (i as u32).to_le_bytes())
            .collect();
        let geometry: Vec<f64> = self.sensor_geometry.iter().flatten().copied().collect();
        let modes = quantise(&self.modes, bands * self.mode_count, precision);
        let bounce_cols = if self.channel_bounce.is_empty() {
            0
        } else {
            m * bands
        };
        let bounce = quantise(&self.channel_bounce, bounce_cols, precision);
        let view = quantise(&self.output_view, outputs, precision);

        let tables = [
            f32_bytes(&self.eigenvalues),
            f32_bytes(&self.patch_area),
            f32_bytes(&centroid),
            f32_bytes(&self.patch_reflectance),
            f32_bytes(&self.patch_emission),
            f32_bytes(&self.black_projection),
            f32_bytes(&self.channel_projection),
            f32_bytes(&geometry),
            f32_bytes(&self.zone_area),
            f32_bytes(&self.output_modes),
            f32_bytes(&self.output_channels),
        ];
        let [eig, area, cen, refl, emis, bproj, cproj, geom, zarea, omodes, ochan] = &tables;
        let payload = Payload {
            bands: u8::try_from(bands).map_err(|_| Error::EncodeOverflow { field: "bands" })?,
            quantity: quantity as u8,
            formulation: formulation as u8,
            precision: precision as u8,
            patch_count: count("patch_count", n)?,
            mode_count: count("mode_count", self.mode_count)?,
            surface_count: count("surface_count", self.surface_names.len())?,
            channel_count: count("channel_count", m)?,
            sensor_count: count("sensor_count", self.sensor_names.len())?,
            zone_count: count("zone_count", self.zone_names.len())?,
            names: &names,
            eigenvalues: eig,
            patch_area: area,
            patch_centroid: cen,
            patch_surface: &surface,
            patch_channel: &channel,
            patch_reflectance: refl,
            patch_emission: emis,
            modes: MatrixBytes {
                scales: &modes.0,
                data: &modes.1,
            },
            black_patches: &black,
            black_projection: bproj,
            channel_projection: cproj,
            channel_bounce: MatrixBytes {
                scales: &bounce.0,
                data: &bounce.1,
            },
            sensor_geometry: geom,
            zone_area: zarea,
            output_modes: omodes,
            output_channels: ochan,
            output_view: MatrixBytes {
                scales: &view.0,
                data: &view.1,
            },
        };
        let mut out = vec![0u8; format::encoded_len(&payload)?];
        let used = format::encode(&payload, &mut out)?.len();
        out.truncate(used);
        Ok(out)
    }
}
