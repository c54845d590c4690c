//! Both evaluators against a plain f64 evaluation of the same basis, the channel evaluator
//! against the full one, incremental patch updates against full recomputation (the
//! evaluators' contracts are in `contracts.rs`).
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic,
    clippy::needless_range_loop
)]

mod common;

use common::Rng;
use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::{
    Basis, ChannelEvaluator, Error, Evaluator, Figures, Formulation, Precision,
};

/// Relative tolerance of the f32 evaluator against f64 arithmetic on the same stored
/// numbers (f32 storage): accumulated rounding of sums of ~10 terms, with margin.
const F32_RTOL: f64 = 1e-5;
/// Against the unquantised f64 tables: f16 keeps 11 significant bits (2^-11 ≈ 4.9e-4),
/// i16 with a per-column scale 15 bits of the column maximum; sums of a few dozen terms.
const F16_RTOL: f64 = 3e-3;
const I16_RTOL: f64 = 3e-4;

/// f64 rounded through f32, as the writer stores it.
fn r(v: f64) -> f64 {
    f64::from(v as f32)
}

/// Independent f64 evaluation of `docs/format.md`'s formulas from the tables.
struct Reference<'t> {
    t: &'t BasisTables,
    levels: Vec<f64>,
    extra: Vec<Vec<f64>>, // per patch, per band
}

impl Reference<'_> {
    fn n(&self) -> usize {
        self.t.patch_area.len()
    }
    fn split(&self) -> bool {
        self.t.formulation == Formulation::Split
    }
    fn rho(&self, i: usize, b: usize) -> f64 {
        r(self.t.patch_reflectance[i * self.t.bands + b])
    }
    fn v(&self, i: usize, b: usize, k: usize) -> f64 {
        r(self.t.modes[i * self.t.bands * self.t.mode_count + b * self.t.mode_count + k])
    }
    fn black_rank(&self, i: usize) -> usize {
        let bands = self.t.bands;
        (0..i)
            .filter(|&j| (0..bands).any(|b| self.rho(j, b) == 0.0))
            .count()
    }
    fn identity(&self, i: usize, b: usize) -> bool {
        self.split() || self.rho(i, b) == 0.0
    }
    /// Mode amplitude from the exitance set patch by patch (channels do not use the modes).
    fn amplitude(&self, b: usize, k: usize) -> f64 {
        let (bands, p) = (self.t.bands, self.t.mode_count);
        let mut a = 0.0;
        let e = r(self.t.eigenvalues[b * p + k]);
        let coef = if self.split() { e / (1.0 - e) } else { 1.0 / e };
        for i in 0..self.n() {
            let x = self.extra[i][b];
            if x == 0.0 {
                continue;
            }
            if self.rho(i, b) == 0.0 {
                a += x * r(self.t.black_projection[(self.black_rank(i) * bands + b) * p + k]);
            } else {
                a += x * r(self.t.patch_area[i]) / self.rho(i, b) * self.v(i, b, k) * coef;
            }
        }
        a
    }
    fn emitted(&self, i: usize, b: usize) -> f64 {
        let ch = self.t.patch_channel[i].map_or(0.0, |c| self.levels[usize::from(c)]);
        self.extra[i][b] + ch * r(self.t.patch_emission[i * self.t.bands + b])
    }
    fn exitance(&self, i: usize, b: usize) -> f64 {
        let (bands, p, m) = (self.t.bands, self.t.mode_count, self.levels.len());
        let mut v = 0.0;
        for c in 0..m {
            v += self.levels[c] * r(self.t.channel_response[i * m * bands + c * bands + b]);
        }
        if self.identity(i, b) {
            v += self.extra[i][b];
        }
        for k in 0..p {
            v += self.v(i, b, k) * self.amplitude(b, k);
        }
        v
    }
    fn output(&self, o: usize, b: usize) -> f64 {
        let (bands, p, m) = (self.t.bands, self.t.mode_count, self.levels.len());
        let outputs = self.t.sensor_names.len() + self.t.zone_names.len();
        let mut v = 0.0;
        for k in 0..p {
            v += r(self.t.output_modes[(o * bands + b) * p + k]) * self.amplitude(b, k);
        }
        for c in 0..m {
            v += self.levels[c] * r(self.t.output_channels[(o * bands + b) * m + c]);
        }
        for i in 0..self.n() {
            if self.identity(i, b) {
                v += r(self.t.output_view[i * outputs + o]) * self.extra[i][b];
            }
        }
        v
    }
    /// Grid point `g` (among all), the same formula over the grid tables (`grid_view` is
    /// point-major).
    fn grid(&self, g: usize, b: usize) -> f64 {
        let (bands, p, m, n) = (self.t.bands, self.t.mode_count, self.levels.len(), self.n());
        let mut v = 0.0;
        for k in 0..p {
            v += r(self.t.grid_modes[(g * bands + b) * p + k]) * self.amplitude(b, k);
        }
        for c in 0..m {
            v += self.levels[c] * r(self.t.grid_channels[(g * bands + b) * m + c]);
        }
        for i in 0..n {
            if self.identity(i, b) {
                v += r(self.t.grid_view[g * n + i]) * self.extra[i][b];
            }
        }
        v
    }
}

