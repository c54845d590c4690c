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
    let window = r#"
[[quad]]
name = "window"
material = "glass"
corners = [[1, 0, 1], [1, 0, 2], [3, 0, 2], [3, 0, 1]]
"#;
    room_with(window, sensors, max_edge)
}

/// The 4 m × 3 m × 2.5 m room of [`room`] with the surface `window` (TOML, named `window`) as
/// its opening, and the sensors given as TOML.
fn room_with(window: &str, sensors: &str, max_edge: f64) -> Scene {
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
{window}
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

/// A triangular window (base 2 m at the sill z = 1 m, apex at 2.2 m), cut out of its wall as
/// a polygon: a uniform sky at a point below the sill is π times the point's form factor to
/// the triangle (the exact Lambert contour integral, `formfactor::point_form_factors` on that
/// one triangle, nothing occluding), within the cells' quadrature tolerance [`SMOOTH`].
#[test]
fn a_uniform_sky_through_a_triangular_window_is_pi_times_its_form_factor() {
    let window = r#"
[[polygon]]
name = "window"
material = "glass"
vertices = [[1, 0, 1], [2, 0, 2.2], [3, 0, 1]]
"#;
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
    let scene = daylit(room_with(window, sensors, 0.5), clear(), 0.0, 0.7);
    let triangle = Patch::new(
        Polygon::new(vec![
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(2.0, 0.0, 2.2),
            Vec3::new(3.0, 0.0, 1.0),
        ]),
        0,
    );
    // The window's patches are the triangle, whole: 1.2 m², none left behind the wall.
    assert!((scene.surface_area("window").unwrap() - 1.2).abs() < 1e-12);
    let wall = 4.0 * 2.5 - 1.2;
    assert!((scene.surface_area("room.wall_ymin").unwrap() - wall).abs() < 1e-9 * wall);
    let r = sky::response(
        &scene,
        &occluders(&scene),
        SkyPatches::TREGENZA,
        &DaylightOptions::default(),
        &unit,
    );
    for (o, s) in scene.sensors.iter().enumerate() {
        let exact = PI
            * formfactor::point_form_factors(
                s.position,
                s.normal,
                scene::FieldOfView::HEMISPHERE,
                std::slice::from_ref(&triangle),
                &Occluders::new(&[]),
            )[0];
        let sum = uniform_sky(&r, o);
        println!(
            "{}: {sum:.6} lux, π F = {exact:.6} lux, rel. err {:.1e}",
            s.name,
            relative(sum, exact)
        );
        assert!(
            relative(sum, exact) < SMOOTH,
            "{}: {sum} lux against π F = {exact}",
            s.name
        );
        assert_eq!(r.exterior.output_irradiance[0][o], 0.0, "{}", s.name);
    }
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

/// A sensor's response weighs the sky it sees: under a uniform sky the daylight quadrature
/// (window cells, each point weighted by `S(θ)`) equals π times the window's view through
/// the response (`formfactor::point_form_factors`: exact cone form factors weighted ring by
/// ring), two independent paths.
#[test]
fn a_sensor_response_weighs_the_sky() {
    let sensors = r#"
[[sensor]]
name = "shielded"
position = [2.0, 1.5, 0.4]
normal = [0, -0.6, 0.8]
response = { preset = "shielded", cutoff = 50 }
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
    let Some(response) = &s.response else {
        panic!("the sensor has a response");
    };
    let seen = formfactor::point_form_factors(
        s.position,
        s.normal,
        scene::FieldOfView::response(response),
        &[window],
        &Occluders::new(&[]),
    )[0];
    let got = uniform_sky(&r, 0);
    let error = relative(got, PI * seen);
    println!(
        "shielded sensor under a uniform sky: {got} against {} ({error:.2e})",
        PI * seen
    );
    // Measured 1.4e-4: the window cells' quadrature of a sensitivity with a kink at the
    // cut-off, and the rings' constant weight across 1°.
    assert!(error < 2e-3, "{got} against {} ({error:.2e})", PI * seen);
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

/// A sky-patch boundary that runs between a window cell's outermost Gauss points and its
/// edge: the cell's points all see one patch, its corners the other. The overcast sky's
/// component at a point 2.5 m from the window, against a fine midpoint rule over the window
/// that classifies every one of its points by the same sky patches (so only the refinement
/// differs).
///
/// The sensor faces up, level with nothing, 2.5 m in front of the window's middle; its
/// height puts the Tregenza boundary at 24° of altitude at z = 1.51 m straight ahead. The
/// window's 0.5 m patches are cut once for their distance into 0.25 m cells, one row of which
/// starts at z = 1.5 m: its outermost Gauss points (order 3) lie 0.028 m above that edge,
/// so the boundary falls between them and the edge over the middle 0.9 m of the window.
#[test]
fn a_sky_patch_boundary_between_the_outer_points_and_the_cell_edge_is_resolved() {
    let height = 1.51 - 2.5 * 24f64.to_radians().tan();
    let sensors = format!(
        r#"
[[sensor]]
name = "desk"
position = [2.0, 2.5, {height}]
normal = [0, 0, 1]
"#
    );
    let scene = daylit(room(&sensors, 0.5), clear(), 0.0, 0.0);
    let occ = occluders(&scene);
    let patches = SkyPatches::TREGENZA;
    let r = sky::response(&scene, &occ, patches, &DaylightOptions::default(), &unit);
    let luminance = |k: usize| overcast(patches, k);
    let ours: f64 = (0..patches.count())
        .map(|k| luminance(k) * r.sky[k].output_irradiance[0][0])
        .sum();
    // The midpoint rule on 1 mm squares of the 2 m × 1 m window: E = Σ L cos θ_x cos θ_w / r² dA
    // (τ ≡ 1, nothing in the room between), each point in the patch its ray continues to.
    let site = scene.site.as_ref().expect("a site");
    let outside = Outside::new(&scene, patches, site.north, site.ground_reflectance);
    let x = scene.sensors[0].position;
    let (nx, nz) = (2000, 1000);
    let da = (2.0 / nx as f64) * (1.0 / nz as f64);
    let mut reference = 0.0;
    for i in 0..nx {
        for j in 0..nz {
            let y = Vec3::new(
                1.0 + 2.0 * (i as f64 + 0.5) / nx as f64,
                0.0,
                1.0 + (j as f64 + 0.5) / nz as f64,
            );
            let d = y - x;
            let r2 = d.dot(d);
            let dir = d / r2.sqrt();
            let (cos_x, cos_w) = (dir.z, -dir.y);
            if let super::outside::Seen::Sky(k) = outside.seen(y, dir) {
                reference += luminance(k) * cos_x * cos_w / r2 * da;
            }
        }
    }
    // Measured: 9.1e-5 (the midpoint rule's own error among it: its cells are 1 mm). Without
    // the corners' test the strip is counted in the patch above and the component is 6.2e-4
    // high.
    let error = relative(ours, reference);
    println!("overcast component {ours:.6e} against {reference:.6e}: {error:.2e}");
    assert!(
        error < 3e-4,
        "overcast component {ours:.6e} against the midpoint rule's {reference:.6e} ({error:.2e})"
    );
}

mod sun_and_glazing;

/// CIE traditional overcast sky (Moon and Spencer 1942; CIE S 011 type 16), relative to the
/// zenith: L(γ) = (1 + 2 sin γ) / 3 at sky patch `k`'s centre altitude γ.
fn overcast(patches: SkyPatches, k: usize) -> f64 {
    let p = patches.patch(k).expect("a patch");
    let centre = 0.5 * f64::from(p.altitude[0] + p.altitude[1]);
    (1.0 + 2.0 * centre.sin()) / 3.0
}

/// Points next to the window's own plane (0.2 mm, 2 mm and 2 cm in front of the wall, under
/// the sill and beside the window), where the window is seen almost edge-on and all the sky's
/// patches crowd into thin strips of it. Their overcast sky component against a midpoint rule on
/// 1 mm squares of the window that classifies every point by the same sky patches, and their
/// uniform sky (the sum over the patches) against π times the exact form factor
/// (`formfactor::point_form_factors`, Lambert's contour integral), split at the horizon.
#[test]
fn points_next_to_the_window_plane_agree_with_a_fine_quadrature() {
    let scene = daylit(room("", 0.5), clear(), 0.0, 0.0);
    let occ = occluders(&scene);
    let opts = DaylightOptions::default();
    let patches = SkyPatches::TREGENZA;
    let site = scene.site.as_ref().expect("a site");
    let outside = Outside::new(&scene, patches, site.north, site.ground_reflectance);
    let ctx = Ctx::new(&scene, &occ, outside, &opts, &unit);
    let outside = Outside::new(&scene, patches, site.north, site.ground_reflectance);
    let bins = patches.count() + 1;
    let up = Vec3::new(0.0, 0.0, 1.0);
    // Cells are split for the sky's boundaries by their solid angle (the apparent size), not
    // their angular diameter: measured 5.8e-5 at 0.2 mm from the wall; 6.6e-5, 2.9e-5 and
    // 1.5e-4 at the other points seen at usual incidence (7.7e-6, 5.1e-6 and 5.6e-6 with the angular diameter, at 10 to 40
    // times the cost), within the 3e-4 the boundary test above holds the quadrature to.
    // Where the window is seen within 1° of edge-on as a whole (beside it, 2 mm from its
    // plane) the component is 2.0e-3 from the reference (1.9e-5 with the angular diameter),
    // of a light 30 times weaker than under the window 2 mm from the wall (4.2e-4 against
    // 1.3e-2 lux per cd/m²): 7e-5 of that neighbour's.
    const EDGE_ON: f64 = 3e-3;
    for (x, normal, tolerance) in [
        // On the work plane under the window's middle, 0.2 m below the sill.
        (Vec3::new(2.0, 0.0002, 0.8), up, 3e-4),
        (Vec3::new(2.0, 0.002, 0.8), up, 3e-4),
        (Vec3::new(2.0, 0.02, 0.8), up, 3e-4),
        // Beside the window, level with its middle: the horizon cuts it.
        (Vec3::new(0.5, 0.002, 1.5), up, EDGE_ON),
        // Facing along the wall, towards the window.
        (Vec3::new(0.7, 0.02, 1.2), Vec3::new(1.0, 0.0, 0.0), 3e-4),
    ] {
        let start = std::time::Instant::now();
        let ours = ctx.sky_at_point(x, normal, scene::FieldOfView::HEMISPHERE, bins);
        let took = start.elapsed();
        let component: f64 = (0..patches.count())
            .map(|k| overcast(patches, k) * ours[k])
            .sum();
        let uniform: f64 = ours[..patches.count()].iter().sum();
        let (nx, nz) = (2000, 1000);
        let da = (2.0 / nx as f64) * (1.0 / nz as f64);
        let mut reference = 0.0;
        for i in 0..nx {
            for j in 0..nz {
                let y = Vec3::new(
                    1.0 + 2.0 * (i as f64 + 0.5) / nx as f64,
                    0.0,
                    1.0 + (j as f64 + 0.5) / nz as f64,
                );
                let d = y - x;
                let r2 = d.dot(d);
                let dir = d / r2.sqrt();
                let (cos_x, cos_w) = (normal.dot(dir), -dir.y);
                if cos_x <= 0.0 {
                    continue;
                }
                if let super::outside::Seen::Sky(k) = outside.seen(y, dir) {
                    reference += overcast(patches, k) * cos_x * cos_w / r2 * da;
                }
            }
        }
        let above = x.z.clamp(1.0, 2.0);
        let exact = PI * window_form_factor(x, normal, above, 2.0);
        let (error, smooth) = (relative(component, reference), relative(uniform, exact));
        println!(
            "{x:?}: overcast {component:.6e} against {reference:.6e} ({error:.2e}), \
             uniform {uniform:.6e} against π F {exact:.6e} ({smooth:.2e}), {took:?}"
        );
        assert!(
            error < tolerance,
            "{x:?}: overcast component {error:.2e} from the midpoint rule"
        );
        assert!(smooth < SMOOTH, "{x:?}: uniform sky {smooth:.2e} from π F");
    }
}

/// A receiving patch of the work plane that reaches the window wall (0.5 m × 0.25 m, under
/// the window's middle, 0.2 m below the sill), as the work plane's receivers with no margin
/// are: its mean under a uniform sky (τ ≡ 1, no ground) against the mean of π times the exact
/// form factor (Lambert's contour integral, `formfactor::point_form_factors`) by a fine
/// Gauss–Legendre rule over the patch, and its overcast sky component against a midpoint rule
/// over the patch of the point quadrature (itself held to a 1 mm midpoint rule over the
/// window by the test above).
#[test]
fn a_receiver_at_the_window_wall_is_its_area_mean() {
    let scene = daylit(room("", 0.5), clear(), 0.0, 0.0);
    let occ = occluders(&scene);
    let opts = DaylightOptions::default();
    let patches = SkyPatches::TREGENZA;
    let site = scene.site.as_ref().expect("a site");
    let outside = Outside::new(&scene, patches, site.north, site.ground_reflectance);
    let ctx = Ctx::new(&scene, &occ, outside, &opts, &unit);
    let bins = patches.count() + 1;
    let up = Vec3::new(0.0, 0.0, 1.0);
    let (x0, x1, y1, z) = (1.75, 2.25, 0.25, 0.8);
    let receiver = Patch::new(
        Polygon::new(vec![
            Vec3::new(x0, 0.0, z),
            Vec3::new(x1, 0.0, z),
            Vec3::new(x1, y1, z),
            Vec3::new(x0, y1, z),
        ]),
        0,
    );
    assert!((receiver.normal - up).length() < 1e-12);
    let start = std::time::Instant::now();
    let ours = ctx.sky_on_patch(&receiver, None, bins);
    let took = start.elapsed();
    let uniform: f64 = ours[..patches.count()].iter().sum();
    let component: f64 = (0..patches.count())
        .map(|k| overcast(patches, k) * ours[k])
        .sum();
    // π F by Gauss–Legendre of order 8 on 16 × 16 cells of the patch.
    let gl = formfactor::gauss_legendre(8);
    let n = 16;
    let mut exact = 0.0;
    for a in 0..n {
        for b in 0..n {
            for &(u, wu) in &gl {
                for &(v, wv) in &gl {
                    let x = Vec3::new(
                        x0 + (x1 - x0) * (a as f64 + u) / n as f64,
                        y1 * (b as f64 + v) / n as f64,
                        z,
                    );
                    exact += wu * wv * PI * window_form_factor(x, up, 1.0, 2.0);
                }
            }
        }
    }
    exact /= (n * n) as f64;
    // The overcast component by the midpoint rule on 24 × 24 points of the patch.
    let m = 24;
    let mut reference = 0.0;
    for a in 0..m {
        for b in 0..m {
            let x = Vec3::new(
                x0 + (x1 - x0) * (a as f64 + 0.5) / m as f64,
                y1 * (b as f64 + 0.5) / m as f64,
                z,
            );
            let e = ctx.sky_at_point(x, up, scene::FieldOfView::HEMISPHERE, bins);
            reference += (0..patches.count())
                .map(|k| overcast(patches, k) * e[k])
                .sum::<f64>()
                / (m * m) as f64;
        }
    }
    let (smooth, error) = (relative(uniform, exact), relative(component, reference));
    println!(
        "receiver at the wall: uniform {uniform:.6e} against π F {exact:.6e} ({smooth:.2e}), \
         overcast {component:.6e} against {reference:.6e} ({error:.2e}), {took:?}"
    );
    assert!(
        smooth < SMOOTH,
        "uniform sky {smooth:.2e} from the mean of π F"
    );
    // The patch rule against the midpoint rule, as for the patches of `a_patch_is_its_area_mean`.
    assert!(
        error < 5e-4,
        "overcast component {error:.2e} from the midpoint rule"
    );
}
