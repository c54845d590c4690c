//! The model alone: expansion, interpolation and flux against closed forms.

use std::f64::consts::PI;

use super::super::{Distribution, LampGeometry, Symmetry, Tilt};

fn steps(step: f64, to: f64) -> Vec<f64> {
    let n = (to / step).round() as usize;
    (0..=n).map(|k| k as f64 * step).collect()
}

fn rotational(gamma: Vec<f64>, f: impl Fn(f64) -> f64) -> Distribution {
    let plane = gamma.iter().map(|&g| f(g)).collect();
    Distribution::new(Symmetry::Rotational, &[0.0], gamma, vec![plane]).unwrap()
}

#[test]
fn isotropic_flux_is_four_pi_i_for_any_step() {
    for step in [90.0, 22.5, 10.0, 2.5] {
        let d = rotational(steps(step, 180.0), |_| 250.0);
        let exact = 4.0 * PI * 250.0;
        assert!(
            (d.flux() / exact - 1.0).abs() < 1e-12,
            "step {step}: {}",
            d.flux()
        );
        // Half of it downward, exactly.
        assert!((d.flux_between(0.0, 90.0) / (exact / 2.0) - 1.0).abs() < 1e-12);
    }
}

#[test]
fn lambertian_flux_is_pi_i0_within_the_interpolation_error() {
    // I = I0 cos γ, 0 beyond 90°: Φ = π I0. Linear interpolation of a concave profile lies
    // below it: the flux is short by about h²/12 of it (h the step in radians), and never by
    // more than h²/8.
    let i0 = 400.0;
    let mut last_error = f64::INFINITY;
    for step in [10.0, 5.0, 2.5, 1.0] {
        let d = rotational(steps(step, 90.0), |g: f64| i0 * g.to_radians().cos());
        let error = 1.0 - d.flux() / (PI * i0);
        let h2 = f64::to_radians(step).powi(2);
        assert!(
            error > 0.0 && error < h2 / 8.0,
            "step {step}: relative error {error}"
        );
        assert!(
            (error / (h2 / 12.0) - 1.0).abs() < 0.01,
            "step {step}: {error} vs h²/12"
        );
        assert!(
            error < last_error / 3.9 || step == 10.0,
            "second order in the step"
        );
        last_error = error;
    }
}

#[test]
fn flux_does_not_depend_on_how_the_planes_are_stored() {
    // The same rotationally symmetric distribution, stored as one plane or as four quadrant
    // planes at uneven angles, carries the same flux.
    let gamma = steps(10.0, 180.0);
    let f = |g: f64| 100.0 + 50.0 * g.to_radians().cos();
    let one = rotational(gamma.clone(), f);
    let planes = [0.0, 20.0, 50.0, 90.0];
    let rows = planes
        .iter()
        .map(|_| gamma.iter().map(|&g| f(g)).collect())
        .collect();
    let four = Distribution::new(Symmetry::Quadrant, &planes, gamma, rows).unwrap();
    assert!((one.flux() / four.flux() - 1.0).abs() < 1e-12);
}

/// A quadrant distribution stored at uneven planes, with distinct values on each.
fn quadrant() -> Distribution {
    let planes = [0.0, 20.0, 50.0, 90.0];
    let gamma = vec![0.0, 45.0, 90.0];
    let rows = planes
        .iter()
        .map(|&c| gamma.iter().map(|&g| 100.0 + c + g / 10.0).collect())
        .collect();
    Distribution::new(Symmetry::Quadrant, &planes, gamma, rows).unwrap()
}

#[test]
fn expansion_covers_the_circle_with_mirror_images() {
    let d = quadrant();
    let expected = [
        0.0, 20.0, 50.0, 90.0, 130.0, 160.0, 180.0, 200.0, 230.0, 270.0, 310.0, 340.0,
    ];
    assert_eq!(d.c_angles().len(), expected.len());
    for (a, e) in d.c_angles().iter().zip(expected) {
        assert!((a - e).abs() < 1e-9, "{:?}", d.c_angles());
    }
    // 130° is the image of 50° about the C90–C270 plane.
    assert_eq!(d.plane(4), d.plane(2));
}

#[test]
fn interpolation_is_bilinear_and_exact_at_the_nodes() {
    let d = quadrant();
    assert_eq!(d.intensity(20.0, 45.0), 124.5);
    // Midway between C 20° and 50° at γ 45°: the mean of 124.5 and 154.5.
    assert!((d.intensity(35.0, 45.0) - 139.5).abs() < 1e-12);
    // Midway in both: the mean of the four corners.
    let mean = (120.0 + 124.5 + 150.0 + 154.5) / 4.0;
    assert!((d.intensity(35.0, 22.5) - mean).abs() < 1e-12);
}

