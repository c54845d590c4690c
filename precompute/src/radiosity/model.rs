//! A room's radiosity system with its modes in one formulation: the truncated expansions the
//! basis stores, the host-side twin of the runtime.
//!
//! Notation (docs/math.md): `G = A F` symmetric, `b_i = A_i/ρ_i`, modes `v_k` with eigenvalue
//! `μ_k` (split) or `λ_k` (seed). A patch with ρ = 0 in a band is "black" there: it is not
//! part of that band's eigenproblem (its mode entries are 0) and its emission enters the room
//! through its first bounce `G e_j`.

use faer::Mat;

use crate::radiosity::eigen::{self, Formulation, Modes, Solver};
use crate::radiosity::system::{alone, System};

/// Per-band part of the model.
pub struct BandModel {
    /// Kept modes, strongest first.
    pub modes: Modes,
    /// `W = G V` (n × p): `W[j,k] = v_k · G e_j`, the mode response to a unit emitter.
    pub g_modes: Mat<f64>,
}

/// A room's system with its strongest modes in one formulation.
pub struct Model<'s> {
    /// The room's radiosity problem and its exact solutions.
    pub system: &'s System,
    /// Expansion used for the modes.
    pub formulation: Formulation,
    /// Per band.
    pub bands: Vec<BandModel>,
    /// Exact exitance of every patch for each channel alone at level 1,
    /// `responses[c][b][i]` (W/m² or lux), from the system's exact solve.
    responses: &'s [Vec<Vec<f64>>],
}

impl BandModel {
    fn eigen(&self, k: usize) -> f64 {
        self.modes.values.get(k).copied().unwrap_or(0.0)
    }

    /// Coefficient of a reflecting emitter's projection `v_k·(b∘M0)` on mode `k`.
    pub fn reflecting_coefficient(&self, formulation: Formulation, k: usize) -> f64 {
        let e = self.eigen(k);
        match formulation {
            Formulation::Split => e / (1.0 - e),
            Formulation::Seed => 1.0 / e,
        }
    }

    /// Coefficient of a black emitter's projection `v_k·G e_j` on mode `k`.
    pub fn black_coefficient(&self, formulation: Formulation, k: usize) -> f64 {
        let e = self.eigen(k);
        match formulation {
            Formulation::Split => 1.0 / (1.0 - e),
            Formulation::Seed => 1.0 / e,
        }
    }

    /// Number of modes kept.
    pub fn mode_count(&self) -> usize {
        self.modes.vectors.ncols()
    }
}

