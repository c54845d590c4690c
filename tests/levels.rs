//! The runtime's least-power level solver (`eigenrad_runtime::target`) against an independent
//! host optimiser: `microlp` (a dual/primal simplex in f64, Apache-2.0, dev-dependency only)
//! solves the same linear programme, on hundreds of seeded random cases from synthetic gain
//! matrices and from the example office's basis, and hand-derived answers on tiny cases.
//!
//! Tolerances (the issue's): the same power within [`POWER_RTOL`] (relative), every bound met
//! within [`BOUND_RTOL`] of the reading's scale, and an infeasible case reported with the
//! right failing bound and the reference's least total violation.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;

use eigenrad::precompute::accuracy::rng::Rng;
use eigenrad::precompute::basis::basis_tables;
use eigenrad::precompute::formfactor::FormFactorOptions;
use eigenrad::precompute::pipeline::prepare;
use eigenrad::precompute::radiosity::eigen::{Formulation, Solver};
use eigenrad::precompute::radiosity::model::Model;
use eigenrad_runtime::target::{output_gains, MAX_BOUNDS, MAX_CONTROLS, MAX_PIVOTS};
use eigenrad_runtime::{Basis, ChannelEvaluator, Error, LevelProblem, Output, Precision};
use microlp::{ComparisonOp, OptimizationDirection, Problem};

/// Power of the runtime's levels against the reference optimum, relative (floor 1e-3 in the
/// weights' unit, for optima at or near 0).
const POWER_RTOL: f64 = 1e-4;
/// A bound is met when its violation is at most this fraction of the reading's scale: the
/// larger of the bound, the ambient and the row's largest gain (lux).
const BOUND_RTOL: f64 = 1e-5;
/// The reference calls a case infeasible when its least total violation exceeds this
/// fraction of the largest row scale; cases closer to the edge are skipped (either verdict is
/// right within rounding).
const EDGE_RTOL: f64 = 1e-4;

/// One problem in f64, as the reference sees it.
#[derive(Clone, Debug)]
struct Case {
    weights: Vec<f64>,
    /// Per bound: gains, ambient, lower, upper (lux; upper may be +∞).
    bounds: Vec<(Vec<f64>, f64, f64, f64)>,
}

impl Case {
    /// The values as the runtime holds them (f32), so both sides solve the same numbers.
    fn to_f32(&self) -> Case {
        let r = |x: f64| f64::from(x as f32);
        Case {
            weights: self.weights.iter().map(|&w| r(w)).collect(),
            bounds: self
                .bounds
                .iter()
                .map(|(g, a, l, u)| (g.iter().map(|&x| r(x)).collect(), r(*a), r(*l), r(*u)))
                .collect(),
        }
    }

    fn problem(&self) -> LevelProblem {
        let w: Vec<f32> = self.weights.iter().map(|&w| w as f32).collect();
        let mut p = LevelProblem::new(&w).unwrap();
        for (g, a, l, u) in &self.bounds {
            let g: Vec<f32> = g.iter().map(|&x| x as f32).collect();
            p.add_bound(&g, *a as f32, *l as f32, *u as f32).unwrap();
        }
        p
    }

    fn reading(&self, j: usize, x: &[f64]) -> f64 {
        let (g, a, ..) = &self.bounds[j];
        a + g.iter().zip(x).map(|(g, x)| g * x).sum::<f64>()
    }

    /// Violation of bound `j` at `x` (lux): shortfall below lower or excess above upper.
    fn violation(&self, j: usize, x: &[f64]) -> f64 {
        let (_, _, l, u) = &self.bounds[j];
        let r = self.reading(j, x);
        (l - r).max(0.0) + (r - u).max(0.0)
    }

    fn scale(&self, j: usize) -> f64 {
        let (g, a, l, u) = &self.bounds[j];
        let gmax = g.iter().fold(0.0f64, |m, &x| m.max(x.abs()));
        let u = if u.is_finite() { u.abs() } else { 0.0 };
        gmax.max(a.abs()).max(l.abs()).max(u).max(1.0)
    }

    fn power(&self, x: &[f64]) -> f64 {
        self.weights.iter().zip(x).map(|(w, x)| w * x).sum()
    }
}