/// What both evaluators read, so that one comparison serves both.
trait Reads<const B: usize> {
    fn exitance(&self, i: usize) -> Result<[f32; B], Error>;
    fn exitance_all(&self, out: &mut [[f32; B]]) -> Result<(), Error>;
    fn irradiance(&self, i: usize) -> Result<[f32; B], Error>;
    fn luminance(&self, i: usize) -> Result<[f32; B], Error>;
    fn sensor_irradiance(&self, s: usize) -> Result<[f32; B], Error>;
    fn zone_irradiance(&self, z: usize) -> Result<[f32; B], Error>;
    fn grid_point_irradiance(&self, z: usize, point: usize) -> Result<[f32; B], Error>;
    fn zone_figures(&self, z: usize) -> Result<[Figures; B], Error>;
}

macro_rules! reads {
    ($ty:ty) => {
        fn exitance(&self, i: usize) -> Result<[f32; B], Error> {
            <$ty>::exitance(self, i)
        }
        fn exitance_all(&self, out: &mut [[f32; B]]) -> Result<(), Error> {
            <$ty>::exitance_all(self, out)
        }
        fn irradiance(&self, i: usize) -> Result<[f32; B], Error> {
            <$ty>::irradiance(self, i)
        }
        fn luminance(&self, i: usize) -> Result<[f32; B], Error> {
            <$ty>::luminance(self, i)
        }
        fn sensor_irradiance(&self, s: usize) -> Result<[f32; B], Error> {
            <$ty>::sensor_irradiance(self, s)
        }
        fn zone_irradiance(&self, z: usize) -> Result<[f32; B], Error> {
            <$ty>::zone_irradiance(self, z)
        }
        fn grid_point_irradiance(&self, z: usize, point: usize) -> Result<[f32; B], Error> {
            <$ty>::grid_point_irradiance(self, z, point)
        }
        fn zone_figures(&self, z: usize) -> Result<[Figures; B], Error> {
            <$ty>::zone_figures(self, z)
        }
    };
}

impl<const B: usize> Reads<B> for Evaluator<'_, B, 64, 16, 8, 8> {
    reads!(Evaluator<'_, B, 64, 16, 8, 8>);
}

impl<const B: usize> Reads<B> for ChannelEvaluator<'_, B, 8> {
    reads!(ChannelEvaluator<'_, B, 8>);
}

type Eval3<'a> = Evaluator<'a, 3, 64, 16, 8, 8>;
type Eval1<'a> = Evaluator<'a, 1, 64, 16, 8, 8>;

