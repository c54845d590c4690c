//! `[[luminaire]]` entries: the example office and classroom, arrays, orientation, channels driven by
//! luminaires only, and an error for each mistake naming the file, line and field.

use super::*;

/// The photometric test files of the photometry reader, by absolute path (a scene joins an
/// absolute `file` as it is).
fn testdata(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("src/scene/photometry/testdata")
        .join(name)
        .display()
        .to_string()
}

fn lamp(fields: &str) -> String {
    format!(
        "\n[[channel]]\nname = \"c\"\n\n[[luminaire]]\nname = \"lamp\"\nfile = \"{}\"\n\
         position = [0.5, 0.5, 2]\nchannel = \"c\"\n{fields}",
        testdata("isotropic.ies")
    )
}

#[test]
fn scene_classroom_example_places_six_luminaires_on_two_channels() {
    let scene = load(&example("classroom")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.channels.len(), 2);
    assert!(scene.channels.iter().all(|c| c.surfaces.is_empty()));
    assert!(scene.emission.iter().flatten().all(|&e| e == 0.0));
    let names: Vec<&str> = scene.luminaires.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "window_row[1,1]",
            "window_row[1,2]",
            "window_row[1,3]",
            "corridor_row[1,1]",
            "corridor_row[1,2]",
            "corridor_row[1,3]"
        ]
    );
    let l = &scene.luminaires[4];
    assert_eq!(l.channel, 1);
    assert!((l.position - Vec3::new(4.0, 4.5, 3.0)).length() < 1e-12);
    assert_eq!(l.maintenance_factor, 0.8);
    assert!((l.nadir - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-15);
    // One file, read once, shared.
    assert!(std::sync::Arc::ptr_eq(
        &l.photometry,
        &scene.luminaires[0].photometry
    ));
    let p = &l.photometry;
    assert!((p.opening.length - 0.6).abs() < 1e-12 && (p.opening.width - 0.6).abs() < 1e-12);
    assert!((p.flux() / 3141.6 - 1.0).abs() < 2e-2, "{} lm", p.flux());
}

/// The office: the Lambertian office's room with its four luminaires given by the shipped
/// photometric files (examples/photometry/), one channel each, the window's channel as before.
#[test]
fn scene_office_example_places_four_luminaires_with_photometry() {
    let scene = load(&example("office")).unwrap_or_else(|e| panic!("{e}"));
    let lambertian = load(&example("office-lambertian")).unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<&str> = scene.channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["lum1", "lum2", "lum3", "lum4", "window"]);
    assert_eq!(scene.sensors, lambertian.sensors);
    // Only the window emits; the luminaires' faces are ceiling (no openings for them).
    assert!(scene.channels[..4].iter().all(|c| c.surfaces.is_empty()));
    assert_eq!(scene.channels[4].exitance, vec![3000.0]);
    let ceiling: f64 = patches(&scene, "room.ceiling").iter().map(|p| p.area).sum();
    assert!((ceiling - 24.0).abs() < 1e-12, "{ceiling} m²");
    let files = [
        "linear-panel.ldt",
        "linear-panel.ldt",
        "downlight.ies",
        "downlight.ies",
    ];
    // The Lambertian office's luminaires are the centres of its 0.6 m quads.
    let centres = [[1.5, 1.2], [4.5, 1.2], [1.5, 2.8], [4.5, 2.8]];
    for (k, l) in scene.luminaires.iter().enumerate() {
        assert_eq!(l.name, format!("lum{}", k + 1));
        assert_eq!(l.channel, k);
        assert!(l.file.ends_with(files[k]), "{}", l.file.display());
        let [x, y] = centres[k];
        assert!((l.position - Vec3::new(x, y, 2.8)).length() < 1e-12);
        assert!((l.nadir - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-15);
        assert!((l.c0 - Vec3::new(1.0, 0.0, 0.0)).length() < 1e-15);
        assert_eq!(l.maintenance_factor, 0.8);
    }
    // The flux of the files (their generator's closed forms: 4400 lm and 3300 lm).
    for (k, flux) in [(0, 4400.0), (2, 3300.0)] {
        let f = scene.luminaires[k].photometry.flux();
        assert!((f / flux - 1.0).abs() < 5e-4, "{f} lm");
    }
}

