//! Form factors against closed forms (Howell's catalogue) and the shared reference data.

use super::*;
use crate::geometry::Polygon;
use std::f64::consts::PI;

fn v(x: f64, y: f64, z: f64) -> Vec3 {
    Vec3::new(x, y, z)
}

/// Quads tiling the parallelogram `origin + s e1 + t e2`, `n1 × n2` of them, facing `e1 × e2`.
fn grid(origin: Vec3, e1: Vec3, e2: Vec3, n1: usize, n2: usize, surface: usize) -> Vec<Patch> {
    let (d1, d2) = (e1 / n1 as f64, e2 / n2 as f64);
    let mut out = Vec::with_capacity(n1 * n2);
    for a in 0..n1 {
        for b in 0..n2 {
            let p = origin + d1 * a as f64 + d2 * b as f64;
            out.push(Patch::new(
                Polygon::new(vec![p, p + d1, p + d1 + d2, p + d2]),
                surface,
            ));
        }
    }
    out
}

/// The six faces of the box `lo..hi` cut into patches about `size` metres wide, facing inwards
/// (a room) or outwards (a blocker).
fn meshed_box(lo: Vec3, hi: Vec3, size: f64, inward: bool, surface: usize) -> Vec<Patch> {
    let d = hi - lo;
    let cuts = |len: f64| ((len / size).round() as usize).max(1);
    let (ex, ey, ez) = (v(d.x, 0.0, 0.0), v(0.0, d.y, 0.0), v(0.0, 0.0, d.z));
    let (nx, ny, nz) = (cuts(d.x), cuts(d.y), cuts(d.z));
    // (origin, e1, e2, n1, n2) with e1 × e2 pointing into the box.
    let faces = [
        (lo, ex, ey, nx, ny),
        (lo + ez, ey, ex, ny, nx),
        (lo, ey, ez, ny, nz),
        (lo + ex, ez, ey, nz, ny),
        (lo, ez, ex, nz, nx),
        (lo + ey, ex, ez, nx, nz),
    ];
    let mut out = Vec::new();
    for (k, &(o, e1, e2, n1, n2)) in faces.iter().enumerate() {
        if inward {
            out.extend(grid(o, e1, e2, n1, n2, surface + k));
        } else {
            out.extend(grid(o, e2, e1, n2, n1, surface + k));
        }
    }
    out
}

fn unit_square_facing(z: f64, up: bool) -> Patch {
    if up {
        grid(v(0.0, 0.0, z), v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0), 1, 1, 0).remove(0)
    } else {
        grid(v(0.0, 0.0, z), v(0.0, 1.0, 0.0), v(1.0, 0.0, 0.0), 1, 1, 0).remove(0)
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn opposed_unit_squares_match_howell_c11() {
    // Reference: Howell C-11, two opposed unit squares one unit apart, F = 0.199825.
    // Tolerance 0.05% relative.
    let patches = [
        unit_square_facing(0.0, true),
        unit_square_facing(1.0, false),
    ];
    let ff = patch_form_factors(&patches, &FormFactorOptions::default());
    let f = ff.matrix[(0, 1)];
    println!("C-11: F = {f:.7}, rel. error {:.2e}", rel(f, 0.199825));
    assert!(rel(f, 0.199825) < 5e-4);
    assert!(rel(ff.matrix[(1, 0)], 0.199825) < 5e-4);
}

#[test]
fn perpendicular_unit_squares_sharing_an_edge_match_howell_c14() {
    // Reference: Howell C-14, two unit squares at 90° with a common edge, F = 0.200044.
    // Tolerance 0.05% relative.
    let floor = unit_square_facing(0.0, true);
    // Wall x = 0, facing +x.
    let wall = grid(
        v(0.0, 0.0, 0.0),
        v(0.0, 1.0, 0.0),
        v(0.0, 0.0, 1.0),
        1,
        1,
        1,
    )
    .remove(0);
    let ff = patch_form_factors(&[floor, wall], &FormFactorOptions::default());
    for f in [ff.matrix[(0, 1)], ff.matrix[(1, 0)]] {
        println!("C-14: F = {f:.7}, rel. error {:.2e}", rel(f, 0.200044));
        assert!(rel(f, 0.200044) < 5e-4);
    }
}

fn reference_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/reference")
}

/// Patches from a reference `_patches.csv` (id, surface, then four corners x, y, z).
fn load_patches(name: &str) -> Vec<Patch> {
    let path = reference_dir().join(name);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let mut surfaces: Vec<String> = Vec::new();
    let mut out = Vec::new();
    for (line_no, line) in text.lines().enumerate().skip(1) {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        assert_eq!(
            fields.len(),
            14,
            "{}:{}: expected 14 fields",
            path.display(),
            line_no + 1
        );
        let surface = match surfaces.iter().position(|s| s == fields[1]) {
            Some(k) => k,
            None => {
                surfaces.push(fields[1].to_string());
                surfaces.len() - 1
            }
        };
        let num = |k: usize| -> f64 {
            fields[k].parse().unwrap_or_else(|e| {
                panic!(
                    "{}:{}: bad number {:?}: {e}",
                    path.display(),
                    line_no + 1,
                    fields[k]
                )
            })
        };
        let corners = (0..4)
            .map(|c| v(num(2 + 3 * c), num(3 + 3 * c), num(4 + 3 * c)))
            .collect();
        out.push(Patch::new(Polygon::new(corners), surface));
    }
    out
}

/// A dense matrix from a reference CSV of numbers.
fn load_matrix(name: &str) -> Vec<Vec<f64>> {
    let path = reference_dir().join(name);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            l.split(',')
                .map(|x| {
                    x.trim()
                        .parse()
                        .unwrap_or_else(|e| panic!("{}: {x:?}: {e}", path.display()))
                })
                .collect()
        })
        .collect()
}

fn check_cube(k: usize) {
    // Reference: data/reference/cube{k}x{k}_formfactors.csv (pyviewfactor, exact contour
    // integral). Tolerance: |diff| ≤ 1e-4 · max(F_ref, 1e-3) per entry; raw reciprocity
    // mismatch below 1e-5.
    let patches = load_patches(&format!("cube{k}x{k}_patches.csv"));
    let reference = load_matrix(&format!("cube{k}x{k}_formfactors.csv"));
    let n = patches.len();
    assert_eq!(reference.len(), n);
    let ff = patch_form_factors(&patches, &FormFactorOptions::default());
    let mut worst = (0.0_f64, 0, 0);
    for (i, row) in reference.iter().enumerate() {
        assert_eq!(row.len(), n);
        for (j, &f_ref) in row.iter().enumerate() {
            let err = (ff.matrix[(i, j)] - f_ref).abs() / f_ref.max(1e-3);
            if err > worst.0 {
                worst = (err, i, j);
            }
        }
    }
    let worst_row = ff
        .row_sums
        .iter()
        .map(|s| (s - 1.0).abs())
        .fold(0.0, f64::max);
    println!(
        "cube {k}x{k}: worst rel. error {:.2e} at ({}, {}), reciprocity mismatch {:.2e}, \
         worst row-sum deviation {worst_row:.2e}",
        worst.0, worst.1, worst.2, ff.reciprocity_mismatch
    );
    assert!(worst.0 <= 1e-4);
    assert!(ff.reciprocity_mismatch < 1e-5);
}

#[test]
fn cube_2x2_matches_reference() {
    check_cube(2);
}

#[test]
fn cube_3x3_matches_reference() {
    check_cube(3);
}
