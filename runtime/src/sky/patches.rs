//! The Tregenza sky of 145 patches (P. R. Tregenza, "Subdivision of the sky hemisphere for
//! luminance measurements", Lighting Research and Technology 19(1), 13–14, 1987) and its
//! Reinhart subdivisions MF:n (Radiance's `reinhart.cal`, G. Ward 2009).
//!
//! Tregenza: seven rows of altitude 12° each, from the horizon, with 30, 30, 24, 24, 18, 12
//! and 6 patches, and a cap above 84° (one patch): 145. Reinhart MF:n splits every row into
//! n rows and every patch of it into n along the azimuth, with rows of height
//! `α = 90°/(7n + 0.5)` and the cap of height α/2 above them: `144 n² + 1` patches (n = 1 is
//! Tregenza, n = 2 gives 577, n = 4 2305). The order is Radiance's (`tregenza.cal`,
//! `reinhart.cal`, and so `genskyvec` and `rfluxmtx`): row by row from the horizon, each
//! row from the patch centred due north, then eastwards (clockwise seen from above), with
//! patch `i` here Radiance's bin `i + 1` (Radiance's bin 0 is the ground).
//!
//! A patch spans the altitudes `[h0, h1)` of its row and `±180°/N` of azimuth about its
//! centre for N patches in the row; its centre is at `(h0 + h1)/2` (the zenith for the
//! cap), its solid angle `2π (sin h1 − sin h0)/N` sr and its projected solid angle
//! `π (sin² h1 − sin² h0)/N` sr (what a horizontal receiver sees of it: `∫ cos Z dω`). The
//! solid angles add up to 2π sr, the projected ones to π sr.

use super::approx;
use crate::error::{Error, Result};

/// Patches per row in each Tregenza band, from the horizon.
const BANDS: [u16; 7] = [30, 30, 24, 24, 18, 12, 6];

/// The largest Reinhart subdivision supported (MF:8, 9217 patches).
pub const MAX_SUBDIVISION: u8 = 8;

/// A Tregenza or Reinhart sky subdivision.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SkyPatches {
    subdivision: u8,
}

/// One sky patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Patch {
    /// Centre direction (unit vector in the site's frame: x east, y north, z up).
    pub direction: [f32; 3],
    /// Altitudes it spans, rad: `[low, high)`.
    pub altitude: [f32; 2],
    /// Azimuth of its centre, rad clockwise from north.
    pub azimuth: f32,
    /// Azimuth it spans, rad (centred on `azimuth`; 2π for the cap).
    pub azimuth_width: f32,
    /// Solid angle, sr.
    pub solid_angle: f32,
    /// Projected solid angle `∫ cos Z dω`, sr.
    pub projected_solid_angle: f32,
}

impl SkyPatches {
    /// The Tregenza sky (MF:1), 145 patches.
    pub const TREGENZA: Self = Self { subdivision: 1 };

    /// Reinhart subdivision MF:`n`, `n` from 1 (Tregenza) to [`MAX_SUBDIVISION`].
    pub fn reinhart(n: u8) -> Result<Self> {
        if (1..=MAX_SUBDIVISION).contains(&n) {
            Ok(Self { subdivision: n })
        } else {
            Err(Error::OutOfRange {
                what: "Reinhart sky subdivision MF",
                range: "from 1 to 8",
            })
        }
    }

    /// The subdivision n of MF:n (1 for Tregenza).
    pub fn subdivision(&self) -> u8 {
        self.subdivision
    }

    /// Number of patches, `144 n² + 1`.
    pub fn count(&self) -> usize {
        let n = usize::from(self.subdivision);
        144 * n * n + 1
    }

    /// Rows below the cap, `7n`.
    fn rows(&self) -> usize {
        7 * usize::from(self.subdivision)
    }

    /// Row height α, rad.
    fn row_height(&self) -> f32 {
        core::f32::consts::FRAC_PI_2 / (7.0 * f32::from(self.subdivision) + 0.5)
    }

    /// Patches in row `r` (the cap, `r = 7n`, has one).
    fn row_len(&self, r: usize) -> usize {
        let n = usize::from(self.subdivision);
        match BANDS.get(r / n) {
            Some(&band) if r < self.rows() => n * usize::from(band),
            _ => 1,
        }
    }

