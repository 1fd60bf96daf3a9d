//! What can go wrong on the link to a device; each message names the cause and the way out.

use shared::protocol::{DeviceError, PROTOCOL_VERSION};

use super::explain::explain;

/// What a silence at opening adds: a board running its own sketch that printed nothing yet.
fn silent_sketch(at_open: bool) -> String {
    let listened_s = crate::limits::LISTEN_FIRST.as_secs_f64();
    match at_open {
        true => format!(
            "; if it runs its own sketch, that printed nothing in the {listened_s} s listened to nor since: run accelcal again once it prints"
        ),
        false => String::new(),
    }
}

/// A failure of the link or a refusal by the device.
#[derive(Debug, thiserror::Error)]
pub enum LinkError {
    #[error("cannot open {port}: {reason}; check the cable and the path (`accelcal ports` lists the ports)")]
    Open { port: String, reason: String },
    #[error("{port} is in use by another program (a serial terminal, a monitor, ModemManager, another accelcal): close it and run the command again; `fuser -v {port}` or `lsof {port}` names it")]
    PortBusy { port: String },
    #[error("no answer from the device within {seconds} s: is it an accelcal board running the firmware? (reflash it, or unplug and replug it){}", silent_sketch(*at_open))]
    Silent { seconds: f64, at_open: bool },
    #[error("the device stopped answering in the middle of the operation: it restarted or lost power; check the cable and the power, then run the command again")]
    StoppedAnswering,
    #[error("something answers on this port but it is not an accelcal board: it sent {seen} and no accelcal frame within {seconds} s; check that --port names the board (`accelcal ports` marks it)")]
    NotAccelcal { seconds: f64, seen: String },
    #[error("{path} prints on its own ({seen}), so it is not an accelcal board (which speaks only when asked){}; if it is a sketch printing the sensor, `accelcal calibrate --port {path}` calibrates from what it prints (docs/streams.md); else check that --port names the board (`accelcal ports` marks it)", if *greeted { ", though it began only after accelcal's hello" } else { " and accelcal wrote nothing to it" })]
    TalksOnItsOwn { path: String, seen: String, greeted: bool },
    #[error("the device went away ({reason}): it was unplugged or restarted; reconnect and run the command again")]
    Disconnected { reason: String },
    #[error("the device speaks protocol version {device}, this accelcal speaks {host}: update {}", if device < host { "the firmware (cargo run --release in firmware/)" } else { "accelcal" })]
    Version { device: u8, host: u8 },
    #[error("{}", explain(.0))]
    Device(DeviceError),
    #[error("the device answered {answer} to {request}: is it running this version of the firmware? (reflash it)")]
    UnexpectedAnswer { request: &'static str, answer: String },
    #[error("{} of {expected} samples were lost ({dropped} dropped by the board, which the host did not read in time; {} on the link): the rows written are real but not consecutive (see the index column); stream at a lower --rate, or keep other programs off the USB port, then stream again", .dropped + .on_link, .on_link)]
    SamplesLost { expected: u32, dropped: u32, on_link: u32 },
    #[error("cannot encode the request {request}: {reason}; this is a bug in accelcal, please report it")]
    Encode { request: &'static str, reason: String },
    #[error("cannot set the read timeout of the port: {0}; unplug and replug the board")]
    Timeout(std::io::Error),
    #[error("interrupted (Ctrl-C); the board's capture or stream was cancelled")]
    Interrupted,
    #[error("no serial port has the serial number {serial} ({found}): give the serial number `accelcal ports` shows, or the port's path")]
    NoSuchSerial { serial: String, found: String },
    #[error("no accelcal board found: no serial port has accelcal's USB ids, and no other USB serial port answered accelcal's hello ({asked} asked, each listened to first); plug the board in, or give --port PATH (see `accelcal ports`) or --sim")]
    NoBoardFound { asked: usize },
    #[error("several accelcal boards are plugged in ({paths}): give --port with the path or the serial number of one (`accelcal ports` lists them)")]
    SeveralBoards { paths: String },
    #[error("cannot list serial ports: {reason}; give the port path with --port")]
    ListPorts { reason: String },
}

impl From<DeviceError> for LinkError {
    fn from(error: DeviceError) -> Self {
        match error {
            DeviceError::UnsupportedVersion { device, host } => LinkError::Version { device, host },
            other => LinkError::Device(other),
        }
    }
}

impl LinkError {
    /// The version mismatch of a device speaking protocol `device`.
    pub fn version(device: u8) -> Self {
        LinkError::Version { device, host: PROTOCOL_VERSION }
    }

    /// An I/O failure of the port: the device went away.
    pub fn disconnected(error: std::io::Error) -> Self {
        LinkError::Disconnected { reason: error.to_string() }
    }
}
