//! The direct light of luminaires against closed forms: a point source over a plane (at
//! points and averaged over patches), flux conservation in a closed room, occlusion,
//! orientation, and the near-field split against the exact form factor of a Lambertian
//! rectangle.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::{channel_lights, lights_and_flux, LuminaireFlux, LuminaireOptions, Source};
use crate::formfactor::{gauss_legendre, Occluders};
use crate::geometry::{Patch, Polygon, Vec3};
use crate::scene::photometry::{
    Distribution, Format, Identity, LampGeometry, Opening, OpeningShape, Photometry, Symmetry, Tilt,
};
use crate::scene::{self, luminaire_frame, FieldOfView, Luminaire};

fn photometry(
    symmetry: Symmetry,
    planes: &[f64],
    gamma: Vec<f64>,
    candela: Vec<Vec<f64>>,
    opening: Opening,
) -> Photometry {
    Photometry {
        format: Format::Eulumdat,
        identity: Identity::default(),
        symmetry,
        opening,
        luminaire: None,
        lamps: 1,
        absolute: true,
        lamp_flux: None,
        luminaire_flux: None,
        downward_fraction: None,
        input_watts: None,
        tilt: None,
        distribution: Distribution::new(symmetry, planes, gamma, candela).unwrap(),
    }
}

fn point() -> Opening {
    Opening {
        shape: OpeningShape::Point,
        length: 0.0,
        width: 0.0,
        height: 0.0,
        side_heights: None,
    }
}

/// `i` cd in every direction.
fn isotropic(i: f64) -> Photometry {
    photometry(
        Symmetry::Rotational,
        &[0.0],
        vec![0.0, 180.0],
        vec![vec![i, i]],
        point(),
    )
}

/// `i0 cos γ` cd downward (flux π i0 lm), tabulated every degree, from a flat rectangular
/// opening `length × width` (m).
fn lambertian(i0: f64, length: f64, width: f64) -> Photometry {
    let gamma: Vec<f64> = (0..=90).map(f64::from).collect();
    let values = gamma.iter().map(|g| i0 * g.to_radians().cos()).collect();
    let opening = Opening {
        shape: OpeningShape::Rectangular,
        length,
        width,
        height: 0.0,
        side_heights: None,
    };
    photometry(Symmetry::Rotational, &[0.0], gamma, vec![values], opening)
}

/// `p` placed at `position`, aimed and spun as a scene's `[[luminaire]]` is (its tilt factor
/// computed as the scene computes it).
fn luminaire(p: Photometry, position: Vec3, aim: Vec3, spin_degrees: f64) -> Luminaire {
    let (nadir, c0, c90) = luminaire_frame(aim, spin_degrees.to_radians());
    let tilt_factor = p.tilt_factor(nadir, c0, c90);
    Luminaire {
        name: "l".into(),
        file: PathBuf::from("synthetic"),
        photometry: Arc::new(p),
        position,
        nadir,
        c0,
        c90,
        channel: 0,
        maintenance_factor: 1.0,
        tilt_factor,
    }
}

const DOWN: Vec3 = Vec3::new(0.0, 0.0, -1.0);
const UP: Vec3 = Vec3::new(0.0, 0.0, 1.0);

/// A `cells × cells` grid of square patches of side `side` (m) on the plane z = `z`, centred
/// on the origin, facing up.
fn floor(cells: usize, side: f64, z: f64) -> Vec<Patch> {
    let o = -0.5 * side * cells as f64;
    let mut out = Vec::new();
    for i in 0..cells {
        for j in 0..cells {
            let (x, y) = (o + side * i as f64, o + side * j as f64);
            let v = vec![
                Vec3::new(x, y, z),
                Vec3::new(x + side, y, z),
                Vec3::new(x + side, y + side, z),
                Vec3::new(x, y + side, z),
            ];
            out.push(Patch::new(Polygon::new(v), 0));
        }
    }
    out
}

