//! `eigenrad render`: the pictures show the values `solve` and `eval` give.
//!
//! References:
//! - the plan's colours against the exact solve's grid values (`cli::solve`), and the
//!   surfaces' against the runtime's patch values (`cli::eval` of a basis built from the
//!   scene), read back from the decoded PNG through the inverse of the colour map
//!   (`Scale::value_of`): within half a colour bin, the map's quantisation;
//! - the SVG's isolux lines on a linear field, whose isolines are straight lines at known
//!   positions, within a pixel (the SVG's coordinates are whole pixels);
//! - a hand-checked case: the white furnace (every surface emitting `e` at reflectance `ρ`,
//!   `M = e/(1 − ρ)` everywhere, docs/math.md), drawn in the one colour of `M` without
//!   isolux lines;
//! - the same bytes from the same input, PNG and SVG; and the command's errors.

mod common;

use std::path::{Path, PathBuf};

use eigenrad::precompute::cli::{
    self, DaylightArgs, LevelArgs, RenderRequest, SkyInput, SurfaceQuantity, Units,
};
use eigenrad::precompute::formfactor::FormFactorOptions;
use eigenrad::precompute::picture::plan::colours;
use eigenrad::precompute::picture::{colour, Frame, Panel, Plan, PlanGrid, PlanInput, Scale};
use eigenrad::precompute::pipeline::{self, BuildOptions, ModeSelection};
use eigenrad::precompute::scene;

/// The white furnace's exact values differ from `e/(1 − ρ)` by the form factors' closure
/// (tests/grids.rs, FURNACE_RTOL).
const FURNACE_RTOL: f64 = 1e-3;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eigenrad-render-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `common::two_channel_room` with a work plane and its grid.
fn room(dir: &Path) -> PathBuf {
    let text = common::two_channel_room("render", 0.5)
        + r#"
[[zone]]
name = "work_plane"
work_plane = { room = "room", height = 0.8, margin = 0.3 }
"#;
    let path = dir.join("room.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn request<'a>(
    scene: &'a Path,
    levels: &'a LevelArgs,
    ff: &'a FormFactorOptions,
) -> RenderRequest<'a> {
    RenderRequest {
        scene,
        basis: None,
        levels,
        units: Units::Native,
        zones: &[],
        plan: true,
        surfaces: Some(SurfaceQuantity::Illuminance),
        form_factors: ff,
        daylight: None,
    }
}

/// A decoded PNG: width, height, RGB rows.
struct Image {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

fn decode(bytes: &[u8]) -> Image {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut rgb = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut rgb).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    Image {
        width: info.width as usize,
        height: info.height as usize,
        rgb,
    }
}

impl Image {
    fn at(&self, (c, r): (i32, i32)) -> colour::Rgb {
        assert!(c >= 0 && r >= 0 && (c as usize) < self.width && (r as usize) < self.height);
        let i = 3 * (r as usize * self.width + c as usize);
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }

    /// The colour most pixels of the rectangle between two pixels have (the cell's own, where
    /// an isolux line or its label crosses a few of them).
    fn majority(&self, a: (i32, i32), b: (i32, i32)) -> colour::Rgb {
        let mut counts: Vec<(colour::Rgb, usize)> = Vec::new();
        for r in a.1.min(b.1)..=a.1.max(b.1) {
            for c in a.0.min(b.0)..=a.0.max(b.0) {
                let p = self.at((c, r));
                match counts.iter_mut().find(|(q, _)| *q == p) {
                    Some((_, n)) => *n += 1,
                    None => counts.push((p, 1)),
                }
            }
        }
        counts.into_iter().max_by_key(|&(_, n)| n).unwrap().0
    }
}

/// The value the picture shows in the cell around `(x, y)` (m) of half-sides `half` (m),
/// inset by 3 pixels from its edges.
fn cell_value(
    img: &Image,
    frame: &Frame,
    scale: &Scale,
    (x, y): (f64, f64),
    half: [f64; 2],
) -> Option<f64> {
    let a = frame.pixel(x - half[0], y - half[1]);
    let b = frame.pixel(x + half[0], y + half[1]);
    let inset = |p: i32, q: i32| {
        if p < q {
            (p + 3, q - 3)
        } else {
            (p - 3, q + 3)
        }
    };
    let (c0, c1) = inset(a.0, b.0);
    let (r0, r1) = inset(a.1, b.1);
    scale.value_of(img.majority((c0, r0), (c1, r1)))
}

