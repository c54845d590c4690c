//! The files a scene is read from, found without meshing it: the scene file, the OBJ files it
//! names and their MTL libraries. Commands check their outputs against these before any work,
//! so that no output ever replaces an input.

use std::path::{Path, PathBuf};

use super::error::SceneError;
use super::file::SceneFile;
use super::obj::mtl_paths;

/// A scene's name and the files it is read from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneInputs {
    /// `scene.name`.
    pub name: String,
    /// The scene file, then every OBJ file and the MTL files each names, the building models
    /// of the `[[import]]`s, then the
    /// luminaires' photometric files (each once), as the scene's loader would open them
    /// (relative to the scene's folder). Files that do not exist are listed too: loading will
    /// report them.
    pub files: Vec<PathBuf>,
}

/// Reads the scene file at `path` far enough to list its inputs (its TOML, not its meshes).
pub fn inputs(path: &Path) -> Result<SceneInputs, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|reason| SceneError::Read {
        path: path.to_path_buf(),
        reason,
    })?;
    let file = SceneFile::parse(&text, path)?;
    let dir = path.parent().unwrap_or(Path::new(""));
    let mut files = vec![path.to_path_buf()];
    for o in &file.obj {
        let obj = dir.join(o.get_ref().file.get_ref());
        // An unreadable OBJ names no MTL; the loader reports it.
        let mtls = std::fs::read_to_string(&obj)
            .map(|t| mtl_paths(&obj, &t))
            .unwrap_or_default();
        files.push(obj);
        files.extend(mtls);
    }
    for i in &file.import {
        files.push(super::import::model_path(path, i.get_ref().file.get_ref()));
    }
    for luminaire in &file.luminaire {
        let photometry = dir.join(luminaire.get_ref().file.get_ref());
        if !files.contains(&photometry) {
            files.push(photometry);
        }
    }
    // A sensor's response table is an input too: no output may replace it.
    let tables = file.sensor.iter().filter_map(|s| {
        let r = s.get_ref().response.as_ref()?;
        r.get_ref().file.as_ref().map(|f| dir.join(f.get_ref()))
    });
    files.extend(tables);
    Ok(SceneInputs {
        name: file.scene.name,
        files,
    })
}
