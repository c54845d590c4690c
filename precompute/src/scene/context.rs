//! What every stage of building a scene shares: the parsing context (file, bands, unit) with
//! its checked conversions, and the intermediate material and surface records.

use std::collections::HashSet;
use std::path::Path;

use toml::Spanned;

use super::error::{Location, SceneError};
use super::file::{PerBand, Xyz};
use super::Surface;
use crate::geometry::Vec3;
use eigenrad_runtime::{MAX_EXITANCE, MIN_REFLECTANCE};

/// Luminance weights of linear RGB (ITU-R BT.709 primaries), used to make photopic values.
pub(crate) const LUMINANCE: [f64; 3] = [0.2126, 0.7152, 0.0722];

/// Largest coordinate magnitude a scene may use, metres (1000 km): far beyond any building,
/// and far enough inside `f64`'s range that squared lengths, areas and the patch-count
/// estimate stay finite (a vertex at 1e300 m would make them infinite).
pub(crate) const LARGEST_COORDINATE: f64 = 1e6;

/// Parsing context: where the text came from, its bands and its length unit.
pub(crate) struct Ctx<'a> {
    /// The scene file (for messages and relative paths).
    pub origin: &'a Path,
    /// The scene file's text (to turn spans into lines).
    pub text: &'a str,
    /// Number of bands (1 or 3).
    pub bands: usize,
    /// Metres per unit of length in the file.
    pub unit: f64,
}

/// A material's values in SI units.
#[derive(Clone, Debug)]
pub(crate) struct MaterialInfo {
    /// Per band, in [0, 1).
    pub reflectance: Vec<f64>,
    /// Exitance at level 1 per band (lux or W/m²).
    pub emission: Vec<f64>,
    /// The glazing of a material with a transmittance: its surfaces are windows.
    pub glazing: Option<eigenrad_runtime::sky::glazing::Glazing>,
}

/// A surface before meshing: faces in metres, material by name.
#[derive(Clone, Debug)]
pub(crate) struct RawSurface {
    pub name: String,
    pub material: String,
    /// Where the material was named (for unknown-material errors).
    pub material_at: Location,
    /// Polygons, metres, counter-clockwise seen from the front.
    pub faces: Vec<Vec<Vec3>>,
    /// Longest patch edge, metres (`None`: the scene default).
    pub max_edge: Option<f64>,
    /// Where the surface was defined.
    pub at: Location,
    /// Outside the room (`exterior = true`): an obstruction, not meshed.
    pub exterior: bool,
}

impl RawSurface {
    /// Its material among `materials`, or the error naming the surface and where the material
    /// was named.
    pub fn material_in<'m>(
        &self,
        materials: &'m std::collections::BTreeMap<String, MaterialInfo>,
    ) -> Result<&'m MaterialInfo, SceneError> {
        materials
            .get(&self.material)
            .ok_or_else(|| SceneError::Unknown {
                at: self.material_at.clone(),
                field: format!("surface `{}`.material", self.name),
                kind: "material",
                name: self.material.clone(),
            })
    }
}

