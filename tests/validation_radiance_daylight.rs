//! Daylight against Radiance (`gensky`, `oconv`, `rtrace`): the harness that lights a room
//! through a window with Radiance's skies and sun, and its checks against closed forms.
//!
//! The room: the example office's shell (`examples/office/scene.toml`), 6 m × 4 m, 2.8 m high,
//! grey Lambertian floor 0.2, walls 0.5, ceiling 0.7, and its one window, 2.0 m × 1.4 m in the
//! wall y = 0 from x = 2 m to 4 m and z = 0.9 m to 2.3 m, facing −y: with north = 0 (the
//! scene's +y is true north) it faces south. Readings: upward points on the work plane
//! (0.8 m), the 9 × 5 cell centres that eigenrad's EN 12464-1 rule lays over the room less a
//! 0.5 m border (docs/scene.md, "Grids"); all of them lie below the sill, so each sees the
//! whole window above its own horizon.
//!
//! How Radiance is set up (pyradiance 1.3.1 ships Radiance 6.0a):
//!
//! - Glazing: Radiance's `glass` (`src/rt/m_glass.c`): one pane of index 1.52, Fresnel
//!   reflection per polarisation, the transmissivity `t` along the refracted path as
//!   `t^(1/cos θ_t)`, the inter-reflections within the pane added up,
//!   `T = ½ Σ_{s,p} (1 − r)² d / (1 − r² d²)`. The transmissivity comes from the normal
//!   transmittance τ_n by Radiance's formula (reference manual, "Glass"):
//!   `t = (√(0.8402528435 + 0.0072522239 τ_n²) − 0.9166530661) / 0.0036261119 / τ_n`.
//!   `glass_transmittance` below writes the same model out, so the test can integrate it.
//! - Sky: `gensky` (`-u` uniform, `-c` CIE overcast, `+s` CIE clear with sun) prints a
//!   `skyfunc` brightness function and, with `+s`, the sun as a `light` `source` of 0.5°. The
//!   scene keeps gensky's numbers but evaluates them with `SKY_CAL`, `skybright.cal`'s own
//!   formulas without its blend of sky and ground within about 10° of the horizon (weights
//!   `(Dz + 1.01)^±10`: at the horizon 55 % sky and 45 % ground), because the sky eigenrad is
//!   compared with ends at the horizon. Sky and ground are `glow` hemispheres of radius 0, so
//!   only Monte Carlo (ambient) rays see them, as gensky's manual shows.
//! - Units: Radiance's radiance is W/sr/m² of a white of 179 lm/W; `rtrace -I` answers in
//!   W/m² of it and illuminance is `179 (0.265 R + 0.670 G + 0.065 B)` lux
//!   (`common::radiance::lux`).
//!
//! The checks, each against a closed form or a quadrature written out here, so that a harness
//! bug (a window facing the wrong way, a unit, the glass conversion, the sun's direction or
//! its scaling) cannot pass:
//!
//! 1. The sky component under a uniform sky through an open hole equals π L F(point →
//!    window), with F the point-to-polygon form factor in closed form (`form_factor`); through
//!    the glass, `L ∫ τ(θ_w) cos θ_p cos θ_w / r² dA` by quadrature. All interior surfaces
//!    black, `rtrace -ab 1` (Monte Carlo: the tolerance is `MC_SIGMAS` standard errors of the
//!    mean of `REPEATS_CHECK` runs).
//! 2. The unobstructed horizontal illuminance under gensky's CIE overcast sky is its `-B`
//!    (W/m²) times 179, and its zenith luminance `9 E_h / (7π)`.
//! 3. Direct sun through the glass (`-ab 0`, deterministic): `E_dn τ(θ_w) sin h` where the ray
//!    from the point towards the sun crosses the window, nothing elsewhere; the sun's direction
//!    from `eigenrad sky` (NREL SPA) for the site and time of the clear-sky case, given to
//!    gensky as `-ang`.
//!
//! Then eigenrad against Radiance in the lit room (floor 0.2, walls 0.5, ceiling 0.7, the
//! window one pane of τ_n = 0.88), at the grid's 45 points, `cli::solve_with_daylight` (the
//! code of `eigenrad solve --time ... <sky>`, the exact dense solve) at `max_edge` 0.25 m with
//! Tregenza's sky against `rtrace -ab 16 -aa 0 -lr 0 -lw 1e-3` (`RTRACE_ROOM`), `REPEATS`
//! runs:
//!
//! 4. The daylight factor under the CIE overcast sky (gensky `-c`), `E / E_h` with E_h the
//!    sky's own horizontal illuminance (7π/9 L_z), which eigenrad is given as `--dhi-lux`.
//! 5. The illuminance under the CIE clear sky with sun (gensky `+s`, ISO 15469 type 12 for
//!    eigenrad, the same formula to its rounded constant 0.91) at the March equinox at noon,
//!    when the sun patch covers six of the points: eigenrad is given the Radiance sky's
//!    diffuse horizontal illuminance (`sky_horizontal`) and the sun's direct normal
//!    illuminance (its radiance times its solid angle).
//!
//! The ground, in both programs, is Lambertian at `ρ_g E_gh / π` (E_gh the global horizontal
//! illuminance, sky and sun). Each point must agree within `MC_SIGMAS` standard errors of
//! rtrace's mean plus three measured parts of eigenrad's error, each checked against its
//! stated bound on every run: the mesh (`MESH_ERROR`), the sky discretisation
//! (`SKY_DISCRETISATION`) and the window's reflection of the room's light, which the programs
//! model differently (`GLASS_REFLECTION`); and the mean relative difference over the points
//! within the mean allowance plus `MC_SIGMAS` standard errors of that mean (`compare`), which
//! catches a scale error that the per-point noise would hide. Negative controls: eigenrad with
//! the window in the opposite wall, glazing of 0.80, the sky 5 % too bright (overcast), north
//! turned by 180° or off by 15° (clear sky) must fail the same comparison.
//!
//! Run with `cargo test --test validation_radiance_daylight -- --nocapture` to see the tables
//! (about 140 CPU-seconds, 92 s to 2¼ minutes on two shared cores; the MF:4 solves take most of
//! eigenrad's part). Without Radiance each test prints "SKIPPED" and passes.

mod common;

use std::fmt::Write as _;
use std::path::Path;

use common::radiance::{self, Radiance, WHITE_EFFICACY};
use eigenrad::precompute::cli;
use eigenrad::precompute::formfactor::FormFactorOptions;

/// Room, from the origin to here, m.
const ROOM: [f64; 3] = [6.0, 4.0, 2.8];
/// The window in the wall y = 0: x from, x to, z from (sill), z to (head), m.
const WINDOW: [f64; 4] = [2.0, 4.0, 0.9, 2.3];
/// Every surface black: only the light through the window.
const BLACK: Reflectance = Reflectance {
    floor: 0.0,
    wall: 0.0,
    ceiling: 0.0,
};
/// The glazing's normal transmittance (clear single glazing).
const TAU_N: f64 = 0.88;
/// Radiance's `glass` index of refraction (its default).
const GLASS_INDEX: f64 = 1.52;
/// Height of the work plane and the border of its grid, m.
const WORK_PLANE: f64 = 0.8;
const GRID_BORDER: f64 = 0.5;
/// The grid's cells: EN 12464-1's spacing `p = 0.2 · 5^log10(d)` m for the longer side
/// d = 5 m is 0.616 m, so 5 m / p → 9 cells and 3 m / p → 5 cells.
const GRID_CELLS: [usize; 2] = [9, 5];
/// The site of the clear-sky case (Vienna) and the time: at the March equinox at noon the sun
/// stands 41.7° high due south and lays a sun patch on the work plane 0.1 m to 1.7 m from the
/// window wall.
const LATITUDE: f64 = 48.21;
const LONGITUDE: f64 = 16.37;
const CLEAR_TIME: &str = "2026-03-20T12:00+01:00";
/// Ground reflectance, gensky's `-g`.
const GROUND_REFLECTANCE: f64 = 0.2;

