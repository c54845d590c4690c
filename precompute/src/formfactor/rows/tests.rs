//! Rows of points and receivers against closed forms (Howell's catalogue), closed rooms, and
//! fields of view and responses.

use super::*;
use crate::formfactor::tests::{blocker, grid, rel, room, v};
use crate::geometry::{Face, Polygon};
use std::f64::consts::PI;

/// Howell B-3: element to a parallel rectangle a × b at height c, one corner above the element.
fn howell_b3(a: f64, b: f64, c: f64) -> f64 {
    let (x, y) = (a / c, b / c);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI)
}

#[test]
fn point_under_rectangle_corner_matches_howell_b3() {
    // Reference: Howell B-3 closed form. Tolerance 1e-6 absolute.
    let (a, b, c) = (1.3, 0.7, 0.9);
    let rect = grid(v(0.0, 0.0, c), v(0.0, b, 0.0), v(a, 0.0, 0.0), 1, 1, 0);
    let occ = Occluders::new(&rect);
    let f = point_form_factors(
        v(0.0, 0.0, 0.0),
        v(0.0, 0.0, 1.0),
        FieldOfView::HEMISPHERE,
        &rect,
        &occ,
    );
    let exact = howell_b3(a, b, c);
    println!(
        "B-3: F = {:.9}, exact {exact:.9}, error {:.1e}",
        f[0],
        (f[0] - exact).abs()
    );
    assert!((f[0] - exact).abs() < 1e-6);
}

#[test]
fn rays_take_over_beyond_the_shadow_capacities() {
    // Reference: the exact (shadow-cutting) visibility of the same scene. A plate cut into
    // 30 × 30 patches, each its own blocker, seen from near the floor gives shafts of more
    // than 64 blockers (a ceiling patch's shadow spans about 9 × 9 of them): visibility then
    // falls back to rays refined at silhouettes. With the plate as one face it is exact.
    // The two must agree to the rays' accuracy, and both see a full hemisphere (nine ceiling
    // patches take the ray path here; they agree to about 1e-6). Tolerance 1e-4 on the
    // ceiling's share (about 0.22) and on the sum.
    let mut scene = room(0.5);
    let first = scene.len();
    let (o, e1, e2) = (v(1.5, 1.0, 1.5), v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0));
    scene.extend(grid(o, e2, e1, 30, 30, 6));
    let mut faces: Vec<Face> = (0..first)
        .map(|i| Face {
            polygon: scene[i].polygon.clone(),
            patches: i..i + 1,
        })
        .collect();
    faces.push(Face {
        polygon: Polygon::new(vec![o, o + e2, o + e1 + e2, o + e1]),
        patches: first..scene.len(),
    });
    let per_patch = Occluders::new(&scene);
    let per_face = Occluders::with_faces(&scene, &faces);
    let (x, up) = (v(1.9, 1.6, 0.1), v(0.0, 0.0, 1.0));
    let rays = point_form_factors(x, up, FieldOfView::HEMISPHERE, &scene, &per_patch);
    let exact = point_form_factors(x, up, FieldOfView::HEMISPHERE, &scene, &per_face);
    let ceiling = |f: &[f64]| -> f64 {
        (0..first)
            .filter(|&i| scene[i].normal.z < -0.5)
            .map(|i| f[i])
            .sum()
    };
    let (c_rays, c_exact) = (ceiling(&rays), ceiling(&exact));
    let (s_rays, s_exact) = (rays.iter().sum::<f64>(), exact.iter().sum::<f64>());
    println!("ceiling share: rays {c_rays:.6}, exact {c_exact:.6}; Σ F rays {s_rays:.6}, exact {s_exact:.9}");
    assert!(
        c_exact > 0.05 && c_exact < 0.5,
        "the plate hides part of the ceiling"
    );
    assert!((c_rays - c_exact).abs() < 1e-4);
    assert!((s_exact - 1.0).abs() < 1e-9);
    assert!((s_rays - 1.0).abs() < 1e-4);
}

