//! Board facts the library needs: where the calibration lives in the STM32F411CE's flash.

use core::ops::Range;

/// Byte offsets, from the start of flash, of the sectors holding the calibration: sectors 6 and 7
/// (0x08040000-0x0807FFFF, 128 KiB each, RM0383 table 5). `memory.x` keeps them out of FLASH as
/// its CALIBRATION region; the two must agree.
pub const CALIBRATION_FLASH_RANGE: Range<u32> = 0x0004_0000..0x0008_0000;
