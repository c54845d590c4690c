//! A year of daylight against Radiance's daylight coefficients.
//!
//! The room is the example daylight office at Greensboro (`examples/office-year/scene.toml`:
//! a 2.0 m × 1.4 m south window of clear double glazing, τ_n = 0.70, an overhang 0.8 m deep
//! above it, the building across the street 20 m away and 12 m high, two desks), the weather
//! the shipped typical year (`data/weather/greensboro-723170-tmy3.epw`), the readings the 45
//! work-plane grid points (`Basis::grid_point` of the zone `work_plane`) in the analysis hours
//! of IES LM-83-12: 08:00 to 18:00 local standard time, the records of hour-ending 9 to 18,
//! every day of the year (3650 hours).
//!
//! **eigenrad**: `simulate::hours` with [`SkySource::Irradiance`] (every record's Perez sky
//! from its direct normal and diffuse horizontal irradiances through the Perez efficacies,
//! at the middle of its hour, the water of its dew point), then the runtime's
//! `DaylightEvaluator::set_sky` and `grid_point_illuminance`, as `eigenrad simulate
//! --sky-from irradiance` computes them; the direct sun's share from `DirectSun`.
//!
//! **Radiance** (`radiance_reference_run`, ignored: about 7 minutes on two cores), the
//! daylight-coefficient method as Honeybee runs it, with each hour's direct sun traced at its
//! own position:
//!
//! - `epw2wea` (each record at `hour − 0.5`, as eigenrad), `gendaymtx -m 1` (Tregenza's 145
//!   patches and the ground; Perez from the irradiances, with a constant dew point of 11 °C
//!   since a `.wea` carries none) for the sky with its sun spread over the three patches
//!   nearest it, `gendaymtx -m 1 -d` for that sun alone, `gendaymtx -D` for the suns;
//! - `rfluxmtx` for the points' daylight coefficients of the whole room (`RFLUX_TOTAL`) and of
//!   the direct sky alone (every opaque surface black, one bounce: `RFLUX_DIRECT`), two runs
//!   each (rcontrib's `-u+` seeds by the clock: their difference is the Monte Carlo noise),
//!   `rcontrib -ab 0` for each hour's sun (`RCONTRIB_SUN`), `dctimestep` for every hour;
//! - the daylight without the direct sun = room × sky − direct sky × sun alone, and the
//!   direct sun traced, `179 (0.265 R + 0.670 G + 0.065 B)` lux.
//!
//! The room goes to Radiance as eigenrad reads it (`scene::load`): every convex face of the
//! room and its desks `plastic` of its grey, the obstructions outside likewise, the window
//! `BRTDfunc` whose specular transmittance is eigenrad's clear-glazing model (Fresnel for
//! n = 1.52 per polarisation, the panes' absorption solved for τ_n, the reflections within and
//! between the panes; `runtime/src/sky/glazing.rs`, checked by `icalc` to 10⁻⁵) and whose room
//! side reflects the glass' reflectance diffusely, as eigenrad's window patches do.
//!
//! Two exteriors (`VARIANTS`): `physical`, the obstructions lit by the sky and the sun as they
//! stand (what a Radiance user computes), and `exterior-model`, each obstruction a glow of
//! eigenrad's luminance `ρ E_gh/π` (its rfluxmtx column folded into the ground's times
//! `ρ/ρ_g`): the two methods on the same sky, ground and obstructions. The fixtures
//! (`FIXTURES`, `SUN_FIXTURE`) hold Radiance's answers, one line per hour, 0.1 lux; the test
//! (`annual_daylight_matches_radiance`) computes eigenrad's and compares them, in about 15 s
//! (the build of the office). Regenerate them with
//! `cargo test --release --test validation_radiance_annual -- --ignored --nocapture
//! radiance_reference_run`; two diagnoses read the run's files (`WORK`): the daylight
//! coefficients patch by patch and the direct sun at Radiance's own sun positions. The
//! figures are in docs/accuracy.md, "A year of daylight against Radiance's daylight
//! coefficients".

mod common;

use std::fmt::Write as _;
use std::io::{BufRead, Read, Write as _};
use std::path::{Path, PathBuf};

use common::radiance::{self, Radiance};
use eigenrad_precompute::pipeline;
use eigenrad_precompute::scene;
use eigenrad_precompute::simulate::{self, SkySource};
use eigenrad_precompute::weather;
use eigenrad_runtime::sky::direct::DirectSun;
use eigenrad_runtime::{Basis, DaylightEvaluator};

/// The room, the weather and the grid compared.
const SCENE: &str = "examples/office-year/scene.toml";
const WEATHER: &str = "data/weather/greensboro-723170-tmy3.epw";
const ZONE: &str = "work_plane";
/// Radiance's hourly illuminance at the grid points (gzip'd CSV): with the obstructions
/// outside lit as they are (`physical`), and at eigenrad's luminance of them
/// (`exterior-model`), in the order of `VARIANTS`.
/// Each holds the daylight without the direct sun (the sky, the ground, the obstructions and
/// every reflection, the sun's included); `SUN_FIXTURE` the direct sun, traced.
const FIXTURES: [&str; 2] = [
    "tests/fixtures/radiance-annual-office-year.csv.gz",
    "tests/fixtures/radiance-annual-office-year-exterior-model.csv.gz",
];
const SUN_FIXTURE: &str = "tests/fixtures/radiance-annual-office-year-sun.csv.gz";
/// Where the reference run keeps its files (scene, matrices), for inspection.
const WORK: &str = "target/radiance-annual";

/// `rfluxmtx` for the whole room's daylight coefficients: irradiance (`-I+`), pure Monte
/// Carlo (rcontrib keeps no ambient cache), 10⁵ hemisphere samples at a point, uncorrelated
/// sampling seeded by the clock (`-u+`), Russian roulette below a ray weight of 10⁻⁶ with no
/// reflection limit (`-lr 0`: unbiased), 12 ambient bounces (6 lose 0.51 % of the year's
/// daylight). Below the point's own hemisphere a bounce's samples go as √(0.8 w/lw), not
/// with `-ad` (`samp_hemi`, `src/rt/ambcomp.c`), so `-lw` rules the interreflections' noise:
/// `-ad 10⁶ -lw 10⁻⁵` and `-ad 4·10⁵ -lw 10⁻⁵` gave the same noise and, within 0.07 %, the
/// same year.
const RFLUX_TOTAL: &[&str] = &[
    "-I+", "-ab", "12", "-ad", "100000", "-lw", "1e-6", "-lr", "0", "-u+",
];
/// `rfluxmtx` for the direct sky: the same room with every opaque surface black, one bounce
/// (the sky seen through the window, and nothing else).
const RFLUX_DIRECT: &[&str] = &["-I+", "-ab", "1", "-ad", "1000000", "-lw", "1e-5", "-u+"];
/// `rcontrib` for the suns: direct light only, each sun sampled at its centre, every source
/// tested, contributions (`-V+`) rather than coefficients.
const RCONTRIB_SUN: &[&str] = &[
    "-I+", "-ab", "0", "-dj", "0", "-dt", "0", "-dc", "1", "-dr", "0", "-dp", "0", "-V+",
];

