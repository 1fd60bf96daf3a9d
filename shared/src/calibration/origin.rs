//! Where a calibration came from, as a tag that does not list the host's fit models.

use serde::{Deserialize, Serialize};

/// Longest model tag in bytes: room for every model name the host has ("reference-norm12") and more.
pub const MODEL_TAG_LEN: usize = 16;

/// Which procedure made a calibration.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
// NOTE: a JSON file spells each variant as a person reads it (issue 40: sessions said "G2", "Hz44",
// "HostFit"); the old spellings are still read. postcard (the wire and the flash) keeps the variant's
// index, so the renames change no byte there.
pub enum Procedure {
    /// Nothing fitted: the identity, samples pass through.
    #[serde(rename = "identity", alias = "Identity")]
    Identity,
    /// Fitted on the chip from its own captures (the six-position closed form or `ortho9`).
    #[serde(rename = "chip-fit", alias = "ChipFit")]
    ChipFit,
    /// A fit made by the host tool from a guided session or a data file.
    #[serde(rename = "host-fit", alias = "HostFit")]
    HostFit,
    /// Supplied from elsewhere (a file, another tool) and uploaded as it was.
    #[serde(rename = "uploaded", alias = "Uploaded")]
    Uploaded,
}

/// A model's short name in ASCII, zero-padded: the host names its models, the chip only carries the name.
///
/// NOTE: a fixed-size name keeps the wire and flash formats unchanged when the host adds a model.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ModelTag([u8; MODEL_TAG_LEN]);

impl ModelTag {
    /// The tag for `name`; `None` when it is longer than [`MODEL_TAG_LEN`] bytes or not printable ASCII.
    pub const fn new(name: &str) -> Option<Self> {
        let bytes = name.as_bytes();
        if bytes.len() > MODEL_TAG_LEN {
            return None;
        }
        let mut tag = [0u8; MODEL_TAG_LEN];
        let mut i = 0;
        while i < bytes.len() {
            if !bytes[i].is_ascii_graphic() {
                return None;
            }
            tag[i] = bytes[i];
            i += 1;
        }
        Some(ModelTag(tag))
    }

    /// The name (empty for no model); a tag from a damaged record reads as far as its ASCII goes.
    pub fn as_str(&self) -> &str {
        let len = self.0.iter().position(|&b| b == 0).unwrap_or(MODEL_TAG_LEN);
        let end = self.0[..len].iter().position(|b| !b.is_ascii_graphic()).unwrap_or(len);
        core::str::from_utf8(&self.0[..end]).unwrap_or("")
    }
}

/// The model tag of the chip's own fit.
pub const SIX_POSITION: ModelTag = match ModelTag::new("six-position") {
    Some(tag) => tag,
    None => ModelTag([0; MODEL_TAG_LEN]),
};

/// The model tag of the chip's 9-parameter fit (the host's `ortho9`, the same solver in f32).
pub const ORTHO9: ModelTag = match ModelTag::new("ortho9") {
    Some(tag) => tag,
    None => ModelTag([0; MODEL_TAG_LEN]),
};

/// Which procedure and which model made a calibration.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub struct Origin {
    /// The procedure.
    pub procedure: Procedure,
    /// The model's name, as its maker calls it.
    pub model: ModelTag,
}

impl Origin {
    /// The identity calibration's origin: no procedure, no model.
    pub const IDENTITY: Origin = Origin { procedure: Procedure::Identity, model: ModelTag([0; MODEL_TAG_LEN]) };
    /// The chip's six-position fit.
    pub const CHIP_SIX_POSITION: Origin = Origin { procedure: Procedure::ChipFit, model: SIX_POSITION };
    /// The chip's 9-parameter (`ortho9`) fit.
    pub const CHIP_ORTHO9: Origin = Origin { procedure: Procedure::ChipFit, model: ORTHO9 };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_model_tag_keeps_names_up_to_its_length_and_refuses_longer_or_unprintable_ones() {
        assert_eq!(ModelTag::new("reference-norm12").map(|t| t.as_str().len()), Some(16));
        assert_eq!(ModelTag::new("ortho9").unwrap().as_str(), "ortho9");
        assert_eq!(ModelTag::new("a-name-of-17-byte"), None);
        assert_eq!(ModelTag::new("two words"), None);
        assert_eq!(SIX_POSITION.as_str(), "six-position");
        assert_eq!(ORTHO9.as_str(), "ortho9");
        assert_eq!(Origin::IDENTITY.model.as_str(), "");
    }
}
