//! Properties of the level solver (`eigenrad_runtime::target`) over arbitrary input: any
//! numbers (NaN, infinities, huge, negative), any lengths, up to one past every capacity.
//! Nothing panics, invalid input is refused when added, and every solve of accepted input
//! writes levels in [0, 1] and returns a solution, the closest levels with `BoundUnmet`, or
//! (never seen) `PivotLimit`, with a finite power and finite readings.
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::panic)]

use eigenrad_runtime::target::{MAX_BOUNDS, MAX_CONTROLS};
use eigenrad_runtime::{Error, LevelProblem};
use proptest::prelude::*;

/// Any f32 now and then, else a plausible value in lux or W.
fn number() -> impl Strategy<Value = f32> {
    prop_oneof![
        8 => 0.0f32..2000.0,
        1 => any::<f32>(),
        1 => prop::sample::select(vec![0.0f32, -1.0, 1.0e9, 2.0e9, f32::INFINITY, f32::NAN]),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    #[test]
    fn any_input_is_refused_or_solved(
        weights in prop::collection::vec(number(), 0..=MAX_CONTROLS + 1),
        bounds in prop::collection::vec(
            (prop::collection::vec(number(), 0..=MAX_CONTROLS + 1), number(), number(), number()),
            0..=MAX_BOUNDS + 1,
        ),
    ) {
        let Ok(mut problem) = LevelProblem::new(&weights) else {
            return Ok(());
        };
        let m = weights.len();
        for (gains, ambient, lower, upper) in &bounds {
            // The gain list is cut or padded to the channel count half the time.
            let mut g = gains.clone();
            if gains.len() % 2 == 0 {
                g.resize(m, 1.0);
            }
            let _ = problem.add_bound(&g, *ambient, *lower, *upper);
        }
        let mut levels = vec![f32::NAN; m];
        let result = problem.solve(&mut levels);
        match result {
            Ok(_) | Err(Error::BoundUnmet { .. }) | Err(Error::PivotLimit { .. }) => {}
            Err(e) => panic!("unexpected {e:?}"),
        }
        prop_assert!(levels.iter().all(|l| (0.0..=1.0).contains(l)), "{levels:?}");
        if let Ok(s) = result {
            prop_assert!(s.power.is_finite() && s.power >= 0.0);
            for j in 0..problem.bound_count() {
                prop_assert!(problem.reading(j, &levels).unwrap().is_finite());
            }
        }
    }
}