impl<'s> Model<'s> {
    /// The modes of every band of `system` in `formulation`, `modes` per band (capped by the
    /// reflecting patches), by `solver`; the channels' exact responses from the system.
    pub fn new(
        system: &'s System,
        formulation: Formulation,
        modes: usize,
        solver: Solver,
    ) -> Result<Model<'s>, eigen::EigenError> {
        let bands = Model::modes(system, formulation, modes, solver)?;
        Model::from_modes(system, formulation, bands)
    }

    /// The modes of every band of `system` ([`Model::new`] without the channels' responses).
    pub fn modes(
        system: &System,
        formulation: Formulation,
        modes: usize,
        solver: Solver,
    ) -> Result<Vec<BandModel>, eigen::EigenError> {
        let g = system.operator();
        let mut bands = Vec::with_capacity(system.band_count());
        for reflectance in &system.reflectance {
            let mut m = eigen::modes(g, &system.area, reflectance, formulation, modes, solver)?;
            fix_signs(&mut m.vectors);
            let mut g_modes = Mat::<f64>::zeros(g.len(), m.vectors.ncols());
            g.apply(
                g_modes.as_mut(),
                m.vectors.as_ref(),
                faer::get_global_parallelism(),
            );
            bands.push(BandModel { modes: m, g_modes });
        }
        Ok(bands)
    }

    /// The model of `system` with the modes `bands` (from [`Model::modes`] in `formulation`)
    /// and the channels' exact responses, solved now if the system has not solved them yet.
    /// Solved after the modes, so that an LU factorisation and the dense eigensolver's
    /// workspace are never held at once (`crate::memory`).
    pub fn from_modes(
        system: &'s System,
        formulation: Formulation,
        bands: Vec<BandModel>,
    ) -> Result<Model<'s>, eigen::EigenError> {
        let responses = system.channel_responses()?;
        Ok(Model {
            system,
            formulation,
            bands,
            responses,
        })
    }

    /// Number of patches.
    pub fn patch_count(&self) -> usize {
        self.system.patch_count()
    }

    /// Patch areas, m².
    pub fn area(&self) -> &[f64] {
        &self.system.area
    }

    /// ρ of every patch in band `b`.
    pub fn reflectance(&self, b: usize) -> &[f64] {
        &self.system.reflectance[b]
    }

    /// Number of channels.
    pub fn channel_count(&self) -> usize {
        self.system.channel_count()
    }

    /// Exitance the patches of channel `c` emit at level 1 in band `b`, W/m² or lux.
    pub fn emission(&self, c: usize, b: usize) -> &[f64] {
        self.system.emission(c, b)
    }

    /// Mode-space response (coefficient included) of unit exitance on patch `j`, band `b`.
    pub fn patch_projection(&self, j: usize, b: usize) -> Vec<f64> {
        let band = &self.bands[b];
        let r = self.reflectance(b)[j];
        let area = self.area();
        (0..band.mode_count())
            .map(|k| {
                if r > 0.0 {
                    band.reflecting_coefficient(self.formulation, k) * area[j] / r
                        * band.modes.vectors[(j, k)]
                } else {
                    band.black_coefficient(self.formulation, k) * band.g_modes[(j, k)]
                }
            })
            .collect()
    }

    /// The two parts of the expansion for channel levels `levels` and per-patch exitance
    /// `extra` (W/m² or lux) in band `b`: the exactly carried part (n values) and the mode
    /// amplitudes (all kept modes, coefficient included).
    pub fn expansion(&self, b: usize, levels: &[f64], extra: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let band = &self.bands[b];
        let reflectance = self.reflectance(b);
        let mut amplitude = vec![0.0; band.mode_count()];
        let mut identity = vec![0.0; self.patch_count()];
        // Channels are carried by their exact responses, as the basis stores them: the modes
        // serve only exitance set patch by patch.
        for (c, &l) in levels.iter().enumerate() {
            if l == 0.0 {
                continue;
            }
            for (o, x) in identity.iter_mut().zip(self.channel_response(c, b)) {
                *o += l * x;
            }
        }
        for (j, &x) in extra.iter().enumerate() {
            if x == 0.0 {
                continue;
            }
            for (a, y) in amplitude.iter_mut().zip(self.patch_projection(j, b)) {
                *a += x * y;
            }
            if self.formulation == Formulation::Split || reflectance[j] == 0.0 {
                identity[j] += x;
            }
        }
        (identity, amplitude)
    }

    /// Exitance of every patch in band `b` from the truncated expansion with the first `p`
    /// modes, for channel levels `levels` and per-patch exitance `extra` (W/m² or lux).
    pub fn truncated(&self, b: usize, p: usize, levels: &[f64], extra: &[f64]) -> Vec<f64> {
        let (mut out, amplitude) = self.expansion(b, levels, extra);
        let v = &self.bands[b].modes.vectors;
        for (k, a) in amplitude.iter().enumerate().take(p) {
            for (i, o) in out.iter_mut().enumerate() {
                *o += v[(i, k)] * a;
            }
        }
        out
    }

    /// Readings of every output in band `b` for patch exitance `m` and the channel levels
    /// that produced it ([`System::readings`]).
    pub fn readings(&self, b: usize, m: &[f64], levels: &[f64]) -> Vec<f64> {
        self.system.readings(b, m, levels)
    }

    /// Exact exitance of every patch for channel `c` alone at level 1 in band `b`, W/m² or lux.
    pub fn channel_response(&self, c: usize, b: usize) -> &[f64] {
        &self.responses[c][b]
    }

    /// Exact readings of every output (sensors, then zones) for channel `c` alone at level 1
    /// in band `b`, W/m² or lux.
    pub fn channel_readings(&self, c: usize, b: usize) -> Vec<f64> {
        let unit = alone(self.channel_count(), c);
        self.readings(b, self.channel_response(c, b), &unit)
    }

    /// The amplitudes on the first `p` modes of band `b` of an exitance `m` (W/m² or lux)
    /// over the reflecting patches: `a_k = v_kᵀ B m` (split, `Vᵀ B V = I`) or `v_kᵀ m` (seed,
    /// orthonormal modes), so that `Σ_k a_k v_k` is `m` projected on the modes, and `m`
    /// itself on the reflecting patches when `p = n`.
    pub fn mode_amplitudes(&self, b: usize, m: &[f64], p: usize) -> Vec<f64> {
        let v = &self.bands[b].modes.vectors;
        let reflectance = self.reflectance(b);
        let area = self.area();
        let weight = |j: usize| amplitude_weight(self.formulation, area[j], reflectance[j]);
        (0..p)
            .map(|k| {
                if k >= v.ncols() {
                    return 0.0;
                }
                (0..m.len()).map(|j| weight(j) * v[(j, k)] * m[j]).sum()
            })
            .collect()
    }
}

/// The weight `w_j` of a patch of area `area` (m²) and reflectance `reflectance` in a mode
/// amplitude `a_k = Σ_j w_j v_jk m_j` ([`Model::mode_amplitudes`]): `A/ρ` in the split
/// formulation (`Vᵀ B V = I`), 1 in the seed one (orthonormal modes), 0 on a black patch,
/// which the modes do not span.
pub fn amplitude_weight(formulation: Formulation, area: f64, reflectance: f64) -> f64 {
    match (formulation, reflectance) {
        (_, r) if r <= 0.0 => 0.0,
        (Formulation::Split, r) => area / r,
        (Formulation::Seed, _) => 1.0,
    }
}

/// Makes each mode's largest-magnitude entry positive, so that the basis bytes do not depend
/// on the eigensolver's arbitrary sign choice.
fn fix_signs(v: &mut Mat<f64>) {
    for k in 0..v.ncols() {
        let mut best = 0.0f64;
        for i in 0..v.nrows() {
            if v[(i, k)].abs() > best.abs() + 1e-12 * best.abs() {
                best = v[(i, k)];
            }
        }
        if best < 0.0 {
            for i in 0..v.nrows() {
                v[(i, k)] = -v[(i, k)];
            }
        }
    }
}
