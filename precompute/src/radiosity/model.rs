//! The radiosity model of a scene in `f64`: form factors, per-band modes, the exact solver,
//! and the truncated expansions the basis stores — the host-side twin of the runtime.
//!
//! Notation (docs/math.md): `G = A F` symmetric, `b_i = A_i/ρ_i`, modes `v_k` with eigenvalue
//! `μ_k` (split) or `λ_k` (seed). A patch with ρ = 0 in a band is "black" there: it is not
//! part of that band's eigenproblem (its mode entries are 0) and its emission enters the room
//! through its first bounce `G e_j`.

use faer::Mat;

use crate::formfactor::exchange;
use crate::radiosity::eigen::{self, Formulation, Modes, Solver};
use crate::radiosity::exact::ExactSolver;
use crate::scene::Scene;
use crate::sources::{ChannelLight, ExternalLight};

/// Per-band part of the model.
pub struct BandModel {
    /// ρ of every patch in this band.
    pub reflectance: Vec<f64>,
    /// Kept modes, strongest first.
    pub modes: Modes,
    /// `W = G V` (n × p): `W[j,k] = v_k · G e_j`, the mode response to a unit emitter.
    pub g_modes: Mat<f64>,
}

/// A scene's radiosity model.
pub struct Model {
    /// Expansion used for the modes.
    pub formulation: Formulation,
    /// Patch areas, m².
    pub area: Vec<f64>,
    /// `G = A F`, symmetrised (m²).
    pub g: Mat<f64>,
    /// Per band.
    pub bands: Vec<BandModel>,
    /// The light of every channel at level 1, from its sources.
    pub lights: Vec<ChannelLight>,
    /// Per channel, the part of its direct light its emitting patches do not account for.
    pub external: Vec<ExternalLight>,
    /// Output rows `R_o` (sensors, then zones): irradiance at output `o` is `Σ_j R_oj M_j`.
    pub output_rows: Vec<Vec<f64>>,
    /// Exact exitance of every patch for each channel alone at level 1,
    /// `responses[c][b][i]` (W/m² or lux): `(I − R F)⁻¹ M0_c` by the exact solver.
    pub responses: Vec<Vec<Vec<f64>>>,
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

impl Model {
    /// Builds the model: modes of every band from `g` (already symmetrised), the channels'
    /// light from `lights` (one per channel of the scene, from [`crate::sources`]).
    ///
    /// `modes` is the number of modes to keep per band (capped by the reflecting patches).
    pub fn new(
        scene: &Scene,
        g: Mat<f64>,
        output_rows: Vec<Vec<f64>>,
        lights: Vec<ChannelLight>,
        formulation: Formulation,
        modes: usize,
        solver: Solver,
    ) -> Result<Model, eigen::EigenError> {
        assert_eq!(
            lights.len(),
            scene.channels.len(),
            "one channel light per channel of the scene"
        );
        let area: Vec<f64> = scene.patches.iter().map(|p| p.area).collect();
        let band_count = scene.bands.count();
        let mut bands = Vec::with_capacity(band_count);
        for b in 0..band_count {
            let reflectance: Vec<f64> = scene.reflectance.iter().map(|r| r[b]).collect();
            let mut m = eigen::modes(g.as_ref(), &area, &reflectance, formulation, modes, solver)?;
            fix_signs(&mut m.vectors);
            let g_modes = &g * &m.vectors;
            bands.push(BandModel {
                reflectance,
                modes: m,
                g_modes,
            });
        }
        let external = lights
            .iter()
            .map(|l| l.external(&g, &area, &output_rows))
            .collect();
        let mut model = Model {
            formulation,
            area,
            g,
            bands,
            lights,
            external,
            output_rows,
            responses: Vec::new(),
        };
        model.responses = model.exact_channel_responses()?;
        Ok(model)
    }

    /// Number of patches.
    pub fn patch_count(&self) -> usize {
        self.area.len()
    }

    /// `F x` for a vector over patches: `(G x)_i / A_i`.
    pub fn apply_f(&self, x: &[f64]) -> Vec<f64> {
        exchange::patch_irradiance(&self.g, &self.area, x)
    }

    /// Number of channels.
    pub fn channel_count(&self) -> usize {
        self.lights.len()
    }

    /// Exitance the patches of channel `c` emit at level 1 in band `b`, W/m² or lux.
    pub fn emission(&self, c: usize, b: usize) -> &[f64] {
        &self.lights[c].emission[b]
    }

