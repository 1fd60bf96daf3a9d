//! What a stream delivered: samples carry consecutive sequence numbers, so every gap is a lost
//! sample, whether the board dropped it (it says how many at the end) or the link did.

use super::LinkError;

/// Samples received, and the sequence numbers not seen, of one stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Tally {
    /// Samples that arrived.
    pub received: u32,
    /// Sequence numbers the board issued: the samples it sent plus those it dropped.
    pub expected: u32,
    /// Samples the board dropped because the host did not read in time.
    pub dropped: u32,
    next_index: u32,
    gaps: u32,
}

impl Tally {
    /// A sample with sequence number `index` arrived.
    pub fn arrived(&mut self, index: u32) {
        self.received += 1;
        self.gaps += index.saturating_sub(self.next_index);
        self.next_index = self.next_index.max(index.saturating_add(1));
    }

    /// The board ended the stream having sent `samples` and dropped `dropped`.
    pub fn ended(mut self, samples: u32, dropped: u32) -> Self {
        self.expected = samples.saturating_add(dropped);
        self.dropped = dropped;
        self
    }

    /// Samples that never arrived: gaps in the sequence, and any missing at its end.
    pub fn lost(&self) -> u32 {
        self.expected.saturating_sub(self.received).max(self.gaps)
    }

    /// `Err` naming the loss when any sample was lost.
    pub fn complete(&self) -> Result<(), LinkError> {
        match self.lost() {
            0 => Ok(()),
            lost => Err(LinkError::SamplesLost {
                expected: self.expected,
                dropped: self.dropped.min(lost),
                on_link: lost - self.dropped.min(lost),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tally(indices: impl IntoIterator<Item = u32>, samples: u32, dropped: u32) -> Tally {
        let mut tally = Tally::default();
        indices.into_iter().for_each(|i| tally.arrived(i));
        tally.ended(samples, dropped)
    }

    #[test]
    fn consecutive_samples_are_complete() {
        assert!(tally(0..100, 100, 0).complete().is_ok());
    }

    #[test]
    fn gaps_dropped_samples_and_a_missing_tail_are_counted() {
        // 3 and 4 lost on the link.
        let link = tally((0..3).chain(5..10), 10, 0);
        assert_eq!(link.lost(), 2);
        assert!(matches!(link.complete(), Err(LinkError::SamplesLost { expected: 10, dropped: 0, on_link: 2 })));
        // the board dropped 6 of 10, sending 0-1 and 8-9.
        let board = tally([0, 1, 8, 9], 4, 6);
        assert!(matches!(board.complete(), Err(LinkError::SamplesLost { expected: 10, dropped: 6, on_link: 0 })));
        // the last two never came.
        assert_eq!(tally(0..8, 10, 0).lost(), 2);
    }
}
