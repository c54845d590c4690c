//! The one value-to-colour map of every picture: a scale of round values in lux, fc, cd/m²
//! or W/m², cut into [`LEVELS`] equal bins, each drawn in one colour of viridis (van der Walt
//! and Smith, 2015: perceptually uniform, ordered in lightness, readable with the common
//! colour-vision deficiencies, and in grey). The picture, its colour bar and the tests all go
//! through [`Scale::colour`] and its inverse [`Scale::value_of`].

/// The number of colours, and of equal bins of the scale: viridis sampled at 128 evenly spaced
/// points of matplotlib's 256-entry table (`_viridis_data`, CC0), rounded to 8 bits. Every
/// one of them is a different colour (the full table rounded to 8 bits has two repeats), so a
/// colour read back from a picture names its bin.
pub const LEVELS: usize = 128;

/// Values that differ by at most this fraction of their magnitude are drawn as one value:
/// centred on the scale, without isolux lines. 1 %: about the uncertainty of a good
/// illuminance meter (DIN 5032-7 class A: 3 %), and far more than the form factors' closure
/// error that makes a white furnace's exact values differ (1e-4).
pub const UNIFORM: f64 = 0.01;

/// An 8-bit sRGB colour.
pub type Rgb = [u8; 3];

/// Values above the scale (an emitting patch's luminance): white, outside viridis.
pub const ABOVE: Rgb = [255, 255, 255];
/// No value (a black patch's illuminance, which the runtime cannot tell): mid grey.
pub const NO_VALUE: Rgb = [150, 150, 150];

/// Viridis at 128 points, darkest (lowest value) first: entry `k` is matplotlib's entry
/// `round(k · 255 / 127)`.
const VIRIDIS: [Rgb; LEVELS] = [
    [68, 1, 84],
    [69, 4, 87],
    [70, 7, 90],
    [70, 10, 93],
    [71, 13, 96],
    [71, 16, 99],
    [71, 19, 101],
    [72, 22, 104],
    [72, 24, 106],
    [72, 27, 109],
    [72, 29, 111],
    [72, 32, 113],
    [72, 35, 116],
    [72, 37, 118],
    [72, 40, 120],
    [71, 42, 122],
    [71, 45, 123],
    [71, 47, 125],
    [70, 50, 126],
    [70, 52, 128],
    [69, 55, 129],
    [68, 57, 131],
    [68, 59, 132],
    [67, 62, 133],
    [66, 64, 134],
    [65, 66, 135],
    [64, 69, 136],
    [63, 71, 136],
    [62, 73, 137],
    [62, 76, 138],
    [61, 78, 138],
    [60, 80, 139],
    [59, 82, 139],
    [58, 84, 140],
    [57, 86, 140],
    [56, 89, 140],
    [55, 91, 141],
    [54, 93, 141],
    [53, 95, 141],
    [52, 97, 141],
    [51, 99, 141],
    [50, 101, 142],
    [49, 103, 142],
    [48, 105, 142],
    [47, 107, 142],
    [46, 109, 142],
    [46, 111, 142],
    [45, 113, 142],
    [44, 114, 142],
    [43, 116, 142],
    [42, 118, 142],
    [42, 120, 142],
    [41, 122, 142],
    [40, 124, 142],
    [39, 126, 142],
    [39, 128, 142],
    [38, 130, 142],
    [37, 131, 142],
    [37, 133, 142],
    [36, 135, 142],
    [35, 137, 142],
    [34, 139, 141],
    [34, 141, 141],
    [33, 143, 141],
    [32, 146, 140],
    [32, 147, 140],
    [31, 149, 139],
    [31, 151, 139],
    [31, 153, 138],
    [30, 155, 138],
    [30, 157, 137],
    [31, 159, 136],
    [31, 161, 136],
    [31, 162, 135],
    [32, 164, 134],
    [33, 166, 133],
    [34, 168, 132],
    [36, 170, 131],
    [37, 172, 130],
    [39, 173, 129],
    [41, 175, 127],
    [44, 177, 126],
    [46, 179, 124],
    [49, 181, 123],
    [52, 182, 121],
    [55, 184, 120],
    [58, 186, 118],
    [61, 188, 116],
    [64, 189, 114],
    [68, 191, 112],
    [72, 193, 110],
    [76, 194, 108],
    [80, 196, 106],
    [84, 197, 104],
    [88, 199, 101],
    [92, 200, 99],
    [96, 202, 96],
    [101, 203, 94],
    [105, 205, 91],
    [110, 206, 88],
    [115, 208, 86],
    [119, 209, 83],
    [124, 210, 80],
    [129, 211, 77],
    [134, 213, 73],
    [139, 214, 70],
    [144, 215, 67],
    [149, 216, 64],
    [155, 217, 60],
    [160, 218, 57],
    [165, 219, 54],
    [170, 220, 50],
    [176, 221, 47],
    [181, 222, 43],
    [186, 222, 40],
    [192, 223, 37],
    [197, 224, 33],
    [202, 225, 31],
    [208, 225, 28],
    [213, 226, 26],
    [218, 227, 25],
    [223, 227, 24],
    [229, 228, 25],
    [234, 229, 26],
    [239, 229, 28],
    [244, 230, 30],
    [248, 230, 33],
    [253, 231, 37],
];