/// The analysis hours' records: hour-ending 9 to 18 (08:00 to 18:00 local standard time).
fn analysis(hour: u8) -> bool {
    (9..=18).contains(&hour)
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// One record of the year: month, day, hour-ending.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
struct Key {
    month: u8,
    day: u8,
    hour: u8,
}

/// Hourly illuminance at the grid points, lux: `lux[h][p]` for hour `keys[h]`.
#[derive(Clone, Debug, Default)]
struct Year {
    keys: Vec<Key>,
    lux: Vec<Vec<f64>>,
}

// ---------------------------------------------------------------------------------------------
// eigenrad's year
// ---------------------------------------------------------------------------------------------

/// The office's basis, built as `eigenrad build` builds the example (its default options), in
/// this process: the test's profile optimises the library, where the `eigenrad` binary of a
/// debug run would not be.
fn office_basis() -> Vec<u8> {
    pipeline::build(&root().join(SCENE), &pipeline::BuildOptions::default())
        .unwrap()
        .0
}

/// The work plane's zone, its first point among all grid points, and its points (m).
fn grid(basis: &Basis<'_>) -> (usize, usize, Vec<[f64; 3]>) {
    let mut first = 0;
    for z in 0..basis.zone_count() {
        let n = basis.grid_points(z).unwrap();
        if basis.zone_name(z).unwrap() == ZONE {
            let points = (0..n)
                .map(|p| basis.grid_point(z, p).unwrap().map(f64::from))
                .collect();
            return (z, first, points);
        }
        first += n;
    }
    panic!("no zone {ZONE}");
}

/// eigenrad's daylight at the grid points over the analysis hours, and the direct sun's part
/// of it; `dew_point`, when given, replaces every record's (°C).
fn eigenrad_year(bytes: &[u8], dew_point: Option<f64>, year: Option<i32>) -> (Year, Year) {
    let basis = Basis::from_bytes(bytes).unwrap();
    let (zone, first, points) = grid(&basis);
    let mut weather = weather::read(&root().join(WEATHER)).unwrap();
    if let Some(t) = dew_point {
        weather
            .records
            .iter_mut()
            .for_each(|r| r.dew_point = Some(t));
    }
    let occupancy = simulate::Occupancy {
        days: [true; 7],
        from_hour: 8,
        to_hour: 18,
        days_text: "all".into(),
    };
    let options = simulate::HourOptions {
        year,
        source: SkySource::Irradiance,
    };
    let (hours, warnings, _) = simulate::hours(&weather, &basis, &occupancy, options).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let mut day = Box::new(DaylightEvaluator::<145, 8, 0>::new(basis).unwrap());
    let direct = DirectSun::new(&basis)
        .unwrap()
        .expect("the basis stores the direct sun");
    let (mut total, mut sun) = (Year::default(), Year::default());
    for (hour, record) in hours.iter().zip(&weather.records) {
        if !analysis(record.hour) {
            continue;
        }
        assert!(hour.analysis);
        let key = Key {
            month: record.month,
            day: record.day,
            hour: record.hour,
        };
        day.set_sky(
            &hour.sky.luminance,
            hour.sky.global_horizontal,
            hour.sky.sun,
        )
        .unwrap();
        let lux = (0..points.len())
            .map(|p| f64::from(day.grid_point_illuminance(zone, p).unwrap()))
            .collect();
        let direct_lux = match hour.sky.sun {
            Some(s) if s.direct_normal > 0.0 => {
                let room = direct.room_direction(s.direction);
                (0..points.len())
                    .map(|p| f64::from(s.direct_normal * direct.at_grid_point(first + p, room)))
                    .collect()
            }
            _ => vec![0.0; points.len()],
        };
        total.keys.push(key);
        total.lux.push(lux);
        sun.keys.push(key);
        sun.lux.push(direct_lux);
    }
    (total, sun)
}

// ---------------------------------------------------------------------------------------------
// The comparison
// ---------------------------------------------------------------------------------------------

/// LM-83's and UDI's figures of a year at the points.
#[derive(Clone, Copy, Debug)]
struct Metrics {
    /// Mean over the points of the share of the hours at or above 300 lux.
    da300: f64,
    /// The share of the points at or above 300 lux for at least half the hours.
    sda: f64,
    /// Mean shares of the hours below 100, 100–300, 300–3000, above 3000 lux.
    udi: [f64; 4],
    /// Mean illuminance over the points and hours, lux.
    mean: f64,
}

fn metrics(year: &Year) -> Metrics {
    let hours = year.lux.len() as f64;
    let points = year.lux[0].len();
    let limits = simulate::UDI_LIMITS.map(f64::from);
    let mut da = vec![0.0; points];
    let mut udi = [0.0; 4];
    let mut sum = 0.0;
    for hour in &year.lux {
        for (p, &e) in hour.iter().enumerate() {
            if e >= f64::from(simulate::DA_LUX) {
                da[p] += 1.0 / hours;
            }
            udi[limits.iter().filter(|&&l| e >= l).count()] += 1.0 / hours / points as f64;
            sum += e;
        }
    }
    Metrics {
        da300: da.iter().sum::<f64>() / points as f64,
        sda: da.iter().filter(|&&d| d >= simulate::SDA_SHARE).count() as f64 / points as f64,
        udi,
        mean: sum / hours / points as f64,
    }
}

/// eigenrad against a reference over the same hours and points.
#[derive(Clone, Copy, Debug)]
struct Agreement {
    /// Σ ours / Σ theirs − 1 over every point-hour.
    bias: f64,
    /// RMS of the hourly differences over the reference's mean.
    rms: f64,
    /// The same over the points and hours the reference reads at least 100 lux.
    ours: Metrics,
    theirs: Metrics,
}

fn agreement(ours: &Year, theirs: &Year) -> Agreement {
    assert_eq!(ours.keys, theirs.keys, "the same hours");
    let (mut so, mut st, mut sq, mut n) = (0.0, 0.0, 0.0, 0.0);
    for (o, t) in ours.lux.iter().zip(&theirs.lux) {
        assert_eq!(o.len(), t.len(), "the same points");
        for (a, b) in o.iter().zip(t) {
            so += a;
            st += b;
            sq += (a - b) * (a - b);
            n += 1.0;
        }
    }
    Agreement {
        bias: so / st - 1.0,
        rms: (sq / n).sqrt() / (st / n),
        ours: metrics(ours),
        theirs: metrics(theirs),
    }
}

/// `a + sign b`, hour by hour and point by point.
fn combine(a: &Year, b: &Year, sign: f64) -> Year {
    assert_eq!(a.keys, b.keys, "the same hours");
    Year {
        keys: a.keys.clone(),
        lux: a
            .lux
            .iter()
            .zip(&b.lux)
            .map(|(x, y)| x.iter().zip(y).map(|(x, y)| x + sign * y).collect())
            .collect(),
    }
}

fn print_agreement(what: &str, a: &Agreement) {
    println!(
        "{what}: bias {:+.2} %, RMS {:.1} % of the mean; mean {:.1} lux against {:.1}",
        100.0 * a.bias,
        100.0 * a.rms,
        a.ours.mean,
        a.theirs.mean
    );
    println!(
        "  DA300 {:.3} against {:.3}, sDA300/50% {:.3} against {:.3}",
        a.ours.da300, a.theirs.da300, a.ours.sda, a.theirs.sda
    );
    println!(
        "  UDI <100 {:.3}/{:.3}, 100-300 {:.3}/{:.3}, 300-3000 {:.3}/{:.3}, >3000 {:.3}/{:.3}",
        a.ours.udi[0],
        a.theirs.udi[0],
        a.ours.udi[1],
        a.theirs.udi[1],
        a.ours.udi[2],
        a.theirs.udi[2],
        a.ours.udi[3],
        a.theirs.udi[3]
    );
}

// ---------------------------------------------------------------------------------------------
// The fixture
// ---------------------------------------------------------------------------------------------

/// Writes `year` at `points` with the `header` lines (each becomes a `# ` comment).
fn write_fixture(path: &Path, header: &[String], points: &[[f64; 3]], year: &Year) {
    let mut text = String::new();
    for line in header {
        writeln!(text, "# {line}").unwrap();
    }
    text.push_str("# points (x y z, m):");
    for p in points {
        write!(text, " {:.4} {:.4} {:.4};", p[0], p[1], p[2]).unwrap();
    }
    text.push('\n');
    text.push_str("month,day,hour");
    for i in 0..points.len() {
        write!(text, ",p{i}").unwrap();
    }
    text.push('\n');
    for (k, lux) in year.keys.iter().zip(&year.lux) {
        write!(text, "{},{},{}", k.month, k.day, k.hour).unwrap();
        for e in lux {
            // 0.1 lux, without a trailing ".0".
            let tenths = (e * 10.0).round() as i64;
            if tenths % 10 == 0 {
                write!(text, ",{}", tenths / 10).unwrap();
            } else {
                write!(text, ",{:.1}", tenths as f64 / 10.0).unwrap();
            }
        }
        text.push('\n');
    }
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let mut gz = flate2::write::GzEncoder::new(
        std::fs::File::create(path).unwrap(),
        flate2::Compression::best(),
    );
    gz.write_all(text.as_bytes()).unwrap();
    gz.finish().unwrap();
}

/// The fixture: its header lines, its points and its year.
fn read_fixture(path: &Path) -> (Vec<String>, Vec<[f64; 3]>, Year) {
    let mut text = String::new();
    flate2::read::GzDecoder::new(std::fs::File::open(path).unwrap())
        .read_to_string(&mut text)
        .unwrap();
    let (mut header, mut points, mut year) = (Vec::new(), Vec::new(), Year::default());
    for line in text.as_bytes().lines() {
        let line = line.unwrap();
        if let Some(comment) = line.strip_prefix("# ") {
            if let Some(list) = comment.strip_prefix("points (x y z, m):") {
                points = list
                    .split(';')
                    .filter(|s| !s.trim().is_empty())
                    .map(|s| {
                        let v: Vec<f64> =
                            s.split_whitespace().map(|w| w.parse().unwrap()).collect();
                        [v[0], v[1], v[2]]
                    })
                    .collect();
            } else {
                header.push(comment.to_owned());
            }
            continue;
        }
        if line.starts_with("month") {
            continue;
        }
        let fields: Vec<&str> = line.split(',').collect();
        year.keys.push(Key {
            month: fields[0].parse().unwrap(),
            day: fields[1].parse().unwrap(),
            hour: fields[2].parse().unwrap(),
        });
        year.lux
            .push(fields[3..].iter().map(|w| w.parse().unwrap()).collect());
    }
    (header, points, year)
}

// ---------------------------------------------------------------------------------------------
// The room in Radiance
// ---------------------------------------------------------------------------------------------

/// eigenrad's clear glazing (`runtime/src/sky/glazing.rs`) as a function file for
/// `BRTDfunc`: `tau` of the incidence cosine `Rdot` for `A0` (one pane's internal
/// transmittance at normal incidence) and `PANES` panes.
fn glazing_cal(a0: f64, panes: u8) -> String {
    let stack = match panes {
        1 => "t1(r)",
        2 => "t1(r)*t1(r)/(1 - r1(r)*r1(r))",
        3 => "t1(r)*t1(r)/(1 - r1(r)*r1(r))*t1(r)/(1 - (r1(r) + t1(r)*t1(r)*r1(r)/(1 - r1(r)*r1(r)))*r1(r))",
        _ => panic!("{panes} panes"),
    };
    format!(
        "{{ eigenrad's clear glazing: Fresnel for n = 1.52 per polarisation, absorption \
         a0^(1/cos t), reflections within and between {panes} panes }}\n\
         A0 = {a0:.9};\n\
         n = 1.52;\n\
         ci = min(1, abs(Rdot));\n\
         ct = sqrt(1 - (1 - ci*ci)/(n*n));\n\
         rs = ((ci - n*ct)/(ci + n*ct))^2;\n\
         rp = ((n*ci - ct)/(n*ci + ct))^2;\n\
         a = if(ci - 1e-6, A0^(1/ct), 0);\n\
         t1(r) = (1 - r)^2*a/(1 - r*r*a*a);\n\
         r1(r) = r + (1 - r)^2*r*a*a/(1 - r*r*a*a);\n\
         stack(r) = {stack};\n\
         tau = if(ci - 1e-6, (stack(rs) + stack(rp))/2, 0);\n"
    )
}

/// The room of `scene` as Radiance primitives: each opaque face `plastic` of its surface's
/// grey (black with `black`), each window `BRTDfunc` over `glazing<k>.cal`, the obstructions
/// outside `plastic` of their reflectance (black with `black`). Writes the function files
/// into `dir`.
fn radiance_room(scene: &scene::Scene, dir: &Path, black: bool) -> String {
    let mut text = String::new();
    let name = |s: &str| s.replace(|c: char| !c.is_ascii_alphanumeric(), "_");
    for (i, surface) in scene.surfaces.iter().enumerate() {
        let material = format!("m_{}", name(&surface.name));
        if let Some((k, w)) = scene
            .windows
            .iter()
            .enumerate()
            .find(|(_, w)| w.surface == i)
        {
            let g = w.glazing;
            assert!(!g.is_diffusing(), "clear glazing only");
            let cal = format!("glazing{k}.cal");
            std::fs::write(
                dir.join(&cal),
                glazing_cal(f64::from(g.internal_transmittance()), g.panes()),
            )
            .unwrap();
            let r = surface.reflectance[0];
            // Specular reflectance 0, specular transmittance tau, no directional-diffuse
            // part; the room side (front) reflects r diffusely, the outside nothing.
            writeln!(
                text,
                "void BRTDfunc {material} 10 0 0 0 tau tau tau 0 0 0 {cal} 0 9 {r} {r} {r} 0 0 0 0 0 0"
            )
            .unwrap();
        } else {
            let r = if black { 0.0 } else { surface.reflectance[0] };
            writeln!(text, "void plastic {material} 0 0 5 {r} {r} {r} 0 0").unwrap();
        }
    }
    for (f, face) in scene.faces.iter().enumerate() {
        let surface = &scene.surfaces[scene.patches[face.patches.start].surface];
        let corners: Vec<[f64; 3]> = face
            .polygon
            .vertices
            .iter()
            .map(|v| [v.x, v.y, v.z])
            .collect();
        radiance::write_polygon(
            &mut text,
            &format!("m_{}", name(&surface.name)),
            &format!("face{f}"),
            &corners,
        );
    }
    for (o, obstruction) in scene.obstructions.iter().enumerate() {
        let material = format!("x_{}", name(&obstruction.name));
        let r = if black { 0.0 } else { obstruction.reflectance };
        writeln!(text, "void plastic {material} 0 0 5 {r} {r} {r} 0 0").unwrap();
        for (f, face) in obstruction.faces.iter().enumerate() {
            let corners: Vec<[f64; 3]> = face
                .polygon
                .vertices
                .iter()
                .map(|v| [v.x, v.y, v.z])
                .collect();
            radiance::write_polygon(&mut text, &material, &format!("x{o}_{f}"), &corners);
        }
    }
    text
}

/// The sky and the ground as `rfluxmtx` receivers in `gendaymtx -m 1`'s order: the ground
/// (one bin) then Tregenza's 145 patches (`reinhartb.cal` with MF 1), +Y north.
const SKY_RECEIVERS: &str = "\
#@rfluxmtx h=u u=+Y
void glow ground_glow 0 0 4 1 1 1 0
ground_glow source ground 0 0 4 0 0 -1 180
#@rfluxmtx h=r1 u=+Y
void glow sky_glow 0 0 4 1 1 1 0
sky_glow source sky 0 0 4 0 0 1 180
";

/// The numbers of a Radiance matrix file in ASCII (its header skipped): rows of `cols`
/// RGB triples, as lux per `179 (0.265 R + 0.670 G + 0.065 B)`.
fn read_matrix_lux(path: &Path, rows: usize, cols: usize) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let body = match text.find("\n\n") {
        Some(i) if text.starts_with("#?RADIANCE") => &text[i + 2..],
        _ => &text[..],
    };
    let numbers: Vec<f64> = body
        .split_whitespace()
        .map(|w| {
            w.parse()
                .unwrap_or_else(|_| panic!("{}: `{w}`", path.display()))
        })
        .collect();
    assert_eq!(
        numbers.len(),
        rows * cols * 3,
        "{}: {rows} × {cols} × 3 numbers",
        path.display()
    );
    numbers
        .chunks(cols * 3)
        .map(|row| {
            row.chunks(3)
                .map(|c| radiance::lux([c[0], c[1], c[2]]))
                .collect()
        })
        .collect()
}

