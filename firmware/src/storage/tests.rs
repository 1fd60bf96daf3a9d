//! Power cuts at every flash operation of a save; erase; corrupted records.

use embassy_futures::block_on;
use shared::calibration::{GyroCalibration, ModelTag, Origin, Procedure, TemperatureModel};
use shared::protocol::LowPassFilter;
use shared::{AccelRange, Calibration};

use super::{Storage, StorageError};
use crate::sim::flash::RamFlash;

/// Four 2 KiB pages: small pages make the store wrap and compact within a few dozen saves.
type Flash = RamFlash<2048, 4>;
const RANGE: core::ops::Range<u32> = 0..(4 * 2048);

fn calibration(n: u32) -> Calibration {
    let tweak = n as f32 * 1e-4;
    Calibration {
        origin: Origin::CHIP_SIX_POSITION,
        range: AccelRange::G2,
        filter: LowPassFilter::Hz21,
        matrix: [[1.0 + tweak, 0.001, 0.0], [0.0, 0.99 - tweak, 0.002], [0.0, 0.0, 1.01]],
        offset_g: [0.02 + tweak, -0.01, 0.07],
        gyro: GyroCalibration {
            matrix: [[1.01, 0.0, 0.0], [0.0, 0.99, 0.0], [0.0, 0.0, 1.0]],
            bias_dps: [0.5, -0.25, tweak],
        },
        mean_temp_c: 25.0 + tweak,
        temperature: Some(TemperatureModel {
            offset_g: [[1e-3, 0.0, -tweak * 1e-2], [0.0; 3], [0.0; 3]],
            ..TemperatureModel::flat(24.0)
        }),
        residual_mg: 0.1,
    }
}

fn boot(flash: Flash) -> (Storage<Flash>, Result<Option<Calibration>, StorageError>) {
    let mut storage = Storage::new(flash, RANGE).unwrap();
    let loaded = block_on(storage.load());
    (storage, loaded)
}

#[test]
fn a_fresh_flash_holds_no_calibration_and_a_save_survives_a_reboot() {
    let (mut storage, loaded) = boot(Flash::new());
    assert_eq!(loaded, Ok(None));
    block_on(storage.save(&calibration(1))).unwrap();
    let (_, loaded) = boot(storage.into_flash());
    assert_eq!(loaded, Ok(Some(calibration(1))));
}

#[test]
fn erase_leaves_no_calibration() {
    let (mut storage, _) = boot(Flash::new());
    block_on(storage.save(&calibration(1))).unwrap();
    block_on(storage.erase()).unwrap();
    let (_, loaded) = boot(storage.into_flash());
    assert_eq!(loaded, Ok(None));
}

#[test]
fn a_cut_after_every_flash_operation_of_every_save_boots_to_the_old_or_the_new_calibration() {
    let (mut storage, _) = boot(Flash::new());
    let mut cuts_tested = 0;
    // Enough saves to fill the pages several times, so cuts land in compaction and page erases too.
    for n in 1..=60u32 {
        let before = storage.into_flash();
        let old = if n == 1 { None } else { Some(calibration(n - 1)) };
        // Count the operations of this save on a copy, then cut at each one of them in turn.
        let mut probe = Storage::new(before.clone(), RANGE).unwrap();
        block_on(probe.save(&calibration(n))).unwrap();
        let operations = probe.into_flash().operations() - before.operations();
        for cut in 0..operations {
            let mut flash = before.clone();
            flash.cut_power_at(cut);
            let mut storage = Storage::new(flash, RANGE).unwrap();
            assert!(block_on(storage.save(&calibration(n))).is_err(), "save {n} survived a cut at {cut}");
            let mut flash = storage.into_flash();
            assert!(flash.was_cut());
            flash.restore_power();
            let (_, loaded) = boot(flash);
            let loaded = loaded.unwrap_or_else(|e| panic!("save {n}, cut at {cut}: {e:?}"));
            assert!(loaded == old || loaded == Some(calibration(n)), "save {n}, cut at {cut}: booted to {loaded:?}");
            cuts_tested += 1;
        }
        let mut storage_next = Storage::new(before, RANGE).unwrap();
        block_on(storage_next.save(&calibration(n))).unwrap();
        storage = storage_next;
    }
    println!("{cuts_tested} power cuts across 60 saves");
    assert!(cuts_tested > 120, "only {cuts_tested} cut points exercised");
}

#[test]
fn a_corrupted_record_is_refused_not_applied() {
    let (mut storage, _) = boot(Flash::new());
    block_on(storage.save(&calibration(3))).unwrap();
    let clean = storage.into_flash();
    let written: Vec<usize> = clean.bytes().enumerate().filter(|(_, b)| *b != 0xFF).map(|(i, _)| i).collect();
    let (mut refused, mut intact) = (0, 0);
    for &offset in &written {
        for bit in [0, 5] {
            let mut flash = clean.clone();
            flash.flip_bit(offset, bit);
            match boot(flash).1 {
                Ok(Some(found)) => {
                    assert_eq!(found, calibration(3), "flip of bit {bit} at {offset} returned an altered calibration");
                    intact += 1;
                }
                Ok(None) | Err(_) => refused += 1,
            }
        }
    }
    println!("{} written bytes: {refused} flips refused, {intact} left the record intact", written.len());
    // The record's own bytes (the bulk of what is written) are CRC-protected: most flips are refused.
    assert!(refused > written.len(), "only {refused} of {} flips refused", 2 * written.len());
}

