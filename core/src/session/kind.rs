//! What kind of calibration a session is: how its positions were captured, and so how its
//! calibration is fitted and reported. Sessions written before the kind existed said it with two
//! booleans (`quick`, `adaptive`); they still read.

use serde::{Deserialize, Serialize};

/// How a session's positions were captured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SessionKind {
    /// `calibrate --chip-fit`: ten positions of a fixed length, fitted on the chip (`ortho9`).
    Quick,
    /// Every position for a fixed length (`calibrate --seconds`, `accelcal capture`): the host's
    /// choice of model.
    #[default]
    Fixed,
    /// Each position captured until its mean is known, the offset's drift with the temperature
    /// fitted with the calibration (`ortho9`).
    Adaptive,
    /// A board's own stream (`calibrate --port` on a port that prints on its own): its still
    /// periods at faces and corners fitted (`ortho9`), those at fresh orientations its verification.
    Stream,
}

impl SessionKind {
    /// What a new session is asked to be: quick (`--chip-fit`), of fixed-length captures (`--seconds`),
    /// or adaptive. A resumed session keeps what it was begun as, so that its collection, its fit and
    /// its report agree.
    pub fn asked(quick: bool, seconds: Option<u8>) -> Self {
        match (quick, seconds) {
            (true, _) => SessionKind::Quick,
            (false, Some(_)) => SessionKind::Fixed,
            (false, None) => SessionKind::Adaptive,
        }
    }

    /// The kind a session file written with the two booleans of before meant.
    pub fn from_flags(quick: bool, adaptive: bool) -> Self {
        match (quick, adaptive) {
            (true, _) => SessionKind::Quick,
            (false, true) => SessionKind::Adaptive,
            (false, false) => SessionKind::Fixed,
        }
    }
}

/// The kind as a session file holds it (flattened into the session): `"kind": "adaptive"`, or in
/// files of before, the booleans.
pub(super) mod stored {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    use super::SessionKind;

    #[derive(Serialize)]
    struct Written {
        kind: SessionKind,
    }

    #[derive(Deserialize)]
    struct Read {
        #[serde(default)]
        kind: Option<SessionKind>,
        #[serde(default)]
        quick: bool,
        #[serde(default)]
        adaptive: bool,
    }

    pub fn serialize<S: Serializer>(kind: &SessionKind, serializer: S) -> Result<S::Ok, S::Error> {
        Written { kind: *kind }.serialize(serializer)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<SessionKind, D::Error> {
        let read = Read::deserialize(deserializer)?;
        Ok(read.kind.unwrap_or_else(|| SessionKind::from_flags(read.quick, read.adaptive)))
    }
}

#[cfg(test)]
mod tests {
    use super::SessionKind;
    use crate::session::Session;

    #[test]
    fn old_session_files_with_the_booleans_read_as_their_kind() {
        let kind = |json: &str| serde_json::from_str::<Session>(json).unwrap().kind;
        assert_eq!(kind(r#"{"captures": [], "quick": true, "adaptive": false}"#), SessionKind::Quick);
        assert_eq!(kind(r#"{"captures": [], "quick": false, "adaptive": true}"#), SessionKind::Adaptive);
        assert_eq!(kind(r#"{"captures": []}"#), SessionKind::Fixed);
        assert_eq!(kind(r#"{"captures": [], "kind": "adaptive"}"#), SessionKind::Adaptive);
        let written = serde_json::to_string(&Session { kind: SessionKind::Quick, ..Session::default() }).unwrap();
        assert!(written.contains(r#""kind":"quick""#) && !written.contains("adaptive"), "{written}");
    }
}

/// Issue 40: the session file spelled the sensor's settings and faces as Rust names ("G2", "Hz44",
/// "HostFit", "PosX"). They are now spelled as a person reads them; files with the old names still read.
#[cfg(test)]
mod spelling {
    use serde::de::DeserializeOwned;
    use serde::Serialize;
    use shared::calibration::{AccelRange, Procedure};
    use shared::orientation::Position;
    use shared::protocol::LowPassFilter;

    /// `value` is written as `new` and read back from both `new` and `old`.
    fn spelled<T: Serialize + DeserializeOwned + PartialEq + std::fmt::Debug>(value: T, new: &str, old: &str) {
        assert_eq!(serde_json::to_string(&value).unwrap(), format!("\"{new}\""));
        for text in [new, old] {
            assert_eq!(serde_json::from_str::<T>(&format!("\"{text}\"")).unwrap(), value, "{text}");
        }
    }

    #[test]
    fn settings_and_faces_are_written_as_read_and_the_old_names_still_read() {
        spelled(AccelRange::G2, "2g", "G2");
        spelled(AccelRange::G16, "16g", "G16");
        spelled(LowPassFilter::Hz44, "44Hz", "Hz44");
        spelled(LowPassFilter::Hz260, "260Hz", "Hz260");
        spelled(Procedure::HostFit, "host-fit", "HostFit");
        spelled(Procedure::ChipFit, "chip-fit", "ChipFit");
        spelled(Position::PosX, "+X", "PosX");
        spelled(Position::NegZ, "-Z", "NegZ");
    }
}