#[test]
fn the_plan_shows_the_exact_grid_values() {
    let dir = scratch("plan");
    let path = room(&dir);
    let levels = LevelArgs {
        levels: vec!["panel=0.4".into()],
        arcs: vec!["lamp=230".into()],
    };
    let ff = FormFactorOptions::default();
    let pictures = cli::render(&request(&path, &levels, &ff)).unwrap();
    let plan = pictures.plan.as_ref().unwrap();
    let exact = cli::solve(&path, &levels, false, &ff).unwrap();
    let grid = &exact.grids[0];
    assert_eq!(grid.zone, "work_plane");
    let (bytes, frame) = plan.png().unwrap();
    let img = decode(&bytes);
    let half = plan.scale.bin_width() / 2.0;
    let cell = [
        grid.pieces[0].cell_m[0] / 2.0,
        grid.pieces[0].cell_m[1] / 2.0,
    ];
    assert!(grid.points.len() >= 12, "{} points", grid.points.len());
    for p in &grid.points {
        let [x, y, _] = p.position_m;
        let shown = cell_value(&img, &frame, &plan.scale, (x, y), cell)
            .unwrap_or_else(|| panic!("({x}, {y}): not a colour of the scale"));
        let e = p.irradiance[0];
        assert!(
            (shown - e).abs() <= half * (1.0 + 1e-9),
            "({x:.3}, {y:.3}): drawn {shown:.3} lx, exact {e:.3} lx, half a bin {half:.3} lx"
        );
    }
    // The caption carries the exact figures; the scale spans the values.
    assert_eq!(plan.input.grids[0].figures[0], grid.average[0]);
    assert_eq!(plan.input.grids[0].figures[3], grid.uniformity[0]);
    assert!(plan.scale.min <= grid.minimum[0] && grid.maximum[0] <= plan.scale.max);
    // Isolux lines at the scale's round values inside the grid's range, each where the
    // values cross it: between a point below and one above.
    assert!(!plan.isolux.is_empty());
    for (level, _) in &plan.isolux {
        assert!(*level > grid.minimum[0] && *level < grid.maximum[0]);
        assert_eq!((level / plan.scale.step).round() * plan.scale.step, *level);
    }
}

