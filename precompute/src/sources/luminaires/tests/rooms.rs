//! Luminaires in closed rooms from photometric files: the flux each room receives, its
//! account, and tilt tables.

use super::*;

/// A closed 4 m × 3 m × 2.5 m room with a luminaire of `file` (absolute path) at `position`.
fn room_with(file: &Path, position: [f64; 3], maintenance: f64) -> scene::Scene {
    let text = format!(
        r#"[scene]
name = "lit room"
bands = "photopic"
unit = "m"
max_edge = 0.5

[materials]
wall = {{ reflectance = 0.5 }}

[[room]]
name = "room"
min = [0, 0, 0]
max = [4, 3, 2.5]
material = "wall"

[[channel]]
name = "lamps"

[[luminaire]]
name = "lamp"
file = "{}"
position = {position:?}
channel = "lamps"
maintenance_factor = {maintenance}
"#,
        file.display()
    );
    scene::parse(&text, Path::new("/nowhere/room.toml")).unwrap_or_else(|e| panic!("{e}"))
}

/// An LM-63 file of `i0 cos γ` cd (absolute photometry) from a flat `width × length` (m)
/// opening, written to a scratch folder.
fn lambertian_file(test: &str, width: f64, length: f64) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eigenrad-lum-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let gamma: Vec<String> = (0..=18).map(|k| (5 * k).to_string()).collect();
    let candela: Vec<String> = (0..=18)
        .map(|k| format!("{:.6}", 800.0 * f64::from(5 * k).to_radians().cos()))
        .collect();
    let text = format!(
        "IESNA:LM-63-2002\n[TEST] synthetic\nTILT=NONE\n1 -1 1 19 1 1 2 {width} {length} 0\n\
         1 1 30\n{}\n0\n{}\n",
        gamma.join(" "),
        candela.join(" ")
    );
    let path = dir.join("panel.ies");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_closed_room_receives_the_luminaires_flux() {
    let testdata = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/scene/photometry/testdata");
    let cases = [
        // An isotropic point source in the middle of the room.
        (testdata.join("isotropic.ies"), [2.0, 1.5, 1.25], 0.8, 1e-5),
        // A 0.6 m panel recessed in the ceiling: split near the walls and the floor.
        (
            lambertian_file("flux", 0.6, 0.6),
            [2.0, 1.5, 2.5],
            1.0,
            1e-3,
        ),
    ];
    for (file, position, mf, tolerance) in cases {
        let scene = room_with(&file, position, mf);
        assert_eq!(scene.luminaires.len(), 1);
        let occluders = Occluders::with_faces(&scene.patches, &scene.faces);
        let lights = channel_lights(&scene, &occluders, &LuminaireOptions::default());
        assert_eq!(lights.len(), 1);
        assert!(lights[0].emission[0].iter().all(|&e| e == 0.0));
        let received: f64 = scene
            .patches
            .iter()
            .zip(&lights[0].patch_irradiance[0])
            .map(|(p, e)| p.area * e)
            .sum();
        let flux = scene.luminaires[0].photometry.flux() * mf;
        assert!(
            relative(received, flux) < tolerance,
            "{}: {received} lm of {flux} lm",
            file.display()
        );
    }
}

#[test]
fn the_flux_account_of_a_closed_room_loses_nothing_and_flags_files_that_disagree() {
    // Closed room: what the luminaire emits reaches the surfaces; nothing escapes.
    let testdata = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/scene/photometry/testdata");
    let scene = room_with(&testdata.join("isotropic.ies"), [2.0, 1.5, 1.25], 0.8);
    let occluders = Occluders::with_faces(&scene.patches, &scene.faces);
    let (_, accounts) = lights_and_flux(&scene, &occluders, &LuminaireOptions::default());
    assert_eq!(accounts.len(), 1);
    let a = &accounts[0];
    assert_eq!(a.name, "lamp");
    assert!(relative(a.emitted, 0.8 * a.integrated) < 1e-15);
    assert!(a.escaping.abs() < 1e-5 * a.emitted, "{a:?}");
    assert!(a.warning.is_none(), "{a:?}");

    // A stated flux the candela table does not carry, and lamps giving less than the
    // luminaire sends out, are flagged; agreement within the tolerance is not.
    let account = |stated: Option<f64>, lamps: Option<f64>| {
        let mut p = isotropic(100.0);
        p.luminaire_flux = stated;
        p.lamp_flux = lamps;
        let lum = luminaire(p, Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 0.0, -1.0), 0.0);
        LuminaireFlux::new(&lum, 0.0)
    };
    let flux = 400.0 * PI;
    assert!(account(Some(flux * 1.001), None).warning.is_none());
    let off = account(Some(flux * 1.02), None).warning.expect("2 % apart");
    assert!(
        off.contains("integrates to") && off.contains("% apart"),
        "{off}"
    );
    assert!(account(None, Some(flux * 1.25)).warning.is_none());
    let more = account(None, Some(flux * 0.9))
        .warning
        .expect("more than the lamps");
    assert!(more.contains("more than the"), "{more}");
    // A tilted luminaire with a tilt table: the file's flux stays the table's own, what it
    // emits carries the factor (0.8 at 30°, `tilted_isotropic`), and nothing is flagged.
    let aim = Vec3::new(30f64.to_radians().sin(), 0.0, -30f64.to_radians().cos());
    let position = Vec3::new(0.0, 0.0, 1.0);
    let lum = luminaire(
        tilted_isotropic(100.0, LampGeometry::Vertical),
        position,
        aim,
        0.0,
    );
    let a = LuminaireFlux::new(&lum, 0.0);
    assert!(relative(a.integrated, flux) < 1e-12, "{a:?}");
    assert!((a.tilt_factor - 0.8).abs() < 1e-12, "{a:?}");
    assert!(relative(a.emitted, 0.8 * flux) < 1e-12, "{a:?}");
    assert!(a.warning.is_none(), "{a:?}");
}

