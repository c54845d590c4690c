//! The figures of a calculation grid (EN 12464-1:2021, 4.4): average, minimum, maximum and
//! uniformity of the illuminance (or irradiance) at its points. Defined here once; the
//! evaluators stream a zone's points through it in `f32` and the host tools reuse it in `f64`
//! for the exact solve.

/// A reading the figures can be taken of: `f32` (the evaluators) or `f64` (host tools).
pub trait Reading: Copy + PartialOrd + sealed::Sealed {
    /// Zero.
    const ZERO: Self;
    /// The value as `f64` (exact for both).
    fn to_f64(self) -> f64;
    /// The nearest value to `x`.
    fn from_f64(x: f64) -> Self;
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

impl Reading for f32 {
    const ZERO: Self = 0.0;
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    fn from_f64(x: f64) -> Self {
        x as f32
    }
}

impl Reading for f64 {
    const ZERO: Self = 0.0;
    fn to_f64(self) -> f64 {
        self
    }
    fn from_f64(x: f64) -> Self {
        x
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
/// sum is kept in `f64`, so that the mean of many `f32` points keeps its digits.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Accumulator<T> {
    sum: f64,
    minimum: T,
    maximum: T,
    points: usize,
    finite: bool,
}

impl<T: Reading> Default for Accumulator<T> {
    fn default() -> Self {
        Accumulator {
            sum: 0.0,
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
        let x = v.to_f64();
        self.finite &= x.is_finite();
        self.sum += x;
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
        let mean = self.sum / self.points as f64;
        let uniformity = if mean > 0.0 {
            self.minimum.to_f64() / mean
        } else {
            0.0
        };
        Some(Figures {
            average: T::from_f64(mean),
            minimum: self.minimum,
            maximum: self.maximum,
            uniformity: T::from_f64(uniformity),
            points: self.points,
        })
    }
}