/// Solid angle (sr) of the rectangle `[x1, x2] × [y1, y2]` of a plane seen from a point at
/// height `h` above its origin: `Σ ± atan(x y / (h √(x² + y² + h²)))` over the corners.
fn solid_angle(x1: f64, x2: f64, y1: f64, y2: f64, h: f64) -> f64 {
    let f = |x: f64, y: f64| (x * y / (h * (x * x + y * y + h * h).sqrt())).atan();
    f(x2, y2) - f(x1, y2) - f(x2, y1) + f(x1, y1)
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn point_source_over_a_plane_at_points_and_over_patches() {
    let (i, h) = (100.0, 1.0);
    let lum = luminaire(isotropic(i), Vec3::new(0.0, 0.0, h), DOWN, 0.0);
    // 0.5 m patches out to 2 m: the nearest are half their distance to the source across.
    let patches = floor(8, 0.5, 0.0);
    let occluders = Occluders::new(&patches);
    let opts = LuminaireOptions::default();
    let gl = gauss_legendre(opts.order);
    let source = Source::new(&lum, &occluders, &opts, &gl);
    // At points: E = I h / (r² + h²)^{3/2}, to rounding.
    for r in [0.0, 0.3, 1.0, 1.9] {
        let e = source.point(Vec3::new(r, 0.0, 0.0), UP, FieldOfView::HEMISPHERE, &[]);
        let exact = i * h / (r * r + h * h).powf(1.5);
        assert!(relative(e, exact) < 1e-12, "r = {r}: {e} against {exact}");
    }
    // Over patches: the patch average of the closed form is I Ω / A.
    let mut worst = 0.0f64;
    for (k, p) in patches.iter().enumerate() {
        let v = &p.polygon.vertices;
        let exact = i * solid_angle(v[0].x, v[2].x, v[0].y, v[2].y, h) / p.area;
        worst = worst.max(relative(source.patch(p, &[k]), exact));
    }
    assert!(worst < 1e-5, "patch averages within {worst:.2e}");
    // The centroid alone would be off by far more near the source: why patches integrate.
    let p = &patches[27];
    let v = &p.polygon.vertices;
    let exact = i * solid_angle(v[0].x, v[2].x, v[0].y, v[2].y, h) / p.area;
    let centroid = source.point(p.centroid, UP, FieldOfView::HEMISPHERE, &[]);
    assert!(relative(centroid, exact) > 1e-2);
}

#[test]
fn a_blocker_shadows_a_sensor_and_a_patch() {
    let lum = luminaire(isotropic(50.0), Vec3::new(0.0, 0.0, 2.0), DOWN, 0.0);
    let mut patches = floor(4, 1.0, 0.0);
    // A 0.6 m square at 1 m, over the origin.
    let blocker = floor(1, 0.6, 1.0).remove(0);
    patches.push(blocker);
    let occluders = Occluders::new(&patches);
    let opts = LuminaireOptions::default();
    let gl = gauss_legendre(opts.order);
    let source = Source::new(&lum, &occluders, &opts, &gl);
    assert_eq!(
        source.point(Vec3::new(0.1, 0.2, 0.0), UP, FieldOfView::HEMISPHERE, &[]),
        0.0
    );
    let far = Vec3::new(1.5, 0.0, 0.0);
    let e = source.point(far, UP, FieldOfView::HEMISPHERE, &[]);
    assert!(relative(e, 50.0 * 2.0 / (1.5f64 * 1.5 + 4.0).powf(1.5)) < 1e-12);
    // The blocker's shadow is the square of side 1.2 m around the origin: the four central
    // patches lose exactly that area's share of their light, the rest nothing.
    let open = luminaire(isotropic(50.0), lum.position, DOWN, 0.0);
    let clear_patches = floor(4, 1.0, 0.0);
    let clear_occluders = Occluders::new(&clear_patches);
    let clear = Source::new(&open, &clear_occluders, &opts, &gl);
    let all: f64 = (0..16).map(|k| clear.patch(&clear_patches[k], &[k])).sum();
    let shadow = 50.0 * solid_angle(-0.6, 0.6, -0.6, 0.6, 2.0);
    // The shadow cut out of the cells as a polygon (the default): exact but for rounding;
    // by rays, its edges refined to 1/256 of a patch, within 2e-3 of the shadow's flux.
    let rays = LuminaireOptions {
        polygon_shadows: false,
        ..LuminaireOptions::default()
    };
    for (opts, tolerance) in [(&opts, 1e-9), (&rays, 2e-3)] {
        let source = Source::new(&lum, &occluders, opts, &gl);
        let shadowed: f64 = (0..16)
            .map(|k| patches[k].area * source.patch(&patches[k], &[k]))
            .sum();
        let error = relative(all - shadowed, shadow);
        assert!(
            error < tolerance,
            "polygons {}: {all} − {shadowed} against {shadow}: {error:.2e}",
            opts.polygon_shadows
        );
    }
}

/// An extended opening casts a penumbra: its points see some pieces of the opening and not
/// others. An isotropic opening (1000 cd, 1.2 m × 0.3 m, 2 m up) over a floor of 0.5 m
/// patches, a 0.6 m square blocker at 1 m. Seen from the floor (2 m to 2.2 m from the
/// opening) the five-times rule splits it into 3 × 1 pieces (`⌈5 · 1.2 / d⌉ = 3` along its
/// length, module documentation), and a shadow ratio of 10 into 6 × 2 (`⌈10 · 1.2 / d⌉ = 6`,
/// `⌈10 · 0.3 / d⌉ = 2`); a piece at `(p, q)` is a point source of its share of the
/// intensity and hides the rectangle `[−0.6 − p, 0.6 − p] × [−0.6 − q, 0.6 − q]` of the floor.
/// Reference, exact for those pieces: a piece of intensity `I` at height `h` puts `I Ω` lm on a
/// rectangle below it, `Ω` its solid angle (`solid_angle`), so each patch receives `Σ I
/// (Ω(patch) − Ω(patch ∩ shadow))`.
#[test]
fn an_extended_opening_casts_a_penumbra_integrated_over_patches() {
    let (i, h) = (1000.0, 2.0);
    let mut p = isotropic(i);
    p.opening = Opening {
        shape: OpeningShape::Rectangular,
        length: 1.2,
        width: 0.3,
        height: 0.0,
        side_heights: None,
    };
    let lum = luminaire(p, Vec3::new(0.0, 0.0, h), DOWN, 0.0);
    let mut patches = floor(4, 0.5, 0.0);
    patches.push(floor(1, 0.6, 1.0).remove(0));
    let occluders = Occluders::new(&patches);
    // The pieces' centres of a split into `along × across`, from a side's centre fractions.
    let centres = |k: usize, half: f64| -> Vec<f64> {
        (0..k)
            .map(|m| half * (-1.0 + (2.0 * m as f64 + 1.0) / k as f64))
            .collect()
    };
    let exact = |lo: Vec3, hi: Vec3, along: usize, across: usize| -> f64 {
        let share = i / (along * across) as f64;
        let mut lumens = 0.0;
        for &px in &centres(along, 0.6) {
            for &py in &centres(across, 0.15) {
                let all = solid_angle(lo.x - px, hi.x - px, lo.y - py, hi.y - py, h);
                let (x1, x2) = ((-0.6 - px).max(lo.x), (0.6 - px).min(hi.x));
                let (y1, y2) = ((-0.6 - py).max(lo.y), (0.6 - py).min(hi.y));
                let hidden = if x1 < x2 && y1 < y2 {
                    solid_angle(x1 - px, x2 - px, y1 - py, y2 - py, h)
                } else {
                    0.0
                };
                lumens += share * (all - hidden);
            }
        }
        lumens / ((hi.x - lo.x) * (hi.y - lo.y))
    };
    let worst = |opts: &LuminaireOptions, along: usize, across: usize| -> f64 {
        let gl = gauss_legendre(opts.order);
        let source = Source::new(&lum, &occluders, opts, &gl);
        let mut worst = 0.0f64;
        for (k, p) in patches[..16].iter().enumerate() {
            let (lo, hi) = (p.polygon.vertices[0], p.polygon.vertices[2]);
            let reference = exact(lo, hi, along, across);
            assert!(reference > 0.0);
            worst = worst.max(relative(source.patch(p, &[k]), reference));
        }
        worst
    };
    // The shadows as polygons (the default): each piece's shadow is cut out of the cells
    // exactly, and the 4 × 4 rule on the lit parts integrates a smooth `I cos θ / r²`.
    // Measured 1.2e-12 with 3 × 1 pieces (a shadow ratio of 5, as the five-times rule).
    let polygons = LuminaireOptions {
        shadow_ratio: 10.0,
        ..LuminaireOptions::default()
    };
    for (ratio, along, across) in [(5.0, 3, 1), (10.0, 6, 2)] {
        let opts = LuminaireOptions {
            shadow_ratio: ratio,
            ..polygons.clone()
        };
        let error = worst(&opts, along, across);
        assert!(
            error < 1e-9,
            "{along} × {across} pieces: patch means within {error:.2e} of exact"
        );
    }
    // The pieces matter: the 3 × 1 split is far from the 6 × 2 one in the penumbra.
    assert!(worst(&polygons, 3, 1) > 1e-2);
    // A point in the penumbra, 0.7 m from the centre below the opening's length: the
    // segments from the opening to it cross the blocker's plane halfway, so the part of the
    // opening with `x ∈ [−0.6, −0.1]` is hidden. Reference: the opening as the limit of its
    // pieces, `∫ (I / A) cos θ / r² dA` over its visible part, by the midpoint rule on 2400 ×
    // 600 points (a hidden edge along a column boundary of the grid). The default split
    // (pieces at most 1/20 of the distance, 12 × 3) within 1e-2, measured 5.1e-4; the
    // five-times rule's 3 × 1 pieces, one of which is hidden, 12.8 % off.
    let x = Vec3::new(0.7, 0.0, 0.0);
    let (m, n) = (2400, 600);
    let mut limit = 0.0;
    for a in 0..m {
        let px = -0.6 + 1.2 * (a as f64 + 0.5) / m as f64;
        if (-0.6..=-0.1).contains(&px) {
            continue;
        }
        for b in 0..n {
            let py = -0.15 + 0.3 * (b as f64 + 0.5) / n as f64;
            let r2 = (px - x.x).powi(2) + py * py + h * h;
            limit += h / r2.powf(1.5);
        }
    }
    let limit = limit * i / (m * n) as f64;
    let gl = gauss_legendre(4);
    let at = |opts: &LuminaireOptions| {
        Source::new(&lum, &occluders, opts, &gl).point(x, UP, FieldOfView::HEMISPHERE, &[])
    };
    let fine = relative(at(&LuminaireOptions::default()), limit);
    let coarse = relative(
        at(&LuminaireOptions {
            shadow_ratio: 5.0,
            ..LuminaireOptions::default()
        }),
        limit,
    );
    assert!(
        fine < 1e-2 && coarse > 1e-1,
        "a point in the penumbra: {fine:.1e} finer, {coarse:.1e} by the five-times rule"
    );
    // Rays refined along the shadow edges, where the polygons do not fit their capacities,
    // with the five-times rule's 3 × 1 pieces. Measured: 6.4e-4 worst (the four patches the
    // penumbra crosses), the error of the 4 × 4 rule on the cells a shadow edge cuts, of
    // order their side (1/256 of the patch's): 1.6e-4 at edge_depth 10 and 4.0e-5 at 12,
    // while order 8 in place of 4 gives 5.2e-4. Against the same exact reference, the
    // midpoint rule on a 256 × 256 grid of `Source::point` per patch is 2.6e-3 off, 512²
    // 7.6e-4, 1024² 6.4e-4, 2048² 1.9e-4: as a reference for this tolerance a grid needs to
    // be finer than 2048².
    let rays = LuminaireOptions {
        polygon_shadows: false,
        ..LuminaireOptions::default()
    };
    let traced = worst(&rays, 3, 1);
    assert!(
        traced < 1e-3,
        "patch means by rays within {traced:.2e} of exact"
    );
    // Finer edge cells close in on the exact means as their side: the error is the edges'.
    let finer = worst(
        &LuminaireOptions {
            edge_depth: 10,
            ..rays
        },
        3,
        1,
    );
    assert!(
        finer < traced / 3.0,
        "edge_depth 10: {finer:.2e}, 8: {traced:.2e}"
    );
}

#[test]
fn aim_and_spin_turn_the_distribution() {
    // A narrow beam: 1000 cd within 10° of the nadir, none beyond 15°.
    let gamma = vec![0.0, 10.0, 15.0, 180.0];
    let beam = photometry(
        Symmetry::Rotational,
        &[0.0],
        gamma,
        vec![vec![1000.0, 1000.0, 0.0, 0.0]],
        point(),
    );
    // Aimed at +x from 2 m: the wall there is lit at I/d², the floor below not at all.
    let wall = Patch::new(
        Polygon::new(vec![
            Vec3::new(2.0, -1.0, 0.0),
            Vec3::new(2.0, -1.0, 2.0),
            Vec3::new(2.0, 1.0, 2.0),
            Vec3::new(2.0, 1.0, 0.0),
        ]),
        0,
    );
    let ground = floor(1, 4.0, 0.0).remove(0);
    let patches = vec![wall.clone(), ground.clone()];
    let occluders = Occluders::new(&patches);
    let opts = LuminaireOptions::default();
    let gl = gauss_legendre(opts.order);
    let sideways = luminaire(
        beam,
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 0.0),
        0.0,
    );
    let source = Source::new(&sideways, &occluders, &opts, &gl);
    let on_wall = source.point(
        Vec3::new(2.0, 0.0, 1.0),
        Vec3::new(-1.0, 0.0, 0.0),
        FieldOfView::HEMISPHERE,
        &[0],
    );
    assert!(relative(on_wall, 1000.0 / 4.0) < 1e-12, "{on_wall}");
    assert!(source.patch(&wall, &[0]) > 0.0);
    assert_eq!(source.patch(&ground, &[1]), 0.0);

    // One-sided: all the light in the C0 half-plane, none at C90…C270.
    let planes = [0.0, 90.0, 180.0, 270.0];
    let lopsided = |spin| {
        let p = photometry(
            Symmetry::None,
            &planes,
            vec![0.0, 90.0],
            vec![vec![100.0, 100.0], vec![0.0; 2], vec![0.0; 2], vec![0.0; 2]],
            point(),
        );
        luminaire(p, Vec3::new(0.0, 0.0, 1.0), DOWN, spin)
    };
    let (east, north) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
    let lit = 100.0 * 0.5f64.sqrt() / 2.0;
    for (spin, bright, dark) in [(0.0, east, north), (90.0, north, east)] {
        let l = lopsided(spin);
        let s = Source::new(&l, &occluders, &opts, &gl);
        assert!(
            relative(s.point(bright, UP, FieldOfView::HEMISPHERE, &[]), lit) < 1e-12,
            "spin {spin}"
        );
        assert_eq!(
            s.point(dark, UP, FieldOfView::HEMISPHERE, &[]),
            0.0,
            "spin {spin}"
        );
    }
}