/// A scale of values: `[min, max]` in round numbers (multiples of `step`), cut into
/// [`LEVELS`] bins of one colour each.
#[derive(Clone, Debug, PartialEq)]
pub struct Scale {
    /// Lowest value, at the bottom of the colour bar.
    pub min: f64,
    /// Highest value, at its top.
    pub max: f64,
    /// Distance between the round values labelled on the colour bar (and, on a plan, between
    /// isolux lines).
    pub step: f64,
    /// Unit of the values: `lux`, `fc`, `cd/m²`, `W/m²`, `W/(m²·sr)`.
    pub unit: &'static str,
}

/// The round step (1, 2, 2.5 or 5 times a power of ten) at least `raw`.
fn round_step(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let magnitude = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0]
        .into_iter()
        .map(|m| m * magnitude)
        .find(|&s| s >= raw * (1.0 - 1e-12))
        .unwrap_or(10.0 * magnitude)
}

impl Scale {
    /// Whether values from `lo` to `hi` are one value for a picture: they differ by at most
    /// [`UNIFORM`] of the larger magnitude (less than any eye or meter tells apart).
    pub fn is_uniform(lo: f64, hi: f64) -> bool {
        hi - lo <= UNIFORM * hi.abs().max(lo.abs())
    }

    /// The scale of values from `lo` to `hi` (`lo ≤ hi`, finite): a round step giving about
    /// six intervals, and the bounds rounded out to multiples of it. A uniform field
    /// ([`Scale::is_uniform`]) gets a step of about a fifth of its magnitude and one step on
    /// either side, so it sits in the middle of the bar. A scale of non-negative values starts
    /// at 0 or above.
    pub fn around(lo: f64, hi: f64, unit: &'static str) -> Scale {
        let (lo, hi) = if lo.is_finite() && hi.is_finite() && lo <= hi {
            (lo, hi)
        } else {
            (0.0, 1.0)
        };
        let range = hi - lo;
        let uniform = Scale::is_uniform(lo, hi);
        let step = if uniform {
            round_step(if hi.abs() > 0.0 { hi.abs() / 5.0 } else { 1.0 })
        } else {
            round_step(range / 6.0)
        };
        let (mut min, max) = if uniform {
            let centre = ((lo + hi) / 2.0 / step).round() * step;
            (centre - step, centre + step)
        } else {
            ((lo / step).floor() * step, (hi / step).ceil() * step)
        };
        if lo >= 0.0 {
            min = min.max(0.0);
        }
        Scale {
            min,
            max,
            step,
            unit,
        }
    }

    /// Width of one colour's bin, in the scale's unit: a value read back from a colour
    /// ([`Scale::value_of`]) is within half of it of the value drawn.
    pub fn bin_width(&self) -> f64 {
        (self.max - self.min) / LEVELS as f64
    }

    /// The round values from `min` to `max`, `step` apart.
    pub fn ticks(&self) -> Vec<f64> {
        let n = ((self.max - self.min) / self.step).round() as usize;
        (0..=n).map(|k| self.min + k as f64 * self.step).collect()
    }

    /// The isolux levels of a plan whose values run from `lo` to `hi` on this scale: each round
    /// value ([`Scale::ticks`]) strictly between them; none for a uniform field
    /// ([`Scale::is_uniform`]), which has no lines to draw.
    pub fn isolux_levels(&self, lo: f64, hi: f64) -> Vec<f64> {
        if Scale::is_uniform(lo, hi) {
            return Vec::new();
        }
        self.ticks()
            .into_iter()
            .filter(|&t| t > lo && t < hi)
            .collect()
    }

    /// The bin of `value`: `None` above the scale (beyond rounding) or not a number; values
    /// below `min` fall in the first bin.
    pub fn bin(&self, value: f64) -> Option<usize> {
        let span = self.max - self.min;
        if !value.is_finite() || value > self.max + 1e-9 * span {
            return None;
        }
        let t = ((value - self.min) / span * LEVELS as f64).floor();
        Some((t.max(0.0) as usize).min(LEVELS - 1))
    }

    /// The colour `value` is drawn in: its bin's, [`ABOVE`] above the scale, [`NO_VALUE`]
    /// without a value.
    pub fn colour(&self, value: Option<f64>) -> Rgb {
        match value {
            None => NO_VALUE,
            Some(v) if v.is_nan() => NO_VALUE,
            Some(v) => self.bin(v).map_or(ABOVE, |k| VIRIDIS[k]),
        }
    }

