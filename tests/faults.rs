//! The machine failing under eigenrad: `build`, `solve`, `render`, `building` and `merge`
//! killed (SIGKILL) at a sweep of moments; under `build`, a full disk, a read-only cache
//! folder, a cache path that is a file, two builds at once. After each, the previous output is
//! byte-identical or the new one complete (the bytes of an uninterrupted run), the cache holds
//! only sound entries, and the next run proceeds.
//!
//! Mounting a small tmpfs needs root and a kernel that lets the test mount; without them the
//! tests that need one print `SKIPPED: ...` and pass.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::{eigenrad, listing, scene, scratch, stderr};

/// The small cube at 0.25 m (about 400 patches): a build of a fraction of a second to a few
/// seconds, long enough to be killed in its every stage.
fn cube() -> String {
    scene(0.25)
}

/// `eigenrad build scene -o out` with its cache in `cache`.
fn build_command(scene: &Path, out: &Path, cache: &Path) -> Command {
    let mut c = Command::new(eigenrad());
    c.args(["build", path(scene), "-o", path(out), "--modes", "4"])
        .env("EIGENRAD_CACHE_DIR", cache)
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    c
}

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// Builds and returns the run's standard error; the build must succeed.
fn build_ok(scene: &Path, out: &Path, cache: &Path) -> String {
    let o = build_command(scene, out, cache)
        .output()
        .expect("run eigenrad");
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "build failed: {err}");
    err
}

/// The scene file and the bytes of an uninterrupted build of it (and how long that took).
fn reference(dir: &Path) -> (PathBuf, Vec<u8>, Duration) {
    let scene = dir.join("cube.toml");
    std::fs::write(&scene, cube()).expect("write scene");
    let out = dir.join("reference.basis");
    let start = Instant::now();
    build_ok(&scene, &out, &dir.join("reference-cache"));
    let took = start.elapsed();
    (scene, std::fs::read(&out).expect("reference basis"), took)
}

/// Hidden temporaries (`.<name>.<pid>.tmp`) in `dir`.
fn temporaries(dir: &Path) -> Vec<String> {
    listing(dir)
        .into_iter()
        .filter(|n| n.starts_with('.') && n.ends_with(".tmp"))
        .collect()
}

/// A command's outputs: the files it writes, and their bytes before a run and after an
/// uninterrupted one.
struct Outputs {
    files: Vec<PathBuf>,
    previous: Vec<Vec<u8>>,
    complete: Vec<Vec<u8>>,
}

impl Outputs {
    /// `files` as they are now (the previous outputs) and after one uninterrupted `run`
    /// (which must succeed), then put back as they were; with the run's duration.
    fn around(files: Vec<PathBuf>, run: &dyn Fn() -> Command) -> (Outputs, Duration) {
        let previous = read_all(&files);
        let start = Instant::now();
        let o = run().stderr(Stdio::piped()).output().expect("run eigenrad");
        let took = start.elapsed();
        assert!(o.status.success(), "run failed: {}", stderr(&o));
        let complete = read_all(&files);
        for (file, bytes) in files.iter().zip(&previous) {
            assert_ne!(&read(file), bytes, "{} was not rewritten", file.display());
            std::fs::write(file, bytes).expect("restore previous");
        }
        let outputs = Outputs {
            files,
            previous,
            complete,
        };
        (outputs, took)
    }
}

fn read(file: &Path) -> Vec<u8> {
    std::fs::read(file).unwrap_or_else(|e| panic!("{} is gone: {e}", file.display()))
}

fn read_all(files: &[PathBuf]) -> Vec<Vec<u8>> {
    files.iter().map(|f| read(f)).collect()
}

