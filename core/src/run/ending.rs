//! How a run ended: complete, or cut short and why. Only a complete run is certified; one cut short
//! (Ctrl-C, a pulled cable, a stream that stopped or was refused as read in another unit) is kept to resume.

/// Why a run ended, and whether it is complete (every position rested and enough fresh orientations
/// held) rather than cut short.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Ended {
    /// Why it ended, as the person is told.
    pub why: String,
    /// Whether it is complete.
    pub complete: bool,
}

impl Ended {
    /// Complete: what it held is certified.
    pub fn complete(why: impl Into<String>) -> Self {
        Ended { why: why.into(), complete: true }
    }

    /// Cut short (the port gone, the stream stopped, unreadable or refused): kept, never certified.
    pub fn short(why: impl Into<String>) -> Self {
        Ended { why: why.into(), complete: false }
    }

    /// Stopped by Ctrl-C: cut short however much it holds, as a person who stops a run means it
    /// unfinished (what is long enough to fit is still fitted and shown, never certified).
    pub fn interrupted() -> Self {
        mutant!(
            "stream-ctrl-c-certified",
            Ended::short("stopped by Ctrl-C"),
            Ended { why: "stopped by Ctrl-C".to_owned(), complete: true }
        )
    }

    /// Whether the run's certificate may be issued.
    pub fn certifies(&self) -> bool {
        self.complete
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_stopped_by_ctrl_c_is_not_complete_so_gets_no_certificate() {
        let ended = Ended::interrupted();
        assert!(!ended.certifies(), "Ctrl-C counted as a complete session: `report` would certify it");
        assert_eq!(ended.why, "stopped by Ctrl-C");
        assert!(!Ended::short("the stream stopped").certifies());
        assert!(Ended::complete("every position rested").certifies());
    }
}