    /// Patch `index` (0-based), or `None` beyond [`Self::count`].
    pub fn patch(&self, index: usize) -> Option<Patch> {
        let alpha = self.row_height();
        let mut first = 0;
        for r in 0..=self.rows() {
            let len = self.row_len(r);
            if index < first + len {
                let k = index - first;
                let cap = r == self.rows();
                let low = r as f32 * alpha;
                let high = if cap {
                    core::f32::consts::FRAC_PI_2
                } else {
                    low + alpha
                };
                let width = 2.0 * core::f32::consts::PI / len as f32;
                let azimuth = k as f32 * width;
                let centre = if cap {
                    core::f32::consts::FRAC_PI_2
                } else {
                    0.5 * (low + high)
                };
                // sin h1 − sin h0 and sin² h1 − sin² h0 as products, free of the
                // cancellation of small rows near the zenith.
                let band = 2.0 * libm::cosf(0.5 * (high + low)) * libm::sinf(0.5 * (high - low));
                let band2 = libm::sinf(high + low) * libm::sinf(high - low);
                let mut dir = geometric_direction(centre, azimuth);
                if cap {
                    dir = [0.0, 0.0, 1.0];
                }
                return Some(Patch {
                    direction: dir,
                    altitude: [low, high],
                    azimuth,
                    azimuth_width: width,
                    solid_angle: width * band,
                    projected_solid_angle: 0.5 * width * band2,
                });
            }
            first += len;
        }
        None
    }

    /// Every patch's luminance under `sky`: its relative luminance at the patch's centre times
    /// `scale` (cd/m² per unit of relative luminance, e.g. a CIE sky's zenith luminance), in
    /// the patches' order, into `out` (one slot per patch): what a
    /// [`DaylightEvaluator`](crate::DaylightEvaluator) takes. A wrong length or a `scale`
    /// that is negative or not finite is an error and writes nothing.
    ///
    /// The centres are computed on every call, as [`SkyPatches::centres`] gives them; a
    /// controller that updates its sky often computes them once and calls
    /// [`SkyPatches::luminances_at`], which gives the same values to the bit.
    pub fn luminances<S: super::RelativeSky + ?Sized>(
        &self,
        sky: &S,
        scale: f32,
        out: &mut [f32],
    ) -> Result<()> {
        check_luminances(self.count(), scale, out.len())?;
        let mut slots = out.iter_mut();
        self.for_each_centre(|dir| {
            if let Some(slot) = slots.next() {
                *slot = sky.relative_luminance(dir) * scale;
            }
        });
        Ok(())
    }

    /// Every patch's centre direction (unit vector, site frame), in the patches' order, into
    /// `centres` (one slot per patch): the patch geometry [`SkyPatches::luminances_at`] needs,
    /// computed once for a basis rather than on every sky update. In `f32` alone: within
    /// 2 × 10⁻⁷ of [`SkyPatches::patch`]'s directions (the tests' bound). A wrong length is
    /// an error and writes nothing.
    pub fn centres(&self, centres: &mut [[f32; 3]]) -> Result<()> {
        if centres.len() != self.count() {
            return Err(Error::LengthMismatch {
                what: "sky patch centres",
                expected: self.count(),
                found: centres.len(),
            });
        }
        let mut slots = centres.iter_mut();
        self.for_each_centre(|dir| {
            if let Some(slot) = slots.next() {
                *slot = dir;
            }
        });
        Ok(())
    }

    /// [`SkyPatches::luminances`] from centres computed once ([`SkyPatches::centres`]): per
    /// patch, one relative luminance and a product. `centres` and `out` must both have one
    /// slot per patch, and `scale` be finite and not negative, else an error and nothing
    /// written.
    pub fn luminances_at<S: super::RelativeSky + ?Sized>(
        &self,
        centres: &[[f32; 3]],
        sky: &S,
        scale: f32,
        out: &mut [f32],
    ) -> Result<()> {
        if centres.len() != self.count() {
            return Err(Error::LengthMismatch {
                what: "sky patch centres",
                expected: self.count(),
                found: centres.len(),
            });
        }
        check_luminances(self.count(), scale, out.len())?;
        for (slot, &dir) in out.iter_mut().zip(centres) {
            *slot = sky.relative_luminance(dir) * scale;
        }
        Ok(())
    }