/// Compares every read of `eval` with the reference, norm-wise per kind of output.
fn compare<const B: usize>(eval: &impl Reads<B>, reference: &Reference<'_>, rtol: f64, what: &str) {
    let n = reference.n();
    let mut worst = 0.0f64;
    let mut all = vec![[0.0f32; B]; n];
    eval.exitance_all(&mut all).unwrap();
    let scale = (0..n)
        .flat_map(|i| (0..B).map(move |b| (i, b)))
        .map(|(i, b)| reference.exitance(i, b).abs())
        .fold(0.0, f64::max);
    for (i, row) in all.iter().enumerate() {
        let one = eval.exitance(i).unwrap();
        let lum = eval.luminance(i).unwrap();
        for b in 0..B {
            let want = reference.exitance(i, b);
            assert_eq!(one[b], row[b]);
            assert_eq!(lum[b], one[b] / std::f32::consts::PI);
            worst = worst.max((f64::from(one[b]) - want).abs());
            if reference.rho(i, b) > 0.0 {
                let e = eval.irradiance(i).unwrap()[b];
                let want_e = (want - reference.emitted(i, b)) / reference.rho(i, b);
                let err = (f64::from(e) - want_e).abs();
                assert!(
                    err <= rtol * scale / reference.rho(i, b),
                    "{what}: irradiance {i}: {e} vs {want_e}, scale {scale}"
                );
            } else {
                assert_eq!(
                    eval.irradiance(i).unwrap_err(),
                    Error::BlackPatch { patch: i }
                );
            }
        }
    }
    assert!(
        worst <= rtol * scale,
        "{what}: exitance error {worst:e} of scale {scale:e}"
    );
    let sensors = reference.t.sensor_names.len();
    let mut worst = 0.0f64;
    let mut scale = 0.0f64;
    for o in 0..sensors + reference.t.zone_names.len() {
        let got = if o < sensors {
            eval.sensor_irradiance(o)
        } else {
            eval.zone_irradiance(o - sensors)
        }
        .unwrap();
        for b in 0..B {
            let want = reference.output(o, b);
            worst = worst.max((f64::from(got[b]) - want).abs());
            scale = scale.max(want.abs());
        }
    }
    assert!(
        worst <= rtol * scale,
        "{what}: output error {worst:e} of scale {scale:e}"
    );
    // Grid points, zone by zone, and each zone's figures against the same figures of the
    // reference's points computed here in f64 (mean, min, max, min/mean).
    let mut next = 0;
    let mut pieces = reference.t.grid_lattice.iter();
    for (z, &count) in reference.t.grid_pieces.iter().enumerate() {
        let points: usize = pieces
            .by_ref()
            .take(count as usize)
            .map(|l| l[2] as usize)
            .sum();
        let mut want = vec![Vec::new(); B];
        for point in 0..points {
            let got = eval.grid_point_irradiance(z, point).unwrap();
            for b in 0..B {
                let w = reference.grid(next + point, b);
                want[b].push(w);
                let err = (f64::from(got[b]) - w).abs();
                assert!(
                    err <= rtol * scale,
                    "{what}: grid {z}/{point}: {} vs {w}",
                    got[b]
                );
            }
        }
        assert!(matches!(
            eval.grid_point_irradiance(z, points),
            Err(Error::IndexOutOfRange { .. })
        ));
        next += points;
        if points == 0 {
            assert_eq!(eval.zone_figures(z).unwrap_err(), Error::NoGrid { zone: z });
            continue;
        }
        let figures = eval.zone_figures(z).unwrap();
        for b in 0..B {
            let v = &want[b];
            let avg = v.iter().sum::<f64>() / v.len() as f64;
            let min = v.iter().copied().fold(f64::INFINITY, f64::min);
            let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let f = figures[b];
            assert_eq!(f.points, points);
            for (got, want, name) in [
                (f.average, avg, "E_avg"),
                (f.minimum, min, "E_min"),
                (f.maximum, max, "E_max"),
            ] {
                let err = (f64::from(got) - want).abs();
                assert!(
                    err <= rtol * scale,
                    "{what}: zone {z} {name}: {got} vs {want}"
                );
            }
            // U_o is E_min / E_avg of the figures just checked (0 where E_avg is not
            // positive, which random modes can make it): checked as that quotient, since
            // near a zero mean the quotient of two checked values amplifies their rounding.
            // The runtime divides by the unrounded mean: within 1e-6 of the f32 quotient.
            let want_u = if f.average > 0.0 {
                f64::from(f.minimum) / f64::from(f.average)
            } else {
                0.0
            };
            let err = (f64::from(f.uniformity) - want_u).abs();
            assert!(
                err <= 1e-6 * want_u.abs(),
                "{what}: zone {z} U_o {} vs {want_u}",
                f.uniformity
            );
        }
    }
}

