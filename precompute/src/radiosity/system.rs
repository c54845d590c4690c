//! The radiosity problem of one room as one value: the form-factor operator `G = A F`, the
//! patch areas, the reflectances of every band, the receivers' rows, the channels' light, and
//! the exact solves, factorised once per band and kept.
//!
//! Everything that needs an exact answer asks a [`System`]: the build (channel responses,
//! daylight nodes, the accuracy report), `solve`, `render`, `verify` and the benchmarks. The
//! truncated expansions ([`crate::radiosity::model::Model`]) are computed from it on demand,
//! in either formulation.

use std::sync::{Arc, OnceLock};

use faer::Mat;

use crate::formfactor::exchange;
use crate::formfactor::operator::FormFactorOperator;
use crate::radiosity::eigen::EigenError;
use crate::radiosity::exact::ExactSolver;
use crate::sources::{ChannelLight, ExternalLight};

/// A room's radiosity problem and its exact solutions.
#[derive(Debug)]
pub struct System {
    /// `G = A F`, symmetric (m²), shared with the solvers that iterate on it.
    operator: Arc<dyn FormFactorOperator>,
    /// Patch areas, m².
    pub area: Vec<f64>,
    /// `reflectance[b][i]`: ρ of patch `i` in band `b`.
    pub reflectance: Vec<Vec<f64>>,
    /// Output rows `R_o` (sensors, zones, then grid points): irradiance at output `o` is
    /// `Σ_j R_oj M_j`.
    pub output_rows: Vec<Vec<f64>>,
    /// The light of every channel at level 1, from its sources.
    pub lights: Vec<ChannelLight>,
    /// Per channel, the part of its direct light its emitting patches do not account for.
    pub external: Vec<ExternalLight>,
    /// The exact solver of each band, made on first use.
    solvers: Vec<OnceLock<Result<ExactSolver, EigenError>>>,
    /// `responses[c][b][i]`: every channel's exact exitance at level 1, made on first use.
    responses: OnceLock<Result<Vec<Vec<Vec<f64>>>, EigenError>>,
}

/// The exact response of the room to one light alone, in one band.
#[derive(Clone, Debug, PartialEq)]
pub struct LightResponse {
    /// Exitance of every patch, W/m² or lux.
    pub exitance: Vec<f64>,
    /// Reading of every output (sensors, zones, then grid points), W/m² or lux.
    pub readings: Vec<f64>,
}

impl System {
    /// The system of a meshed room: `operator` is `G = A F` (m², symmetrised), `area` the
    /// patch areas (m²), `reflectance[b]` every patch's ρ in band `b`, `output_rows` the
    /// receivers' rows, `lights` one per channel from [`crate::sources`].
    pub fn new(
        operator: Arc<dyn FormFactorOperator>,
        area: Vec<f64>,
        reflectance: Vec<Vec<f64>>,
        output_rows: Vec<Vec<f64>>,
        lights: Vec<ChannelLight>,
    ) -> System {
        let external = lights
            .iter()
            .map(|l| l.external(operator.as_ref(), &area, &output_rows))
            .collect();
        let bands = reflectance.len();
        System {
            operator,
            area,
            reflectance,
            output_rows,
            lights,
            external,
            solvers: (0..bands).map(|_| OnceLock::new()).collect(),
            responses: OnceLock::new(),
        }
    }

    /// The same room lit by other channels' light (same operator, areas, reflectances and
    /// receivers; nothing solved yet).
    pub fn with_lights(&self, lights: Vec<ChannelLight>) -> System {
        System::new(
            Arc::clone(&self.operator),
            self.area.clone(),
            self.reflectance.clone(),
            self.output_rows.clone(),
            lights,
        )
    }

    /// The same room with only the first `count` outputs (the grids left out of a basis).
    pub fn with_outputs(mut self, count: usize) -> System {
        self.output_rows.truncate(count);
        for light in &mut self.lights {
            for band in &mut light.output_irradiance {
                band.truncate(count);
            }
        }
        for external in &mut self.external {
            for band in external.outputs.iter_mut().flatten() {
                band.truncate(count);
            }
        }
        self
    }

    /// The form-factor operator `G = A F` (m²).
    pub fn operator(&self) -> &dyn FormFactorOperator {
        self.operator.as_ref()
    }

    /// Number of patches.
    pub fn patch_count(&self) -> usize {
        self.area.len()
    }

    /// Number of bands.
    pub fn band_count(&self) -> usize {
        self.reflectance.len()
    }

    /// Number of channels.
    pub fn channel_count(&self) -> usize {
        self.lights.len()
    }

    /// Number of outputs (sensors, zones, then grid points).
    pub fn output_count(&self) -> usize {
        self.output_rows.len()
    }

    /// `F x` for a vector over patches: `(G x)_i / A_i`.
    pub fn apply_f(&self, x: &[f64]) -> Vec<f64> {
        exchange::patch_irradiance(self.operator(), &self.area, x)
    }

