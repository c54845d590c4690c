//! The hierarchical operator against the dense matrix of the same pair integrals, closed-room
//! identities, and the guard on a block built to fool the cross approximation.

use std::sync::Arc;

use faer::{Mat, Par};

use super::aca;
use super::tree::{self, ClusterTree, Kind, Seeing};
use super::*;
use crate::formfactor::tests::{meshed_box, v};
use crate::formfactor::{
    exchange, patch_form_factors_hierarchical, patch_form_factors_with, FormFactorOptions,
    Occluders, Solid,
};
use crate::geometry::Aabb;
use crate::radiosity::exact::ExactSolver;

/// A long 16 × 3 × 2.7 m room (inward: an open-plan strip, where far clusters abound) with a
/// desk (a box floating at desk height) and a column from floor to ceiling, about `size`
/// metres a patch.
fn furnished_room(size: f64) -> Vec<Patch> {
    let mut patches = meshed_box(v(0.0, 0.0, 0.0), v(16.0, 3.0, 2.7), size, true, 0);
    for (k, solid) in furnished_solids().iter().enumerate() {
        let b = solid.bounds;
        patches.extend(meshed_box(b.min, b.max, size, false, 6 + 6 * k));
    }
    patches
}

/// The desk and the column of [`furnished_room`] as solids: all six faces of each are
/// patches.
fn furnished_solids() -> Vec<Solid> {
    [
        (v(5.0, 1.0, 0.7), v(6.6, 1.8, 0.75)),
        (v(10.0, 2.0, 0.0), v(10.4, 2.4, 2.7)),
    ]
    .map(closed)
    .to_vec()
}

/// A box all of whose faces are patches.
fn closed((min, max): (Vec3, Vec3)) -> Solid {
    Solid {
        bounds: Aabb { min, max },
        open_below: false,
        open_above: false,
    }
}

/// Small leaves, so that a room of a few hundred patches has well-separated blocks.
fn small_leaves() -> Settings {
    Settings {
        leaf: 16,
        ..Settings::default()
    }
}

