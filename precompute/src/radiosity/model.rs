//! The radiosity model of a scene in `f64`: form factors, per-band modes, the exact solver,
//! and the truncated expansions the basis stores — the host-side twin of the runtime.
//!
//! Notation (docs/math.md): `G = A F` symmetric, `b_i = A_i/ρ_i`, modes `v_k` with eigenvalue
//! `μ_k` (split) or `λ_k` (seed). A patch with ρ = 0 in a band is "black" there: it is not
//! part of that band's eigenproblem (its mode entries are 0) and its emission enters the room
//! through its first bounce `G e_j`.

use faer::Mat;

use crate::radiosity::eigen::{self, Formulation, Modes, Solver};
use crate::radiosity::exact::ExactSolver;
use crate::scene::Scene;

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
    /// Channel emission at level 1: `emission[c][b][i]`, W/m² or lux.
    pub emission: Vec<Vec<Vec<f64>>>,
    /// Output rows `R_o` (sensors, then zones): irradiance at output `o` is `Σ_j R_oj M_j`.
    pub output_rows: Vec<Vec<f64>>,
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
    /// Builds the model: modes of every band from `g` (already symmetrised).
    ///
    /// `modes` is the number of modes to keep per band (capped by the reflecting patches).
    pub fn new(
        scene: &Scene,
        g: Mat<f64>,
        output_rows: Vec<Vec<f64>>,
        formulation: Formulation,
        modes: usize,
        solver: Solver,
    ) -> Result<Model, eigen::EigenError> {
        let n = scene.patches.len();
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
        let emission = (0..scene.channels.len())
            .map(|c| {
                (0..band_count)
                    .map(|b| {
                        (0..n)
                            .map(|i| {
                                if scene.channel_of_patch[i] == Some(c) {
                                    scene.emission[i][b]
                                } else {
                                    0.0
                                }
                            })
                            .collect()
                    })
                    .collect()
            })
            .collect();
        Ok(Model {
            formulation,
            area,
            g,
            bands,
            emission,
            output_rows,
        })
    }

    /// Number of patches.
    pub fn patch_count(&self) -> usize {
        self.area.len()
    }

    /// `F x` for a vector over patches: `(G x)_i / A_i`.
    pub fn apply_f(&self, x: &[f64]) -> Vec<f64> {
        let gx = &self.g * faer::ColRef::from_slice(x);
        (0..self.patch_count())
            .map(|i| gx[i] / self.area[i])
            .collect()
    }

    /// First bounce `R F e` of an emission vector in band `b`.
    pub fn first_bounce(&self, b: usize, e: &[f64]) -> Vec<f64> {
        let fe = self.apply_f(e);
        fe.iter()
            .zip(&self.bands[b].reflectance)
            .map(|(x, r)| x * r)
            .collect()
    }

    /// The part of a channel's response carried exactly, not by the modes: emission plus
    /// first bounce (split), emission of black patches (seed).
    pub fn channel_identity(&self, c: usize, b: usize) -> Vec<f64> {
        let e = &self.emission[c][b];
        let rho = &self.bands[b].reflectance;
        match self.formulation {
            Formulation::Split => {
                let d = self.first_bounce(b, e);
                e.iter().zip(&d).map(|(x, y)| x + y).collect()
            }
            Formulation::Seed => e
                .iter()
                .zip(rho)
                .map(|(x, r)| if *r == 0.0 { *x } else { 0.0 })
                .collect(),
        }
    }

    /// Mode-space response (coefficient included) of a channel at level 1, band `b`.
    ///
    /// Split (exact first bounce, docs/math.md "Sharper still: exact first bounce"): `(I−RF)⁻¹ e = e + RF e +
    /// V diag(μ/(1−μ)) Vᵀ G e`. Seed: `M_r = S⁻¹ (B e_r + G e_black)`.
    pub fn channel_projection(&self, c: usize, b: usize) -> Vec<f64> {
        let e = &self.emission[c][b];
        let band = &self.bands[b];
        let p = band.mode_count();
        (0..p)
            .map(|k| {
                let ge: f64 = (0..e.len()).map(|j| band.g_modes[(j, k)] * e[j]).sum();
                match self.formulation {
                    Formulation::Split => band.reflecting_coefficient(Formulation::Split, k) * ge,
                    Formulation::Seed => {
                        let mut acc = 0.0;
                        for (j, &x) in e.iter().enumerate() {
                            if x == 0.0 {
                                continue;
                            }
                            let r = band.reflectance[j];
                            acc += if r > 0.0 {
                                self.area[j] / r * band.modes.vectors[(j, k)] * x
                            } else {
                                band.g_modes[(j, k)] * x
                            };
                        }
                        acc / band.eigen(k)
                    }
                }
            })
            .collect()
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
        for (c, &l) in levels.iter().enumerate() {
            if l == 0.0 {
                continue;
            }
            for (a, x) in amplitude.iter_mut().zip(self.channel_projection(c, b)) {
                *a += l * x;
            }
            for (o, x) in identity.iter_mut().zip(self.channel_identity(c, b)) {
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
        let mut m0 = extra.to_vec();
        for (c, &l) in levels.iter().enumerate() {
            for (x, e) in m0.iter_mut().zip(&self.emission[c][b]) {
                *x += l * e;
            }
        }
        solver.solve(&m0)
    }

    /// Irradiance at every output for the exitance `m` of one band.
    pub fn outputs(&self, m: &[f64]) -> Vec<f64> {
        self.output_rows
            .iter()
            .map(|r| r.iter().zip(m).map(|(a, b)| a * b).sum())
            .collect()
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
            for i in 0..n {
                m0[(i, k)] = extra.get(i).copied().unwrap_or(0.0);
            }
            for (c, &l) in levels.iter().enumerate() {
                for (i, e) in self.emission[c][b].iter().enumerate() {
                    m0[(i, k)] += l * e;
                }
            }
        }
        let m = solver.solve_many(m0.as_ref());
        (0..cases.len())
            .map(|k| (0..n).map(|i| m[(i, k)]).collect())
            .collect()
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