/// gendaymtx's and rcontrib's identifier of a record's sun: the minute of the year of the
/// middle of its hour (`solar_minute`, `src/gen/gendaymtx.c`; the year has no 29 February).
fn solar_minute(k: Key) -> usize {
    const MONTH_START: [usize; 12] = [0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334];
    let jd = MONTH_START[usize::from(k.month) - 1] + usize::from(k.day);
    24 * 60 * (jd - 1) + 60 * usize::from(k.hour) - 30
}

/// Seconds since `start`.
fn since(start: std::time::Instant) -> f64 {
    start.elapsed().as_secs_f64()
}

/// A Radiance matrix of `rows` × `cols` RGB triples in ASCII, with its header.
fn write_matrix(path: &Path, rows: &[Vec<f64>]) {
    let mut text = format!(
        "#?RADIANCE\nNROWS={}\nNCOLS={}\nNCOMP=3\nFORMAT=ascii\n\n",
        rows.len(),
        rows[0].len()
    );
    for row in rows {
        for v in row {
            write!(text, "{v:e} {v:e} {v:e} ").unwrap();
        }
        text.push('\n');
    }
    std::fs::write(path, text).unwrap();
}

/// The receivers of the exterior as eigenrad models it: the sky and the ground, then each
/// obstruction a glow receiver of its own (one bin), so that its column is the light it would
/// send at a luminance of 1; and the room without the obstructions.
fn exterior_model_files(scene: &scene::Scene, dir: &Path) {
    let mut receivers = SKY_RECEIVERS.to_owned();
    for (o, obstruction) in scene.obstructions.iter().enumerate() {
        writeln!(
            receivers,
            "#@rfluxmtx h=u u=+Y\nvoid glow obstruction{o} 0 0 4 1 1 1 0"
        )
        .unwrap();
        for (f, face) in obstruction.faces.iter().enumerate() {
            let corners: Vec<[f64; 3]> = face
                .polygon
                .vertices
                .iter()
                .map(|v| [v.x, v.y, v.z])
                .collect();
            radiance::write_polygon(
                &mut receivers,
                &format!("obstruction{o}"),
                &format!("o{o}_{f}"),
                &corners,
            );
        }
    }
    std::fs::write(dir.join("sky_obstructions.rad"), &receivers).unwrap();
    let open = scene::Scene {
        obstructions: Vec::new(),
        ..scene.clone()
    };
    std::fs::write(dir.join("room_open.rad"), radiance_room(&open, dir, false)).unwrap();
}

