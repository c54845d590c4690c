//! A build's stages as they run: each one timed for the report and, when standard error is a
//! log rather than a terminal (a file, a pipe, a CI job), announced there by one line at its
//! start with its expected time and one at its end with the time it took. Terminals get the
//! progress bars instead; the library is silent unless asked.

use std::io::Write as _;
use std::time::Instant;

use super::report::Stage;

/// How a build tells on standard error what it is doing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Narration {
    /// Nothing (the library's default: tests and benchmarks print their own).
    #[default]
    Silent,
    /// Standard error is a terminal: the build's plan before the form factors, then the
    /// progress bars of the long stages.
    Terminal,
    /// Standard error is a log: the build's plan, and a line at the start and at the end of
    /// every stage.
    Log,
}

impl Narration {
    /// Whether the build's plan (expected time, memory and flash) is printed.
    pub fn tells_plan(self) -> bool {
        self != Narration::Silent
    }

    /// Whether every stage prints its start and end lines.
    pub fn tells_stages(self) -> bool {
        self == Narration::Log
    }
}

/// Prefix of every line a build writes on standard error while it runs, so that a log mixing
/// several tools still says whose line it is.
pub const LINE_PREFIX: &str = "eigenrad build:";

/// Writes one line on standard error; a closed or full standard error is no reason to stop a
/// build, so a failed write is ignored.
pub fn tell(text: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{LINE_PREFIX} {text}");
}

/// The stages run so far, with their times.
pub(crate) struct Stages {
    timings: Vec<Stage>,
    narration: Narration,
}

impl Stages {
    pub(crate) fn new(narration: Narration) -> Self {
        Stages {
            timings: Vec::new(),
            narration,
        }
    }

    /// How this build narrates.
    pub(crate) fn narration(&self) -> Narration {
        self.narration
    }

    /// Runs `f` as the stage `stage`, expected to take about `expected` seconds (wall clock;
    /// `None` where the time model has no figure for it), and records how long it took.
    pub(crate) fn run<T>(
        &mut self,
        stage: &'static str,
        expected: Option<f64>,
        f: impl FnOnce() -> T,
    ) -> T {
        if self.narration.tells_stages() {
            let expected = match expected {
                Some(s) => format!("expected {}", seconds(s)),
                None => "no estimate".to_string(),
            };
            tell(&format!("{stage}: started, {expected}"));
        }
        let start = Instant::now();
        let out = f();
        let took = start.elapsed().as_secs_f64();
        if self.narration.tells_stages() {
            tell(&format!("{stage}: done in {}", seconds(took)));
        }
        self.timings.push(Stage {
            stage,
            seconds: took,
        });
        out
    }

    /// The stages' times, in the order they ran.
    pub(crate) fn into_timings(self) -> Vec<Stage> {
        self.timings
    }
}

/// A duration in seconds as a person reads it in a log: `0.4 s`, `12 s`, `3 min 20 s`.
pub fn seconds(s: f64) -> String {
    if !s.is_finite() || s < 0.0 {
        return format!("{s} s");
    }
    if s < 0.05 {
        "under 0.1 s".to_string()
    } else if s < 10.0 {
        format!("{s:.1} s")
    } else if s < 120.0 {
        format!("{s:.0} s")
    } else {
        let whole = s.round() as u64;
        format!("{} min {} s", whole / 60, whole % 60)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_read_in_the_unit_that_suits_them() {
        assert_eq!(seconds(0.04), "under 0.1 s");
        assert_eq!(seconds(3.26), "3.3 s");
        assert_eq!(seconds(87.3), "87 s");
        assert_eq!(seconds(200.0), "3 min 20 s");
        assert_eq!(seconds(3600.4), "60 min 0 s");
    }
}
