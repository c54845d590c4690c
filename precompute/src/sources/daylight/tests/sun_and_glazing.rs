//! The sun patch on the floor against the window's projection, an overhang's shadow, a
//! diffusing window's exitance, north, the tabulated transmittance and the example office.

use super::*;

/// The sun from altitude atan(1.2/√1.09) through the window and onto the floor: every ray
/// the window lets in lands there.
#[test]
fn the_sun_patch_on_the_floor_is_the_windows_projection() {
    let sensors = r#"
[[sensor]]
name = "lit"
position = [1.5, 1.0, 0.0]
normal = [0, 0, 1]
half_angle = 60

[[sensor]]
name = "narrow"
position = [1.5, 1.0, 0.0]
normal = [0, 0, 1]
half_angle = 20

[[sensor]]
name = "dark"
position = [3.5, 1.0, 0.0]
normal = [0, 0, 1]
"#;
    let scene = daylit(room(sensors, 0.35), clear(), 0.0, 0.2);
    let occ = occluders(&scene);
    let s = Vec3::new(0.3, -1.0, 1.2).normalized();
    let light = sun_light(&scene, &occ, s, &DaylightOptions::default());
    let glazing = clear();
    let cos_w = s.y.abs();
    let tau = f64::from(glazing.transmittance(cos_w.acos() as f32));
    // Flux: E_n τ A_w cos θ_w with E_n = 1 lux and A_w = 2 m².
    let flux: f64 = scene
        .patches
        .iter()
        .zip(&light.patch_irradiance[0])
        .map(|(p, e)| p.area * e)
        .sum();
    let expected = tau * 2.0 * cos_w;
    assert!(
        relative(flux, expected) < 1e-12,
        "{flux} lm against {expected}"
    );
    // The sun patch: the parallelogram of the window's corners moved along −s to z = 0;
    // each floor patch's covered fraction by a 200 × 200 midpoint grid of point-in-polygon
    // tests (an independent area, to about 1/200 of a patch along its edges).
    let shadow: Vec<(f64, f64)> = [(1.0, 1.0), (1.0, 2.0), (3.0, 2.0), (3.0, 1.0)]
        .iter()
        .map(|&(x, z)| (x - s.x * z / s.z, -s.y * z / s.z))
        .collect();
    let inside = |x: f64, y: f64| {
        (0..4).all(|k| {
            let (a, b) = (shadow[k], shadow[(k + 1) % 4]);
            (b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0) <= 0.0
        })
    };
    let floor = scene
        .surfaces
        .iter()
        .find(|s| s.name == "room.floor")
        .expect("floor");
    let mut worst = 0.0f64;
    for i in floor.patch_range.clone() {
        let v = &scene.patches[i].polygon.vertices;
        let lo = v.iter().fold(Vec3::new(f64::MAX, f64::MAX, 0.0), |m, c| {
            Vec3::new(m.x.min(c.x), m.y.min(c.y), 0.0)
        });
        let hi = v.iter().fold(Vec3::new(f64::MIN, f64::MIN, 0.0), |m, c| {
            Vec3::new(m.x.max(c.x), m.y.max(c.y), 0.0)
        });
        let n = 200;
        let mut covered = 0usize;
        for a in 0..n {
            for b in 0..n {
                let x = lo.x + (hi.x - lo.x) * (a as f64 + 0.5) / n as f64;
                let y = lo.y + (hi.y - lo.y) * (b as f64 + 0.5) / n as f64;
                covered += usize::from(inside(x, y));
            }
        }
        let fraction = covered as f64 / (n * n) as f64;
        let e = light.patch_irradiance[0][i];
        worst = worst.max((e - tau * s.z * fraction).abs());
    }
    assert!(worst < 1e-2 * tau * s.z, "worst {worst}");
    // Nothing but the floor is lit.
    for (i, p) in scene.patches.iter().enumerate() {
        if !floor.patch_range.contains(&i) {
            assert_eq!(
                light.patch_irradiance[0][i], 0.0,
                "patch {i} at {:?}",
                p.centroid
            );
        }
    }
    // Sensors: in the sun patch with the sun in view τ cos θ, out of view or out of the patch 0.
    assert!(inside(1.5, 1.0) && !inside(3.5, 1.0));
    let out = &light.output_irradiance[0];
    assert!(relative(out[0], tau * s.z) < 1e-12, "{}", out[0]);
    assert_eq!(out[1], 0.0, "the sun is 41° from the zenith, outside 20°");
    assert_eq!(out[2], 0.0);
    // The floor zone's mean is the flux over the floor's 12 m².
    assert!(relative(out[3], expected / 12.0) < 1e-12);
    assert!(light.emission[0].iter().all(|&e| e == 0.0));
}

