//! Daylight through windows against closed forms: a uniform sky through a window is π times
//! the window's form factor (Howell's catalogue; the project's exact Lambert contour
//! integral), split at the receiver's horizon between sky and ground; patch means against a
//! midpoint rule; the sun patch on the floor against the window's projection; an overhang's
//! shadow against the horizontal line it casts on the window; a diffusing window's exitance
//! against a one-dimensional integral of the glazing's transmittance; determinism.

use std::f64::consts::PI;
use std::path::Path;

use eigenrad_runtime::sky::glazing::Glazing;
use eigenrad_runtime::sky::patches::SkyPatches;

use super::outside::Outside;
use super::{sky, sky_response, sun, sun_light, Ctx, DaylightOptions, SkyResponse};
use crate::formfactor::{self, exchange, FormFactorOptions, Occluders};
use crate::geometry::{Face, Patch, Polygon, Vec3};
use crate::scene::{self, Obstruction, Scene, Site, Window};
use crate::sources::ChannelLight;

/// A 4 m × 3 m × 2.5 m room with a 2 m × 1 m window in the wall y = 0 (x from 1 to 3, sill
/// at 1 m, head at 2 m), facing into the room, and the sensors given as TOML.
fn room(sensors: &str, max_edge: f64) -> Scene {
    let text = format!(
        r#"[scene]
name = "daylit room"
bands = "photopic"
unit = "m"
max_edge = {max_edge}

[materials]
wall = {{ reflectance = 0.5 }}
glass = {{ reflectance = 0.0 }}

[[room]]
name = "room"
min = [0, 0, 0]
max = [4, 3, 2.5]
material = "wall"
openings = ["window"]

[[quad]]
name = "window"
material = "glass"
corners = [[1, 0, 1], [1, 0, 2], [3, 0, 2], [3, 0, 1]]

[[zone]]
name = "floor"
surfaces = ["room.floor"]

[[zone]]
name = "work_plane"
work_plane = {{ room = "room", height = 0.8, margin = 0.5, max_edge = 0.5 }}
{sensors}
"#
    );
    scene::parse(&text, Path::new("/nowhere/room.toml")).unwrap_or_else(|e| panic!("{e}"))
}

/// The room's window made a window of `glazing`, at a site with north `north` (degrees) and
/// ground reflectance `ground`.
fn daylit(mut scene: Scene, glazing: Glazing, north: f64, ground: f64) -> Scene {
    let surface = scene
        .surfaces
        .iter()
        .position(|s| s.name == "window")
        .expect("the window quad");
    scene.windows = vec![Window { surface, glazing }];
    scene.site = Some(Site {
        location: crate::daylight::sun::Site {
            latitude: 52.0,
            longitude: 5.0,
            elevation: 0.0,
        },
        north,
        utc_offset: Some(3600),
        ground_reflectance: ground,
    });
    scene
}

fn clear() -> Glazing {
    Glazing::clear(0.8, 2).expect("a valid glazing")
}

fn occluders(scene: &Scene) -> Occluders {
    Occluders::with_faces(&scene.patches, &scene.faces)
}

/// τ ≡ 1: the geometry alone.
fn unit(_: usize, _: f64) -> f64 {
    1.0
}

/// Form factor from a point (normal `normal`) to the part of the window between heights
/// `z0` and `z1` (m): Lambert's contour integral, the project's exact point-to-polygon form
/// factor (`formfactor::point_form_factors` on that one rectangle, nothing occluding).
fn window_form_factor(x: Vec3, normal: Vec3, z0: f64, z1: f64) -> f64 {
    let part = Patch::new(
        Polygon::new(vec![
            Vec3::new(1.0, 0.0, z0),
            Vec3::new(1.0, 0.0, z1),
            Vec3::new(3.0, 0.0, z1),
            Vec3::new(3.0, 0.0, z0),
        ]),
        0,
    );
    formfactor::point_form_factors(
        x,
        normal,
        scene::FieldOfView::HEMISPHERE,
        &[part],
        &Occluders::new(&[]),
    )[0]
}

/// Howell's catalogue, B-3: a point facing a parallel rectangle `[x1, x2] × [y1, y2]` at
/// distance `h` (coordinates in the rectangle's plane from the point's foot).
fn parallel_rectangle(x1: f64, x2: f64, y1: f64, y2: f64, h: f64) -> f64 {
    let f = |x: f64, y: f64| {
        let (a, b) = (x / h, y / h);
        let (sa, sb) = ((1.0 + a * a).sqrt(), (1.0 + b * b).sqrt());
        (a / sa * (b / sa).atan() + b / sb * (a / sb).atan()) / (2.0 * PI)
    };
    f(x2, y2) - f(x1, y2) - f(x2, y1) + f(x1, y1)
}