/// Folds the obstructions' columns of `glows.dc` (after the sky's 146) into the ground's:
/// at eigenrad's luminance `ρ E_gh/π` an obstruction's light is the ground patch's (whose
/// radiance gendaymtx sets to `ρ_g E_gh/π`) times `ρ/ρ_g`. Writes a 146-column matrix.
fn fold_obstructions(scene: &scene::Scene, from: &Path, to: &Path, points: usize) {
    let rho_g = scene.site.as_ref().unwrap().ground_reflectance;
    let rows: Vec<Vec<f64>> = read_coefficients(from, points)
        .into_iter()
        .map(|row| {
            assert_eq!(row.len(), 146 + scene.obstructions.len());
            let mut folded = row[..146].to_vec();
            for (o, obstruction) in scene.obstructions.iter().enumerate() {
                folded[0] += row[146 + o] * obstruction.reflectance / rho_g;
            }
            folded
        })
        .collect();
    write_matrix(to, &rows);
}

/// Checks the function file of the window against eigenrad's glazing at a few angles
/// (`icalc`, which evaluates Radiance's expression language).
fn check_glazing_cal(radiance: &Radiance, dir: &Path, scene: &scene::Scene) {
    let glazing = scene.windows[0].glazing;
    let cal = std::fs::read_to_string(dir.join("glazing0.cal")).unwrap();
    for cos in [1.0, 0.9, 0.7, 0.5, 0.3, 0.1] {
        std::fs::write(
            dir.join("check.cal"),
            cal.replace("abs(Rdot)", &format!("{cos}")),
        )
        .unwrap();
        std::fs::write(dir.join("check.in"), "tau\n").unwrap();
        radiance.pipe("icalc", dir, &["check.cal"], Some("check.in"), "check.out");
        let out = std::fs::read_to_string(dir.join("check.out")).unwrap();
        let theirs: f64 = out.trim().trim_start_matches("$1=").parse().unwrap();
        let ours = f64::from(glazing.transmittance((cos as f32).acos()));
        assert!(
            (theirs - ours).abs() < 1e-5,
            "τ at cos {cos}: Radiance's function {theirs}, eigenrad {ours}"
        );
    }
}

/// One variant of the exterior: its daylight coefficients' two runs and their hours.
struct Variant {
    what: &'static str,
    receivers: &'static str,
    system: &'static str,
    /// Folds the obstructions' columns (the exterior as eigenrad models it).
    fold: bool,
}

const VARIANTS: [Variant; 2] = [
    Variant {
        what: "physical",
        receivers: "sky.rad",
        system: "room.rad",
        fold: false,
    },
    Variant {
        what: "exterior-model",
        receivers: "sky_obstructions.rad",
        system: "room_open.rad",
        fold: true,
    },
];

