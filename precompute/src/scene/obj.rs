//! Geometry and materials from an OBJ/MTL pair (via `tobj`).
//!
//! MTL `Kd` is the reflectance and `Ke` the emitted radiance (exitance π·Ke) or, with
//! `ke = "exitance"`, the exitance at level 1; photopic scenes reduce RGB to
//! one band with the luminance weights of ITU-R BT.709 (0.2126, 0.7152, 0.0722).

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use toml::Spanned;

use super::context::{Ctx, MaterialInfo, RawSurface, LARGEST_COORDINATE};
use super::error::{Location, SceneError};
use super::file::{KeMeaning, NameBy, ObjDef, UpAxis};
use crate::geometry::Vec3;

/// What one OBJ file contributes.
pub(crate) struct ObjContent {
    /// Its surfaces, in the order they first appear in the file.
    pub surfaces: Vec<RawSurface>,
    /// The 1-based line of each surface's faces' `f` statements, as `surfaces[k].faces`
    /// (`None` if the faces could not be matched to the lines).
    pub lines: Vec<Vec<Option<usize>>>,
    /// Its MTL materials (name, values), in MTL order.
    pub materials: Vec<(String, MaterialInfo)>,
}

/// Reads the OBJ file of one `[[obj]]` entry and its MTL files.
pub(crate) fn load(ctx: &Ctx, def: &Spanned<ObjDef>) -> Result<ObjContent, SceneError> {
    let o = def.get_ref();
    let at = ctx.at(&o.file);
    let path = ctx
        .origin
        .parent()
        .unwrap_or(Path::new(""))
        .join(o.file.get_ref());
    let transform = Transform::new(ctx, o)?;
    let Loaded {
        models,
        materials,
        mtls,
        face_lines,
    } = read(o, &at, &path, &transform)?;
    // Materials are located in their MTL file when there is one; tobj does not say which
    // file a material came from when there are several.
    let obj_at = Location::file(&path);
    let mtl_at = match mtls.as_slice() {
        [one] => Location::file(one),
        _ => obj_at.clone(),
    };
    let infos = material_infos(ctx, &materials, &mtl_at, o.ke)?;
    let max_edge = ctx.optional_length(o.max_edge.as_ref(), "obj.max_edge")?;
    let placed = Placement {
        transform,
        max_edge,
        material_at: at,
        at: obj_at,
    };
    let (surfaces, lines) = surfaces(o, &models, &materials, &placed, &face_lines);
    Ok(ObjContent {
        surfaces,
        lines,
        materials: infos,
    })
}

/// An OBJ file as tobj reads it.
struct Loaded {
    models: Vec<tobj::Model>,
    materials: Vec<tobj::Material>,
    /// Its MTL files.
    mtls: Vec<PathBuf>,
    /// The 1-based line of every `f` statement, in file order: the faces of `models` in
    /// order (tobj starts a model at each group or material change and keeps the faces' order).
    face_lines: Vec<usize>,
}

