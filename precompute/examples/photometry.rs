//! Writes the example photometric files of `examples/photometry/` from closed forms:
//!
//! - `downlight.ies` (IES LM-63-2002): a narrow recessed downlight, `I(γ) = I₀ cos⁸ γ` for
//!   γ ≤ 90° and nothing upward, the same in every C-plane; a round luminous opening of
//!   200 mm diameter; absolute photometry.
//! - `linear-panel.ldt` (EULUMDAT): a wide-distribution recessed linear luminaire of
//!   1200 × 300 mm, `I(C, γ) = A cos γ (1 + sin²γ sin²C)` for γ ≤ 90°: a cosine (Lambertian)
//!   distribution along its length (the C0 plane), widened into a batwing across it (C90,
//!   peak at γ = 35.3°); quadrant symmetry.
//!
//! Each is defined by its flux Φ (lm), from which its scale follows by the analytic integral
//! over the sphere: `Φ = 2π I₀ / (n + 1)` for `cos^n`, `Φ = π A (1 + b/4)` for
//! `A cos γ (1 + b sin²γ sin²C)` (`∫₀^{π/2} cos γ sin²γ sin γ dγ = 1/4`, `∫₀^{2π} sin²C dC = π`).
//! `examples/photometry/PROVENANCE.md` says the same for readers of the files.
//!
//! ```sh
//! cargo run -p eigenrad-precompute --example photometry            # rewrites examples/photometry/
//! cargo run -p eigenrad-precompute --example photometry -- DIR     # writes them into DIR
//! ```
//!
//! The tests (`cargo test -p eigenrad-precompute --example photometry`) check that the shipped
//! files are byte for byte what this program writes, and that eigenrad's readers give each
//! file the closed form's flux, dimensions and symmetry.

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, Result};

/// The date both files carry (fixed, so that the output does not depend on the day it is run).
const ISSUE_DATE: &str = "2026-12-01";

/// The narrow downlight: `I(γ) = I₀ cos^n γ` for γ ≤ 90°, 0 above.
struct Downlight {
    /// Luminaire flux, lm.
    flux: f64,
    /// The exponent `n` (dimensionless): the beam (50 % of the peak) is `2 acos(2^(-1/n))`.
    exponent: i32,
    /// Diameter of the round luminous opening, m.
    diameter: f64,
    /// Input power, W.
    watts: f64,
    /// Vertical angle step of the table, degrees.
    step: f64,
}

const DOWNLIGHT: Downlight = Downlight {
    flux: 3300.0,
    exponent: 8,
    diameter: 0.2,
    watts: 28.0,
    step: 1.0,
};

impl Downlight {
    /// The peak intensity `I₀ = Φ (n + 1) / (2π)`, cd.
    fn peak(&self) -> f64 {
        self.flux * f64::from(self.exponent + 1) / (2.0 * PI)
    }

    /// Intensity, cd, at `gamma` degrees from the nadir.
    fn intensity(&self, gamma: f64) -> f64 {
        if gamma >= 90.0 {
            0.0
        } else {
            self.peak() * gamma.to_radians().cos().powi(self.exponent)
        }
    }

    /// The beam angle, degrees: twice the angle at which the intensity is half the peak.
    fn beam(&self) -> f64 {
        2.0 * 0.5f64
            .powf(1.0 / f64::from(self.exponent))
            .acos()
            .to_degrees()
    }
}

/// The linear panel: `I(C, γ) = A cos γ (1 + b sin²γ sin²C)` for γ ≤ 90°, 0 above.
struct Panel {
    /// Luminaire flux, lm.
    flux: f64,
    /// The widening `b` across the luminaire (dimensionless).
    widening: f64,
    /// Luminaire length (along C0), width (along C90) and height, mm.
    body: [f64; 3],
    /// Luminous area length and width, mm.
    area: [f64; 2],
    /// Input power, W.
    watts: f64,
    /// C-plane step, degrees.
    c_step: f64,
    /// γ step, degrees.
    gamma_step: f64,
}

