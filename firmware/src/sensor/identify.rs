//! Finding the chip: which of its two addresses answers, the part its WHO_AM_I names and the family
//! its registers show ([`super::family`]).

use embedded_hal_async::i2c::I2c;
use shared::protocol::{SensorConfig, SensorIdentity};

use super::access::read_register;
use super::family::{family_of, TempEncoding};
use super::registers as reg;
use super::{Error, Sensor};

impl Sensor {
    /// Looks for the chip at 0x68, then 0x69, by WHO_AM_I.
    pub async fn probe<I: I2c>(bus: &mut I) -> Result<Self, Error<I::Error>> {
        for address in reg::ADDRESSES {
            let Ok(who_am_i) = read_register(bus, address, reg::WHO_AM_I).await else {
                continue; // no acknowledge: try the other address
            };
            let Some(family) = family_of(bus, address, who_am_i).await? else {
                return Err(Error::UnknownChip { address, who_am_i });
            };
            let identity = SensorIdentity { address, who_am_i, family };
            let temperature = TempEncoding::of(identity.identification().temperature());
            return Ok(Sensor { identity, config: SensorConfig::default(), temperature });
        }
        Err(Error::Missing)
    }
}