/// A horizontal overhang at the window's head, 1 m deep and far wider than the room, with
/// reflectance 0.5.
fn overhang(scene: &mut Scene) {
    let polygon = Polygon::new(vec![
        Vec3::new(-50.0, 0.0, 2.0),
        Vec3::new(54.0, 0.0, 2.0),
        Vec3::new(54.0, -1.0, 2.0),
        Vec3::new(-50.0, -1.0, 2.0),
    ]);
    scene.obstructions = vec![Obstruction {
        name: "overhang".into(),
        faces: vec![Face {
            polygon,
            patches: 0..0,
        }],
        reflectance: 0.5,
    }];
}

#[test]
fn an_overhang_hides_the_sun_and_the_sky_above_its_edge() {
    let sensors = r#"
[[sensor]]
name = "low"
position = [2.0, 1.5, 0.5]
normal = [0, -1, 0]
"#;
    let mut scene = daylit(room(sensors, 0.5), clear(), 0.0, 0.0);
    let occ = occluders(&scene);
    let opts = DaylightOptions::default();
    // Without it, the high sun lights the floor; with it, nothing.
    let s = Vec3::new(0.0, -1.0, 2.0).normalized();
    let open = sun_light(&scene, &occ, s, &opts);
    assert!(open.patch_irradiance[0].iter().any(|&e| e > 0.0));
    overhang(&mut scene);
    let shaded = sun_light(&scene, &occ, s, &opts);
    assert!(shaded.patch_irradiance[0].iter().all(|&e| e == 0.0));
    assert!(shaded.output_irradiance[0].iter().all(|&e| e == 0.0));
    // A low sun passes under it: the patch is cut along the line where the overhang's
    // edge (y = −1, z = 2) shadows the window, z = 2 − 1 m · tan h for a sun due south at
    // altitude h (tan h = 0.5: z = 1.5), so half the open flux arrives.
    let low = Vec3::new(0.0, -1.0, 0.5).normalized();
    let under = sun_light(&scene, &occ, low, &opts);
    scene.obstructions.clear();
    let full = sun_light(&scene, &occ, low, &opts);
    // With nothing outside, a sun below the horizon is the ground's: it would shine up
    // through the window onto the ceiling.
    let night = sun_light(&scene, &occ, Vec3::new(0.0, -1.0, -0.1).normalized(), &opts);
    assert!(night.patch_irradiance[0].iter().all(|&e| e == 0.0));
    let flux = |l: &ChannelLight| -> f64 {
        scene
            .patches
            .iter()
            .zip(&l.patch_irradiance[0])
            .map(|(p, e)| p.area * e)
            .sum()
    };
    // The overhang's shadow clipped exactly: measured 0 to the last digit (2e-3 when shadow
    // edges were a quadrature's, resolved to 1/256 of a patch).
    assert!(
        relative(flux(&under), 0.5 * flux(&full)) < 1e-9,
        "{} against half of {}",
        flux(&under),
        flux(&full)
    );
    // The uniform sky: seen from (x, 1.5, 0.5) the overhang's edge falls on the window at
    // z_cut = 0.5 + 1.5 / (1 + 1/1.5) = 1.4 m; below it the sky, above it the overhang.
    overhang(&mut scene);
    let r = sky::response(&scene, &occ, SkyPatches::TREGENZA, &opts, &unit);
    let x = scene.sensors[0].position;
    let n = scene.sensors[0].normal;
    let sky = PI * window_form_factor(x, n, 1.0, 1.4);
    let hidden = PI * window_form_factor(x, n, 1.4, 2.0);
    let (got_sky, got_exterior) = (uniform_sky(&r, 0), r.exterior.output_irradiance[0][0]);
    // The overhang's edge is a discontinuity across the window cells, resolved to
    // `edge_angle` (0.02 rad, 3 cm cells at this distance): measured 3.9e-3 of the sky.
    assert!(relative(got_sky, sky) < 5e-3, "sky {got_sky} against {sky}");
    assert!(
        relative(got_exterior, 0.5 * hidden) < 5e-3,
        "overhang {got_exterior} against {}",
        0.5 * hidden
    );
}

