//! Every line of a stream that is not a sample, counted by why it was dropped, with the first such
//! line so that a person can look at it.

use serde::Serialize;

/// Why a line carries no sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DropReason {
    /// Empty.
    Empty,
    /// Words: a boot message, a banner, a prompt.
    Text,
    /// The header naming the columns.
    Header,
    /// One of the sketch's other records (`Uni:`, `Cal1:`, `Cal2:`).
    SideRecord,
    /// Numbers, but not as the stream's lines have them: cut short, run together, or other labels.
    OtherShape,
    /// Bytes that are not text: boot noise, or the whole stream read at the wrong baud rate.
    NotText,
    /// A value beyond what the sensor can read (its widest range, or 16-bit counts): a garbled line.
    BeyondRange,
    /// A line of a sample printed over several, before the line that ends it: no line is lost.
    Continued,
}

impl DropReason {
    /// The reason in words.
    pub fn words(self) -> &'static str {
        match self {
            DropReason::Empty => "empty",
            DropReason::Text => "text, not numbers (boot messages, banners, prompts)",
            DropReason::Header => "the header",
            DropReason::SideRecord => "the sketch's other records (Uni:, Cal1:, Cal2:)",
            DropReason::OtherShape => "cut short, run together or otherwise not as the other lines",
            DropReason::NotText => "bytes that are not text (boot noise; all of them: the wrong --baud)",
            DropReason::BeyondRange => "a value beyond what the sensor can read (a garbled line)",
            DropReason::Continued => "a part of a sample printed over several lines",
        }
    }
}

/// The lines dropped for one reason.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DroppedLines {
    /// Why.
    pub reason: DropReason,
    /// How many lines.
    pub lines: usize,
    /// The first of them (1-based).
    pub first_line: usize,
}

/// Every dropped line, by reason, in the order the reasons first came up.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Dropped(pub Vec<DroppedLines>);

impl Dropped {
    /// Counts line `line` as dropped for `reason`.
    pub fn add(&mut self, reason: DropReason, line: usize) {
        match self.0.iter_mut().find(|d| d.reason == reason) {
            Some(dropped) => dropped.lines += mutant!("dropped-lines-counted-once", 1, 0),
            None => {
                let at = self.0.partition_point(|d| d.first_line < line);
                self.0.insert(at, DroppedLines { reason, lines: 1, first_line: line });
            }
        }
    }

    /// Lines dropped for any reason.
    pub fn total(&self) -> usize {
        self.0.iter().map(|d| d.lines).sum()
    }

    /// Lines dropped for `reason`.
    pub fn count(&self, reason: DropReason) -> usize {
        self.0.iter().filter(|d| d.reason == reason).map(|d| d.lines).sum()
    }
}
