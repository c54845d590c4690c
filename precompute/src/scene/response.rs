//! A photosensor's angular response: its relative sensitivity `S(θ)` over the polar angle `θ`
//! from its normal, so that it reads `∫ L(ω) S(θ) dω` over its front hemisphere (L the
//! luminance, lux from cd/m²). `S = cos θ` reads illuminance; a real ceiling photocell is
//! shielded and sees less of the walls than a cosine does.
//!
//! A table is given inline in the scene, read from a file in the layout of Radiance's
//! `rsensor` (its man page, `rsensor.1`: a header row `degrees` followed by azimuth angles,
//! then one row per polar angle in degrees with one relative sensitivity per azimuth), or made
//! from the shielded preset ([`Response::shielded`]). Between rows `S` is interpolated
//! linearly in `θ`; past the last row it is zero, as in `rsensor`. Sensitivity that varies
//! with azimuth is refused: every row's columns must agree.

use std::fmt;
use std::path::{Path, PathBuf};

/// Polar width of the rings the view of the patches is cut into, radians (1°): within a ring
/// the sensitivity relative to a cosine is taken as constant ([`Response::rings`]).
const RING_WIDTH: f64 = std::f64::consts::PI / 180.0;

/// Gauss–Legendre nodes and weights on [0, 1], order 4, for a ring's mean sensitivity (exact
/// for the piecewise-linear table times `sin θ` to well below the table's own precision).
const GAUSS_4: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_9),
    (0.330_009_478_207_571_9, 0.326_072_577_431_273_1),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_1),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_9),
];

/// A photosensor's relative sensitivity over the polar angle from its normal.
#[derive(Clone, Debug, PartialEq)]
pub struct Response {
    /// Polar angles of the rows, radians: from 0, strictly increasing, at most π/2.
    polar: Vec<f64>,
    /// Relative sensitivity at each row (dimensionless, ≥ 0, the last one positive).
    sensitivity: Vec<f64>,
}

/// Why a sensitivity table is refused; [`TableError`] adds the file and line.
#[derive(Clone, Debug, PartialEq)]
pub struct TableError {
    /// 1-based line of the file (or index of the row in the scene's list), when one is at
    /// fault.
    pub line: Option<usize>,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "line {line}: {}", self.message),
            None => f.write_str(&self.message),
        }
    }
}

fn refuse(line: Option<usize>, message: impl Into<String>) -> TableError {
    TableError {
        line,
        message: message.into(),
    }
}

impl Response {
    /// A table from rows of (polar angle in degrees, relative sensitivity); `lines` gives each
    /// row's line for messages (`None`: rows of an inline list, named by their index).
    pub fn from_rows(rows: &[(f64, f64)], lines: Option<&[usize]>) -> Result<Response, TableError> {
        let line = |k: usize| lines.and_then(|l| l.get(k).copied());
        let row = |k: usize| match lines {
            Some(_) => String::new(),
            None => format!("row {}: ", k + 1),
        };
        let Some(&(first, _)) = rows.first() else {
            return Err(refuse(None, "the table has no rows"));
        };
        if first != 0.0 {
            return Err(refuse(
                line(0),
                format!(
                    "{}the first polar angle must be 0 degrees, found {first}",
                    row(0)
                ),
            ));
        }
        for (k, &(theta, s)) in rows.iter().enumerate() {
            if !theta.is_finite() || !s.is_finite() {
                return Err(refuse(
                    line(k),
                    format!(
                        "{}polar angle {theta} and sensitivity {s} must be finite",
                        row(k)
                    ),
                ));
            }
            if s < 0.0 {
                return Err(refuse(
                    line(k),
                    format!("{}sensitivity must not be negative, found {s}", row(k)),
                ));
            }
            if k > 0 && theta <= rows[k - 1].0 {
                return Err(refuse(
                    line(k),
                    format!(
                        "{}polar angles must increase, found {theta} after {}",
                        row(k),
                        rows[k - 1].0
                    ),
                ));
            }
            if theta > 90.0 && s > 0.0 {
                return Err(refuse(
                    line(k),
                    format!(
                        "{}sensitivity {s} at polar angle {theta} degrees: a sensor sees only \
                         its front hemisphere (at most 90 degrees)",
                        row(k)
                    ),
                ));
            }
        }
        // Trailing zero rows say nothing: the sensitivity past the last row is zero anyway.
        let Some(last) = rows.iter().rposition(|&(_, s)| s > 0.0) else {
            return Err(refuse(
                None,
                "no positive sensitivity: the sensor would read nothing",
            ));
        };
        // The zero row after it, if any, brings the interpolation down to zero.
        let end = match rows.get(last + 1) {
            Some(&(theta, _)) if theta <= 90.0 => last + 1,
            _ => last,
        };
        let kept = &rows[..=end];
        Ok(Response {
            polar: kept.iter().map(|r| r.0.to_radians()).collect(),
            sensitivity: kept.iter().map(|r| r.1).collect(),
        })
    }

