//! Radiance as a reference program: finding its binaries, running them, tracing points with
//! `rtrace -I`, and turning its answers into lux. Shared by `validation_radiance.rs`
//! (luminaires) and `validation_radiance_daylight.rs` (sky and sun).
//!
//! Radiance is found as `EIGENRAD_RADIANCE` (a folder holding its programs, `RAYPATH` as set;
//! an error if rtrace does not run there), on `PATH`, or in the `pyradiance` wheel (`pip
//! install pyradiance`; its `bin/`, with its `lib/` as `RAYPATH`). Without it the tests print
//! "SKIPPED" and pass: the project's other tests do not need Radiance.

use std::ffi::OsString;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// Radiance's luminous efficacy of white light, lm/W (`WHTEFFICACY`, `src/common/color.h`):
/// `ies2rad` divides candela by it, `gensky` and `gendaylit` divide luminance by it, and
/// `luminance()` multiplies by it.
pub const WHITE_EFFICACY: f64 = 179.0;
/// Radiance's luminance weights of its RGB primaries (`CIE_rf`, `CIE_gf`, `CIE_bf`,
/// `src/common/color.h`), which `bright()` applies.
pub const LUMINANCE_WEIGHTS: [f64; 3] = [0.265074126, 0.670114631, 0.064811243];

/// The message of a test that finds no Radiance.
pub const SKIPPED: &str =
    "SKIPPED: Radiance not found (pip install pyradiance, or set EIGENRAD_RADIANCE)";

/// Illuminance, lux, of an `rtrace -I` answer (W/m² of Radiance's white, per primary).
pub fn lux(rgb: [f64; 3]) -> f64 {
    WHITE_EFFICACY * (0..3).map(|k| LUMINANCE_WEIGHTS[k] * rgb[k]).sum::<f64>()
}

/// Radiance's programs and the `RAYPATH` their function files (`source.cal`, `rayinit.cal`,
/// `skybright.cal`) need.
pub struct Radiance {
    /// Folder of the programs, `None` for `PATH`.
    bin: Option<PathBuf>,
    /// `RAYPATH` to set, `None` to keep the environment's.
    raypath: Option<OsString>,
}

impl Radiance {
    /// The Radiance to use, `None` if there is none.
    pub fn find() -> Option<Radiance> {
        if let Some(dir) = std::env::var_os("EIGENRAD_RADIANCE") {
            let named = Radiance {
                bin: Some(dir.into()),
                raypath: None,
            };
            // Named on purpose: a folder where rtrace does not run is an error, not a skip.
            assert!(
                named.works(),
                "EIGENRAD_RADIANCE: no working rtrace in {:?} (is RAYPATH set?)",
                named.bin
            );
            return Some(named);
        }
        let on_path = Radiance {
            bin: None,
            raypath: None,
        };
        if on_path.works() {
            return Some(on_path);
        }
        let script = "import os, pyradiance; print(os.path.dirname(pyradiance.__file__))";
        let out = Command::new("python3").args(["-c", script]).output().ok()?;
        if !out.status.success() {
            return None;
        }
        let package = PathBuf::from(String::from_utf8(out.stdout).ok()?.trim());
        let wheel = Radiance {
            bin: Some(package.join("bin")),
            raypath: Some(std::env::join_paths([Path::new("."), &package.join("lib")]).ok()?),
        };
        wheel.works().then_some(wheel)
    }

    /// Whether `rtrace` runs (it fails without its `rayinit.cal`).
    fn works(&self) -> bool {
        self.command("rtrace", &std::env::temp_dir())
            .arg("-version")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    }

    fn command(&self, program: &str, dir: &Path) -> Command {
        let mut command = Command::new(match &self.bin {
            Some(bin) => bin.join(program),
            None => program.into(),
        });
        command.current_dir(dir);
        // A scene's `!xform` runs through the shell: the programs' folder goes on `PATH`.
        if let Some(bin) = &self.bin {
            let path = std::env::var_os("PATH").unwrap_or_default();
            let paths = std::iter::once(bin.clone()).chain(std::env::split_paths(&path));
            command.env("PATH", std::env::join_paths(paths).unwrap());
        }
        if let Some(raypath) = &self.raypath {
            command.env("RAYPATH", raypath);
        }
        command
    }

