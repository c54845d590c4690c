//! The open-plan floor of `examples/scaling/` meshes to the patch counts its variants are
//! named for (docs/performance.md, "Scenes at scale"), with every desk, tower, window,
//! luminaire and output it declares: the benchmark's sizes are what they say.

use std::path::Path;

use eigenrad_precompute::scene;

/// How far a variant's patch count may fall from its name: the names round to 10k, 20k, 50k,
/// 100k and `max_edge` is given to two or three digits.
const COUNT_TOLERANCE: f64 = 0.05;

#[test]
fn open_plan_variants_mesh_to_their_named_sizes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scaling");
    for (variant, named) in [("10k", 1e4), ("20k", 2e4), ("50k", 5e4), ("100k", 1e5)] {
        let path = root.join(format!("open-plan-{variant}.toml"));
        let s = scene::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let n = s.patches.len() as f64;
        assert!(
            (n - named).abs() <= COUNT_TOLERANCE * named,
            "{variant}: {n} patches"
        );
        // 48 desks and 3 towers, a room, 4 windows; 24 luminaires in 5 channels.
        assert_eq!(s.luminaires.len(), 24, "{variant}");
        assert_eq!(s.channels.len(), 5, "{variant}");
        assert_eq!(s.sensors.len(), 2, "{variant}");
        assert_eq!(s.zones.len(), 1, "{variant}");
        let desks = s
            .surfaces
            .iter()
            .filter(|f| f.name.starts_with("desk_") && f.name.ends_with(".top"))
            .count();
        assert_eq!(desks, 48, "{variant}");
    }
}
