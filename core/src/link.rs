//! The link to a board, free of I/O: what can go wrong on it and what each device error means for a
//! person ([`LinkError`], [`explain`]), and the wire's decisions ([`Exchange`]: frames out under
//! their ids, bytes in as answers, silence judged by frames at the times the host gives), one board's
//! [`Link`] with a typed method per request over the host's [`Transport`]. The host owns the port and
//! the clock (`accelcal::link`).

mod board;
mod error;
mod exchange;
mod explain;
mod listening;
mod requests;
mod tally;
mod transport;

pub use board::Link;
pub use error::LinkError;
pub use exchange::{holds_accelcal_frame, Call, Exchange, Step};
pub use explain::explain;
pub use listening::{describe, Listening};
pub use requests::{ChipOrtho9, StreamRequest};
pub use tally::Tally;
pub use transport::Transport;

use shared::protocol::Request;

/// The name of a request, as messages name it.
pub fn request_name(request: &Request) -> &'static str {
    match request {
        Request::Hello { .. } => "Hello",
        Request::Configure(_) => "Configure",
        Request::Capture { .. } => "Capture",
        Request::Cancel => "Cancel",
        Request::ClearPositions => "ClearPositions",
        Request::FitSixPosition => "FitSixPosition",
        Request::GetCalibration(_) => "GetCalibration",
        Request::SetCalibration(_) => "SetCalibration",
        Request::SaveCalibration => "SaveCalibration",
        Request::EraseCalibration => "EraseCalibration",
        Request::Stream { .. } => "Stream",
        Request::TakeTemperatureBins => "TakeTemperatureBins",
        Request::FitOrtho9 => "FitOrtho9",
        Request::CaptureUntil(_) => "CaptureUntil",
        Request::Register { .. } => "Register",
        Request::StoreSelfTest(_) => "StoreSelfTest",
    }
}
