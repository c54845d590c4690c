//! The precompute's error type: every failure names the file, line, field or patch at fault.

use std::path::PathBuf;

/// Result with the precompute's [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

/// Everything that can stop a precompute command.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The scene file or a file it references is invalid.
    #[error(transparent)]
    Scene(#[from] crate::scene::SceneError),
    /// The eigensolver failed (non-convergence, bad input).
    #[error("eigensolver: {0}")]
    Eigen(#[from] crate::radiosity::eigen::EigenError),
    /// A basis file is unreadable or invalid.
    #[error("basis {}: {reason}", path.display())]
    Basis {
        /// The basis file.
        path: PathBuf,
        /// What the runtime's decoder or evaluator said.
        reason: eigenrad_runtime::Error,
    },
    /// The runtime refused a request while evaluating.
    #[error("runtime: {0}")]
    Runtime(#[from] eigenrad_runtime::Error),
    /// Reading or writing a file failed.
    #[error("{}: {reason}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        reason: std::io::Error,
    },
    /// A command was asked to write over a file it reads.
    #[error("{}: refusing to write over {}, an input of this command; choose another output path", output.display(), input.display())]
    OutputIsInput {
        /// The output path as given.
        output: PathBuf,
        /// The input it names.
        input: PathBuf,
    },
    /// Writing to standard output failed (a closed pipe is [`Error::ClosedPipe`]).
    #[error("standard output: {0}")]
    Stdout(std::io::Error),
    /// Standard output was closed by its reader (`| head`): the command stops quietly.
    #[error("standard output closed")]
    ClosedPipe,
    /// A `--level NAME=VALUE` or `--arc NAME=ARC` argument is wrong.
    #[error("{flag} {argument}: {reason}")]
    Level {
        /// `--level` or `--arc`.
        flag: &'static str,
        /// The argument as given.
        argument: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A command-line argument names something its inputs do not have (`simulate
    /// --heatmap-of daylight:ZONE` of a zone the basis lacks).
    #[error("{flag} {argument}: {reason}")]
    Argument {
        /// The flag, `--heatmap-of`.
        flag: &'static str,
        /// The argument as given.
        argument: String,
        /// What is wrong with it.
        reason: String,
    },
    /// `--tolerance` could not be met with the modes available.
    #[error("tolerance {tolerance} not reached with up to {modes} modes (best relative error {best:.3e}); raise the tolerance or refine the mesh")]
    Tolerance {
        /// The tolerance asked for.
        tolerance: f64,
        /// Largest p tried.
        modes: usize,
        /// Best error reached.
        best: f64,
    },
    /// Readings cannot be given in the units asked for (footcandles of a radiometric basis).
    #[error("--units {units}: {reason}")]
    Units {
        /// The units asked for.
        units: &'static str,
        /// Why not.
        reason: String,
    },
    /// The scene is too large for this machine.
    #[error("{0}")]
    TooLarge(String),
    /// A report could not be written as JSON.
    #[error("JSON: {0}")]
    Json(#[from] serde_json::Error),
    /// A site, time, sun or sky input (`eigenrad sky`, [`crate::daylight`]) is wrong.
    #[error("{what}: {reason}")]
    Daylight {
        /// The input: a command-line flag or a named quantity.
        what: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A picture cannot be drawn (`eigenrad render`): no work plane, a basis of another
    /// scene, a drawing failure.
    #[error("render {}: {reason}", scene.display())]
    Render {
        /// The scene file.
        scene: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// A form factor came out not finite (degenerate geometry the scene checks missed).
    #[error("{}: the form factor between patches {} and {} is not finite; check the surfaces they were cut from", scene.display(), patches[0], patches[1])]
    FormFactor {
        /// The scene file.
        scene: PathBuf,
        /// The two patches.
        patches: [usize; 2],
    },
    /// The thread that runs the runtime's evaluator could not start, or panicked.
    #[error("evaluator thread: {0}")]
    Thread(String),
    /// A weather file (EPW or TMY3) is unreadable or invalid.
    #[error(transparent)]
    Weather(#[from] crate::weather::WeatherError),
    /// A controller file (`eigenrad simulate --controller`) is invalid.
    #[error("{}{}: {field}: {reason}", path.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
    Controller {
        /// The controller file.
        path: PathBuf,
        /// 1-based line, when known.
        line: Option<usize>,
        /// The field at fault (`target.zone`, `channel.power`, ...).
        field: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A building's port names an opening the room's scene meshed into no patch.
    #[error("port {port}: the scene has no patches of its opening {surface}")]
    PortOpening {
        /// The port.
        port: String,
        /// The opening's surface.
        surface: String,
    },
}

impl From<crate::atomic::WriteError> for Error {
    fn from(e: crate::atomic::WriteError) -> Error {
        Error::Io {
            path: e.path,
            reason: e.reason,
        }
    }
}

impl From<crate::daylight::DaylightError> for Error {
    fn from(e: crate::daylight::DaylightError) -> Error {
        Error::Daylight {
            what: e.what,
            reason: e.reason,
        }
    }
}
