//! `eigenrad verify` on a tiny room: the report's structure, and its split (and seed) error at
//! p = n is rounding (docs/math.md: "Any truncation p = n reproduces the dense solve to rounding").

use eigenrad::precompute::cli;
use eigenrad::precompute::verify::{self, CaseKind, Metric, VerifyOptions};

/// f64 expansion with every mode against an f64 LU solve, ~100 patches: 1e-9 relative leaves
/// room for the conditioning of `(I − R F)` at ρ ≤ 0.8 (the dense end-to-end test uses the
/// same figure).
const FULL_BASIS: f64 = 1e-9;

const SCENE: &str = r#"
[scene]
name = "tiny"
bands = "photopic"
unit = "m"
max_edge = 0.9

[materials]
floor = { reflectance = 0.3 }
ceiling = { reflectance = 0.8 }
walls = { reflectance = 0.6 }
desk = { reflectance = 0.4 }
lamp = { reflectance = 0.0 }

[[room]]
name = "room"
min = [0, 0, 0]
max = [3, 2, 2.5]
material = "walls"
floor = "floor"
ceiling = "ceiling"

[[block]]
name = "desk"
min = [0.8, 0.6, 0]
max = [2.0, 1.4, 0.7]
material = "desk"
bottom = false

[[quad]]
name = "lamp"
material = "lamp"
corners = [[1.2, 0.7, 2.45], [1.2, 1.3, 2.45], [1.8, 1.3, 2.45], [1.8, 0.7, 2.45]]

[[quad]]
name = "panel"
material = "walls"
corners = [[0.01, 0.5, 1.0], [0.01, 1.5, 1.0], [0.01, 1.5, 2.0], [0.01, 0.5, 2.0]]

[[channel]]
name = "lamp"
surfaces = ["lamp"]
flux = 3000

[[channel]]
name = "panel"
surfaces = ["panel"]
exitance = 200

[[sensor]]
name = "desk"
position = [1.4, 1.0, 0.7]
normal = [0, 0, 1]

[[zone]]
name = "work_plane"
work_plane = { room = "room", height = 0.8, margin = 0.3, max_edge = 0.8 }

[[zone]]
name = "floor"
surfaces = ["room.floor"]
"#;