impl Ctx<'_> {
    /// The location of a spanned value.
    pub fn at<T>(&self, s: &Spanned<T>) -> Location {
        Location::at_offset(self.origin, self.text, s.span().start)
    }

    /// A point or vector from the file, checked finite and converted to metres.
    pub fn point(&self, p: &Spanned<Xyz>, field: &str) -> Result<Vec3, SceneError> {
        self.coordinates(**p.get_ref(), p, field)
    }

    /// Coordinates checked finite and converted to metres; `span` locates errors.
    pub fn coordinates<T>(
        &self,
        c: [f64; 3],
        span: &Spanned<T>,
        field: &str,
    ) -> Result<Vec3, SceneError> {
        if c.iter().any(|v| !v.is_finite()) {
            return Err(SceneError::OutOfRange {
                at: self.at(span),
                field: field.into(),
                message: format!("coordinates must be finite, found {c:?}"),
            });
        }
        let metres = Vec3::new(c[0], c[1], c[2]) * self.unit;
        if let Some(axis) = (0..3).find(|&k| metres.axis(k).abs() > LARGEST_COORDINATE) {
            return Err(SceneError::OutOfRange {
                at: self.at(span),
                field: field.into(),
                message: format!(
                    "coordinate {} = {} is {:.3e} m from the origin, beyond the ±{LARGEST_COORDINATE:.0e}                      m a scene may span (a unit mistake?)",
                    ["x", "y", "z"][axis],
                    c[axis],
                    metres.axis(axis).abs()
                ),
            });
        }
        Ok(metres)
    }

    /// A positive finite length from the file, in metres.
    pub fn length(&self, l: &Spanned<f64>, field: &str) -> Result<f64, SceneError> {
        let v = *l.get_ref();
        if !(v.is_finite() && v > 0.0) {
            return Err(SceneError::OutOfRange {
                at: self.at(l),
                field: field.into(),
                message: format!("must be a positive finite length, found {v}"),
            });
        }
        Ok(v * self.unit)
    }

    /// An optional positive length, in metres.
    pub fn optional_length(
        &self,
        l: Option<&Spanned<f64>>,
        field: &str,
    ) -> Result<Option<f64>, SceneError> {
        l.map(|l| self.length(l, field)).transpose()
    }

    /// One value per band from an RGB triple (photopic: luminance-weighted sum).
    pub fn bands_of_rgb(&self, rgb: [f64; 3]) -> Vec<f64> {
        if self.bands == 1 {
            vec![rgb.iter().zip(LUMINANCE).map(|(c, w)| c * w).sum()]
        } else {
            rgb.to_vec()
        }
    }

    /// One value per band from `x = 0.5` or `x = [r, g, b]`.
    pub fn per_band(&self, v: &Spanned<PerBand>, field: &str) -> Result<Vec<f64>, SceneError> {
        match v.get_ref() {
            PerBand::One(x) => Ok(vec![*x; self.bands]),
            PerBand::Many(xs) if xs.len() == self.bands => Ok(xs.clone()),
            PerBand::Many(xs) => Err(SceneError::BandCount {
                at: self.at(v),
                field: field.into(),
                expected: self.bands,
                found: xs.len(),
            }),
        }
    }

    /// Checks reflectances are what a basis can store: 0 (black), or at least
    /// [`MIN_REFLECTANCE`] and still below 1 once rounded to f32.
    pub fn check_reflectance(
        &self,
        r: Vec<f64>,
        at: &Location,
        field: &str,
    ) -> Result<Vec<f64>, SceneError> {
        let storable = |x: f64| {
            let stored = x as f32;
            x == 0.0 || (x > 0.0 && (MIN_REFLECTANCE..1.0).contains(&stored))
        };
        if r.iter().all(|&x| storable(x)) {
            Ok(r)
        } else {
            Err(SceneError::OutOfRange {
                at: at.clone(),
                field: field.into(),
                message: format!(
                    "reflectance must be in [0, 1): 0 for a black surface, otherwise at least \
                     {MIN_REFLECTANCE:e} and at most {LARGEST_REFLECTANCE} (the largest below 1 \
                     in single precision); found {r:?}"
                ),
            })
        }
    }

    /// Checks exitances (or fluxes) are finite, non-negative and at most [`MAX_EXITANCE`].
    pub fn check_exitance(
        &self,
        e: Vec<f64>,
        at: &Location,
        field: &str,
    ) -> Result<Vec<f64>, SceneError> {
        if e.iter()
            .all(|x| x.is_finite() && (0.0..=f64::from(MAX_EXITANCE)).contains(x))
        {
            Ok(e)
        } else {
            Err(SceneError::OutOfRange {
                at: at.clone(),
                field: field.into(),
                message: format!(
                    "must be finite, non-negative and at most {MAX_EXITANCE:e}, found {e:?}"
                ),
            })
        }
    }
}

/// The largest reflectance below 1 that single precision holds: `1 − 2⁻²⁴`.
const LARGEST_REFLECTANCE: f32 = 1.0 - f32::EPSILON / 2.0;

/// Checks that no two items share a name.
pub(crate) fn unique<'n>(
    kind: &'static str,
    names: impl IntoIterator<Item = (&'n str, Location)>,
) -> Result<(), SceneError> {
    let mut seen = HashSet::new();
    for (name, at) in names {
        if !seen.insert(name) {
            return Err(SceneError::Duplicate {
                at,
                kind,
                name: name.into(),
            });
        }
    }
    Ok(())
}

/// Surfaces matching a reference: an exact name, or a prefix followed by `*`.
pub(crate) fn matching(names: &[Surface], pattern: &str) -> Vec<usize> {
    match pattern.strip_suffix('*') {
        Some(prefix) => (0..names.len())
            .filter(|&i| names[i].name.starts_with(prefix))
            .collect(),
        None => names
            .iter()
            .position(|s| s.name == pattern)
            .into_iter()
            .collect(),
    }
}

/// Resolves a list of surface references to surface indices (in reference order, no repeats).
pub(crate) fn resolve_surfaces(
    ctx: &Ctx,
    surfaces: &[Surface],
    refs: &Spanned<Vec<String>>,
    field: &str,
) -> Result<Vec<usize>, SceneError> {
    let mut out = Vec::new();
    for r in refs.get_ref() {
        let found = matching(surfaces, r);
        if found.is_empty() {
            return Err(SceneError::Unknown {
                at: ctx.at(refs),
                field: field.into(),
                kind: "surface",
                name: r.clone(),
            });
        }
        for i in found {
            if !out.contains(&i) {
                out.push(i);
            }
        }
    }
    Ok(out)
}
