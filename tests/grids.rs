//! Calculation grids and their figures (EN 12464-1:2021, 4.4; docs/scene.md, "Grids"):
//!
//! - every grid point and every figure (`E_avg`, `E_min`, `E_max`, `U_o`) of `eigenrad solve`
//!   (the exact path) and of `eigenrad eval` (a basis through the runtime) against an
//!   independent computation of the same grid: the exact patch exitance of the dense solve
//!   (`solve --patches`) times point form factors computed here for each point, and the
//!   figures as plain mean, minimum, maximum and their quotient in f64;
//! - a hand-checked case: in a closed room with the same exitance `M` on every patch, an
//!   upward point anywhere inside sees `E = M` (its form factors to the enclosure sum to 1),
//!   and with every surface emitting `e` at reflectance `ρ`, `M = e/(1 − ρ)` (the white
//!   furnace of docs/math.md, "Exact results");
//! - the grid's layout as the scene states it (counts, border, task area, explicit spacing,
//!   the band around a task area, surface grids with the holes of their openings);
//! - `eigenrad eval` and `solve` with `--json` and `--csv FILE`: the same points and values,
//!   the CSV written only where it overwrites no input.

mod common;

use std::path::{Path, PathBuf};

use eigenrad::precompute::cli::{self, Readout};
use eigenrad::precompute::formfactor::{self, FormFactorOptions, Occluders};
use eigenrad::precompute::geometry::Vec3;
use eigenrad::precompute::pipeline::{self, BuildOptions, ModeSelection};
use eigenrad::precompute::radiosity::eigen::Solver;
use eigenrad::precompute::scene::{self, FieldOfView};

/// The exact path against the same exact exitance and point form factors: both are the same
/// f64 sums in another order, 1e-9 relative.
const EXACT_RTOL: f64 = 1e-9;
/// Through the runtime: f32 storage and arithmetic on sums of a few dozen terms (the build's
/// own accuracy table shows ~1e-7), with margin.
const RUNTIME_RTOL: f64 = 2e-5;
/// White furnace: a point's form factors to a closed box sum to 1 within the quadrature's
/// closure, and the patch exitance is `e/(1 − ρ)` within the form factors' row sums (the
/// project's white-furnace figure is 1e-4, tests/validation_closed_room.rs).
const FURNACE_RTOL: f64 = 1e-3;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eigenrad-grids-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `common::two_channel_room` with a work plane (with grid), a task area on the desk and its
/// 0.5 m surrounding, the walls as a zone without a grid, and the ceiling and the walls as
/// zones with grids (the lamp and the panel are openings in them).
fn room() -> String {
    common::two_channel_room("grids", 0.5)
        + r#"
[[zone]]
name = "work_plane"
work_plane = { room = "room", height = 0.8, max_edge = 0.5 }

[[zone]]
name = "desk_task"
work_plane = { height = 0.75, area = { min = [0.9, 0.7], max = [1.9, 1.3] }, grid = { spacing = 0.25 } }

[[zone]]
name = "walls"
surfaces = ["room.wall*"]

[[zone]]
name = "desk_surrounding"
work_plane = { height = 0.75, area = { min = [0.9, 0.7], max = [1.9, 1.3] }, band = 0.5 }

[[zone]]
name = "ceiling"
surfaces = ["room.ceiling"]
grid = {}

[[zone]]
name = "wall_grid"
surfaces = ["room.wall*"]
grid = { spacing = 0.4 }
"#
}

/// The figures of `values` computed here: mean, minimum, maximum, minimum / mean.
fn figures(values: &[f64]) -> [f64; 4] {
    let avg = values.iter().sum::<f64>() / values.len() as f64;
    let min = values.iter().copied().fold(f64::INFINITY, f64::min);
    let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    [avg, min, max, min / avg]
}