/// The reference: microlp in f64. First the least total violation `V*` (elastic variables
/// per bound), then the least power with the total violation held at most `V*` (exactly 0
/// when feasible: the bounds as hard constraints), and the least power with it at most
/// `V* + slack` lux. Returns `(V*, levels, power, power with the slack)`.
fn reference(case: &Case, slack: f64) -> (f64, Vec<f64>, f64, f64) {
    let m = case.weights.len();
    let elastic = |objective_power: bool, cap: Option<f64>| {
        let mut lp = Problem::new(OptimizationDirection::Minimize);
        let xs: Vec<_> = (0..m)
            .map(|c| {
                lp.add_var(
                    if objective_power {
                        case.weights[c]
                    } else {
                        0.0
                    },
                    (0.0, 1.0),
                )
            })
            .collect();
        let mut slack = Vec::new();
        for (g, a, l, u) in &case.bounds {
            let q = lp.add_var(
                if objective_power { 0.0 } else { 1.0 },
                (0.0, f64::INFINITY),
            );
            let mut lower: Vec<_> = xs.iter().zip(g).map(|(&x, &g)| (x, g)).collect();
            lower.push((q, 1.0));
            lp.add_constraint(lower.as_slice(), ComparisonOp::Ge, l - a);
            slack.push(q);
            if u.is_finite() {
                let p = lp.add_var(
                    if objective_power { 0.0 } else { 1.0 },
                    (0.0, f64::INFINITY),
                );
                let mut upper: Vec<_> = xs.iter().zip(g).map(|(&x, &g)| (x, g)).collect();
                upper.push((p, -1.0));
                lp.add_constraint(upper.as_slice(), ComparisonOp::Le, u - a);
                slack.push(p);
            }
        }
        if let Some(cap) = cap {
            let total: Vec<_> = slack.iter().map(|&s| (s, 1.0)).collect();
            lp.add_constraint(total.as_slice(), ComparisonOp::Le, cap);
        }
        let solution = lp.solve().unwrap().into_solution().unwrap();
        let x: Vec<f64> = xs.iter().map(|&v| solution.var_value(v)).collect();
        (solution.objective(), x)
    };
    let (v, _) = elastic(false, None);
    let smax = (0..case.bounds.len()).fold(1.0f64, |s, j| s.max(case.scale(j)));
    let cap = if v <= 1e-9 * smax {
        0.0
    } else {
        v * (1.0 + 1e-9) + 1e-9 * smax
    };
    let (power, x) = elastic(true, Some(cap));
    let (loose, _) = if v <= 1e-9 * smax {
        (power, x.clone())
    } else {
        elastic(true, Some(cap + slack))
    };
    (v, x, power, loose)
}

/// What a comparison saw.
#[derive(Default, Debug)]
struct Tally {
    feasible: usize,
    infeasible: usize,
    skipped: usize,
    max_pivots: u32,
    worst_power: f64,
    worst_bound: f64,
}