/// Calls `f(point)` at the centroids of the `n²` equal triangles each triangle of the
/// convex polygon's fan is cut into, with the share of the polygon's area each stands for.
fn over_fan(corners: &[Vec3], n: usize, f: &mut dyn FnMut(Vec3, f64)) {
    let area = |a: Vec3, b: Vec3, c: Vec3| 0.5 * (b - a).cross(c - a).length();
    let total: f64 = (1..corners.len() - 1)
        .map(|k| area(corners[0], corners[k], corners[k + 1]))
        .sum();
    for k in 1..corners.len() - 1 {
        let (a, b, c) = (corners[0], corners[k], corners[k + 1]);
        let w = area(a, b, c) / total / (n * n) as f64;
        let at = |i: f64, j: f64| a + (b - a) * (i / n as f64) + (c - a) * (j / n as f64);
        for i in 0..n {
            for j in 0..n - i {
                f(at(i as f64 + 1.0 / 3.0, j as f64 + 1.0 / 3.0), w);
                if j + 1 < n - i {
                    f(at(i as f64 + 2.0 / 3.0, j as f64 + 2.0 / 3.0), w);
                }
            }
        }
    }
}

/// The sun patch less the shadows of a pillar in the room, a short overhang and a fin
/// outside, against a grid of rays: on every patch, the share of `over_fan`'s points (80 × 80
/// triangles a fan triangle) whose ray towards the sun crosses the window, then no room
/// surface (`Occluders::visible`) and no obstruction (`Outside::sun_reaches`), times
/// `τ cos θ`. The rays' own error along a shadow's edge is about a row of their triangles:
/// under 1/160 of a patch's irradiance.
#[test]
fn shadows_inside_and_outside_agree_with_a_grid_of_rays() {
    let window_and_pillar = r#"
[[quad]]
name = "window"
material = "glass"
corners = [[1, 0, 1], [1, 0, 2], [3, 0, 2], [3, 0, 1]]

[[block]]
name = "pillar"
min = [1.6, 0.8, 0]
max = [1.9, 1.1, 2.5]
material = "wall"
bottom = false
top = false
"#;
    let mut scene = daylit(room_with(window_and_pillar, "", 0.5), clear(), 0.0, 0.2);
    let quad = |c: [[f64; 3]; 4]| Face {
        polygon: Polygon::new(c.iter().map(|&[x, y, z]| Vec3::new(x, y, z)).collect()),
        patches: 0..0,
    };
    scene.obstructions = vec![Obstruction {
        name: "shades".into(),
        faces: vec![
            quad([
                [1.5, 0.0, 2.1],
                [2.6, 0.0, 2.1],
                [2.6, -0.5, 2.1],
                [1.5, -0.5, 2.1],
            ]),
            quad([
                [2.2, 0.0, 0.5],
                [2.2, -0.4, 0.5],
                [2.2, -0.4, 2.2],
                [2.2, 0.0, 2.2],
            ]),
        ],
        reflectance: 0.3,
    }];
    let occ = occluders(&scene);
    let outside = Outside::new(&scene, SkyPatches::TREGENZA, 0.0, 0.2);
    let window = &scene.surfaces[scene.windows[0].surface];
    let glazing = clear();
    let mut partly_lit = 0;
    for s in [Vec3::new(0.3, -1.0, 0.8), Vec3::new(-0.6, -1.0, 0.45)] {
        let s = s.normalized();
        let light = sun_light(&scene, &occ, s, &DaylightOptions::default());
        let tau = f64::from(glazing.transmittance(s.y.abs().acos() as f32));
        for (i, p) in scene.patches.iter().enumerate() {
            let cos = p.normal.dot(s);
            if cos <= 0.0 || window.patch_range.contains(&i) {
                continue;
            }
            let mut lit = 0.0;
            over_fan(&p.polygon.vertices, 80, &mut |x, w| {
                // The window lies in y = 0, x from 1 to 3, z from 1 to 2.
                let y = x + s * (-x.y / s.y);
                let Some(pane) = window.patch_range.clone().find(|&j| {
                    let v = &scene.patches[j].polygon.vertices;
                    let (lo, hi) = v.iter().fold((v[0], v[0]), |(lo, hi), c| {
                        (
                            Vec3::new(lo.x.min(c.x), 0.0, lo.z.min(c.z)),
                            Vec3::new(hi.x.max(c.x), 0.0, hi.z.max(c.z)),
                        )
                    });
                    (lo.x..=hi.x).contains(&y.x) && (lo.z..=hi.z).contains(&y.z)
                }) else {
                    return;
                };
                if occ.visible(x, y, &[i, pane]) && outside.sun_reaches(y, s) {
                    lit += w;
                }
            });
            let rays = tau * cos * lit;
            let clipped = light.patch_irradiance[0][i];
            if lit > 0.01 && lit < 0.99 {
                partly_lit += 1;
            }
            assert!(
                (clipped - rays).abs() <= tau * cos / 160.0,
                "sun {:?}, patch {i} at {:?}: {clipped} lux per lux clipped, {rays} by rays",
                s.to_array(),
                p.centroid.to_array()
            );
        }
    }
    assert!(partly_lit >= 10, "{partly_lit} patches partly lit");
}