fn exercise<const B: usize>(formulation: Formulation, precision: Precision, rtol: f64) {
    for seed in 1..4u64 {
        let t = common::random(seed * 977, formulation, precision, B);
        // For quantised storage the reference uses the unquantised tables, so rtol covers
        // the quantisation too.
        let bytes = t.to_bytes().unwrap();
        let basis = Basis::from_bytes(&bytes).unwrap();
        let mut eval = Evaluator::<B, 64, 16, 8, 8>::new(basis).unwrap();
        let mut channels = ChannelEvaluator::<B, 8>::new(basis).unwrap();
        let mut rng = Rng(seed);
        let n = t.patch_area.len();
        let m = t.channel_names.len();
        let levels: Vec<f64> = (0..m).map(|_| rng.range(0.0, 1.0)).collect();
        let levels32: Vec<f32> = levels.iter().map(|&l| l as f32).collect();
        eval.set_channel_levels(&levels32).unwrap();
        channels.set_channel_levels(&levels32).unwrap();
        let mut reference = Reference {
            t: &t,
            levels: levels32.iter().map(|&l| f64::from(l)).collect(),
            extra: vec![vec![0.0; B]; n],
        };
        let what = format!("{formulation:?}/{precision:?}/{B} bands/seed {seed}");
        compare(&eval, &reference, rtol, &format!("{what}: levels"));
        compare(
            &channels,
            &reference,
            rtol,
            &format!("{what}: channel evaluator"),
        );

        // One channel changed.
        channels.set_channel_level(1, 0.25).unwrap();
        eval.set_channel_level(1, 0.25).unwrap();
        reference.levels[1] = 0.25;
        compare(&channels, &reference, rtol, &format!("{what}: one channel"));

        // General case: arbitrary exitance on reflecting patches in no channel (0, 5), on a
        // reflecting lamp (10) and on black lamps (3, 17).
        for i in [0, 3, 5, 10, 17] {
            let x: [f32; B] = core::array::from_fn(|_| rng.range(0.0, 500.0) as f32);
            eval.set_patch_exitance(i, x).unwrap();
            reference.extra[i] = x.iter().map(|&v| f64::from(v)).collect();
        }
        compare(&eval, &reference, rtol, &format!("{what}: patch exitance"));

        // Channels change on top of patch exitance.
        eval.set_channel_level(2, 0.9).unwrap();
        reference.levels[2] = 0.9;
        compare(
            &eval,
            &reference,
            rtol,
            &format!("{what}: channel and patches"),
        );
    }
}

#[test]
fn f32_evaluation_equals_f64_on_the_same_basis() {
    for f in [Formulation::Split, Formulation::Seed] {
        exercise::<1>(f, Precision::F32, F32_RTOL);
        exercise::<3>(f, Precision::F32, F32_RTOL);
    }
}

#[test]
fn quantised_storage_stays_within_its_tolerance() {
    for f in [Formulation::Split, Formulation::Seed] {
        exercise::<1>(f, Precision::F16, F16_RTOL);
        exercise::<3>(f, Precision::F16, F16_RTOL);
        exercise::<1>(f, Precision::I16, I16_RTOL);
        exercise::<3>(f, Precision::I16, I16_RTOL);
    }
}

#[test]
fn incremental_updates_equal_full_recomputation() {
    let t = common::random(42, Formulation::Split, Precision::F32, 3);
    let bytes = t.to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    // 200 single-channel updates and a few per-patch changes, applied incrementally...
    let mut inc = Eval3::new(basis).unwrap();
    let mut rng = Rng(9);
    let mut levels = [0.0f32; 3];
    let mut patch = vec![[0.0f32; 3]; 23];
    for step in 0..200 {
        let c = step % 3;
        levels[c] = rng.range(0.0, 1.0) as f32;
        inc.set_channel_level(c, levels[c]).unwrap();
        if step % 17 == 0 {
            patch[step % 23] = [rng.range(0.0, 100.0) as f32; 3];
            inc.set_patch_exitance(step % 23, patch[step % 23]).unwrap();
        }
    }
    // ...and the final state set once, from scratch.
    let mut full = Eval3::new(basis).unwrap();
    for (i, x) in patch.iter().enumerate() {
        full.set_patch_exitance(i, *x).unwrap();
    }
    full.set_channel_levels(&levels).unwrap();
    let mut scale = 0.0f32;
    let mut worst = 0.0f32;
    for i in 0..23 {
        let (a, b) = (inc.exitance(i).unwrap(), full.exitance(i).unwrap());
        for k in 0..3 {
            worst = worst.max((a[k] - b[k]).abs());
            scale = scale.max(b[k].abs());
        }
    }
    for s in 0..2 {
        let (a, b) = (
            inc.sensor_irradiance(s).unwrap(),
            full.sensor_irradiance(s).unwrap(),
        );
        for k in 0..3 {
            worst = worst.max((a[k] - b[k]).abs());
        }
    }
    // 200 incremental f32 updates: drift of a few ulps per update at most.
    assert!(worst <= 1e-5 * scale, "drift {worst} of scale {scale}");
}