/// Every grid point's irradiance from the readout's patch exitance (`--patches`) and point
/// form factors computed here, each facing its piece's normal, per zone with a grid.
fn independent(path: &Path, exact: &Readout) -> Vec<Vec<f64>> {
    let scene = scene::load(path).unwrap();
    let occluders = Occluders::with_faces(&scene.patches, &scene.faces);
    let exitance: Vec<f64> = exact
        .patches
        .as_ref()
        .unwrap()
        .iter()
        .map(|p| p.exitance[0])
        .collect();
    exact
        .grids
        .iter()
        .map(|g| {
            let normals = g.pieces.iter().flat_map(|p| {
                let [x, y, z] = p.normal;
                std::iter::repeat_n(Vec3::new(x, y, z), p.points)
            });
            g.points
                .iter()
                .zip(normals)
                .map(|(p, normal)| {
                    let [x, y, z] = p.position_m;
                    let f = formfactor::point_form_factors(
                        Vec3::new(x, y, z),
                        normal,
                        FieldOfView::HEMISPHERE,
                        &scene.patches,
                        &occluders,
                    );
                    f.iter().zip(&exitance).map(|(f, m)| f * m).sum()
                })
                .collect()
        })
        .collect()
}

/// `got` within `rtol` of `want`, relative to `scale`.
fn close(got: f64, want: f64, rtol: f64, scale: f64, what: &str) {
    assert!(
        (got - want).abs() <= rtol * scale,
        "{what}: {got} vs {want} (scale {scale})"
    );
}

/// Checks every point and figure of `r` against `points` (the independent irradiances).
fn check(r: &Readout, points: &[Vec<f64>], rtol: f64, what: &str) {
    assert_eq!(r.grids.len(), points.len(), "{what}: grids");
    for (g, want) in r.grids.iter().zip(points) {
        assert_eq!(g.points.len(), want.len());
        let scale = want.iter().copied().fold(0.0, f64::max);
        for (i, (p, w)) in g.points.iter().zip(want).enumerate() {
            close(
                p.irradiance[0],
                *w,
                rtol,
                scale,
                &format!("{what}: {} point {i}", g.zone),
            );
        }
        let [avg, min, max, u] = figures(want);
        close(
            g.average[0],
            avg,
            rtol,
            scale,
            &format!("{what}: {} E_avg", g.zone),
        );
        close(
            g.minimum[0],
            min,
            rtol,
            scale,
            &format!("{what}: {} E_min", g.zone),
        );
        close(
            g.maximum[0],
            max,
            rtol,
            scale,
            &format!("{what}: {} E_max", g.zone),
        );
        close(
            g.uniformity[0],
            u,
            rtol * scale / avg,
            1.0,
            &format!("{what}: {} U_o", g.zone),
        );
    }
}

