//! What an export is (`Export`, or why there is none: `ExportError`) and how every text target
//! writes one: its statement in the file's comment syntax, then the body, numbers as the shortest
//! float that reads back. Below the table of targets and each target's file.

use super::loss::Loss;
use crate::calibration::CalibrationRecordError;
use crate::fit::FitError;

/// An exported file.
#[derive(Debug, Clone, PartialEq)]
pub struct Export {
    /// The file's bytes.
    pub bytes: Vec<u8>,
    /// Whether the file is binary (no comment syntax: the statement goes to the terminal instead).
    pub binary: bool,
    /// What the file states, as plain lines (for a binary file, shown beside it).
    pub statement: Vec<String>,
    /// What the target loses on this unit.
    pub loss: Loss,
}

/// Why an export could not be made.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error("not JSON: {reason}; give the output of calibrate --json, fit --json, download, or a session file")]
    NotJson { reason: String },
    #[error(transparent)]
    Record(#[from] CalibrationRecordError),
    #[error("the session cannot be fitted: {0}; capture the positions it lacks (calibrate --resume SESSION)")]
    Fit(FitError),
    #[error("not a noise report: {reason}")]
    NoiseFile { reason: String },
    #[error("kalibr's imu.yaml is noise terms: give --noise NOISE.json (from `accelcal noise RECORDING --json`)")]
    NeedsNoise,
    #[error("the noise report was recorded on board {recorded}, the calibration is board {calibrated}'s: every board's noise differs; record this board (`accelcal record --port P` then `accelcal noise RECORDING --json`)")]
    NoiseOfAnotherBoard { calibrated: String, recorded: String },
    #[error("{target} is a binary file: give -o FILE")]
    BinaryNeedsFile { target: String },
    #[error("the fixed-point header takes whole counts and this stream printed {units}: use --to c, which takes them as printed")]
    FixedNeedsCounts { units: String },
    #[error("the fixed-point form would overflow int32 ({reason}); use --to c")]
    FixedPointOverflow { reason: String },
}

/// A comment syntax: an opening line, a prefix for each line, a closing line.
pub(super) struct Comment {
    pub(super) open: &'static str,
    pub(super) line: &'static str,
    pub(super) close: &'static str,
}

/// `// ...` (C++, Rust).
pub(super) const SLASHES: Comment = Comment { open: "", line: "// ", close: "" };
/// `# ...` (parameter files, YAML).
pub(super) const HASH: Comment = Comment { open: "", line: "# ", close: "" };
/// `/* ... */` (C).
pub(super) const C_BLOCK: Comment = Comment { open: "/*\n", line: " * ", close: " */\n" };

/// A text export: the statement in the file's comment syntax, then the body.
pub(super) fn text(statement: Vec<String>, comment: &Comment, body: &str, loss: Loss) -> Export {
    let mut out = comment.open.to_owned();
    for line in &statement {
        out.push_str(format!("{}{line}", comment.line).trim_end());
        out.push('\n');
    }
    out.push_str(comment.close);
    out.push_str(body);
    Export { bytes: out.into_bytes(), binary: false, statement, loss }
}

/// An f32 value as the shortest decimal that reads back to the same f32 (valid C, Rust, MATLAB).
pub(super) fn float(value: f64) -> String {
    format!("{:e}", value as f32)
}