#[test]
fn clearing_patch_exitance_restores_the_channel_state() {
    let t = common::random(4, Formulation::Split, Precision::F32, 1);
    let bytes = t.to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let mut e = Eval1::new(basis).unwrap();
    e.set_channel_levels(&[0.3, 0.6, 0.9]).unwrap();
    let before: Vec<f32> = (0..23).map(|i| e.exitance(i).unwrap()[0]).collect();
    let sensor = e.sensor_irradiance(0).unwrap();
    e.set_patch_exitance(2, [700.0]).unwrap();
    e.set_patch_exitance(3, [300.0]).unwrap();
    assert_ne!(e.exitance(2).unwrap()[0], before[2]);
    assert_ne!(e.sensor_irradiance(0).unwrap(), sensor);
    // Channels are not in the modes: clearing restores their readings to the bit.
    e.clear_patch_exitance();
    for (i, b) in before.iter().enumerate() {
        assert_eq!(e.exitance(i).unwrap()[0], *b, "patch {i}");
    }
    assert_eq!(e.sensor_irradiance(0).unwrap(), sensor);
    // So does setting every patch back to 0, one at a time.
    e.set_patch_exitance(2, [700.0]).unwrap();
    e.set_patch_exitance(3, [300.0]).unwrap();
    e.set_patch_exitance(2, [0.0]).unwrap();
    assert_ne!(e.sensor_irradiance(0).unwrap(), sensor);
    e.set_patch_exitance(3, [0.0]).unwrap();
    for (i, b) in before.iter().enumerate() {
        assert_eq!(e.exitance(i).unwrap()[0], *b, "patch {i}");
    }
    assert_eq!(e.sensor_irradiance(0).unwrap(), sensor);
}

/// Every read of `a` and `b` agrees to the bit.
fn same_reads<const B: usize>(a: &impl Reads<B>, b: &impl Reads<B>, n: usize, what: &str) {
    let mut all_a = vec![[0.0f32; B]; n];
    let mut all_b = vec![[0.0f32; B]; n];
    a.exitance_all(&mut all_a).unwrap();
    b.exitance_all(&mut all_b).unwrap();
    assert_eq!(all_a, all_b, "{what}: exitance_all");
    for i in 0..n {
        assert_eq!(a.exitance(i), b.exitance(i), "{what}: exitance {i}");
        assert_eq!(a.irradiance(i), b.irradiance(i), "{what}: irradiance {i}");
        assert_eq!(a.luminance(i), b.luminance(i), "{what}: luminance {i}");
    }
    for s in 0..3 {
        assert_eq!(
            a.sensor_irradiance(s),
            b.sensor_irradiance(s),
            "{what}: sensor {s}"
        );
        assert_eq!(
            a.zone_irradiance(s),
            b.zone_irradiance(s),
            "{what}: zone {s}"
        );
    }
}

fn channel_and_full_agree<const B: usize>(formulation: Formulation, precision: Precision) {
    let t = common::random(31, formulation, precision, B);
    let bytes = t.to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let mut full = Evaluator::<B, 64, 16, 8, 8>::new(basis).unwrap();
    let mut channels = ChannelEvaluator::<B, 8>::new(basis).unwrap();
    let what = format!("{formulation:?}/{precision:?}/{B} bands");
    same_reads(&full, &channels, 23, &format!("{what}: all off"));
    let mut rng = Rng(5);
    for step in 0..20 {
        let c = step % 3;
        let level = [0.0, 0.1, 0.37, 0.8, 1.0][(rng.next_f64() * 5.0) as usize % 5];
        full.set_channel_level(c, level).unwrap();
        channels.set_channel_level(c, level).unwrap();
        if step == 10 {
            // Patch exitance set and removed again leaves nothing behind.
            full.set_patch_exitance(5, [250.0; B]).unwrap();
            full.clear_patch_exitance();
        }
        same_reads(&full, &channels, 23, &format!("{what}: step {step}"));
    }
    full.set_channel_levels(&[0.2, 0.4, 0.6]).unwrap();
    channels.set_channel_levels(&[0.2, 0.4, 0.6]).unwrap();
    same_reads(&full, &channels, 23, &format!("{what}: all set"));
    // The full evaluator exposes its channel part as the same reads.
    same_reads(
        full.channels(),
        &channels,
        23,
        &format!("{what}: channels()"),
    );
}