/// Sum over the sky patches of output `o`'s illuminance (a uniform sky of 1 cd/m²).
fn uniform_sky(r: &SkyResponse, o: usize) -> f64 {
    r.sky.iter().map(|l| l.output_irradiance[0][o]).sum()
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Quadrature tolerance of a uniform sky's total against the exact form factor: the window
/// cells' Gauss–Legendre rule on a smooth integrand (`(cell_angle/2)^(2 order)` ~ 4e-6 at
/// worst; measured 1e-9 at the sensors below the sill, 1.4e-5 for the floor's mean against
/// its midpoint reference).
const SMOOTH: f64 = 2e-5;

#[test]
fn a_uniform_sky_below_the_sill_is_pi_times_the_form_factor() {
    let sensors = r#"
[[sensor]]
name = "up"
position = [2.0, 1.0, 0.3]
normal = [0, 0, 1]

[[sensor]]
name = "facing"
position = [1.5, 2.0, 0.8]
normal = [0, -1, 0]

[[sensor]]
name = "oblique"
position = [3.5, 0.7, 0.5]
normal = [-0.6, -0.8, 0]
"#;
    let scene = daylit(room(sensors, 0.5), clear(), 0.0, 0.7);
    let occ = occluders(&scene);
    // Reinhart MF:2 (577 patches) only moves light between finer patches.
    let mf2 = sky::response(
        &scene,
        &occ,
        SkyPatches::reinhart(2).expect("MF:2"),
        &DaylightOptions::default(),
        &unit,
    );
    assert_eq!(mf2.sky.len(), 577);
    let r = sky::response(
        &scene,
        &occ,
        SkyPatches::TREGENZA,
        &DaylightOptions::default(),
        &unit,
    );
    assert_eq!(r.sky.len(), 145);
    for (o, s) in scene.sensors.iter().enumerate() {
        let exact = PI * window_form_factor(s.position, s.normal, 1.0, 2.0);
        assert!(
            relative(uniform_sky(&mf2, o), exact) < SMOOTH,
            "{} at MF:2",
            s.name
        );
    }
    for (o, s) in scene.sensors.iter().enumerate() {
        let exact = PI * window_form_factor(s.position, s.normal, 1.0, 2.0);
        let sum = uniform_sky(&r, o);
        assert!(
            relative(sum, exact) < SMOOTH,
            "{}: {sum} lux against π F = {exact}",
            s.name
        );
        // Every direction through the window rises: no ground.
        assert_eq!(r.exterior.output_irradiance[0][o], 0.0, "{}", s.name);
    }
    // The sensor facing the window: Howell B-3 for the parallel rectangle, independently.
    let b3 = parallel_rectangle(-0.5, 1.5, 0.2, 1.2, 2.0);
    assert!(relative(uniform_sky(&r, 1), PI * b3) < SMOOTH);
    // Patches and zones too: the floor's mean is π times the floor-to-window form factor,
    // here against the midpoint rule of the exact point form factor on a 200 × 200 grid.
    let floor_zone = scene.sensors.len();
    let n = 200;
    let mut mean = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = Vec3::new(
                4.0 * (i as f64 + 0.5) / n as f64,
                3.0 * (j as f64 + 0.5) / n as f64,
                0.0,
            );
            mean += window_form_factor(x, Vec3::new(0.0, 0.0, 1.0), 1.0, 2.0);
        }
    }
    let exact = PI * mean / (n * n) as f64;
    let zone = uniform_sky(&r, floor_zone);
    // The midpoint rule's own error on a smooth integrand: ~1e-5 at this grid.
    assert!(relative(zone, exact) < 1e-4, "floor {zone} against {exact}");
}

/// A sensor's field of view cuts the window: the sky it sees is π times the form factor of the
/// window within the cone (`formfactor::point_form_factors` with the half-angle: the cone as a
/// 64-sided pyramid, within 2e-5).
#[test]
fn a_sensor_sees_the_sky_within_its_half_angle() {
    let sensors = r#"
[[sensor]]
name = "narrow"
position = [2.0, 1.5, 0.4]
normal = [0, -0.6, 0.8]
half_angle = 30
"#;
    let scene = daylit(room(sensors, 0.5), clear(), 0.0, 0.0);
    let occ = occluders(&scene);
    let r = sky::response(
        &scene,
        &occ,
        SkyPatches::TREGENZA,
        &DaylightOptions::default(),
        &unit,
    );
    let s = &scene.sensors[0];
    let window = Patch::new(
        Polygon::new(vec![
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 2.0),
            Vec3::new(3.0, 0.0, 2.0),
            Vec3::new(3.0, 0.0, 1.0),
        ]),
        0,
    );
    let within = formfactor::point_form_factors(
        s.position,
        s.normal,
        scene::FieldOfView::cone(s.half_angle),
        &[window],
        &Occluders::new(&[]),
    )[0];
    let whole = window_form_factor(s.position, s.normal, 1.0, 2.0);
    assert!(within < 0.9 * whole, "the cone must cut the window");
    let got = uniform_sky(&r, 0);
    // The cone's edge is a discontinuity across the window cells, resolved to `edge_angle`:
    // measured 4.9e-4.
    let error = relative(got, PI * within);
    assert!(error < 2e-3, "{got} against {} ({error:.2e})", PI * within);
}

