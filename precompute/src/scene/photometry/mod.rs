//! Luminaire photometry: IES LM-63 (`.ies`) and EULUMDAT (`.ldt`) files of type C photometry
//! read into one model, [`Photometry`], in SI units, with the intensity between the tabulated
//! angles and the flux it carries.
//!
//! # Why a reader of our own
//!
//! `eulumdat` is AGPL-3.0, which an MIT/Apache-2.0 project cannot take. `lidrs` (0.2.3, MIT,
//! one author) was read in full and tried on small files, and does not fit: an LM-63-2019 file
//! fails (the version line is not known, so the file is read as LM-63-1986 and that line then
//! fails as a keyword); a tilt table whose records run over several lines, as LM-63 allows,
//! fails; a file whose first keyword is `[MORE]` panics (an `unwrap` of the absent keyword it
//! continues); negative and NaN candela are accepted; errors name a line but not the file
//! (inside a tilt table, a line counted from the table), and hold an `Rc`, so they cannot
//! travel in the precompute's `Send + Sync` errors; and `TILT=<file>` opens that name relative
//! to the working directory. The two readers here are small: [`ies`] reads LM-63 record by
//! record, tracking the line of every value, and [`eulumdat`] reads EULUMDAT's one field a
//! line.
//!
//! # Coordinates
//!
//! Type C: a C-plane is a vertical half-plane through the luminaire's vertical axis, at the
//! angle `C` (degrees) counted counter-clockwise seen from above from the 0° plane (LM-63's
//! "horizontal angle"); `γ` (degrees) is the angle from straight down (0°, nadir) to straight
//! up (180°), LM-63's "vertical angle".
//!
//! # Symmetries
//!
//! Files store part of the distribution; [`Photometry`] holds it expanded to the full circle
//! of C-planes, each stored plane copied to its mirror images:
//!
//! | [`Symmetry`] | LM-63 horizontal angles | EULUMDAT `Isym` | images of a stored plane `C` |
//! |---|---|---|---|
//! | `Rotational` | `0` alone | 1 | every C |
//! | `Quadrant` | 0 … 90 | 4 | `C`, `180−C`, `180+C`, `360−C` |
//! | `AboutC0C180` | 0 … 180 | 2 | `C`, `360−C` |
//! | `AboutC90C270` | 90 … 270 | 3 (C270 … C90) | `C`, `180−C` |
//! | `None` | 0 … 360 (or beyond 180) | 0 | `C` |
//!
//! # Interpolation
//!
//! [`Photometry::intensity`] is bilinear in (C, γ): linear in γ between the two tabulated
//! γ angles around it, on the two expanded C-planes around C, then linear in C between them.
//! C is periodic: the interval from the last plane to the first plus 360° is a cell like any
//! other, so the intensity is continuous across C = 0°/360°; and since the mirrored planes
//! carry the same values as the planes they mirror, it is continuous across every symmetry
//! plane too. Outside the tabulated γ range the intensity is zero: LM-63 and EULUMDAT both
//! tabulate 0–90° for a luminaire that sends nothing upward and 90–180° for one that sends
//! nothing downward. Within the range it is the data's own, nothing is extrapolated.
//!
//! # Flux
//!
//! [`Photometry::flux`] is the integral of the interpolated intensity over the sphere,
//! `Φ = ∫∫ I(C, γ) sin γ dγ dC`, computed exactly for the bilinear interpolant: along γ each
//! linear segment times `sin γ` has a closed form, and along C the trapezoid rule is exact for
//! an interpolant linear in C. The flux is thus that of the very distribution
//! [`Photometry::intensity`] evaluates; it differs from a smooth distribution's flux only by
//! the interpolation error, of the order of the squared angular step.

mod error;
pub mod eulumdat;
pub mod ies;
mod text;

use std::path::Path;

pub use error::PhotometryError;

use crate::geometry::Vec3;

