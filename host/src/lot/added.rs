//! What adding a certificate to the lot did, and the tests' pause inside a write: below the file's
//! and the server's writers, which both use them.

use std::time::Duration;

/// What adding a certificate did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Added {
    New,
    /// The same certificate (by its hash) was already in the lot.
    AlreadyThere,
}

/// Pauses inside a write's transaction when the tests ask for it, saying so on stderr.
pub(super) fn pause_inside(serial: &str, pause: Option<Duration>) {
    if let Some(pause) = pause {
        eprintln!("lot: inside the transaction of board {serial}");
        std::thread::sleep(pause);
    }
}