#[test]
fn scene_luminaire_aim_spin_array_and_units() {
    let text = BASE
        .replace("unit = \"m\"", "unit = \"cm\"")
        .replace("max_edge = 0.5", "max_edge = 50");
    let extra = format!(
        "\n[[channel]]\nname = \"c\"\n\n[[luminaire]]\nname = \"wash\"\nfile = \"{}\"\n\
         position = [10, 20, 200]\naim = [1, 0, 0]\nspin = 90\n\
         array = {{ rows = 2, columns = 3, spacing = [100, 50] }}\nchannel = \"c\"\n",
        testdata("lm63-2019-none.ies")
    );
    let scene = parse(&format!("{text}{extra}"), Path::new(FILE)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.luminaires.len(), 6);
    let last = &scene.luminaires[5];
    assert_eq!(last.name, "wash[2,3]");
    // Columns along x, rows along y, in the scene's unit.
    assert!((last.position - Vec3::new(2.1, 0.7, 2.0)).length() < 1e-12);
    // Aimed at +x: C0 points up before the spin, and the spin of 90° turns it onto C90's
    // place (+y), counter-clockwise seen from behind the luminaire.
    assert!((last.nadir - Vec3::new(1.0, 0.0, 0.0)).length() < 1e-12);
    assert!(
        (last.c0 - Vec3::new(0.0, 1.0, 0.0)).length() < 1e-12,
        "{:?}",
        last.c0
    );
    assert!((last.c90 - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
    // Straight at the nadir the luminaire gives its distribution's γ = 0 value.
    let (c, gamma) = last.angles(Vec3::new(3.0, 0.0, 0.0));
    assert!(gamma.abs() < 1e-9, "{c} {gamma}");
}

/// A file with a tilt table (`lm63-2002-tilt.ies`: a vertical lamp, factors 1, 0.98, 0.95,
/// 0.9 … at 0°, 15°, 30°, 45° …): each entry's factor comes from its own aim, every element of
/// an array shares it, and every intensity carries it.
#[test]
fn scene_luminaire_tilt_factor_follows_its_aim() {
    let entry = |name: &str, aim: &str| {
        format!(
            "\n[[luminaire]]\nname = \"{name}\"\nfile = \"{}\"\nposition = [1, 1, 2]\n\
             aim = {aim}\narray = {{ rows = 1, columns = 2, spacing = [0.5, 0.5] }}\n\
             channel = \"c\"\n",
            testdata("lm63-2002-tilt.ies")
        )
    };
    let text = format!(
        "{BASE}\n[[channel]]\nname = \"c\"\n{}{}{}",
        entry("down", "[0, 0, -1]"),
        entry("tilted", "[1, 0, -1]"),
        // 37.5° from straight down: halfway between the factors at 30° and 45°.
        entry(
            "between",
            &format!("[{}, 0, -1]", 37.5f64.to_radians().tan())
        ),
    );
    let scene = parse(&text, Path::new(FILE)).unwrap_or_else(|e| panic!("{e}"));
    let factors: Vec<f64> = scene.luminaires.iter().map(|l| l.tilt_factor).collect();
    let expected = [1.0, 1.0, 0.9, 0.9, 0.925, 0.925];
    for (f, e) in factors.iter().zip(expected) {
        assert!((f - e).abs() < 1e-12, "{factors:?}");
    }
    // The intensity along the nadir is the file's γ = 0 value times the factor.
    for l in &scene.luminaires {
        let at_nadir = l.photometry.intensity(0.0, 0.0);
        assert!((l.intensity(l.nadir) - l.tilt_factor * at_nadir).abs() < 1e-9 * at_nadir);
    }
}

#[test]
fn scene_error_luminaire_unknown_channel_file_and_photometry() {
    let extra = lamp("").replace("channel = \"c\"\n", "channel = \"d\"\n");
    let m = error(&extra);
    assert_names(
        &m,
        &[
            "luminaire `lamp`.channel",
            "unknown channel `d`",
            &format!(":{}:", line_of(&extra, "channel = \"d\"")),
        ],
    );

    let extra = lamp("").replace("isotropic.ies", "absent.ies");
    assert_names(
        &error(&extra),
        &["luminaire `lamp`.file", "not found", "absent.ies"],
    );

    // The reader's error keeps the photometric file and its line.
    let dir = scratch("bad-photometry");
    let bad = dir.join("bad.ies");
    std::fs::write(&bad, "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 x 1 1 2 0 0 0\n").unwrap();
    let extra = lamp("").replace(&testdata("isotropic.ies"), &bad.display().to_string());
    let m = error(&extra);
    assert_names(&m, &["luminaire `lamp`.file", "bad.ies:3"]);
}

#[test]
fn scene_error_luminaire_values() {
    for (fields, parts) in [
        (
            "maintenance_factor = 1.5\n",
            &["luminaire `lamp`.maintenance_factor", "(0, 1]"][..],
        ),
        (
            "maintenance_factor = 0\n",
            &["maintenance_factor", "found 0"][..],
        ),
        (
            "aim = [0, 0, 0]\n",
            &["luminaire `lamp`.aim", "non-zero"][..],
        ),
        (
            "array = { rows = 0, columns = 2, spacing = [1, 1] }\n",
            &["luminaire `lamp`.array", "at least 1"][..],
        ),
        (
            "array = { rows = 2, columns = 2, spacing = [1] }\n",
            &["luminaire `lamp`.array", "two lengths"][..],
        ),
        (
            "array = { rows = 2, columns = 2, spacing = [1, -1] }\n",
            &["luminaire `lamp`.array", "positive"][..],
        ),
        ("spinn = 3\n", &["unknown field `spinn`"][..]),
    ] {
        let extra = lamp(fields);
        let m = error(&extra);
        assert_names(&m, parts);
        assert!(
            m.contains(&format!(":{}:", line_of(&extra, fields.trim_end()))),
            "{m}"
        );
    }
    // Two elements of the same name.
    let twice = format!(
        "{}{}",
        lamp(""),
        lamp("")
            .split("[[luminaire]]")
            .nth(1)
            .map(|l| format!("[[luminaire]]{l}"))
            .unwrap()
    );
    assert_names(&error(&twice), &["duplicate luminaire name `lamp`"]);
}

#[test]
fn scene_error_luminaire_channels() {
    // A channel of luminaires only is fine; one driving nothing is not.
    parse(&format!("{BASE}{}", lamp("")), Path::new(FILE)).unwrap_or_else(|e| panic!("{e}"));
    let extra = format!("{}\n[[channel]]\nname = \"idle\"\n", lamp(""));
    assert_names(
        &error(&extra),
        &["channel `idle`", "names no surface", "[[luminaire]]"],
    );
    // Luminaires only: a flux or exitance would have nothing to spread over.
    let extra = lamp("").replace("name = \"c\"\n", "name = \"c\"\nflux = 100\n");
    assert_names(
        &error(&extra),
        &[
            "channel `c`",
            "names no surface",
            &format!(":{}:", line_of(&extra, "flux = 100")),
        ],
    );
    // Photometry is in candela: RGB scenes are refused.
    let rgb = BASE.replace("photopic", "rgb");
    let m = error_in(&format!("{rgb}{}", lamp("")));
    assert_names(&m, &["luminaire `lamp`", "photopic"]);
}