#[test]
fn figures_of_solve_and_eval_match_the_exact_exitance_at_the_grid_points() {
    let dir = scratch("room");
    let path = dir.join("room.toml");
    std::fs::write(&path, room()).unwrap();
    let levels = cli::LevelArgs {
        levels: vec!["lamp=0.8".to_string(), "panel=0.3".to_string()],
        arcs: Vec::new(),
    };
    let exact = cli::solve(&path, &levels, true, &FormFactorOptions::default()).unwrap();
    let points = independent(&path, &exact);
    // Lamp, panel and walls light the plane unevenly: not the figures of a uniform field.
    let [avg, min, _, u] = figures(&points[0]);
    assert!(u < 0.9 && min > 0.0 && avg > 0.0, "U_o {u}");
    check(&exact, &points, EXACT_RTOL, "solve");

    let opts = BuildOptions {
        modes: ModeSelection::Count(16),
        solver: Solver::Dense,
        ..BuildOptions::default()
    };
    let (bytes, report) = pipeline::build(&path, &opts).unwrap();
    let eval = cli::eval(&path, &bytes, &levels, false).unwrap();
    check(&eval, &points, RUNTIME_RTOL, "eval");
    // The build report's figures (every channel at level 1) against its own exact solve.
    assert_eq!(report.grids.len(), 5);
    assert!(
        report.grid_figure_error < RUNTIME_RTOL,
        "{}",
        report.grid_figure_error
    );

    // The layout as stated: the room less the default 0.5 m border is 2 m × 1 m:
    // p = 0.2 × 5^(log10 2) = 0.3247 m, 2/0.3247 = 6.2 → 7 and 1/0.3247 = 3.1 → 4 points.
    let plane = &eval.grids[0].pieces[..];
    assert_eq!(
        (plane.len(), plane[0].counts, plane[0].border_m),
        (1, [7, 4], 0.5)
    );
    assert!((plane[0].spacing_m - 0.32468).abs() < 1e-4);
    // The task area: 1 m × 0.6 m at an explicit 0.25 m: 4 × 3 points, no border.
    let task = &eval.grids[1];
    assert_eq!(
        (
            task.zone.as_str(),
            task.pieces[0].counts,
            task.pieces[0].border_m
        ),
        ("desk_task", [4, 3], 0.0)
    );
    assert!((task.pieces[0].spacing_m - 0.25).abs() < 1e-6);
    let first = task.points[0].position_m;
    assert!((first[0] - 1.025).abs() < 1e-6 && (first[1] - 0.8).abs() < 1e-6);
    // A surface zone has no grid unless it asks for one.
    assert!(eval.grids.iter().all(|g| g.zone != "walls"));
    // The surrounding: the band 0.5 m out from the task area ([0.4, 2.4] × [0.2, 1.8] less
    // [0.9, 1.9] × [0.7, 1.3]) as four strips, every point in it and none in the task area.
    let band = &eval.grids[2];
    assert_eq!(
        (band.zone.as_str(), band.pieces.len()),
        ("desk_surrounding", 4)
    );
    let inside =
        |p: [f64; 3], [x0, y0, x1, y1]: [f64; 4]| p[0] > x0 && p[0] < x1 && p[1] > y0 && p[1] < y1;
    for p in &band.points {
        assert!(
            inside(p.position_m, [0.4, 0.2, 2.4, 1.8]),
            "{:?}",
            p.position_m
        );
        assert!(
            !inside(p.position_m, [0.9, 0.7, 1.9, 1.3]),
            "{:?}",
            p.position_m
        );
    }
    // The ceiling (3 m × 2 m: p = 0.2 × 5^(log10 3) = 0.4310 m, 7 × 5 cells of 3/7 m × 0.4 m)
    // facing down, without the one cell centre in the lamp's opening ([1.2, 1.8] × [0.7, 1.3]:
    // x = 1.5, y = 1; the next ones, x = 1.5 ± 3/7 and y = 1 ± 0.4, lie outside it).
    let ceiling = &eval.grids[3];
    assert_eq!(ceiling.pieces.len(), 1);
    let piece = ceiling.pieces[0];
    assert_eq!(piece.normal, [0.0, 0.0, -1.0]);
    assert_eq!(piece.counts[0] * piece.counts[1], 35);
    assert_eq!(piece.points, 34);
    assert!(ceiling
        .points
        .iter()
        .all(|p| p.position_m[2] == 2.5 && !inside(p.position_m, [1.2, 0.7, 1.8, 1.3])));
    // The walls: four planes, four pieces, each facing into the room; the wall x = 0 keeps no
    // point in the panel's opening ([0.5, 1.5] in y, [0.8, 1.8] in z).
    let walls = &eval.grids[4];
    assert_eq!(walls.pieces.len(), 4);
    let mut next = 0;
    for piece in &walls.pieces {
        let points = &walls.points[next..next + piece.points];
        next += piece.points;
        let [nx, ny, _] = piece.normal;
        for p in points {
            let [x, y, z] = p.position_m;
            // Into the room: at the wall x = 0 the normal is +x, and so on.
            let toward_centre = nx * (1.5 - x) + ny * (1.0 - y);
            assert!(
                toward_centre > 0.0,
                "{:?} faces {:?}",
                p.position_m,
                piece.normal
            );
            if x == 0.0 {
                assert!(
                    !(y > 0.5 && y < 1.5 && z > 0.8 && z < 1.8),
                    "{:?}",
                    p.position_m
                );
            }
        }
    }
    assert!(walls
        .pieces
        .iter()
        .any(|p| p.points < p.counts[0] * p.counts[1]));

    // Without the grids: no grid tables, the same sensor and zone readings to the bit, and
    // smaller by each point's f32 position, modes, channel readings and view row.
    let bare = BuildOptions {
        grids: false,
        ..opts
    };
    let (small, _) = pipeline::build(&path, &bare).unwrap();
    let without = cli::eval(&path, &small, &levels, false).unwrap();
    assert!(without.grids.is_empty());
    for (a, b) in without.zones.iter().zip(&eval.zones) {
        assert_eq!(a.irradiance, b.irradiance, "{}", a.name);
    }
    let scene = scene::load(&path).unwrap();
    let points: usize = eval.grids.iter().map(|g| g.points.len()).sum();
    let per_point = 4 * (3 + 16 + 2 + scene.patches.len());
    let saved = bytes.len() - small.len();
    // Besides the points, only the pieces' lattices and layouts (40 bytes each) and varint
    // lengths differ.
    let pieces: usize = eval.grids.iter().map(|g| g.pieces.len()).sum();
    assert!(
        saved >= points * per_point + 40 * pieces
            && saved <= points * per_point + 40 * pieces + 128,
        "{saved}"
    );
}

