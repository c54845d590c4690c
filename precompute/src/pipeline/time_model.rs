//! The time model: wall-clock seconds of each stage of `eigenrad build` on the 2-core machine
//! of docs/performance.md, from `eigenrad-bench scale` on the office at 1101 to 9905 patches
//! (idle machine, "Precompute scaling"), `eigenrad-bench compress` ("The hierarchical
//! operator") and builds of the open-plan floor ("Scenes at scale"; the stages after the form
//! factors). A loaded machine takes longer: the lines give the order of magnitude.

/// Seconds of the dense form factors at [`REFERENCE_PATCHES`]: 87.3 s for the office.
pub const DENSE_FORM_FACTOR_SECONDS: f64 = 87.3;
/// Growth exponent of the dense form factors' time with the patch count: 5.7 s at 2028
/// patches and 87.3 s at 9905 give `ln(87.3 / 5.7) / ln(9905 / 2028) = 1.72`.
pub const DENSE_FORM_FACTOR_EXPONENT: f64 = 1.72;
/// The hierarchical operator's assembly against the dense one at [`REFERENCE_PATCHES`]:
/// 0.61 at 9905 patches in the first measurement, where it reads about half of the `n²`
/// entries (its time ratio was 1.24 at 2028 patches, 0.76 at 4947); a second run under a
/// load that doubled while it ran gave 1.39, so the figure is good to a factor of two.
pub const HIERARCHICAL_FORM_FACTOR_RATIO: f64 = 0.61;
/// Growth exponent of the hierarchical assembly's time, taken from its time ratios:
/// the ratio falls as `n^-0.42` from 2028 to 9905 patches, so `1.72 − 0.42 = 1.3`.
pub const HIERARCHICAL_FORM_FACTOR_EXPONENT: f64 = 1.3;
/// The patch count the figures above are measured at.
pub const REFERENCE_PATCHES: f64 = 9905.0;
/// What a pair that a blocker may cut costs against a clear one (dimensionless): the
/// exact visibility casts a shadow per blocker per quadrature point. On the open-plan
/// floor cut to 1809 patches (docs/performance.md, "Why the floor's form factors are
/// slow") the pair integrals with blockers in their shaft took 194 µs each and the clear
/// ones 19.7 µs, in one run. The office the figures above come from has two desks, so
/// its own few occluded pairs are in them. With `s` the sampled share of pairs a blocker
/// may cut and `T_d(n)`, `T_h(n)` the office's dense and hierarchical figures, the form
/// factors are expected to take `(1 − s) T_d + c s T_d` dense and `(1 − s) T_h + c s T_d`
/// hierarchical: the occluded pairs fall in blocks stored whole, so they grow as `n²`
/// with either operator. For that floor (`s` = 0.71, dense) 42.7 s, against the 49 s its
/// 97.6 CPU-seconds make on two cores.
pub const OCCLUDED_PAIR_COST: f64 = 10.0;
/// Seconds per patch of the hierarchical form factors with `--visibility clusters` (and
/// its default `--cluster-misfit`) on the open-plan floor, about half of whose facing
/// pairs a blocker may cut: 51.5 s at 9888 patches, 75.9 s at 20 892, 195.5 s at 50 111
/// and 343.2 s at 102 934 (3.3–5.2 ms a patch; docs/performance.md, "Visibility between
/// clusters").
pub const CLUSTERS_FORM_FACTOR_SECONDS_PER_PATCH: f64 = 3.6e-3;
/// Vectors the block Lanczos eigensolve applies the operator to per wanted mode
/// (`radiosity::eigen`, a basis of six columns a mode): 784 for 32 modes of the
/// open-plan floor at 5643 patches, 896 at 9888 and at 20 892 (the build report's
/// "modes" line).
pub const EIGEN_COLUMNS_PER_MODE: f64 = 28.0;
/// Operator bytes times vectors the eigensolve gets through per second with the dense
/// f64 operator (faer's matrix product), the rest of the Lanczos work included: 784
/// vectors of 195.8 MB in 1.44 s on office-5k (`--solver partial`).
pub const DENSE_F64_BYTE_COLUMNS_PER_SECOND: f64 = 1.07e11;
/// The same with the dense f32 operator: 784 vectors of 97.9 MB in 1.59 s on office-5k.
pub const DENSE_F32_BYTE_COLUMNS_PER_SECOND: f64 = 4.8e10;
/// The same with the hierarchical operator: 896 vectors of 80.5 MB in 3.09 s and of
/// 208.8 MB in 8.03 s on the open-plan floor at 9888 and 20 892 patches
/// (`--visibility clusters`).
pub const HIERARCHICAL_BYTE_COLUMNS_PER_SECOND: f64 = 2.3e10;
/// Operator bytes per second of the exact channel responses and of the report's exact
/// cases with a dense operator (conjugate gradients, every right-hand side in one
/// block): 785 MB in 0.6 s.
pub const SOLVE_OPERATOR_BYTES_PER_SECOND: f64 = 1.3e9;
/// The same with the hierarchical operator, for the channels' responses: 80.5 MB in
/// 0.88 s and 208.8 MB in 2.43 s on the open-plan floor (five channels) at 9888 and
/// 20 892 patches.
pub const HIERARCHICAL_SOLVE_BYTES_PER_SECOND: f64 = 8.8e7;
/// The same for the report's cases: 80.5 MB in 1.12 s and 208.8 MB in 3.18 s.
pub const HIERARCHICAL_CASES_BYTES_PER_SECOND: f64 = 6.9e7;
/// Seconds per patch of the sensors' and zones' rows (0.3 s at 9905 patches).
pub const OUTPUT_SECONDS_PER_PATCH: f64 = 3.0e-5;
/// Seconds per patch of writing the basis (0.32 s at 9905 patches).
pub const SERIALIZATION_SECONDS_PER_PATCH: f64 = 3.2e-5;
/// Seconds per patch of the accuracy check through the runtime (0.95 s at 9905 patches).
pub const VERIFICATION_SECONDS_PER_PATCH: f64 = 1.0e-4;