    /// A cosine-corrected detector at the bottom of a cylindrical shield whose wall hides it
    /// entirely beyond `cutoff` (radians, in (0, π/2)): `S(θ) = cos θ · A(θ)`, with `A` the
    /// lit fraction of the detector, the overlap of two discs of radius `a` offset by
    /// `h tan θ` (the shield's opening projected onto the detector), `h = 2a / tan(cutoff)`:
    /// `A = (2/π)(acos u − u √(1 − u²))`, `u = tan θ / tan(cutoff)`. Tabulated at 1° steps.
    /// The geometry is the whole model: no measured photocell is claimed.
    pub fn shielded(cutoff: f64) -> Response {
        let degrees = cutoff.to_degrees();
        let mut rows: Vec<(f64, f64)> = (0..)
            .map(f64::from)
            .take_while(|&d| d < degrees)
            .map(|d| (d, shielded_sensitivity(d.to_radians(), cutoff)))
            .collect();
        rows.push((degrees, 0.0));
        Response {
            polar: rows.iter().map(|r| r.0.to_radians()).collect(),
            sensitivity: rows.iter().map(|r| r.1).collect(),
        }
    }

    /// Relative sensitivity (dimensionless) to light arriving at cosine `cos` to the normal:
    /// the table interpolated linearly in the polar angle, zero past its last row and behind
    /// the sensor. NaN gives zero.
    pub fn at_cos(&self, cos: f64) -> f64 {
        if cos.is_nan() || cos <= 0.0 {
            return 0.0;
        }
        self.at_angle(cos.min(1.0).acos())
    }

    /// Relative sensitivity at polar angle `theta`, radians.
    pub fn at_angle(&self, theta: f64) -> f64 {
        let k = self.polar.partition_point(|&p| p <= theta);
        if k == 0 {
            return 0.0;
        }
        let (p0, s0) = (self.polar[k - 1], self.sensitivity[k - 1]);
        match (self.polar.get(k), self.sensitivity.get(k)) {
            (Some(&p1), Some(&s1)) => s0 + (s1 - s0) * (theta - p0) / (p1 - p0),
            // Past the last row only the row itself counts (zero beyond it).
            _ if theta == p0 => s0,
            _ => 0.0,
        }
    }

    /// The largest polar angle with sensitivity, radians: the edge of the sensor's view.
    pub fn view_edge(&self) -> f64 {
        self.polar.last().copied().unwrap_or(0.0)
    }

    /// The rows as (polar angle in radians, relative sensitivity), for keys and reports.
    pub fn rows(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.polar
            .iter()
            .copied()
            .zip(self.sensitivity.iter().copied())
    }

    /// The view cut into rings of polar angle: `(edge, weight)` pairs such that the reading
    /// is `Σ_k weight_k F(edge_k)`, `F(α)` the cosine-weighted view (form factor) within the
    /// cone of half-angle `α` (radians; `π/2` is the hemisphere).
    ///
    /// With `w = S / cos θ` taken as its cosine-weighted mean `w_k` over ring k (between
    /// `edge_{k−1}` and `edge_k`), `∫ S dω / π = Σ_k w_k (F(edge_k) − F(edge_{k−1}))
    /// = Σ_k (w_k − w_{k+1}) F(edge_k)`: exact for a uniformly bright surround, and within a
    /// ring's variation of `w` for anything else.
    pub fn rings(&self) -> Vec<(f64, f64)> {
        let edge = self.view_edge();
        let count = (edge / RING_WIDTH).ceil().max(1.0) as usize;
        let step = edge / count as f64;
        let mean: Vec<f64> = (0..count)
            .map(|k| {
                let (a, b) = (k as f64 * step, (k + 1) as f64 * step);
                // ∫ S sin θ dθ over ∫ cos θ sin θ dθ = (sin² b − sin² a) / 2.
                let s: f64 = GAUSS_4
                    .iter()
                    .map(|&(x, w)| {
                        let t = a + x * (b - a);
                        w * (b - a) * self.at_angle(t) * t.sin()
                    })
                    .sum();
                s / (0.5 * (b.sin().powi(2) - a.sin().powi(2)))
            })
            .collect();
        (0..count)
            .map(|k| {
                let next = mean.get(k + 1).copied().unwrap_or(0.0);
                let edge = if k + 1 == count {
                    edge
                } else {
                    (k + 1) as f64 * step
                };
                (edge, mean[k] - next)
            })
            .filter(|&(_, w)| w != 0.0)
            .collect()
    }
}

