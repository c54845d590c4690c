//! A microcontroller's flash budget for a basis: how it is written on the command line and in
//! manifests (`512KiB`, `1MiB`, `1.5MiB` or a plain byte count), and how it is printed.
//!
//! A basis lives in the part's flash next to the firmware, so its size is a hard limit that a
//! build states before the long stages and every basis written is checked against.

use std::fmt;
use std::str::FromStr;

/// Bytes of flash a basis may take.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct FlashBudget {
    /// The budget in bytes.
    pub bytes: u64,
}

impl FlashBudget {
    /// 512 KiB: half of a common 1 MiB Cortex-M4F part, leaving the rest to the firmware.
    pub const DEFAULT: FlashBudget = FlashBudget { bytes: 512 * 1024 };

    /// Whether a basis of `bytes` bytes fits.
    pub fn fits(self, bytes: u64) -> bool {
        bytes <= self.bytes
    }
}

impl Default for FlashBudget {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Why a flash budget could not be read; its `Display` says what is accepted.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseFlashBudgetError {
    /// The text that was given.
    pub given: String,
}

impl fmt::Display for ParseFlashBudgetError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "flash budget {:?} is not a size: give bytes (524288) or a number with KiB, MiB, \
             kB or MB (512KiB, 1.5MiB)",
            self.given
        )
    }
}

impl std::error::Error for ParseFlashBudgetError {}

/// Units a budget may carry, longest first so that `KiB` is not read as `B`.
const UNITS: [(&str, f64); 7] = [
    ("KiB", 1024.0),
    ("MiB", 1024.0 * 1024.0),
    ("GiB", 1024.0 * 1024.0 * 1024.0),
    ("kB", 1000.0),
    ("KB", 1000.0),
    ("MB", 1000.0 * 1000.0),
    ("B", 1.0),
];

impl FromStr for FlashBudget {
    type Err = ParseFlashBudgetError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let error = || ParseFlashBudgetError {
            given: text.to_owned(),
        };
        let trimmed = text.trim();
        let (number, scale) = UNITS
            .iter()
            .find_map(|(unit, scale)| {
                trimmed
                    .strip_suffix(unit)
                    .map(|number| (number.trim(), *scale))
            })
            .unwrap_or((trimmed, 1.0));
        let value: f64 = number.parse().map_err(|_| error())?;
        let bytes = (value * scale).round();
        // A budget is a positive whole number of bytes that a u64 holds.
        if !(bytes >= 1.0 && bytes < u64::MAX as f64) {
            return Err(error());
        }
        Ok(FlashBudget {
            bytes: bytes as u64,
        })
    }
}

impl fmt::Display for FlashBudget {
    /// The budget in the largest binary unit that divides it, else in bytes: `512 KiB`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const MIB: u64 = 1024 * 1024;
        match self.bytes {
            bytes if bytes % MIB == 0 => write!(f, "{} MiB", bytes / MIB),
            bytes if bytes % 1024 == 0 => write!(f, "{} KiB", bytes / 1024),
            bytes => write!(f, "{bytes} B"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn budgets_read_in_every_unit_and_print_in_the_largest() {
        let read = |text: &str| text.parse::<FlashBudget>().map(|budget| budget.bytes);
        assert_eq!(read("512KiB"), Ok(524_288));
        assert_eq!(read(" 512 KiB "), Ok(524_288));
        assert_eq!(read("1.5MiB"), Ok(1_572_864));
        assert_eq!(read("2MB"), Ok(2_000_000));
        assert_eq!(read("64kB"), Ok(64_000));
        assert_eq!(read("524288"), Ok(524_288));
        assert_eq!(read("100B"), Ok(100));
        for bad in ["", "KiB", "-1KiB", "0", "nan", "1e30MiB", "512 KB flash"] {
            assert!(read(bad).is_err(), "{bad:?} read as a budget");
        }
        assert_eq!(FlashBudget::DEFAULT.to_string(), "512 KiB");
        assert_eq!(FlashBudget { bytes: 3 << 20 }.to_string(), "3 MiB");
        assert_eq!(FlashBudget { bytes: 1000 }.to_string(), "1000 B");
        assert!(FlashBudget::DEFAULT.fits(524_288) && !FlashBudget::DEFAULT.fits(524_289));
    }
}