#[test]
fn the_surfaces_show_what_the_runtime_reads() {
    let dir = scratch("surfaces");
    let path = room(&dir);
    let opts = BuildOptions {
        modes: ModeSelection::Count(8),
        ..BuildOptions::default()
    };
    let (bytes, _) = pipeline::build(&path, &opts).unwrap();
    let basis = dir.join("room.basis");
    std::fs::write(&basis, &bytes).unwrap();
    let levels = LevelArgs {
        levels: vec!["lamp=0.7".into()],
        arcs: vec![],
    };
    let ff = FormFactorOptions::default();
    let eval = cli::eval(&basis, &bytes, &levels, true).unwrap();
    let patches = eval.patches.as_ref().unwrap();
    let scene = scene::load(&path).unwrap();
    for quantity in [SurfaceQuantity::Illuminance, SurfaceQuantity::Luminance] {
        let mut r = request(&path, &levels, &ff);
        r.basis = Some((&basis, &bytes));
        r.plan = false;
        r.surfaces = Some(quantity);
        let pictures = cli::render(&r).unwrap();
        assert!(pictures.plan.is_none());
        let net = pictures.surfaces.as_ref().unwrap();
        let (png, frame) = net.png().unwrap();
        let img = decode(&png);
        let half = net.scale.bin_width() / 2.0;
        let (mut checked, mut grey) = (0, 0);
        for (i, p) in scene.patches.iter().enumerate() {
            // Patches nothing stands in front of: the ceiling's, and the walls' above the
            // desk (0.7 m high).
            let panel = net.panels[i];
            if panel == Panel::Floor || (panel != Panel::Ceiling && p.centroid.z < 0.8) {
                continue;
            }
            let [u, v] = net.centre(i);
            let (c, r) = frame.pixel(u, v);
            let colour = img.majority((c - 2, r - 2), (c + 2, r + 2));
            let expected = match quantity {
                SurfaceQuantity::Illuminance => patches[i].irradiance.as_ref().map(|e| e[0]),
                SurfaceQuantity::Luminance => Some(patches[i].exitance[0] / std::f64::consts::PI),
            };
            match expected {
                // A black patch's illuminance the runtime cannot tell: drawn "no value".
                None => {
                    assert_eq!(colour, colour::NO_VALUE, "patch {i}");
                    grey += 1;
                }
                Some(x) if net.scale.bin(x).is_none() => {
                    assert_eq!(colour, colour::ABOVE, "patch {i}")
                }
                Some(x) => {
                    let shown = net
                        .scale
                        .value_of(colour)
                        .unwrap_or_else(|| panic!("patch {i}: {colour:?}"));
                    assert!(
                        (shown - x).abs() <= half * (1.0 + 1e-9),
                        "{quantity:?} patch {i}: drawn {shown}, runtime {x}, half a bin {half}"
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 20, "{checked} patches checked");
        if quantity == SurfaceQuantity::Illuminance {
            // The lamp (ρ = 0) has no illuminance through the runtime.
            assert!(grey > 0);
        }
    }
}

/// A linear field `E = 100 x` lux on a 9 × 5 grid of 0.5 m cells: the scale runs 0–500 lx
/// in steps of 100, and the isolux lines of 100, 200, 300 and 400 lx are the straight lines
/// x = 1, 2, 3, 4 m (linear interpolation is exact on a linear field).
fn linear_plan() -> Plan {
    let counts = [9, 5];
    let mut points = Vec::new();
    for j in 0..counts[1] {
        for i in 0..counts[0] {
            points.push([0.25 + 0.5 * i as f64, 0.25 + 0.5 * j as f64]);
        }
    }
    let values: Vec<f64> = points.iter().map(|p| 100.0 * p[0]).collect();
    Plan::new(PlanInput {
        title: "linear".into(),
        notes: vec![],
        unit: "lux",
        grids: vec![PlanGrid {
            zone: "linear".into(),
            counts,
            cell: [0.5, 0.5],
            border: 0.0,
            values,
            points,
            figures: [225.0, 25.0, 425.0, 25.0 / 225.0],
        }],
        room: [[0.0, 0.0], [4.5, 2.5]],
        floor: vec![],
        walls: vec![],
        windows: vec![],
        doors: vec![],
        blocks: vec![],
        luminaires: vec![],
        luminaire_points: vec![],
        sensors: vec![],
    })
}

/// `name="value"` of an SVG element's text.
fn attribute<'a>(element: &'a str, name: &str) -> Option<&'a str> {
    let start = element.find(&format!(" {name}=\""))? + name.len() + 3;
    let end = element[start..].find('"')? + start;
    Some(&element[start..end])
}

#[test]
fn the_svg_has_isolux_lines_at_their_levels_and_cells_in_their_colours() {
    let plan = linear_plan();
    assert_eq!(
        (plan.scale.min, plan.scale.max, plan.scale.step),
        (0.0, 500.0, 100.0)
    );
    let levels: Vec<f64> = plan.isolux.iter().map(|(l, _)| *l).collect();
    assert_eq!(levels, vec![100.0, 200.0, 300.0, 400.0]);
    let (svg, frame) = plan.svg().unwrap();
    // One metre in pixels: the tolerance of a whole-pixel coordinate is half of 1/that.
    let (a, b) = (frame.pixel(0.0, 0.0), frame.pixel(1.0, 0.0));
    let pixel_m = 1.0 / f64::from(b.0 - a.0);
    let mut found = vec![0; levels.len()];
    for element in svg.split('<').filter(|e| e.starts_with("polyline")) {
        if attribute(element, "stroke") != Some("#141414") {
            continue;
        }
        let points: Vec<[f64; 2]> = attribute(element, "points")
            .unwrap()
            .split_whitespace()
            .map(|xy| {
                let (c, r) = xy.split_once(',').unwrap();
                frame.position(c.parse().unwrap(), r.parse().unwrap())
            })
            .collect();
        // A vertical line x = level / 100 from the first row of points to the last.
        let x = points[0][0];
        let k = levels
            .iter()
            .position(|l| (l / 100.0 - x).abs() <= pixel_m)
            .unwrap_or_else(|| panic!("an isolux line at x = {x} m"));
        for p in &points {
            assert!((p[0] - levels[k] / 100.0).abs() <= pixel_m, "{p:?}");
        }
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p[1]), b.max(p[1]))
            });
        assert!(
            (lo - 0.25).abs() <= pixel_m && (hi - 2.25).abs() <= pixel_m,
            "{lo} {hi}"
        );
        found[k] += 1;
    }
    assert_eq!(found, vec![1; 4], "one line per level");
    let texts: Vec<&str> = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| Some(t[t.find('>')? + 1..t.find("</text>")?].trim()))
        .collect();
    for level in ["100", "200", "300", "400"] {
        assert!(texts.contains(&level), "label {level}: {texts:?}");
    }
    // The colour of the topmost rectangle over each grid point maps back to its value.
    let half = plan.scale.bin_width() / 2.0;
    let rects: Vec<(i32, i32, i32, i32, colour::Rgb)> = svg
        .split('<')
        .filter(|e| e.starts_with("rect"))
        .filter_map(|e| {
            let n = |k| attribute(e, k)?.parse::<i32>().ok();
            let fill = attribute(e, "fill")?.strip_prefix('#')?;
            let hex = |i| u8::from_str_radix(&fill[i..i + 2], 16).ok();
            Some((
                n("x")?,
                n("y")?,
                n("width")?,
                n("height")?,
                [hex(0)?, hex(2)?, hex(4)?],
            ))
        })
        .collect();
    for (p, v) in plan.input.grids[0]
        .points
        .iter()
        .zip(&plan.input.grids[0].values)
    {
        let (c, r) = frame.pixel(p[0], p[1]);
        let top = rects
            .iter()
            .rev()
            .find(|(x, y, w, h, _)| *x <= c && c <= x + w && *y <= r && r <= y + h)
            .unwrap();
        let shown = plan.scale.value_of(top.4).unwrap();
        assert!(
            (shown - v).abs() <= half * (1.0 + 1e-9),
            "{p:?}: {shown} against {v}"
        );
    }
}

