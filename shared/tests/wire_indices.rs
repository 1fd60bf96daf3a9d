//! The JSON files name the sensor's settings and the faces as a person reads them ("2g", "44Hz",
//! "host-fit", "+X"; issue 40); postcard, on the wire and in the flash, writes a variant as its index,
//! so those names must not move a byte there: each setting keeps the index it always had.

use shared::calibration::{AccelRange, Procedure};
use shared::orientation::Position;
use shared::protocol::LowPassFilter;

#[test]
fn the_wire_and_the_flash_keep_each_setting_s_index() {
    assert_eq!(postcard::to_allocvec(&AccelRange::G16).unwrap(), [3]);
    assert_eq!(postcard::to_allocvec(&LowPassFilter::Hz5).unwrap(), [6]);
    assert_eq!(postcard::to_allocvec(&Procedure::Uploaded).unwrap(), [3]);
    assert_eq!(postcard::to_allocvec(&Position::NegZ).unwrap(), [5]);
    assert_eq!(postcard::from_bytes::<LowPassFilter>(&[3]).unwrap(), LowPassFilter::Hz44);
}
