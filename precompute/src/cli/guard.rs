//! No output ever replaces an input: before any work, a command compares every path it will
//! write with every file it reads, after resolving `..`, symbolic links and hard links.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// Fails with [`Error::OutputIsInput`] if any of `outputs` is, or would overwrite, one of
/// `inputs`.
pub fn check_outputs(outputs: &[PathBuf], inputs: &[PathBuf]) -> Result<()> {
    for output in outputs {
        let target = resolve(output);
        for input in inputs {
            if same_file(output, &target, input) {
                return Err(Error::OutputIsInput {
                    output: output.clone(),
                    input: input.clone(),
                });
            }
        }
    }
    Ok(())
}

/// Fails, before any work, when `path` cannot become a file: it is a folder, or its folder
/// does not exist.
pub fn check_file_output(path: &Path) -> Result<()> {
    let problem = if path.is_dir() {
        Some("is a folder: name the file to write")
    } else {
        match path.parent() {
            Some(d) if !d.as_os_str().is_empty() && !d.is_dir() => {
                Some("its folder does not exist")
            }
            _ => None,
        }
    };
    match problem {
        Some(problem) => Err(Error::Io {
            path: path.to_path_buf(),
            reason: std::io::Error::other(problem),
        }),
        None => Ok(()),
    }
}

/// The path `path` names once its folder's links and `..` are resolved: the file itself when
/// it exists (a link to an input resolves to the input), otherwise its resolved folder joined
/// with its name. Falls back to the path as given when the folder does not exist (then it
/// cannot hold an input either).
fn resolve(path: &Path) -> PathBuf {
    if let Ok(p) = path.canonicalize() {
        return p;
    }
    let name = path.file_name();
    let parent = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    match (parent.canonicalize(), name) {
        (Ok(dir), Some(name)) => dir.join(name),
        _ => path.to_path_buf(),
    }
}

/// Whether writing `output` (resolved to `target`) would change the file `input`.
fn same_file(output: &Path, target: &Path, input: &Path) -> bool {
    if resolve(input) == target {
        return true;
    }
    same_inode(output, input)
}

/// Two names of one file (hard links), where the platform can tell.
#[cfg(unix)]
fn same_inode(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_inode(_: &Path, _: &Path) -> bool {
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("eigenrad-guard-{name}-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        dir
    }

    #[test]
    fn an_output_naming_an_input_in_any_spelling_is_refused() {
        let dir = scratch("spelling");
        let input = dir.join("scene.toml");
        std::fs::write(&input, "x").unwrap();
        for output in [
            input.clone(),
            dir.join("sub/../scene.toml"),
            dir.join("./scene.toml"),
        ] {
            let err = check_outputs(std::slice::from_ref(&output), std::slice::from_ref(&input))
                .unwrap_err();
            assert!(
                matches!(err, Error::OutputIsInput { .. }),
                "{}: {err}",
                output.display()
            );
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    #[cfg(unix)]
    #[test]
    fn links_to_an_input_are_refused() {
        let dir = scratch("links");
        let input = dir.join("scene.toml");
        std::fs::write(&input, "x").unwrap();
        let soft = dir.join("soft.basis");
        std::os::unix::fs::symlink(&input, &soft).unwrap();
        let hard = dir.join("hard.basis");
        std::fs::hard_link(&input, &hard).unwrap();
        let linked_dir = dir.join("linked");
        std::os::unix::fs::symlink(&dir, &linked_dir).unwrap();
        for output in [soft, hard, linked_dir.join("scene.toml")] {
            assert!(
                check_outputs(std::slice::from_ref(&output), std::slice::from_ref(&input)).is_err(),
                "{}",
                output.display()
            );
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn other_outputs_pass() {
        let dir = scratch("other");
        let input = dir.join("scene.toml");
        std::fs::write(&input, "x").unwrap();
        let outputs = [
            dir.join("office.basis"),
            dir.join("sub/scene.toml"),
            dir.join("missing/scene.toml"),
        ];
        check_outputs(&outputs, &[input]).unwrap();
        std::fs::remove_dir_all(&dir).ok();
    }
}
