//! gbXML (<https://www.gbxml.org>): `Campus/Building/Space`s, the `Surface`s whose
//! `AdjacentSpaceId` names each, their `Opening`s, and the visible reflectance and
//! transmittance of `Construction`s, `Material`s and `WindowType`s.
//!
//! A space's faces are its surfaces, taken from the space's own `SpaceBoundary` (the interior
//! face of the wall) where the file gives one, else from the surface's `PlanarGeometry`; the
//! openings of a face given by its space boundary are moved into that plane. Whether a face
//! is a floor, a wall or a ceiling is read from its geometry, not from `surfaceType` (an
//! `InteriorFloor` is the ceiling of the space below it). Shades, air boundaries and
//! columns are listed as warnings.

use std::collections::{BTreeMap, HashMap};

use roxmltree::{Document, Node};

use super::model::{
    unit_metres, Model, ModelFace, ModelFaceKind, ModelMaterial, ModelOpening, OpeningKind, Space,
};
use super::ImportError;
use crate::geometry::{Polygon, Vec3};

/// How far apart two points may be and still count as one, metres: gbXML states no
/// tolerance; exporters write coordinates to far better than a millimetre.
const TOLERANCE: f64 = 1e-3;

/// Reads a gbXML model from its text.
pub(crate) fn read(text: &str) -> Result<Model, ImportError> {
    let doc = Document::parse(text).map_err(|e| ImportError {
        line: Some(e.pos().row as usize),
        element: "gbXML".into(),
        message: format!("not well-formed XML: {e}"),
    })?;
    let line = |n: Node| Some(doc.text_pos_at(n.range().start).row as usize);
    let root = doc.root_element();
    if root.tag_name().name() != "gbXML" {
        return Err(ImportError {
            line: line(root),
            element: root.tag_name().name().into(),
            message: "the root element is not `gbXML`".into(),
        });
    }
    let unit_name = root.attribute("lengthUnit").unwrap_or("");
    let Some(unit) = unit_metres(unit_name) else {
        return Err(ImportError {
            line: line(root),
            element: "gbXML lengthUnit".into(),
            message: format!(
                "units `{unit_name}` are not understood (Meters, Millimeters, Centimeters, Feet, \
                 Inches, ...)"
            ),
        });
    };
    let name_of = |n: Node| {
        child(n, "Name")
            .and_then(|c| c.text())
            .map(str::trim)
            .filter(|t| !t.is_empty())
            .map(str::to_owned)
    };
    let id_of = |n: Node, what: &str| {
        n.attribute("id")
            .map(str::to_owned)
            .ok_or_else(|| ImportError {
                line: line(n),
                element: what.into(),
                message: "has no `id`".into(),
            })
    };
    // A PolyLoop's corners, metres.
    let poly_loop = |n: Node, element: &str| -> Result<Vec<Vec3>, ImportError> {
        let mut out = Vec::new();
        for p in children(n, "CartesianPoint") {
            let c: Vec<f64> = children(p, "Coordinate")
                .map(|c| c.text().unwrap_or("").trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|e| ImportError {
                    line: line(p),
                    element: element.into(),
                    message: format!("a coordinate is not a number: {e}"),
                })?;
            match c[..] {
                [x, y, z] if c.iter().all(|v| v.is_finite()) => out.push(Vec3::new(x, y, z) * unit),
                _ => {
                    return Err(ImportError {
                        line: line(p),
                        element: element.into(),
                        message: format!(
                            "a CartesianPoint must have three finite coordinates, found {c:?}"
                        ),
                    })
                }
            }
        }
        if out.len() < 3 {
            return Err(ImportError {
                line: line(n),
                element: element.into(),
                message: format!(
                    "missing geometry: its PolyLoop has {} corners, at least 3 are needed",
                    out.len()
                ),
            });
        }
        Ok(out)
    };
    let planar = |n: Node, element: &str| -> Result<Vec<Vec3>, ImportError> {
        let Some(l) = child(n, "PlanarGeometry").and_then(|g| child(g, "PolyLoop")) else {
            return Err(ImportError {
                line: line(n),
                element: element.into(),
                message: "missing geometry: no PlanarGeometry/PolyLoop".into(),
            });
        };
        poly_loop(l, element)
    };

    let mut warnings = Vec::new();
    let materials = materials(&doc, &mut warnings);
    let campus = child(root, "Campus").ok_or_else(|| ImportError {
        line: line(root),
        element: "gbXML".into(),
        message: "missing geometry: no Campus".into(),
    })?;
    // The spaces, in file order, and each space's boundaries by surface.
    let mut spaces: Vec<Space> = Vec::new();
    let mut boundaries: HashMap<(String, String), Node> = HashMap::new();
    for building in children(campus, "Building") {
        for s in children(building, "Space") {
            let id = id_of(s, "Space")?;
            for b in children(s, "SpaceBoundary") {
                if let Some(surface) = b.attribute("surfaceIdRef") {
                    boundaries.insert((id.clone(), surface.to_owned()), b);
                }
            }
            spaces.push(Space {
                name: name_of(s).unwrap_or_else(|| id.clone()),
                id,
                line: line(s),
                faces: Vec::new(),
            });
        }
    }
    let index: HashMap<String, usize> = spaces
        .iter()
        .enumerate()
        .map(|(k, s)| (s.id.clone(), k))
        .collect();
    for surface in children(campus, "Surface") {
        let id = id_of(surface, "Surface")?;
        let element = format!("Surface `{id}`");
        let kind = surface.attribute("surfaceType").unwrap_or("");
        let adjacent: Vec<String> = children(surface, "AdjacentSpaceId")
            .filter_map(|a| a.attribute("spaceIdRef").map(str::to_owned))
            .collect();
        match kind {
            "Shade" | "Air" | "FreestandingColumn" | "EmbeddedColumn" => {
                warnings.push(format!(
                    "surface `{id}` of type `{kind}` is not imported (not mapped)"
                ));
                continue;
            }
            _ => {}
        }
        if adjacent.is_empty() {
            warnings.push(format!(
                "surface `{id}` bounds no space (no AdjacentSpaceId): not imported"
            ));
            continue;
        }
        let own = planar(surface, &element)?;
        let mut openings = Vec::new();
        for o in children(surface, "Opening") {
            let oid = id_of(o, "Opening")?;
            let o_element = format!("Opening `{oid}`");
            let o_kind = match o.attribute("openingType").unwrap_or("") {
                "FixedWindow" | "OperableWindow" | "FixedSkylight" | "OperableSkylight" => {
                    OpeningKind::Window
                }
                "SlidingDoor" | "NonSlidingDoor" => OpeningKind::Door,
                other => {
                    warnings.push(format!(
                        "opening `{oid}` of type `{other}` is not imported (not mapped)"
                    ));
                    continue;
                }
            };
            openings.push(ModelOpening {
                name: name_of(o).unwrap_or_else(|| oid.clone()),
                line: line(o),
                kind: o_kind,
                polygon: planar(o, &o_element)?,
                material: o
                    .attribute("windowTypeIdRef")
                    .or(o.attribute("constructionIdRef"))
                    .map(str::to_owned),
                id: oid,
            });
        }
        for (k, space) in adjacent.iter().enumerate() {
            let Some(&s) = index.get(space) else {
                return Err(ImportError {
                    line: line(surface),
                    element,
                    message: format!("its AdjacentSpaceId names no space: `{space}`"),
                });
            };
            let boundary = boundaries
                .get(&(space.clone(), id.clone()))
                .map(|b| planar(*b, &format!("SpaceBoundary of `{id}` in `{space}`")))
                .transpose()?;
            let mut openings = openings.clone();
            if let Some(b) = &boundary {
                // The space's face of the wall: its openings moved across into it.
                let normal = Polygon::new(b.clone()).normal();
                for o in &mut openings {
                    for c in &mut o.polygon {
                        *c = *c - normal * (*c - b[0]).dot(normal);
                    }
                }
            }
            let polygon = boundary.unwrap_or_else(|| own.clone());
            spaces[s].faces.push(ModelFace {
                id: id.clone(),
                name: name_of(surface).unwrap_or_else(|| id.clone()),
                line: line(surface),
                // Set from the space's geometry below.
                kind: ModelFaceKind::Wall,
                polygon,
                material: surface.attribute("constructionIdRef").map(str::to_owned),
                adjacent: adjacent
                    .iter()
                    .enumerate()
                    .find(|&(j, _)| j != k)
                    .map(|(_, other)| other.clone()),
                openings,
            });
        }
    }
    for space in &mut spaces {
        classify(space);
    }
    Ok(Model {
        spaces,
        materials,
        tolerance: TOLERANCE,
        grids: Vec::new(),
        warnings,
    })
}