#[test]
fn in_a_white_furnace_every_grid_point_sees_the_uniform_exitance() {
    let (rho, e) = (0.5, 100.0);
    let dir = scratch("furnace");
    let path = dir.join("furnace.toml");
    std::fs::write(&path, common::white_furnace(rho, e)).unwrap();
    // M = e / (1 − ρ) on every patch; an upward point inside sees E = M.
    let m = e / (1.0 - rho);
    let exact = cli::solve(
        &path,
        &cli::LevelArgs::default(),
        false,
        &FormFactorOptions::default(),
    )
    .unwrap();
    let opts = BuildOptions {
        modes: ModeSelection::Count(8),
        ..BuildOptions::default()
    };
    let (bytes, _) = pipeline::build(&path, &opts).unwrap();
    let eval = cli::eval(&path, &bytes, &cli::LevelArgs::default(), false).unwrap();
    for (r, what) in [(&exact, "solve"), (&eval, "eval")] {
        let g = &r.grids[0];
        // 3 m × 3 m after the 0.5 m border: p = 0.2 × 5^(log10 3) = 0.4310 m, 6.96 → 7.
        assert_eq!(g.pieces[0].counts, [7, 7], "{what}");
        for p in &g.points {
            close(p.irradiance[0], m, FURNACE_RTOL, m, what);
        }
        for (got, name) in [
            (g.average[0], "E_avg"),
            (g.minimum[0], "E_min"),
            (g.maximum[0], "E_max"),
        ] {
            close(got, m, FURNACE_RTOL, m, &format!("{what}: {name}"));
        }
        close(
            g.uniformity[0],
            1.0,
            FURNACE_RTOL,
            1.0,
            &format!("{what}: U_o"),
        );
    }
}