/// Form factor from a point to the parallel rectangle `[x1, x2] × [y1, y2]` at height `h`
/// above it (Howell's catalogue, B-3: `(1/2π) Σ ± (X/√(1+X²)) atan(Y/√(1+X²)) + (Y/√(1+Y²))
/// atan(X/√(1+Y²))`, `X = x/h`, `Y = y/h`, over the corners).
fn parallel_rectangle(x1: f64, x2: f64, y1: f64, y2: f64, h: f64) -> f64 {
    let f = |x: f64, y: f64| {
        let (a, b) = (x / h, y / h);
        let (sa, sb) = ((1.0 + a * a).sqrt(), (1.0 + b * b).sqrt());
        (a / sa * (b / sa).atan() + b / sb * (a / sb).atan()) / (2.0 * PI)
    };
    f(x2, y2) - f(x1, y2) - f(x2, y1) + f(x1, y1)
}

#[test]
fn a_large_opening_near_a_plane_converges_to_its_exitance_form_factor() {
    // A 0.6 m × 0.6 m Lambertian panel of 1000 cd at nadir, 0.3 m above the receiving points:
    // its exitance M = π I0 / A lights a parallel point with M times the exact form factor.
    let (i0, side, h) = (1000.0, 0.6, 0.3);
    let lum = luminaire(
        lambertian(i0, side, side),
        Vec3::new(0.0, 0.0, h),
        DOWN,
        0.0,
    );
    let exitance = PI * i0 / (side * side);
    let occluders = Occluders::new(&[]);
    let gl = gauss_legendre(4);
    for x in [0.0, 0.25, 0.6] {
        let exact = exitance * parallel_rectangle(-0.3 - x, 0.3 - x, -0.3, 0.3, h);
        let mut previous = f64::INFINITY;
        let mut errors = Vec::new();
        for ratio in [2.5, 5.0, 10.0, 20.0] {
            let opts = LuminaireOptions {
                near_field_ratio: ratio,
                ..LuminaireOptions::default()
            };
            let s = Source::new(&lum, &occluders, &opts, &gl);
            let error = relative(
                s.point(Vec3::new(x, 0.0, 0.0), UP, FieldOfView::HEMISPHERE, &[]),
                exact,
            );
            assert!(
                error < previous,
                "x = {x}: not converging: {errors:?} then {error}"
            );
            previous = error;
            errors.push(error);
        }
        // The midpoint rule over the pieces: the error falls as 1/k², 0.7 % at the default.
        assert!(errors[1] < 1e-2, "x = {x}: five-times rule {errors:?}");
        assert!(errors[3] < 1e-3, "x = {x}: refined {errors:?}");
        // As a point source it would be far off.
        let d2 = x * x + h * h;
        let as_point = i0 * (h * h / d2) / d2;
        assert!(relative(as_point, exact) > 0.05, "x = {x}");
    }
}

