//! The keys that name entries: SHA-256 over everything an entry's values depend on.

use sha2::{Digest, Sha256};

use super::entry::ENTRY_VERSION;
use crate::formfactor::{self, hierarchical, outputs, FormFactorOptions};
use crate::geometry::{Face, Patch, Vec3};
use crate::scene::{Scene, ZoneKind};

fn hash_point(h: &mut Sha256, p: &Vec3) {
    for c in [p.x, p.y, p.z] {
        h.update(c.to_bits().to_le_bytes());
    }
}

fn hash_usize(h: &mut Sha256, x: usize) {
    h.update((x as u64).to_le_bytes());
}

fn hash_patches(h: &mut Sha256, patches: &[Patch]) {
    hash_usize(h, patches.len());
    for p in patches {
        hash_usize(h, p.polygon.vertices.len());
        for v in &p.polygon.vertices {
            hash_point(h, v);
        }
        hash_point(h, &p.normal);
        hash_point(h, &p.centroid);
        h.update(p.area.to_bits().to_le_bytes());
        hash_usize(h, p.surface);
    }
}

/// The key of the form factors of `patches` (with occluders from `faces`) under `opts`.
pub fn key(patches: &[Patch], faces: &[Face], opts: &FormFactorOptions) -> [u8; 32] {
    // Every field named, so that a new option cannot be forgotten here.
    let FormFactorOptions {
        gauss_order,
        progress: _,
        cache: _,
        touching_order,
        quadrature_tolerance,
        visibility_depth,
        visibility_cell_share,
        occluded_order,
        visibility,
        // In the hierarchical key, as `Settings::shade_misfit`: no pair integral reads it.
        cluster_misfit: _,
        operator: _,
    } = opts;
    let mut h = Sha256::new();
    h.update(b"eigenrad patch form factors\0");
    h.update(env!("CARGO_PKG_VERSION").as_bytes());
    h.update([0]);
    h.update(formfactor::ALGORITHM_VERSION.to_le_bytes());
    h.update(ENTRY_VERSION.to_le_bytes());
    for x in [*gauss_order, *touching_order, *occluded_order] {
        hash_usize(&mut h, x);
    }
    h.update(u64::from(*visibility_depth).to_le_bytes());
    h.update(quadrature_tolerance.to_bits().to_le_bytes());
    h.update(visibility_cell_share.to_bits().to_le_bytes());
    // Hashed only when sampled, so that the keys of exact form factors are unchanged.
    if let formfactor::Visibility::Sampled { per_side } = visibility {
        h.update(b"sampled visibility\0");
        h.update(per_side.to_le_bytes());
    }
    hash_patches(&mut h, patches);
    hash_usize(&mut h, faces.len());
    for f in faces {
        hash_usize(&mut h, f.patches.start);
        hash_usize(&mut h, f.patches.end);
        hash_usize(&mut h, f.polygon.vertices.len());
        for v in &f.polygon.vertices {
            hash_point(&mut h, v);
        }
    }
    h.finalize().into()
}

/// The key of the hierarchical operator of `patches` (with occluders from `faces`) under
/// `opts` and `settings`: the patch form factors' key and every setting of the compression.
pub fn hierarchical_key(
    patches: &[Patch],
    faces: &[Face],
    opts: &FormFactorOptions,
    settings: &hierarchical::Settings,
) -> [u8; 32] {
    // Every field named, so that a new setting cannot be forgotten here.
    let hierarchical::Settings {
        leaf,
        admissibility,
        tolerance,
        split_by_sight,
        shade_mixed,
        shade_misfit,
    } = settings;
    let mut h = Sha256::new();
    h.update(b"eigenrad hierarchical form factors\0");
    h.update(key(patches, faces, opts));
    hash_usize(&mut h, *leaf);
    h.update(admissibility.to_bits().to_le_bytes());
    h.update(tolerance.to_bits().to_le_bytes());
    h.update([u8::from(*split_by_sight)]);
    h.update([u8::from(*shade_mixed)]);
    h.update(shade_misfit.to_bits().to_le_bytes());
    hash_usize(&mut h, hierarchical::ASSEMBLY_VERSION);
    h.finalize().into()
}