#[test]
#[ignore = "the Radiance reference run: about 7 minutes on two cores; rewrites the fixtures"]
fn radiance_reference_run() {
    let radiance = Radiance::find().expect(radiance::SKIPPED);
    let dir = root().join(WORK);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let version = radiance
        .output("rtrace", &dir, &["-version"])
        .trim()
        .to_owned();
    let scene = scene::load(&root().join(SCENE)).unwrap();
    let site = scene.site.as_ref().expect("a site");
    assert_eq!(
        site.north, 0.0,
        "the scene's +y is north, as Radiance's sky's"
    );
    let bytes = office_basis();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let (_, _, points) = grid(&basis);
    let n = points.len();
    let mut rays = String::new();
    for p in &points {
        writeln!(rays, "{} {} {} 0 0 1", p[0], p[1], p[2]).unwrap();
    }
    std::fs::write(dir.join("points.txt"), rays).unwrap();
    std::fs::write(dir.join("room.rad"), radiance_room(&scene, &dir, false)).unwrap();
    std::fs::write(dir.join("black.rad"), radiance_room(&scene, &dir, true)).unwrap();
    std::fs::write(dir.join("sky.rad"), SKY_RECEIVERS).unwrap();
    exterior_model_files(&scene, &dir);
    check_glazing_cal(&radiance, &dir, &scene);
    let ground = site.ground_reflectance.to_string();

    // The skies.
    let epw = root().join(WEATHER);
    radiance.run("epw2wea", &dir, &[epw.to_str().unwrap(), "year.wea"], None);
    let g = ["-g", &ground, &ground, &ground];
    let sky_args = [&["-m", "1"][..], &g, &["year.wea"]].concat();
    radiance.pipe("gendaymtx", &dir, &sky_args, None, "sky.mtx");
    let sun_args = [&["-m", "1", "-d"][..], &g, &["year.wea"]].concat();
    radiance.pipe("gendaymtx", &dir, &sun_args, None, "sun.mtx");
    radiance.pipe(
        "gendaymtx",
        &dir,
        &["-D", "suns.rad", "-M", "suns.mod", "-n", "year.wea"],
        None,
        "suns.out",
    );

    // The daylight coefficients: two runs of each variant of the room (seeded by the clock,
    // started a second apart at least), one of the direct sky, one of the room with half the
    // bounces (the truncation's share).
    let rflux = |args: &[&str], receivers: &str, system: &str, out: &str| {
        std::thread::sleep(std::time::Duration::from_millis(1100));
        let args = [args, &["-faa", "-", receivers, system]].concat();
        let start = std::time::Instant::now();
        let notes = radiance.pipe("rfluxmtx", &dir, &args, Some("points.txt"), out);
        if !notes.is_empty() {
            println!("rfluxmtx {out}: {notes}");
        }
        println!("rfluxmtx {out}: {:.0} s", since(start));
        since(start)
    };
    let mut seconds = Vec::new();
    for v in &VARIANTS {
        for run in 1..=2 {
            let out = format!("{}{run}.dc", v.what);
            seconds.push(rflux(RFLUX_TOTAL, v.receivers, v.system, &out));
            if v.fold {
                fold_obstructions(&scene, &dir.join(&out), &dir.join(&out), n);
            }
        }
    }
    let t_direct = rflux(RFLUX_DIRECT, "sky.rad", "black.rad", "direct1.dc");
    rflux(RFLUX_DIRECT, "sky.rad", "black.rad", "direct2.dc");
    let mut half = RFLUX_TOTAL.to_vec();
    let ab = RFLUX_TOTAL[RFLUX_TOTAL.iter().position(|&a| a == "-ab").unwrap() + 1];
    let half_ab = (ab.parse::<u32>().unwrap() / 2).to_string();
    half[RFLUX_TOTAL.iter().position(|&a| a == "-ab").unwrap() + 1] = &half_ab;
    rflux(&half, "sky.rad", "room.rad", "half.dc");

    // Each hour's sun at its own position.
    let start = std::time::Instant::now();
    let suns = std::fs::read_to_string(dir.join("suns.rad")).unwrap();
    let room = std::fs::read_to_string(dir.join("room.rad")).unwrap();
    let oct = radiance.octree(&dir, "room_suns", &(room + &suns));
    let modifiers: Vec<String> = std::fs::read_to_string(dir.join("suns.mod"))
        .unwrap()
        .split_whitespace()
        .map(str::to_owned)
        .collect();
    let sun_args = [RCONTRIB_SUN, &["-faa", "-M", "suns.mod", &oct]].concat();
    radiance.pipe("rcontrib", &dir, &sun_args, Some("points.txt"), "suns.dat");
    let t_suns = since(start);
    let sun_lux = read_matrix_lux(&dir.join("suns.dat"), n, modifiers.len());
    let sun_column: std::collections::HashMap<&str, usize> = modifiers
        .iter()
        .enumerate()
        .map(|(i, m)| (m.as_str(), i))
        .collect();

    // Every hour of every matrix.
    let start = std::time::Instant::now();
    let mut steps = std::collections::HashMap::new();
    let mut products: Vec<(String, &str)> = VARIANTS
        .iter()
        .flat_map(|v| (1..=2).map(move |run| (format!("{}{run}.dc", v.what), "sky.mtx")))
        .collect();
    products.push(("half.dc".into(), "sky.mtx"));
    products.push(("direct1.dc".into(), "sun.mtx"));
    products.push(("direct2.dc".into(), "sun.mtx"));
    for (dc, sky) in &products {
        let out = format!("{dc}.{sky}.dat");
        radiance.pipe("dctimestep", &dir, &["-oa", "-h", dc, sky], None, &out);
        steps.insert(dc.clone(), read_matrix_lux(&dir.join(&out), n, 8760));
    }
    let t_steps = since(start);
    let records = weather::read(&epw).unwrap().records;
    assert_eq!(records.len(), 8760);
    // For each matrix: its year with the sun traced (total − the spread sun's direct part +
    // the suns), and as two-phase (the sun spread).
    // `traced`: None the two-phase year, Some(true) with the suns, Some(false) without the
    // direct sun.
    let year_of = |dc: &str, traced: Option<bool>| {
        // Each run of the room pairs with its own run of the direct sky.
        let direct = if dc.ends_with("2.dc") {
            "direct2.dc"
        } else {
            "direct1.dc"
        };
        let mut year = Year::default();
        for (t, r) in records.iter().enumerate() {
            if !analysis(r.hour) {
                continue;
            }
            let key = Key {
                month: r.month,
                day: r.day,
                hour: r.hour,
            };
            let sun = sun_column.get(format!("solar{}", solar_minute(key)).as_str());
            year.keys.push(key);
            year.lux.push(
                (0..n)
                    .map(|p| {
                        let total = steps[dc][p][t];
                        match traced {
                            None => total,
                            Some(with_sun) => {
                                total - steps[direct][p][t]
                                    + if with_sun {
                                        sun.map_or(0.0, |&c| sun_lux[p][c])
                                    } else {
                                        0.0
                                    }
                            }
                        }
                    })
                    .collect(),
            );
        }
        year
    };
    let mean_of = |a: &Year, b: &Year| Year {
        keys: a.keys.clone(),
        lux: a
            .lux
            .iter()
            .zip(&b.lux)
            .map(|(x, y)| x.iter().zip(y).map(|(x, y)| 0.5 * (x + y)).collect())
            .collect(),
    };
    let suns_alone = {
        let mut year = year_of("half.dc", None);
        for (k, row) in year.keys.iter().zip(year.lux.iter_mut()) {
            let sun = sun_column.get(format!("solar{}", solar_minute(*k)).as_str());
            for (p, e) in row.iter_mut().enumerate() {
                *e = sun.map_or(0.0, |&c| sun_lux[p][c]);
            }
        }
        year
    };
    let (ours, our_sun) = eigenrad_year(&bytes, None, None);
    print_agreement("the direct sun alone", &agreement(&our_sun, &suns_alone));
    let (ours_11, _) = eigenrad_year(&bytes, Some(11.0), None);
    let (ours_1987, sun_1987) = eigenrad_year(&bytes, None, Some(1987));
    print_agreement(
        "the direct sun alone, the dates in 1987",
        &agreement(&sun_1987, &suns_alone),
    );
    let pyradiance = std::process::Command::new("python3")
        .args(["-c", "import pyradiance; print(pyradiance.__version__)"])
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
        .unwrap_or_default();
    for (i, v) in VARIANTS.iter().enumerate() {
        let runs = [
            year_of(&format!("{}1.dc", v.what), Some(true)),
            year_of(&format!("{}2.dc", v.what), Some(true)),
        ];
        let noise = agreement(&runs[0], &runs[1]);
        let theirs = mean_of(&runs[0], &runs[1]);
        let two_phase = mean_of(
            &year_of(&format!("{}1.dc", v.what), None),
            &year_of(&format!("{}2.dc", v.what), None),
        );
        let without_sun = mean_of(
            &year_of(&format!("{}1.dc", v.what), Some(false)),
            &year_of(&format!("{}2.dc", v.what), Some(false)),
        );
        println!(
            "{}: two runs' annual sums differ by {:+.3} %, their hourly RMS difference is {:.2} % \
             of the mean",
            v.what,
            100.0 * noise.bias,
            100.0 * noise.rms
        );
        print_agreement(
            &format!("eigenrad against Radiance, {}", v.what),
            &agreement(&ours, &theirs),
        );
        print_agreement(
            &format!(
                "eigenrad against Radiance without the direct sun, {}",
                v.what
            ),
            &agreement(&combine(&ours, &our_sun, -1.0), &without_sun),
        );
        print_agreement(
            &format!(
                "eigenrad against Radiance's two-phase (sun spread), {}",
                v.what
            ),
            &agreement(&ours, &two_phase),
        );
        print_agreement(
            &format!("eigenrad, dew point 11 °C, against Radiance, {}", v.what),
            &agreement(&ours_11, &theirs),
        );
        print_agreement(
            &format!("eigenrad, the dates in 1987, against Radiance, {}", v.what),
            &agreement(&ours_1987, &theirs),
        );
        if i == 0 {
            let half = year_of("half.dc", Some(true));
            println!(
                "{} ambient bounces instead of {ab}: annual sum {:+.3} %",
                half_ab,
                100.0 * agreement(&half, &runs[0]).bias
            );
        }
        let exterior = match v.fold {
            false => "the obstructions outside plastic of their reflectance, lit by the sky and the sun".to_owned(),
            true => "the obstructions outside glow receivers at eigenrad's luminance ρ E_gh/π (their columns folded into the ground's times ρ/ρ_g)".to_owned(),
        };
        let header = vec![
            format!(
                "Radiance's daylight coefficients for {SCENE} under {WEATHER}: illuminance (lux, 0.1) \
                 at the grid points of zone {ZONE}, records of hour-ending 9 to 18"
            ),
            format!("exterior: {exterior}"),
            format!("radiance: {version} (pyradiance {pyradiance})"),
            format!("sky: epw2wea; gendaymtx -m 1 -g {ground} {ground} {ground} (with sun), -d (sun alone), -D (suns)"),
            format!(
                "room: rfluxmtx {} (mean of two runs, -u+ seeds by the clock); direct sky: rfluxmtx {} \
                 (every opaque surface black, two runs, each paired with one of the room's); suns: rcontrib {}",
                RFLUX_TOTAL.join(" "),
                RFLUX_DIRECT.join(" "),
                RCONTRIB_SUN.join(" ")
            ),
            "illuminance: dctimestep(room, sky) - dctimestep(direct sky, sun alone), 179 (0.265 R + 0.670 G + 0.065 B) lux: the daylight without the direct sun, which is in the sun's fixture".into(),
            format!(
                "noise: the two runs' annual sums differ by {:+.3} %, their hourly RMS difference is {:.2} % of the mean",
                100.0 * noise.bias,
                100.0 * noise.rms
            ),
            format!(
                "times: room {:.0} s and {:.0} s, direct sky {t_direct:.0} s, suns {t_suns:.0} s, dctimestep {t_steps:.0} s",
                seconds[2 * i], seconds[2 * i + 1]
            ),
            "regenerate: cargo test --release --test validation_radiance_annual -- --ignored --nocapture radiance_reference_run".into(),
        ];
        write_fixture(&root().join(FIXTURES[i]), &header, &points, &without_sun);
    }
    let header = vec![
        format!(
            "Radiance's direct sun for {SCENE} under {WEATHER}: illuminance (lux, 0.1) at the \
             grid points of zone {ZONE}, records of hour-ending 9 to 18"
        ),
        format!("radiance: {version} (pyradiance {pyradiance})"),
        format!(
            "suns: gendaymtx -D (each record's sun at the middle of its hour, Radiance's position \
             and direct normal illuminance); rcontrib {}",
            RCONTRIB_SUN.join(" ")
        ),
        "regenerate: cargo test --release --test validation_radiance_annual -- --ignored --nocapture radiance_reference_run".into(),
    ];
    write_fixture(&root().join(SUN_FIXTURE), &header, &points, &suns_alone);
}