/// Solves `case` with the runtime and checks it against the reference.
fn check(case: &Case, what: &str, tally: &mut Tally) {
    let case = case.to_f32();

    let m = case.weights.len();
    let smax = (0..case.bounds.len()).fold(1.0f64, |s, j| s.max(case.scale(j)));
    let slack = BOUND_RTOL * smax * case.bounds.len() as f64;
    let (v, _, ref_power, loose_power) = reference(&case, slack);
    let what = &format!("{what}: {case:?}");
    let mut levels = vec![-1.0f32; m];
    let got = case.problem().solve(&mut levels);
    assert!(
        levels.iter().all(|l| (0.0..=1.0).contains(l)),
        "{what}: levels {levels:?} outside [0, 1]"
    );
    let x: Vec<f64> = levels.iter().map(|&l| f64::from(l)).collect();
    let power = case.power(&x);
    let power_gap = (power - ref_power).abs() / ref_power.abs().max(1e-3);
    let total: f64 = (0..case.bounds.len()).map(|j| case.violation(j, &x)).sum();
    if v > EDGE_RTOL * smax {
        tally.infeasible += 1;
        let Err(Error::BoundUnmet { bound, upper, by }) = got else {
            panic!("{what}: reference least total violation {v:e} lux, runtime {got:?}");
        };
        // The least total violation, within the bound tolerance of the largest row.
        assert!(
            (total - v).abs() <= slack,
            "{what}: total violation {total:e} lux, reference {v:e}"
        );
        // The reported bound is the one most violated at the levels written, by the amount
        // and on the side reported.
        let worst = (0..case.bounds.len())
            .map(|j| case.violation(j, &x))
            .fold(0.0f64, f64::max);
        let own = case.violation(bound, &x);
        assert!(
            (own - worst).abs() <= BOUND_RTOL * smax,
            "{what}: reported bound {bound} violated by {own:e}, the worst by {worst:e}"
        );
        assert!(
            (f64::from(by) - own).abs() <= BOUND_RTOL * smax,
            "{what}: by {by} vs {own}"
        );
        let reading = case.reading(bound, &x);
        assert_eq!(upper, reading > case.bounds[bound].3, "{what}: side");
        // The least power among the closest levels. The set of least violation is
        // ill-conditioned (near-parallel rows make it jump with the last bit of a gain), so
        // the power is held between the reference's with the violation at most V* and at
        // most V* + slack, the violation the runtime's levels are allowed.
        let floor = loose_power.abs().max(1e-3);
        assert!(
            power <= ref_power + POWER_RTOL * ref_power.abs().max(1e-3)
                && power >= loose_power - POWER_RTOL * floor,
            "{what}: closest levels' power {power:e}, reference {ref_power:e} (with a \
             violation {slack:e} lux larger: {loose_power:e})"
        );
        let gap = if power > ref_power { power_gap } else { 0.0 };
        tally.worst_power = tally.worst_power.max(gap);
        return;
    }
    if v > 1e-9 * smax {
        tally.skipped += 1;
        return;
    }
    tally.feasible += 1;
    let solution = got.unwrap_or_else(|e| panic!("{what}: feasible case refused: {e}"));
    tally.max_pivots = tally.max_pivots.max(solution.pivots);
    for j in 0..case.bounds.len() {
        let rel = case.violation(j, &x) / case.scale(j);
        assert!(
            rel <= BOUND_RTOL,
            "{what}: bound {j} violated by {rel:e} of its scale"
        );
        tally.worst_bound = tally.worst_bound.max(rel);
    }
    assert!(
        power_gap <= POWER_RTOL,
        "{what}: power {power:e}, reference {ref_power:e} (relative {power_gap:e}), levels {x:?}"
    );
    assert!((f64::from(solution.power) - power).abs() <= 1e-5 * power.max(1e-3));
    tally.worst_power = tally.worst_power.max(power_gap);
}

/// A random problem: `m` channels, `r` bounds. Gains 0–1000 lux at level 1 (a fifth of them
/// 0), ambient 0–300 lux, lower bounds 0–900 lux, a third with an upper bound 0–600 lux
/// above the lower; weights 0.5–60 W. Some cases copy a row or a column, or zero a weight,
/// to make degenerate vertices and ties.
fn random_case(rng: &mut Rng, m: usize, r: usize) -> Case {
    let mut weights: Vec<f64> = (0..m).map(|_| rng.range(0.5, 60.0)).collect();
    let mut bounds: Vec<(Vec<f64>, f64, f64, f64)> = (0..r)
        .map(|_| {
            let g = (0..m)
                .map(|_| {
                    if rng.next_f64() < 0.2 {
                        0.0
                    } else {
                        rng.range(0.0, 1000.0)
                    }
                })
                .collect();
            let lower = rng.range(0.0, 900.0);
            let upper = if rng.next_f64() < 0.33 {
                lower + rng.range(0.0, 600.0)
            } else {
                f64::INFINITY
            };
            (g, rng.range(0.0, 300.0), lower, upper)
        })
        .collect();
    let pick = rng.next_f64();
    if pick < 0.1 && r > 1 {
        bounds[1] = bounds[0].clone();
    } else if pick < 0.2 && m > 1 {
        for b in &mut bounds {
            b.0[1] = b.0[0];
        }
        weights[1] = weights[0];
    } else if pick < 0.25 {
        weights[0] = 0.0;
    }
    Case { weights, bounds }
}

#[test]
fn random_synthetic_cases_match_the_reference_optimiser() {
    let mut rng = Rng(0x1e7e15);
    let mut tally = Tally::default();
    for k in 0..600 {
        let m = 1 + (rng.next_f64() * MAX_CONTROLS as f64) as usize;
        let r = 1 + (rng.next_f64() * MAX_BOUNDS as f64) as usize;
        let case = random_case(&mut rng, m.min(MAX_CONTROLS), r.min(MAX_BOUNDS));
        check(
            &case,
            &format!("case {k} ({m} channels, {r} bounds)"),
            &mut tally,
        );
    }
    eprintln!("synthetic: {tally:?}");
    // Both kinds of case are exercised.
    assert!(
        tally.feasible >= 150 && tally.infeasible >= 150,
        "{tally:?}"
    );
    assert!(tally.max_pivots < MAX_PIVOTS);
}