/// The child elements of `n` named `name`.
fn children<'a, 'i>(n: Node<'a, 'i>, name: &'static str) -> impl Iterator<Item = Node<'a, 'i>> {
    n.children()
        .filter(move |c| c.is_element() && c.tag_name().name() == name)
}

/// The first child element of `n` named `name`.
fn child<'a, 'i>(n: Node<'a, 'i>, name: &'static str) -> Option<Node<'a, 'i>> {
    children(n, name).next()
}

/// Sets each face's kind from its geometry: vertical faces are walls; the others are the
/// floor below the space's mid-height and the ceiling above it.
fn classify(space: &mut Space) {
    let zs = space
        .faces
        .iter()
        .flat_map(|f| f.polygon.iter().map(|p| p.z));
    let (lo, hi) = zs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), z| {
        (a.min(z), b.max(z))
    });
    let middle = 0.5 * (lo + hi);
    for f in &mut space.faces {
        let normal = Polygon::new(f.polygon.clone()).normal();
        let mean = f.polygon.iter().map(|p| p.z).sum::<f64>() / f.polygon.len() as f64;
        f.kind = if normal.z.abs() < 1e-6 {
            ModelFaceKind::Wall
        } else if mean < middle {
            ModelFaceKind::Floor
        } else {
            ModelFaceKind::Ceiling
        };
    }
}