#[test]
fn sky_and_ground_add_up_where_the_window_straddles_the_horizon() {
    let sensors = r#"
[[sensor]]
name = "facing"
position = [2.5, 1.5, 1.4]
normal = [0, -1, 0]

[[sensor]]
name = "tilted"
position = [1.2, 2.2, 1.7]
normal = [0.3, -0.9, -0.3]
"#;
    let ground = 0.6;
    let scene = daylit(room(sensors, 0.5), clear(), 30.0, ground);
    let occ = occluders(&scene);
    let r = sky::response(
        &scene,
        &occ,
        SkyPatches::TREGENZA,
        &DaylightOptions::default(),
        &unit,
    );
    for (o, s) in scene.sensors.iter().enumerate() {
        // The horizon through the sensor cuts the window at the sensor's height.
        let h = s.position.z;
        let upper = PI * window_form_factor(s.position, s.normal, h, 2.0);
        let lower = PI * window_form_factor(s.position, s.normal, 1.0, h);
        let sky = uniform_sky(&r, o);
        let exterior = r.exterior.output_irradiance[0][o];
        assert!(
            relative(sky, upper) < SMOOTH,
            "{}: sky {sky} against {upper}",
            s.name
        );
        // The ground's edge is a discontinuity across the window cells: resolved to
        // `edge_angle`, measured 3e-5 here.
        assert!(
            relative(exterior, ground * lower) < 1e-4,
            "{}: ground {exterior} against {}",
            s.name,
            ground * lower
        );
        let total = PI * window_form_factor(s.position, s.normal, 1.0, 2.0);
        assert!(relative(sky + exterior / ground, total) < SMOOTH);
    }
}

#[test]
fn a_patch_is_its_area_mean() {
    let scene = daylit(room("", 0.5), clear(), 0.0, 0.3);
    let occ = occluders(&scene);
    let opts = DaylightOptions::default();
    let tau = super::glazing(&scene);
    let site = scene.site.as_ref().expect("a site");
    let outside = Outside::new(
        &scene,
        SkyPatches::TREGENZA,
        site.north,
        site.ground_reflectance,
    );
    let ctx = Ctx::new(&scene, &occ, outside, &opts, &tau);
    let bins = 146;
    // The floor patch nearest the window's middle, and the side wall's patch nearest it.
    let nearest = |name: &str| {
        let s = scene.surfaces.iter().find(|s| s.name == name).expect(name);
        s.patch_range
            .clone()
            .min_by(|&a, &b| {
                let d = |i: usize| (scene.patches[i].centroid - Vec3::new(2.0, 0.0, 1.5)).length();
                d(a).total_cmp(&d(b))
            })
            .expect("patches")
    };
    for name in ["room.floor", "room.wall_xmin"] {
        let i = nearest(name);
        let p = &scene.patches[i];
        let ours = ctx.sky_on_patch(p, Some(i), bins);
        // Midpoint rule on a 24 × 24 grid of the point illuminance (the same inner rule,
        // integrated over the patch independently of its cells).
        let v = &p.polygon.vertices;
        let (u, w) = (v[1] - v[0], v[3] - v[0]);
        let n = 24;
        let mut reference = vec![0.0; bins];
        for a in 0..n {
            for b in 0..n {
                let x =
                    v[0] + u * ((a as f64 + 0.5) / n as f64) + w * ((b as f64 + 0.5) / n as f64);
                let e = ctx.sky_at_point(x, p.normal, scene::FieldOfView::HEMISPHERE, bins);
                for (r, e) in reference.iter_mut().zip(e) {
                    *r += e / (n * n) as f64;
                }
            }
        }
        let total: f64 = reference.iter().sum();
        let worst = ours
            .iter()
            .zip(&reference)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let sum: f64 = ours.iter().sum();
        assert!(total > 0.0);
        // The receiving patch's rule (`receiver_order` 3 on cells of `receiver_cell_angle`
        // 0.5) against the midpoint rule: measured 2.5e-4 under the window, as with order 4
        // on cells of 0.1 (2.3e-4, the reference's own error). A sky patch's share moves
        // with the point (its edges sweep over the window), so single patches converge more
        // slowly: measured 5.4e-3 of the total at worst (the side wall).
        assert!(relative(sum, total) < 5e-4, "{name}: {sum} against {total}");
        println!("{name}: sum {sum:.6e} against {total:.6e}, worst sky patch {worst:.3e}");
        assert!(
            worst < 1e-2 * total,
            "{name}: worst patch {worst:.3e} of {total:.3e}"
        );
    }
}

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
    // Shadow edges resolved to 1/256 of a patch: 2e-3 of the flux.
    assert!(
        relative(flux(&under), 0.5 * flux(&full)) < 2e-3,
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
        sun::light(&scene, &occ, s, &opts, &super::glazing(&scene))
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
        let tau = super::glazing(&scene);
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
        // Shadow edges of the desks resolved to 1/256 of a patch: measured 2e-10 (the sun
        // patch on the floor only) and 1.7e-5 (on the desks, their shadows, the side wall).
        let error = relative(flux(&light), expected);
        assert!(
            error < 2e-4,
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