#[test]
fn verify_reports_every_case_and_is_exact_with_every_mode() {
    let dir = std::env::temp_dir().join(format!("eigenrad-val-{}-verify", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tiny.toml");
    std::fs::write(&path, SCENE).unwrap();

    let opts = VerifyOptions {
        random_mixes: 2,
        random_patterns: 2,
        ..VerifyOptions::default()
    };
    let r = verify::verify(&path, &opts).unwrap();
    let n = r.patches;
    assert!(n > 40, "{n} patches");
    assert_eq!(r.channels, ["lamp", "panel"]);
    assert_eq!(r.zones, ["work_plane", "floor"]);
    assert_eq!(r.sensors, ["desk"]);

    // The ladder is ascending and ends with every mode of the reflecting patches (the lamp is
    // black: n − its patches).
    let black = 1;
    assert!(r.modes.windows(2).all(|w| w[0] < w[1]));
    assert_eq!(r.modes[0], 1);
    assert_eq!(*r.modes.last().unwrap(), n - black);

    assert_eq!(r.formulations.len(), 2);
    assert_eq!(r.formulations[0].formulation, "split");
    assert_eq!(r.formulations[1].formulation, "seed");
    let last = r.modes.len() - 1;
    for f in &r.formulations {
        let kinds: Vec<CaseKind> = f.cases.iter().map(|c| c.kind).collect();
        assert_eq!(
            kinds,
            [
                CaseKind::Channel,
                CaseKind::Channel,
                CaseKind::ChannelMix,
                CaseKind::ChannelMix,
                CaseKind::EmitterPattern,
                CaseKind::EmitterPattern
            ]
        );
        assert_eq!(f.basis_bytes.len(), r.modes.len());
        assert!(
            f.basis_bytes.windows(2).all(|w| w[0] < w[1]),
            "bytes grow with p"
        );
        for c in &f.cases {
            assert_eq!(c.patches.len(), r.modes.len());
            assert_eq!(c.zones.len(), 2);
            assert_eq!(c.sensors.len(), 1);
            let worst_at_n = c
                .patches
                .get(last)
                .into_iter()
                .chain(c.zones.iter().map(|z| &z[last]))
                .chain(c.sensors.iter().map(|s| &s[last]))
                .fold(0.0f64, |a, &b| a.max(b));
            assert!(
                worst_at_n <= FULL_BASIS,
                "{} {}: error {worst_at_n:e} at p = n",
                f.formulation,
                c.case
            );
        }
    }
    // Channels are carried by their exact responses: exact at every p in both formulations.
    let split = &r.formulations[0];
    let seed = &r.formulations[1];
    for f in [split, seed] {
        for t in 0..r.modes.len() {
            for kind in [CaseKind::Channel, CaseKind::ChannelMix] {
                for metric in [Metric::Patches, Metric::Zones, Metric::Sensors] {
                    let e = f.worst(Some(kind), metric, t).unwrap();
                    assert!(
                        e <= FULL_BASIS,
                        "{} {kind:?} {metric:?} p = {}: {e:e}",
                        f.formulation,
                        r.modes[t]
                    );
                }
            }
        }
    }
    // Exitance set patch by patch goes through the modes. The split carries each patch's own
    // exitance exactly: with one mode it is already far better than the seed expansion
    // (docs/math.md, "Seed errata").
    let (s1, e1) = (
        split
            .worst(Some(CaseKind::EmitterPattern), Metric::Patches, 0)
            .unwrap(),
        seed.worst(Some(CaseKind::EmitterPattern), Metric::Patches, 0)
            .unwrap(),
    );
    println!("p = 1, emitter patterns, patches: split {s1:.2e}, seed {e1:.2e}");
    assert!(s1 > FULL_BASIS && s1 < e1);

    // Baseline: rounding for channel states, no figure for patterns.
    let base = r.baseline.channel_error.unwrap();
    assert!(base.iter().all(|&e| e <= 1e-12), "{base:?}");
    assert_eq!(r.baseline.bytes, 4 * (n + 3) * 2);

    // The tables.
    let md = verify::markdown(&r);
    println!("{md}");
    for heading in [
        "# Accuracy of the eigenbasis: tiny",
        "## Smallest p within 1 %, every case",
        "## `split`: worst relative error by case kind",
        "## `seed`: worst relative error by case kind",
        "## Each zone and sensor, worst over every case",
        "## Baseline: exact per-channel superposition",
    ] {
        assert!(md.contains(heading), "missing {heading}");
    }
    assert!(md.contains("| zone `work_plane` |"));
    assert!(md.contains(
        "| emitter pattern | not representable | not representable | not representable |"
    ));
    // One row per tested p in each formulation's table (plus the per-output table).
    for p in &r.modes {
        let rows = md
            .lines()
            .filter(|l| l.starts_with(&format!("| {p} |")))
            .count();
        assert_eq!(rows, 3, "rows for p = {p}");
    }
    let ps = r.zone_p("work_plane", 0.01);
    assert_eq!(ps.len(), 2);
    assert!(ps.iter().all(|(_, p)| p.is_some_and(|p| p <= n)));

    // The curves.
    let files = cli::write_svgs(&r, &dir).unwrap();
    assert_eq!(files.len(), 3);
    for f in &files {
        let svg = std::fs::read_to_string(f).unwrap();
        assert!(svg.starts_with("<svg"), "{}", f.display());
        assert!(svg.contains("split, channel alone") && svg.contains("seed, emitter pattern"));
    }
    std::fs::remove_dir_all(&dir).ok();
}
