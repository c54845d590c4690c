//! One opened basis and the runtime's evaluators over it: the channels' electric light, the
//! daylight of a sky state when the basis carries daylight, and the least-power level solver.
//! Every number the page shows comes from here, and every one of them from the runtime.

use eigenrad_runtime::target::{LevelProblem, Output};
use eigenrad_runtime::{dali, Basis, ChannelEvaluator, DaylightEvaluator, Error, Figures};

use crate::sun::{sky_state, Moment, SkyError, SkyInput, SkyState};

/// Channels the page drives (the solver controls at most 16 of them).
pub const CHANNELS: usize = 64;
/// Sky patches and outputs of the daylight evaluator: Reinhart MF:8 (9217 patches), 256
/// sensors and zones.
pub const SKY: usize = 9217;
pub const OUTPUTS: usize = 256;
/// Modes of daylight patch exitance: as many as `eigenrad build --tolerance` may keep.
pub const MODES: usize = 512;
/// The daylight evaluator's patch-exitance state: the modes' amplitudes and the coefficients
/// of the sky's first reflection (format 7), whose rank is at most the sky's patches plus the
/// exterior. A basis that needs more (more than [`MODES`] modes) is refused when opened with
/// the runtime's capacity error, which the page shows.
pub const EXITANCE: usize = MODES + SKY + 1;

pub type Channels = ChannelEvaluator<'static, 1, CHANNELS>;
pub type Daylight = DaylightEvaluator<'static, SKY, OUTPUTS, EXITANCE>;

/// An opened basis and its evaluators.
pub struct Session {
    pub basis: Basis<'static>,
    pub channels: Channels,
    /// Present when the basis carries daylight.
    pub daylight: Option<Box<Daylight>>,
    /// The sky state set last (none: dark outside).
    pub sky: Option<SkyState>,
}

/// A reading of the page: electric, daylight, and their sum, lux.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Split {
    pub total: f64,
    pub electric: f64,
    pub daylight: f64,
}

impl Split {
    /// The sum as `eigenrad eval` forms it: the two `f32` parts added in `f64`.
    fn of(electric: f32, daylight: f32) -> Split {
        Split {
            total: f64::from(electric) + f64::from(daylight),
            electric: f64::from(electric),
            daylight: f64::from(daylight),
        }
    }
}

/// The grid of a zone: points `(x, y, z)` and the layout of its first piece.
pub struct Grid {
    pub points: Vec<[f64; 3]>,
    pub counts: [usize; 2],
    pub cell: [f64; 2],
    pub pieces: usize,
}

impl Session {
    /// Opens `bytes` (kept for the page's lifetime), every channel at level 1, dark outside:
    /// one band only, the page shows lux.
    pub fn open(bytes: &'static [u8]) -> Result<Session, Error> {
        let basis = Basis::from_bytes(bytes)?;
        if basis.bands() != 1 {
            return Err(Error::Capacity {
                what: "bands",
                needed: basis.bands(),
                capacity: 1,
            });
        }
        // Every channel as built (level 1), as `eigenrad eval` starts.
        let mut channels = ChannelEvaluator::new(basis)?;
        channels.set_channel_levels(&vec![1.0; basis.channel_count()])?;
        let daylight = if basis.has_daylight() {
            Some(Box::new(DaylightEvaluator::new(basis)?))
        } else {
            None
        };
        Ok(Session {
            basis,
            channels,
            daylight,
            sky: None,
        })
    }

    pub fn set_level(&mut self, channel: usize, level: f32) -> Result<(), Error> {
        self.channels.set_channel_level(channel, level)
    }

    pub fn set_arc(&mut self, channel: usize, arc: u8) -> Result<(), Error> {
        self.channels.set_channel_arc_power(channel, arc)
    }

    /// The lowest DALI arc power level that gives at least `channel`'s level, or none above
    /// level 1 (the arc scale ends there).
    pub fn arc(&self, channel: usize) -> Result<Option<u8>, Error> {
        let level = self.channels.channel_level(channel)?;
        Ok(dali::level_to_arc_power(level).ok())
    }

    /// Sets the sky of `input` at `moment` (the site's standard time).
    pub fn set_sky(&mut self, moment: Moment, input: SkyInput) -> Result<&SkyState, SkyError> {
        let (Some(daylight), Some(site), Some(patches)) = (
            self.daylight.as_mut(),
            self.basis.site(),
            self.basis.sky_patches(),
        ) else {
            return Err(SkyError::Runtime("daylight", Error::NoDaylight));
        };
        let state = sky_state(&site, &patches, moment, input)?;
        daylight
            .set_sky(&state.luminance, state.global_horizontal as f32, state.sun)
            .map_err(|e| SkyError::Runtime("sky", e))?;
        Ok(self.sky.insert(state))
    }

    /// Dark outside: no sky, no sun.
    pub fn clear_sky(&mut self) -> Result<(), Error> {
        if let Some(d) = self.daylight.as_mut() {
            let dark = vec![0.0; d.basis().sky_patches().map_or(0, |p| p.count())];
            d.set_sky(&dark, 0.0, None)?;
        }
        self.sky = None;
        Ok(())
    }

    fn daylight_on(&self) -> Option<&Daylight> {
        self.sky.as_ref().and(self.daylight.as_deref())
    }