/// `S(θ)` of [`Response::shielded`] at polar angle `theta` for a shield cutting off at
/// `cutoff`, radians.
fn shielded_sensitivity(theta: f64, cutoff: f64) -> f64 {
    let u = (theta.tan() / cutoff.tan()).clamp(0.0, 1.0);
    let lit = 2.0 / std::f64::consts::PI * (u.acos() - u * (1.0 - u * u).sqrt());
    theta.cos() * lit
}

/// Reads a sensitivity table in the layout of Radiance's `rsensor` from `text` (of `file`,
/// for messages): an optional first line starting with `Elevation `, a header `degrees`
/// followed by azimuth angles (from 0), then one row per polar angle (degrees, from 0) with a
/// relative sensitivity per azimuth, tab- or space-separated. Blank lines and lines starting
/// with `#` are skipped. Every row's columns must agree (no azimuthal variation).
pub fn parse_rsensor(text: &str) -> Result<Response, TableError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'))
        .peekable();
    if lines
        .peek()
        .is_some_and(|(_, l)| l.starts_with("Elevation "))
    {
        lines.next();
    }
    let Some((header_line, header)) = lines.next() else {
        return Err(refuse(
            None,
            "empty file: expected a header line starting with `degrees`",
        ));
    };
    let mut fields = header.split_whitespace();
    if fields.next() != Some("degrees") {
        return Err(refuse(
            Some(header_line),
            format!("the header must start with `degrees`, found `{header}`"),
        ));
    }
    let azimuths = fields
        .map(|f| {
            f.parse::<f64>()
                .map_err(|_| refuse(Some(header_line), format!("azimuth `{f}` is not a number")))
        })
        .collect::<Result<Vec<f64>, _>>()?;
    if azimuths.is_empty() {
        return Err(refuse(
            Some(header_line),
            "the header names no azimuth column after `degrees`",
        ));
    }
    if azimuths[0] != 0.0 {
        return Err(refuse(
            Some(header_line),
            format!("the first azimuth must be 0 degrees, found {}", azimuths[0]),
        ));
    }
    let (mut rows, mut at) = (Vec::new(), Vec::new());
    for (line, text) in lines {
        let values = text
            .split_whitespace()
            .map(|f| {
                f.parse::<f64>()
                    .map_err(|_| refuse(Some(line), format!("`{f}` is not a number")))
            })
            .collect::<Result<Vec<f64>, _>>()?;
        if values.len() != azimuths.len() + 1 {
            return Err(refuse(
                Some(line),
                format!(
                    "expected a polar angle and {} sensitivities (one per azimuth of the \
                     header), found {} values",
                    azimuths.len(),
                    values.len()
                ),
            ));
        }
        let (theta, columns) = (values[0], &values[1..]);
        let first = columns[0];
        if let Some((k, &other)) = columns
            .iter()
            .enumerate()
            .find(|&(_, &v)| (v - first).abs() > 1e-9 * first.abs().max(v.abs()))
        {
            return Err(refuse(
                Some(line),
                format!(
                    "sensitivity {other} at azimuth {} differs from {first} at azimuth 0: \
                     sensitivity varying with azimuth is not supported",
                    azimuths[k]
                ),
            ));
        }
        rows.push((theta, first));
        at.push(line);
    }
    Response::from_rows(&rows, Some(&at))
}