/// The OBJ file at `path` (named by `o`, written at `at`, placed by `transform`) and its MTL
/// files, every file checked first so that an error names its line.
fn read(
    o: &ObjDef,
    at: &Location,
    path: &Path,
    transform: &Transform,
) -> Result<Loaded, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|source| match source.kind() {
        std::io::ErrorKind::NotFound => SceneError::MissingFile {
            at: at.clone(),
            field: "obj.file".into(),
            path: path.to_path_buf(),
        },
        _ => SceneError::Read {
            path: path.to_path_buf(),
            reason: source,
        },
    })?;
    // tobj reports a missing MTL without its name: look for it first, so the error can say.
    let mtls = mtl_paths(path, &text);
    for mtl in mtls.iter().cloned() {
        if !mtl.is_file() {
            return Err(SceneError::MissingFile {
                at: at.clone(),
                field: format!("obj.file (mtllib of {})", path.display()),
                path: mtl,
            });
        }
    }
    let options = tobj::LoadOptions {
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let obj_error = |what: &str, e: tobj::LoadError| SceneError::Obj {
        at: at.clone(),
        field: o.file.get_ref().clone(),
        message: format!("{what}: {e}"),
    };
    // tobj says what failed but not where: find the line first, so the error can say.
    let located = |file: &Path, (line, message): (usize, String)| SceneError::Obj {
        at: Location {
            file: file.to_path_buf(),
            line: Some(line),
        },
        field: o.file.get_ref().clone(),
        message,
    };
    if let Some(problem) = obj_problem(&text, transform) {
        return Err(located(path, problem));
    }
    let mut defined = HashSet::new();
    // What tobj is given for each MTL file: its text as checked here, colours normalised.
    let mut for_tobj: Vec<(PathBuf, String)> = Vec::new();
    for mtl in &mtls {
        let bytes = std::fs::read(mtl).map_err(|reason| SceneError::Read {
            path: mtl.clone(),
            reason,
        })?;
        let text = match String::from_utf8(bytes) {
            Ok(text) => text,
            Err(e) => {
                let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
                let line = valid.iter().filter(|&&b| b == b'\n').count() + 1;
                return Err(located(
                    mtl,
                    (line, "not UTF-8 text: is this an MTL file?".into()),
                ));
            }
        };
        if let Some(problem) = mtl_problem(&text) {
            return Err(located(mtl, problem));
        }
        defined.extend(material_names(&text));
        for_tobj.push((mtl.clone(), mtl_for_tobj(&text)));
    }
    if let Some((line, name)) = undefined_material(&text, &defined) {
        let known = if defined.is_empty() {
            "its MTL files define none".to_string()
        } else {
            let mut names: Vec<&str> = defined.iter().map(String::as_str).collect();
            names.sort_unstable();
            format!("its MTL files define {}", names.join(", "))
        };
        return Err(located(
            path,
            (line, format!("`usemtl {name}` names no material ({known})")),
        ));
    }
    // The OBJ and MTL texts checked above are the ones tobj reads: no second read of a file
    // that may have changed, and MTL colours in the form tobj parses.
    let dir = path.parent().unwrap_or(Path::new(""));
    let (models, materials) = tobj::load_obj_buf(&mut text.as_bytes(), &options, |name| {
        let full = dir.join(name);
        match for_tobj.iter().find(|(mtl, _)| *mtl == full) {
            Some((_, text)) => tobj::load_mtl_buf(&mut text.as_bytes()),
            None => tobj::load_mtl(full),
        }
    })
    .map_err(|e| obj_error("OBJ", e))?;
    let materials = materials.map_err(|e| obj_error("MTL", e))?;
    let face_lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| l.split_whitespace().next() == Some("f"))
        .map(|(n, _)| n + 1)
        .collect();
    Ok(Loaded {
        models,
        materials,
        mtls,
        face_lines,
    })
}

/// The MTL materials in the scene's bands: `Kd` as reflectance, `Ke` as the emitted radiance
/// or the exitance (`ke`), checked as exitance in RGB and located at `mtl_at`.
fn material_infos(
    ctx: &Ctx,
    materials: &[tobj::Material],
    mtl_at: &Location,
    ke: KeMeaning,
) -> Result<Vec<(String, MaterialInfo)>, SceneError> {
    let mut infos = Vec::with_capacity(materials.len());
    for m in materials {
        let field = format!("MTL material `{}`", m.name);
        let kd = m.diffuse.unwrap_or([0.0; 3]);
        let exitance = m
            .emissive
            .unwrap_or([0.0; 3])
            .map(|k| k * ke.exitance_per_ke());
        // Checked in RGB, before a photopic scene reduces them to one band.
        let kd = ctx.check_reflectance(kd.to_vec(), mtl_at, &format!("{field} Kd"))?;
        let ke_field = match ke {
            KeMeaning::Radiance => format!("{field} Ke (radiance; exitance π·Ke)"),
            KeMeaning::Exitance => format!("{field} Ke (exitance)"),
        };
        let ke = ctx.check_exitance(exitance.to_vec(), mtl_at, &ke_field)?;
        let reflectance = ctx.bands_of_rgb([kd[0], kd[1], kd[2]]);
        let emission = ctx.bands_of_rgb([ke[0], ke[1], ke[2]]);
        infos.push((
            m.name.clone(),
            MaterialInfo {
                reflectance,
                emission,
                glazing: None,
            },
        ));
    }
    Ok(infos)
}

/// What every surface of one OBJ file shares.
struct Placement {
    /// File coordinates to the scene's, metres.
    transform: Transform,
    /// `obj.max_edge`, metres.
    max_edge: Option<f64>,
    /// Where the `[[obj]]` entry names the file (for unknown-material errors).
    material_at: Location,
    /// The OBJ file itself.
    at: Location,
}