/// The sky function: `skybright.cal` (Radiance 6.0a) with its arguments (A1 sky type: 1 CIE
/// clear, 2 CIE overcast, 3 uniform; A2 zenith brightness; A3 ground brightness; A4 the clear
/// sky's normalisation; A5..A7 the sun's direction), its formulas unchanged, but sky above the
/// horizon and ground below it with no blend between them.
const SKY_CAL: &str = "\
skybr = if(Dz, select(A1, sunnysky, cloudysky, unifsky), A3);
cosgamma = Dx*A5 + Dy*A6 + Dz*A7;
gamma = Acos(cosgamma);
sunnysky = A2 * (.91 + 10*exp(-3*gamma) + .45*cosgamma*cosgamma)
    * if(Dz - .01, 1.0 - exp(-.32/Dz), 1.0) / A4;
cloudysky = A2 * (1 + 2*Dz)/3;
unifsky = A2;
";

/// Monte Carlo tolerance: this many standard errors of rtrace's mean (a normal error exceeds
/// 5σ with probability 6e-7).
const MC_SIGMAS: f64 = 5.0;
/// Runs per point in the sky-component check (`-ab 1`, black room: only the first hemisphere
/// sampling is random, `RTRACE_SKY_COMPONENT`).
const REPEATS_CHECK: usize = 16;
/// The standard error the sky-component check may have, relative: measured 0.3 % on average
/// and 0.6 % at most over the points (checked on every run, so that its tolerance is as
/// small as stated).
const MC_NOISE_CHECK: f64 = 1e-2;
/// gensky prints four significant digits: its numbers are exact to this, relative.
const GENSKY_DIGITS: f64 = 6e-4;
/// The quadrature over the window (`window_integral`): midpoint cells of this size, m. Its
/// error against the closed form is checked below `QUADRATURE_TOLERANCE`.
const QUADRATURE_CELL: f64 = 0.005;
const QUADRATURE_TOLERANCE: f64 = 1e-5;
/// A point closer than this to the sun patch's edge (in the window's plane, m) is left out of
/// the direct-sun check: there the answer depends on the last digit of the sun's direction.
const SUN_EDGE_MARGIN: f64 = 0.01;

/// `rtrace` for the sky component: one Monte Carlo bounce (`-ab 1`) with 16 384 rays over the
/// hemisphere, no ambient cache (`-aa 0`), no super-sampling, uncorrelated sampling (`-u+`),
/// so that repeated runs are independent.
const RTRACE_SKY_COMPONENT: &[&str] = &[
    "-h", "-I", "-ab", "1", "-aa", "0", "-ad", "16384", "-as", "0", "-lw", "1e-6", "-u+",
];
/// `rtrace` for direct light only: the sun sampled at its centre (`-dj 0`), every source tested
/// (`-dt 0 -dc 1`), no virtual sources, no ambient bounce.
const RTRACE_DIRECT: &[&str] = &[
    "-h", "-I", "-ab", "0", "-dj", "0", "-dt", "0", "-dc", "1", "-dr", "0", "-dp", "0",
];

struct Reflectance {
    floor: f64,
    wall: f64,
    ceiling: f64,
}

/// What fills the window in the Radiance scene.
#[derive(Clone, Copy)]
enum Opening {
    /// An open hole.
    Hole,
    /// Radiance `glass` of this normal transmittance.
    Glass(f64),
}

/// The work-plane points, upward: the grid's cell centres, first side (x) fastest.
fn work_plane_points() -> Vec<([f64; 3], [f64; 3])> {
    let [nx, ny] = GRID_CELLS;
    let (wx, wy) = (
        (ROOM[0] - 2.0 * GRID_BORDER) / nx as f64,
        (ROOM[1] - 2.0 * GRID_BORDER) / ny as f64,
    );
    let mut points = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let x = GRID_BORDER + (i as f64 + 0.5) * wx;
            let y = GRID_BORDER + (j as f64 + 0.5) * wy;
            points.push(([x, y, WORK_PLANE], [0.0, 0.0, 1.0]));
        }
    }
    points
}

/// The window's corners, counter-clockwise seen from inside the room (from +y).
fn window_corners() -> [[f64; 3]; 4] {
    let [x0, x1, z0, z1] = WINDOW;
    [[x0, 0., z0], [x0, 0., z1], [x1, 0., z1], [x1, 0., z0]]
}

/// The room as Radiance primitives: `plastic` of the given greys with no specularity and no
/// roughness (Lambertian), polygons wound to face into the room (counter-clockwise seen from
/// inside: Radiance's right-hand normal), the wall y = 0 in four pieces around the window,
/// and the window as `opening`.
fn radiance_room(rho: &Reflectance, opening: Opening) -> String {
    let [x, _, z] = ROOM;
    let [wx0, wx1, wz0, wz1] = WINDOW;
    let mut text = radiance::grey_room_but_y0(ROOM, rho.floor, rho.wall, rho.ceiling);
    // The y = 0 wall, seen from inside (+y), counter-clockwise: (x0, z0), (x0, z1), (x1, z1),
    // (x1, z0) in x and z.
    let wall_y0 = |x0: f64, x1: f64, z0: f64, z1: f64| {
        [[x0, 0., z0], [x0, 0., z1], [x1, 0., z1], [x1, 0., z0]]
    };
    let polygons: Vec<(&str, &str, [[f64; 3]; 4])> = vec![
        ("wall_mat", "wall_ymin_below", wall_y0(0., x, 0., wz0)),
        ("wall_mat", "wall_ymin_above", wall_y0(0., x, wz1, z)),
        ("wall_mat", "wall_ymin_left", wall_y0(0., wx0, wz0, wz1)),
        ("wall_mat", "wall_ymin_right", wall_y0(wx1, x, wz0, wz1)),
    ];
    for (material, name, corners) in polygons {
        radiance::write_polygon(&mut text, material, name, &corners);
    }
    if let Opening::Glass(tau_n) = opening {
        let t = glass_transmissivity(tau_n);
        writeln!(text, "void glass glass_mat 0 0 3 {t} {t} {t}").unwrap();
        radiance::write_polygon(&mut text, "glass_mat", "window", &window_corners());
    }
    text
}

/// Radiance's transmissivity of `glass` from the normal transmittance (reference manual,
/// "Glass").
fn glass_transmissivity(tau_n: f64) -> f64 {
    ((0.8402528435 + 0.0072522239 * tau_n * tau_n).sqrt() - 0.9166530661) / 0.0036261119 / tau_n
}

/// The transmittance of Radiance's `glass` of normal transmittance `tau_n` at an angle of
/// incidence of cosine `cos_i` (`m_glass.c`): Fresnel for index `GLASS_INDEX` per
/// polarisation, the transmissivity along the refracted path, the pane's inter-reflections.
fn glass_transmittance(tau_n: f64, cos_i: f64) -> f64 {
    let n = GLASS_INDEX;
    let cos_t = (1.0 - (1.0 - cos_i * cos_i) / (n * n)).sqrt();
    let r_s = ((cos_i - n * cos_t) / (cos_i + n * cos_t)).powi(2);
    let r_p = ((1.0 / cos_i - n / cos_t) / (1.0 / cos_i + n / cos_t)).powi(2);
    let d = glass_transmissivity(tau_n).powf(1.0 / cos_t);
    [r_s, r_p]
        .iter()
        .map(|r| 0.5 * (1.0 - r) * (1.0 - r) * d / (1.0 - r * r * d * d))
        .sum()
}