#[test]
fn an_invalid_calibration_in_a_well_formed_record_is_refused() {
    let (mut storage, _) = boot(Flash::new());
    let mut absurd = calibration(1);
    absurd.offset_g[0] = 3.0;
    block_on(storage.save(&absurd)).unwrap();
    let (_, loaded) = boot(storage.into_flash());
    assert_eq!(loaded, Err(StorageError::Corrupt));
}

/// The flash image record format 1 (the firmware before issue 9) left after one save, on
/// `RamFlash<2048, 4>`: kept, not regenerated, since today's code can no longer write it.
const V1_FLASH_IMAGE: &[u8; 4 * 2048] = include_bytes!("v1_flash.bin");

/// What that image holds, as the old firmware was given it.
fn v1_calibration_migrated() -> Calibration {
    Calibration {
        origin: Origin { procedure: Procedure::HostFit, model: ModelTag::new("ortho9").unwrap() },
        range: AccelRange::G2,
        filter: LowPassFilter::Hz44,
        matrix: [[1.0123, 0.0021, -0.0034], [-0.0011, 0.9876, 0.0045], [0.0007, -0.0018, 1.0211]],
        offset_g: [0.0276, -0.0057, -0.0783],
        gyro: GyroCalibration { bias_dps: [-1.25, 0.75, 0.125], ..GyroCalibration::default() },
        mean_temp_c: 27.5,
        temperature: None,
        residual_mg: 1.5,
    }
}

#[test]
fn a_board_updated_from_record_format_1_boots_with_its_calibration_migrated() {
    let (mut storage, loaded) = boot(Flash::from_bytes(V1_FLASH_IMAGE));
    assert_eq!(loaded, Ok(Some(v1_calibration_migrated())));
    // The next save writes today's format over it, and that reads back as saved.
    block_on(storage.save(&calibration(2))).unwrap();
    let (_, loaded) = boot(storage.into_flash());
    assert_eq!(loaded, Ok(Some(calibration(2))));
}

#[test]
fn a_record_of_an_unknown_format_version_is_refused_as_corrupt_not_misread() {
    let mut record = [0u8; super::RECORD_LEN];
    let body_len = postcard::to_slice(&Some(calibration(4)), &mut record[1..]).unwrap().len();
    for (version, expected) in [
        (super::RECORD_FORMAT_VERSION, Ok(Some(calibration(4)))),
        (3, Err(StorageError::Corrupt)),
        (0, Err(StorageError::Corrupt)),
    ] {
        let (mut storage, _) = boot(Flash::new());
        record[0] = version;
        block_on(storage.store(1, &record[..1 + body_len])).unwrap();
        assert_eq!(boot(storage.into_flash()).1, expected, "format version {version}");
    }
}

#[test]
fn an_erase_written_by_record_format_1_reads_as_no_calibration_and_a_cut_one_as_corrupt() {
    let (mut storage, _) = boot(Flash::new());
    block_on(storage.store(1, &[1, 0])).unwrap(); // format 1, postcard `None`
    let (mut storage, loaded) = boot(storage.into_flash());
    assert_eq!(loaded, Ok(None));
    block_on(storage.store(1, &[1, 1, 0x0c, 0x93])).unwrap(); // format 1, `Some`, cut after two bytes
    assert_eq!(boot(storage.into_flash()).1, Err(StorageError::Corrupt));
}

#[test]
fn the_self_test_and_the_calibration_are_kept_apart_through_saves_erases_and_compactions() {
    let (mut storage, _) = boot(Flash::new());
    assert_eq!(block_on(storage.load_self_test()), Ok(None));
    let record = |n: u8| shared::selftest::SelfTestRecord::from_slice(&[n; 60]).unwrap();
    block_on(storage.write(super::Record::SelfTest(&record(1)))).unwrap();
    // NOTE: 40 saves of 240-byte records fill the four 2 KiB pages several times over.
    for n in 0..40 {
        block_on(storage.save(&calibration(n))).unwrap();
    }
    block_on(storage.erase()).unwrap();
    let (mut storage, loaded) = boot(storage.into_flash());
    assert_eq!((loaded, block_on(storage.load_self_test())), (Ok(None), Ok(Some(record(1)))));
    block_on(storage.save(&calibration(3))).unwrap();
    block_on(storage.write(super::Record::SelfTest(&record(2)))).unwrap();
    let (mut storage, loaded) = boot(storage.into_flash());
    assert_eq!((loaded, block_on(storage.load_self_test())), (Ok(Some(calibration(3))), Ok(Some(record(2)))));
}