fn relative_max(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |s, x| s.max(x.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / scale
}

/// Reference: the dense exchange areas `G` from the same pair integrals
/// (`patch_form_factors_with`). The blocks are approximated to 1e-4 here, so that blocks
/// between leaves of 16 patches compress (at the default 1e-6 only larger blocks do, which
/// takes a larger scene: `eigenrad-bench compress`). Tolerances, from that 1e-4: products,
/// row sums and every entry (against the largest) within 1e-4 relative; exact symmetry;
/// products the same bytes whatever the threads.
#[test]
fn compressed_matches_dense_in_a_furnished_room() {
    let patches = furnished_room(0.45);
    assert!(patches.len() > 500, "{} patches", patches.len());
    compressed_matches_dense(&patches, &furnished_solids(), 0.1);
}

/// An open-plan floor in small: a 12 × 6 × 2.7 m room with six desks in two rows and two
/// columns from floor to ceiling, about `size` metres a patch (0.9 in most tests), so that
/// most pairs have several blockers between them (as on `examples/scaling/open-plan-*.toml`).
/// Its desks and columns are closed boxes, returned as solids too.
pub(in crate::formfactor) fn open_plan_in_small(size: f64) -> (Vec<Patch>, Vec<Solid>) {
    let mut patches = meshed_box(v(0.0, 0.0, 0.0), v(12.0, 6.0, 2.7), size, true, 0);
    let mut solids = Vec::new();
    for row in 0..2 {
        for desk in 0..3 {
            let (x, y) = (1.5 + 3.5 * desk as f64, 1.2 + 2.8 * row as f64);
            solids.push(closed((v(x, y, 0.7), v(x + 1.6, y + 0.8, 0.75))));
        }
    }
    solids.push(closed((v(4.0, 2.8, 0.0), v(4.4, 3.2, 2.7))));
    solids.push(closed((v(8.0, 2.8, 0.0), v(8.4, 3.2, 2.7))));
    for (k, solid) in solids.iter().enumerate() {
        let b = solid.bounds;
        patches.extend(meshed_box(b.min, b.max, size, false, 6 + 6 * k));
    }
    (patches, solids)
}

/// The same comparison with many blockers (`open_plan_in_small`). Occlusion leaves few far
/// blocks of low rank there (under 1 % of the entries: most run out of rank and are computed
/// whole, docs/performance.md, "Why the floor's form factors are slow"), so this checks the
/// fallbacks and the near blocks against the dense matrix rather than the compression.
#[test]
fn compressed_matches_dense_among_many_blockers() {
    let (patches, solids) = open_plan_in_small(0.9);
    compressed_matches_dense(&patches, &solids, 0.0);
}

/// Reference: the pair integrals themselves. On the furnished strip (`furnished_room`, a
/// desk and a column among far clusters, both solids), with the leaves of the tests, every
/// block the partition calls dark holds only pairs whose form factors, computed without the
/// solids, are 0 both ways (to [`HIDDEN_RESIDUE`]), and every block it calls clear only pairs
/// whose own shaft (the blockers that may cut them, with the pair's faces ignored as in the
/// pair integral) is clear: the classification never hides light or skips an occluded pair.
/// Every pair a solid hides is 0 in that reference too, and some of them no single face
/// hides. The split by sight must also read fewer entries than the partition by distance
/// alone.
#[test]
fn sight_of_blocks_agrees_with_their_pairs() {
    let patches = furnished_room(0.6);
    let n = patches.len();
    // The reference knows no solid: its hidden pairs are those the faces' shadows cover.
    let faces_only = Occluders::new(&patches);
    let dense = patch_form_factors_with(&patches, &faces_only, &FormFactorOptions::default());
    let occluders = faces_only.clone().with_solids(&furnished_solids());
    let half = 0.5e-9
        * patches
            .iter()
            .map(smallest_radius)
            .fold(f64::INFINITY, f64::min);
    let tree = ClusterTree::new(&patches, small_leaves().leaf, half);
    let clear =
        |a: &[Vec3], na: Vec3, b: &[Vec3], nb: Vec3| occluders.shaft(a, na, b, nb, &[]).is_clear();
    let by_face = |a: &[Vec3], b: &[Vec3]| occluders.one_blocker_hides(a, b);
    let by_solid =
        |a: &[Vec3], b: &[Vec3]| occluders.one_blocker_hides(a, b) || occluders.solid_hides(a, b);
    let dark_pairs = |hidden: &(dyn Fn(&[Vec3], &[Vec3]) -> bool + Sync)| {
        let seeing = Seeing {
            clear: &clear,
            hidden,
            dark_tolerance: half,
        };
        let spans = tree::partition(&tree, &small_leaves(), Some(&seeing));
        let dark: usize = spans
            .iter()
            .filter(|s| s.kind == Kind::Dark)
            .map(|s| s.rows.len() * s.cols.len())
            .sum();
        (spans, dark)
    };
    let (_, dark_by_faces) = dark_pairs(&by_face);
    let (spans, dark_by_solids) = dark_pairs(&by_solid);
    println!("pairs in dark blocks: {dark_by_faces} by single faces, {dark_by_solids} with solids");
    assert!(dark_by_solids >= dark_by_faces);
    let (mut dark, mut clear_far) = (0usize, 0usize);
    for span in &spans {
        let pairs = span
            .rows
            .clone()
            .flat_map(|a| span.cols.clone().map(move |b| (a, b)));
        for (a, b) in pairs {
            let (i, j) = (tree.order[a], tree.order[b]);
            match span.kind {
                Kind::Dark => {
                    let (f, g) = (dense.matrix[(i, j)], dense.matrix[(j, i)]);
                    assert!(
                        f.abs().max(g.abs()) <= HIDDEN_RESIDUE,
                        "dark block, pair ({i}, {j}): {f:e}, {g:e}"
                    );
                    dark += 1;
                }
                Kind::Clear => {
                    let (p, q) = (&patches[i], &patches[j]);
                    let shaft = occluders.shaft(
                        &p.polygon.vertices,
                        p.normal,
                        &q.polygon.vertices,
                        q.normal,
                        &[i, j],
                    );
                    assert!(shaft.is_clear(), "clear block, occluded pair ({i}, {j})");
                    clear_far += 1;
                }
                // The tests' settings split mixed pairs: none is shaded.
                Kind::Near | Kind::Far | Kind::Shaded => {}
            }
        }
    }
    println!("{n} patches: {dark} pairs in dark blocks, {clear_far} in clear far blocks");
    assert!(dark > n * n / 100, "{dark}");
    assert!(clear_far > 0, "{clear_far}");
    // Pair by pair, as the pair integral asks: every pair a solid hides is dark both ways in
    // the reference, and some of them no single face hides.
    let (mut by_solids, mut only_by_solids) = (0usize, 0usize);
    for i in 0..n {
        for j in 0..n {
            let (a, b) = (&patches[i].polygon.vertices, &patches[j].polygon.vertices);
            if i == j || !occluders.solid_hides(a, b) {
                continue;
            }
            let f = dense.matrix[(i, j)];
            assert!(f.abs() <= HIDDEN_RESIDUE, "pair ({i}, {j}): {f:e}");
            by_solids += 1;
            only_by_solids += usize::from(!occluders.one_blocker_hides(a, b));
        }
    }
    println!("{by_solids} ordered pairs hidden by a solid, {only_by_solids} by no single face");
    assert!(only_by_solids > 0);
    // The operator built on this partition against the one by distance alone.
    let build = |split_by_sight| {
        let settings = Settings {
            tolerance: 1e-4,
            split_by_sight,
            ..small_leaves()
        };
        let ff = patch_form_factors_hierarchical(
            &patches,
            &occluders,
            &FormFactorOptions::default(),
            &settings,
        )
        .expect("finite");
        (ff.matrix.compression().clone(), ff.matrix.stored_bytes())
    };
    let ((by_sight, sight_bytes), (by_distance, distance_bytes)) = (build(true), build(false));
    println!("by sight {by_sight:?}, {sight_bytes} bytes");
    println!("by distance {by_distance:?}, {distance_bytes} bytes");
    assert!(by_sight.entries_read < by_distance.entries_read);
}

/// The most a pair integral without solids leaves of a pair that a solid hides whole
/// (dimensionless): the shadows of its faces cover the target to rounding, and a form factor
/// between patches of this room is at least 1e-6 where it is not 0.
const HIDDEN_RESIDUE: f64 = 1e-12;

/// The comparison of the hierarchical operator with the dense matrix on `patches`, with at
/// least `low_rank_share` of the entries in low-rank blocks. The operator knows the scene's
/// `solids`; the dense reference does not (its hidden pairs come from the faces' shadows).
fn compressed_matches_dense(patches: &[Patch], solids: &[Solid], low_rank_share: f64) {
    let n = patches.len();
    let occluders = Occluders::new(patches);
    let opts = FormFactorOptions::default();
    let area: Vec<f64> = patches.iter().map(|p| p.area).collect();
    let dense = exchange::exchange_areas(
        patch_form_factors_with(patches, &occluders, &opts).matrix,
        &area,
    );
    let occluders = occluders.with_solids(solids);
    let tolerance = 1e-4;
    let settings = Settings {
        tolerance,
        ..small_leaves()
    };
    let ff =
        patch_form_factors_hierarchical(patches, &occluders, &opts, &settings).expect("finite");
    let h = &ff.matrix;
    let c = h.compression();
    println!(
        "{n} patches: {c:?}, {} bytes against {}",
        h.stored_bytes(),
        4 * n * n
    );
    assert!(c.low_rank_share >= low_rank_share, "{c:?}");
    assert!(c.low_rank_blocks > 0, "{c:?}");
    if low_rank_share > 0.0 {
        assert!(c.max_rank > 0, "{c:?}");
    }
    assert!(c.row_error < tolerance, "{c:?}");
    let gmax = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .fold(0.0f64, |s, (i, j)| s.max(dense[(i, j)].abs()));
    let mut worst = 0.0f64;
    for i in 0..n {
        let mut row = vec![0.0; n];
        h.row(i, &mut row);
        for j in 0..n {
            assert_eq!(
                h.entry(i, j).to_bits(),
                h.entry(j, i).to_bits(),
                "({i}, {j})"
            );
            assert_eq!(row[j].to_bits(), h.entry(i, j).to_bits(), "row {i}, {j}");
            worst = worst.max((row[j] - dense[(i, j)]).abs() / gmax);
        }
    }
    println!("worst entry error {worst:.2e} of the largest entry");
    assert!(worst < tolerance, "{worst:e}");
    // 13 columns: one thread carries them in chunks of 8, 4 and 1, two threads 7 each as
    // 4, 1, 1, 1 (Block::product_by_rows), and one at a time column after column.
    const COLUMNS: usize = 13;
    let x = Mat::<f64>::from_fn(n, COLUMNS, |i, k| {
        (((i * 7 + k * 13) % 17) as f64 - 8.0) / 8.0
    });
    let (mut want, mut got) = (Mat::<f64>::zeros(n, COLUMNS), Mat::<f64>::zeros(n, COLUMNS));
    dense.apply(want.as_mut(), x.as_ref(), Par::Seq);
    h.apply(got.as_mut(), x.as_ref(), Par::rayon(2));
    for k in 0..COLUMNS {
        let w: Vec<f64> = (0..n).map(|i| want[(i, k)]).collect();
        let g: Vec<f64> = (0..n).map(|i| got[(i, k)]).collect();
        let e = relative_max(&g, &w);
        assert!(e < tolerance, "column {k}: {e:e}");
    }
    let dense_sums = dense.form_factor_row_sums(&area);
    let e = ff
        .row_sums
        .iter()
        .zip(&dense_sums)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(e < tolerance, "row sums {e:e}");
    // Products are the same bytes however many threads run them.
    let mut again = Mat::<f64>::zeros(n, COLUMNS);
    h.apply(again.as_mut(), x.as_ref(), Par::Seq);
    assert!((0..n).all(|i| (0..COLUMNS).all(|k| again[(i, k)].to_bits() == got[(i, k)].to_bits())));
    // And whichever columns are carried together.
    for k in 0..COLUMNS {
        let mut alone = Mat::<f64>::zeros(n, 1);
        h.apply(alone.as_mut(), x.as_ref().get(.., k..k + 1), Par::Seq);
        assert!((0..n).all(|i| alone[(i, 0)].to_bits() == got[(i, k)].to_bits()));
    }
}

/// Reference: the white furnace. In a closed room of uniform reflectance ρ, uniform emitted
/// exitance `e` gives `M = e / (1 − ρ)` everywhere (docs/math.md), and every row of F sums
/// to one. Tolerance 1e-5 relative: the dense form factors meet both to 1e-6, the
/// compression adds 1e-6 per block.
#[test]
fn white_furnace_through_the_compressed_operator() {
    let patches = meshed_box(v(0.0, 0.0, 0.0), v(5.0, 4.0, 3.0), 0.4, true, 0);
    let n = patches.len();
    let occluders = Occluders::new(&patches);
    let ff = patch_form_factors_hierarchical(
        &patches,
        &occluders,
        &FormFactorOptions::default(),
        &small_leaves(),
    )
    .expect("finite");
    let worst_row = ff
        .row_sums
        .iter()
        .map(|s| (s - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(worst_row < 1e-5, "{worst_row:e}");
    assert!(ff.matrix.compression().low_rank_blocks > 0);
    let area: Vec<f64> = patches.iter().map(|p| p.area).collect();
    let rho = vec![0.6; n];
    let g: Arc<dyn FormFactorOperator> = Arc::new(ff.matrix);
    let solver = ExactSolver::iterative(g, &area, &rho).expect("valid inputs");
    let e = 100.0;
    let m = solver.solve(&vec![e; n]);
    let want = e / (1.0 - 0.6);
    let worst = m
        .iter()
        .map(|x| (x - want).abs() / want)
        .fold(0.0, f64::max);
    assert!(worst < 1e-5, "{worst:e}");
}

/// A block that cross approximation alone gets wrong: a smooth part seen by every row and
/// column (here exactly of rank one), plus three rows that see three quarters of the columns
/// strongly (light through a gap between blockers). Once the smooth part is taken, every row
/// and column ACA probes next is dark, and it stops with an error of the order of the hidden
/// part; the guard, reading rows and columns of its own, sees it, and the block is computed
/// whole.
#[test]
fn guard_catches_what_cross_approximation_misses() {
    let (m, n) = (64, 64);
    let smooth = |i: usize, j: usize| 10.0 / ((10.0 + i as f64 * 0.01) * (10.0 + j as f64 * 0.02));
    let lit = |i: usize, j: usize| (61..64).contains(&i) && j >= 16;
    let entry = |i: usize, j: usize| smooth(i, j) + if lit(i, j) { 0.05 } else { 0.0 };
    let tolerance = 1e-6;
    let cross = aca::aca(m, n, &entry, tolerance, 32).expect("converges");
    let approx = &cross.approximation;
    let mut err2 = 0.0;
    let mut norm2 = 0.0;
    for i in 0..m {
        for j in 0..n {
            let e = entry(i, j);
            let a: f64 = (0..approx.rank())
                .map(|k| approx.u[(i, k)] * approx.v[(j, k)])
                .sum();
            err2 += (e - a).powi(2);
            norm2 += e * e;
        }
    }
    let alone = (err2 / norm2).sqrt();
    println!(
        "ACA alone: rank {}, relative error {alone:.2e}",
        approx.rank()
    );
    assert!(
        alone > 100.0 * tolerance,
        "ACA found the gap by itself: {alone:e}"
    );
    // Each of the guard's two columns lands among the lit ones with probability 3/4: over 16
    // seeds (assembly seeds a block with its index) it must fire for most.
    let fired = (0..16u64)
        .filter(|&seed| aca::guard_fires(&cross, m, n, &entry, tolerance, seed))
        .count();
    println!("guard fired for {fired} of 16 seeds");
    assert!(fired >= 12, "{fired}");
    // compress() computes such a block whole when its guard fires.
    let whole = (0..16u64)
        .filter(|&seed| {
            matches!(
                aca::compress(m, n, &entry, tolerance, seed),
                aca::Compressed::Dense { guarded: true, .. }
            )
        })
        .count();
    assert_eq!(whole, fired);
    // On a smooth block ACA gets right, the guard stays quiet.
    let curved = |i: usize, j: usize| 1.0 / (10.0 + i as f64 * 0.01 + j as f64 * 0.02);
    let good = aca::aca(m, n, &curved, tolerance, 32).expect("converges");
    assert!((0..16u64).all(|seed| !aca::guard_fires(&good, m, n, &curved, tolerance, seed)));
}

/// Recompression keeps the approximation within its tolerance and never raises the rank.
#[test]
fn recompression_keeps_the_block() {
    let (m, n) = (40, 30);
    let entry = |i: usize, j: usize| {
        let (x, y) = (i as f64 / 40.0, 3.0 + j as f64 / 30.0);
        1.0 / ((x - y) * (x - y) + 0.5)
    };
    let cross = aca::aca(m, n, &entry, 1e-10, 20).expect("converges");
    let before = cross.approximation.rank();
    let after = aca::recompress(cross.approximation.clone(), 1e-6);
    assert!(after.rank() <= before);
    let mut err2 = 0.0;
    let mut norm2 = 0.0;
    for i in 0..m {
        for j in 0..n {
            let a: f64 = (0..after.rank())
                .map(|k| after.u[(i, k)] * after.v[(j, k)])
                .sum();
            err2 += (entry(i, j) - a).powi(2);
            norm2 += entry(i, j).powi(2);
        }
    }
    assert!((err2 / norm2).sqrt() < 2e-6, "{:e}", (err2 / norm2).sqrt());
}

/// Reference: the dense matrix of the exact pair integrals on the open plan in small (six
/// desks and two columns among far clusters). With [`Settings::shade_mixed`] no pair of
/// clusters is split by sight: each well-separated pair a blocker may cut is one block, its
/// unoccluded entries times the clusters' visible fraction (read without shadows). The
/// approximation is of the visibility, not of the compression: its products and its row
/// sums are held to [`SHADED_PRODUCT`] and [`SHADED_ROW_SUM`] of the dense ones, and the same
/// blocks with no shading at all (every fraction 1) are at least twice as far off, so the
/// fractions do their work. With the blocks whose rays misfit their shares split
/// ([`Settings::shade_misfit`] at its default), both errors fall by at least a third.
#[test]
fn shaded_blocks_approximate_the_exact_visibility() {
    let (patches, solids) = open_plan_in_small(0.6);
    let n = patches.len();
    let occluders = Occluders::new(&patches);
    let opts = FormFactorOptions::default();
    let area: Vec<f64> = patches.iter().map(|p| p.area).collect();
    let dense = exchange::exchange_areas(
        patch_form_factors_with(&patches, &occluders, &opts).matrix,
        &area,
    );
    let occluders = occluders.with_solids(&solids);
    let split = Settings {
        tolerance: 1e-4,
        ..small_leaves()
    };
    let shaded = Settings {
        shade_mixed: true,
        shade_misfit: f64::INFINITY,
        ..split.clone()
    };
    let refined = Settings {
        shade_misfit: super::SHADE_MISFIT,
        ..shaded.clone()
    };
    let exact =
        patch_form_factors_hierarchical(&patches, &occluders, &opts, &split).expect("finite");
    let ff = patch_form_factors_hierarchical(&patches, &occluders, &opts, &shaded).expect("finite");
    let unshaded = crate::formfactor::tests::hierarchical_with_unit_fractions(
        &patches, &occluders, &opts, &shaded,
    );
    let (c, c_exact) = (ff.matrix.compression(), exact.matrix.compression());
    println!("{n} patches, shaded: {c:?}\nsplit: {c_exact:?}");
    assert!(c.shaded_blocks > 0, "{c:?}");
    let census =
        |settings: &Settings| crate::formfactor::partition_census(&patches, &occluders, settings);
    assert_eq!(census(&shaded).mixed_whole, 0.0);
    assert!(census(&split).mixed_whole > 0.0);
    // Products against the dense matrix, relative to each product's largest entry.
    let x = Mat::<f64>::from_fn(n, 4, |i, k| {
        if k == 0 {
            1.0
        } else {
            (((i * 7 + k * 13) % 17) as f64 - 8.0) / 8.0
        }
    });
    let product_error = |h: &Hierarchical| {
        let (mut want, mut got) = (Mat::<f64>::zeros(n, 4), Mat::<f64>::zeros(n, 4));
        dense.apply(want.as_mut(), x.as_ref(), Par::Seq);
        h.apply(got.as_mut(), x.as_ref(), Par::Seq);
        (0..4)
            .map(|k| {
                let w: Vec<f64> = (0..n).map(|i| want[(i, k)]).collect();
                let g: Vec<f64> = (0..n).map(|i| got[(i, k)]).collect();
                relative_max(&g, &w)
            })
            .fold(0.0, f64::max)
    };
    // Against the dense row sums: the faces on the floor see nothing, theirs are 0.
    let dense_sums = dense.form_factor_row_sums(&area);
    let row_error = |h: &Hierarchical| {
        h.form_factor_row_sums(&area)
            .iter()
            .zip(&dense_sums)
            .map(|(s, d)| (s - d).abs())
            .fold(0.0, f64::max)
    };
    let (product, rows) = (product_error(&ff.matrix), row_error(&ff.matrix));
    let (product_unshaded, rows_unshaded) = (product_error(&unshaded), row_error(&unshaded));
    println!(
        "products {product:.2e} (unshaded {product_unshaded:.2e}), row sums {rows:.2e} \
         (unshaded {rows_unshaded:.2e}), exact split {:.2e}",
        product_error(&exact.matrix)
    );
    assert!(product < SHADED_PRODUCT, "{product:e}");
    assert!(rows < SHADED_ROW_SUM, "{rows:e}");
    assert!(
        product_unshaded > 2.0 * product,
        "{product_unshaded:e} {product:e}"
    );
    assert!(rows_unshaded > 2.0 * rows, "{rows_unshaded:e} {rows:e}");
    let refined =
        patch_form_factors_hierarchical(&patches, &occluders, &opts, &refined).expect("finite");
    let c = refined.matrix.compression();
    let (product_refined, rows_refined) =
        (product_error(&refined.matrix), row_error(&refined.matrix));
    println!(
        "split where the shares misfit ({} blocks): products {product_refined:.2e}, row sums \
         {rows_refined:.2e}",
        c.shade_splits
    );
    assert!(c.shade_splits > 0, "{c:?}");
    assert!(
        product_refined < 2.0 / 3.0 * product,
        "{product_refined:e} {product:e}"
    );
    assert!(rows_refined < 2.0 / 3.0 * rows, "{rows_refined:e} {rows:e}");
}

/// Bound of [`shaded_blocks_approximate_the_exact_visibility`] on the products (relative to
/// each product's largest entry).
const SHADED_PRODUCT: f64 = 3e-2;
/// The same test's bound on the row sums' difference from the dense ones.
const SHADED_ROW_SUM: f64 = 3e-2;
