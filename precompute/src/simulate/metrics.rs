//! Climate-based daylight metrics on the calculation grids, counted hour by hour over the
//! analysis hours of IES LM-83-12 (08:00 to 18:00 local standard time, every day of the
//! year): daylight autonomy at 300 lux and spatial daylight autonomy sDA300/50 %, annual
//! sunlight exposure ASE1000,250 from the direct sun alone, and useful daylight
//! illuminance's four bands.

use eigenrad_runtime::sky::direct::DirectSun;
use eigenrad_runtime::{Basis, DaylightEvaluator};
use serde::Serialize;

use super::Hour;
use crate::error::Result;

/// Daylight autonomy's threshold, lux (sDA300/50 %, IES LM-83-12).
pub const DA_LUX: f32 = 300.0;
/// The share of the analysis hours a point must reach [`DA_LUX`] in for sDA (50 %).
pub const SDA_SHARE: f64 = 0.5;
/// Annual sunlight exposure's threshold of direct sunlight, lux (ASE1000,250).
pub const ASE_LUX: f32 = 1000.0;
/// The hours above [`ASE_LUX`] a point must exceed for ASE (250).
pub const ASE_HOURS: u32 = 250;
/// Useful daylight illuminance's band limits, lux: fell short below 100, supplementary
/// from 100 to 300, autonomous from 300 to 3000, exceeded above 3000 (A. Nabil and J.
/// Mardaljevic, "Useful daylight illuminances: a replacement for daylight factors", Energy
/// and Buildings 38(7), 2006, with the 300 lux split of Mardaljevic et al. 2012).
pub const UDI_LIMITS: [f32; 3] = [100.0, 300.0, 3000.0];

/// One zone's grid counted over the analysis hours.
struct ZoneCounts {
    zone: usize,
    name: String,
    /// The zone's first point among every grid point of the basis.
    first: usize,
    /// Per point: hours at or above [`DA_LUX`].
    da: Vec<u32>,
    /// Per point: hours in each of the four UDI bands.
    udi: Vec<[u32; 4]>,
    /// Per point: hours with direct sunlight above [`ASE_LUX`].
    ase: Vec<u32>,
    /// Per point: the sum of its hourly daylight, lux·h.
    sum: Vec<f64>,
}

/// The counts of every zone with a grid.
pub(super) struct GridCounts {
    zones: Vec<ZoneCounts>,
    hours: u32,
    direct: bool,
}

/// A zone's daylight metrics over the year.
#[derive(Clone, Debug, Serialize)]
pub struct GridMetrics {
    /// The zone.
    pub zone: String,
    /// Its grid's points.
    pub points: usize,
    /// The analysis hours counted (08:00–18:00 local standard time, every day).
    pub hours: u32,
    /// Mean over the points of daylight autonomy: the share of the hours at or above
    /// 300 lux.
    pub da300_mean: f64,
    /// sDA300/50 %: the share of the points at or above 300 lux for at least half the hours.
    pub sda_300_50: f64,
    /// ASE1000,250: the share of the points with direct sunlight above 1000 lux for more
    /// than 250 hours; `None` when the basis stores no direct sun geometry.
    pub ase_1000_250: Option<f64>,
    /// Mean over the points of the share of the hours in each UDI band: below 100, 100 to
    /// 300, 300 to 3000, above 3000 lux.
    pub udi: [f64; 4],
    /// Mean daylight illuminance over the points and hours, lux.
    pub mean_lux: f64,
    /// Per point, daylight autonomy (share of the hours at or above 300 lux).
    pub point_da300: Vec<f64>,
    /// Per point, hours of direct sunlight above 1000 lux (empty without direct sun
    /// geometry).
    pub point_ase_hours: Vec<u32>,
}

impl GridCounts {
    /// Empty counts for every zone of `basis` with a grid; `direct`: the basis stores the
    /// direct sun's geometry (ASE counted).
    pub(super) fn new(basis: &Basis<'_>, direct: bool) -> Result<Self> {
        let mut zones = Vec::new();
        let mut first = 0;
        for z in 0..basis.zone_count() {
            let points = basis.grid_points(z)?;
            if points > 0 {
                zones.push(ZoneCounts {
                    zone: z,
                    name: basis.zone_name(z)?.to_owned(),
                    first,
                    da: vec![0; points],
                    udi: vec![[0; 4]; points],
                    ase: vec![0; points],
                    sum: vec![0.0; points],
                });
            }
            first += points;
        }
        Ok(GridCounts {
            zones,
            hours: 0,
            direct,
        })
    }

    /// Counts `hour` when it is an analysis hour, the evaluator holding its sky.
    pub(super) fn add<const S: usize, const O: usize, const E: usize>(
        &mut self,
        day: &DaylightEvaluator<'_, S, O, E>,
        direct: Option<&DirectSun<'_, '_>>,
        hour: &Hour,
    ) -> Result<()> {
        if !hour.analysis {
            return Ok(());
        }
        self.hours += 1;
        let sun = match (direct, hour.sky.sun) {
            (Some(d), Some(s)) if s.direct_normal > 0.0 => {
                Some((d, d.room_direction(s.direction), s.direct_normal))
            }
            _ => None,
        };
        for zone in &mut self.zones {
            for p in 0..zone.da.len() {
                let e = day.grid_point_illuminance(zone.zone, p)?;
                zone.sum[p] += f64::from(e);
                if e >= DA_LUX {
                    zone.da[p] += 1;
                }
                let band = UDI_LIMITS.iter().filter(|&&limit| e >= limit).count();
                zone.udi[p][band] += 1;
                if let Some((d, room, en)) = sun {
                    if en * d.at_grid_point(zone.first + p, room) > ASE_LUX {
                        zone.ase[p] += 1;
                    }
                }
            }
        }
        Ok(())
    }

    /// The metrics of every zone.
    pub(super) fn metrics(&self) -> Vec<GridMetrics> {
        let hours = f64::from(self.hours.max(1));
        self.zones
            .iter()
            .map(|z| {
                let n = z.da.len() as f64;
                let point_da300: Vec<f64> = z.da.iter().map(|&d| f64::from(d) / hours).collect();
                let mut udi = [0.0; 4];
                for counts in &z.udi {
                    for (u, &c) in udi.iter_mut().zip(counts) {
                        *u += f64::from(c) / hours / n;
                    }
                }
                GridMetrics {
                    zone: z.name.clone(),
                    points: z.da.len(),
                    hours: self.hours,
                    da300_mean: point_da300.iter().sum::<f64>() / n,
                    sda_300_50: point_da300.iter().filter(|&&d| d >= SDA_SHARE).count() as f64 / n,
                    ase_1000_250: self
                        .direct
                        .then(|| z.ase.iter().filter(|&&h| h > ASE_HOURS).count() as f64 / n),
                    udi,
                    mean_lux: z.sum.iter().sum::<f64>() / hours / n,
                    point_da300,
                    point_ase_hours: if self.direct {
                        z.ase.clone()
                    } else {
                        Vec::new()
                    },
                }
            })
            .collect()
    }
}