#[test]
fn a_white_furnace_is_one_colour_without_isolux_lines() {
    let (rho, e) = (0.5, 100.0);
    let dir = scratch("furnace");
    let path = dir.join("furnace.toml");
    std::fs::write(&path, common::white_furnace(rho, e)).unwrap();
    // M = e / (1 − ρ) on every patch, and every upward point sees E = M.
    let m = e / (1.0 - rho);
    let levels = LevelArgs::default();
    let ff = FormFactorOptions::default();
    let pictures = cli::render(&request(&path, &levels, &ff)).unwrap();
    let plan = pictures.plan.as_ref().unwrap();
    assert!(plan.isolux.is_empty());
    // The scale centred on M: 150–250 lx in steps of 50.
    assert_eq!(
        (plan.scale.min, plan.scale.max, plan.scale.step),
        (150.0, 250.0, 50.0)
    );
    let tolerance = plan.scale.bin_width() / 2.0 + FURNACE_RTOL * m;
    let (bytes, frame) = plan.png().unwrap();
    let img = decode(&bytes);
    for [x, y] in &plan.input.grids[0].points {
        // The very pixel of the point: nothing is drawn over a uniform plan's cells.
        let shown = plan.scale.value_of(img.at(frame.pixel(*x, *y))).unwrap();
        assert!(
            (shown - m).abs() <= tolerance,
            "({x}, {y}): {shown} lx against {m} lx"
        );
    }
    let net = pictures.surfaces.as_ref().unwrap();
    let (bytes, frame) = net.png().unwrap();
    let img = decode(&bytes);
    for i in 0..net.panels.len() {
        let [u, v] = net.centre(i);
        let shown = net.scale.value_of(img.at(frame.pixel(u, v))).unwrap();
        assert!(
            (shown - m).abs() <= net.scale.bin_width() / 2.0 + FURNACE_RTOL * m,
            "patch {i}: {shown}"
        );
    }
}