mod rooms;

#[test]
fn a_sensor_response_weighs_a_point_source_by_its_sensitivity() {
    // Reference: a sensor with S(θ) = 1 − 2θ/π (a two-row table, linear in θ, so the
    // interpolation is exact) reads I S(θ) / d² from an isotropic point source at distance d
    // and polar angle θ (closed form); tolerance 1e-12 relative.
    let (i, h) = (100.0, 1.0);
    let lum = luminaire(isotropic(i), Vec3::new(0.0, 0.0, h), DOWN, 0.0);
    let patches = floor(2, 0.5, 0.0);
    let occluders = Occluders::new(&patches);
    let opts = LuminaireOptions::default();
    let gl = gauss_legendre(opts.order);
    let source = Source::new(&lum, &occluders, &opts, &gl);
    let response = crate::scene::response::Response::from_rows(&[(0.0, 1.0), (90.0, 0.0)], None)
        .expect("valid table");
    for r in [0.0, 0.3, 1.0, 1.9] {
        let e = source.point(
            Vec3::new(r, 0.0, 0.0),
            UP,
            FieldOfView::response(&response),
            &[],
        );
        let d2 = r * r + h * h;
        let theta = (h / d2.sqrt()).acos();
        let exact = i * (1.0 - 2.0 * theta / std::f64::consts::PI) / d2;
        assert!(relative(e, exact) < 1e-12, "r = {r}: {e} against {exact}");
    }
}
