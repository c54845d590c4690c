//! The figures of a calculation grid (EN 12464-1:2021, 4.4): average, minimum, maximum and
//! uniformity of the illuminance (or irradiance) at its points. Defined here once; the
//! evaluators stream a zone's points through it and the host tools reuse it for the exact
//! solve.

/// A zone's grid figures in one band, lux (photopic) or W/m².
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Figures {
    /// `E_avg`: the arithmetic mean over the grid points.
    pub average: f32,
    /// `E_min`: the lowest point.
    pub minimum: f32,
    /// `E_max`: the highest point.
    pub maximum: f32,
    /// `U_o = E_min / E_avg` (dimensionless; 0 when `E_avg` is 0: an unlit grid has no
    /// uniformity to speak of).
    pub uniformity: f32,
    /// Number of points the figures are over.
    pub points: usize,
}

impl Figures {
    /// The figures of `values` (one reading per grid point), or `None` when there are none or
    /// one is not finite.
    pub fn of(values: impl IntoIterator<Item = f32>) -> Option<Figures> {
        let mut acc = Accumulator::default();
        for v in values {
            acc.add(v);
        }
        acc.figures()
    }
}

/// The running sums of [`Figures`]: what a streaming pass over a grid keeps per band. The
/// sum is kept in `f64`, so that the mean of many points does not lose `f32` digits.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Accumulator {
    sum: f64,
    minimum: f32,
    maximum: f32,
    points: usize,
    finite: bool,
}

impl Default for Accumulator {
    fn default() -> Self {
        Accumulator {
            sum: 0.0,
            minimum: f32::INFINITY,
            maximum: f32::NEG_INFINITY,
            points: 0,
            finite: true,
        }
    }
}

impl Accumulator {
    /// Adds one point's reading.
    pub(crate) fn add(&mut self, v: f32) {
        self.finite &= v.is_finite();
        self.sum += f64::from(v);
        self.minimum = self.minimum.min(v);
        self.maximum = self.maximum.max(v);
        self.points += 1;
    }

    /// The figures so far, `None` without points or with a reading that is not finite.
    pub(crate) fn figures(&self) -> Option<Figures> {
        if self.points == 0 || !self.finite {
            return None;
        }
        let average = (self.sum / self.points as f64) as f32;
        let uniformity = if average > 0.0 {
            self.minimum / average
        } else {
            0.0
        };
        Some(Figures {
            average,
            minimum: self.minimum,
            maximum: self.maximum,
            uniformity,
            points: self.points,
        })
    }
}