/// The full 16 × 16 size, with bounds low enough to be met (all feasible).
#[test]
fn full_size_cases_match_the_reference_optimiser() {
    let mut rng = Rng(0xf011);
    let mut tally = Tally::default();
    for k in 0..100 {
        let mut case = random_case(&mut rng, MAX_CONTROLS, MAX_BOUNDS);
        for b in &mut case.bounds {
            b.2 *= 0.5;
            b.3 = f64::INFINITY;
        }
        check(&case, &format!("full case {k}"), &mut tally);
    }
    eprintln!("full size: {tally:?}");
    assert!(tally.feasible >= 90, "{tally:?}");
}

/// The office example's basis: gains are its stored `output_channels`, checked against the
/// model's exact per-channel readings; the window channel's light is the ambient the
/// evaluator reports without the four luminaires.
#[test]
fn office_cases_match_the_reference_optimiser() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/office/scene.toml");
    let prepared = prepare(&path, &FormFactorOptions::default()).unwrap();
    let scene = &prepared.scene;
    let model = Model::new(&prepared.system, Formulation::Split, 8, Solver::Auto).unwrap();
    let bytes = basis_tables(scene, &model, 8, Precision::F32)
        .to_bytes()
        .unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let lums: Vec<usize> = ["lum1", "lum2", "lum3", "lum4"]
        .iter()
        .map(|n| basis.find_channel(n).unwrap())
        .collect();
    let window = basis.find_channel("window").unwrap();
    let s = basis.sensor_count();
    let outputs: Vec<Output> = (0..s)
        .map(Output::Sensor)
        .chain((0..basis.zone_count()).map(Output::Zone))
        .collect();
    // Gains per output (rows) and controlled channel, against the model's exact readings.
    let exact: Vec<Vec<f64>> = (0..basis.channel_count())
        .map(|c| model.channel_readings(c, 0))
        .collect();
    let mut gains = vec![vec![0.0f32; lums.len()]; outputs.len()];
    for (o, &out) in outputs.iter().enumerate() {
        output_gains(&basis, out, &lums, &mut gains[o]).unwrap();
        for (k, &c) in lums.iter().enumerate() {
            let want = exact[c][o];
            assert!((f64::from(gains[o][k]) - want).abs() <= 1e-6 * want.abs());
        }
    }
    let mut eval = ChannelEvaluator::<1, 8>::new(basis).unwrap();
    let mut rng = Rng(0x0ff1ce);
    let mut tally = Tally::default();
    for k in 0..200 {
        // Some luminaire levels (they must not matter) and a daylight level.
        let mut levels = vec![0.0f32; basis.channel_count()];
        for &c in &lums {
            levels[c] = rng.range(0.0, 1.0) as f32;
        }
        let daylight = rng.range(0.0, 1.0);
        levels[window] = daylight as f32;
        eval.set_channel_levels(&levels).unwrap();
        let weights: Vec<f64> = (0..lums.len()).map(|_| rng.range(20.0, 40.0)).collect();
        let mut bounds = Vec::new();
        for (o, &out) in outputs.iter().enumerate() {
            if rng.next_f64() < 0.25 {
                continue;
            }
            let ambient = eval.reading_without(out, &lums).unwrap();
            let want = f64::from(levels[window]) * exact[window][o];
            assert!(
                (f64::from(ambient) - want).abs() <= 1e-4 * want.abs().max(1.0),
                "ambient {ambient} lux, window alone {want} lux"
            );
            // A lower bound from a tenth of to a tenth above what every luminaire at full
            // gives with the daylight; a third of the outputs with an upper bound as well.
            let full = f64::from(ambient) + gains[o].iter().map(|&g| f64::from(g)).sum::<f64>();
            let lower = full * rng.range(0.1, 1.1);
            let upper = if rng.next_f64() < 0.3 {
                lower + full * rng.range(0.1, 1.0)
            } else {
                f64::INFINITY
            };
            let g = gains[o].iter().map(|&x| f64::from(x)).collect();
            bounds.push((g, f64::from(ambient), lower, upper));
        }
        if bounds.is_empty() {
            continue;
        }
        check(
            &Case { weights, bounds },
            &format!("office case {k}"),
            &mut tally,
        );
    }
    eprintln!("office: {tally:?}");
    assert!(tally.feasible >= 50 && tally.infeasible >= 10, "{tally:?}");
}