/// `H = 2π ∫₀^{π/2} τ(θ) cos θ sin θ dθ`, by Simpson's rule on 2000 intervals: the exitance a
/// window transmits under a uniform sky of 1 cd/m² filling its hemisphere.
fn hemispherical(glazing: &Glazing) -> f64 {
    let n = 2000;
    let h = std::f64::consts::FRAC_PI_2 / n as f64;
    let f = |t: f64| f64::from(glazing.transmittance(t as f32)) * t.cos() * t.sin();
    let mut s = f(0.0) + f(std::f64::consts::FRAC_PI_2);
    for k in 1..n {
        s += f(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    2.0 * PI * s * h / 3.0
}

#[test]
fn a_diffusing_window_emits_what_it_transmits_and_the_model_carries_it() {
    let sensors = r#"
[[sensor]]
name = "desk"
position = [2.0, 1.5, 0.75]
normal = [0, 0, 1]
"#;
    let ground = 0.25;
    let diffusing = Glazing::diffusing(0.8, 2).expect("a valid glazing");
    let scene = daylit(room(sensors, 0.5), diffusing, 20.0, ground);
    let occ = occluders(&scene);
    let opts = DaylightOptions::default();
    let r = sky_response(&scene, &occ, SkyPatches::TREGENZA, &opts);
    // A vertical window sees half the sky and half the ground: each H/2.
    let half = 0.5 * hemispherical(&diffusing);
    let window = &scene.surfaces[scene.windows[0].surface];
    for j in window.patch_range.clone() {
        let sky: f64 = r.sky.iter().map(|l| l.emission[0][j]).sum();
        let exterior = r.exterior.emission[0][j];
        assert!(
            relative(sky, half) < 1e-4,
            "patch {j}: sky {sky} against {half}"
        );
        assert!(
            relative(exterior, ground * half) < 1e-4,
            "patch {j}: {exterior}"
        );
    }
    // No other patch emits.
    let others = |l: &ChannelLight| {
        (0..scene.patches.len())
            .filter(|i| !window.patch_range.contains(i))
            .all(|i| l.emission[0][i] == 0.0)
    };
    assert!(r.sky.iter().all(others) && others(&r.exterior));
    // The sun: τ(θ_w) cos θ_w on every window patch, Lambertian from there.
    let s = Vec3::new(0.3, -1.0, 1.2).normalized();
    let sun = sun_light(&scene, &occ, s, &opts);
    let cos_w = s.y.abs();
    let expected = f64::from(diffusing.transmittance(cos_w.acos() as f32)) * cos_w;
    for j in window.patch_range.clone() {
        assert!(relative(sun.emission[0][j], expected) < 1e-12);
    }
    // Its direct light is its emission through the form factors: nothing external is left,
    // to the two quadratures' agreement.
    let ff =
        formfactor::patch_form_factors_with(&scene.patches, &occ, &FormFactorOptions::default());
    let area: Vec<f64> = scene.patches.iter().map(|p| p.area).collect();
    let g = exchange::exchange_areas(ff.matrix, &area);
    let rows =
        formfactor::outputs::output_rows(&scene, &g, &area, &occ, &FormFactorOptions::default());
    for (what, light) in [("sun", &sun), ("zenith patch", &r.sky[144])] {
        let scale = light.patch_irradiance[0]
            .iter()
            .fold(0.0, |m: f64, e| m.max(e.abs()));
        assert!(scale > 0.0);
        let rest = light.external(&g, &area, &rows);
        let worst = |v: &Option<Vec<f64>>| {
            v.as_ref()
                .map_or(0.0, |v| v.iter().fold(0.0, |m: f64, e| m.max(e.abs())))
        };
        let (on_patches, at_outputs) = (worst(&rest.patches[0]), worst(&rest.outputs[0]));
        assert!(
            on_patches < 1e-4 * scale && at_outputs < 1e-4 * scale,
            "{what}: {on_patches:.2e} on patches, {at_outputs:.2e} at outputs, of {scale:.3e}"
        );
    }
}

#[test]
fn north_turns_the_sky_and_the_answer_is_deterministic() {
    let sensors = r#"
[[sensor]]
name = "facing"
position = [2.0, 2.5, 1.5]
normal = [0, -1, 0]
"#;
    let opts = DaylightOptions::default();
    // The window looks out along −y: south with north = 0, west with north = 90.
    for (north, azimuth) in [(0.0f64, 180.0f64), (90.0, 270.0)] {
        let scene = daylit(room(sensors, 0.5), clear(), north, 0.2);
        let occ = occluders(&scene);
        let r = sky_response(&scene, &occ, SkyPatches::TREGENZA, &opts);
        let brightest = (0..r.sky.len())
            .max_by(|&a, &b| {
                r.sky[a].output_irradiance[0][0].total_cmp(&r.sky[b].output_irradiance[0][0])
            })
            .expect("patches");
        let p = SkyPatches::TREGENZA.patch(brightest).expect("a patch");
        let off = (f64::from(p.azimuth).to_degrees() - azimuth).abs();
        assert!(
            off < 15.0,
            "north {north}: brightest patch {brightest} at {:?}",
            p
        );
        // Same inputs, same bits.
        let again = sky_response(&scene, &occ, SkyPatches::TREGENZA, &opts);
        assert_eq!(r, again);
        let s = Vec3::new(0.2, -0.8, 0.6).normalized();
        assert_eq!(
            sun_light(&scene, &occ, s, &opts),
            sun_light(&scene, &occ, s, &opts)
        );
    }
    // The sun's light and the sky's of the module with the glazing's τ are the internal
    // functions with that τ.
    let scene = daylit(room(sensors, 0.5), clear(), 0.0, 0.2);
    let occ = occluders(&scene);
    let s = Vec3::new(0.2, -0.8, 0.6).normalized();
    assert_eq!(
        sun_light(&scene, &occ, s, &opts),
        sun::light(&scene, &occ, s, &opts, &super::super::glazing(&scene))
    );
}

/// The sky's tabulated transmittance against the glazing's own, for one and three panes.
#[test]
fn the_tabulated_transmittance_is_the_glazings() {
    let mut scene = daylit(room("", 0.5), clear(), 0.0, 0.2);
    let occ = occluders(&scene);
    let opts = DaylightOptions::default();
    for glazing in [Glazing::clear(0.9, 1), Glazing::clear(0.6, 3)] {
        scene.windows[0].glazing = glazing.expect("a valid glazing");
        let tau = super::super::glazing(&scene);
        let outside = Outside::new(&scene, SkyPatches::TREGENZA, 0.0, 0.2);
        let ctx = Ctx::new(&scene, &occ, outside, &opts, &tau);
        let worst = (0..=10_000)
            .map(|k| {
                let cos = k as f64 / 10_000.0;
                (ctx.tabulated(0, cos) - ctx.transmittance(0, cos)).abs()
            })
            .fold(0.0, f64::max);
        // Measured 9.5e-6 at worst, at grazing incidence where τ bends fastest.
        assert!(worst < 2e-5, "{worst:.2e}");
    }
}

/// The example office with its window made a window of `glazing`.
fn office(glazing: Glazing, ground: f64) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/office/scene.toml");
    let scene = scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    daylit(scene, glazing, 0.0, ground)
}

/// A closed room receives all the light its window lets in, desks' shadows and all: from a
/// uniform sky and ground of 1 cd/m² (τ ≡ 1) `π A_w`, the window's area times π; from the sun
/// `E_n τ(θ_w) A_w cos θ_w`.
#[test]
fn the_office_receives_what_its_window_lets_in() {
    let scene = office(Glazing::clear(0.7, 2).expect("a valid glazing"), 1.0);
    let occ = occluders(&scene);
    let opts = DaylightOptions::default();
    let window = &scene.surfaces[scene.windows[0].surface];
    let a_w: f64 = window
        .patch_range
        .clone()
        .map(|i| scene.patches[i].area)
        .sum();
    assert!(relative(a_w, 2.8) < 1e-12);
    let flux = |l: &ChannelLight| -> f64 {
        scene
            .patches
            .iter()
            .zip(&l.patch_irradiance[0])
            .map(|(p, e)| p.area * e)
            .sum()
    };
    for s in [Vec3::new(0.3, -1.0, 1.2), Vec3::new(-0.8, -1.0, 0.4)] {
        let s = s.normalized();
        let light = sun_light(&scene, &occ, s, &opts);
        let cos_w = -s.y;
        let tau = f64::from(scene.windows[0].glazing.transmittance(cos_w.acos() as f32));
        let expected = tau * a_w * cos_w;
        // The sun patch and the desks' shadows on it clipped exactly: measured 1.1e-11 and
        // 1.2e-10 (1.7e-5 on the desks' side when their shadows were a quadrature's).
        let error = relative(flux(&light), expected);
        assert!(
            error < 1e-8,
            "sun {:?}: {} lm against {expected} ({error:.2e})",
            s.to_array(),
            flux(&light)
        );
    }
    let r = sky::response(&scene, &occ, SkyPatches::TREGENZA, &opts, &unit);
    let total = r.sky.iter().map(&flux).sum::<f64>() + flux(&r.exterior);
    // Measured 4.3e-5: the patches' rules near the window.
    let error = relative(total, PI * a_w);
    assert!(
        error < 2e-4,
        "sky and ground: {total} lm against {} ({error:.2e})",
        PI * a_w
    );
}