const PANEL: Panel = Panel {
    flux: 4400.0,
    widening: 1.0,
    body: [1200.0, 300.0, 80.0],
    area: [1180.0, 280.0],
    watts: 34.0,
    c_step: 15.0,
    gamma_step: 2.5,
};

impl Panel {
    /// The scale `A = Φ / (π (1 + b/4))`, cd.
    fn scale(&self) -> f64 {
        self.flux / (PI * (1.0 + self.widening / 4.0))
    }

    /// Intensity, cd, towards `(c, gamma)` degrees.
    fn intensity(&self, c: f64, gamma: f64) -> f64 {
        if gamma >= 90.0 {
            return 0.0;
        }
        let (g, c) = (gamma.to_radians(), c.to_radians());
        self.scale() * g.cos() * (1.0 + self.widening * (g.sin() * c.sin()).powi(2))
    }
}

/// `0, step, 2 step, …, to` degrees.
fn angles(step: f64, to: f64) -> Vec<f64> {
    let n = (to / step).round() as usize;
    (0..=n).map(|i| i as f64 * step).collect()
}

/// Values written `per_line` to a line, separated by blanks.
fn wrapped(out: &mut String, values: &[String], per_line: usize) {
    for line in values.chunks(per_line) {
        out.push_str(&line.join(" "));
        out.push('\n');
    }
}

/// The downlight as IES LM-63-2002 text.
fn downlight_ies(d: &Downlight) -> String {
    let gamma = angles(d.step, 90.0);
    // Candela per 1000 lm of luminaire flux, scaled by the candela multiplier Φ/1000: the
    // multiplier scales every value (LM-63-2002, line 10).
    let per_klm = 1000.0 / d.flux;
    let multiplier = d.flux / 1000.0;
    let mut s = String::new();
    s.push_str("IESNA:LM-63-2002\n");
    s.push_str("[TEST] EIGENRAD-SYNTH-DL200\n");
    s.push_str("[TESTLAB] none: computed from a closed form, not measured\n");
    let _ = writeln!(s, "[ISSUEDATE] {ISSUE_DATE}");
    s.push_str("[MANUFAC] eigenrad example data (synthetic)\n");
    s.push_str("[LUMCAT] SYN-DL200\n");
    s.push_str("[LUMINAIRE] synthetic recessed LED downlight, round opening 200 mm\n");
    let _ = writeln!(
        s,
        "[MORE] I = {:.4} cd x cos^{} gamma for gamma < 90 deg, 0 above; beam {:.1} deg",
        d.peak(),
        d.exponent,
        d.beam()
    );
    let _ = writeln!(
        s,
        "[MORE] flux {} lm (2 pi I0 / {})",
        d.flux,
        d.exponent + 1
    );
    s.push_str("[LAMP] LED module\n");
    s.push_str("[LAMPCAT] none\n");
    s.push_str("[OTHER] Written by eigenrad's generator precompute/examples/photometry.rs;\n");
    s.push_str("[MORE] MIT OR Apache-2.0. Describes no real product.\n");
    s.push_str("TILT=NONE\n");
    // Lamps, lumens per lamp (−1: absolute), multiplier, vertical and horizontal angle
    // counts, photometric type 1 (C), units 2 (metres), width, length, height: negative width
    // and length are a round opening of that diameter.
    let _ = writeln!(
        s,
        "1 -1 {multiplier} {} 1 1 2 {} {} 0",
        gamma.len(),
        -d.diameter,
        -d.diameter
    );
    // Ballast factor, future use, input watts.
    let _ = writeln!(s, "1 1 {}", d.watts);
    let text = |v: &[f64]| v.iter().map(|a| format!("{a}")).collect::<Vec<_>>();
    wrapped(&mut s, &text(&gamma), 10);
    s.push_str("0\n");
    let candela: Vec<String> = gamma
        .iter()
        .map(|&g| format!("{:.2}", d.intensity(g) * per_klm))
        .collect();
    wrapped(&mut s, &candela, 10);
    s
}