/// Reads a photometric file, choosing the reader by its extension: `.ies` for IES LM-63,
/// `.ldt` or `.eul` for EULUMDAT (either case).
pub fn read(path: &Path) -> Result<Photometry, PhotometryError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let parse = match extension.as_deref() {
        Some("ies") => ies::parse,
        Some("ldt" | "eul") => eulumdat::parse,
        _ => {
            return Err(PhotometryError::UnknownFormat {
                path: path.to_path_buf(),
            })
        }
    };
    let bytes = std::fs::read(path).map_err(|reason| PhotometryError::Read {
        path: path.to_path_buf(),
        reason,
    })?;
    parse(path, &bytes)
}

/// The file format a [`Photometry`] was read from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// IES LM-63, in the version its first line names.
    Lm63(Lm63Version),
    /// EULUMDAT.
    Eulumdat,
}

/// The versions of IES LM-63, told apart by the file's first line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Lm63Version {
    /// LM-63-1986: no version line.
    V1986,
    /// LM-63-1991: `IESNA91`.
    V1991,
    /// LM-63-1995: `IESNA:LM-63-1995`.
    V1995,
    /// LM-63-2002: `IESNA:LM-63-2002`.
    V2002,
    /// LM-63-2019: `IES:LM-63-2019`.
    V2019,
}

/// The lateral symmetry a file declares, which says what its stored C-planes stand for (see
/// the module documentation for the images of each).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Symmetry {
    /// Every C-plane is the same: one plane is stored.
    Rotational,
    /// Symmetric about the C0–C180 and the C90–C270 planes: C = 0°…90° is stored.
    Quadrant,
    /// Symmetric about the C0–C180 plane: C = 0°…180° is stored.
    AboutC0C180,
    /// Symmetric about the C90–C270 plane: C = 90°…270° is stored (LM-63), or C = 270°…360°
    /// and 0°…90° (EULUMDAT, given here as −90°…90°).
    AboutC90C270,
    /// No symmetry: the whole circle is stored.
    None,
}

impl Symmetry {
    /// The C angles (degrees) that the stored plane at `c` stands for, itself first.
    fn images(self, c: f64) -> Vec<f64> {
        match self {
            Symmetry::Rotational | Symmetry::None => vec![c],
            Symmetry::Quadrant => vec![c, 180.0 - c, 180.0 + c, 360.0 - c],
            Symmetry::AboutC0C180 => vec![c, 360.0 - c],
            Symmetry::AboutC90C270 => vec![c, 180.0 - c],
        }
    }
}

/// The shape of a luminous opening (or of a luminaire's body), as LM-63's signs of width,
/// length and height or EULUMDAT's zero width encode it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpeningShape {
    /// No extent: a point source.
    Point,
    /// A box `length × width × height`; flat (a rectangle) when the height is zero.
    Rectangular,
    /// A vertical cylinder of elliptic section with diameters `length` and `width` (circular
    /// when equal) and the given height; a flat disc or ellipse when the height is zero.
    VerticalCylinder,
    /// An ellipsoid with diameters `length`, `width`, `height` (a sphere when all are equal).
    Ellipsoid,
    /// A horizontal cylinder whose axis runs along the length, of section `width × height`; a
    /// vertical disc when the length is zero.
    HorizontalCylinderAlongLength,
    /// A horizontal cylinder whose axis runs along the width, of section `length × height`; a
    /// vertical disc when the width is zero.
    HorizontalCylinderAlongWidth,
}

/// The size of a luminous opening or of a luminaire, in metres, all non-negative.
///
/// LM-63: the length runs along the C0–C180 axis and the width along C90–C270. EULUMDAT:
/// length (or diameter) and width as the file names them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Opening {
    /// The shape the dimensions describe.
    pub shape: OpeningShape,
    /// Length or diameter, m.
    pub length: f64,
    /// Width or diameter, m.
    pub width: f64,
    /// Height, m (EULUMDAT: the largest of [`Opening::side_heights`]).
    pub height: f64,
    /// EULUMDAT's heights of the luminous area seen in the C0, C90, C180 and C270 planes, m.
    pub side_heights: Option<[f64; 4]>,
}