/// The surfaces of the models, in the order they first appear: one per group (or material,
/// with `name_by = "material"`); a group holding several materials gets one surface per
/// material, named `<group>.<material>`; with each surface, the line of each of its faces
/// (`face_lines`: every face's, in file order).
fn surfaces(
    o: &ObjDef,
    models: &[tobj::Model],
    materials: &[tobj::Material],
    placed: &Placement,
    face_lines: &[usize],
) -> (Vec<RawSurface>, Vec<Vec<Option<usize>>>) {
    let total: usize = models.iter().map(|m| face_count(&m.mesh)).sum();
    let mut line_of = face_lines
        .iter()
        .map(|&l| Some(l).filter(|_| total == face_lines.len()));
    let material_name =
        |id: Option<usize>| id.and_then(|i| materials.get(i)).map(|m| m.name.clone());
    // (key, material) per model.
    let keys: Vec<(String, Option<String>)> = models
        .iter()
        .map(|m| {
            let mat = material_name(m.mesh.material_id);
            let key = match (o.name_by, &mat) {
                (NameBy::Material, Some(mat)) => mat.clone(),
                _ => m.name.clone(),
            };
            (key, mat)
        })
        .collect();
    let mut surfaces: Vec<RawSurface> = Vec::new();
    let mut lines: Vec<Vec<Option<usize>>> = Vec::new();
    let mut seen: Vec<HashSet<Vec<[u64; 3]>>> = Vec::new();
    for (model, (key, mat)) in models.iter().zip(&keys) {
        let mixed = keys.iter().any(|(k, m)| k == key && m != mat);
        let mut name = match (mixed, mat) {
            (true, Some(mat)) => format!("{key}.{mat}"),
            _ => key.clone(),
        };
        if let Some(prefix) = &o.prefix {
            name = format!("{prefix}.{name}");
        }
        let index = match surfaces.iter().position(|s| s.name == name) {
            Some(i) => i,
            None => {
                surfaces.push(RawSurface {
                    name,
                    material: mat.clone().unwrap_or_default(),
                    material_at: placed.material_at.clone(),
                    faces: Vec::new(),
                    max_edge: placed.max_edge,
                    at: placed.at.clone(),
                    exterior: o.exterior,
                });
                seen.push(HashSet::new());
                lines.push(Vec::new());
                surfaces.len() - 1
            }
        };
        for corners in faces(&model.mesh, &placed.transform) {
            let line = line_of.next().flatten();
            if o.drop_duplicate_faces {
                let mut key: Vec<[u64; 3]> = corners
                    .iter()
                    .map(|c| [c.x.to_bits(), c.y.to_bits(), c.z.to_bits()])
                    .collect();
                key.sort_unstable();
                if !seen[index].insert(key) {
                    continue;
                }
            }
            surfaces[index].faces.push(corners);
            lines[index].push(line);
        }
    }
    (surfaces, lines)
}

/// The number of faces of one mesh.
fn face_count(mesh: &tobj::Mesh) -> usize {
    if mesh.face_arities.is_empty() {
        mesh.indices.len() / 3
    } else {
        mesh.face_arities.len()
    }
}

/// The faces of one mesh, corners in scene coordinates (metres).
fn faces(mesh: &tobj::Mesh, transform: &Transform) -> Vec<Vec<Vec3>> {
    let mut start = 0usize;
    let arities: Vec<usize> = if mesh.face_arities.is_empty() {
        vec![3; mesh.indices.len() / 3]
    } else {
        mesh.face_arities.iter().map(|&a| a as usize).collect()
    };
    let mut out = Vec::with_capacity(arities.len());
    for arity in arities {
        let corners: Vec<Vec3> = mesh
            .indices
            .get(start..start + arity)
            .unwrap_or(&[])
            .iter()
            .map(|&i| {
                let i = i as usize * 3;
                let c = mesh.positions.get(i..i + 3).unwrap_or(&[f64::NAN; 3]);
                transform.apply(Vec3::new(c[0], c[1], c[2]))
            })
            .collect();
        start += arity;
        out.push(corners);
    }
    out
}

