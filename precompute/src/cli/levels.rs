//! Channel levels as the command line gives them: relative levels (`--level NAME=VALUE`) and
//! DALI arc power levels (`--arc NAME=ARC`), checked against the channels' names; what
//! `solve`, `eval`, `render` and the tests share.

use serde::Serialize;

use crate::error::{Error, Result};

/// A channel level as applied.
#[derive(Clone, Debug, Serialize)]
pub struct Level {
    /// Channel name.
    pub name: String,
    /// Relative level (1 = as built).
    pub level: f64,
    /// The DALI arc power level it was given as (`--arc`), if it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub arc: Option<u8>,
}

/// Channel levels as given on the command line: relative levels (`--level NAME=VALUE`) and
/// DALI arc power levels (`--arc NAME=ARC`). Channels named in neither stay at 1.
#[derive(Clone, Debug, Default)]
pub struct LevelArgs {
    /// `NAME=VALUE`, the relative level (1 = as built), 0 to [`eigenrad_runtime::MAX_LEVEL`].
    pub levels: Vec<String>,
    /// `NAME=ARC`, a DALI arc power level 0..=254 (IEC 62386-102), turned into a relative
    /// level by [`eigenrad_runtime::dali::arc_power_to_level`], as the firmware does.
    pub arcs: Vec<String>,
}

/// The channel named in `argument` (`NAME=...`) and the text after `=`.
fn split_argument<'a>(
    flag: &'static str,
    argument: &'a str,
    channels: &[String],
) -> Result<(usize, &'a str)> {
    let bad = |reason: String| Error::Level {
        flag,
        argument: argument.to_owned(),
        reason,
    };
    let expected = if flag == "--arc" {
        "expected NAME=ARC"
    } else {
        "expected NAME=VALUE"
    };
    let (name, value) = argument
        .split_once('=')
        .ok_or_else(|| bad(expected.into()))?;
    let index = channels.iter().position(|c| c == name).ok_or_else(|| {
        bad(format!(
            "no channel named `{name}` (channels: {})",
            channels.join(", ")
        ))
    })?;
    Ok((index, value))
}

/// Parses `--level NAME=VALUE` and `--arc NAME=ARC` arguments against the channel names;
/// unnamed channels stay at 1. A channel given by both `--level` and `--arc` is an error
/// naming it; given twice by the same flag, the last value counts.
pub fn parse_levels(arguments: &LevelArgs, channels: &[String]) -> Result<Vec<f64>> {
    let mut levels = vec![1.0; channels.len()];
    let mut by_level = vec![false; channels.len()];
    for argument in &arguments.levels {
        let (index, value) = split_argument("--level", argument, channels)?;
        let bad = |reason: String| Error::Level {
            flag: "--level",
            argument: argument.clone(),
            reason,
        };
        let value: f64 = value
            .trim()
            .parse()
            .map_err(|_| bad(format!("`{value}` is not a number")))?;
        if !value.is_finite() || value < 0.0 || value > f64::from(eigenrad_runtime::MAX_LEVEL) {
            return Err(bad(format!(
                "level must be between 0 and {}",
                eigenrad_runtime::MAX_LEVEL
            )));
        }
        levels[index] = value;
        by_level[index] = true;
    }
    for argument in &arguments.arcs {
        let (index, value) = split_argument("--arc", argument, channels)?;
        let bad = |reason: String| Error::Level {
            flag: "--arc",
            argument: argument.clone(),
            reason,
        };
        if by_level[index] {
            return Err(bad(format!(
                "channel `{}` is also given by --level; give each channel one way",
                channels[index]
            )));
        }
        let arc: u8 = match value.trim().parse::<u32>() {
            Ok(255) => {
                return Err(bad(
                    "255 is DALI's MASK (\"no change\"), not a light level; arc power levels are 0 (off) to 254 (100 %)".into(),
                ))
            }
            Ok(n) if n <= 254 => n as u8,
            _ => {
                return Err(bad(format!(
                    "`{value}` is not a DALI arc power level (a whole number 0 to 254)"
                )))
            }
        };
        let level =
            eigenrad_runtime::dali::arc_power_to_level(arc).map_err(|e| bad(e.to_string()))?;
        levels[index] = f64::from(level);
    }
    Ok(levels)
}

/// Each channel's name with the level applied to it, and the arc level it was given as.
/// `args` are the arguments [`parse_levels`] accepted.
pub(super) fn applied(names: &[String], levels: &[f64], args: &LevelArgs) -> Vec<Level> {
    names
        .iter()
        .zip(levels)
        .map(|(name, &level)| Level {
            name: name.clone(),
            level,
            // The last `--arc` naming the channel, as in `parse_levels`.
            arc: args.arcs.iter().rev().find_map(|a| {
                let (n, v) = a.split_once('=')?;
                if n == name {
                    v.trim().parse().ok()
                } else {
                    None
                }
            }),
        })
        .collect()
}