/// How the lamp sits in the luminaire, LM-63's lamp-to-luminaire geometry of a tilt table
/// (LM-63-2002, "TILT"): which axis of the luminaire the lamp lies along, and so which turn
/// of the luminaire changes the lamp's burning position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LampGeometry {
    /// Code 1: the lamp is vertical, base up or base down, when the luminaire is aimed
    /// straight down: it lies along the nadir axis.
    Vertical,
    /// Code 2: the lamp is horizontal, along the C0–C180 axis, and stays horizontal when the
    /// luminaire is turned about that axis.
    Horizontal0,
    /// Code 3: the lamp is horizontal when the luminaire is aimed straight down, along the
    /// C90–C270 axis, and tilts when the luminaire is turned about the C0–C180 axis.
    Horizontal90,
}

/// An LM-63 tilt table (`TILT=INCLUDE`, or `TILT=<file>`): how the lamp's output changes with
/// the tilt of the luminaire, for lamps (metal halide) whose output depends on their burning
/// position.
///
/// The distribution is measured with the luminaire aimed straight down; a luminaire mounted
/// otherwise multiplies every intensity by [`Tilt::factor`] at its [`Tilt::angle`], once for
/// its placed orientation (docs/scene.md, "Luminaires").
#[derive(Clone, Debug, PartialEq)]
pub struct Tilt {
    /// How the lamp sits in the luminaire.
    pub geometry: LampGeometry,
    /// Tilt angles, degrees, strictly increasing.
    pub angles: Vec<f64>,
    /// The output multiplying factor at each angle (dimensionless, non-negative).
    pub factors: Vec<f64>,
}

impl Tilt {
    /// The multiplying factor at a tilt of `degrees`: linear between the tabulated angles,
    /// the end values beyond them (1 for a table without entries). LM-63 gives no rule
    /// beyond the table; holding its end keeps the factor within what was measured and never
    /// negative.
    pub fn factor(&self, degrees: f64) -> f64 {
        let (a, f) = (&self.angles, &self.factors);
        if a.is_empty() || a.len() != f.len() {
            return 1.0;
        }
        let i = a.partition_point(|&x| x <= degrees);
        if i == 0 {
            return f[0];
        }
        if i == a.len() {
            return f[a.len() - 1];
        }
        let t = (degrees - a[i - 1]) / (a[i] - a[i - 1]);
        f[i - 1] + t * (f[i] - f[i - 1])
    }

    /// The tilt, degrees, of a luminaire whose nadir, C0 and C90 directions are these unit
    /// vectors of a frame with +z up: the angle through which its lamp's axis has turned from
    /// where it was in the measurement (the luminaire aimed straight down).
    ///
    /// - [`LampGeometry::Vertical`]: the nadir's angle from straight down, 0°…180° (180°
    ///   aimed straight up, the lamp turned over). A table that ends at or below 90° is read
    ///   with the angle folded into 0°…90° (`min(t, 180° − t)`): its lamp is then taken to
    ///   burn alike base up and base down, as Radiance's `tilt.cal` (`tilt_ang2`) reads it.
    /// - [`LampGeometry::Horizontal0`]: the C0 axis's angle from the horizontal, 0°…90°.
    /// - [`LampGeometry::Horizontal90`]: the C90 axis's angle from the horizontal, 0°…90°.
    ///
    /// For a horizontal lamp which way it tilts does not matter: the file does not say which
    /// end holds its base.
    pub fn angle(&self, nadir: Vec3, c0: Vec3, c90: Vec3) -> f64 {
        let from_horizontal = |axis: Vec3| axis.z.abs().min(1.0).asin().to_degrees();
        match self.geometry {
            LampGeometry::Vertical => {
                let t = (-nadir.z).clamp(-1.0, 1.0).acos().to_degrees();
                let beyond_90 = self.angles.last().is_some_and(|&a| a > 90.0);
                if beyond_90 {
                    t
                } else {
                    t.min(180.0 - t)
                }
            }
            LampGeometry::Horizontal0 => from_horizontal(c0),
            LampGeometry::Horizontal90 => from_horizontal(c90),
        }
    }
}

