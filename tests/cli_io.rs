//! The command never destroys an input and never panics on its output streams: an output
//! path naming a file the command reads (in any spelling, through a link) is refused before
//! any work, naming both; a reader that closes the pipe ends the command quietly with status
//! 141 (what a shell reports for tools that SIGPIPE ends); a failing standard output is an
//! error naming it.

mod common;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::Stdio;

use common::{good_basis, run, scene, scratch, stderr};

/// The exit status of a command that stops quietly because its reader closed the pipe.
const CLOSED_PIPE_STATUS: i32 = 141;

/// The Cornell box example (scene, OBJ and MTL) copied into `dir`.
fn cornell_box(dir: &Path) -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/cornell-box");
    for f in [
        "scene.toml",
        "CornellBox-Original.obj",
        "CornellBox-Original.mtl",
    ] {
        std::fs::copy(src.join(f), dir.join(f)).expect("copy example");
    }
    dir.join("scene.toml")
}

fn contents(paths: &[PathBuf]) -> Vec<Vec<u8>> {
    paths
        .iter()
        .map(|p| std::fs::read(p).expect("read input"))
        .collect()
}

fn utf8(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

#[test]
fn cli_build_refuses_an_output_that_is_one_of_its_inputs() {
    let dir = scratch("io-build");
    std::fs::create_dir_all(dir.join("sub")).expect("sub folder");
    let scene = cornell_box(&dir);
    let inputs = [
        scene.clone(),
        dir.join("CornellBox-Original.obj"),
        dir.join("CornellBox-Original.mtl"),
    ];
    let before = contents(&inputs);
    for output in [
        scene.clone(),
        dir.join("sub/../scene.toml"),
        dir.join("CornellBox-Original.obj"),
        dir.join("./CornellBox-Original.mtl"),
    ] {
        let o = run(&["build", utf8(&scene), "-o", utf8(&output), "--modes", "2"]);
        assert_eq!(o.status.code(), Some(1), "{}", output.display());
        let message = stderr(&o);
        assert!(
            message.contains(utf8(&output)) && message.contains("refusing to write over"),
            "{message}"
        );
        assert_eq!(contents(&inputs), before, "{}", output.display());
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[cfg(unix)]
#[test]
fn cli_build_refuses_a_link_to_its_scene() {
    let dir = scratch("io-link");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, scene_text()).expect("write scene");
    let link = dir.join("office.basis");
    std::os::unix::fs::symlink(&scene, &link).expect("symlink");
    let o = run(&["build", utf8(&scene), "-o", utf8(&link), "--modes", "2"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(&scene).expect("scene"),
        scene_text()
    );
    std::fs::remove_dir_all(&dir).ok();
}

fn scene_text() -> String {
    scene(1.0)
}

#[test]
fn cli_verify_refuses_to_write_its_report_over_the_scene() {
    // A scene file named like the report `verify --out .` writes (`<scene name>.md`).
    let dir = scratch("io-verify");
    let scene = dir.join("cube.md");
    std::fs::write(&scene, scene_text()).expect("write scene");
    let o = run(&["verify", utf8(&scene), "--out", utf8(&dir)]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("refusing to write over"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read_to_string(&scene).expect("scene"),
        scene_text()
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn cli_stops_quietly_when_its_reader_closes_the_pipe() {
    let dir = scratch("io-pipe");
    let basis = good_basis(&dir);
    let scene = dir.join("scene.toml");
    for args in [
        vec!["eval", utf8(&basis), "--patches"],
        vec!["form-factors", utf8(&scene)],
        vec!["inspect", utf8(&basis), "--json"],
    ] {
        let mut child = common::command()
            .args(&args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start eigenrad");
        // Read one line, as `| head -1` does, then close the pipe.
        let mut first = String::new();
        let stdout = child.stdout.take().expect("stdout");
        BufReader::new(stdout)
            .read_line(&mut first)
            .expect("first line");
        let o = child.wait_with_output().expect("wait");
        let code = o.status.code();
        // Short outputs may fit the pipe's buffer before it closes: then the command succeeds.
        assert!(
            code == Some(CLOSED_PIPE_STATUS) || code == Some(0),
            "{args:?}: {:?} {}",
            o.status,
            stderr(&o)
        );
        assert!(o.stderr.is_empty(), "{args:?}: {}", stderr(&o));
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn cli_closed_pipe_on_a_long_output_ends_with_the_pipe_status() {
    // 600 patches in JSON: far more than a pipe's buffer holds.
    let dir = scratch("io-pipe-long");
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene(0.2)).expect("write scene");
    let mut child = common::command()
        .args(["solve", utf8(&path), "--patches", "--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start eigenrad");
    drop(child.stdout.take());
    let o = child.wait_with_output().expect("wait");
    assert_eq!(o.status.code(), Some(CLOSED_PIPE_STATUS), "{}", stderr(&o));
    assert!(o.stderr.is_empty(), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).ok();
}

#[cfg(target_os = "linux")]
#[test]
fn cli_full_standard_output_is_an_error_naming_it() {
    let dir = scratch("io-full");
    let basis = good_basis(&dir);
    let full = std::fs::File::create("/dev/full").expect("/dev/full");
    let o = common::command()
        .args(["inspect", utf8(&basis)])
        .stdout(full)
        .output()
        .expect("run eigenrad");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("standard output"), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn cli_build_refuses_an_unwritable_output_or_a_meaningless_tolerance_before_any_work() {
    let dir = scratch("io-args");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, scene_text()).expect("write scene");
    let folder = utf8(&dir).to_string();
    let missing = dir.join("missing/x.basis");
    for (args, says) in [
        (vec!["-o", folder.as_str()], "is a folder"),
        (vec!["-o", utf8(&missing)], "its folder does not exist"),
        (
            vec!["-o", "x.basis", "--tolerance", "nan"],
            "not a relative error",
        ),
        (
            vec!["-o", "x.basis", "--tolerance", "0"],
            "not a relative error",
        ),
    ] {
        let mut all = vec!["build", utf8(&scene)];
        all.extend(&args);
        let o = run(&all);
        assert!(!o.status.success(), "{args:?}");
        assert!(stderr(&o).contains(says), "{args:?}: {}", stderr(&o));
    }
    std::fs::remove_dir_all(&dir).ok();
}
