//! The sensor a board found, named for a person: the part its WHO_AM_I names, the family it
//! behaves as, and a contradiction between the two when there is one. Reading the registers and
//! checking the family on a board are the host's (`accelcal::part`).

use shared::part::{Family, Part};
use shared::protocol::SensorIdentity;

/// The part's name, or "unknown" (what `info --json` and `selftest --json` print as `part`).
pub fn part_name(identity: &SensorIdentity) -> &'static str {
    identity.identification().part.name()
}

/// One line for a person: "MPU-6500 at 0x68", "unknown 0x72, not an InvenSense part, at 0x68
/// (behaves as the MPU-6500 family)", or the contradiction.
pub fn describe(identity: &SensorIdentity) -> String {
    let id = identity.identification();
    let at = format!("at 0x{:02x}", identity.address);
    let family = family_name(id.family);
    match id.part {
        Part::Unknown(value) => {
            format!("unknown 0x{value:02x}, not an InvenSense part, {at} (behaves as the {family} family)")
        }
        part if id.contradicts_who_am_i() => format!(
            "answers WHO_AM_I 0x{:02x} ({}) {at} but behaves as the {family} family: not the part it claims to be; run as the {family} family",
            identity.who_am_i,
            part.name()
        ),
        part => format!("{} {at} ({family} family)", part.name()),
    }
}

/// The family by its first part's name.
pub fn family_name(family: Family) -> &'static str {
    match family {
        Family::Mpu6050 => "MPU-6050",
        Family::Mpu6500 => "MPU-6500",
    }
}