/// The aim: eigenrad's year within 2 % of Radiance's, annual sums over every point-hour, when
/// both see the same sky, ground and obstructions (`exterior-model`). Measured −1.31 %: the
/// daylight without the direct sun +0.51 % and the direct sun −4.0 % (`SUN_BIAS`).
const BIAS: f64 = 0.02;
/// The daylight without the direct sun (the sky, the ground, the obstructions and every
/// reflection), annual sums: measured +0.51 %. What may part the two there: Radiance's Monte
/// Carlo noise (the two runs' sums differ by 0.09 %), its bounces cut at 12 (half of them
/// lose 0.51 %, so 12 lose far less), the sky's discretisation (each program holds
/// the Tregenza patches' centre luminance, but gendaymtx scales them to the record's diffuse
/// horizontal illuminance and eigenrad scales the continuous Perez sky: 0.75 % apart with
/// the sun on the horizon, docs/math.md), and the dew point (gendaymtx's 11 °C against the records': −0.4 %).
const BIAS_WITHOUT_SUN: f64 = 0.02;
/// The hourly RMS difference without the direct sun, relative to Radiance's mean: measured
/// 4.9 %, of which Radiance's noise is 1.5 % (the mean of two runs whose hourly RMS difference
/// is 3.0 %); the rest is the sun's reflected light carried by different skies (gendaymtx
/// spreads the sun over its three nearest patches, eigenrad interpolates between its sun
/// nodes) at different sun positions. Half as much again.
const RMS_WITHOUT_SUN: f64 = 0.075;
/// The direct sun, annual sums: measured −4.0 %. At the same positions and direct normal
/// illuminance the two agree to 3·10⁻⁵ (`direct_sun_against_radiance`); at eigenrad's positions
/// with Radiance's illuminance eigenrad reads 4.9 % less: gendaymtx's sun (its short
/// declination and equation-of-time formulas, no refraction) stands 0.31° lower on average
/// than eigenrad's (NREL SPA with refraction), and a lower sun reaches further under the
/// overhang and into the grid. The rest is the Perez direct efficacy at the records' dew
/// points. Bounds of ±2 % around the measured figure.
const SUN_BIAS: [f64; 2] = [-0.06, -0.02];
/// DA300 and each UDI band, absolute shares: measured within 0.002 with the same exterior.
const METRIC_TOLERANCE: f64 = 0.01;
/// The physical exterior: eigenrad reads 20.0 % more than Radiance over the year (42.9 % more
/// without the direct sun). eigenrad gives every obstruction outside the luminance `ρ E_gh/π`
/// of a horizontal surface under the whole sky and sun (docs/math.md, "Daylight through
/// windows"), where Radiance lights it as it stands: the opposite building's facade faces
/// north and the overhang's underside sees the ground alone. Its own share is the difference
/// of the two comparisons. Held within these bounds so that a change of the exterior's model
/// shows here (and is then written into docs/accuracy.md and these bounds).
const PHYSICAL_BIAS: [f64; 2] = [0.15, 0.25];

