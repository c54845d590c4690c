//! The readers never panic: on arbitrary bytes, and on the shipped models with bytes
//! changed, cut or repeated, reading a model and laying out its spaces returns a model or an
//! error.

use proptest::prelude::*;

use super::{gbxml, hbjson, prism};

fn sample(path: &str) -> Vec<u8> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/import");
    std::fs::read(root.join(path)).unwrap()
}

/// Reads `bytes` as either format and lays out every space read; whatever happens, no panic.
fn read_all(bytes: &[u8]) {
    let text = String::from_utf8_lossy(bytes);
    for model in [hbjson::read(&text), gbxml::read(&text)]
        .into_iter()
        .flatten()
    {
        for space in &model.spaces {
            let _ = prism::prism(space, model.tolerance);
        }
    }
}

/// `base` with `edits` applied: (position, byte) overwrites, then a cut at `cut` (a share of
/// the length).
fn mutated(base: &[u8], edits: &[(usize, u8)], cut: Option<f64>) -> Vec<u8> {
    let mut out = base.to_vec();
    for &(at, byte) in edits {
        let k = at % out.len();
        out[k] = byte;
    }
    if let Some(c) = cut {
        out.truncate((c * out.len() as f64) as usize);
    }
    out
}

#[test]
fn the_shipped_models_read_and_lay_out() {
    for (file, spaces) in [
        ("l-office.hbjson", 1),
        ("l-office.xml", 1),
        ("honeybee/model_complete_multiroom_radiance.hbjson", 3),
        ("honeybee/model_radiance_grid_views.hbjson", 2),
        ("openstudio/3997_WindowScaling_bug.xml", 1),
    ] {
        let text = String::from_utf8(sample(file)).unwrap();
        let model = if file.ends_with(".xml") {
            gbxml::read(&text)
        } else {
            hbjson::read(&text)
        }
        .unwrap_or_else(|e| panic!("{file}: {e:?}"));
        assert_eq!(model.spaces.len(), spaces, "{file}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
        read_all(&bytes);
    }

    #[test]
    fn a_changed_hbjson_never_panics(
        edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 0..8),
        cut in proptest::option::of(0.0..1.0f64),
    ) {
        read_all(&mutated(&sample("l-office.hbjson"), &edits, cut));
    }

    /// The sample with sensor grids: most of its bytes are sensors.
    #[test]
    fn a_changed_model_with_grids_never_panics(
        edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 0..8),
        cut in proptest::option::of(0.0..1.0f64),
    ) {
        read_all(&mutated(&sample("honeybee/model_radiance_grid_views.hbjson"), &edits, cut));
    }

    #[test]
    fn a_changed_gbxml_never_panics(
        edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 0..8),
        cut in proptest::option::of(0.0..1.0f64),
    ) {
        read_all(&mutated(&sample("l-office.xml"), &edits, cut));
    }

    /// Digits changed, so that the files stay well formed and the geometry goes wrong.
    #[test]
    fn changed_coordinates_never_panic(
        edits in proptest::collection::vec((any::<usize>(), 0u8..10), 1..12),
    ) {
        for file in ["l-office.hbjson", "l-office.xml", "honeybee/model_radiance_grid_views.hbjson"] {
            let base = sample(file);
            let digits: Vec<usize> = (0..base.len()).filter(|&k| base[k].is_ascii_digit()).collect();
            let edits: Vec<(usize, u8)> = edits
                .iter()
                .map(|&(at, d)| (digits[at % digits.len()], b'0' + d))
                .collect();
            read_all(&mutated(&base, &edits, None));
        }
    }
}