/// The panel as EULUMDAT text, CRLF line ends as the format's writers use.
fn panel_ldt(p: &Panel) -> String {
    let c_planes = angles(p.c_step, 360.0 - p.c_step);
    let gamma = angles(p.gamma_step, 180.0);
    let mut lines: Vec<String> = Vec::new();
    let put = |l: &mut Vec<String>, v: String| l.push(v);
    for v in [
        "eigenrad example data (synthetic)".to_string(),
        // Ityp 2: linear luminaire; Isym 4: symmetric about C0-C180 and C90-C270.
        "2".into(),
        "4".into(),
        c_planes.len().to_string(),
        format!("{}", p.c_step),
        gamma.len().to_string(),
        format!("{}", p.gamma_step),
        "EIGENRAD-SYNTH-LP1200".into(),
        "synthetic recessed LED linear panel 1200 x 300 mm, wide distribution".into(),
        "SYN-LP1200".into(),
        "linear-panel.ldt".into(),
        format!("{ISSUE_DATE} / eigenrad precompute/examples/photometry.rs"),
    ] {
        put(&mut lines, v);
    }
    for mm in p.body.iter().chain(&p.area) {
        put(&mut lines, format!("{mm}"));
    }
    // Heights of the luminous area in the C0, C90, C180, C270 planes: a flat diffuser.
    for _ in 0..4 {
        put(&mut lines, "0".into());
    }
    // DFF (all downward), LORL (the lamp flux is the luminaire's), conversion factor, tilt.
    for v in ["100", "100", "1", "0"] {
        put(&mut lines, v.into());
    }
    // One lamp set: number of lamps, type, total flux (lm), colour, colour rendering, watts.
    for v in [
        "1".to_string(),
        "1".into(),
        "LED module".into(),
        format!("{}", p.flux),
        "4000 K".into(),
        "80".into(),
        format!("{}", p.watts),
    ] {
        put(&mut lines, v);
    }
    // The direct ratios for the room indices 0.6 … 5 are not computed (eigenrad does not read
    // them): written 0.
    for _ in 0..10 {
        put(&mut lines, "0".into());
    }
    for a in c_planes.iter().chain(&gamma) {
        put(&mut lines, format!("{a}"));
    }
    // Isym 4 stores C0 … C90; intensities in cd per 1000 lm of lamp flux.
    let per_klm = 1000.0 / p.flux;
    for &c in c_planes.iter().filter(|&&c| c <= 90.0) {
        for &g in &gamma {
            put(&mut lines, format!("{:.2}", p.intensity(c, g) * per_klm));
        }
    }
    let mut s = lines.join("\r\n");
    s.push_str("\r\n");
    s
}

/// The files this program writes: name and content.
fn files() -> Vec<(&'static str, String)> {
    vec![
        ("downlight.ies", downlight_ies(&DOWNLIGHT)),
        ("linear-panel.ldt", panel_ldt(&PANEL)),
    ]
}

/// The folder the files are shipped in.
fn shipped() -> PathBuf {
    let precompute = Path::new(env!("CARGO_MANIFEST_DIR"));
    precompute
        .parent()
        .unwrap_or(precompute)
        .join("examples/photometry")
}

