//! What `eigenrad build` says while it runs when nobody watches (standard error to a file):
//! its plan before the form factors (operator, expected time and memory, the basis' size
//! against the flash budget), a line at the start and at the end of every stage, and a
//! warning before the long stages when the basis will not fit, naming the sections and a fix
//! that really fits.

mod common;

use std::fs::File;
use std::process::Stdio;

use common::{command, scene, scratch};
use eigenrad_precompute::flash::FlashBudget;
use eigenrad_precompute::pipeline::{self, BuildOptions, ModeSelection, LINE_PREFIX};

/// The stages every build of the cube runs, in order, and whether the time model gives them
/// an estimate.
const STAGES: [(&str, bool); 9] = [
    ("scene and meshing", false),
    ("form factors", true),
    ("sensors and zones", true),
    ("light sources", false),
    ("eigenbasis", true),
    ("exact channel responses (LU or CG)", true),
    ("exact reference of the report's cases", true),
    ("serialization", true),
    ("verification through the runtime", true),
];

/// Builds the cube with `extra` flags, standard error to a file; returns that file's lines
/// and the report on standard output.
fn build_logged(test: &str, extra: &[&str]) -> (Vec<String>, String) {
    let dir = scratch(test);
    let scene_path = dir.join("scene.toml");
    std::fs::write(&scene_path, scene(0.5)).expect("write scene");
    let log = dir.join("stderr.log");
    let out = dir.join("cube.basis");
    let o = command()
        .args(["build", path(&scene_path), "-o", path(&out), "--modes", "4"])
        .args(extra)
        .stderr(Stdio::from(File::create(&log).expect("log file")))
        .stdout(Stdio::piped())
        .output()
        .expect("run eigenrad");
    let text = std::fs::read_to_string(&log).expect("read log");
    assert!(o.status.success(), "build failed: {text}");
    let lines = text.lines().map(str::to_owned).collect();
    std::fs::remove_dir_all(&dir).ok();
    (lines, String::from_utf8_lossy(&o.stdout).into_owned())
}

fn path(p: &std::path::Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// The index of the first line containing `text`.
fn position(lines: &[String], text: &str) -> usize {
    lines
        .iter()
        .position(|l| l.contains(text))
        .unwrap_or_else(|| panic!("no line with {text:?} in:\n{}", lines.join("\n")))
}

#[test]
fn build_logs_its_plan_and_every_stage_when_standard_error_is_a_file() {
    let (lines, _) = build_logged("narration-stages", &[]);
    for line in &lines {
        assert!(line.starts_with(LINE_PREFIX), "unprefixed line {line:?}");
    }
    let mut last_done = 0;
    for (stage, estimated) in STAGES {
        let started = position(&lines, &format!("{stage}: started"));
        let done = position(&lines, &format!("{stage}: done in "));
        assert!(started < done, "{stage}: ends before it starts");
        assert!(
            started >= last_done,
            "{stage}: starts before the stage before it ended"
        );
        last_done = done;
        let expected = lines[started].contains(": started, expected ");
        assert_eq!(expected, estimated, "{}", lines[started]);
        // Every time carries its unit.
        assert!(lines[done].ends_with(" s"), "{}", lines[done]);
    }
    // The plan: after meshing (it needs the patches), before the form factors.
    let plan = position(&lines, " patches, operator dense f64 (auto: ");
    let basis = position(&lines, "basis about ");
    let form_factors = position(&lines, "form factors: started");
    assert!(position(&lines, "scene and meshing: done") < plan);
    assert!(plan < form_factors && basis < form_factors);
    assert!(lines[plan].contains("GB at the peak"), "{}", lines[plan]);
    assert!(
        lines[basis].contains("flash budget 512 KiB"),
        "{}",
        lines[basis]
    );
    assert!(
        !lines.iter().any(|l| l.contains("warning")),
        "{}",
        lines.join("\n")
    );
}

#[test]
fn build_over_its_flash_budget_warns_before_the_form_factors_naming_the_sections() {
    let (lines, report) = build_logged("narration-flash", &["--flash", "2KiB"]);
    let warning = position(&lines, "warning: the basis would take about");
    assert!(warning < position(&lines, "form factors: started"));
    let text = &lines[warning];
    assert!(text.contains("flash budget of 2 KiB (--flash)"), "{text}");
    for section in ["modes", "channels", "patch tables"] {
        assert!(
            lines[position(&lines, "basis about ")].contains(section),
            "{section}: {}",
            lines.join("\n")
        );
    }
    assert!(text.contains("max_edge"), "{text}");
    // And the report says it again with the size written.
    assert!(
        report.contains("more than the flash budget of 2 KiB"),
        "{report}"
    );
}

/// The plan's basis size against the bytes the build writes (the writer's own count, an
/// independent reference), and its `--modes` fix against a build with that many modes.
#[test]
fn plan_foresees_the_basis_size_and_a_mode_count_that_fits() {
    let dir = scratch("narration-plan");
    let scene_path = dir.join("scene.toml");
    std::fs::write(&scene_path, scene(0.4)).expect("write scene");
    let options = |modes: usize, flash: u64| BuildOptions {
        modes: ModeSelection::Count(modes),
        flash: FlashBudget { bytes: flash },
        ..BuildOptions::default()
    };
    let (bytes, report) = pipeline::build(&scene_path, &options(16, 1 << 30)).expect("build");
    let expected = report.plan.basis.total();
    // The estimate leaves out postcard's varint lengths and the names, and counts every
    // table at its full width: 3.2 % over on this cube, 1.0 % over on the example office
    // (413 684 expected, 409 626 written). Over is the safe side of a flash budget.
    const SIZE_TOLERANCE: f64 = 0.05;
    let written = bytes.len() as f64;
    assert!(
        expected >= 0.99 * written && expected <= (1.0 + SIZE_TOLERANCE) * written,
        "expected {expected:.0} bytes, wrote {written}"
    );
    assert!(report.plan.fits());

    // A budget halfway between the basis without modes and with its 16: the plan names a
    // mode count that fits, and a build with it does fit.
    let without_modes = expected - 16.0 * report.plan.bytes_per_mode;
    let budget = ((without_modes + expected) / 2.0) as u64;
    let (_, over) = pipeline::build(&scene_path, &options(16, budget)).expect("build");
    assert!(!over.plan.fits());
    let warning = over
        .plan
        .lines()
        .into_iter()
        .find(|l| l.starts_with("warning:"))
        .expect("a warning");
    let modes: usize = warning
        .split("--modes ")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|k| k.parse().ok())
        .unwrap_or_else(|| panic!("no mode count in {warning:?}"));
    assert!((1..16).contains(&modes), "{warning}");
    let (fitting, _) = pipeline::build(&scene_path, &options(modes, budget)).expect("build");
    assert!(
        fitting.len() as u64 <= budget,
        "--modes {modes}: {} bytes, budget {budget}",
        fitting.len()
    );
    std::fs::remove_dir_all(&dir).ok();
}