    /// Exitance the patches of channel `c` emit at level 1 in band `b`, W/m² or lux.
    pub fn emission(&self, c: usize, b: usize) -> &[f64] {
        &self.lights[c].emission[b]
    }

    /// The exact solver of band `b`, factorised or set up on first use: an LU factorisation
    /// of `I − R F` up to [`crate::radiosity::exact::EXACT_LU_MAX`] patches of a dense f64
    /// operator, conjugate gradients on the operator otherwise.
    pub fn solver(&self, b: usize) -> Result<&ExactSolver, EigenError> {
        self.solvers[b]
            .get_or_init(|| ExactSolver::auto(&self.operator, &self.area, &self.reflectance[b]))
            .as_ref()
            .map_err(Clone::clone)
    }

    /// `M0` of band `b` for channel levels `levels` and per-patch exitance `extra`: the
    /// emission, plus the first reflection `ρ ∘ E_ext` of light from beyond the patches
    /// (W/m² or lux).
    pub fn initial_exitance(&self, b: usize, levels: &[f64], extra: &[f64]) -> Vec<f64> {
        initial_exitance(
            &self.lights,
            &self.external,
            &self.reflectance[b],
            b,
            levels,
            extra,
        )
    }

    /// Exact exitance of every patch in band `b` (W/m² or lux) for channel levels `levels`
    /// and per-patch exitance `extra`: `(I − R F)⁻¹ M0`.
    pub fn exact(&self, b: usize, levels: &[f64], extra: &[f64]) -> Result<Vec<f64>, EigenError> {
        Ok(self
            .solver(b)?
            .solve(&self.initial_exitance(b, levels, extra)))
    }

    /// [`System::exact`] for several `(levels, extra)` cases at once (one solve with as many
    /// right-hand sides: one pass over `G` per iteration for all of them).
    pub fn exact_many(
        &self,
        b: usize,
        cases: &[(&[f64], &[f64])],
    ) -> Result<Vec<Vec<f64>>, EigenError> {
        let n = self.patch_count();
        let mut m0 = Mat::<f64>::zeros(n, cases.len());
        for (k, (levels, extra)) in cases.iter().enumerate() {
            for (i, x) in self.initial_exitance(b, levels, extra).iter().enumerate() {
                m0[(i, k)] = *x;
            }
        }
        let m = self.solver(b)?.solve_many(m0.as_ref());
        Ok((0..cases.len())
            .map(|k| (0..n).map(|i| m[(i, k)]).collect())
            .collect())
    }

    /// Irradiance at every output (sensors, zones, grid points) that the patch exitance `m`
    /// of one band gives, `Σ_j R_oj M_j`; [`System::readings`] adds the light from beyond the
    /// patches.
    pub fn outputs(&self, m: &[f64]) -> Vec<f64> {
        exchange::output_irradiance(&self.output_rows, m)
    }

    /// Readings of every output in band `b` for patch exitance `m` and the channel levels that
    /// produced it: `Σ_j R_oj M_j` plus the direct light from beyond the patches (W/m² or lux).
    pub fn readings(&self, b: usize, m: &[f64], levels: &[f64]) -> Vec<f64> {
        let mut out = self.outputs(m);
        add_external_readings(&mut out, &self.external, b, levels);
        out
    }

    /// Irradiance on every patch in band `b` for patch exitance `m` and the channel levels
    /// that produced it: `F M` (exact for black patches too) plus the light from beyond the
    /// patches (W/m² or lux).
    pub fn patch_irradiance(&self, b: usize, m: &[f64], levels: &[f64]) -> Vec<f64> {
        let mut e = self.apply_f(m);
        add_external_irradiance(&mut e, &self.external, b, levels);
        e
    }

    /// Every channel's exact exitance at level 1, `[channel][band][patch]` (W/m² or lux): one
    /// solve per band with a right-hand side per channel, made once.
    pub fn channel_responses(&self) -> Result<&[Vec<Vec<f64>>], EigenError> {
        self.responses
            .get_or_init(|| {
                let m = self.channel_count();
                let mut responses = vec![Vec::with_capacity(self.band_count()); m];
                let units: Vec<Vec<f64>> = (0..m).map(|c| alone(m, c)).collect();
                let cases: Vec<(&[f64], &[f64])> =
                    units.iter().map(|u| (u.as_slice(), &[][..])).collect();
                for b in 0..self.band_count() {
                    for (c, x) in self.exact_many(b, &cases)?.into_iter().enumerate() {
                        responses[c].push(x);
                    }
                }
                Ok(responses)
            })
            .as_deref()
            .map_err(Clone::clone)
    }

