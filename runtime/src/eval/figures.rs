//! The figures of a calculation grid (EN 12464-1:2021, 4.4): average, minimum, maximum and
//! uniformity of the illuminance (or irradiance) at its points. Defined here once; the
//! evaluators stream a zone's points through it in `f32` and the host tools reuse it in `f64`
//! for the exact solve.

/// A reading the figures can be taken of: `f32` (the evaluators) or `f64` (host tools).
/// The arithmetic stays in the reading's own type, so that a controller's `f32` figures link
/// no double-precision code (soft float on a single-precision FPU).
pub trait Reading:
    Copy
    + PartialOrd
    + core::ops::Add<Output = Self>
    + core::ops::Sub<Output = Self>
    + core::ops::Div<Output = Self>
    + sealed::Sealed
{
    /// Zero.
    const ZERO: Self;
    /// Whether the value is finite.
    fn finite(self) -> bool;
    /// A count of points as a value (exact up to 2²⁴ points in `f32`).
    fn count(n: usize) -> Self;
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

impl Reading for f32 {
    const ZERO: Self = 0.0;
    fn finite(self) -> bool {
        self.is_finite()
    }
    fn count(n: usize) -> Self {
        n as f32
    }
}

impl Reading for f64 {
    const ZERO: Self = 0.0;
    fn finite(self) -> bool {
        self.is_finite()
    }
    fn count(n: usize) -> Self {
        n as f64
    }
}

/// A zone's grid figures in one band, lux (photopic) or W/m².
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Figures<T = f32> {
    /// `E_avg`: the arithmetic mean over the grid points.
    pub average: T,
    /// `E_min`: the lowest point.
    pub minimum: T,
    /// `E_max`: the highest point.
    pub maximum: T,
    /// `U_o = E_min / E_avg` (dimensionless; 0 when `E_avg` is not positive: an unlit grid
    /// has no uniformity to speak of).
    pub uniformity: T,
    /// Number of points the figures are over.
    pub points: usize,
}

impl<T: Reading> Figures<T> {
    /// The figures of `values` (one reading per grid point), or `None` when there are none or
    /// one is not finite.
    pub fn of(values: impl IntoIterator<Item = T>) -> Option<Figures<T>> {
        let mut acc = Accumulator::default();
        for v in values {
            acc.add(v);
        }
        acc.figures()
    }
}

/// The running sums of [`Figures`]: what a streaming pass over a grid keeps per band. The
/// sum is compensated (Kahan summation: the rounding error of each addition is carried into
/// the next), so that the mean of many points is within a few roundings of the exact mean in
/// the readings' own precision, whatever their number.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Accumulator<T> {
    sum: T,
    /// The rounding error of the last addition to `sum` (what it lost, negated).
    compensation: T,
    minimum: T,
    maximum: T,
    points: usize,
    finite: bool,
}

impl<T: Reading> Default for Accumulator<T> {
    fn default() -> Self {
        Accumulator {
            sum: T::ZERO,
            compensation: T::ZERO,
            minimum: T::ZERO,
            maximum: T::ZERO,
            points: 0,
            finite: true,
        }
    }
}

impl<T: Reading> Accumulator<T> {
    /// Adds one point's reading.
    pub(crate) fn add(&mut self, v: T) {
        self.finite &= v.finite();
        let y = v - self.compensation;
        let t = self.sum + y;
        self.compensation = (t - self.sum) - y;
        self.sum = t;
        if self.points == 0 || v < self.minimum {
            self.minimum = v;
        }
        if self.points == 0 || v > self.maximum {
            self.maximum = v;
        }
        self.points += 1;
    }

    /// The figures so far, `None` without points or with a reading that is not finite.
    pub(crate) fn figures(&self) -> Option<Figures<T>> {
        if self.points == 0 || !self.finite {
            return None;
        }
        let mean = self.sum / T::count(self.points);
        let uniformity = if mean > T::ZERO {
            self.minimum / mean
        } else {
            T::ZERO
        };
        Some(Figures {
            average: mean,
            minimum: self.minimum,
            maximum: self.maximum,
            uniformity,
            points: self.points,
        })
    }
}