/// The visible reflectance and transmittance the file gives, by the id faces refer to:
/// `Construction`s (their own `Reflectance`, else that of the innermost layer's last
/// `Material`) and `WindowType`s. A reflectance is the interior visible one (`IntVisible`),
/// else the one of unstated side (`Visible`); glazing without a reflectance is listed.
fn materials(doc: &Document, warnings: &mut Vec<String>) -> BTreeMap<String, ModelMaterial> {
    let root = doc.root_element();
    let elements = |name: &'static str| {
        root.children()
            .filter(move |c| c.is_element() && c.tag_name().name() == name)
    };
    let value = |n: Node, tag: &str, types: &[&str]| -> Option<f64> {
        types.iter().find_map(|t| {
            n.children()
                .filter(|c| c.is_element() && c.tag_name().name() == tag)
                .find(|c| c.attribute("type") == Some(*t))
                .and_then(|c| c.text()?.trim().parse::<f64>().ok())
                .filter(|v| v.is_finite())
        })
    };
    let reflectance = |n: Node| value(n, "Reflectance", &["IntVisible", "Visible"]);
    let by_id = |name: &'static str| -> HashMap<&str, Node> {
        elements(name)
            .filter_map(|n| Some((n.attribute("id")?, n)))
            .collect()
    };
    let (layers, stuff) = (by_id("Layer"), by_id("Material"));
    let mut out = BTreeMap::new();
    for c in elements("Construction") {
        let Some(id) = c.attribute("id") else {
            continue;
        };
        let innermost = c
            .children()
            .filter(|l| l.is_element() && l.tag_name().name() == "LayerId")
            .filter_map(|l| layers.get(l.attribute("layerIdRef")?))
            .next_back()
            .and_then(|l| {
                l.children()
                    .filter(|m| m.is_element() && m.tag_name().name() == "MaterialId")
                    .filter_map(|m| stuff.get(m.attribute("materialIdRef")?))
                    .next_back()
                    .copied()
            });
        if let Some(r) = reflectance(c).or_else(|| innermost.and_then(reflectance)) {
            out.insert(
                id.to_owned(),
                ModelMaterial {
                    reflectance: [r; 3],
                    transmittance: None,
                    panes: None,
                },
            );
        }
    }
    for w in elements("WindowType") {
        let Some(id) = w.attribute("id") else {
            continue;
        };
        let tau = value(w, "Transmittance", &["Visible"]);
        match (reflectance(w), tau) {
            (Some(r), Some(t)) => {
                let glazes = w
                    .children()
                    .filter(|g| g.is_element() && g.tag_name().name() == "Glaze")
                    .count();
                out.insert(
                    id.to_owned(),
                    ModelMaterial {
                        reflectance: [r; 3],
                        transmittance: Some([t; 3]),
                        panes: (glazes > 0).then_some(glazes),
                    },
                );
            }
            _ => warnings.push(format!(
                "window type `{id}` lacks a visible transmittance or an interior visible \
                 reflectance: windows of this type need a material from the scene"
            )),
        }
    }
    out
}