    /// The exact response in band `b` to each of `lights` alone, lights that are not the
    /// room's channels (a moment's daylight, the daylight's nodes): `(I − R F)⁻¹ M0` with
    /// `M0` each light's emission plus the first reflection of its light from beyond the
    /// patches, and every output's reading of it, that light's direct part included. One
    /// solve with a right-hand side per light.
    pub fn light_responses(
        &self,
        b: usize,
        lights: &[ChannelLight],
    ) -> Result<Vec<LightResponse>, EigenError> {
        self.light_responses_with_irradiance(b, lights)
            .map(|r| r.into_iter().map(|(response, _)| response).collect())
    }

    /// [`System::light_responses`] with each light's irradiance on every patch (W/m² or
    /// lux): `F M` plus its direct light from beyond the patches.
    pub fn light_responses_with_irradiance(
        &self,
        b: usize,
        lights: &[ChannelLight],
    ) -> Result<Vec<(LightResponse, Vec<f64>)>, EigenError> {
        let n = self.patch_count();
        let external = self.external_lights(lights);
        let mut m0 = Mat::<f64>::zeros(n, lights.len());
        for (k, first) in self
            .initial_exitances_of(b, lights, &external)
            .iter()
            .enumerate()
        {
            for (i, x) in first.iter().enumerate() {
                m0[(i, k)] = *x;
            }
        }
        let m = self.solver(b)?.solve_many(m0.as_ref());
        Ok(external
            .iter()
            .enumerate()
            .map(|(k, ext)| {
                let exitance: Vec<f64> = (0..n).map(|i| m[(i, k)]).collect();
                let mut readings = self.outputs(&exitance);
                add_external_readings(&mut readings, std::slice::from_ref(ext), b, &[1.0]);
                let mut irradiance = self.apply_f(&exitance);
                add_external_irradiance(&mut irradiance, std::slice::from_ref(ext), b, &[1.0]);
                (LightResponse { exitance, readings }, irradiance)
            })
            .collect())
    }

    /// Each of `lights`' part of its direct light its emission does not carry.
    fn external_lights(&self, lights: &[ChannelLight]) -> Vec<ExternalLight> {
        lights
            .iter()
            .map(|l| l.external(self.operator(), &self.area, &self.output_rows))
            .collect()
    }

    /// `M0` of band `b` for each of `lights` alone at level 1 (W/m² or lux): its emission
    /// plus the first reflection `ρ ∘ E_ext` of its light from beyond the patches, what
    /// [`System::light_responses`] solves for.
    pub fn initial_exitances(&self, b: usize, lights: &[ChannelLight]) -> Vec<Vec<f64>> {
        self.initial_exitances_of(b, lights, &self.external_lights(lights))
    }

    fn initial_exitances_of(
        &self,
        b: usize,
        lights: &[ChannelLight],
        external: &[ExternalLight],
    ) -> Vec<Vec<f64>> {
        lights
            .iter()
            .zip(external)
            .map(|(light, ext)| {
                initial_exitance(
                    std::slice::from_ref(light),
                    std::slice::from_ref(ext),
                    &self.reflectance[b],
                    b,
                    &[1.0],
                    &[],
                )
            })
            .collect()
    }

    /// The irradiance (W/m² or lux) in band `b` on each patch of `patches` from `light` alone,
    /// whose exact exitance is `m` (its [`LightResponse::exitance`]): what
    /// [`System::light_responses_with_irradiance`] gives on those patches, from the operator's
    /// rows of those patches only, without a pass over every patch.
    pub fn light_irradiance_at(
        &self,
        b: usize,
        light: &ChannelLight,
        m: &[f64],
        patches: &[usize],
    ) -> Vec<f64> {
        let mut row = vec![0.0; self.patch_count()];
        patches
            .iter()
            .map(|&j| {
                self.operator.row(j, &mut row);
                // `F M` plus the light from beyond the patches, `E_direct − F emission`: the
                // emission's own share of `F M` is in its direct light already.
                let passed: f64 = row
                    .iter()
                    .zip(m)
                    .zip(&light.emission[b])
                    .map(|((g, x), e)| g * (x - e))
                    .sum();
                passed / self.area[j] + light.patch_irradiance[b][j]
            })
            .collect()
    }
}

/// The levels of `m` channels with channel `c` alone at level 1.
pub(crate) fn alone(m: usize, c: usize) -> Vec<f64> {
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

/// Adds to the readings `out` (sensors, zones, grid points) of band `b` the direct light from
/// beyond the patches of every channel at its level.
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

/// Adds to the patch irradiance `e` of band `b` the direct light from beyond the patches of
/// every channel at its level.
fn add_external_irradiance(e: &mut [f64], external: &[ExternalLight], b: usize, levels: &[f64]) {
    for (c, &l) in levels.iter().enumerate() {
        if let Some(e_ext) = &external[c].patches[b] {
            for (x, d) in e.iter_mut().zip(e_ext) {
                *x += l * d;
            }
        }
    }
}
