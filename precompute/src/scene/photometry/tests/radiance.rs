//! The LM-63 reader against Radiance's `ies2rad`, where it is installed (the `pyradiance`
//! wheel ships it: `pip install pyradiance`; or name the program in `EIGENRAD_IES2RAD`).
//! Without it the test says so and passes: the project's own tests do not need Radiance.
//!
//! `ies2rad` writes a file's candela values, unscaled, divided by Radiance's white efficacy
//! (179 lm/W), into `NAME.dat` (number of dimensions; per dimension, horizontal first, either
//! `first last count` or `0 0 count` and the angles; then the values), the tilt table into
//! `NAME%.dat`, and the scale into the `brightdata` primitive of `NAME.rad`: its one real
//! argument is candela multiplier × ballast factor (× ballast-lamp factor before LM-63-1995)
//! divided by the area of the source, which with `-i 0.5` is a sphere 1 m across, π/4 m².

use std::path::{Path, PathBuf};
use std::process::Command;

use super::super::ies;
use super::data;

/// Radiance's luminous efficacy of white light, lm/W (`WHTEFFICACY`).
const WHITE_EFFICACY: f64 = 179.0;

/// The `ies2rad` program, if there is one.
fn ies2rad() -> Option<PathBuf> {
    if let Some(path) = std::env::var_os("EIGENRAD_IES2RAD") {
        return Some(path.into());
    }
    if Command::new("ies2rad").output().is_ok() {
        return Some("ies2rad".into());
    }
    let script = "import os, pyradiance; \
                  print(os.path.join(os.path.dirname(pyradiance.__file__), 'bin', 'ies2rad'))";
    let out = Command::new("python3").args(["-c", script]).output().ok()?;
    let path = PathBuf::from(String::from_utf8(out.stdout).ok()?.trim());
    (out.status.success() && path.is_file()).then_some(path)
}

/// The numbers of a Radiance data file: dimensions (angles of each, horizontal first) and
/// values.
fn read_dat(path: &Path) -> (Vec<Vec<f64>>, Vec<f64>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut numbers = text.split_whitespace().map(|w| w.parse::<f64>().unwrap());
    let mut next = || numbers.next().expect("truncated data file");
    let dims = next() as usize;
    let mut axes = Vec::new();
    for _ in 0..dims {
        let (first, last, count) = (next(), next(), next() as usize);
        axes.push(if first == 0.0 && last == 0.0 {
            (0..count).map(|_| next()).collect()
        } else {
            let step = (last - first) / (count as f64 - 1.0);
            (0..count).map(|k| first + k as f64 * step).collect()
        });
    }
    let total = axes.iter().map(Vec::len).product::<usize>();
    let values = (0..total).map(|_| next()).collect();
    (axes, values)
}

/// The real argument of the distribution's `brightdata` in a `.rad` file.
fn multiplier_over_area(rad: &Path) -> f64 {
    let text = std::fs::read_to_string(rad).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let at = lines
        .iter()
        .position(|l| {
            l.contains("brightdata") && l.trim_end().trim_end_matches('\'').ends_with("_dist")
        })
        .expect("a distribution");
    let reals: Vec<f64> = lines[at + 3]
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    assert_eq!(
        reals[0],
        1.0,
        "one real argument with -i: {}",
        lines[at + 3]
    );
    reals[1]
}

fn close(a: f64, b: f64) -> bool {
    // ies2rad prints six significant digits.
    (a - b).abs() <= 5e-6 * a.abs().max(b.abs()) + 1e-9
}

#[test]
fn candela_match_ies2rad() {
    let Some(program) = ies2rad() else {
        eprintln!("skipped: ies2rad not found (pip install pyradiance, or set EIGENRAD_IES2RAD)");
        return;
    };
    let out = std::env::temp_dir().join(format!("eigenrad-ies2rad-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    let mut compared = 0;
    for entry in std::fs::read_dir(data("")).unwrap() {
        let file = entry.unwrap().path();
        if file.extension().and_then(|e| e.to_str()) != Some("ies") {
            continue;
        }
        let name = file.file_stem().unwrap().to_str().unwrap().to_string();
        let status = Command::new(&program)
            .args(["-i", "0.5", "-o", &name])
            .arg(&file)
            .current_dir(&out)
            .stderr(std::process::Stdio::null())
            .status()
            .unwrap();
        assert!(status.success(), "ies2rad failed on {name}");
        let p = ies::parse(&file, &std::fs::read(&file).unwrap()).unwrap();
        let scale =
            multiplier_over_area(&out.join(format!("{name}.rad"))) * std::f64::consts::PI / 4.0;
        let (axes, values) = read_dat(&out.join(format!("{name}.dat")));
        // A rotationally symmetric file has one dimension, the vertical angles.
        let (horizontal, vertical) = match axes.len() {
            1 => (vec![0.0], axes[0].clone()),
            _ => (axes[0].clone(), axes[1].clone()),
        };
        assert_eq!(vertical, p.distribution.gamma_angles(), "{name}");
        for (j, &h) in horizontal.iter().enumerate() {
            for (i, &v) in vertical.iter().enumerate() {
                let theirs = values[j * vertical.len() + i] * WHITE_EFFICACY * scale;
                let ours = p.intensity(h, v);
                assert!(
                    close(ours, theirs),
                    "{name} at C {h}°, γ {v}°: {ours} vs {theirs}"
                );
                compared += 1;
            }
        }
        if let Some(tilt) = &p.tilt {
            let (axes, factors) = read_dat(&out.join(format!("{name}%.dat")));
            assert_eq!(axes[0], tilt.angles, "{name}");
            assert_eq!(factors, tilt.factors, "{name}");
        }
    }
    std::fs::remove_dir_all(&out).unwrap();
    assert!(compared > 1000, "{compared} values compared");
}

#[test]
fn opening_matches_ies2rad_geometry() {
    // Without -i, ies2rad draws the luminous opening: a rectangle from −length/2 to length/2
    // along x (the C0 direction) and −width/2 to width/2 along y.
    let Some(program) = ies2rad() else {
        eprintln!("skipped: ies2rad not found");
        return;
    };
    let out =
        std::env::temp_dir().join(format!("eigenrad-ies2rad-geometry-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    let file = data("lm63-2002-half.ies");
    let status = Command::new(&program)
        .args(["-o", "half"])
        .arg(&file)
        .current_dir(&out)
        .stderr(std::process::Stdio::null())
        .status()
        .unwrap();
    assert!(status.success());
    let rad = std::fs::read_to_string(out.join("half.rad")).unwrap();
    std::fs::remove_dir_all(&out).unwrap();
    let vertices: Vec<Vec<f64>> = rad
        .lines()
        .map(|l| {
            l.split_whitespace()
                .filter_map(|w| w.parse().ok())
                .collect::<Vec<f64>>()
        })
        .filter(|v| v.len() == 3)
        .collect();
    let extent = |k: usize| 2.0 * vertices.iter().map(|v| v[k].abs()).fold(0.0, f64::max);
    let o = ies::parse(&file, &std::fs::read(&file).unwrap())
        .unwrap()
        .opening;
    assert!(
        (extent(0) - o.length).abs() < 1e-9,
        "length {} vs {}",
        extent(0),
        o.length
    );
    assert!(
        (extent(1) - o.width).abs() < 1e-9,
        "width {} vs {}",
        extent(1),
        o.width
    );
}