    /// Calls `visit` with every patch's centre direction in the patches' order, row by row:
    /// one sine and cosine of the row's altitude and one of each patch's azimuth.
    fn for_each_centre(&self, mut visit: impl FnMut([f32; 3])) {
        let alpha = self.row_height();
        for r in 0..self.rows() {
            let len = self.row_len(r);
            let (sin_alt, cos_alt) = approx::sin_cos((r as f32 + 0.5) * alpha);
            let width = 2.0 * core::f32::consts::PI / len as f32;
            for k in 0..len {
                let (sin_az, cos_az) = approx::sin_cos(k as f32 * width);
                visit([sin_az * cos_alt, cos_az * cos_alt, sin_alt]);
            }
        }
        visit([0.0, 0.0, 1.0]);
    }

    /// The patch that direction `dir` (a unit vector, z up, in the site's frame) falls in;
    /// `None` below the horizon (`dir[2] < 0`) or for a direction that is not finite.
    pub fn index(&self, dir: [f32; 3]) -> Option<usize> {
        if !(dir.iter().all(|x| x.is_finite()) && dir[2] >= 0.0) {
            return None;
        }
        // `libm`'s functions: the host bins directions with this while it builds a basis.
        let altitude = libm::asinf(dir[2].clamp(-1.0, 1.0));
        let row = ((altitude / self.row_height()) as usize).min(self.rows());
        let first: usize = (0..row).map(|r| self.row_len(r)).sum();
        let len = self.row_len(row);
        let tau = 2.0 * core::f32::consts::PI;
        let mut azimuth = libm::atan2f(dir[0], dir[1]);
        if azimuth < 0.0 {
            azimuth += tau;
        }
        let width = tau / len as f32;
        let k = ((azimuth + 0.5 * width) / width) as usize % len;
        Some(first + k)
    }
}

/// `len` slots of luminance wanted and `scale` usable, else the error
/// [`SkyPatches::luminances`] documents.
fn check_luminances(count: usize, scale: f32, len: usize) -> Result<()> {
    if len != count {
        return Err(Error::LengthMismatch {
            what: "sky luminances",
            expected: count,
            found: len,
        });
    }
    if !(scale.is_finite() && scale >= 0.0) {
        return Err(Error::OutOfRange {
            what: "sky luminance scale (cd/m²)",
            range: "finite and not negative",
        });
    }
    Ok(())
}

