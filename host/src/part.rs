//! The sensor a board found, named for a person: the part its WHO_AM_I names, the family it
//! behaves as, and a contradiction between the two when there is one.

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

#[cfg(test)]
mod tests {
    use super::*;

    fn identity(who_am_i: u8, family: Family) -> SensorIdentity {
        SensorIdentity { address: 0x68, who_am_i, family }
    }

    #[test]
    fn parts_are_named_and_a_contradiction_is_said() {
        assert_eq!(describe(&identity(0x98, Family::Mpu6500)), "ICM-20689 at 0x68 (MPU-6500 family)");
        assert_eq!(
            describe(&identity(0x72, Family::Mpu6500)),
            "unknown 0x72, not an InvenSense part, at 0x68 (behaves as the MPU-6500 family)"
        );
        let contradiction = describe(&identity(0x68, Family::Mpu6500));
        assert!(contradiction.contains("WHO_AM_I 0x68 (MPU-6050)") && contradiction.contains("not the part it claims"));
        assert_eq!(part_name(&identity(0x74, Family::Mpu6050)), "unknown");
    }
}