/// Reads an `rsensor` table from `path`; errors carry the path (and line).
pub fn read_rsensor(path: &Path) -> Result<Response, (PathBuf, TableError)> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        (
            path.to_path_buf(),
            refuse(None, format!("cannot read file: {e}")),
        )
    })?;
    parse_rsensor(&text).map_err(|e| (path.to_path_buf(), e))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The interpolation is linear in θ between rows and zero past the last one.
    #[test]
    fn sensitivity_interpolates_between_rows() {
        let r = Response::from_rows(&[(0.0, 1.0), (30.0, 0.5), (60.0, 0.25)], None)
            .expect("valid table");
        assert!((r.at_angle(15f64.to_radians()) - 0.75).abs() < 1e-12);
        assert!((r.at_angle(45f64.to_radians()) - 0.375).abs() < 1e-12);
        assert_eq!(r.at_angle(60f64.to_radians()), 0.25);
        assert_eq!(r.at_angle(61f64.to_radians()), 0.0);
        assert_eq!(r.at_cos(-0.1), 0.0);
        assert_eq!(r.at_cos(f64::NAN), 0.0);
    }

    /// The rings reproduce `∫ S dω / π` for a uniform surround exactly: the sum of their
    /// weights times the cone form factor `sin² α` of a uniform surround equals
    /// `2 ∫ S sin θ dθ` (reference: the same integral by a 20 000-step midpoint rule;
    /// tolerance 1e-9 relative).
    #[test]
    fn rings_integrate_a_uniform_surround() {
        let r = Response::shielded(60f64.to_radians());
        let by_rings: f64 = r.rings().iter().map(|&(a, w)| w * a.sin().powi(2)).sum();
        let steps = 20_000;
        let h = r.view_edge() / f64::from(steps);
        let direct: f64 = (0..steps)
            .map(|k| {
                let t = (f64::from(k) + 0.5) * h;
                2.0 * r.at_angle(t) * t.sin() * h
            })
            .sum();
        assert!(
            (by_rings - direct).abs() < 1e-9 * direct,
            "{by_rings} vs {direct}"
        );
    }

    /// The shielded preset: `cos θ` at the normal's neighbourhood, half lit where the shield's
    /// opening is offset by one radius (`u = 1/2`: `A = (2/π)(π/3 − √3/4)`), zero at the
    /// cut-off.
    #[test]
    fn shielded_preset_follows_its_geometry() {
        let cutoff = 60f64.to_radians();
        let r = Response::shielded(cutoff);
        assert_eq!(r.at_angle(0.0), 1.0);
        let half = (0.5 * cutoff.tan()).atan();
        let lit = 2.0 / std::f64::consts::PI * (std::f64::consts::FRAC_PI_3 - 3f64.sqrt() / 4.0);
        assert!((shielded_sensitivity(half, cutoff) - half.cos() * lit).abs() < 1e-12);
        assert_eq!(r.at_angle(cutoff), 0.0);
        assert!((r.view_edge() - cutoff).abs() < 1e-12);
    }

    /// `rsensor` files: Radiance's own example, a table whose columns disagree, and lines
    /// that are not numbers, each error naming its line.
    #[test]
    fn rsensor_tables_are_read_and_bad_ones_name_their_line() {
        let ok = "degrees\t0\t90\t180\t270\n0\t1\t1\t1\t1\n45\t.5\t.5\t.5\t.5\n90\t0\t0\t0\t0\n";
        let r = parse_rsensor(ok).expect("valid");
        assert!((r.at_angle(45f64.to_radians()) - 0.5).abs() < 1e-12);
        // The man page's example varies with azimuth.
        let azimuthal = "degrees\t0\t90\t180\t270\n0\t.02\t.04\t.02\t.04\n";
        let e = parse_rsensor(azimuthal).expect_err("azimuthal");
        assert_eq!(e.line, Some(2));
        assert!(e.message.contains("azimuth"), "{e}");
        let bad = "degrees 0\n0 1\n10 x\n";
        assert_eq!(parse_rsensor(bad).expect_err("bad").line, Some(3));
        let short = "degrees 0 90\n0 1 1\n10 1\n";
        assert_eq!(parse_rsensor(short).expect_err("short").line, Some(3));
        let backwards = "degrees 0\n0 1\n20 1\n10 1\n";
        assert_eq!(parse_rsensor(backwards).expect_err("order").line, Some(4));
        let negative = "degrees 0\n0 1\n10 -1\n";
        assert_eq!(parse_rsensor(negative).expect_err("negative").line, Some(3));
        let behind = "degrees 0\n0 1\n120 1\n";
        assert_eq!(parse_rsensor(behind).expect_err("behind").line, Some(3));
        assert_eq!(parse_rsensor("0 1\n").expect_err("header").line, Some(1));
        assert!(parse_rsensor("degrees 0\n0 0\n").is_err());
        assert!(parse_rsensor("degrees 0\n5 1\n").is_err());
    }
}