/// gensky's sky: the `skyfunc` arguments (A1, A2, ...) and, with `+s`, the sun's radiance
/// (W/sr/m², Radiance's white) and its direction (towards the sun, unit).
struct GenSky {
    sky: Vec<f64>,
    sun: Option<(f64, [f64; 3])>,
}

impl GenSky {
    /// Runs `gensky` with `args` and reads its output; panics if it is not as expected.
    fn run(radiance: &Radiance, dir: &Path, args: &[&str]) -> GenSky {
        let text = radiance.output("gensky", dir, args);
        // Comments off; what remains is primitives: modifier type name, then three argument
        // lists each prefixed by its count.
        let words: Vec<&str> = text
            .lines()
            .filter(|l| !l.trim_start().starts_with('#'))
            .flat_map(str::split_whitespace)
            .collect();
        let number = |w: &str| -> f64 { w.parse().unwrap_or_else(|_| panic!("gensky: `{w}`")) };
        let mut sky = None;
        let mut sun_radiance = None;
        let mut sun_direction = None;
        let mut k = 0;
        while k + 2 < words.len() {
            let (kind, name) = (words[k + 1], words[k + 2]);
            k += 3;
            let mut lists: Vec<Vec<&str>> = Vec::new();
            for _ in 0..3 {
                let count: usize = words[k].parse().expect("gensky argument count");
                lists.push(words[k + 1..k + 1 + count].to_vec());
                k += 1 + count;
            }
            let reals: Vec<f64> = lists[2].iter().map(|w| number(w)).collect();
            match (kind, name) {
                ("brightfunc", "skyfunc") => {
                    assert_eq!(lists[0], ["skybr", "skybright.cal"], "gensky sky function");
                    sky = Some(reals);
                }
                ("light", "solar") => sun_radiance = Some(reals[0]),
                ("source", "sun") => {
                    assert!((reals[3] - 0.5).abs() < 1e-9, "gensky's sun is 0.5°");
                    sun_direction = Some([reals[0], reals[1], reals[2]]);
                }
                other => panic!("gensky printed an unexpected {other:?}"),
            }
        }
        GenSky {
            sky: sky.expect("gensky printed no sky"),
            sun: sun_radiance.zip(sun_direction),
        }
    }

    /// The sky (and sun) as Radiance primitives over `SKY_CAL`, with the ground at
    /// `ground_radiance` (W/sr/m²) below the horizon.
    fn scene(&self, ground_radiance: f64) -> String {
        let mut args = self.sky.clone();
        args[2] = ground_radiance;
        // Skies without a sun direction (uniform, overcast) take the zenith: unused.
        args.resize(7, 0.0);
        if self.sky[0] != 1.0 {
            args[3] = 1.0;
            args[6] = 1.0;
        }
        let mut text = String::new();
        write!(text, "void brightfunc skyfunc 2 skybr sky.cal 0 7").unwrap();
        for a in &args {
            write!(text, " {a}").unwrap();
        }
        text.push('\n');
        text.push_str(
            "skyfunc glow sky_glow 0 0 4 1 1 1 0\n\
             sky_glow source sky 0 0 4 0 0 1 180\n\
             skyfunc glow ground_glow 0 0 4 1 1 1 0\n\
             ground_glow source ground 0 0 4 0 0 -1 180\n",
        );
        if let Some((radiance, [dx, dy, dz])) = self.sun {
            writeln!(
                text,
                "void light solar 0 0 3 {radiance} {radiance} {radiance}"
            )
            .unwrap();
            writeln!(text, "solar source sun 0 0 4 {dx} {dy} {dz} 0.5").unwrap();
        }
        text
    }
}

/// The solid angle of gensky's sun, a disc 0.5° across, sr (Radiance's `source` of angle a
/// subtends `2π (1 − cos(a/2))`).
fn sun_solid_angle() -> f64 {
    2.0 * std::f64::consts::PI * (1.0 - 0.25f64.to_radians().cos())
}

/// The form factor from a point `p` with unit normal `n` to the polygon `corners` (m), which
/// lies wholly above the point's plane: the contour integral of Lambert (Hottel and Sarofim,
/// "Radiative Transfer", 1967; Baum, Rushmeier and Winget, SIGGRAPH 1989, eq. 4),
/// `F = (1/2π) Σ_k γ_k n · (R_k × R_{k+1}) / |R_k × R_{k+1}|`, R_k the corners from p, γ_k the
/// angle between R_k and R_{k+1}.
fn form_factor(p: [f64; 3], n: [f64; 3], corners: &[[f64; 3]]) -> f64 {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let mut sum = 0.0;
    for k in 0..corners.len() {
        let (a, b) = (sub(corners[k], p), sub(corners[(k + 1) % corners.len()], p));
        let c = cross(a, b);
        let (la, lb, lc) = (dot(a, a).sqrt(), dot(b, b).sqrt(), dot(c, c).sqrt());
        let gamma = (dot(a, b) / (la * lb)).clamp(-1.0, 1.0).acos();
        sum += gamma * dot(n, c) / lc;
    }
    (sum / (2.0 * std::f64::consts::PI)).abs()
}

/// `∫ w(cos θ_w) cos θ_p cos θ_w / r² dA` over the window (sr) for an upward point `p`, by
/// the midpoint rule on cells of `QUADRATURE_CELL`; θ_w from the window's normal (+y).
fn window_integral(p: [f64; 3], weight: impl Fn(f64) -> f64) -> f64 {
    let [x0, x1, z0, z1] = WINDOW;
    let (nx, nz) = (
        ((x1 - x0) / QUADRATURE_CELL).round() as usize,
        ((z1 - z0) / QUADRATURE_CELL).round() as usize,
    );
    let (dx, dz) = ((x1 - x0) / nx as f64, (z1 - z0) / nz as f64);
    let mut sum = 0.0;
    for i in 0..nx {
        for k in 0..nz {
            let (x, z) = (x0 + (i as f64 + 0.5) * dx, z0 + (k as f64 + 0.5) * dz);
            let d = [x - p[0], -p[1], z - p[2]];
            let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            let r = r2.sqrt();
            let (cos_p, cos_w) = (d[2] / r, -d[1] / r);
            sum += weight(cos_w) * cos_p * cos_w / r2;
        }
    }
    sum * dx * dz
}

/// Where the ray from `p` towards the sun `s` (unit, towards the sun) meets the window.
enum SunAt {
    /// Through the window, at this cosine of incidence on the glass.
    Lit(f64),
    /// Not through the window.
    Shaded,
    /// Within `SUN_EDGE_MARGIN` of the window's edge: left out.
    Edge,
}

fn sun_at(p: [f64; 3], s: [f64; 3]) -> SunAt {
    let [x0, x1, z0, z1] = WINDOW;
    if s[1] >= 0.0 {
        return SunAt::Shaded;
    }
    let t = p[1] / -s[1];
    let (x, z) = (p[0] + t * s[0], p[2] + t * s[2]);
    let inside = (x - x0).min(x1 - x).min(z - z0).min(z1 - z);
    if inside.abs() < SUN_EDGE_MARGIN {
        SunAt::Edge
    } else if inside > 0.0 {
        SunAt::Lit(-s[1])
    } else {
        SunAt::Shaded
    }
}