fn solve(case: &Case) -> (Result<f32, Error>, Vec<f32>) {
    let mut levels = vec![0.0f32; case.weights.len()];
    let r = case.problem().solve(&mut levels).map(|s| s.power);
    (r, levels)
}

fn case(weights: &[f64], bounds: &[(&[f64], f64, f64, f64)]) -> Case {
    Case {
        weights: weights.to_vec(),
        bounds: bounds
            .iter()
            .map(|(g, a, l, u)| (g.to_vec(), *a, *l, *u))
            .collect(),
    }
}

fn close(a: f32, b: f64) -> bool {
    (f64::from(a) - b).abs() <= 1e-5 * b.abs().max(1.0)
}

/// Hand-derived answers.
#[test]
fn tiny_cases_have_the_answers_derived_by_hand() {
    let inf = f64::INFINITY;
    // One channel of 800 lux at level 1, 100 lux of daylight, at least 500 lux, 10 W:
    // 100 + 800 x = 500 gives x = 0.5, 5 W.
    let (r, x) = solve(&case(&[10.0], &[(&[800.0], 100.0, 500.0, inf)]));
    assert!(close(r.unwrap(), 5.0) && close(x[0], 0.5), "{r:?} {x:?}");

    // The same channel gives 300 lux: at full, 400 lux, 100 lux short of 500.
    let (r, x) = solve(&case(&[10.0], &[(&[300.0], 100.0, 500.0, inf)]));
    let Err(Error::BoundUnmet {
        bound: 0,
        upper: false,
        by,
    }) = r
    else {
        panic!("{r:?}");
    };
    assert!(close(by, 100.0) && close(x[0], 1.0), "{by} {x:?}");

    // Daylight alone is enough: every level 0, 0 W.
    let (r, x) = solve(&case(&[10.0, 5.0], &[(&[800.0, 100.0], 600.0, 500.0, inf)]));
    assert_eq!((r.unwrap(), x), (0.0, vec![0.0, 0.0]));

    // Two channels, two zones, crossed gains 600/200 and 200/600 lux, both zones ≥ 400 lux.
    // Weights 1 and 1: the vertices of the feasible set are (1/2, 1/2) (both rows tight),
    // (1, 1/3), (1/3, 1) and (1, 1); the least a + b is at (1/2, 1/2), power 1.
    let rows: [(&[f64], f64, f64, f64); 2] = [
        (&[600.0, 200.0], 0.0, 400.0, inf),
        (&[200.0, 600.0], 0.0, 400.0, inf),
    ];
    let (r, x) = solve(&case(&[1.0, 1.0], &rows));
    assert!(
        close(r.unwrap(), 1.0) && close(x[0], 0.5) && close(x[1], 0.5),
        "{x:?}"
    );
    // Weights 1 and 4: along the tight second row, b = (2 − a)/3, the power a + 4b =
    // 8/3 − a/3 falls as a grows, to a = 1, b = 1/3 (the first row reads 666.7 ≥ 400):
    // power 7/3.
    let (r, x) = solve(&case(&[1.0, 4.0], &rows));
    assert!(close(r.unwrap(), 7.0 / 3.0) && close(x[0], 1.0) && close(x[1], 1.0 / 3.0));

    // An upper bound: 1000 lux per level on 300 lux of daylight, at least 600 lux and at
    // most 800 (two bounds on one reading): x in [0.3, 0.5], the least is 0.3.
    let (r, x) = solve(&case(
        &[2.0],
        &[
            (&[1000.0], 300.0, 600.0, inf),
            (&[1000.0], 300.0, 0.0, 800.0),
        ],
    ));
    assert!(close(r.unwrap(), 0.6) && close(x[0], 0.3), "{r:?} {x:?}");
    // Daylight alone above the upper bound: 900 > 800 whatever the level; the closest is
    // off, 100 lux over.
    let (r, x) = solve(&case(&[2.0], &[(&[1000.0], 900.0, 0.0, 800.0)]));
    let Err(Error::BoundUnmet {
        bound: 0,
        upper: true,
        by,
    }) = r
    else {
        panic!("{r:?}");
    };
    assert!(close(by, 100.0) && x[0] == 0.0, "{by} {x:?}");

    // Conflicting bounds on one reading 1000 x: ≥ 600 and ≤ 400. The total violation
    // max(0, 600 − 1000x) + max(0, 1000x − 400) is 200 lux for every x in [0.4, 0.6]; the
    // least power there is x = 0.4, where bound 0 is 200 lux short.
    let (r, x) = solve(&case(
        &[1.0],
        &[(&[1000.0], 0.0, 600.0, inf), (&[1000.0], 0.0, 0.0, 400.0)],
    ));
    let Err(Error::BoundUnmet {
        bound: 0,
        upper: false,
        by,
    }) = r
    else {
        panic!("{r:?}");
    };
    assert!(close(by, 200.0) && close(x[0], 0.4), "{by} {x:?}");
}

