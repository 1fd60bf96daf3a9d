//! The host's fit models: its own list, carried to the device only as a name tag in the calibration's
//! origin, so that adding a model changes neither the wire nor the flash format.

use serde::{Deserialize, Serialize};
use shared::calibration::{ModelTag, Origin, Procedure};

/// Every model, richest first: the order in which models are listed, and in which `auto` falls back
/// to the first that fits when none can be tested on left-out rows.
///
/// NOTE: `reference-norm12` uses every row (known orientations and |a| = g), `linear12` only the
/// rows of known orientation; `ortho9` needs no orientation; the six-position closed form uses only
/// six readings, so it comes after the fits over all positions.
pub const RICHEST_FIRST: [Model; 5] =
    [Model::ReferenceNorm12, Model::Linear12, Model::Ortho9, Model::Diag6, Model::SixPosition];

/// The fitting model that produced a calibration (see DESIGN.md for the shape of M in each).
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    /// Closed form from the six axis-aligned positions, full M; the model fitted on the chip.
    SixPosition,
    /// Linear least squares over positions of known orientation, full M.
    Linear12,
    /// Known-orientation rows plus |a| = g rows (Ivanov et al.), full M.
    ReferenceNorm12,
    /// Upper-unit-triangular T times diagonal K, orientation-free.
    Ortho9,
    /// Diagonal M, orientation-free.
    Diag6,
}

impl Model {
    /// The model's name as used on the command line, in JSON and in the calibration's origin tag.
    pub const fn name(self) -> &'static str {
        match self {
            Model::SixPosition => "six-position",
            Model::Linear12 => "linear12",
            Model::ReferenceNorm12 => "reference-norm12",
            Model::Ortho9 => "ortho9",
            Model::Diag6 => "diag6",
        }
    }

    /// The origin of a calibration this host fitted with this model.
    pub fn origin(self) -> Origin {
        // NOTE: every name is within the tag's length (a test checks it).
        Origin { procedure: Procedure::HostFit, model: ModelTag::new(self.name()).unwrap_or_default() }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_model_name_fits_the_origin_tag() {
        for model in super::super::RICHEST_FIRST {
            assert_eq!(model.origin().model.as_str(), model.name());
        }
    }
}