/// What a file says of the luminaire, for reports. Each is `None` when the file does not say.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Identity {
    /// Manufacturer (LM-63 `[MANUFAC]`, EULUMDAT's company line).
    pub manufacturer: Option<String>,
    /// Luminaire catalogue number (LM-63 `[LUMCAT]`, EULUMDAT's luminaire number).
    pub catalogue: Option<String>,
    /// Luminaire description (LM-63 `[LUMINAIRE]`, EULUMDAT's luminaire name).
    pub luminaire: Option<String>,
    /// Lamp (LM-63 `[LAMP]`, EULUMDAT's lamp type of the first lamp set).
    pub lamp: Option<String>,
    /// Test or measurement report (LM-63 `[TEST]`, EULUMDAT's report number).
    pub test: Option<String>,
    /// Every keyword and its value in file order (LM-63 `[MORE]` lines joined to the keyword
    /// they continue; EULUMDAT's other text fields under their names).
    pub keywords: Vec<(String, String)>,
}

/// A luminaire's photometry: its intensity distribution over the full sphere of directions,
/// in candela for the luminaire as a whole, with what the file says of it.
#[derive(Clone, Debug, PartialEq)]
pub struct Photometry {
    /// The format and version read.
    pub format: Format,
    /// What the file says of the luminaire.
    pub identity: Identity,
    /// The symmetry the file declared (the distribution held is already expanded).
    pub symmetry: Symmetry,
    /// The luminous opening, m.
    pub opening: Opening,
    /// The luminaire's body, m (EULUMDAT; LM-63 gives only the luminous opening).
    pub luminaire: Option<Opening>,
    /// Number of lamps.
    pub lamps: u32,
    /// Absolute photometry: the intensities were measured for the luminaire as a whole, with
    /// no rated lamp flux behind them (LM-63 lumens per lamp −1, EULUMDAT negative number of
    /// lamps).
    pub absolute: bool,
    /// Rated flux of all the lamps together, lm (LM-63 lumens per lamp × lamps; EULUMDAT's
    /// total lamp flux of the first lamp set). `None` for LM-63 absolute photometry.
    pub lamp_flux: Option<f64>,
    /// The luminaire's flux as the file states it, lm: EULUMDAT's lamp flux × LORL. `None`
    /// for LM-63, which states none.
    pub luminaire_flux: Option<f64>,
    /// The share of the luminaire's flux emitted downward (γ < 90°), from 0 to 1: EULUMDAT's
    /// DFF. `None` for LM-63.
    pub downward_fraction: Option<f64>,
    /// Electrical input power, W (LM-63 input watts; EULUMDAT's first lamp set's wattage).
    pub input_watts: Option<f64>,
    /// The tilt table, if the file includes one.
    pub tilt: Option<Tilt>,
    /// The distribution, expanded to the full circle of C-planes.
    pub distribution: Distribution,
}

impl Photometry {
    /// Luminous intensity, cd, towards `(c_degrees, gamma_degrees)`: see
    /// [`Distribution::intensity`].
    pub fn intensity(&self, c_degrees: f64, gamma_degrees: f64) -> f64 {
        self.distribution.intensity(c_degrees, gamma_degrees)
    }

    /// The flux of the distribution, lm: see [`Distribution::flux`]. The file's own, as
    /// measured: no tilt factor.
    pub fn flux(&self) -> f64 {
        self.distribution.flux()
    }

    /// The tilt table's factor for a luminaire of this photometry mounted with these unit
    /// nadir, C0 and C90 directions (+z up): [`Tilt::factor`] at [`Tilt::angle`]; 1 without
    /// a table.
    pub fn tilt_factor(&self, nadir: Vec3, c0: Vec3, c90: Vec3) -> f64 {
        self.tilt
            .as_ref()
            .map_or(1.0, |t| t.factor(t.angle(nadir, c0, c90)))
    }
}

/// A type-C intensity distribution over the full circle of C-planes: the tabulated values and
/// their bilinear interpolation.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution {
    /// C angles, degrees, strictly increasing in `[0, 360)`.
    c: Vec<f64>,
    /// γ angles, degrees, strictly increasing in `[0, 180]`, at least two.
    gamma: Vec<f64>,
    /// `candela[i][j]`: intensity, cd, on plane `c[i]` at `gamma[j]`.
    candela: Vec<Vec<f64>>,
}