fn main() -> Result<()> {
    let dir = std::env::args_os()
        .nth(1)
        .map_or_else(shipped, PathBuf::from);
    for (name, text) in files() {
        let path = dir.join(name);
        eigenrad_precompute::atomic::write(&path, text.as_bytes())
            .with_context(|| format!("writing {}", path.display()))?;
        println!("{}", path.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;
    use eigenrad_precompute::scene::photometry::{self, OpeningShape, Symmetry};

    /// The flux of a file, integrated by the reader over its bilinear interpolant, against the
    /// closed form's analytic flux. Linear interpolation between tabulated angles `h` apart
    /// errs by O(h²): computed for these tables (a quadrature of the closed form between the
    /// tabulated angles), 2.0e-4 for cos⁸ at 1° and 3.7e-4 in the panel's C90 plane at 2.5°;
    /// rounding the values to 0.01 cd/klm adds under 1e-5. Far inside the build's 0.5 % check.
    const FLUX_TOLERANCE: f64 = 5e-4;

    #[test]
    fn shipped_files_are_what_the_generator_writes() {
        for (name, text) in files() {
            let path = shipped().join(name);
            let on_disk = std::fs::read_to_string(&path).expect("shipped file");
            assert!(
                on_disk == text,
                "{} differs from what `cargo run -p eigenrad-precompute --example photometry` \
                 writes: run it",
                path.display()
            );
        }
    }

    #[test]
    fn downlight_reads_with_the_closed_form_flux_and_header() {
        let d = &DOWNLIGHT;
        let p = photometry::ies::parse(Path::new("downlight.ies"), downlight_ies(d).as_bytes())
            .expect("reads");
        assert_eq!(
            p.format,
            photometry::Format::Lm63(photometry::Lm63Version::V2002)
        );
        assert_eq!(p.symmetry, Symmetry::Rotational);
        assert!(p.absolute && p.lamp_flux.is_none() && p.lamps == 1);
        assert_eq!(p.opening.shape, OpeningShape::VerticalCylinder);
        assert_eq!((p.opening.length, p.opening.width), (0.2, 0.2));
        assert_eq!(p.input_watts, Some(d.watts));
        let flux = p.flux();
        assert!(
            ((flux - d.flux) / d.flux).abs() < FLUX_TOLERANCE,
            "{flux} lm against {} lm",
            d.flux
        );
        // The multiplier is applied: the peak is I₀ (to the table's rounding, 0.01 cd/klm).
        assert!((p.intensity(0.0, 0.0) - d.peak()).abs() < 0.01 * d.flux / 1000.0);
        // Half the peak at half the beam angle, to the interpolation between 1° steps.
        let half = p.intensity(123.0, d.beam() / 2.0) / d.peak();
        assert!((half - 0.5).abs() < 1e-3, "{half}");
        assert_eq!(p.intensity(0.0, 90.0), 0.0);
        assert_eq!(p.intensity(0.0, 120.0), 0.0);
    }

    #[test]
    fn panel_reads_with_the_closed_form_flux_and_header() {
        let panel = &PANEL;
        let p =
            photometry::eulumdat::parse(Path::new("linear-panel.ldt"), panel_ldt(panel).as_bytes())
                .expect("reads");
        assert_eq!(p.format, photometry::Format::Eulumdat);
        assert_eq!(p.symmetry, Symmetry::Quadrant);
        assert_eq!(p.opening.shape, OpeningShape::Rectangular);
        assert_eq!((p.opening.length, p.opening.width), (1.18, 0.28));
        let body = p.luminaire.expect("EULUMDAT gives the body");
        assert_eq!((body.length, body.width, body.height), (1.2, 0.3, 0.08));
        assert_eq!(p.luminaire_flux, Some(panel.flux));
        assert_eq!(p.downward_fraction, Some(1.0));
        let flux = p.flux();
        assert!(
            ((flux - panel.flux) / panel.flux).abs() < FLUX_TOLERANCE,
            "{flux} lm against {} lm",
            panel.flux
        );
        // All of it downward, as DFF says.
        assert!((p.distribution.flux_between(0.0, 90.0) - flux).abs() < 1e-9 * flux);
        // C0 (along the length) is a cosine, C90 (across) the batwing, and the quadrant
        // symmetry gives C180 = C0 and C270 = C90 = the mirror images.
        let a = panel.scale();
        let tol = 0.01 * panel.flux / 1000.0;
        for g in [0.0, 30.0, 60.0] {
            let cos = f64::to_radians(g).cos();
            let sin2 = f64::to_radians(g).sin().powi(2);
            for c in [0.0, 180.0] {
                assert!((p.intensity(c, g) - a * cos).abs() < tol, "C{c} γ{g}");
            }
            for c in [90.0, 270.0] {
                assert!((p.intensity(c, g) - a * cos * (1.0 + sin2)).abs() < tol);
            }
        }
        // Between the tabulated planes (C 15° apart) the interpolation is linear in C.
        let mid = p.intensity(52.5, 30.0);
        let ends = 0.5 * (p.intensity(45.0, 30.0) + p.intensity(60.0, 30.0));
        assert!((mid - ends).abs() < 1e-9);
    }
}