#[test]
fn channel_evaluator_reads_what_the_full_one_reads_without_patch_exitance() {
    for f in [Formulation::Split, Formulation::Seed] {
        for p in [Precision::F32, Precision::F16, Precision::I16] {
            channel_and_full_agree::<1>(f, p);
            channel_and_full_agree::<3>(f, p);
        }
    }
}

/// Channel exitance of every patch computed here from the stored bytes, in `f32`, in the
/// order the runtime has always summed a row (docs/format.md, "Matrices"): value = stored ×
/// column scale (f16 through `format::f16_to_f32`, i16 as an integer; f32 as it is), then one
/// band as a dot product (`Iterator::sum` of the products), several bands each adding its
/// products channel by channel from 0. `exitance_all` and `exitance` must both give it to the
/// bit, in every precision, in one and three bands, on both evaluators (the full one also
/// after patch exitance has been set and cleared).
fn rows_summed_by_hand<const B: usize>(precision: Precision) {
    let t = common::random(59, Formulation::Split, precision, B);
    let bytes = t.to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let raw = eigenrad_runtime::format::decode(&bytes).unwrap();
    let (n, m) = (t.patch_area.len(), t.channel_names.len());
    let cols = m * B;
    let stored = |i: usize, col: usize| -> f32 {
        let scale = |c: usize| {
            f32::from_le_bytes(
                raw.channel_response.scales[4 * c..4 * c + 4]
                    .try_into()
                    .unwrap(),
            )
        };
        let d = raw.channel_response.data;
        match precision {
            Precision::F32 => {
                let k = 4 * (i * cols + col);
                f32::from_le_bytes(d[k..k + 4].try_into().unwrap())
            }
            Precision::F16 => {
                let k = 2 * (i * cols + col);
                eigenrad_runtime::format::f16_to_f32(u16::from_le_bytes([d[k], d[k + 1]]))
                    * scale(col)
            }
            Precision::I16 => {
                let k = 2 * (i * cols + col);
                f32::from(i16::from_le_bytes([d[k], d[k + 1]])) * scale(col)
            }
        }
    };
    let by_hand = |levels: &[f32]| -> Vec<[f32; B]> {
        (0..n)
            .map(|i| {
                let mut out = [0.0f32; B];
                if B == 1 {
                    out[0] = (0..m).map(|c| stored(i, c) * levels[c]).sum();
                } else {
                    for c in 0..m {
                        for b in 0..B {
                            out[b] += stored(i, c * B + b) * levels[c];
                        }
                    }
                }
                out
            })
            .collect()
    };
    let mut full = Evaluator::<B, 64, 16, 8, 8>::new(basis).unwrap();
    let mut channels = ChannelEvaluator::<B, 8>::new(basis).unwrap();
    let mut rng = Rng(17);
    for case in 0..6 {
        let levels: Vec<f32> = (0..m)
            .map(|c| match (case, c) {
                (0, _) => 0.0,
                (1, 0) => 1.0,
                _ => rng.range(0.0, 1.0) as f32,
            })
            .collect();
        full.set_channel_levels(&levels).unwrap();
        channels.set_channel_levels(&levels).unwrap();
        if case == 3 {
            full.set_patch_exitance(4, [90.0; B]).unwrap();
            full.clear_patch_exitance();
        }
        let want = by_hand(&levels);
        let what = format!("{precision:?}/{B} bands/case {case}");
        for (name, eval) in [
            ("channels", &channels as &dyn Reads<B>),
            ("full", &full as &dyn Reads<B>),
        ] {
            let mut all = vec![[f32::NAN; B]; n];
            eval.exitance_all(&mut all).unwrap();
            for i in 0..n {
                let one = eval.exitance(i).unwrap();
                for b in 0..B {
                    assert_eq!(
                        all[i][b].to_bits(),
                        want[i][b].to_bits(),
                        "{what}: {name} exitance_all {i}"
                    );
                    assert_eq!(
                        one[b].to_bits(),
                        want[i][b].to_bits(),
                        "{what}: {name} exitance {i}"
                    );
                }
            }
        }
    }
}

#[test]
fn every_patch_at_once_sums_each_row_as_one_patch_alone() {
    for p in [Precision::F32, Precision::F16, Precision::I16] {
        rows_summed_by_hand::<1>(p);
        rows_summed_by_hand::<3>(p);
    }
}
