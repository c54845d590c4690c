//! The error figures of every accuracy report: one definition each, used by `eigenrad build`
//! (its report and `--tolerance`), `eigenrad verify` and `eigenrad-bench`.
//!
//! Each compares an approximation (a truncated expansion, the runtime's evaluation of a basis,
//! an iterative solve) with the exact solve of the same band, and is dimensionless: the
//! exitances are in W/m² or lux, the readings (sensor and zone irradiance) in W/m² or lux,
//! and the units cancel. A report takes the worst over bands and cases.
//!
//! A reading (a sensor's or zone's irradiance, a patch's exitance) is measured against its own
//! exact value, never against the largest reading of the scene: a dim sensor 7 % off is 7 %
//! off ([`reading_errors`], [`worst_reading`]). The area-weighted [`patch_error`] sums up a
//! whole room's exitance in one figure.

/// Area-weighted RMS of the difference over that of the exact exitance:
/// `sqrt(Σ A_i (x_i − e_i)² / Σ A_i e_i²)`, for patch areas `area` (m²), approximate
/// exitance `approx` and exact exitance `exact` (both W/m² or lux, one band).
///
/// The denominator is floored at the smallest normal `f64`, so that a band the case leaves
/// dark everywhere, and which the approximation leaves dark too, has error 0.
pub fn patch_error(area: &[f64], approx: &[f64], exact: &[f64]) -> f64 {
    let mut difference = 0.0;
    let mut reference = 0.0;
    for ((a, x), e) in area.iter().zip(approx).zip(exact) {
        difference += a * ((x - e) * (x - e));
        reference += a * (e * e);
    }
    (difference / reference.max(f64::MIN_POSITIVE)).sqrt()
}

/// Readings whose exact value is below this share of the largest exact reading are measured
/// against it instead of against themselves ([`reading_errors`]): a reading that is exactly
/// 0 (a sensor facing away from every emitter) would otherwise divide by zero.
pub const READING_FLOOR: f64 = 1e-12;

/// The error of each reading relative to its own exact value, `|x_o − e_o| / |e_o|`
/// (readings in W/m² or lux, one band), with `|e_o|` floored at [`READING_FLOOR`] times the
/// largest `|e|`; exactly 0 where the two agree exactly.
pub fn reading_errors(approx: &[f64], exact: &[f64]) -> Vec<f64> {
    let floor = READING_FLOOR
        * exact
            .iter()
            .fold(0.0f64, |s, e| s.max(e.abs()))
            .max(f64::MIN_POSITIVE);
    approx
        .iter()
        .zip(exact)
        .map(|(x, e)| {
            let d = (x - e).abs();
            if d == 0.0 {
                0.0
            } else {
                d / e.abs().max(floor)
            }
        })
        .collect()
}

/// The worst of [`reading_errors`]: its error and the index of the reading (0 and index 0
/// for no readings).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Worst {
    /// The relative error, dimensionless.
    pub error: f64,
    /// Which reading (sensor, zone or patch index).
    pub index: usize,
}

impl Worst {
    /// The worse of `self` and `other`; `self` on a tie.
    pub fn max(self, other: Worst) -> Worst {
        if other.error > self.error {
            other
        } else {
            self
        }
    }
}

/// The reading with the largest [`reading_errors`] between `approx` and `exact`.
pub fn worst_reading(approx: &[f64], exact: &[f64]) -> Worst {
    reading_errors(approx, exact)
        .into_iter()
        .enumerate()
        .fold(Worst::default(), |w, (index, error)| {
            w.max(Worst { error, index })
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two patches of 1 and 3 m², exact 2 and 1, approximation 2 and 2: `sqrt(3 / 7)`.
    #[test]
    fn patch_error_is_the_area_weighted_rms_ratio() {
        let e = patch_error(&[1.0, 3.0], &[2.0, 2.0], &[2.0, 1.0]);
        assert!((e - (3.0f64 / 7.0).sqrt()).abs() < 1e-15);
        assert_eq!(patch_error(&[1.0], &[0.0], &[0.0]), 0.0);
    }

    /// A dim reading 50 % off is the worst, though a bright one is further off in lux.
    #[test]
    fn the_worst_reading_is_the_one_furthest_from_itself() {
        let w = worst_reading(&[110.0, 3.0], &[100.0, 2.0]);
        assert_eq!(w.index, 1);
        assert_eq!(w.error, 0.5);
        assert_eq!(worst_reading(&[], &[]), Worst::default());
    }

    /// Each reading against itself; a reading of exactly 0 against the floor.
    #[test]
    fn reading_errors_are_relative_to_each_reading() {
        let r = reading_errors(&[4.0, 2.0, 1e-9], &[4.0, 1.0, 0.0]);
        assert_eq!(r[0], 0.0);
        assert_eq!(r[1], 1.0);
        assert!((r[2] - 1e-9 / (4.0 * READING_FLOOR)).abs() < 1e-12);
    }
}
