//! Adafruit_Sensor_Calibration: `sensor_calib.json` and the 68-byte EEPROM image (the layout MotionCal
//! sends), both offsets only: the library subtracts accel_zerog (m/s^2) and gyro_zerorate (rad/s) from
//! Adafruit_Sensor events (Adafruit_Sensor_Calibration.cpp, calibrate()).

use shared::STANDARD_GRAVITY;

use super::loss::{diagonal, loss, Carried, Loss};
use super::statement::{lines, Said};
use super::{Export, Source};

/// Radians per degree.
const RAD_PER_DEG: f64 = std::f64::consts::PI / 180.0;
/// The EEPROM image (2 magic bytes, 16 little-endian f32, CRC-16; Adafruit_Sensor_Calibration_EEPROM.cpp) starts with these.
pub const EEPROM_MAGIC: [u8; 2] = [0x75, 0x54];
/// The library's CRC: init 0xFFFF, reflected polynomial 0xA001 (crc16_update), which is CRC-16/MODBUS.
const CRC16: crc::Crc<u16> = crc::Crc::<u16>::new(&crc::CRC_16_MODBUS);

const CONVENTION: &[&str] = &[
    "Adafruit_Sensor_Calibration: acceleration = event - accel_zerog in m/s^2; rate = event - gyro_zerorate in rad/s",
    "no scale and no cross-axis terms: M and G are not carried; the magnetometer fields are left neutral",
];

/// The offsets as the library stores them (f32), and what they carry.
fn offsets(source: &Source) -> ([f32; 3], [f32; 3], Carried, Loss) {
    let full = source.full();
    let accel = full.offset_g.map(|v| (v * STANDARD_GRAVITY) as f32);
    let gyro = source.gyro_bias_dps().map(|v| mutant!("adafruit-gyro-in-deg", v * RAD_PER_DEG, v) as f32);
    let carried = Carried {
        matrix: diagonal([1.0; 3]),
        offset_g: accel.map(|v| f64::from(v) / STANDARD_GRAVITY),
        gyro_matrix: diagonal([1.0; 3]),
        gyro_bias_dps: Some(gyro.map(|v| f64::from(v) / RAD_PER_DEG)),
    };
    let loss = loss(&full, &carried);
    (accel, gyro, carried, loss)
}

fn statement(source: &Source, title: &str, loss: &Loss) -> Vec<String> {
    let said = Said {
        title,
        convention: CONVENTION,
        carries: "accelerometer and gyro offsets only",
        temperature: "the library has no temperature model: not carried",
        lossy: true,
    };
    lines(source, &said, loss)
}

/// sensor_calib.json. JSON has no comments: the statement is the `accelcal` key, which the library ignores.
pub fn json(source: &Source) -> Export {
    let (accel, gyro, _, loss) = offsets(source);
    let statement = statement(source, "Adafruit_Sensor_Calibration (sensor_calib.json)", &loss);
    let value = serde_json::json!({
        "accelcal": statement,
        "mag_hardiron": [0.0, 0.0, 0.0],
        "mag_softiron": [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        "mag_field": 0.0,
        "gyro_zerorate": gyro,
        "accel_zerog": accel,
    });
    let text = serde_json::to_string_pretty(&value).unwrap_or_default() + "\n";
    Export { bytes: text.into_bytes(), binary: false, statement, loss }
}

/// The 68-byte EEPROM image: magic, accel_zerog, gyro_zerorate, mag_hardiron, mag_field, the six
/// independent soft-iron entries (diagonal first), CRC-16 little-endian over the first 66 bytes.
pub fn eeprom(source: &Source) -> Export {
    let (accel, gyro, _, loss) = offsets(source);
    let statement = statement(source, "Adafruit_Sensor_Calibration EEPROM image (68 bytes)", &loss);
    let mut floats = [0.0f32; 16];
    floats[0..3].copy_from_slice(&accel);
    floats[3..6].copy_from_slice(&gyro);
    floats[10..13].copy_from_slice(&[1.0; 3]);
    let mut bytes = EEPROM_MAGIC.to_vec();
    bytes.extend(floats.iter().flat_map(|v| v.to_le_bytes()));
    bytes.extend(CRC16.checksum(&bytes).to_le_bytes());
    Export { bytes, binary: true, statement, loss }
}

#[cfg(test)]
mod tests {
    use super::*;

    // NOTE: Adafruit_Sensor_Calibration subtracts gyro_zerorate from the gyro event, which is in rad/s.
    #[test]
    fn the_json_s_gyro_zero_rate_is_the_bias_in_rad_per_s() {
        let exported = json(&super::super::example_source());
        let value: serde_json::Value = serde_json::from_slice(&exported.bytes).unwrap();
        let zero_rate: Vec<f64> =
            value["gyro_zerorate"].as_array().unwrap().iter().filter_map(|v| v.as_f64()).collect();
        for (got, bias_dps) in zero_rate.iter().zip([1.0, -0.5, 0.25]) {
            let wanted = bias_dps * std::f64::consts::PI / 180.0;
            assert!((got - wanted).abs() < 1e-8, "{zero_rate:?}");
        }
        assert_eq!(zero_rate.len(), 3);
    }
}
