//! The settings section's typed values: what the numbers measure, how the modes expand the
//! interreflection, how the large tables are stored. The payload holds each as its
//! discriminant.

/// How the interreflection operator is expanded in modes (see `docs/format.md` and
/// docs/math.md). Channels are stored exactly in either; the expansion serves exitance set
/// patch by patch at run time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "alloc", derive(serde::Serialize, serde::Deserialize))]
#[repr(u8)]
pub enum Formulation {
    /// Default. `M = M0 + Σ c_k v_k (v_k · b∘M0)` with `c_k = μ_k/(1−μ_k)`: a patch's own
    /// exitance exact, the interreflection in modes; the stored eigenvalues are `μ_k`
    /// (eigenvalues of `R F`).
    #[default]
    Split = 0,
    /// The seed paper's expansion, corrected: `M = Σ (1/λ_k) v_k (v_k · b∘M0)` over the
    /// smallest eigenvalues `λ_k` of `S = A R⁻¹ (I − R F)`; kept for comparison.
    Seed = 1,
}

/// How the large tables (mode vectors, channel responses, view rows) are stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "alloc", derive(serde::Serialize, serde::Deserialize))]
#[repr(u8)]
pub enum Precision {
    /// IEEE binary32, 4 bytes a value.
    F32 = 0,
    /// IEEE binary16 times a per-column scale, 2 bytes a value.
    F16 = 1,
    /// Signed 16-bit integer times a per-column scale, 2 bytes a value.
    I16 = 2,
}

impl Formulation {
    /// The name used on the command line and in reports: `split` or `seed`.
    pub const fn name(self) -> &'static str {
        match self {
            Formulation::Split => "split",
            Formulation::Seed => "seed",
        }
    }
}

impl Precision {
    /// The name used on the command line and in reports: `f32`, `f16` or `i16`.
    pub const fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F16 => "f16",
            Precision::I16 => "i16",
        }
    }

    /// Bytes per stored value.
    pub const fn bytes(self) -> usize {
        match self {
            Precision::F32 => 4,
            Precision::F16 | Precision::I16 => 2,
        }
    }
}

/// What the numbers measure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "alloc", derive(serde::Serialize, serde::Deserialize))]
#[repr(u8)]
pub enum Quantity {
    /// Radiometric: exitance and irradiance in W/m², luminance in W/(m²·sr).
    Radiometric = 0,
    /// Photometric, one photopic band: exitance (lm/m²) and illuminance in lux, luminance in
    /// cd/m².
    Photometric = 1,
}
