//! A certificate just issued, into the lot a command names: a file's directly, a server's through
//! this station's queue (`queue.rs`).

use std::path::Path;

use super::queue::Queue;
use super::{server, Lot, LotError};
use crate::certificate::Certificate;

impl Lot {
    /// Adds a certificate just issued to the lot at `place`; what to tell the person. A server's lot
    /// gets it through this station's queue, where it waits when the server does not answer.
    pub fn add_issued(place: &Path, certificate: &Certificate) -> Result<String, LotError> {
        if server::is_server(place) {
            return Queue::of_station()?.keep_and_send(place, certificate);
        }
        Lot::open_for_writing(place)?.add(certificate)?;
        let serial = certificate.board.serial.as_deref().unwrap_or("");
        Ok(format!("certificate of board {serial} added to the lot {}", place.display()))
    }
}