/// Angles closer than this (degrees) are the same angle: a stored plane on a symmetry plane is
/// its own mirror image.
const SAME_ANGLE: f64 = 1e-9;

impl Distribution {
    /// The full distribution from the stored part of one: `planes[i]` is the C angle
    /// (degrees) of `candela[i]`, which holds the intensity (cd) at each of `gamma` (degrees);
    /// `symmetry` says what the stored planes stand for.
    ///
    /// The stored planes must be strictly increasing and cover exactly the range their
    /// symmetry stores (module documentation); the γ angles strictly increasing in `[0, 180]`,
    /// at least two; every intensity finite and non-negative. The error says which is not.
    pub fn new(
        symmetry: Symmetry,
        planes: &[f64],
        gamma: Vec<f64>,
        candela: Vec<Vec<f64>>,
    ) -> Result<Distribution, String> {
        check_planes(symmetry, planes)?;
        if gamma.len() < 2 {
            return Err(format!("{} γ angles: at least two are needed", gamma.len()));
        }
        if !increasing(&gamma) || gamma[0] < 0.0 || gamma[gamma.len() - 1] > 180.0 {
            return Err("γ angles must increase within 0°…180°".into());
        }
        if candela.len() != planes.len() || candela.iter().any(|p| p.len() != gamma.len()) {
            return Err("one intensity per stored plane and γ angle is needed".into());
        }
        if candela.iter().flatten().any(|v| !v.is_finite() || *v < 0.0) {
            return Err("intensities must be finite and non-negative".into());
        }
        let mut expanded: Vec<(f64, usize)> = Vec::new();
        for (i, &c) in planes.iter().enumerate() {
            for image in symmetry.images(c) {
                let a = image.rem_euclid(360.0);
                expanded.push((if a > 360.0 - SAME_ANGLE { 0.0 } else { a }, i));
            }
        }
        // Stable: of two planes at the same angle (LM-63's 0° and 360°), the first read stays.
        expanded.sort_by(|a, b| a.0.total_cmp(&b.0));
        expanded.dedup_by(|later, kept| later.0 - kept.0 < SAME_ANGLE);
        Ok(Distribution {
            c: expanded.iter().map(|(a, _)| *a).collect(),
            candela: expanded.iter().map(|(_, i)| candela[*i].clone()).collect(),
            gamma,
        })
    }

    /// The C angles of the expanded planes, degrees, strictly increasing in `[0, 360)`.
    pub fn c_angles(&self) -> &[f64] {
        &self.c
    }

    /// The tabulated γ angles, degrees, strictly increasing.
    pub fn gamma_angles(&self) -> &[f64] {
        &self.gamma
    }

    /// The intensities on the expanded plane `c_angles()[i]`, cd, one per γ angle.
    pub fn plane(&self, i: usize) -> &[f64] {
        &self.candela[i]
    }

    /// Luminous intensity, cd, towards C = `c_degrees` (any value; periodic) and γ =
    /// `gamma_degrees`: bilinear in (C, γ), periodic in C, zero outside the tabulated γ range
    /// (module documentation). NaN for a non-finite angle.
    pub fn intensity(&self, c_degrees: f64, gamma_degrees: f64) -> f64 {
        if !c_degrees.is_finite() || !gamma_degrees.is_finite() {
            return f64::NAN;
        }
        let g = &self.gamma;
        let (first, last) = (g[0], g[g.len() - 1]);
        if gamma_degrees < first - SAME_ANGLE || gamma_degrees > last + SAME_ANGLE {
            return 0.0;
        }
        let gamma = gamma_degrees.clamp(first, last);
        let j = g.partition_point(|&x| x <= gamma).clamp(1, g.len() - 1);
        let s = (gamma - g[j - 1]) / (g[j] - g[j - 1]);
        let along_gamma = |plane: &[f64]| plane[j - 1] + s * (plane[j] - plane[j - 1]);
        let n = self.c.len();
        if n == 1 {
            return along_gamma(&self.candela[0]);
        }
        let c = c_degrees.rem_euclid(360.0);
        // The cell [c[lo], c[hi]) containing c, the wrap-around cell included.
        let above = self.c.partition_point(|&x| x <= c);
        let lo = (above + n - 1) % n;
        let hi = above % n;
        let span = (self.c[hi] - self.c[lo]).rem_euclid(360.0);
        let t = (c - self.c[lo]).rem_euclid(360.0) / span;
        let (a, b) = (
            along_gamma(&self.candela[lo]),
            along_gamma(&self.candela[hi]),
        );
        a + t * (b - a)
    }

