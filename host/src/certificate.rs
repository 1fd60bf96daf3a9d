//! Certificates as files: what a certificate is, states and renders is the core's
//! ([`accelcal_core::certificate`], re-exported here); this module reads a certificate's file.

use std::path::Path;

pub use accelcal_core::certificate::*;

/// Reads a certificate file and checks its hash; the certificate when it is as issued.
pub fn check(path: &Path) -> Result<Certificate, SealError> {
    let text = std::fs::read_to_string(path).map_err(|source| SealError::Read { path: path.into(), source })?;
    check_text::<Certificate>(path, &text)
}