#[test]
fn annual_daylight_matches_radiance() {
    let start = std::time::Instant::now();
    let bytes = office_basis();
    let t_build = since(start);
    let basis = Basis::from_bytes(&bytes).unwrap();
    let (_, _, ours_points) = grid(&basis);
    let start = std::time::Instant::now();
    let (ours, our_sun) = eigenrad_year(&bytes, None, None);
    let t_year = since(start);
    println!(
        "eigenrad: build {t_build:.1} s, {} hours {t_year:.2} s",
        ours.keys.len()
    );
    assert_eq!(ours.keys.len(), 3650);
    let read = |fixture: &str| {
        let (header, points, year) = read_fixture(&root().join(fixture));
        for line in &header {
            println!("{fixture}: {line}");
        }
        assert_eq!(points.len(), ours_points.len(), "the grid's points");
        for (a, b) in points.iter().zip(&ours_points) {
            assert!(
                (0..3).all(|k| (a[k] - b[k]).abs() < 1e-3),
                "{fixture}: point {a:?}, the basis' {b:?}"
            );
        }
        year
    };
    let their_sun = read(SUN_FIXTURE);
    let sun = agreement(&our_sun, &their_sun);
    print_agreement("the direct sun", &sun);
    assert!(
        (SUN_BIAS[0]..=SUN_BIAS[1]).contains(&sun.bias),
        "the direct sun: {:+.2} % against Radiance, expected {:+.0} % to {:+.0} %",
        100.0 * sun.bias,
        100.0 * SUN_BIAS[0],
        100.0 * SUN_BIAS[1]
    );
    let ours_without_sun = combine(&ours, &our_sun, -1.0);
    for (fixture, variant) in FIXTURES.iter().zip(&VARIANTS) {
        let without_sun = read(fixture);
        let total = agreement(&ours, &combine(&without_sun, &their_sun, 1.0));
        let diffuse = agreement(&ours_without_sun, &without_sun);
        print_agreement(&format!("{}: the daylight", variant.what), &total);
        print_agreement(
            &format!("{}: the daylight without the direct sun", variant.what),
            &diffuse,
        );
        if variant.fold {
            assert!(
                total.bias.abs() <= BIAS,
                "{}: {:+.2} % over the year",
                variant.what,
                100.0 * total.bias
            );
            assert!(
                diffuse.bias.abs() <= BIAS_WITHOUT_SUN,
                "{}: {:+.2} % over the year without the direct sun",
                variant.what,
                100.0 * diffuse.bias
            );
            assert!(
                diffuse.rms <= RMS_WITHOUT_SUN,
                "{}: hourly RMS {:.2} % without the direct sun",
                variant.what,
                100.0 * diffuse.rms
            );
            let (o, t) = (total.ours, total.theirs);
            assert!(
                (o.da300 - t.da300).abs() <= METRIC_TOLERANCE,
                "DA300 {o:?} against {t:?}"
            );
            assert_eq!(o.sda, t.sda, "sDA300/50 %");
            for band in 0..4 {
                assert!(
                    (o.udi[band] - t.udi[band]).abs() <= METRIC_TOLERANCE,
                    "UDI band {band}: {o:?} against {t:?}"
                );
            }
        } else {
            assert!(
                (PHYSICAL_BIAS[0]..=PHYSICAL_BIAS[1]).contains(&total.bias),
                "{}: {:+.2} % over the year, expected {:+.0} % to {:+.0} % from eigenrad's model \
                 of the obstructions' luminance: if the model changed, update PHYSICAL_BIAS and \
                 docs/accuracy.md",
                variant.what,
                100.0 * total.bias,
                100.0 * PHYSICAL_BIAS[0],
                100.0 * PHYSICAL_BIAS[1]
            );
        }
    }
}

/// The raw numbers of an `rfluxmtx` ASCII matrix: per point, per column, the mean of RGB.
fn read_coefficients(path: &Path, points: usize) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let body = &text[text.find("\n\n").expect("a header") + 2..];
    let rows: Vec<Vec<f64>> = body
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
            v.chunks(3).map(|c| (c[0] + c[1] + c[2]) / 3.0).collect()
        })
        .collect();
    assert_eq!(rows.len(), points, "{}", path.display());
    rows
}

/// Radiance's Tregenza bin (`reinhartb.cal`, MF 1: 0 the first patch of the lowest row,
/// clockwise from north) of a direction in the site's frame (x east, y north, z up).
fn tregenza_bin(d: [f64; 3]) -> usize {
    const ROW: [usize; 7] = [30, 30, 24, 24, 18, 12, 6];
    let altitude = d[2].clamp(-1.0, 1.0).asin().to_degrees();
    let row = (altitude / 12.0).floor() as usize;
    if row >= 7 {
        return 144;
    }
    let azimuth = d[0].atan2(d[1]).to_degrees().rem_euclid(360.0);
    let step = 360.0 / ROW[row] as f64;
    ROW[..row].iter().sum::<usize>() + (((azimuth + 0.5 * step) / step).floor() as usize) % ROW[row]
}