#[test]
fn interpolation_is_continuous_across_zero_and_the_symmetry_planes() {
    let d = quadrant();
    for gamma in [0.0, 10.0, 45.0, 77.0, 90.0] {
        for plane in [0.0, 90.0, 180.0, 270.0, 360.0] {
            let (below, above) = (
                d.intensity(plane - 1e-9, gamma),
                d.intensity(plane + 1e-9, gamma),
            );
            assert!(
                (below - above).abs() < 1e-6,
                "C {plane}, γ {gamma}: {below} vs {above}"
            );
        }
        // Mirror images agree everywhere, not only at the planes.
        for c in [3.0, 27.5, 61.0, 89.0] {
            let i = d.intensity(c, gamma);
            for image in [180.0 - c, 180.0 + c, 360.0 - c, -c, c + 360.0, c - 720.0] {
                assert!(
                    (d.intensity(image, gamma) - i).abs() < 1e-9,
                    "C {c} vs {image}"
                );
            }
        }
    }
}

#[test]
fn the_wrap_around_cell_is_a_cell_like_any_other() {
    // No symmetry, planes 10°…300°: between 300° and 370° the intensity runs linearly.
    let gamma = vec![0.0, 180.0];
    let planes = [10.0, 100.0, 300.0];
    let rows = vec![vec![10.0, 10.0], vec![50.0, 50.0], vec![80.0, 80.0]];
    let d = Distribution::new(Symmetry::None, &planes, gamma, rows).unwrap();
    assert!((d.intensity(335.0, 30.0) - 45.0).abs() < 1e-12);
    assert!((d.intensity(-25.0, 30.0) - 45.0).abs() < 1e-12);
    assert!((d.intensity(0.0, 30.0) - (80.0 + (10.0 - 80.0) * 60.0 / 70.0)).abs() < 1e-12);
    assert!((d.intensity(360.0 - 1e-12, 30.0) - d.intensity(0.0, 30.0)).abs() < 1e-9);
}

#[test]
fn intensity_is_zero_outside_the_tabulated_gamma_range() {
    let d = rotational(steps(10.0, 90.0), |_| 100.0);
    assert_eq!(d.intensity(0.0, 90.0), 100.0);
    assert_eq!(d.intensity(0.0, 90.5), 0.0);
    assert_eq!(d.intensity(45.0, 180.0), 0.0);
    let up = Distribution::new(
        Symmetry::Rotational,
        &[0.0],
        vec![90.0, 180.0],
        vec![vec![5.0, 7.0]],
    )
    .unwrap();
    assert_eq!(up.intensity(0.0, 89.0), 0.0);
    assert_eq!(up.intensity(0.0, 135.0), 6.0);
    assert!(up.intensity(f64::NAN, 100.0).is_nan());
    assert!(up.intensity(0.0, f64::INFINITY).is_nan());
}

#[test]
fn invalid_distributions_are_refused() {
    let g = vec![0.0, 90.0];
    let row = || vec![1.0, 1.0];
    let new = |s, planes: &[f64], gamma: Vec<f64>, rows| Distribution::new(s, planes, gamma, rows);
    assert!(new(
        Symmetry::Quadrant,
        &[0.0, 60.0],
        g.clone(),
        vec![row(), row()]
    )
    .is_err());
    assert!(new(Symmetry::AboutC0C180, &[0.0, 180.0], g.clone(), vec![row()]).is_err());
    assert!(new(Symmetry::None, &[0.0, 0.0], g.clone(), vec![row(), row()]).is_err());
    assert!(new(Symmetry::Rotational, &[0.0], vec![0.0], vec![vec![1.0]]).is_err());
    assert!(new(Symmetry::Rotational, &[0.0], vec![90.0, 0.0], vec![row()]).is_err());
    assert!(new(
        Symmetry::Rotational,
        &[0.0],
        g.clone(),
        vec![vec![1.0, -1.0]]
    )
    .is_err());
    assert!(new(Symmetry::Rotational, &[0.0], g, vec![vec![1.0, f64::NAN]]).is_err());
}

#[test]
fn tilt_factors_interpolate_and_hold_their_ends() {
    let tilt = Tilt {
        geometry: LampGeometry::Vertical,
        angles: vec![0.0, 30.0, 90.0],
        factors: vec![1.0, 0.9, 0.6],
    };
    assert_eq!(tilt.factor(-5.0), 1.0);
    assert!((tilt.factor(15.0) - 0.95).abs() < 1e-12);
    assert!((tilt.factor(60.0) - 0.75).abs() < 1e-12);
    assert_eq!(tilt.factor(120.0), 0.6);
}