/// `run` killed (SIGKILL: no handler runs, nothing is flushed) at twelve moments spread over an
/// uninterrupted run of `took`, from its start to past its end. After each kill every output is
/// its previous bytes or its complete ones, nothing but hidden temporaries is left beside
/// them, and the next run completes, finds every cache entry in `cache` sound and removes the
/// killed run's temporaries. Returns how many kills left the previous and the complete outputs.
fn killed_at_a_sweep_of_moments(
    run: &dyn Fn() -> Command,
    outputs: &Outputs,
    took: Duration,
    cache: &Path,
) -> (usize, usize) {
    let steps = 12;
    let mut outcomes = (0, 0);
    // Every folder the outputs are written in, with what it held before.
    let mut dirs: Vec<&Path> = outputs
        .files
        .iter()
        .map(|f| f.parent().expect("an output's folder"))
        .collect();
    dirs.sort();
    dirs.dedup();
    let names: Vec<String> = outputs
        .files
        .iter()
        .map(|f| {
            f.file_name()
                .expect("a file")
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    let before: Vec<Vec<String>> = dirs.iter().map(|d| listing(d)).collect();
    for k in 0..steps {
        let delay = took.mul_f64(k as f64 / (steps - 2) as f64);
        let mut child = run().stderr(Stdio::null()).spawn().expect("spawn eigenrad");
        std::thread::sleep(delay);
        let _ = child.kill();
        let _ = child.wait();
        for ((file, previous), complete) in outputs
            .files
            .iter()
            .zip(&outputs.previous)
            .zip(&outputs.complete)
        {
            let now = std::fs::read(file).expect("an output is never removed");
            if &now == previous {
                outcomes.0 += 1;
            } else {
                assert_eq!(
                    &now,
                    complete,
                    "killed after {delay:?}: {} is partial or other",
                    file.display()
                );
                outcomes.1 += 1;
            }
        }
        // Only hidden `.<name>.<pid>.tmp` temporaries of the outputs may be new.
        for (dir, before) in dirs.iter().zip(&before) {
            for name in listing(dir) {
                let temporary = names
                    .iter()
                    .any(|n| name.starts_with(&format!(".{n}.")) && name.ends_with(".tmp"));
                let the_cache =
                    cache.parent() == Some(*dir) && cache.file_name() == Some(name.as_ref());
                assert!(
                    before.contains(&name) || temporary || the_cache,
                    "killed after {delay:?}: unexpected file {name} in {}",
                    dir.display()
                );
            }
        }
        // The next run proceeds: every cache entry the killed run left is sound (none is
        // reported unusable), the outputs are complete, and the killed run's temporaries of
        // them are gone.
        let o = run().stderr(Stdio::piped()).output().expect("run eigenrad");
        let err = stderr(&o);
        assert!(o.status.success(), "after a kill at {delay:?}: {err}");
        assert!(
            !err.contains("unusable") && !err.contains("cannot read"),
            "killed after {delay:?}, the next run found: {err}"
        );
        assert_eq!(read_all(&outputs.files), outputs.complete);
        for dir in &dirs {
            assert!(
                temporaries(dir).is_empty(),
                "stale temporaries after the next run: {:?}",
                temporaries(dir)
            );
        }
        // Back to the previous outputs and an empty cache for the next moment.
        for (file, previous) in outputs.files.iter().zip(&outputs.previous) {
            std::fs::write(file, previous).expect("restore previous");
        }
        let _ = std::fs::remove_dir_all(cache);
    }
    outcomes
}

#[test]
fn a_build_killed_at_any_moment_loses_nothing_and_the_next_run_proceeds() {
    let dir = scratch("faults-kill");
    let (scene, complete, took) = reference(&dir);
    // The previous output: another basis of the same scene, to be kept or replaced whole.
    let out = dir.join("cube.basis");
    let coarser = dir.join("coarser.toml");
    std::fs::write(&coarser, common::scene(1.0)).expect("write scene");
    build_ok(&coarser, &out, &dir.join("previous-cache"));
    let cache = dir.join("cache");
    let run = || build_command(&scene, &out, &cache);
    let outputs = Outputs {
        files: vec![out.clone()],
        previous: vec![read(&out)],
        complete: vec![complete],
    };
    assert_ne!(outputs.previous, outputs.complete);
    let (kept, replaced) = killed_at_a_sweep_of_moments(&run, &outputs, took, &cache);
    eprintln!("{kept} kills left the previous basis, {replaced} the complete one (an uninterrupted build: {took:?})");
    std::fs::remove_dir_all(&dir).ok();
}

/// The small cube with a work-plane zone and its grid, for `solve --csv` and `render --plan`.
fn cube_with_a_grid() -> String {
    cube()
        + r#"
[[zone]]
name = "work_plane"
work_plane = { room = "room", height = 0.8, margin = 0.25, max_edge = 0.25, grid = {} }
"#
}

#[test]
fn solve_and_render_killed_at_any_moment_lose_nothing_and_the_next_run_proceeds() {
    let dir = scratch("faults-kill-solve-render");
    let scene = dir.join("cube.toml");
    std::fs::write(&scene, cube_with_a_grid()).expect("write scene");
    let cache = dir.join("cache");
    let eigenrad_with_cache = |args: &[&Path]| {
        let mut c = Command::new(eigenrad());
        c.args(args)
            .env("EIGENRAD_CACHE_DIR", &cache)
            .stdout(Stdio::null());
        c
    };
    // Previous outputs: files of the right kind holding something else.
    let csv = dir.join("grid.csv");
    let plan = dir.join("plan.png");
    let surfaces = dir.join("surfaces.svg");
    std::fs::write(&csv, "a previous table\n").expect("write");
    std::fs::write(&plan, b"a previous picture").expect("write");
    std::fs::write(&surfaces, "<svg>a previous picture</svg>").expect("write");

    let solve = || eigenrad_with_cache(&[Path::new("solve"), &scene, Path::new("--csv"), &csv]);
    let (outputs, took) = Outputs::around(vec![csv.clone()], &solve);
    let _ = std::fs::remove_dir_all(&cache);
    let (kept, replaced) = killed_at_a_sweep_of_moments(&solve, &outputs, took, &cache);
    eprintln!(
        "solve: {kept} kills left the previous table, {replaced} the complete one ({took:?})"
    );

    let render = || {
        eigenrad_with_cache(&[
            Path::new("render"),
            &scene,
            Path::new("--plan"),
            &plan,
            Path::new("--surfaces"),
            &surfaces,
        ])
    };
    let (outputs, took) = Outputs::around(vec![plan.clone(), surfaces.clone()], &render);
    let _ = std::fs::remove_dir_all(&cache);
    let (kept, replaced) = killed_at_a_sweep_of_moments(&render, &outputs, took, &cache);
    eprintln!("render: {kept} outputs left as they were, {replaced} complete ({took:?})");
    std::fs::remove_dir_all(&dir).ok();
}

/// `eigenrad building` (every room's part, then every controller's basis and the index) and
/// `eigenrad merge` (the bases and the index from the parts) killed at a sweep of moments.
/// The previous outputs are those of the same building meshed coarser.
#[test]
fn building_and_merge_killed_at_any_moment_lose_nothing_and_the_next_run_proceeds() {
    let dir = scratch("faults-kill-building");
    let out = dir.join("out");
    let parts = out.join("parts");
    let cache = dir.join("cache");
    let eigenrad_with_cache = |command: &str, manifest: &Path| {
        let mut c = Command::new(eigenrad());
        c.args([command, path(manifest), "--out", path(&out)])
            .env("EIGENRAD_CACHE_DIR", &cache)
            .stdout(Stdio::null());
        c
    };
    let manifest = common::small_building(&dir, 1.0, None);
    let o = eigenrad_with_cache("building", &manifest)
        .stderr(Stdio::piped())
        .output()
        .expect("run eigenrad");
    assert!(o.status.success(), "{}", stderr(&o));
    // The same rooms meshed finer: every part and basis changes; the index (the bases' sizes
    // and sections, which the mesh does not change) is given other previous bytes.
    common::small_building(&dir, 0.5, None);
    std::fs::write(out.join("building.json"), "{\"previous\": true}\n").expect("write");
    let bases = [
        out.join("a.basis"),
        out.join("b.basis"),
        out.join("building.json"),
    ];
    let mut files = vec![parts.join("cube-a.part"), parts.join("cube-b.part")];
    files.extend(bases.iter().cloned());

    let building = || eigenrad_with_cache("building", &manifest);
    let (outputs, took) = Outputs::around(files, &building);
    let _ = std::fs::remove_dir_all(&cache);
    let (kept, replaced) = killed_at_a_sweep_of_moments(&building, &outputs, took, &cache);
    eprintln!("building: {kept} outputs left as they were, {replaced} complete ({took:?})");

    // The merge of the finer parts over the coarser bases.
    let o = eigenrad_with_cache("building", &manifest)
        .stderr(Stdio::piped())
        .output()
        .expect("run eigenrad");
    assert!(o.status.success(), "{}", stderr(&o));
    for (file, previous) in bases.iter().zip(&outputs.previous[2..]) {
        std::fs::write(file, previous).expect("restore previous");
    }
    let merge = || eigenrad_with_cache("merge", &manifest);
    let (outputs, took) = Outputs::around(bases.to_vec(), &merge);
    let (kept, replaced) = killed_at_a_sweep_of_moments(&merge, &outputs, took, &cache);
    eprintln!("merge: {kept} outputs left as they were, {replaced} complete ({took:?})");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn two_builds_at_once_leave_a_valid_cache_and_output() {
    let dir = scratch("faults-concurrent");
    let (scene, complete, _) = reference(&dir);
    let out = dir.join("shared.basis");
    let cache = dir.join("cache");
    let children: Vec<_> = (0..2)
        .map(|_| build_command(&scene, &out, &cache).spawn().expect("spawn"))
        .collect();
    for child in children {
        let o = child.wait_with_output().expect("wait");
        assert!(o.status.success(), "{}", stderr(&o));
    }
    assert_eq!(std::fs::read(&out).expect("basis"), complete);
    // The entries both wrote are sound: a third run reads them without complaint.
    let err = build_ok(&scene, &out, &cache);
    assert!(!err.contains("unusable"), "{err}");
    assert!(temporaries(&dir).is_empty() && temporaries(&cache).is_empty());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_cache_path_that_is_a_file_is_a_warning_and_the_build_proceeds() {
    let dir = scratch("faults-cache-file");
    let (scene, complete, _) = reference(&dir);
    let cache = dir.join("not-a-folder");
    std::fs::write(&cache, b"a file").expect("write");
    let out = dir.join("cube.basis");
    let err = build_ok(&scene, &out, &cache);
    assert!(
        err.contains("warning: form factors not cached") && err.contains("not-a-folder"),
        "{err}"
    );
    assert_eq!(std::fs::read(&out).expect("basis"), complete);
    assert_eq!(std::fs::read(&cache).expect("file"), b"a file");
    std::fs::remove_dir_all(&dir).ok();
}

/// A tmpfs mounted at `at` with `options` (its size, `ro`), or why it could not be.
fn mount_tmpfs(at: &Path, options: &str) -> Result<(), String> {
    std::fs::create_dir_all(at).map_err(|e| e.to_string())?;
    let o = Command::new("mount")
        .args(["-t", "tmpfs", "-o", options, "tmpfs", path(at)])
        .output()
        .map_err(|e| format!("cannot run mount: {e}"))?;
    if o.status.success() {
        Ok(())
    } else {
        Err(format!(
            "mount -t tmpfs failed: {}",
            String::from_utf8_lossy(&o.stderr).trim()
        ))
    }
}

fn unmount(at: &Path) {
    let _ = Command::new("umount").arg(at).status();
}

#[test]
fn a_full_disk_is_an_error_naming_the_output_and_a_warning_for_the_cache() {
    let dir = scratch("faults-full");
    let (scene, complete, _) = reference(&dir);
    // 8 KiB: neither the scene's basis nor its form factors fit.
    let small = dir.join("small");
    if let Err(why) = mount_tmpfs(&small, "size=8k") {
        println!("SKIPPED: {why} (needs root and a kernel that allows mounts)");
        return;
    }
    let out = small.join("cube.basis");
    std::fs::write(&out, b"previous").expect("previous output fits");
    let o = build_command(&scene, &out, &dir.join("cache"))
        .output()
        .expect("run");
    let err = stderr(&o);
    let outcome = || {
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(err.contains(path(&out)), "path not named: {err}");
        assert!(err.contains("No space left on device"), "{err}");
        assert_eq!(std::fs::read(&out).expect("previous"), b"previous");
        assert!(temporaries(&small).is_empty(), "{:?}", listing(&small));
        // The cache on the full disk: a warning, and the basis written elsewhere in full.
        let elsewhere = dir.join("cube.basis");
        let err = build_ok(&scene, &elsewhere, &small.join("cache"));
        assert!(err.contains("warning: form factors not cached"), "{err}");
        assert_eq!(std::fs::read(&elsewhere).expect("basis"), complete);
        // What did fit (the small sensor rows) is whole: the next run reads it without
        // complaint, and no temporary is left.
        let cache = small.join("cache");
        let err = build_ok(&scene, &elsewhere, &cache);
        assert!(!err.contains("unusable"), "{err}");
        assert!(temporaries(&cache).is_empty(), "{:?}", listing(&cache));
    };
    let result = std::panic::catch_unwind(outcome);
    unmount(&small);
    std::fs::remove_dir_all(&dir).ok();
    if let Err(e) = result {
        std::panic::resume_unwind(e);
    }
}

#[test]
fn a_read_only_cache_folder_is_a_warning_and_the_build_proceeds() {
    let dir = scratch("faults-read-only");
    let (scene, complete, _) = reference(&dir);
    // Root ignores permission bits: a read-only mount is read-only for root too.
    let cache = dir.join("cache");
    if let Err(why) = mount_tmpfs(&cache, "ro,size=1m") {
        println!("SKIPPED: {why} (needs root and a kernel that allows mounts)");
        return;
    }
    let out = dir.join("cube.basis");
    let o = build_command(&scene, &out, &cache).output().expect("run");
    unmount(&cache);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("warning: form factors not cached") && err.contains(path(&cache)),
        "{err}"
    );
    assert_eq!(std::fs::read(&out).expect("basis"), complete);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_output_folder_removed_during_the_run_is_an_error_naming_the_output() {
    let dir = scratch("faults-removed");
    let (scene, _, took) = reference(&dir);
    let folder = dir.join("gone");
    std::fs::create_dir_all(&folder).expect("folder");
    let out = folder.join("cube.basis");
    let child = build_command(&scene, &out, &dir.join("cache"))
        .spawn()
        .expect("spawn");
    // Removed while the build computes (long before it writes).
    std::thread::sleep(took / 10);
    std::fs::remove_dir_all(&folder).expect("remove the output folder");
    let o = child.wait_with_output().expect("wait");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains(path(&out)), "path not named: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!folder.exists());
    std::fs::remove_dir_all(&dir).ok();
}