/// The first malformed line of an OBJ file (1-based) and what is wrong with it: a vertex
/// whose coordinates are not numbers or lie beyond [`LARGEST_COORDINATE`] once placed by
/// `transform`, a face with fewer than 3 corners or a corner index that is not a vertex of
/// the file.
fn obj_problem(text: &str, transform: &Transform) -> Option<(usize, String)> {
    let total = text
        .lines()
        .filter(|l| l.split_whitespace().next() == Some("v"))
        .count();
    let mut seen = 0usize;
    for (n, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("");
        let mut fields = line.split_whitespace();
        match fields.next() {
            Some("v") => {
                seen += 1;
                let values: Vec<&str> = fields.collect();
                if values.len() < 3 {
                    return Some((
                        n + 1,
                        format!("vertex `{}` needs 3 coordinates", line.trim()),
                    ));
                }
                if let Some(bad) = values.iter().find(|v| v.parse::<f64>().is_err()) {
                    return Some((n + 1, format!("vertex coordinate `{bad}` is not a number")));
                }
                if let Some(bad) = values
                    .iter()
                    .find(|v| v.parse::<f64>().is_ok_and(|x| !x.is_finite()))
                {
                    return Some((n + 1, format!("vertex coordinate `{bad}` is not finite")));
                }
                if let Some(problem) = out_of_range(&values, transform) {
                    return Some((n + 1, problem));
                }
            }
            Some("f") => {
                let corners: Vec<&str> = fields.collect();
                if corners.len() < 3 {
                    return Some((
                        n + 1,
                        format!("face `{}` needs at least 3 corners", line.trim()),
                    ));
                }
                for c in corners {
                    let index = c.split('/').next().unwrap_or("");
                    if index
                        .parse::<i64>()
                        .is_ok_and(|i| i > 0 && (i as usize) <= total && (i as usize) > seen)
                    {
                        return Some((
                            n + 1,
                            format!(
                                "face corner `{c}` uses a vertex defined further down the \
                                 file (only {seen} vertices before this line): define vertices \
                                 before the faces that use them"
                            ),
                        ));
                    }
                    let valid = match index.parse::<i64>() {
                        Ok(i) if i > 0 => (i as usize) <= total,
                        Ok(i) if i < 0 => i.unsigned_abs() as usize <= seen,
                        _ => false,
                    };
                    if !valid {
                        return Some((
                            n + 1,
                            format!(
                                "face corner `{c}` is not a vertex of the file ({total} \
                                 vertices; indices start at 1, negative ones count back)"
                            ),
                        ));
                    }
                }
            }
            _ => {}
        }
    }
    let faces = text
        .lines()
        .any(|l| l.split_whitespace().next() == Some("f"));
    (!faces).then(|| {
        (
            1,
            "no faces (`f` lines): is this an OBJ file, and does it hold the geometry?".into(),
        )
    })
}

/// What is wrong with a vertex line's coordinates `values` (numbers, checked finite) when one
/// of them, scaled, or the placed point lies beyond [`LARGEST_COORDINATE`]; `None` if none.
fn out_of_range(values: &[&str], transform: &Transform) -> Option<String> {
    let c: Vec<f64> = values.iter().map(|v| v.parse().unwrap_or(0.0)).collect();
    let metres_per_unit = transform.scale * transform.unit;
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        let metres = c.get(k).copied().unwrap_or(0.0) * metres_per_unit;
        if metres.abs() > LARGEST_COORDINATE {
            return Some(format!(
                "vertex coordinate {axis} = `{}` is {:.3e} m from the origin (with `unit` and \
                 `scale`), beyond the ±{LARGEST_COORDINATE:.0e} m a scene may span (a unit or \
                 `scale` mistake?)",
                values[k],
                metres.abs()
            ));
        }
    }
    let placed = transform.apply(Vec3::new(c[0], c[1], c[2]));
    let axis = (0..3).find(|&k| placed.axis(k).abs() > LARGEST_COORDINATE)?;
    Some(format!(
        "vertex `{}` is placed at {:.3e} m on the scene's {} axis (with `translate`), beyond \
         the ±{LARGEST_COORDINATE:.0e} m a scene may span",
        values.join(" "),
        placed.axis(axis),
        ["x", "y", "z"][axis]
    ))
}