/// The unit vector of altitude and azimuth (rad) as [`super::direction`] has it, with
/// `libm`'s correctly rounded sine and cosine: the patches' geometry goes into the bytes the
/// host writes into a basis, which should not move with the controller's approximations.
fn geometric_direction(altitude: f32, azimuth: f32) -> [f32; 3] {
    let (s, c) = (libm::sinf(altitude), libm::cosf(altitude));
    [libm::sinf(azimuth) * c, libm::cosf(azimuth) * c, s]
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    // The f64 references use std's float functions.
    extern crate std;
    use super::super::direction;
    use super::*;

    #[test]
    fn counts() {
        assert_eq!(SkyPatches::TREGENZA.count(), 145);
        assert_eq!(SkyPatches::reinhart(2).unwrap().count(), 577);
        assert_eq!(SkyPatches::reinhart(4).unwrap().count(), 2305);
        assert!(SkyPatches::reinhart(0).is_err());
        assert!(SkyPatches::reinhart(MAX_SUBDIVISION + 1).is_err());
        assert!(SkyPatches::TREGENZA.patch(145).is_none());
    }

    /// Tregenza's rows (the 1987 paper): centres at 6°, 18°, …, 78° of altitude with 30, 30,
    /// 24, 24, 18, 12, 6 patches, patch 0 due north, the cap at the zenith.
    #[test]
    fn tregenza_layout() {
        let sky = SkyPatches::TREGENZA;
        let mut i = 0;
        for (row, &n) in BANDS.iter().enumerate() {
            for k in 0..usize::from(n) {
                let p = sky.patch(i).unwrap();
                let alt = 0.5 * (p.altitude[0] + p.altitude[1]);
                assert!((alt.to_degrees() - (6.0 + 12.0 * row as f32)).abs() < 1.0e-4);
                let az = k as f32 * 360.0 / f32::from(n);
                assert!((p.azimuth.to_degrees() - az).abs() < 1.0e-3, "patch {i}");
                i += 1;
            }
        }
        assert_eq!(i, 144);
        let cap = sky.patch(144).unwrap();
        assert_eq!(cap.direction, [0.0, 0.0, 1.0]);
        assert!((cap.altitude[0].to_degrees() - 84.0).abs() < 1.0e-4);
    }

    /// Solid angles add up to 2π sr and projected solid angles to π sr (the hemisphere and
    /// its cosine-weighted measure), for MF:1 to MF:8; each patch's against the f64 closed
    /// form. Tolerance 2 × 10⁻⁶ relative (f32 sums of up to 9217 terms, in f64 here).
    #[test]
    fn solid_angles_add_up() {
        for n in 1..=MAX_SUBDIVISION {
            let sky = SkyPatches::reinhart(n).unwrap();
            let (mut omega, mut projected) = (0.0f64, 0.0f64);
            for i in 0..sky.count() {
                let p = sky.patch(i).unwrap();
                let (h0, h1) = (f64::from(p.altitude[0]), f64::from(p.altitude[1]));
                let w = f64::from(p.azimuth_width);
                let exact = w * (h1.sin() - h0.sin());
                assert!((f64::from(p.solid_angle) - exact).abs() <= 1.0e-5 * exact);
                omega += f64::from(p.solid_angle);
                projected += f64::from(p.projected_solid_angle);
            }
            let tau = 2.0 * std::f64::consts::PI;
            assert!((omega - tau).abs() <= 2.0e-6 * tau, "MF:{n}: {omega}");
            assert!(
                (projected - tau / 2.0).abs() <= 2.0e-6 * tau,
                "MF:{n}: {projected}"
            );
        }
    }

    /// The centres [`SkyPatches::centres`] computes in `f32` alone against the geometric
    /// ones of [`SkyPatches::patch`], within 2 × 10⁻⁷ in every component, for MF:1 to MF:8;
    /// the luminances from them, by either call, the same to the bit; wrong lengths refused.
    #[test]
    fn centres_match_the_geometry() {
        for n in 1..=MAX_SUBDIVISION {
            let sky = SkyPatches::reinhart(n).unwrap();
            let mut centres = std::vec![[0.0f32; 3]; sky.count()];
            sky.centres(&mut centres).unwrap();
            for (i, c) in centres.iter().enumerate() {
                let exact = sky.patch(i).unwrap().direction;
                for k in 0..3 {
                    assert!((c[k] - exact[k]).abs() <= 2.0e-7, "MF:{n} patch {i}");
                }
            }
            let cie =
                super::super::cie::CieSky::standard(12, super::super::direction(0.6, 2.0)).unwrap();
            let (mut a, mut b) = (
                std::vec![0.0f32; sky.count()],
                std::vec![0.0f32; sky.count()],
            );
            sky.luminances(&cie, 7000.0, &mut a).unwrap();
            sky.luminances_at(&centres, &cie, 7000.0, &mut b).unwrap();
            assert_eq!(a, b);
            assert!(sky.luminances_at(&centres[1..], &cie, 1.0, &mut b).is_err());
            assert!(sky.luminances_at(&centres, &cie, 1.0, &mut b[1..]).is_err());
            assert!(sky.luminances_at(&centres, &cie, -1.0, &mut b).is_err());
            assert!(sky.centres(&mut centres[1..]).is_err());
        }
    }

    /// Every patch's centre maps back to its own index; so do points just inside its
    /// corners; below the horizon is no patch.
    #[test]
    fn directions_map_back_to_their_patch() {
        for n in [1u8, 2, 4, 8] {
            let sky = SkyPatches::reinhart(n).unwrap();
            for i in 0..sky.count() {
                let p = sky.patch(i).unwrap();
                assert_eq!(sky.index(p.direction), Some(i), "MF:{n} patch {i}");
                if i + 1 < sky.count() {
                    for (fa, fz) in [(0.49f32, 0.02f32), (-0.49, 0.98), (0.3, 0.5)] {
                        let alt = p.altitude[0] + fz * (p.altitude[1] - p.altitude[0]);
                        let az = p.azimuth + fa * p.azimuth_width;
                        let d = direction(alt, az);
                        assert_eq!(sky.index(d), Some(i), "MF:{n} patch {i} ({fa}, {fz})");
                    }
                }
            }
            assert_eq!(sky.index([0.0, 1.0, -0.01]), None);
            assert_eq!(sky.index([f32::NAN, 0.0, 1.0]), None);
            assert_eq!(sky.index([0.0, 0.0, 1.0]), Some(sky.count() - 1));
        }
    }
}