/// eigenrad's daylight coefficients against Radiance's, patch by patch, from the files of
/// the reference run (`WORK`): each sky patch's illuminance per cd/m² averaged over the grid,
/// and the exterior's (the ground and the obstructions) per cd/m² of `E_gh/π`. Radiance's
/// exterior is the ground's coefficient times its reflectance with the obstructions lit as
/// they are (their light then lies in the sky's columns), and again with each obstruction a
/// glow receiver of its own (eigenrad's model: its luminance `ρ E_gh/π`).
#[test]
#[ignore = "a diagnosis of the reference run's files: run it after radiance_reference_run"]
fn daylight_coefficients_against_radiance() {
    let radiance = Radiance::find().expect(radiance::SKIPPED);
    let dir = root().join(WORK);
    let scene = scene::load(&root().join(SCENE)).unwrap();
    let rho_g = scene.site.as_ref().unwrap().ground_reflectance;
    let bytes = office_basis();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let (zone, _, points) = grid(&basis);
    let n = points.len();
    let patches = basis.sky_patches().unwrap();
    let mut centres = vec![[0.0f32; 3]; patches.count()];
    patches.centres(&mut centres).unwrap();
    let mut day = Box::new(DaylightEvaluator::<145, 8, 0>::new(basis).unwrap());
    let mean = |day: &DaylightEvaluator<'_, 145, 8, 0>| {
        (0..n)
            .map(|p| f64::from(day.grid_point_illuminance(zone, p).unwrap()))
            .sum::<f64>()
            / n as f64
    };
    let mut ours = Vec::new();
    for k in 0..patches.count() {
        let mut l = vec![0.0f32; patches.count()];
        l[k] = 1.0;
        day.set_sky(&l, 0.0, None).unwrap();
        ours.push(mean(&day));
    }
    let zero = vec![0.0f32; patches.count()];
    day.set_sky(&zero, std::f32::consts::PI, None).unwrap();
    let ours_exterior = mean(&day);

    // Radiance: obstructions as glow receivers, the rest as the reference run.
    exterior_model_files(&scene, &dir);
    let args = [
        RFLUX_TOTAL,
        &["-faa", "-", "sky_obstructions.rad", "room_open.rad"],
    ]
    .concat();
    let notes = radiance.pipe("rfluxmtx", &dir, &args, Some("points.txt"), "glows.dc");
    println!("{notes}");
    let glows = read_coefficients(&dir.join("glows.dc"), n);
    let runs = [
        read_coefficients(&dir.join("physical1.dc"), n),
        read_coefficients(&dir.join("physical2.dc"), n),
    ];
    let column = |m: &Vec<Vec<f64>>, c: usize| m.iter().map(|row| row[c]).sum::<f64>() / n as f64;
    println!("patch  alt   azi   eigenrad  Radiance(run 1, run 2)  glow model   ratio");
    let (mut so, mut sr, mut sg) = (0.0, 0.0, 0.0);
    for (k, c) in centres.iter().enumerate() {
        let d = c.map(f64::from);
        let bin = 1 + tregenza_bin(d);
        let (r1, r2, g) = (
            column(&runs[0], bin),
            column(&runs[1], bin),
            column(&glows, bin),
        );
        so += ours[k];
        sr += 0.5 * (r1 + r2);
        sg += g;
        println!(
            "{k:4} {:5.1} {:5.1}  {:9.3e}  {:9.3e} {:9.3e}  {:9.3e}  {:6.3}",
            d[2].asin().to_degrees(),
            d[0].atan2(d[1]).to_degrees().rem_euclid(360.0),
            ours[k],
            r1,
            r2,
            g,
            ours[k] / g
        );
    }
    println!("sum over the patches: eigenrad {so:.4e}, Radiance {sr:.4e}, glow model {sg:.4e}");
    let ground = 0.5 * (column(&runs[0], 0) + column(&runs[1], 0)) * rho_g;
    let mut glow_exterior = column(&glows, 0) * rho_g;
    for (o, obstruction) in scene.obstructions.iter().enumerate() {
        let c = column(&glows, 146 + o);
        println!(
            "{}: {c:.4e} per cd/m², ρ {}",
            obstruction.name, obstruction.reflectance
        );
        glow_exterior += c * obstruction.reflectance;
    }
    println!(
        "exterior per cd/m² of E_gh/π: eigenrad {ours_exterior:.4e}, Radiance's ground {ground:.4e}, \
         the glow model {glow_exterior:.4e}"
    );
}

/// The suns `gendaymtx -D` writes: per modifier name, the direct normal illuminance (lux:
/// the `light`'s radiance over gendaymtx's disc of 0.533°, times 179) and the direction.
fn read_suns(path: &Path) -> Vec<(String, f64, [f64; 3])> {
    let text = std::fs::read_to_string(path).unwrap();
    let words: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .flat_map(str::split_whitespace)
        .collect();
    let half_angle = (0.533f64 / 2.0).to_radians();
    let mut suns = Vec::new();
    let mut k = 0;
    while k + 2 < words.len() {
        // void light solarN 0 0 3 R G B   solarN source sunN 0 0 4 dx dy dz angle
        assert_eq!(words[k + 1], "light", "gendaymtx -D");
        let name = words[k + 2].to_owned();
        let r: f64 = words[k + 6].parse().unwrap();
        let d: Vec<f64> = words[k + 15..k + 18]
            .iter()
            .map(|w| w.parse().unwrap())
            .collect();
        let lux = radiance::WHITE_EFFICACY * r * std::f64::consts::PI * half_angle * half_angle;
        suns.push((name, lux, [d[0], d[1], d[2]]));
        k += 19;
    }
    suns
}

/// eigenrad's direct sun at the grid points (`DirectSun`) against Radiance's traced suns, each
/// at Radiance's position and direct normal illuminance: the geometry and the glazing alone.
#[test]
#[ignore = "a diagnosis of the reference run's files: run it after radiance_reference_run"]
fn direct_sun_against_radiance() {
    let radiance = Radiance::find().expect(radiance::SKIPPED);
    let dir = root().join(WORK);
    radiance.pipe(
        "gendaymtx",
        &dir,
        &[
            "-D",
            "suns_only.rad",
            "-M",
            "suns_only.mod",
            "-n",
            "year.wea",
        ],
        None,
        "suns_only.out",
    );
    let suns = read_suns(&dir.join("suns_only.rad"));
    let modifiers: Vec<String> = std::fs::read_to_string(dir.join("suns.mod"))
        .unwrap()
        .split_whitespace()
        .map(str::to_owned)
        .collect();
    assert_eq!(suns.len(), modifiers.len());
    let bytes = office_basis();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let (_, first, points) = grid(&basis);
    let n = points.len();
    let theirs = read_matrix_lux(&dir.join("suns.dat"), n, modifiers.len());
    let direct = DirectSun::new(&basis).unwrap().unwrap();
    let (mut so, mut st, mut sq, mut count) = (0.0, 0.0, 0.0, 0.0);
    let mut worst = (0.0, String::new());
    for (c, (name, lux, d)) in suns.iter().enumerate() {
        assert_eq!(name, &modifiers[c]);
        if *lux <= 0.0 {
            continue;
        }
        let room = direct.room_direction(d.map(|x| x as f32));
        for p in 0..n {
            let ours = lux * f64::from(direct.at_grid_point(first + p, room));
            let t = theirs[p][c];
            so += ours;
            st += t;
            sq += (ours - t) * (ours - t);
            count += 1.0;
            if (ours - t).abs() > worst.0 {
                worst = (
                    (ours - t).abs(),
                    format!("{name} at {:?}: {ours:.1} against {t:.1} lux", points[p]),
                );
            }
        }
    }
    println!(
        "direct sun at Radiance's positions: eigenrad/Radiance {:.5}, RMS {:.2} lux over {count} \
         point-hours, worst {}",
        so / st,
        (sq / count).sqrt(),
        worst.1
    );
    // eigenrad's own positions with Radiance's direct normal illuminance: the positions' share.
    let weather = weather::read(&root().join(WEATHER)).unwrap();
    let occupancy = simulate::Occupancy {
        days: [true; 7],
        from_hour: 8,
        to_hour: 18,
        days_text: "all".into(),
    };
    let options = simulate::HourOptions {
        year: None,
        source: SkySource::Irradiance,
    };
    let (hours, _, _) = simulate::hours(&weather, &basis, &occupancy, options).unwrap();
    let by_name: std::collections::HashMap<&str, usize> = suns
        .iter()
        .enumerate()
        .map(|(c, s)| (s.0.as_str(), c))
        .collect();
    let (mut so, mut st) = (0.0, 0.0);
    for (hour, r) in hours.iter().zip(&weather.records) {
        if !analysis(r.hour) {
            continue;
        }
        let key = Key {
            month: r.month,
            day: r.day,
            hour: r.hour,
        };
        let Some(&c) = by_name.get(format!("solar{}", solar_minute(key)).as_str()) else {
            continue;
        };
        let lux = suns[c].1;
        for p in 0..n {
            st += theirs[p][c];
            if let Some(s) = hour.sky.sun {
                let room = direct.room_direction(s.direction);
                so += lux * f64::from(direct.at_grid_point(first + p, room));
            }
        }
    }
    println!(
        "direct sun at eigenrad's positions, Radiance's direct normal: eigenrad/Radiance {:.5}",
        so / st
    );
}