/// The key of the output rows of `scene` under `opts`: the patch form factors' key, every
/// sensor, every zone and every zone's calculation-grid points.
pub fn rows_key(scene: &Scene, opts: &FormFactorOptions) -> [u8; 32] {
    let mut h = Sha256::new();
    h.update(b"eigenrad sensor and zone rows\0");
    h.update(key(&scene.patches, &scene.faces, opts));
    hash_usize(&mut h, scene.sensors.len());
    for s in &scene.sensors {
        hash_point(&mut h, &s.position);
        hash_point(&mut h, &s.normal);
        match s.half_angle {
            None => h.update([0]),
            Some(a) => {
                h.update([1]);
                h.update(a.to_bits().to_le_bytes());
            }
        }
        // Hashed only when present, so that the keys of sensors without one are unchanged.
        if let Some(r) = &s.response {
            h.update(b"response\0");
            for (theta, sensitivity) in r.rows() {
                h.update(theta.to_bits().to_le_bytes());
                h.update(sensitivity.to_bits().to_le_bytes());
            }
        }
    }
    hash_usize(&mut h, scene.zones.len());
    for z in &scene.zones {
        match &z.kind {
            ZoneKind::Surfaces(patches) => {
                h.update([0]);
                hash_usize(&mut h, patches.len());
                for &p in patches {
                    hash_usize(&mut h, p);
                }
            }
            ZoneKind::WorkPlane { height, receivers } => {
                h.update([1]);
                h.update(height.to_bits().to_le_bytes());
                hash_patches(&mut h, receivers);
            }
            ZoneKind::Points { points, area } => {
                h.update([2]);
                h.update(area.to_bits().to_le_bytes());
                hash_usize(&mut h, points.len());
                for (position, normal) in points {
                    hash_point(&mut h, position);
                    hash_point(&mut h, normal);
                }
            }
        }
    }
    hash_usize(&mut h, outputs::grid_points(scene).count());
    for (zone, position, normal) in outputs::grid_points(scene) {
        hash_usize(&mut h, zone);
        hash_point(&mut h, &position);
        hash_point(&mut h, &normal);
    }
    h.finalize().into()
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use super::super::fixtures::{pair, scratch, square};
    use super::*;

    #[test]
    fn the_key_changes_with_the_geometry_and_the_settings_but_not_with_progress() {
        let patches = pair();
        let base = FormFactorOptions::default();
        let k = key(&patches, &[], &base);
        let mut moved = pair();
        moved[1] = square(0.0, 1.5, false);
        assert_ne!(k, key(&moved, &[], &base));
        let finer = FormFactorOptions {
            gauss_order: 6,
            ..FormFactorOptions::default()
        };
        assert_ne!(k, key(&patches, &[], &finer));
        let tolerance = FormFactorOptions {
            quadrature_tolerance: 1e-7,
            ..FormFactorOptions::default()
        };
        assert_ne!(k, key(&patches, &[], &tolerance));
        let shown = FormFactorOptions {
            progress: true,
            cache: Some(PathBuf::from("/elsewhere")),
            ..FormFactorOptions::default()
        };
        assert_eq!(k, key(&patches, &[], &shown));
    }

    #[test]
    fn the_rows_key_follows_the_sensors_and_zones_and_the_patch_key_does_not() {
        let dir = scratch("rows-key");
        std::fs::create_dir_all(&dir).unwrap();
        let text = |x: f64, margin: f64| {
            format!(
                "[scene]\nname = \"box\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 1\n\n\
                 [materials]\nwall = {{ reflectance = 0.5 }}\n\n\
                 [[room]]\nname = \"room\"\nmin = [0, 0, 0]\nmax = [2, 2, 2]\nmaterial = \"wall\"\n\n\
                 [[sensor]]\nname = \"s\"\nposition = [{x}, 1, 0.5]\nnormal = [0, 0, 1]\n\n\
                 [[zone]]\nname = \"wp\"\nwork_plane = {{ height = 0.8, margin = {margin} }}\n"
            )
        };
        let load = |name: &str, body: String| {
            let path = dir.join(name);
            std::fs::write(&path, body).unwrap();
            crate::scene::load(&path).unwrap()
        };
        let opts = FormFactorOptions::default();
        let base = load("a.toml", text(1.0, 0.2));
        let moved = load("b.toml", text(1.5, 0.2));
        let narrower = load("c.toml", text(1.0, 0.3));
        let same = load("d.toml", text(1.0, 0.2));
        let patches = |s: &Scene| key(&s.patches, &s.faces, &opts);
        assert_eq!(patches(&base), patches(&moved));
        assert_eq!(patches(&base), patches(&narrower));
        assert_ne!(rows_key(&base, &opts), rows_key(&moved, &opts));
        assert_ne!(rows_key(&base, &opts), rows_key(&narrower, &opts));
        assert_eq!(rows_key(&base, &opts), rows_key(&same, &opts));
        std::fs::remove_dir_all(&dir).ok();
    }
}