#[test]
fn points_in_closed_room_see_everything() {
    // Reference: a point inside a closed room sees a full hemisphere, Σ_j F_sj = 1.
    // Tolerance 1e-6 unoccluded; 1e-6 with the blocker too, as visibility is exact (the
    // shadows cut out of the room's patches are exactly what the blocker's patches gain).
    let empty = room(0.5);
    let mut furnished = empty.clone();
    furnished.extend(blocker(0.35));
    let sensors = [
        (v(2.0, 1.5, 0.8), v(0.0, 0.0, 1.0)),
        (v(0.3, 2.9, 2.5), v(0.3, -0.5, -0.2)),
        (v(3.99, 1.0, 1.0), v(-1.0, 0.0, 0.0)),
        (v(1.0, 0.5, 0.3), v(1.0, 1.0, 0.4)),
    ];
    let occ_empty = Occluders::new(&empty);
    let occ_full = Occluders::new(&furnished);
    for (p, n) in sensors {
        let s: f64 = point_form_factors(p, n, FieldOfView::HEMISPHERE, &empty, &occ_empty)
            .iter()
            .sum();
        println!("point {p:?}: Σ F = {s:.9} (empty room)");
        assert!((s - 1.0).abs() < 1e-6);
        if p.z > 1.2 || p.z < 0.5 || p.x < 1.5 || p.x > 2.5 {
            let s: f64 = point_form_factors(p, n, FieldOfView::HEMISPHERE, &furnished, &occ_full)
                .iter()
                .sum();
            println!("point {p:?}: Σ F = {s:.9} (with blocker)");
            assert!((s - 1.0).abs() < 1e-6);
        }
    }
}

#[test]
fn point_field_of_view_sees_sin_squared_of_ceiling() {
    // Reference: a cone of half-angle α looking up at a ceiling that fills it sees
    // F = sin² α (element to coaxial disk, Howell B-13). Tolerance 1e-5 relative.
    let empty = room(0.5);
    let occ = Occluders::new(&empty);
    let alpha = 40.0_f64.to_radians();
    let f = point_form_factors(
        v(2.0, 1.5, 1.5),
        v(0.0, 0.0, 1.0),
        FieldOfView::cone(Some(alpha)),
        &empty,
        &occ,
    );
    let s: f64 = f.iter().sum();
    let exact = alpha.sin().powi(2);
    println!("cone 40°: Σ F = {s:.8}, exact {exact:.8}");
    assert!(rel(s, exact) < 1e-5);
}

#[test]
fn work_plane_in_closed_room_sees_everything() {
    // Reference: a one-sided receiver inside a closed room sees a full hemisphere, rows sum
    // to 1. Tolerance 1e-6, with the blocker above part of the plane's view (the plane is at
    // 0.3 m, under the floating blocker): each receiver uses one quadrature rule for all its
    // pairs and visibility is exact, so the rule's points each see exactly one hemisphere.
    let mut scene = room(0.4);
    scene.extend(blocker(0.35));
    let occ = Occluders::new(&scene);
    let plane = grid(
        v(0.5, 0.5, 0.3),
        v(3.0, 0.0, 0.0),
        v(0.0, 2.0, 0.0),
        6,
        4,
        0,
    );
    let f = receiver_form_factors(&plane, &scene, &occ, &FormFactorOptions::default());
    let worst = (0..plane.len())
        .map(|r| ((0..scene.len()).map(|j| f[(r, j)]).sum::<f64>() - 1.0).abs())
        .fold(0.0, f64::max);
    println!(
        "work plane: {} receivers, worst row-sum deviation {worst:.2e}",
        plane.len()
    );
    assert!(worst < 1e-6);
}

/// A table at every degree from `f(θ)` (θ in radians) up to 90°.
fn tabulated(f: impl Fn(f64) -> f64) -> crate::scene::response::Response {
    let rows: Vec<(f64, f64)> = (0..=90)
        .map(|d| (f64::from(d), f(f64::from(d).to_radians()).max(0.0)))
        .collect();
    crate::scene::response::Response::from_rows(&rows, None).expect("a valid table")
}