    /// Runs `program` in `dir`, stdout to `stdout` (a file in `dir`) if given; panics with its
    /// stderr if it fails or warns (a missing `!xform` is only a warning to oconv).
    pub fn run(&self, program: &str, dir: &Path, args: &[&str], stdout: Option<&str>) {
        let mut command = self.command(program, dir);
        command.args(args);
        if let Some(file) = stdout {
            command.stdout(std::fs::File::create(dir.join(file)).unwrap());
        }
        let out = command.stderr(Stdio::piped()).output().unwrap();
        assert!(
            out.status.success() && out.stderr.is_empty(),
            "{program} {args:?} failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }

    /// Runs `program` in `dir` and returns its standard output; panics as [`Radiance::run`].
    pub fn output(&self, program: &str, dir: &Path, args: &[&str]) -> String {
        let out = self
            .command(program, dir)
            .args(args)
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        assert!(
            out.status.success() && out.stderr.is_empty(),
            "{program} {args:?} failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    }

    /// Runs `program` in `dir` with standard input from the file `stdin` (in `dir`) if given
    /// and standard output to the file `stdout` (in `dir`); returns its standard error, which
    /// programs such as `rfluxmtx` fill with notes. Panics if it fails.
    pub fn pipe(
        &self,
        program: &str,
        dir: &Path,
        args: &[&str],
        stdin: Option<&str>,
        stdout: &str,
    ) -> String {
        let mut command = self.command(program, dir);
        command.args(args);
        if let Some(file) = stdin {
            command.stdin(std::fs::File::open(dir.join(file)).unwrap());
        }
        command.stdout(std::fs::File::create(dir.join(stdout)).unwrap());
        let out = command.stderr(Stdio::piped()).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(out.status.success(), "{program} {args:?} failed: {stderr}");
        stderr
    }

    /// The octree `name.oct` of `scene` (Radiance text), in `dir`.
    pub fn octree(&self, dir: &Path, name: &str, scene: &str) -> String {
        let rad = format!("{name}.rad");
        std::fs::write(dir.join(&rad), scene).unwrap();
        let oct = format!("{name}.oct");
        // Frozen (`-f`): rtrace reads the octree alone.
        self.run("oconv", dir, &["-f", &rad], Some(&oct));
        oct
    }

    /// `rtrace` with `options` (which hold `-I`) at every `(position, normal)` of `points` (m),
    /// `repeats` times over: per point the mean illuminance and the standard error of that mean
    /// (0 for one repeat), lux.
    pub fn trace(
        &self,
        dir: &Path,
        octree: &str,
        options: &[&str],
        points: &[([f64; 3], [f64; 3])],
        repeats: usize,
    ) -> Vec<Estimate> {
        let mut input = String::new();
        for _ in 0..repeats {
            for ([x, y, z], [nx, ny, nz]) in points {
                writeln!(input, "{x} {y} {z} {nx} {ny} {nz}").unwrap();
            }
        }
        let path = dir.join(format!("{octree}.points"));
        std::fs::write(&path, input).unwrap();
        let out = self
            .command("rtrace", dir)
            .args(options)
            .arg(octree)
            .stdin(std::fs::File::open(&path).unwrap())
            .output()
            .unwrap();
        assert!(
            out.status.success() && out.stderr.is_empty(),
            "rtrace failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let lux: Vec<f64> = String::from_utf8(out.stdout)
            .unwrap()
            .lines()
            .map(|line| {
                let rgb: Vec<f64> = line
                    .split_whitespace()
                    .map(|w| w.parse().unwrap())
                    .collect();
                assert_eq!(rgb.len(), 3, "rtrace line `{line}`");
                lux([rgb[0], rgb[1], rgb[2]])
            })
            .collect();
        assert_eq!(lux.len(), repeats * points.len(), "rtrace's output lines");
        (0..points.len())
            .map(|i| {
                let runs: Vec<f64> = (0..repeats).map(|r| lux[r * points.len() + i]).collect();
                Estimate::of(&runs)
            })
            .collect()
    }
}

/// A Monte Carlo mean and its standard error, lux.
#[derive(Clone, Copy, Debug)]
pub struct Estimate {
    /// Mean of the runs.
    pub mean: f64,
    /// Standard error of that mean (the runs' sample standard deviation over √runs).
    pub standard_error: f64,
}

impl Estimate {
    /// The mean and standard error of independent `runs`.
    pub fn of(runs: &[f64]) -> Estimate {
        let n = runs.len() as f64;
        let mean = runs.iter().sum::<f64>() / n;
        let standard_error = if runs.len() < 2 {
            0.0
        } else {
            (runs.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt()
        };
        Estimate {
            mean,
            standard_error,
        }
    }
}

/// A fresh folder for one Radiance test's files.
pub fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eigenrad-radiance-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A grey room of `size` (m) as Radiance primitives, all but its y = 0 wall (whose openings
/// each test cuts itself): materials `floor_mat`, `wall_mat` and `ceiling_mat`, `plastic` of
/// the given greys with no specularity and no roughness (Lambertian), and the floor, ceiling
/// and walls x = 0, x = size x and y = size y as polygons counter-clockwise seen from inside
/// (Radiance's right-hand normal points into the room, as eigenrad's room faces do).
pub fn grey_room_but_y0(size: [f64; 3], floor: f64, wall: f64, ceiling: f64) -> String {
    let [x, y, z] = size;
    let mut text = String::new();
    for (name, r) in [
        ("floor_mat", floor),
        ("wall_mat", wall),
        ("ceiling_mat", ceiling),
    ] {
        writeln!(text, "void plastic {name} 0 0 5 {r} {r} {r} 0 0").unwrap();
    }
    let faces: [(&str, &str, [[f64; 3]; 4]); 5] = [
        (
            "floor_mat",
            "floor",
            [[0., 0., 0.], [x, 0., 0.], [x, y, 0.], [0., y, 0.]],
        ),
        (
            "ceiling_mat",
            "ceiling",
            [[0., 0., z], [0., y, z], [x, y, z], [x, 0., z]],
        ),
        (
            "wall_mat",
            "wall_xmin",
            [[0., 0., 0.], [0., y, 0.], [0., y, z], [0., 0., z]],
        ),
        (
            "wall_mat",
            "wall_xmax",
            [[x, 0., 0.], [x, 0., z], [x, y, z], [x, y, 0.]],
        ),
        (
            "wall_mat",
            "wall_ymax",
            [[0., y, 0.], [x, y, 0.], [x, y, z], [0., y, z]],
        ),
    ];
    for (material, name, corners) in faces {
        write_polygon(&mut text, material, name, &corners);
    }
    text
}

/// One Radiance `polygon` of `material` named `name`, on a line of its own.
pub fn write_polygon(text: &mut String, material: &str, name: &str, corners: &[[f64; 3]]) {
    write!(text, "{material} polygon {name} 0 0 {}", 3 * corners.len()).unwrap();
    for [a, b, c] in corners {
        write!(text, "  {a} {b} {c}").unwrap();
    }
    text.push('\n');
}