/// The names an MTL file defines (`newmtl NAME`).
fn material_names(text: &str) -> Vec<String> {
    text.lines()
        .filter_map(|l| l.trim_start().strip_prefix("newmtl "))
        .map(|name| name.trim().to_string())
        .collect()
}

/// The first `usemtl` line (1-based) naming a material outside `defined`, and that name.
fn undefined_material(text: &str, defined: &HashSet<String>) -> Option<(usize, String)> {
    text.lines().enumerate().find_map(|(n, l)| {
        let name = l.trim_start().strip_prefix("usemtl ")?.trim();
        (!defined.contains(name)).then(|| (n + 1, name.to_string()))
    })
}

/// The first malformed line of an MTL file (1-based): a colour or scalar that is not numbers.
fn mtl_problem(text: &str) -> Option<(usize, String)> {
    for (n, line) in text.lines().enumerate() {
        let mut fields = line.split('#').next().unwrap_or("").split_whitespace();
        let Some(key) = fields.next() else { continue };
        let expected = match key {
            "Ka" | "Kd" | "Ks" | "Ke" | "Tf" => 3,
            "Ns" | "Ni" | "d" | "Tr" => 1,
            _ => continue,
        };
        let values: Vec<&str> = fields.collect();
        if let Some(bad) = values.iter().find(|v| v.parse::<f64>().is_err()) {
            return Some((n + 1, format!("`{key}` value `{bad}` is not a number")));
        }
        // A colour is three numbers or one grey value ([`mtl_for_tobj`] writes it as three).
        let counts = if expected == 3 { "1 or 3" } else { "1" };
        if !(values.len() == expected || values.len() == 1) {
            return Some((
                n + 1,
                format!("`{key}` takes {counts} number(s), found {}", values.len()),
            ));
        }
    }
    None
}

/// An MTL file's text as tobj parses it: a colour (`Ka`, `Kd`, `Ks`, `Ke`) given as one grey
/// value, which the MTL format allows, written as three (tobj takes exactly three and fails
/// on fewer), and comments after a colour or scalar removed (tobj would read them as values).
fn mtl_for_tobj(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 64);
    for line in text.lines() {
        let data = line.split('#').next().unwrap_or("");
        let mut fields = data.split_whitespace();
        match fields.next() {
            Some(key @ ("Ka" | "Kd" | "Ks" | "Ke")) => {
                let values: Vec<&str> = fields.collect();
                match values.as_slice() {
                    [grey] => out.push_str(&format!("{key} {grey} {grey} {grey}")),
                    _ => out.push_str(data),
                }
            }
            Some("Ns" | "Ni" | "d" | "Tr" | "Tf") => out.push_str(data),
            _ => out.push_str(line),
        }
        out.push('\n');
    }
    out
}

/// The MTL files an OBJ file names, resolved against its folder.
pub(crate) fn mtl_paths(obj: &Path, text: &str) -> Vec<PathBuf> {
    let dir = obj.parent().unwrap_or(Path::new(""));
    text.lines()
        .filter_map(|l| l.trim_start().strip_prefix("mtllib "))
        .map(|name| dir.join(name.trim()))
        .collect()
}

/// OBJ coordinates to metres: turn the file's up axis to z, scale, translate, convert units.
struct Transform {
    up: UpAxis,
    scale: f64,
    translate: Vec3,
    unit: f64,
}

impl Transform {
    fn new(ctx: &Ctx, o: &ObjDef) -> Result<Self, SceneError> {
        let scale = match &o.scale {
            Some(s) => {
                let v = *s.get_ref();
                if !(v.is_finite() && v > 0.0) {
                    return Err(SceneError::OutOfRange {
                        at: ctx.at(s),
                        field: "obj.scale".into(),
                        message: format!("must be a positive finite number, found {v}"),
                    });
                }
                v
            }
            None => 1.0,
        };
        let translate = match &o.translate {
            Some(t) => ctx.point(t, "obj.translate")?,
            None => Vec3::ZERO,
        };
        Ok(Transform {
            up: o.up,
            scale,
            translate,
            unit: ctx.unit,
        })
    }

    fn apply(&self, p: Vec3) -> Vec3 {
        // y up to z up: a proper rotation of +90° about x, so windings are kept.
        let p = match self.up {
            UpAxis::Y => Vec3::new(p.x, -p.z, p.y),
            UpAxis::Z => p,
        };
        p * (self.scale * self.unit) + self.translate
    }
}
