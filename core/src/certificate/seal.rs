//! The certificate's hash: SHA-256 of its canonical JSON (keys sorted, no spaces) with the hash field
//! empty, so that any change to a copy, a digit or a word, is detected.

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::Serialize;
use sha2::{Digest, Sha256};

use crate::session::Session;

/// Why a certificate file does not check.
#[derive(Debug, thiserror::Error)]
pub enum SealError {
    #[error("cannot read {path}: {source}; give the certificate's .json file")]
    Read { path: PathBuf, source: std::io::Error },
    #[error("{path} is not a certificate ({reason}); give the .certificate.json file calibrate --session or `certificate issue` wrote")]
    NotACertificate { path: PathBuf, reason: String },
    #[error("{path} is a session, not its certificate; issue one with `accelcal certificate issue {path}` and give the .certificate.json file it writes")]
    ASession { path: PathBuf },
    #[error("{path} was changed after it was issued: its content hashes to {found}, the certificate states {stated}; ask for the original")]
    Changed { path: PathBuf, stated: String, found: String },
}

/// The hash of a certificate's content (its `sha256` field left out).
pub(super) fn digest(certificate: &impl Serialize) -> String {
    // NOTE: serialising numbers, strings, maps and options cannot fail.
    let value = serde_json::to_value(certificate).unwrap_or_default();
    digest_of(value)
}

/// SHA-256 of the canonical JSON of `value` with `sha256` removed. serde_json's map keeps its keys
/// sorted, so the same content always gives the same bytes.
pub fn digest_of(mut value: serde_json::Value) -> String {
    if let Some(object) = value.as_object_mut() {
        object.remove("sha256");
    }
    let bytes = serde_json::to_vec(&value).unwrap_or_default();
    Sha256::digest(&bytes).iter().map(|b| format!("{b:02x}")).collect()
}

/// Checks the hash (its `sha256` field) of a sealed file's `text` (read from `path`, which messages
/// name); its content when it is as issued.
pub fn check_text<Sealed: DeserializeOwned>(path: &Path, text: &str) -> Result<Sealed, SealError> {
    let refused = |reason: String| SealError::NotACertificate { path: path.into(), reason };
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| refused(e.to_string()))?;
    if Session::is_session_json(&value) {
        return Err(SealError::ASession { path: path.into() });
    }
    let sealed: Sealed = serde_json::from_value(value.clone()).map_err(|e| refused(e.to_string()))?;
    let stated = value["sha256"].as_str().unwrap_or_default().to_owned();
    let found = digest_of(value);
    if found != stated {
        return Err(SealError::Changed { path: path.into(), stated, found });
    }
    Ok(sealed)
}
