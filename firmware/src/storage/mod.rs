//! The calibration in flash, power-fail-safely, through sequential-storage.
//!
//! sequential-storage appends each save as a new CRC-checked item and only erases a page once the
//! live item has been copied out of it, so a power cut at any moment of a save leaves the previous
//! item readable: the board boots with the old or the new calibration, never garbage and never none
//! when one existed. An erase stores an empty record rather than removing the item, for the same
//! reason. On top of the item CRC, each record carries a format version and is validated before use;
//! a record of an older format is read by its frozen layout ([`v1`]) and migrated, one of an unknown
//! format is refused.
//!
//! The latest self-test is a second item of the same map ([`SELF_TEST_KEY`]), so a calibration's save
//! or erase leaves it as it was and the other way round.

mod v1;

use core::ops::Range;

use embedded_storage_async::nor_flash::NorFlash;
use sequential_storage::cache::{Cache, Uncached};
use sequential_storage::map::{MapConfig, MapStorage};
use shared::selftest::SelfTestRecord;
use shared::Calibration;

/// The map key of the calibration record.
const CALIBRATION_KEY: u8 = 1;
/// The map key of the latest self-test: its format version and its postcard body.
const SELF_TEST_KEY: u8 = 2;
/// Version of the record layout: bump it when `Calibration` changes shape, and keep the old layout
/// readable (as [`v1`] is) so that stored calibrations survive the update.
pub const RECORD_FORMAT_VERSION: u8 = 2;
/// The layout of the firmware before the calibration record of issue 9.
const V1_FORMAT_VERSION: u8 = 1;
/// Largest record: format version and postcard `Option<Calibration>` (at most 237 bytes today).
const RECORD_LEN: usize = 256;
/// sequential-storage's scratch buffer: key plus record, rounded up to the flash word.
const RECORD_BUFFER_LEN: usize = 288;

/// One of the records the storage keeps.
#[derive(Debug, Clone, Copy)]
pub enum Record<'a> {
    /// The calibration, or "none" (an erase).
    Calibration(Option<&'a Calibration>),
    /// The latest self-test, as the host encoded it (the board keeps it unread).
    SelfTest(&'a SelfTestRecord),
}

/// Why the stored calibration could not be read or written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StorageError {
    /// The flash range does not suit the flash (not page-aligned, fewer than two pages).
    BadRange,
    /// The flash reported an error.
    Flash,
    /// The record is unreadable, of another format, or holds an invalid calibration: refused.
    Corrupt,
    /// The storage is full and could not be compacted.
    Full,
}

impl<E> From<sequential_storage::Error<E>> for StorageError {
    fn from(error: sequential_storage::Error<E>) -> Self {
        match error {
            sequential_storage::Error::Storage { .. } => StorageError::Flash,
            sequential_storage::Error::FullStorage => StorageError::Full,
            _ => StorageError::Corrupt,
        }
    }
}

/// The calibration store on a NOR flash range.
pub struct Storage<F: NorFlash> {
    map: MapStorage<u8, F, Cache<Uncached, Uncached, Uncached, u8>>,
    buffer: [u8; RECORD_BUFFER_LEN],
}

impl<F: NorFlash> Storage<F> {
    /// A store on `range` (byte offsets into `flash`, whole erase pages, at least two).
    pub fn new(flash: F, range: Range<u32>) -> Result<Self, StorageError> {
        let config = MapConfig::try_new(range).map_err(|_| StorageError::BadRange)?;
        Ok(Storage { map: MapStorage::new(flash, config, Cache::new_uncached()), buffer: [0; RECORD_BUFFER_LEN] })
    }

    /// The stored calibration, `None` when there is none; a damaged or invalid record is refused.
    pub async fn load(&mut self) -> Result<Option<Calibration>, StorageError> {
        let Some(record) = self.fetch(CALIBRATION_KEY).await? else {
            return Ok(None);
        };
        match decode(record)? {
            Some(c) if c.validate().is_err() => Err(StorageError::Corrupt),
            other => Ok(other),
        }
    }

    /// Stores a calibration; the previous one stays readable until this one is complete.
    pub async fn save(&mut self, calibration: &Calibration) -> Result<(), StorageError> {
        self.write(Record::Calibration(Some(calibration))).await
    }

    /// Stores "no calibration".
    pub async fn erase(&mut self) -> Result<(), StorageError> {
        self.write(Record::Calibration(None)).await
    }

    /// The latest self-test stored, `None` when there is none; a record of another format is refused.
    pub async fn load_self_test(&mut self) -> Result<Option<SelfTestRecord>, StorageError> {
        match self.fetch(SELF_TEST_KEY).await? {
            Some([RECORD_FORMAT_VERSION, body @ ..]) => {
                SelfTestRecord::from_slice(body).map(Some).map_err(|_| StorageError::Corrupt)
            }
            Some(_) => Err(StorageError::Corrupt),
            None => Ok(None),
        }
    }

    /// Writes one record in place of the one before under its key; the other key's stays as it is.
    pub async fn write(&mut self, record: Record<'_>) -> Result<(), StorageError> {
        let mut bytes = [0u8; RECORD_LEN];
        bytes[0] = RECORD_FORMAT_VERSION;
        let body = &mut bytes[1..];
        let (key, body_len) = match record {
            Record::Calibration(calibration) => {
                (CALIBRATION_KEY, postcard::to_slice(&calibration, body).map_err(|_| StorageError::Corrupt)?.len())
            }
            Record::SelfTest(self_test) => {
                body[..self_test.len()].copy_from_slice(self_test);
                (SELF_TEST_KEY, self_test.len())
            }
        };
        self.store(key, &bytes[..1 + body_len]).await
    }

    /// Stores one record as it is.
    async fn store(&mut self, key: u8, record: &[u8]) -> Result<(), StorageError> {
        self.map.store_item(&mut self.buffer, &key, &record).await?;
        Ok(())
    }

    /// The record under `key`, as stored.
    async fn fetch(&mut self, key: u8) -> Result<Option<&[u8]>, StorageError> {
        Ok(self.map.fetch_item(&mut self.buffer, &key).await?)
    }

    /// Gives the flash back (to simulate a reboot on the same flash in tests).
    pub fn into_flash(self) -> F {
        self.map.destroy().0
    }
}

/// The calibration in a record of a known format, migrated to today's; anything else is refused.
fn decode(record: &[u8]) -> Result<Option<Calibration>, StorageError> {
    let (&version, body) = record.split_first().ok_or(StorageError::Corrupt)?;
    let decoded = match version {
        RECORD_FORMAT_VERSION => postcard::from_bytes(body),
        V1_FORMAT_VERSION => return v1::decode(body).ok_or(StorageError::Corrupt),
        _ => return Err(StorageError::Corrupt),
    };
    decoded.map_err(|_| StorageError::Corrupt)
}

#[cfg(test)]
mod tests;