    pub fn sensor(&self, s: usize) -> Result<Split, Error> {
        let [e] = self.channels.sensor_irradiance(s)?;
        let d = match self.daylight_on() {
            Some(d) => d.sensor_illuminance(s)?,
            None => 0.0,
        };
        Ok(Split::of(e, d))
    }

    pub fn zone(&self, z: usize) -> Result<Split, Error> {
        let [e] = self.channels.zone_irradiance(z)?;
        let d = match self.daylight_on() {
            Some(d) => d.zone_illuminance(z)?,
            None => 0.0,
        };
        Ok(Split::of(e, d))
    }

    /// Every grid point of zone `z`, daylight and electric light together, lux.
    pub fn grid_values(&self, z: usize) -> Result<Vec<f64>, Error> {
        let n = self.basis.grid_points(z)?;
        let mut out = Vec::with_capacity(n);
        for i in 0..n {
            let [e] = self.channels.grid_point_irradiance(z, i)?;
            let d = match self.daylight_on() {
                Some(d) => d.grid_point_illuminance(z, i)?,
                None => 0.0,
            };
            out.push(Split::of(e, d).total);
        }
        Ok(out)
    }

    /// `E_avg`, `E_min`, `E_max`, `U_o` of zone `z`'s grid, daylight and electric light
    /// together, point by point.
    pub fn figures(&self, z: usize) -> Result<Figures, Error> {
        match self.daylight_on() {
            Some(d) => d.zone_figures_with(z, &self.channels),
            None => {
                let [f] = self.channels.zone_figures(z)?;
                Ok(f)
            }
        }
    }

    /// The grid of zone `z`: its points and its first piece's lattice.
    pub fn grid(&self, z: usize) -> Result<Grid, Error> {
        let n = self.basis.grid_points(z)?;
        let mut points = Vec::with_capacity(n);
        for i in 0..n {
            points.push(self.basis.grid_point(z, i)?.map(f64::from));
        }
        let pieces = self.basis.grid_piece_count(z)?;
        let first = self.basis.grid_piece(z, 0)?;
        Ok(Grid {
            points,
            counts: first.counts,
            cell: first.cell.map(f64::from),
            pieces,
        })
    }

    /// Patch `p`'s exitance, lux: the channels' (exact) plus the daylight's through the modes.
    pub fn patch_exitance(&self, p: usize) -> Result<Split, Error> {
        let [e] = self.channels.exitance(p)?;
        let d = match self.daylight_on() {
            Some(d) => d.exitance(p)?,
            None => 0.0,
        };
        Ok(Split::of(e, d))
    }

    /// The least-power levels of `controlled` channels (`weights`, W at level 1) meeting
    /// `bounds` (`(output, lower, upper)`, lux); the other channels and the daylight count as
    /// ambient. Sets the levels found on the channels, also when a bound is unmet (the
    /// levels closest to meeting them); returns the power, W, and the runtime's verdict.
    pub fn solve(
        &mut self,
        controlled: &[usize],
        weights: &[f32],
        bounds: &[(Output, f32, f32)],
    ) -> Result<(f32, Result<(), Error>), Error> {
        let mut problem = LevelProblem::new(weights)?;
        for &(output, lower, upper) in bounds {
            let daylight = match (self.daylight_on(), output) {
                (Some(d), Output::Sensor(s)) => d.sensor_illuminance(s)?,
                (Some(d), Output::Zone(z)) => d.zone_illuminance(z)?,
                (None, _) => 0.0,
            };
            let ambient = self.channels.reading_without(output, controlled)? + daylight;
            problem.add_output_bound(&self.basis, controlled, output, ambient, lower, upper)?;
        }
        let mut levels = vec![0.0f32; controlled.len()];
        let verdict = problem.solve(&mut levels);
        if let Err(e @ Error::LengthMismatch { .. }) = verdict {
            return Err(e);
        }
        for (&c, &l) in controlled.iter().zip(&levels) {
            self.channels.set_channel_level(c, l)?;
        }
        let power = problem.power(&levels)?;
        Ok((power, verdict.map(|_| ())))
    }
}

/// The runtime's hand-built test bases.
#[cfg(test)]
#[path = "../../../runtime/tests/common/mod.rs"]
mod common;

#[cfg(test)]
mod tests {
    use super::*;

    /// A basis with a first reflection (format 7) opens with its patch exitance, its state
    /// (modes plus the sky's rank) within [`EXITANCE`]; an evaluator with less room than that
    /// state is refused with the capacity error naming it, not truncated.
    #[test]
    fn daylight_exitance_fits_or_is_refused() {
        let bytes = common::tiny_daylight_reflection().to_bytes().unwrap();
        let session = Session::open(Vec::leak(bytes)).unwrap();
        let basis = session.basis;
        let state = basis.daylight_exitance_state();
        assert_eq!(state, basis.mode_count() + 2, "1 mode and rank 2");
        assert!(state <= EXITANCE);
        let daylight = session.daylight.as_ref().expect("daylight");
        assert!(daylight.exitance(0).is_ok());
        assert_eq!(
            DaylightEvaluator::<SKY, OUTPUTS, 2>::new(basis).err(),
            Some(Error::Capacity {
                what: "modes and first reflection",
                needed: state,
                capacity: 2,
            })
        );
    }
}
