//! Record format 1, written by the firmware up to the calibration record of issue 9: read by its
//! frozen byte layout so that a board updated from it boots with its calibration intact.
//!
//! The layout is postcard's encoding of `Option<Calibration>` as format 1 defined it: a byte 0 (none)
//! or 1 (some), then M (9 f32), o (3 f32), the gyro bias (3 f32), the model and the range as one-byte
//! variant indices, the mean temperature and the residual (f32); every f32 little-endian.
//!
//! NOTE: read by hand rather than through a frozen serde type: a second derived deserializer costs
//! about a kilobyte of the board's flash.

use shared::calibration::{GyroCalibration, ModelTag, Origin, Procedure};
use shared::linalg::Vec3;
use shared::protocol::LowPassFilter;
use shared::{AccelRange, Calibration};

/// The fit models format 1 named, by variant index, and the procedure that made each.
///
/// NOTE: format 1 did not say where a six-position fit was made; the chip's own fit is by far the
/// usual source of one, so it is taken for that.
const MODELS: [(Procedure, &str); 5] = [
    (Procedure::ChipFit, "six-position"),
    (Procedure::HostFit, "linear12"),
    (Procedure::HostFit, "reference-norm12"),
    (Procedure::HostFit, "ortho9"),
    (Procedure::HostFit, "diag6"),
];

/// The accelerometer ranges format 1 named, by variant index.
const RANGES: [AccelRange; 4] = [AccelRange::G2, AccelRange::G4, AccelRange::G8, AccelRange::G16];

/// The calibration of a format-1 record body, migrated: the gyro matrix is the identity, there is
/// no temperature model, and the filter is the default (44 Hz), as format 1 had none of them.
///
/// NOTE: the firmware that wrote format 1 never changed the filter from its default, so every
/// format-1 calibration was captured through it. `None` when the body does not follow the layout.
pub fn decode(body: &[u8]) -> Option<Option<Calibration>> {
    let mut reader = Reader(body);
    match reader.byte()? {
        0 => Some(None),
        1 => read_calibration(&mut reader).map(Some),
        _ => None,
    }
}

fn read_calibration(reader: &mut Reader<'_>) -> Option<Calibration> {
    let matrix = [reader.vec3()?, reader.vec3()?, reader.vec3()?];
    let (offset_g, gyro_bias_dps) = (reader.vec3()?, reader.vec3()?);
    let (procedure, name) = *MODELS.get(usize::from(reader.byte()?))?;
    let range = *RANGES.get(usize::from(reader.byte()?))?;
    let (mean_temp_c, residual_mg) = (reader.f32()?, reader.f32()?);
    Some(Calibration {
        origin: Origin { procedure, model: ModelTag::new(name)? },
        range,
        filter: LowPassFilter::default(),
        matrix,
        offset_g,
        gyro: GyroCalibration { bias_dps: gyro_bias_dps, ..GyroCalibration::default() },
        mean_temp_c,
        temperature: None,
        residual_mg,
    })
}

/// Reads fields off the front of a record body.
struct Reader<'a>(&'a [u8]);

impl Reader<'_> {
    fn byte(&mut self) -> Option<u8> {
        let (&first, rest) = self.0.split_first()?;
        self.0 = rest;
        Some(first)
    }

    fn f32(&mut self) -> Option<f32> {
        let (bytes, rest) = self.0.split_first_chunk::<4>()?;
        self.0 = rest;
        Some(f32::from_le_bytes(*bytes))
    }

    fn vec3(&mut self) -> Option<Vec3<f32>> {
        Some([self.f32()?, self.f32()?, self.f32()?])
    }
}