/// The sun's position for the site at `time` from `eigenrad sky` (NREL SPA): altitude and
/// azimuth (°, clockwise from north) and the direction towards it in the scene's axes.
fn sun_position(time: &str) -> (f64, f64, [f64; 3]) {
    let out = common::run(&[
        "sky",
        "--lat",
        &LATITUDE.to_string(),
        "--lon",
        &LONGITUDE.to_string(),
        "--time",
        time,
        "--cie",
        "overcast",
        "--dhi-lux",
        "10000",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "eigenrad sky: {}",
        common::stderr(&out)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let sun = &json["sun"];
    let direction = &json["sun_direction_room"];
    let d = |k: usize| direction[k].as_f64().expect("sun_direction_room");
    (
        sun["altitude"].as_f64().expect("sun altitude"),
        sun["azimuth"].as_f64().expect("sun azimuth"),
        [d(0), d(1), d(2)],
    )
}

/// Whether `theirs` is within `MC_SIGMAS` of its standard errors plus `relative` of the
/// reference from `reference`.
fn within(reference: f64, theirs: radiance::Estimate, relative: f64) -> bool {
    (theirs.mean - reference).abs() <= MC_SIGMAS * theirs.standard_error + relative * reference
}

/// Radiance's readings `theirs` against `ours` (lux, deterministic) point by point, and the
/// mean of their relative differences, which averages the noise down and so tells a scale
/// error (glazing, sky scaling) that the per-point tolerance cannot. `allowance[i]` (lux) is
/// the systematic error allowed at point i on top of `MC_SIGMAS` standard errors; the mean may
/// differ by the mean relative allowance plus `MC_SIGMAS` standard errors of the mean. `Err`
/// names the first point or figure out of bounds.
fn compare(ours: &[f64], allowance: &[f64], theirs: &[radiance::Estimate]) -> Result<f64, String> {
    let points = work_plane_points();
    for (i, (p, _)) in points.iter().enumerate() {
        let (o, t) = (ours[i], theirs[i]);
        let tolerance = MC_SIGMAS * t.standard_error + allowance[i];
        if (t.mean - o).abs() > tolerance {
            return Err(format!(
                "at ({:.2}, {:.2}) m: {o:.1} lux against Radiance's {:.1} ± {:.1} lux, \
                 tolerance {tolerance:.1} lux",
                p[0], p[1], t.mean, t.standard_error
            ));
        }
    }
    let n = ours.len() as f64;
    let mean = (0..ours.len())
        .map(|i| theirs[i].mean / ours[i] - 1.0)
        .sum::<f64>()
        / n;
    let noise = (0..ours.len())
        .map(|i| (theirs[i].standard_error / ours[i]).powi(2))
        .sum::<f64>()
        .sqrt()
        / n;
    let systematic = (0..ours.len()).map(|i| allowance[i] / ours[i]).sum::<f64>() / n;
    let tolerance = MC_SIGMAS * noise + systematic;
    if mean.abs() > tolerance {
        return Err(format!(
            "Radiance reads {:+.2} % on average (± {:.2} %), tolerance {:.2} %",
            100.0 * mean,
            100.0 * noise,
            100.0 * tolerance
        ));
    }
    Ok(mean)
}

#[test]
fn contour_form_factor_matches_howell_b3() {
    // Howell's catalogue B-3: a plane element to a parallel rectangle a × b at distance c, the
    // element under one corner: F = (1/2π) [A/√(1+A²) atan(B/√(1+A²)) + B/√(1+B²)
    // atan(A/√(1+B²))], A = a/c, B = b/c.
    let (a, b, c): (f64, f64, f64) = (2.0, 1.4, 0.7);
    let (aa, bb) = (a / c, b / c);
    let howell = ((aa / (1.0 + aa * aa).sqrt()) * (bb / (1.0 + aa * aa).sqrt()).atan()
        + (bb / (1.0 + bb * bb).sqrt()) * (aa / (1.0 + bb * bb).sqrt()).atan())
        / (2.0 * std::f64::consts::PI);
    let corners = [[0., 0., c], [a, 0., c], [a, b, c], [0., b, c]];
    let ours = form_factor([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], &corners);
    assert!((ours - howell).abs() < 1e-12, "{ours} against {howell}");
    // And the quadrature the glass check uses, at an upward point facing the vertical window:
    // with weight 1 it is π F.
    for (p, _) in work_plane_points() {
        let closed = std::f64::consts::PI * form_factor(p, [0.0, 0.0, 1.0], &window_corners());
        let quadrature = window_integral(p, |_| 1.0);
        assert!(
            (quadrature / closed - 1.0).abs() < QUADRATURE_TOLERANCE,
            "{p:?}: quadrature {quadrature}, closed form {closed}"
        );
    }
    // And the glass model at normal incidence gives back τ_n (Radiance's conversion).
    for tau_n in [0.6, 0.8, 0.88, 0.9] {
        let t = glass_transmittance(tau_n, 1.0);
        // Radiance's constants have ten digits.
        assert!((t - tau_n).abs() < 1e-7, "τ(0) = {t} for τ_n = {tau_n}");
    }
}

#[test]
fn radiance_sky_component_through_the_window_matches_the_closed_form() {
    let Some(radiance) = Radiance::find() else {
        eprintln!("{}", radiance::SKIPPED);
        return;
    };
    let dir = radiance::scratch("daylight-sky-component");
    std::fs::write(dir.join("sky.cal"), SKY_CAL).unwrap();
    let points = work_plane_points();

    // A uniform sky of 100 W/m² horizontal: L = 100/π W/sr/m² (E_h = π L).
    let uniform = GenSky::run(&radiance, &dir, &["-ang", "45", "0", "-u", "-B", "100"]);
    let l = uniform.sky[1];
    assert_eq!(uniform.sky[0], 3.0, "gensky -u is sky type 3");
    assert!(
        (l * std::f64::consts::PI / 100.0 - 1.0).abs() < GENSKY_DIGITS,
        "gensky -u -B 100: zenith brightness {l}"
    );
    let sky = uniform.scene(GROUND_REFLECTANCE * 100.0 / std::f64::consts::PI);
    println!(
        "Sky component under a uniform sky of {:.0} cd/m², black room, rtrace -ab 1 -ad 16384, \
         mean of {REPEATS_CHECK} runs (lux)",
        WHITE_EFFICACY * l
    );
    println!("  point (x, y) m      hole: closed   rtrace  rel. diff | glass: quadrature   rtrace  rel. diff");
    let mut rows = Vec::new();
    for opening in [Opening::Hole, Opening::Glass(TAU_N)] {
        let name = match opening {
            Opening::Hole => "hole",
            Opening::Glass(_) => "glass",
        };
        let scene = radiance_room(&BLACK, opening) + &sky;
        let oct = radiance.octree(&dir, name, &scene);
        let theirs = radiance.trace(&dir, &oct, RTRACE_SKY_COMPONENT, &points, REPEATS_CHECK);
        let reference: Vec<f64> = points
            .iter()
            .map(|&(p, n)| match opening {
                Opening::Hole => {
                    WHITE_EFFICACY * l * std::f64::consts::PI * form_factor(p, n, &window_corners())
                }
                Opening::Glass(tau_n) => {
                    WHITE_EFFICACY * l * window_integral(p, |c| glass_transmittance(tau_n, c))
                }
            })
            .collect();
        rows.push((reference, theirs));
    }
    for (i, (p, _)) in points.iter().enumerate() {
        let (h, g) = (&rows[0], &rows[1]);
        println!(
            "  ({:4.2}, {:4.2})   {:14.1} {:8.1} {:10.2e} | {:17.1} {:8.1} {:10.2e}",
            p[0],
            p[1],
            h.0[i],
            h.1[i].mean,
            h.1[i].mean / h.0[i] - 1.0,
            g.0[i],
            g.1[i].mean,
            g.1[i].mean / g.0[i] - 1.0
        );
    }
    for ((reference, theirs), what) in rows.iter().zip(["hole", "glass"]) {
        for (i, (p, _)) in points.iter().enumerate() {
            assert!(
                theirs[i].standard_error <= MC_NOISE_CHECK * reference[i],
                "{what}, {p:?}: rtrace's standard error {} of {} lux",
                theirs[i].standard_error,
                reference[i]
            );
        }
        let allowance: Vec<f64> = reference.iter().map(|r| GENSKY_DIGITS * r).collect();
        let mean = compare(reference, &allowance, theirs).unwrap_or_else(|e| panic!("{what}: {e}"));
        println!("  {what}: Radiance {:+.3} % on average", 100.0 * mean);
    }
    // gensky's CIE overcast sky: zenith luminance 9 E_h / (7π), and an unobstructed upward
    // point outdoors reads E_h = 179 × B lux.
    let b = 100.0;
    let overcast = GenSky::run(
        &radiance,
        &dir,
        &["-ang", "45", "0", "-c", "-B", &b.to_string()],
    );
    assert_eq!(overcast.sky[0], 2.0, "gensky -c is sky type 2");
    let zenith = 9.0 * b / (7.0 * std::f64::consts::PI);
    assert!(
        (overcast.sky[1] / zenith - 1.0).abs() < GENSKY_DIGITS,
        "gensky -c -B {b}: zenith brightness {} against {zenith}",
        overcast.sky[1]
    );
    let oct = radiance.octree(
        &dir,
        "outdoors",
        &overcast.scene(GROUND_REFLECTANCE * b / std::f64::consts::PI),
    );
    let open = radiance.trace(
        &dir,
        &oct,
        RTRACE_SKY_COMPONENT,
        &[([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])],
        REPEATS_CHECK,
    )[0];
    let horizontal = WHITE_EFFICACY * b;
    println!(
        "Unobstructed horizontal illuminance under gensky -c -B {b}: {horizontal:.1} lux, rtrace \
         {:.1} ± {:.1} lux",
        open.mean, open.standard_error
    );
    assert!(
        within(horizontal, open, GENSKY_DIGITS),
        "outdoors: {horizontal} lux expected, rtrace {} ± {} lux",
        open.mean,
        open.standard_error
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn radiance_direct_sun_through_the_glass_is_the_window_projected() {
    let Some(radiance) = Radiance::find() else {
        eprintln!("{}", radiance::SKIPPED);
        return;
    };
    let dir = radiance::scratch("daylight-sun");
    std::fs::write(dir.join("sky.cal"), SKY_CAL).unwrap();
    let (altitude, azimuth, s) = sun_position(CLEAR_TIME);
    // gensky's azimuth runs west from south; its sun direction must be eigenrad's.
    let (dhi, dni) = (100.0, 500.0);
    let dir_horizontal = dni * altitude.to_radians().sin();
    let clear = GenSky::run(
        &radiance,
        &dir,
        &[
            "-ang",
            &altitude.to_string(),
            &(azimuth - 180.0).to_string(),
            "+s",
            "-B",
            &dhi.to_string(),
            "-R",
            &dir_horizontal.to_string(),
        ],
    );
    let (sun_radiance, sun_direction) = clear.sun.expect("gensky +s prints a sun");
    for k in 0..3 {
        assert!(
            (sun_direction[k] - s[k]).abs() < 2e-6,
            "gensky's sun {sun_direction:?}, eigenrad's {s:?}"
        );
    }
    // gensky's sun gives `-R` on the horizontal: its direct normal is R / sin h.
    let e_dn = sun_radiance * sun_solid_angle();
    assert!(
        (e_dn / dni - 1.0).abs() < GENSKY_DIGITS,
        "gensky's sun: {e_dn} W/m² normal, {dni} asked"
    );
    let scene = radiance_room(&BLACK, Opening::Glass(TAU_N)) + &clear.scene(0.0);
    let oct = radiance.octree(&dir, "sun", &scene);
    let points = work_plane_points();
    let theirs = radiance.trace(&dir, &oct, RTRACE_DIRECT, &points, 1);
    println!(
        "Direct sun at altitude {altitude:.2}°, azimuth {azimuth:.2}°, {:.0} lux normal, \
         through the glass, black room, rtrace -ab 0 (lux)",
        WHITE_EFFICACY * e_dn
    );
    let (mut lit, mut shaded) = (0, 0);
    for ((p, _), t) in points.iter().zip(&theirs) {
        let expected = match sun_at(*p, s) {
            SunAt::Edge => {
                println!(
                    "  ({:4.2}, {:4.2})  at the sun patch's edge: left out",
                    p[0], p[1]
                );
                continue;
            }
            SunAt::Shaded => {
                shaded += 1;
                0.0
            }
            SunAt::Lit(cos_w) => {
                lit += 1;
                WHITE_EFFICACY * e_dn * glass_transmittance(TAU_N, cos_w) * s[2]
            }
        };
        println!(
            "  ({:4.2}, {:4.2})  {expected:10.1} {:10.1}",
            p[0], p[1], t.mean
        );
        assert!(
            (t.mean - expected).abs() <= GENSKY_DIGITS * expected + 1e-9,
            "{p:?}: the window's projection gives {expected} lux, rtrace {} lux",
            t.mean
        );
    }
    assert!(
        lit >= 5 && shaded >= 5,
        "the sun patch covers part of the work plane ({lit} points lit, {shaded} not)"
    );
    std::fs::remove_dir_all(&dir).ok();
}

// ---------------------------------------------------------------------------------------------
// eigenrad against Radiance in the lit room: daylight factor under the CIE overcast sky and
// illuminance under the clear sky with sun.
// ---------------------------------------------------------------------------------------------

/// Reflectances of floor, walls and ceiling (grey, diffuse).
const REFLECTANCE: Reflectance = Reflectance {
    floor: 0.2,
    wall: 0.5,
    ceiling: 0.7,
};
/// The weather of the comparisons: the overcast sky's diffuse horizontal illuminance, and the
/// clear sky's diffuse horizontal and direct normal illuminance, lux.
const OVERCAST_DHI: f64 = 10_000.0;
const CLEAR_DHI: f64 = 15_000.0;
const CLEAR_DNI: f64 = 70_000.0;
/// eigenrad's patch size compared with Radiance, and the coarser one that measures its mesh
/// error, m.
const MAX_EDGE: f64 = 0.25;
const MAX_EDGE_COARSE: f64 = 0.5;
/// The finer sky discretisation that measures the error of eigenrad's default (Tregenza, MF:1):
/// Reinhart MF:4, 2305 patches.
const MF_FINE: u8 = 4;

/// Runs per point in the interreflected comparisons.
const REPEATS: usize = 64;
/// `rtrace` in the lit room: 16 diffuse bounces, no ambient cache (`-aa 0`: pure Monte Carlo),
/// 2048 hemisphere samples at most per bounce, no super-sampling, uncorrelated sampling, and
/// Russian roulette below a ray weight of 10⁻³ (`-lr 0 -lw 1e-3`; `rayorigin()` in
/// `src/rt/raytrace.c`: a ray under the weight survives with probability weight/10⁻³ and is
/// promoted, so the estimate stays unbiased). With a positive `-lr`, rays under `-lw` are
/// dropped instead, which biases the interreflected light low: averaged over the work plane
/// under the overcast sky, 21 % at `-lr 20 -lw 1e-3`, 8 % at `1e-4` and 0.1 % ± 0.1 % at
/// `1e-6` (16 runs each), which costs nine times the roulette's time for its noise. The sun is
/// sampled at its centre (`-dj 0`), every source tested for every point.
const RTRACE_ROOM: &[&str] = &[
    "-h", "-I", "-ab", "16", "-aa", "0", "-ad", "2048", "-as", "0", "-lr", "0", "-lw", "1e-3",
    "-u+", "-dj", "0", "-dt", "0", "-dc", "1", "-dr", "0", "-dp", "0",
];
/// The standard error rtrace's mean may have, relative, in the lit room: measured 0.6 % on
/// average and 1.2 % at most over the points under the overcast sky, 0.9 % at most under the
/// clear sky (checked on every run).
const MC_NOISE: f64 = 2e-2;
/// eigenrad's mesh error at `MAX_EDGE`, relative: measured as the change of each point's
/// reading from `MAX_EDGE_COARSE`, at most 0.15 % under the overcast sky and 0.19 % under the
/// clear sky (checked on every run: the mesh is deterministic).
/// The error of constant exitance per patch falls by 2 to 4 when the patches halve, so this
/// change bounds the finer mesh's error.
const MESH_ERROR: f64 = 5e-3;
/// The error of the sky discretisation (Tregenza's 145 patches, each at its centre's
/// luminance), relative: measured as the change of each reading from MF:1 to MF:4, at most
/// 0.54 % under the overcast sky and 0.65 % under the clear sky (checked on every run). Its error falls about as the patches' area, 16 times from MF:1 to
/// MF:4, so this change bounds MF:1's error against the continuous sky.
const SKY_DISCRETISATION: f64 = 1e-2;
/// The window's own reflection of the room's light, relative: Radiance's glass reflects
/// specularly, 7.8 % at normal incidence and 14.8 % averaged over a diffuse hemisphere
/// (`glass_reflectance`), eigenrad's window diffusely at `window_reflectance()` (the most its
/// scene check lets a glazing of τ_n have). The allowance is all the light the window reflects
/// onto the point in eigenrad, scaled up to Radiance's hemispherical reflectance: measured
/// 0.44 % at most under the overcast sky and 1.1 % under the clear sky (checked on every run).
const GLASS_REFLECTION: f64 = 2e-2;

/// The reflectance of Radiance's `glass` of normal transmittance `tau_n` at an angle of
/// incidence of cosine `cos_i` (`m_glass.c`, as `glass_transmittance`).
fn glass_reflectance(tau_n: f64, cos_i: f64) -> f64 {
    let n = GLASS_INDEX;
    let cos_t = (1.0 - (1.0 - cos_i * cos_i) / (n * n)).sqrt();
    let r_s = ((cos_i - n * cos_t) / (cos_i + n * cos_t)).powi(2);
    let r_p = ((1.0 / cos_i - n / cos_t) / (1.0 / cos_i + n / cos_t)).powi(2);
    let d = glass_transmissivity(tau_n).powf(1.0 / cos_t);
    [r_s, r_p]
        .iter()
        .map(|r| 0.5 * (r + (1.0 - r) * (1.0 - r) * r * d * d / (1.0 - r * r * d * d)))
        .sum()
}

/// `glass_reflectance` averaged over a diffuse (cosine-weighted) hemisphere of incidence:
/// `2 ∫ R(θ) cos θ sin θ dθ` by the midpoint rule on 2000 steps.
fn glass_reflectance_hemispherical(tau_n: f64) -> f64 {
    let steps = 2000;
    let h = std::f64::consts::FRAC_PI_2 / steps as f64;
    (0..steps)
        .map(|k| {
            let theta = (k as f64 + 0.5) * h;
            2.0 * glass_reflectance(tau_n, theta.cos()) * theta.cos() * theta.sin() * h
        })
        .sum()
}

/// eigenrad's reflectance for the window: `1 − τ_n`, the most its scene check allows with
/// the transmittance τ_n.
fn window_reflectance() -> f64 {
    1.0 - TAU_N
}

/// What an eigenrad scene may get wrong, for the negative controls.
#[derive(Clone, Copy)]
struct Variant {
    /// The scene's `north`, degrees.
    north: f64,
    /// The window in the wall y = 4 m (facing +y outwards, north) instead of y = 0.
    window_opposite: bool,
    /// The glazing's normal transmittance.
    tau_n: f64,
    /// The window's reflectance.
    window_reflectance: f64,
}

const RIGHT: Variant = Variant {
    north: 0.0,
    window_opposite: false,
    tau_n: TAU_N,
    window_reflectance: 1.0 - TAU_N,
};

/// The room as eigenrad TOML: the same shell, window and work plane, one pane of clear glass
/// (Radiance's `glass` model), the site of `LATITUDE`, `LONGITUDE`.
fn eigenrad_scene(max_edge: f64, v: Variant) -> String {
    let [x, y, z] = ROOM;
    let [wx0, wx1, wz0, wz1] = WINDOW;
    // Wound to face into the room: +y for the wall y = 0, −y for the wall y = 4 m.
    let corners = if v.window_opposite {
        format!(
            "[[{wx1}, {y}, {wz0}], [{wx1}, {y}, {wz1}], [{wx0}, {y}, {wz1}], [{wx0}, {y}, {wz0}]]"
        )
    } else {
        format!("[[{wx0}, 0, {wz0}], [{wx0}, 0, {wz1}], [{wx1}, 0, {wz1}], [{wx1}, 0, {wz0}]]")
    };
    format!(
        r#"[scene]
name = "daylight room"
bands = "photopic"
unit = "m"
max_edge = {max_edge}

[site]
latitude = {LATITUDE}
longitude = {LONGITUDE}
north = {north}
ground_reflectance = {GROUND_REFLECTANCE}

[materials]
floor = {{ reflectance = {floor} }}
wall = {{ reflectance = {wall} }}
ceiling = {{ reflectance = {ceiling} }}
glass = {{ reflectance = {glass_r}, transmittance = {tau_n}, panes = 1 }}

[[room]]
name = "room"
min = [0, 0, 0]
max = [{x}, {y}, {z}]
material = "wall"
floor = "floor"
ceiling = "ceiling"
openings = ["window"]

[[quad]]
name = "window"
material = "glass"
corners = {corners}

[[zone]]
name = "work_plane"
work_plane = {{ room = "room", height = {WORK_PLANE}, margin = {GRID_BORDER}, max_edge = 0.5 }}
"#,
        north = v.north,
        floor = REFLECTANCE.floor,
        wall = REFLECTANCE.wall,
        ceiling = REFLECTANCE.ceiling,
        glass_r = v.window_reflectance,
        tau_n = v.tau_n,
    )
}

/// eigenrad's exact solve with daylight (`cli::solve_with_daylight`, the code of `eigenrad
/// solve --time ... <sky>`) of the scene `text` (written into `dir` as `name.toml`) under
/// `sky` at `time`, the sky in Reinhart MF:`mf` patches: the work-plane grid's illuminances,
/// lux, in `work_plane_points()` order (checked).
fn eigenrad_grid(dir: &Path, name: &str, text: &str, time: &str, sky: Sky) -> Vec<f64> {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    let daylight = cli::DaylightArgs {
        time: time.into(),
        input: cli::SkyInput::Cie {
            sky_type: sky.cie,
            diffuse_horizontal: sky.dhi,
            direct_normal: sky.dni,
        },
        water: 2.0,
        subdivision: sky.mf,
    };
    let readout = cli::solve_with_daylight(
        &path,
        &cli::LevelArgs::default(),
        Some(&daylight),
        false,
        &FormFactorOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"));
    let points = work_plane_points();
    let grid = &readout.grids[0].points;
    assert_eq!(
        grid.len(),
        points.len(),
        "{name}: the work plane's grid points"
    );
    grid.iter()
        .zip(&points)
        .map(|(g, (p, _))| {
            for k in 0..3 {
                assert!(
                    (g.position_m[k] - p[k]).abs() < 1e-9,
                    "{name}: grid point {:?} is not at {p:?}",
                    g.position_m
                );
            }
            g.irradiance[0]
        })
        .collect()
}

/// A CIE sky for eigenrad: type (0: the traditional overcast sky), diffuse horizontal and
/// direct normal illuminance (lux), Reinhart MF.
#[derive(Clone, Copy)]
struct Sky {
    cie: u8,
    dhi: f64,
    dni: f64,
    mf: u8,
}

/// `∫ L cos Z dω` over the upper hemisphere of the `SKY_CAL` sky `args` (Radiance units,
/// W/m²), by the midpoint rule on 1500 zenith × 3000 azimuth cells (the clear sky's
/// circumsolar cusp makes it converge as the cells' area: 10⁻⁵ relative here).
fn sky_horizontal(args: &[f64]) -> f64 {
    let (nz, na) = (1500usize, 3000usize);
    let (hz, ha) = (
        std::f64::consts::FRAC_PI_2 / nz as f64,
        2.0 * std::f64::consts::PI / na as f64,
    );
    let sun = [args[4], args[5], args[6]];
    let mut sum = 0.0;
    for i in 0..nz {
        let zenith = (i as f64 + 0.5) * hz;
        let (sz, cz) = zenith.sin_cos();
        let mut row = 0.0;
        for j in 0..na {
            let (sa, ca) = ((j as f64 + 0.5) * ha).sin_cos();
            row += sky_luminance(args, [sz * ca, sz * sa, cz], sun);
        }
        sum += row * cz * sz;
    }
    sum * hz * ha
}

/// `SKY_CAL`'s sky brightness in the direction `d` (unit, upward).
fn sky_luminance(args: &[f64], d: [f64; 3], sun: [f64; 3]) -> f64 {
    match args[0] as u32 {
        1 => {
            let cos_g = (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2]).clamp(-1.0, 1.0);
            let gamma = cos_g.acos();
            let gradation = if d[2] > 0.01 {
                1.0 - (-0.32 / d[2]).exp()
            } else {
                1.0
            };
            args[1] * (0.91 + 10.0 * (-3.0 * gamma).exp() + 0.45 * cos_g * cos_g) * gradation
                / args[3]
        }
        2 => args[1] * (1.0 + 2.0 * d[2]) / 3.0,
        3 => args[1],
        other => panic!("sky type {other}"),
    }
}

/// Radiance in the lit room (`REFLECTANCE`, the glazed window) under `sky` with the ground at
/// `ground` (W/sr/m²): every work-plane point, `REPEATS` runs.
fn radiance_in_the_room(
    radiance: &Radiance,
    dir: &Path,
    name: &str,
    sky: &GenSky,
    ground: f64,
) -> Vec<radiance::Estimate> {
    let scene = radiance_room(&REFLECTANCE, Opening::Glass(TAU_N)) + &sky.scene(ground);
    let oct = radiance.octree(dir, name, &scene);
    radiance.trace(dir, &oct, RTRACE_ROOM, &work_plane_points(), REPEATS)
}

/// eigenrad's readings of one sky and what each may be off by.
struct Ours {
    /// At `MAX_EDGE`, Tregenza sky, lux.
    readings: Vec<f64>,
    /// The allowance per point, lux: mesh change + sky discretisation change + the window's
    /// reflection (`GLASS_REFLECTION`).
    allowance: Vec<f64>,
    /// The three parts, relative to the reading.
    mesh: Vec<f64>,
    sky: Vec<f64>,
    glass: Vec<f64>,
}

/// eigenrad under `sky` at `time`, with its error budget measured: the mesh at `MAX_EDGE`
/// against `MAX_EDGE_COARSE`, Tregenza against MF:`MF_FINE` (at the coarse mesh: the
/// discretisation's error is in the light through the window, which the mesh does not change
/// at a point), and the window's reflection (at the coarse mesh). Checks each part against its
/// stated bound.
fn eigenrad_with_budget(dir: &Path, name: &str, time: &str, sky: Sky) -> Ours {
    let grid = |what: &str, max_edge: f64, v: Variant, mf: u8| {
        let sky = Sky { mf, ..sky };
        let scene = eigenrad_scene(max_edge, v);
        eigenrad_grid(dir, &format!("{name}-{what}"), &scene, time, sky)
    };
    let unreflecting = Variant {
        window_reflectance: 0.0,
        ..RIGHT
    };
    // Four independent solves: run side by side.
    let [readings, coarse, fine_sky, no_glass_reflection] = std::thread::scope(|scope| {
        [
            scope.spawn(|| grid("fine", MAX_EDGE, RIGHT, 1)),
            scope.spawn(|| grid("coarse", MAX_EDGE_COARSE, RIGHT, 1)),
            scope.spawn(|| grid("mf", MAX_EDGE_COARSE, RIGHT, MF_FINE)),
            scope.spawn(|| grid("unreflecting", MAX_EDGE_COARSE, unreflecting, 1)),
        ]
        .map(|h| h.join().expect("eigenrad solve"))
    });
    let scale = glass_reflectance_hemispherical(TAU_N) / window_reflectance();
    let n = readings.len();
    let mesh: Vec<f64> = (0..n)
        .map(|i| (coarse[i] - readings[i]).abs() / readings[i])
        .collect();
    let sky: Vec<f64> = (0..n)
        .map(|i| (fine_sky[i] - coarse[i]).abs() / coarse[i])
        .collect();
    let glass: Vec<f64> = (0..n)
        .map(|i| scale * (coarse[i] - no_glass_reflection[i]).abs() / coarse[i])
        .collect();
    let points = work_plane_points();
    for i in 0..n {
        let p = points[i].0;
        assert!(
            mesh[i] <= MESH_ERROR,
            "{name}, {p:?}: mesh change {}",
            mesh[i]
        );
        assert!(
            sky[i] <= SKY_DISCRETISATION,
            "{name}, {p:?}: change from MF:1 to MF:{MF_FINE} {}",
            sky[i]
        );
        assert!(
            glass[i] <= GLASS_REFLECTION,
            "{name}, {p:?}: the window's reflection {}",
            glass[i]
        );
    }
    let allowance = (0..n)
        .map(|i| (mesh[i] + sky[i] + glass[i]) * readings[i])
        .collect();
    Ours {
        readings,
        allowance,
        mesh,
        sky,
        glass,
    }
}

/// Prints eigenrad's and Radiance's readings side by side, `unit` (lux) divided by `per`.
fn print_table(ours: &Ours, theirs: &[radiance::Estimate], per: f64, unit: &str) {
    println!(
        "  point (x, y) m   eigenrad {unit:>5}   Radiance {unit:>5}  std. err.  rel. diff | mesh chg.  sky chg.  window r.  tolerance"
    );
    for (i, (p, _)) in work_plane_points().iter().enumerate() {
        let (o, t) = (ours.readings[i], theirs[i]);
        let tolerance = (MC_SIGMAS * t.standard_error + ours.allowance[i]) / o;
        println!(
            "  ({:4.2}, {:4.2})   {:14.3} {:16.3} {:10.2e} {:10.2e} | {:9.2e} {:9.2e} {:10.2e} {:10.2e}",
            p[0],
            p[1],
            o / per,
            t.mean / per,
            t.standard_error / t.mean,
            t.mean / o - 1.0,
            ours.mesh[i],
            ours.sky[i],
            ours.glass[i],
            tolerance
        );
    }
}

/// Checks rtrace's noise against `MC_NOISE`.
fn check_noise(name: &str, theirs: &[radiance::Estimate]) {
    for ((p, _), t) in work_plane_points().iter().zip(theirs) {
        assert!(
            t.standard_error <= MC_NOISE * t.mean,
            "{name}, {p:?}: rtrace's standard error {} of {} lux",
            t.standard_error,
            t.mean
        );
    }
}

/// A negative control: what eigenrad would get wrong, its scene and its sky flags.
struct Control {
    what: &'static str,
    variant: Variant,
    sky: Sky,
}

/// The negative controls: eigenrad with each control's mistake, at the coarse mesh under the
/// same sky, must fail the comparison that the right scene passes (the solves run side by
/// side).
fn must_miss(
    dir: &Path,
    time: &str,
    controls: &[Control],
    ours: &Ours,
    theirs: &[radiance::Estimate],
) {
    let wrong: Vec<Vec<f64>> = std::thread::scope(|scope| {
        let handles: Vec<_> = controls
            .iter()
            .map(|c| {
                scope.spawn(move || {
                    eigenrad_grid(
                        dir,
                        &format!("control-{}", c.what.replace(' ', "-")),
                        &eigenrad_scene(MAX_EDGE_COARSE, c.variant),
                        time,
                        c.sky,
                    )
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("eigenrad solve"))
            .collect()
    });
    for (c, wrong) in controls.iter().zip(&wrong) {
        match compare(wrong, &ours.allowance, theirs) {
            Ok(mean) => panic!(
                "eigenrad with {} passes the comparison ({:+.2} % on average)",
                c.what,
                100.0 * mean
            ),
            Err(e) => println!("  control, {}: fails as it must: {e}", c.what),
        }
    }
}

#[test]
fn daylight_factor_under_the_cie_overcast_sky_matches_radiance() {
    let Some(radiance) = Radiance::find() else {
        eprintln!("{}", radiance::SKIPPED);
        return;
    };
    let dir = radiance::scratch("daylight-overcast");
    std::fs::write(dir.join("sky.cal"), SKY_CAL).unwrap();
    let (altitude, azimuth, _) = sun_position(CLEAR_TIME);
    let b = OVERCAST_DHI / WHITE_EFFICACY;
    let overcast = GenSky::run(
        &radiance,
        &dir,
        &[
            "-ang",
            &altitude.to_string(),
            &(azimuth - 180.0).to_string(),
            "-c",
            "-B",
            &b.to_string(),
        ],
    );
    // The sky's own horizontal illuminance (7π/9 L_z, exact for SKY_CAL's overcast sky), which
    // eigenrad is given and the daylight factor divides by.
    let e_h = WHITE_EFFICACY * 7.0 * std::f64::consts::PI / 9.0 * overcast.sky[1];
    assert!(
        (e_h / OVERCAST_DHI - 1.0).abs() < GENSKY_DIGITS,
        "gensky -c: {e_h} lux"
    );
    let ground = GROUND_REFLECTANCE * e_h / std::f64::consts::PI / WHITE_EFFICACY;
    let sky = Sky {
        cie: 0,
        dhi: e_h,
        dni: 0.0,
        mf: 1,
    };
    let (theirs, ours) = std::thread::scope(|scope| {
        let theirs =
            scope.spawn(|| radiance_in_the_room(&radiance, &dir, "overcast", &overcast, ground));
        let ours = eigenrad_with_budget(&dir, "overcast", CLEAR_TIME, sky);
        (theirs.join().expect("rtrace"), ours)
    });
    println!(
        "Daylight factor (%) under the CIE overcast sky, E_h = {e_h:.0} lux: eigenrad solve at \
         max_edge {MAX_EDGE} m, Tregenza sky, against rtrace -ab 16 -aa 0 -ad 2048 -lr 0 -lw 1e-3, \
         mean of {REPEATS} runs"
    );
    print_table(&ours, &theirs, e_h / 100.0, "DF %");
    check_noise("overcast", &theirs);
    let mean = compare(&ours.readings, &ours.allowance, &theirs)
        .unwrap_or_else(|e| panic!("overcast: {e}"));
    println!("  Radiance {:+.2} % on average", 100.0 * mean);

    // The comparison tells a wrong window, glazing or sky scaling apart.
    let controls = [
        Control {
            what: "the window in the opposite wall",
            variant: Variant {
                window_opposite: true,
                ..RIGHT
            },
            sky,
        },
        Control {
            what: "glazing of 0.80",
            variant: Variant {
                tau_n: 0.8,
                window_reflectance: 0.2,
                ..RIGHT
            },
            sky,
        },
        Control {
            what: "the sky 5 % too bright",
            variant: RIGHT,
            sky: Sky {
                dhi: 1.05 * e_h,
                ..sky
            },
        },
    ];
    must_miss(&dir, CLEAR_TIME, &controls, &ours, &theirs);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn clear_sky_and_sun_on_the_work_plane_match_radiance() {
    let Some(radiance) = Radiance::find() else {
        eprintln!("{}", radiance::SKIPPED);
        return;
    };
    let dir = radiance::scratch("daylight-clear");
    std::fs::write(dir.join("sky.cal"), SKY_CAL).unwrap();
    let (altitude, azimuth, s) = sun_position(CLEAR_TIME);
    let sin_h = altitude.to_radians().sin();
    let clear = GenSky::run(
        &radiance,
        &dir,
        &[
            "-ang",
            &altitude.to_string(),
            &(azimuth - 180.0).to_string(),
            "+s",
            "-B",
            &(CLEAR_DHI / WHITE_EFFICACY).to_string(),
            "-R",
            &(CLEAR_DNI * sin_h / WHITE_EFFICACY).to_string(),
        ],
    );
    let (sun_radiance, _) = clear.sun.expect("gensky +s prints a sun");
    let e_dn = WHITE_EFFICACY * sun_radiance * sun_solid_angle();
    // The sky's own diffuse horizontal illuminance (gensky normalises it by a fit, within
    // 0.3 % of `-B`), which eigenrad is given.
    let e_dh = WHITE_EFFICACY * sky_horizontal(&clear.sky);
    assert!(
        (e_dh / CLEAR_DHI - 1.0).abs() < 5e-3,
        "gensky +s: {e_dh} lux diffuse"
    );
    let ground = GROUND_REFLECTANCE * (e_dh + e_dn * sin_h) / std::f64::consts::PI / WHITE_EFFICACY;
    let sky = Sky {
        cie: 12,
        dhi: e_dh,
        dni: e_dn,
        mf: 1,
    };
    let (theirs, ours) = std::thread::scope(|scope| {
        let theirs = scope.spawn(|| radiance_in_the_room(&radiance, &dir, "clear", &clear, ground));
        let ours = eigenrad_with_budget(&dir, "clear", CLEAR_TIME, sky);
        (theirs.join().expect("rtrace"), ours)
    });
    println!(
        "Illuminance (lux) under the CIE clear sky (type 12), {e_dh:.0} lux diffuse and {e_dn:.0} \
         lux direct normal, sun at {altitude:.2}° and {azimuth:.2}°: eigenrad solve at max_edge \
         {MAX_EDGE} m, Tregenza sky, against rtrace -ab 16 -aa 0 -ad 2048 -lr 0 -lw 1e-3, mean of \
         {REPEATS} runs"
    );
    print_table(&ours, &theirs, 1.0, "lux");
    // The sun patch covers part of the grid, no point on its edge.
    let points = work_plane_points();
    let lit = points
        .iter()
        .filter(|(p, _)| match sun_at(*p, s) {
            SunAt::Lit(_) => true,
            SunAt::Shaded => false,
            SunAt::Edge => panic!("{p:?} lies on the sun patch's edge: choose another time"),
        })
        .count();
    assert!(
        lit >= 5 && lit + 5 <= points.len(),
        "{lit} points in the sun"
    );
    check_noise("clear", &theirs);
    let mean =
        compare(&ours.readings, &ours.allowance, &theirs).unwrap_or_else(|e| panic!("clear: {e}"));
    println!("  Radiance {:+.2} % on average", 100.0 * mean);

    // The comparison tells a wrong north apart: the sun patch moves.
    let controls = [
        Control {
            what: "north turned by 180°",
            variant: Variant {
                north: 180.0,
                ..RIGHT
            },
            sky,
        },
        Control {
            what: "north off by 15°",
            variant: Variant {
                north: 15.0,
                ..RIGHT
            },
            sky,
        },
    ];
    must_miss(&dir, CLEAR_TIME, &controls, &ours, &theirs);
    std::fs::remove_dir_all(&dir).ok();
}