/// `isotropic(i)` with a tilt table of lamp geometry `geometry`: factors 1, 0.9, 0.8 and 0.5
/// at 0°, 15°, 30° and 90°.
fn tilted_isotropic(i: f64, geometry: LampGeometry) -> Photometry {
    let mut p = isotropic(i);
    p.tilt = Some(Tilt {
        geometry,
        angles: vec![0.0, 15.0, 30.0, 90.0],
        factors: vec![1.0, 0.9, 0.8, 0.5],
    });
    p
}

/// A tilted luminaire's illuminance is its tilt factor times the untilted file's, from the
/// point-source closed form `E = I / d²` straight along its nadir, for each lamp geometry:
/// vertical lamps read the table at the nadir's angle from straight down, horizontal lamps
/// at their axis's (C0 for code 2, C90 for code 3) angle from the horizontal. The factors
/// are hand-computed from `tilted_isotropic`'s table: 0.8 at 30°, 0.85 at 22.5° (halfway
/// from 15° to 30°), 0.65 at 60° (halfway from 30° to 90°), 0.5 at 90°, 1 untilted.
#[test]
fn tilt_tables_multiply_each_luminaire_by_the_factor_at_its_tilt() {
    let (i, d) = (200.0, 2.0);
    let at = Vec3::new(0.3, -0.2, 2.5);
    // Aimed `degrees` from straight down, leaning towards +x (a turn about y) or +y (about x).
    let towards_x = |deg: f64| {
        let t = deg.to_radians();
        Vec3::new(t.sin(), 0.0, -t.cos())
    };
    let towards_y = |deg: f64| {
        let t = deg.to_radians();
        Vec3::new(0.0, t.sin(), -t.cos())
    };
    let occluders = Occluders::new(&[]);
    let opts = LuminaireOptions::default();
    let gl = gauss_legendre(opts.order);
    use LampGeometry::{Horizontal0, Horizontal90, Vertical};
    let cases: &[(LampGeometry, Vec3, f64, f64)] = &[
        // Untilted, whatever the spin: the table at 0°.
        (Vertical, DOWN, 0.0, 1.0),
        (Horizontal0, DOWN, 40.0, 1.0),
        (Horizontal90, DOWN, -70.0, 1.0),
        // Code 1: the nadir's angle from straight down, whichever way it leans.
        (Vertical, towards_x(30.0), 0.0, 0.8),
        (Vertical, towards_y(30.0), 55.0, 0.8),
        (Vertical, towards_x(22.5), 0.0, 0.85),
        (Vertical, towards_y(90.0), 0.0, 0.5),
        // A table ending at 90° folds 120° onto 60°, and straight up onto 0°.
        (Vertical, towards_x(120.0), 0.0, 0.65),
        (Vertical, UP, 0.0, 1.0),
        // Code 2, lamp along C0: leaning towards +x raises C0 (to 30°); a turn about x, the
        // C0 axis, leaves the lamp horizontal; spun by 90°, C0 lies across that turn and rises.
        (Horizontal0, towards_x(30.0), 0.0, 0.8),
        (Horizontal0, towards_y(30.0), 0.0, 1.0),
        (Horizontal0, towards_y(30.0), 90.0, 0.8),
        (Horizontal0, towards_x(60.0), 0.0, 0.65),
        // Code 3, lamp along C90: the other way round.
        (Horizontal90, towards_y(30.0), 0.0, 0.8),
        (Horizontal90, towards_x(30.0), 0.0, 1.0),
        (Horizontal90, towards_x(30.0), 90.0, 0.8),
        (Horizontal90, towards_y(22.5), 0.0, 0.85),
    ];
    for &(geometry, aim, spin, factor) in cases {
        let tilted = luminaire(tilted_isotropic(i, geometry), at, aim, spin);
        let plain = luminaire(isotropic(i), at, aim, spin);
        assert!(
            (tilted.tilt_factor - factor).abs() < 1e-12,
            "{geometry:?} aimed {aim:?} spun {spin}°: factor {}, expected {factor}",
            tilted.tilt_factor
        );
        assert_eq!(plain.tilt_factor, 1.0);
        let nadir = tilted.nadir;
        let x = at + nadir * d;
        let lit = Source::new(&tilted, &occluders, &opts, &gl).point(
            x,
            -nadir,
            FieldOfView::HEMISPHERE,
            &[],
        );
        let bare = Source::new(&plain, &occluders, &opts, &gl).point(
            x,
            -nadir,
            FieldOfView::HEMISPHERE,
            &[],
        );
        assert!(relative(bare, i / (d * d)) < 1e-12, "{bare}");
        assert!(
            relative(lit, factor * i / (d * d)) < 1e-12,
            "{geometry:?} aimed {aim:?} spun {spin}°: {lit} lux, untilted {bare} lux"
        );
    }
}