#[test]
fn response_in_a_closed_room_reads_its_integral() {
    // Reference: in a closed room of uniform exitance M a sensor reads M ∫ S dω / π =
    // 2M ∫ S sin θ dθ; for S = cos² θ that is 2M/3 (closed form). Tolerance 1e-4 relative:
    // the table's linear interpolation of cos² at 1° (h² |S''| / 8 ≈ 8e-5 at most) and the
    // pyramid standing in for each cone (below 1e-5).
    let empty = room(0.5);
    let occ = Occluders::new(&empty);
    let response = tabulated(|t| t.cos().powi(2));
    let f = point_form_factors(
        v(2.0, 1.5, 1.5),
        v(0.0, 0.0, 1.0),
        FieldOfView::response(&response),
        &empty,
        &occ,
    );
    let s: f64 = f.iter().sum();
    println!("cos² response: Σ R = {s:.8}, exact {:.8}", 2.0 / 3.0);
    assert!(rel(s, 2.0 / 3.0) < 1e-4);
}

#[test]
fn cosine_table_equals_illuminance_under_a_rectangle() {
    // Reference: Howell B-3 closed form (a cosine sensor reads illuminance, F M). Tolerance
    // 1e-4 relative: a tabulated cosine interpolated linearly at 1° is within 4e-5 of cos θ.
    let (a, b, c) = (1.3, 0.7, 0.9);
    let rect = grid(v(0.0, 0.0, c), v(0.0, b, 0.0), v(a, 0.0, 0.0), 1, 1, 0);
    let occ = Occluders::new(&rect);
    let response = tabulated(f64::cos);
    let f = point_form_factors(
        v(0.0, 0.0, 0.0),
        v(0.0, 0.0, 1.0),
        FieldOfView::response(&response),
        &rect,
        &occ,
    );
    let exact = howell_b3(a, b, c);
    println!("cosine table under B-3: R = {:.9}, exact {exact:.9}", f[0]);
    assert!(rel(f[0], exact) < 1e-4);
}

#[test]
fn shielded_response_to_a_rectangle_matches_a_direct_quadrature() {
    // Reference: `∫ S(θ) cos θ_j / (π r²) dA` over the rectangle by a 1200 × 1200 midpoint
    // rule (an independent path: no cones, no rings). Tolerance 1e-5 relative (1.1e-7
    // measured): the response relative to a cosine taken as constant over each 1° ring, the
    // pyramids standing in for the cones, and the midpoint rule's own error.
    let (a, b, c) = (2.3, 1.7, 0.9);
    let rect = grid(v(0.0, 0.0, c), v(0.0, b, 0.0), v(a, 0.0, 0.0), 1, 1, 0);
    let occ = Occluders::new(&rect);
    let response = crate::scene::response::Response::shielded(60f64.to_radians());
    let up = v(0.0, 0.0, 1.0);
    let f = point_form_factors(
        v(0.0, 0.0, 0.0),
        up,
        FieldOfView::response(&response),
        &rect,
        &occ,
    );
    let steps = 1200;
    let (hx, hy) = (a / f64::from(steps), b / f64::from(steps));
    let mut direct = 0.0;
    for i in 0..steps {
        for j in 0..steps {
            let d = v((f64::from(i) + 0.5) * hx, (f64::from(j) + 0.5) * hy, c);
            let r2 = d.dot(d);
            let cos = up.dot(d) / r2.sqrt();
            direct += response.at_cos(cos) * cos / (PI * r2) * hx * hy;
        }
    }
    println!(
        "shielded 60°: R = {:.7}, quadrature {direct:.7}, rel {:.1e}",
        f[0],
        rel(f[0], direct)
    );
    assert!(rel(f[0], direct) < 1e-5);
}