#[test]
fn the_same_input_gives_the_same_bytes() {
    let dir = scratch("bytes");
    let path = room(&dir);
    let levels = LevelArgs::default();
    let ff = FormFactorOptions::default();
    let one = cli::render(&request(&path, &levels, &ff)).unwrap();
    let two = cli::render(&request(&path, &levels, &ff)).unwrap();
    let (p1, n1) = (one.plan.as_ref().unwrap(), one.surfaces.as_ref().unwrap());
    let (p2, n2) = (two.plan.as_ref().unwrap(), two.surfaces.as_ref().unwrap());
    assert_eq!(p1.png().unwrap().0, p2.png().unwrap().0);
    assert_eq!(p1.svg().unwrap().0, p2.svg().unwrap().0);
    assert_eq!(n1.png().unwrap().0, n2.png().unwrap().0);
    assert_eq!(n1.svg().unwrap().0, n2.svg().unwrap().0);
    // And through the command, into files, twice.
    let out = |name: &str| dir.join(name);
    let mut written = Vec::new();
    for run in 0..2 {
        let (plan, surfaces) = (
            out(&format!("plan{run}.png")),
            out(&format!("surfaces{run}.svg")),
        );
        let o = common::run(&[
            "render",
            path.to_str().unwrap(),
            "--plan",
            plan.to_str().unwrap(),
            "--surfaces",
            surfaces.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", common::stderr(&o));
        written.push((
            std::fs::read(&plan).unwrap(),
            std::fs::read(&surfaces).unwrap(),
        ));
    }
    assert_eq!(written[0], written[1]);
    assert_eq!(
        written[0].0,
        p1.png().unwrap().0,
        "the command draws what the library does"
    );
    for (bytes, _) in &written {
        assert!(bytes.len() < 200_000);
    }
}

/// A daylight plan (`render --time ... <sky>`, lamp off) shows the exact daylight grid of
/// `solve --time` within half a colour bin, and names the sky in its notes.
#[test]
fn a_daylight_plan_shows_the_daylight_grid() {
    let dir = scratch("daylight");
    let path = dir.join("daylit.toml");
    std::fs::write(&path, common::daylit_room(common::VIENNA)).unwrap();
    let levels = LevelArgs {
        levels: vec!["lamp=0".into()],
        arcs: Vec::new(),
    };
    let ff = FormFactorOptions::default();
    let daylight = DaylightArgs {
        time: "2026-06-21T12:00+02:00".into(),
        input: SkyInput::Cie {
            sky_type: 0,
            diffuse_horizontal: 10_000.0,
            direct_normal: 0.0,
        },
        water: 2.0,
        subdivision: 1,
    };
    let mut r = request(&path, &levels, &ff);
    r.daylight = Some(&daylight);
    let pictures = cli::render(&r).unwrap();
    let plan = pictures.plan.as_ref().unwrap();
    assert!(
        plan.input
            .notes
            .iter()
            .any(|n| n.contains("CIE traditional overcast")),
        "{:?}",
        plan.input.notes
    );
    let exact = cli::solve_with_daylight(&path, &levels, Some(&daylight), false, &ff).unwrap();
    let day = &exact.daylight.as_ref().unwrap().grids[0];
    let (bytes, frame) = plan.png().unwrap();
    let img = decode(&bytes);
    let half = plan.scale.bin_width() / 2.0;
    let cell = [day.pieces[0].cell_m[0] / 2.0, day.pieces[0].cell_m[1] / 2.0];
    for p in &day.points {
        let [x, y, _] = p.position_m;
        let shown = cell_value(&img, &frame, &plan.scale, (x, y), cell)
            .unwrap_or_else(|| panic!("({x}, {y}): not a colour of the scale"));
        let e = p.irradiance[0];
        assert!(e > 0.0, "({x}, {y}): no daylight");
        assert!(
            (shown - e).abs() <= half * (1.0 + 1e-9),
            "({x:.3}, {y:.3}): drawn {shown:.3} lx, exact daylight {e:.3} lx"
        );
    }
    // A basis built without daylight: asked for daylight, render says so and draws nothing.
    let basis = common::good_basis(&dir);
    let out = dir.join("plan.png");
    let o = common::run(&[
        "render",
        path.to_str().unwrap(),
        "--basis",
        basis.to_str().unwrap(),
        "--time",
        "2026-06-21T12:00+02:00",
        "--cie",
        "overcast",
        "--dhi-lux",
        "10000",
        "--plan",
        out.to_str().unwrap(),
    ]);
    let e = common::stderr(&o);
    assert!(
        !o.status.success() && e.contains("carries no daylight"),
        "{e}"
    );
    assert!(!out.exists());
}

/// The surfaces under daylight from a basis (`render --basis --time ... --surfaces`, lamp
/// off): every patch carries the illuminance `eval --time` reads through the runtime (its
/// first reflection from the basis, the rest through the modes), the black window and lamp
/// none, and the picture names the basis and the sky.
#[test]
fn daylight_surfaces_from_a_basis_show_what_the_runtime_reads() {
    let dir = scratch("daylight-surfaces");
    let path = dir.join("daylit.toml");
    std::fs::write(&path, common::daylit_room(common::VIENNA)).unwrap();
    let opts = BuildOptions {
        modes: ModeSelection::Count(8),
        ..BuildOptions::default()
    };
    let (bytes, _) = pipeline::build(&path, &opts).unwrap();
    let basis = dir.join("daylit.basis");
    std::fs::write(&basis, &bytes).unwrap();
    let levels = LevelArgs {
        levels: vec!["lamp=0".into()],
        arcs: Vec::new(),
    };
    let ff = FormFactorOptions::default();
    let daylight = DaylightArgs {
        time: "2026-03-20T12:00+01:00".into(),
        input: SkyInput::Cie {
            sky_type: 12,
            diffuse_horizontal: 15_000.0,
            direct_normal: 70_000.0,
        },
        water: 2.0,
        subdivision: 1,
    };
    let mut r = request(&path, &levels, &ff);
    r.basis = Some((&basis, &bytes));
    r.plan = false;
    r.daylight = Some(&daylight);
    let pictures = cli::render(&r).unwrap();
    let net = pictures.surfaces.as_ref().expect("the surfaces are drawn");
    assert!(net.input.notes.iter().any(|n| n.contains("daylit.basis")));
    assert!(net.input.notes.iter().any(|n| n.starts_with("daylight:")));
    let eval = cli::eval_with_daylight(&basis, &bytes, &levels, Some(&daylight), true).unwrap();
    let patches = eval.patches.as_ref().unwrap();
    let mut lit = 0;
    for (i, (drawn, read)) in net.input.patches.iter().zip(patches).enumerate() {
        let read = read.irradiance.as_ref().map(|e| e[0]);
        assert_eq!(drawn.value, read, "patch {i}");
        lit += usize::from(read.is_some_and(|e| e > 0.0));
    }
    assert!(lit > patches.len() / 2, "{lit} patches lit");
    assert!(net.png().is_ok());
}

#[test]
fn errors_name_what_is_wrong() {
    let dir = scratch("errors");
    // A scene without a work plane has no plan, but its surfaces.
    let cube = dir.join("cube.toml");
    std::fs::write(&cube, common::scene(1.0)).unwrap();
    let plan = dir.join("plan.png");
    let o = common::run(&[
        "render",
        cube.to_str().unwrap(),
        "--plan",
        plan.to_str().unwrap(),
    ]);
    let e = common::stderr(&o);
    assert!(
        !o.status.success() && e.contains("no work-plane zone") && e.contains("cube.toml"),
        "{e}"
    );
    assert!(!plan.exists());
    let surfaces = dir.join("surfaces.png");
    let o = common::run(&[
        "render",
        cube.to_str().unwrap(),
        "--surfaces",
        surfaces.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", common::stderr(&o));
    decode(&std::fs::read(&surfaces).unwrap());
    // Nothing to draw; a format by an unknown extension.
    let o = common::run(&["render", cube.to_str().unwrap()]);
    assert!(!o.status.success() && common::stderr(&o).contains("nothing to draw"));
    let jpeg = dir.join("plan.jpg");
    let o = common::run(&[
        "render",
        cube.to_str().unwrap(),
        "--surfaces",
        jpeg.to_str().unwrap(),
    ]);
    let e = common::stderr(&o);
    assert!(
        !o.status.success() && e.contains("plan.jpg") && e.contains(".png or .svg"),
        "{e}"
    );
    let twice = dir.join("twice.svg");
    let o = common::run(&[
        "render",
        cube.to_str().unwrap(),
        "--surfaces",
        twice.to_str().unwrap(),
        "--surfaces",
        twice.to_str().unwrap(),
    ]);
    assert!(!o.status.success() && common::stderr(&o).contains("named twice"));
    // Never over an input: a scene file that happens to be named .svg.
    let odd = dir.join("scene.svg");
    std::fs::write(&odd, common::scene(1.0)).unwrap();
    let o = common::run(&[
        "render",
        odd.to_str().unwrap(),
        "--surfaces",
        odd.to_str().unwrap(),
    ]);
    assert!(!o.status.success() && common::stderr(&o).contains("refusing to write over"));
    assert_eq!(std::fs::read_to_string(&odd).unwrap(), common::scene(1.0));
    // A zone that is not there; a basis of another scene.
    let room = room(&dir);
    let o = common::run(&[
        "render",
        room.to_str().unwrap(),
        "--zone",
        "desk",
        "--plan",
        plan.to_str().unwrap(),
    ]);
    let e = common::stderr(&o);
    assert!(
        !o.status.success() && e.contains("no zone named `desk`") && e.contains("work_plane"),
        "{e}"
    );
    let basis = common::good_basis(&dir);
    let o = common::run(&[
        "render",
        room.to_str().unwrap(),
        "--basis",
        basis.to_str().unwrap(),
        "--plan",
        plan.to_str().unwrap(),
    ]);
    let e = common::stderr(&o);
    assert!(
        !o.status.success() && e.contains("was not built from this scene"),
        "{e}"
    );
    assert!(!plan.exists());
    // The band around a task area is a grid of four pieces, which a plan does not draw.
    let banded = dir.join("banded.toml");
    let band = "\n[[zone]]\nname = \"around\"\nwork_plane = { height = 0.8, area = \
                { min = [1, 0.8], max = [2, 1.2] }, band = 0.5 }\n";
    std::fs::write(&banded, std::fs::read_to_string(&room).unwrap() + band).unwrap();
    let o = common::run(&[
        "render",
        banded.to_str().unwrap(),
        "--zone",
        "around",
        "--plan",
        plan.to_str().unwrap(),
    ]);
    let e = common::stderr(&o);
    assert!(
        !o.status.success() && e.contains("zone `around`'s grid has 4 pieces"),
        "{e}"
    );
    assert!(!plan.exists());
}

/// The L-shaped office of `examples/l-office` meshed coarser (1 m: the plan is what is tested,
/// not the light), its photometry found where the example keeps it, with `zones` in place of
/// its work plane.
fn l_office(dir: &Path, zones: &str) -> PathBuf {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/l-office/scene.toml");
    let photometry = example.parent().unwrap().join("../photometry/");
    let text = std::fs::read_to_string(&example).unwrap();
    let at = text.find("[[zone]]").expect("the example's zone");
    let text = text[..at]
        .replace("max_edge = 0.6", "max_edge = 1.0")
        .replace("../photometry/", photometry.to_str().unwrap())
        + zones;
    let path = dir.join("l-office.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// The colour of a plan's pixel at `(x, y)` (m) is `expected`, or (`near`) some pixel within
/// two of it is (a line two pixels wide).
fn shows(img: &Image, frame: &Frame, (x, y): (f64, f64), expected: [u8; 3], near: bool) -> bool {
    let (c, r) = frame.pixel(x, y);
    let reach = if near { 2 } else { 0 };
    (-reach..=reach).any(|dc| (-reach..=reach).any(|dr| img.at((c + dc, r + dr)) == expected))
}

/// The plan of an L-shaped room: the notch is background, the columns their colour, the
/// walls follow the L (not its bounding rectangle), the windows lie on the façades, the
/// sensor and the desk are marked, isolux lines run over the L's grid, and the title names
/// the plane's height.
#[test]
fn the_plan_of_an_l_shaped_room_draws_its_walls_openings_and_blocks() {
    let dir = scratch("l-office");
    let path = l_office(
        &dir,
        "[[zone]]\nname = \"work_plane\"\nwork_plane = { room = \"office\", height = 0.8, margin = 0.5 }\n",
    );
    let (levels, ff) = (LevelArgs::default(), FormFactorOptions::default());
    let mut r = request(&path, &levels, &ff);
    r.surfaces = None;
    let pictures = cli::render(&r).unwrap();
    let plan = pictures.plan.as_ref().unwrap();
    let title = &plan.input.title;
    assert!(
        !title.contains("NaN") && title.contains("work_plane at 0.80 m"),
        "{title}"
    );
    assert!(!plan.isolux.is_empty(), "isolux lines over the L's grid");
    let (bytes, frame) = plan.png().unwrap();
    let img = decode(&bytes);
    let is = |p: (f64, f64), c: colour::Rgb| shows(&img, &frame, p, c, false);
    let near = |p: (f64, f64), c: colour::Rgb| shows(&img, &frame, p, c, true);
    // The notch (x > 7, y > 4) is no floor: background, away from its walls and the axes.
    for p in [(9.5, 6.0), (8.0, 7.5), (11.5, 4.5)] {
        assert!(is(p, colours::BACKGROUND), "{p:?} in the notch");
    }
    // The columns, 0.4 m square, filled: the work plane stands in them.
    for p in [(3.5, 4.0), (3.4, 3.9), (9.0, 2.0), (9.1, 2.1)] {
        assert!(is(p, colours::BLOCK), "{p:?} in a column");
    }
    // Walls along the L, the notch's two walls among them; windows on the south and east
    // façades; the desk's outline; the desk sensor.
    for p in [
        (0.0, 4.0),
        (7.0, 6.0),
        (9.5, 4.0),
        (12.0, 3.5),
        (5.0, 0.0),
        (3.0, 8.0),
    ] {
        assert!(near(p, colours::INK), "{p:?} on a wall");
    }
    for p in [(3.0, 0.0), (9.0, 0.0), (12.0, 2.0)] {
        assert!(near(p, colours::WINDOW), "{p:?} on a window");
    }
    assert!(near((6.0, 0.0), colours::INK) && !near((6.0, 0.0), colours::WINDOW));
    assert!(near((1.2, 6.0), colours::FURNITURE), "the desk's west edge");
    assert!(is((2.0, 6.0), colours::SENSOR), "the desk sensor");
    std::fs::remove_dir_all(&dir).ok();
}

/// Two work-plane zones of one floor (the L's two wings as task areas) on one plan: both
/// grids drawn in their colours on one scale, each zone's figures in the caption; zones at
/// different heights are refused.
#[test]
fn a_plan_draws_several_zones_of_one_floor() {
    let dir = scratch("l-office-zones");
    let zones = "[[zone]]\nname = \"west\"\nwork_plane = { room = \"office\", height = 0.8, area = { min = [0.5, 0.5], max = [6.5, 7.5] } }\n\n\
                 [[zone]]\nname = \"east\"\nwork_plane = { room = \"office\", height = 0.8, area = { min = [7.5, 0.5], max = [11.5, 3.5] } }\n\n\
                 [[zone]]\nname = \"high\"\nwork_plane = { room = \"office\", height = 1.2, area = { min = [0.5, 0.5], max = [2.5, 2.5] } }\n";
    let path = l_office(&dir, zones);
    let (levels, ff) = (LevelArgs::default(), FormFactorOptions::default());
    let names = ["west".to_string(), "east".to_string()];
    let mut r = request(&path, &levels, &ff);
    r.surfaces = None;
    r.zones = &names;
    let pictures = cli::render(&r).unwrap();
    let plan = pictures.plan.as_ref().unwrap();
    assert_eq!(plan.input.grids.len(), 2);
    assert!(
        plan.input.title.contains("west at 0.80 m") && plan.input.title.contains("east at 0.80 m")
    );
    let (bytes, frame) = plan.png().unwrap();
    let img = decode(&bytes);
    let half = plan.scale.bin_width() / 2.0;
    for (name, g) in names.iter().zip(&plan.input.grids) {
        assert_eq!(&g.zone, name);
        let grid = pictures
            .readout
            .grids
            .iter()
            .find(|r| &r.zone == name)
            .unwrap();
        assert_eq!(g.figures[0], grid.average[0]);
        for (p, v) in g.points.iter().zip(&g.values) {
            // Away from the columns, whose footprint covers part of their cells.
            if (p[0] - 3.5).abs() < 1.0 && (p[1] - 4.0).abs() < 1.0 {
                continue;
            }
            if (p[0] - 9.0).abs() < 1.0 && (p[1] - 2.0).abs() < 1.0 {
                continue;
            }
            let cell = [g.cell[0] / 2.0, g.cell[1] / 2.0];
            let shown =
                cell_value(&img, &frame, &plan.scale, (p[0], p[1]), cell).unwrap_or_else(|| {
                    panic!("{name} ({}, {}): not a colour of the scale", p[0], p[1])
                });
            assert!(
                (shown - v).abs() <= half + 1e-9,
                "{name} {p:?}: {shown} for {v}"
            );
        }
    }
    let both = ["west".to_string(), "high".to_string()];
    r.zones = &both;
    let e = cli::render(&r).unwrap_err().to_string();
    assert!(e.contains("--zone high") && e.contains("one height"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}