    /// Mode-space response (coefficient included) of unit exitance on patch `j`, band `b`.
    pub fn patch_projection(&self, j: usize, b: usize) -> Vec<f64> {
        let band = &self.bands[b];
        let r = band.reflectance[j];
        (0..band.mode_count())
            .map(|k| {
                if r > 0.0 {
                    band.reflecting_coefficient(self.formulation, k) * self.area[j] / r
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
            if self.formulation == Formulation::Split || band.reflectance[j] == 0.0 {
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

    /// Exact exitance (dense LU) in band `b` for the same inputs as [`Model::truncated`].
    pub fn exact(&self, solver: &ExactSolver, b: usize, levels: &[f64], extra: &[f64]) -> Vec<f64> {
        solver.solve(&self.initial_exitance(b, levels, extra))
    }

    /// `M0` of band `b` for channel levels `levels` and per-patch exitance `extra`: the
    /// emission, plus the first reflection `ρ ∘ E_ext` of light from beyond the patches
    /// (W/m² or lux).
    pub fn initial_exitance(&self, b: usize, levels: &[f64], extra: &[f64]) -> Vec<f64> {
        initial_exitance(
            &self.lights,
            &self.external,
            &self.bands[b].reflectance,
            b,
            levels,
            extra,
        )
    }

    /// Readings of every output (sensors, then zones) in band `b` for patch exitance `m`
    /// and the channel levels that produced it: `Σ_j R_oj M_j` plus the direct light from
    /// beyond the patches (W/m² or lux).
    pub fn readings(&self, b: usize, m: &[f64], levels: &[f64]) -> Vec<f64> {
        let mut out = self.outputs(m);
        add_external_readings(&mut out, &self.external, b, levels);
        out
    }

    /// Irradiance at every output that the patch exitance `m` of one band gives,
    /// `Σ_j R_oj M_j`; [`Model::readings`] adds the light from beyond the patches.
    pub fn outputs(&self, m: &[f64]) -> Vec<f64> {
        exchange::output_irradiance(&self.output_rows, m)
    }

    /// Every channel's exact response at level 1, per band: one solve with a right-hand side
    /// per channel.
    fn exact_channel_responses(&self) -> Result<Vec<Vec<Vec<f64>>>, eigen::EigenError> {
        let m = self.channel_count();
        let mut responses = vec![Vec::with_capacity(self.bands.len()); m];
        for b in 0..self.bands.len() {
            let solver = self.exact_solver(b)?;
            let units: Vec<Vec<f64>> = (0..m).map(|c| alone(m, c)).collect();
            let cases: Vec<(&[f64], &[f64])> =
                units.iter().map(|u| (u.as_slice(), &[][..])).collect();
            for (c, m) in self.exact_many(&solver, b, &cases).into_iter().enumerate() {
                responses[c].push(m);
            }
        }
        Ok(responses)
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

    /// The exact solver of band `b`: an LU factorisation of `I − R F` up to
    /// [`crate::radiosity::exact::EXACT_LU_MAX`] patches, conjugate gradients on `G` above (no n×n copy).
    pub fn exact_solver(&self, b: usize) -> Result<ExactSolver<'_>, eigen::EigenError> {
        ExactSolver::auto(self.g.as_ref(), &self.area, &self.bands[b].reflectance)
    }

    /// [`Model::exact`] for several `(levels, extra)` cases at once (one solve with as many
    /// right-hand sides: one pass over `G` per iteration for all of them).
    pub fn exact_many(
        &self,
        solver: &ExactSolver,
        b: usize,
        cases: &[(&[f64], &[f64])],
    ) -> Vec<Vec<f64>> {
        let n = self.patch_count();
        let mut m0 = Mat::<f64>::zeros(n, cases.len());
        for (k, (levels, extra)) in cases.iter().enumerate() {
            for (i, x) in self.initial_exitance(b, levels, extra).iter().enumerate() {
                m0[(i, k)] = *x;
            }
        }
        let m = solver.solve_many(m0.as_ref());
        (0..cases.len())
            .map(|k| (0..n).map(|i| m[(i, k)]).collect())
            .collect()
    }
}

/// The exact response of the room to one light alone, in one band.
#[derive(Clone, Debug, PartialEq)]
pub struct LightResponse {
    /// Exitance of every patch, W/m² or lux.
    pub exitance: Vec<f64>,
    /// Reading of every output (sensors, zones, then grid points), W/m² or lux.
    pub readings: Vec<f64>,
}

impl Model {
    /// The exact response in band `b` to each of `lights` alone, lights that are not the
    /// scene's channels (the daylight's nodes): `(I − R F)⁻¹ M0` with `M0` each light's
    /// emission plus the first reflection of its light from beyond the patches, and every
    /// output's reading of it, that light's direct part included. One solve with a
    /// right-hand side per light.
    pub fn light_responses(
        &self,
        b: usize,
        lights: &[ChannelLight],
    ) -> Result<Vec<LightResponse>, eigen::EigenError> {
        let n = self.patch_count();
        let reflectance = &self.bands[b].reflectance;
        let external: Vec<ExternalLight> = lights
            .iter()
            .map(|l| l.external(&self.g, &self.area, &self.output_rows))
            .collect();
        let mut m0 = Mat::<f64>::zeros(n, lights.len());
        for (k, (light, ext)) in lights.iter().zip(&external).enumerate() {
            let first = initial_exitance(
                std::slice::from_ref(light),
                std::slice::from_ref(ext),
                reflectance,
                b,
                &[1.0],
                &[],
            );
            for (i, x) in first.iter().enumerate() {
                m0[(i, k)] = *x;
            }
        }
        let solver = self.exact_solver(b)?;
        let m = solver.solve_many(m0.as_ref());
        Ok(external
            .iter()
            .enumerate()
            .map(|(k, ext)| {
                let exitance: Vec<f64> = (0..n).map(|i| m[(i, k)]).collect();
                let mut readings = self.outputs(&exitance);
                add_external_readings(&mut readings, std::slice::from_ref(ext), b, &[1.0]);
                LightResponse { exitance, readings }
            })
            .collect())
    }

    /// The amplitudes on the first `p` modes of band `b` of an exitance `m` (W/m² or lux)
    /// over the reflecting patches: `a_k = v_kᵀ B m` (split, `Vᵀ B V = I`) or `v_kᵀ m` (seed,
    /// orthonormal modes), so that `Σ_k a_k v_k` is `m` projected on the modes, and `m`
    /// itself on the reflecting patches when `p = n`.
    pub fn mode_amplitudes(&self, b: usize, m: &[f64], p: usize) -> Vec<f64> {
        let band = &self.bands[b];
        let v = &band.modes.vectors;
        let weight = |j: usize| match (self.formulation, band.reflectance[j]) {
            (_, r) if r <= 0.0 => 0.0,
            (Formulation::Split, r) => self.area[j] / r,
            (Formulation::Seed, _) => 1.0,
        };
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

/// The levels of `m` channels with channel `c` alone at level 1.
fn alone(m: usize, c: usize) -> Vec<f64> {
    (0..m).map(|d| if d == c { 1.0 } else { 0.0 }).collect()
}

/// `M0` of band `b` (W/m² or lux): `extra` (empty or one value per patch), plus each
/// channel's emission and the first reflection `ρ ∘ E_ext` of its light from beyond the
/// patches, at its level.
pub fn initial_exitance(
    lights: &[ChannelLight],
    external: &[ExternalLight],
    reflectance: &[f64],
    b: usize,
    levels: &[f64],
    extra: &[f64],
) -> Vec<f64> {
    let mut m0: Vec<f64> = (0..reflectance.len())
        .map(|i| extra.get(i).copied().unwrap_or(0.0))
        .collect();
    for (c, &l) in levels.iter().enumerate() {
        for (x, e) in m0.iter_mut().zip(&lights[c].emission[b]) {
            *x += l * e;
        }
        if let Some(e_ext) = &external[c].patches[b] {
            for ((x, e), r) in m0.iter_mut().zip(e_ext).zip(reflectance) {
                *x += l * r * e;
            }
        }
    }
    m0
}

/// Adds to the readings `out` (sensors, then zones) of band `b` the direct light from beyond
/// the patches of every channel at its level.
pub fn add_external_readings(
    out: &mut [f64],
    external: &[ExternalLight],
    b: usize,
    levels: &[f64],
) {
    for (c, &l) in levels.iter().enumerate() {
        if let Some(direct) = &external[c].outputs[b] {
            for (o, d) in out.iter_mut().zip(direct) {
                *o += l * d;
            }
        }
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
