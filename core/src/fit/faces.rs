//! The six faces in a data file, for the six-position closed form: found from each row's known
//! orientation, or from its reading normalised so that the file's zero and unit do not matter.

use shared::linalg::{self, Vec3};
use shared::Position;

use super::normalization::Normalization;
use super::FitError;
use crate::data::{Dataset, Row};
use crate::limits::REFERENCE_FACE_TOLERANCE_DEG;

/// The index of the row at each face, in the order of `Position::ALL`; a face met twice is refused.
/// Readings are judged after the normalisation of the least-squares models, so that a file's zero
/// and unit do not matter.
pub(super) fn rows_at_faces(dataset: &Dataset, tolerance_deg: f64) -> Result<[Option<usize>; 6], FitError> {
    let normalization = Normalization::of_dataset(dataset);
    let mut first_row_at: [Option<usize>; 6] = [None; 6];
    for (index, row) in dataset.rows.iter().enumerate() {
        let Some(position) = face_of(row, &normalization, tolerance_deg) else {
            continue;
        };
        if let Some(first) = first_row_at[position.index()] {
            let first_line = dataset.rows[first].line;
            return Err(FitError::DuplicatePosition { position, first_line, second_line: row.line });
        }
        first_row_at[position.index()] = Some(index);
    }
    Ok(first_row_at)
}

/// The face a row was taken at: from its known orientation when it has one, else from its
/// normalised reading.
fn face_of(row: &Row, normalization: &Normalization, tolerance_deg: f64) -> Option<Position> {
    let (vector, tolerance) = match row.reference {
        Some(reference) => (reference, REFERENCE_FACE_TOLERANCE_DEG as f32),
        None => (normalization.apply(row.reading).into(), tolerance_deg as f32),
    };
    Position::detect(vector.map(|v| v as f32), tolerance).ok().map(|(position, _)| position)
}

pub(super) fn face_force(position: Position, g: f64) -> Vec3<f64> {
    linalg::scale(position.specific_force_g(), g)
}