#[test]
fn bad_input_is_an_error_naming_it() {
    assert_eq!(
        LevelProblem::new(&[1.0, -1.0]).unwrap_err(),
        Error::InvalidInput { what: "weight" }
    );
    assert_eq!(
        LevelProblem::new(&[f32::NAN]).unwrap_err(),
        Error::InvalidInput { what: "weight" }
    );
    assert!(matches!(
        LevelProblem::new(&[1.0; MAX_CONTROLS + 1]),
        Err(Error::Capacity {
            what: "controlled channels",
            ..
        })
    ));
    let mut p = LevelProblem::new(&[1.0, 2.0]).unwrap();
    let inf = f32::INFINITY;
    assert_eq!(
        p.add_bound(&[1.0], 0.0, 1.0, inf),
        Err(Error::LengthMismatch {
            what: "gains",
            expected: 2,
            found: 1
        })
    );
    assert_eq!(
        p.add_bound(&[1.0, f32::NAN], 0.0, 1.0, inf),
        Err(Error::InvalidInput { what: "gain" })
    );
    assert_eq!(
        p.add_bound(&[1.0, 1.0], inf, 1.0, inf),
        Err(Error::InvalidInput { what: "ambient" })
    );
    assert_eq!(
        p.add_bound(&[1.0, 1.0], 0.0, -inf, inf),
        Err(Error::InvalidInput { what: "lower" })
    );
    assert_eq!(
        p.add_bound(&[1.0, 1.0], 0.0, 1.0, f32::NAN),
        Err(Error::InvalidInput { what: "upper" })
    );
    assert_eq!(
        p.add_bound(&[1.0, 1.0], 0.0, 5.0, 4.0),
        Err(Error::InvalidBound { bound: 0 })
    );
    for _ in 0..MAX_BOUNDS {
        p.add_bound(&[1.0, 1.0], 0.0, 1.0, inf).unwrap();
    }
    assert!(matches!(
        p.add_bound(&[1.0, 1.0], 0.0, 1.0, inf),
        Err(Error::Capacity { what: "bounds", .. })
    ));
    let mut short = [0.5f32];
    assert_eq!(
        p.solve(&mut short),
        Err(Error::LengthMismatch {
            what: "levels",
            expected: 2,
            found: 1
        })
    );
    assert_eq!(short, [0.5]);
    let mut ok = [0.0f32; 2];
    assert!(p.solve(&mut ok).is_ok());
    // The error says which bound failed and by how much.
    let msg = Error::BoundUnmet {
        bound: 3,
        upper: false,
        by: 12.5,
    }
    .to_string();
    assert!(
        msg.contains("bound 3") && msg.contains("1.25e1") && msg.contains("lower"),
        "{msg}"
    );
}

/// Many small cases (up to 4 channels and 4 bounds), where ties and degenerate vertices are
/// most frequent.
#[test]
fn small_cases_match_the_reference_optimiser() {
    let mut rng = Rng(0x5a11);
    let mut tally = Tally::default();
    for k in 0..1000 {
        let m = 1 + (rng.next_f64() * 4.0) as usize;
        let r = 1 + (rng.next_f64() * 4.0) as usize;
        let case = random_case(&mut rng, m, r);
        check(
            &case,
            &format!("small case {k} ({m} channels, {r} bounds)"),
            &mut tally,
        );
    }
    eprintln!("small: {tally:?}");
    assert!(
        tally.feasible >= 300 && tally.infeasible >= 300,
        "{tally:?}"
    );
}
