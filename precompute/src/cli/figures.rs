//! Figures as the commands print them: a fixed number of decimals, and no minus sign on a
//! figure that shows as zero.
//!
//! A reading with every channel off sums responses of both signs (the modes of the basis) to
//! a value within rounding of 0, and `-0.0` or `-0.0000` would read as a negative light.

/// `x` to `decimals` places; a value that rounds to zero at that precision (including
/// `-0.0`) prints without its sign.
pub fn fixed(x: f64, decimals: usize) -> String {
    let text = format!("{x:.decimals$}");
    match text.strip_prefix('-') {
        Some(unsigned) if unsigned.bytes().all(|b| b == b'0' || b == b'.') => unsigned.to_owned(),
        _ => text,
    }
}

#[cfg(test)]
mod tests {
    use super::fixed;

    #[test]
    fn a_figure_that_shows_as_zero_has_no_sign() {
        assert_eq!(fixed(-0.0, 1), "0.0");
        assert_eq!(fixed(-1e-9, 4), "0.0000");
        assert_eq!(fixed(-0.00004, 4), "0.0000");
        assert_eq!(fixed(-0.00005001, 4), "-0.0001");
        assert_eq!(fixed(-2.5, 1), "-2.5");
        assert_eq!(fixed(0.0, 0), "0");
        assert_eq!(fixed(-0.4, 0), "0");
        assert_eq!(fixed(f64::NAN, 2), "NaN");
        assert_eq!(fixed(f64::NEG_INFINITY, 2), "-inf");
    }
}