    /// The colour of bin `k` (`k < LEVELS`), for the colour bar.
    pub fn bin_colour(k: usize) -> Rgb {
        VIRIDIS[k.min(LEVELS - 1)]
    }

    /// The inverse of [`Scale::colour`]: the centre of the bin drawn in `rgb`, or `None` for a
    /// colour that is none of the scale's.
    pub fn value_of(&self, rgb: Rgb) -> Option<f64> {
        let k = VIRIDIS.iter().position(|&c| c == rgb)?;
        Some(self.min + (k as f64 + 0.5) * self.bin_width())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Viridis' published ends, #440154 and #FDE725 (matplotlib's `viridis(0)` and
    /// `viridis(1)`), and every colour different, so that colours can be read back.
    #[test]
    fn the_table_is_viridis_with_distinct_colours() {
        assert_eq!(VIRIDIS[0], [0x44, 0x01, 0x54]);
        assert_eq!(VIRIDIS[LEVELS - 1], [0xFD, 0xE7, 0x25]);
        for (i, a) in VIRIDIS.iter().enumerate() {
            for b in &VIRIDIS[i + 1..] {
                assert_ne!(a, b);
            }
        }
        // Ordered in lightness: the relative luminance Y of sRGB (IEC 61966-2-1: linearised
        // channels weighted 0.2126, 0.7152, 0.0722) rises from each colour to the next.
        let linear = |c: u8| {
            let c = f64::from(c) / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        let y = |c: &Rgb| 0.2126 * linear(c[0]) + 0.7152 * linear(c[1]) + 0.0722 * linear(c[2]);
        for w in VIRIDIS.windows(2) {
            assert!(y(&w[1]) > y(&w[0]), "{w:?}");
        }
    }

    /// Round bounds and steps worked by hand: 312–687 lx is a range of 375, a sixth 62.5 →
    /// step 100, bounds 300 and 700; 0.013–0.049 → 0.006 → 0.01, 0.01–0.05; a uniform 500 lx →
    /// step 100 around it.
    #[test]
    fn scales_are_round() {
        let s = Scale::around(312.0, 687.0, "lux");
        assert_eq!((s.min, s.max, s.step), (300.0, 700.0, 100.0));
        assert_eq!(s.ticks(), vec![300.0, 400.0, 500.0, 600.0, 700.0]);
        let s = Scale::around(0.013, 0.049, "W/m²");
        assert!((s.step - 0.01).abs() < 1e-15);
        assert!((s.min - 0.01).abs() < 1e-15 && (s.max - 0.05).abs() < 1e-15);
        let s = Scale::around(500.0, 500.0, "lux");
        assert_eq!((s.min, s.max, s.step), (400.0, 600.0, 100.0));
        let s = Scale::around(0.0, 0.0, "lux");
        assert!(s.min == 0.0 && s.max > 0.0);
        // Within 1 %: one value, centred; beyond it a scale of its own.
        assert!(Scale::is_uniform(199.0, 201.0) && !Scale::is_uniform(197.0, 201.0));
        let s = Scale::around(199.9, 200.1, "lux");
        assert_eq!((s.min, s.max, s.step), (150.0, 250.0, 50.0));
    }

    /// The isolux levels of 312–687 lx are the scale's round values inside that range, worked
    /// by hand (ticks 300 to 700 every 100); a field within 1 % has none.
    #[test]
    fn isolux_levels_lie_inside_the_values() {
        let s = Scale::around(312.0, 687.0, "lux");
        assert_eq!(s.isolux_levels(312.0, 687.0), vec![400.0, 500.0, 600.0]);
        // A level equal to an end value is no line: nothing lies beyond it.
        assert_eq!(s.isolux_levels(300.0, 700.0), vec![400.0, 500.0, 600.0]);
        let u = Scale::around(199.9, 200.1, "lux");
        assert!(u.isolux_levels(199.9, 200.1).is_empty());
    }

    /// Every value maps to a colour that maps back to within half a bin, and the bins
    /// follow the values.
    #[test]
    fn colours_map_back_to_their_values() {
        let s = Scale::around(312.0, 687.0, "lux");
        let half = s.bin_width() / 2.0;
        for i in 0..=4000 {
            let v = 300.0 + 400.0 * i as f64 / 4000.0;
            let back = s.value_of(s.colour(Some(v))).unwrap();
            assert!((back - v).abs() <= half * (1.0 + 1e-12), "{v}: {back}");
        }
        assert_eq!(s.colour(Some(700.1)), ABOVE);
        assert_eq!(s.colour(None), NO_VALUE);
        assert_eq!(s.colour(Some(f64::NAN)), NO_VALUE);
        assert_eq!(s.value_of(ABOVE), None);
        assert_eq!(s.bin(299.0), Some(0));
        assert_eq!(s.bin(700.0), Some(LEVELS - 1));
    }
}