    /// The flux of the distribution over the whole sphere, lm: the exact integral of the
    /// bilinear interpolant (module documentation).
    pub fn flux(&self) -> f64 {
        self.flux_between(0.0, 180.0)
    }

    /// The flux emitted between γ = `from` and γ = `to` (degrees, `from ≤ to`), lm, exact for
    /// the interpolant: the downward flux is `flux_between(0.0, 90.0)`.
    pub fn flux_between(&self, from: f64, to: f64) -> f64 {
        let n = self.c.len();
        // Weight of each plane in the periodic trapezoid rule along C, radians.
        let gap = |i: usize| {
            if n == 1 {
                360.0
            } else {
                (self.c[(i + 1) % n] - self.c[i]).rem_euclid(360.0)
            }
        };
        (0..n)
            .map(|i| {
                let weight = 0.5 * (gap((i + n - 1) % n) + gap(i)).to_radians();
                weight * plane_integral(&self.gamma, &self.candela[i], from, to)
            })
            .sum()
    }
}

/// `∫ I(γ) sin γ dγ` over `[from, to]` (degrees) for `I` linear between the tabulated values.
fn plane_integral(gamma: &[f64], values: &[f64], from: f64, to: f64) -> f64 {
    let mut total = 0.0;
    for k in 1..gamma.len() {
        let (a, b) = (gamma[k - 1].max(from), gamma[k].min(to));
        if a >= b {
            continue;
        }
        let at = |x: f64| {
            let t = (x - gamma[k - 1]) / (gamma[k] - gamma[k - 1]);
            values[k - 1] + t * (values[k] - values[k - 1])
        };
        total += linear_times_sine(a.to_radians(), b.to_radians(), at(a), at(b));
    }
    total
}

/// `∫_a^b y(x) sin x dx` for `y` linear from `ya` at `a` to `yb` at `b` (radians):
/// `ya cos a − yb cos b + (yb − ya)(sin b − sin a)/(b − a)`.
fn linear_times_sine(a: f64, b: f64, ya: f64, yb: f64) -> f64 {
    ya * a.cos() - yb * b.cos() + (yb - ya) * (b.sin() - a.sin()) / (b - a)
}

fn increasing(values: &[f64]) -> bool {
    values.windows(2).all(|w| w[0] < w[1])
}

fn near(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-6
}

/// The stored planes of `symmetry` must cover exactly its range.
fn check_planes(symmetry: Symmetry, planes: &[f64]) -> Result<(), String> {
    if planes.is_empty() || !increasing(planes) {
        return Err("C angles must increase".into());
    }
    let (first, last) = (planes[0], planes[planes.len() - 1]);
    let ok = match symmetry {
        Symmetry::Rotational => planes.len() == 1,
        Symmetry::Quadrant => near(first, 0.0) && near(last, 90.0),
        Symmetry::AboutC0C180 => near(first, 0.0) && near(last, 180.0),
        Symmetry::AboutC90C270 => {
            (near(first, 90.0) && near(last, 270.0)) || (near(first, -90.0) && near(last, 90.0))
        }
        Symmetry::None => first >= 0.0 && last <= 360.0 && (last < 360.0 || near(first, 0.0)),
    };
    if ok {
        Ok(())
    } else {
        Err(format!(
            "C angles {first}°…{last}° ({} planes) do not match {symmetry:?} symmetry",
            planes.len()
        ))
    }
}

#[cfg(test)]
mod tests;