#[test]
fn json_and_csv_list_the_same_points() {
    let dir = common::scratch("grids-csv");
    let text = format!(
        "{}\n[[zone]]\nname = \"plane\"\nwork_plane = {{ height = 0.8, margin = 0.25 }}\n",
        common::scene(0.5)
    );
    let o = common::build(&dir, &text, "cube.basis", &[]);
    assert!(o.status.success(), "build: {}", common::stderr(&o));
    let report = String::from_utf8_lossy(&o.stdout).into_owned();
    // 2 m less 0.25 m on each side: 1.5 m, p = 0.2 × 5^(log10 1.5) = 0.2 × 1.3276 = 0.2655 m,
    // 1.5/0.2655 = 5.65 → 6 points a side.
    assert!(
        report.contains("6 × 6 points") && report.contains("border 0.25 m"),
        "{report}"
    );
    assert!(
        report.contains("E_avg") && report.contains("U_o"),
        "{report}"
    );
    let basis = dir.join("cube.basis");
    let scene = dir.join("scene.toml");
    for (command, input) in [("eval", &basis), ("solve", &scene)] {
        let csv = dir.join(format!("{command}.csv"));
        let args = [
            command,
            input.to_str().unwrap(),
            "--json",
            "--csv",
            csv.to_str().unwrap(),
        ];
        let o = common::run(&args);
        assert!(o.status.success(), "{command}: {}", common::stderr(&o));
        let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let points = json["grids"][0]["points"].as_array().unwrap();
        assert_eq!(points.len(), 36);
        let text = std::fs::read_to_string(&csv).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "zone,point,x_m,y_m,z_m,photopic_lux");
        assert_eq!(lines.len(), 37);
        for (line, p) in lines[1..].iter().zip(points) {
            let fields: Vec<&str> = line.split(',').collect();
            assert_eq!(fields[0], "\"plane\"");
            let x: f64 = fields[2].parse().unwrap();
            let e: f64 = fields[5].parse().unwrap();
            assert!(
                (x - p["position_m"][0].as_f64().unwrap()).abs() < 1e-4,
                "{line}"
            );
            // serde_json's default float parsing may be off by an ulp: 1e-12 relative.
            let want = p["irradiance"][0].as_f64().unwrap();
            assert!((e - want).abs() <= 1e-12 * want.abs(), "{command}: {line}");
        }
        // The figures in the JSON are those of the points it lists.
        let values: Vec<f64> = points
            .iter()
            .map(|p| p["irradiance"][0].as_f64().unwrap())
            .collect();
        let [avg, min, max, _] = figures(&values);
        let g = &json["grids"][0];
        close(g["average"][0].as_f64().unwrap(), avg, 1e-6, avg, command);
        close(g["minimum"][0].as_f64().unwrap(), min, 1e-6, avg, command);
        close(g["maximum"][0].as_f64().unwrap(), max, 1e-6, avg, command);
        // The CSV never replaces an input.
        let o = common::run(&[
            command,
            input.to_str().unwrap(),
            "--csv",
            input.to_str().unwrap(),
        ]);
        assert!(
            !o.status.success(),
            "{command}: CSV over its input accepted"
        );
        assert!(
            common::stderr(&o).contains("an input of this command"),
            "{}",
            common::stderr(&o)
        );
        // In footcandles the header says so, and every value is the lux value over 10.7639.
        let fc = dir.join(format!("{command}-fc.csv"));
        let o = common::run(&[
            command,
            input.to_str().unwrap(),
            "--units",
            "fc",
            "--csv",
            fc.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{command}: {}", common::stderr(&o));
        let fc_text = std::fs::read_to_string(&fc).unwrap();
        let fc_lines: Vec<&str> = fc_text.lines().collect();
        assert_eq!(fc_lines[0], "zone,point,x_m,y_m,z_m,photopic_fc");
        for (line, lux_line) in fc_lines[1..].iter().zip(&lines[1..]) {
            let value = |l: &str| -> f64 { l.split(',').nth(5).unwrap().parse().unwrap() };
            let (f, l) = (value(line), value(lux_line));
            // 1 fc = 1/0.3048² lx exactly; the two files print f64 to the last digit.
            assert!(
                (f * 10.763_910_416_709_722 - l).abs() <= 1e-12 * l.abs(),
                "{line}"
            );
        }
        let missing = dir.join("no-such-folder/grid.csv");
        let o = common::run(&[
            command,
            input.to_str().unwrap(),
            "--csv",
            missing.to_str().unwrap(),
        ]);
        assert!(!o.status.success() && common::stderr(&o).contains("folder does not exist"));
    }
    assert!(basis.exists() && scene.exists());
}
