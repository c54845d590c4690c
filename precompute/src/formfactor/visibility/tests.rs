//! The visible shares between two clusters against every ray between their patches.

use super::*;
use crate::formfactor::tests::{grid, v};

/// [`between_clusters`] on two 2 × 2 m plates of 8 × 8 patches facing each other
/// 2 m apart: every share 1 with nothing between, 0 behind a sheet that covers the gap.
/// Behind a sheet over the half x < 1 m: at mid-height the shares' kernel-weighted mean is
/// that of the rays between every pair of centroids (counted here, ray by ray) within 0.1
/// (rays through the sheet's edge may count either way); just above the lower plate, each
/// lower patch sees the upper plate whole or not at all, and its share is within 0.1 of
/// the exact one. Either way round, the same shares. The misfit is 0 where nothing is cut
/// or everything is, above 1e-2 behind the sheet half-way, under half of that for the sheet
/// just above the lower plate, and within [`MISFIT_SAMPLING`] of its sum over every pair of
/// centroids.
#[test]
fn visible_shares_between_clusters() {
    let below = grid(
        v(0.0, 0.0, 0.0),
        v(2.0, 0.0, 0.0),
        v(0.0, 2.0, 0.0),
        8,
        8,
        0,
    );
    let above = grid(
        v(0.0, 0.0, 2.0),
        v(0.0, 2.0, 0.0),
        v(2.0, 0.0, 0.0),
        8,
        8,
        1,
    );
    let (a, b): (Vec<usize>, Vec<usize>) = ((0..64).collect(), (64..128).collect());
    let scene = |sheet: Vec<Patch>| {
        let mut patches = below.clone();
        patches.extend(above.iter().cloned());
        patches.extend(sheet);
        patches
    };
    let misfits = std::cell::RefCell::new(Vec::new());
    let shares = |patches: &[Patch]| {
        let occluders = Occluders::new(patches);
        let ab = between_clusters(&occluders, patches, &a, &b);
        let ba = between_clusters(&occluders, patches, &b, &a);
        assert_eq!(
            (&ab.rows, &ab.cols, ab.misfit),
            (&ba.cols, &ba.rows, ba.misfit)
        );
        // The misfit's own sum over every pair of centroids rather than 16 ends a patch.
        let every = |from: &[usize], to: &[usize], own: &[f64], other: &[f64]| {
            let sum: f64 = from
                .iter()
                .enumerate()
                .map(|(x, &i)| {
                    let p = &patches[i];
                    to.iter()
                        .enumerate()
                        .map(|(y, &j)| {
                            let q = &patches[j];
                            let d = q.centroid - p.centroid;
                            let w = q.area * p.normal.dot(d) * -q.normal.dot(d) / d.dot(d).powi(2);
                            let seen = occluders.visible(p.centroid, q.centroid, &[i, j]);
                            w * (f64::from(u8::from(seen)) - (own[x] * other[y]).min(1.0)).abs()
                        })
                        .sum::<f64>()
                })
                .sum();
            sum / (std::f64::consts::PI * from.len() as f64)
        };
        let full = every(&a, &b, &ab.rows, &ab.cols).max(every(&b, &a, &ab.cols, &ab.rows));
        misfits.borrow_mut().push((ab.misfit, full));
        (ab.rows, ab.cols, occluders)
    };
    let sheet = |x: f64, z: f64| {
        grid(
            v(-1.0, -1.0, z),
            v(x + 1.0, 0.0, 0.0),
            v(0.0, 4.0, 0.0),
            1,
            1,
            2,
        )
    };
    let open = scene(Vec::new());
    let (r, c, _) = shares(&open);
    assert!(r.iter().chain(&c).all(|&x| x == 1.0));
    let (r, c, _) = shares(&scene(sheet(3.0, 1.0)));
    assert!(r.iter().chain(&c).all(|&x| x == 0.0));
    // Kernel-weighted sums over the pairs of patch `a[ia]` with every patch of `b`: the
    // model's, the rays' between centroids, and the weights'.
    let sums = |patches: &[Patch], r: &[f64], c: &[f64], occluders: &Occluders, ia: usize| {
        let (i, (mut model, mut rays, mut total)) = (a[ia], (0.0, 0.0, 0.0));
        let p = &patches[i];
        for (jb, &j) in b.iter().enumerate() {
            let q = &patches[j];
            let d = q.centroid - p.centroid;
            let w = p.normal.dot(d) * -q.normal.dot(d) / d.dot(d).powi(2);
            total += w;
            model += w * r[ia] * c[jb];
            if occluders.visible(p.centroid, q.centroid, &[i, j]) {
                rays += w;
            }
        }
        (model, rays, total)
    };
    // The same over every pair: the model's mean and the rays'.
    let means = |patches: &[Patch], r: &[f64], c: &[f64], occluders: &Occluders| {
        let (model, rays, total) = (0..a.len())
            .map(|ia| sums(patches, r, c, occluders, ia))
            .fold((0.0, 0.0, 0.0), |s, x| (s.0 + x.0, s.1 + x.1, s.2 + x.2));
        (model / total, rays / total)
    };
    let half = scene(sheet(1.0, 1.0));
    let (r, c, occluders) = shares(&half);
    let (model, rays) = means(&half, &r, &c, &occluders);
    assert!((model - rays).abs() < 0.1, "{model} {rays}");
    // A sheet 1 cm above the lower plate: patch by patch.
    let low = scene(sheet(1.0, 0.01));
    let (r, c, occluders) = shares(&low);
    let (model, rays) = means(&low, &r, &c, &occluders);
    assert!((model - rays).abs() < 0.1, "{model} {rays}");
    for (ia, &i) in a.iter().enumerate() {
        let (model, rays, total) = sums(&low, &r, &c, &occluders, ia);
        let (modelled, exact) = (model / total, rays / total);
        assert!(
            (modelled - exact).abs() < 0.1,
            "patch {i}: {modelled} against {exact}"
        );
    }
    // Nothing between and nothing seen are products of the shares. Behind the sheet, what a
    // patch sees depends on both ends: less so for the sheet on the lower plate, where only
    // the upper patches' shares vary with their place. Either way the 16 ends a patch
    // estimate the sum over every pair of centroids.
    let misfits = misfits.into_inner();
    println!("misfits (16 ends, every pair): open, covered, half-way, low: {misfits:?}");
    let [open, covered, half_way, low] = misfits[..] else {
        panic!("four scenes: {misfits:?}");
    };
    assert_eq!((open.0, covered.0), (0.0, 0.0));
    assert!(half_way.0 > 1e-2, "{half_way:?}");
    assert!(low.0 < 0.5 * half_way.0, "{low:?} {half_way:?}");
    for (estimate, every) in [half_way, low] {
        assert!(
            (estimate - every).abs() <= MISFIT_SAMPLING * every,
            "{estimate:e} against {every:e}"
        );
    }
}

/// How far [`ClusterShares::misfit`] from 16 ends a patch may be from the same sum over every
/// pair of centroids in [`visible_shares_between_clusters`] (relative).
const MISFIT_SAMPLING: f64 = 0.05;
