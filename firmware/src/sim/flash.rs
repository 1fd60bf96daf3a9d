//! A RAM NOR flash with power-cut injection, for the storage tests and the simulated device.
//!
//! Behaves like the STM32F4's flash as sequential-storage sees it: erase sets a page to 0xFF, a
//! write may only clear bits of erased words. A power cut interrupts one operation halfway (half the
//! words of a write land, half of an erased page is left as it was) and fails everything after it
//! until power returns, as a board that lost power and rebooted would see.

use embedded_storage_async::nor_flash::{ErrorType, NorFlash, NorFlashError, NorFlashErrorKind, ReadNorFlash};

/// Flash errors of the simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FlashFault {
    /// Power was cut during or before this operation.
    PowerCut,
    /// An address or length outside the flash or not aligned.
    OutOfBounds,
}

impl NorFlashError for FlashFault {
    fn kind(&self) -> NorFlashErrorKind {
        match self {
            FlashFault::PowerCut => NorFlashErrorKind::Other,
            FlashFault::OutOfBounds => NorFlashErrorKind::OutOfBounds,
        }
    }
}

/// A flash of `PAGES` erase pages of `PAGE` bytes.
#[derive(Debug, Clone)]
pub struct RamFlash<const PAGE: usize, const PAGES: usize> {
    pages: [[u8; PAGE]; PAGES],
    operations: u32,
    cut_at: Option<u32>,
    powered: bool,
}

impl<const PAGE: usize, const PAGES: usize> Default for RamFlash<PAGE, PAGES> {
    fn default() -> Self {
        RamFlash { pages: [[0xFF; PAGE]; PAGES], operations: 0, cut_at: None, powered: true }
    }
}

impl<const PAGE: usize, const PAGES: usize> RamFlash<PAGE, PAGES> {
    /// An erased flash.
    pub fn new() -> Self {
        Self::default()
    }

    /// A flash holding `image` (a dump of [`Self::bytes`]), as a board's flash after a firmware update;
    /// bytes beyond the flash are ignored, a short image leaves the rest erased.
    pub fn from_bytes(image: &[u8]) -> Self {
        let mut flash = Self::default();
        for (page, bytes) in flash.pages.iter_mut().zip(image.chunks_exact(PAGE)) {
            page.copy_from_slice(bytes);
        }
        flash
    }

    /// Writes and erases done so far.
    pub fn operations(&self) -> u32 {
        self.operations
    }

    /// Cuts the power in the middle of the `n`-th write or erase from now (0 = the next one).
    pub fn cut_power_at(&mut self, n: u32) {
        self.cut_at = Some(self.operations + n);
    }

    /// Restores power (a reboot): operations work again, the contents are as the cut left them.
    pub fn restore_power(&mut self) {
        self.powered = true;
        self.cut_at = None;
    }

    /// Whether a planned power cut has happened.
    pub fn was_cut(&self) -> bool {
        !self.powered
    }

    /// Flips one bit of the contents (a corrupted record).
    pub fn flip_bit(&mut self, offset: usize, bit: u8) {
        self.pages[offset / PAGE][offset % PAGE] ^= 1 << bit;
    }

    /// The contents, for comparisons in tests.
    pub fn bytes(&self) -> impl Iterator<Item = u8> + '_ {
        self.pages.iter().flatten().copied()
    }

    /// Counts an operation; `Ok(true)` when it runs whole, `Ok(false)` when the cut interrupts it.
    fn begin_operation(&mut self) -> Result<bool, FlashFault> {
        if !self.powered {
            return Err(FlashFault::PowerCut);
        }
        let index = self.operations;
        self.operations += 1;
        if self.cut_at == Some(index) {
            self.powered = false;
            return Ok(false);
        }
        Ok(true)
    }

    fn check(&self, offset: u32, len: usize, align: usize) -> Result<usize, FlashFault> {
        let offset = offset as usize;
        if !offset.is_multiple_of(align) || !len.is_multiple_of(align) || offset + len > PAGE * PAGES {
            return Err(FlashFault::OutOfBounds);
        }
        Ok(offset)
    }
}

impl<const PAGE: usize, const PAGES: usize> ErrorType for RamFlash<PAGE, PAGES> {
    type Error = FlashFault;
}

impl<const PAGE: usize, const PAGES: usize> ReadNorFlash for RamFlash<PAGE, PAGES> {
    const READ_SIZE: usize = 1;

    async fn read(&mut self, offset: u32, bytes: &mut [u8]) -> Result<(), FlashFault> {
        let start = self.check(offset, bytes.len(), 1)?;
        for (i, byte) in bytes.iter_mut().enumerate() {
            *byte = self.pages[(start + i) / PAGE][(start + i) % PAGE];
        }
        Ok(())
    }

    fn capacity(&self) -> usize {
        PAGE * PAGES
    }
}

impl<const PAGE: usize, const PAGES: usize> NorFlash for RamFlash<PAGE, PAGES> {
    /// NOTE: the STM32F411 programs 32 bits at a time at 2.7-3.6 V (RM0383 section 3.6.2, PSIZE x32).
    const WRITE_SIZE: usize = 4;
    const ERASE_SIZE: usize = PAGE;

    async fn erase(&mut self, from: u32, to: u32) -> Result<(), FlashFault> {
        let start = self.check(from, (to - from) as usize, PAGE)?;
        for page in start / PAGE..to as usize / PAGE {
            let whole = self.begin_operation()?;
            let erased = if whole { PAGE } else { PAGE / 2 };
            self.pages[page][..erased].fill(0xFF);
            if !whole {
                return Err(FlashFault::PowerCut);
            }
        }
        Ok(())
    }

    async fn write(&mut self, offset: u32, bytes: &[u8]) -> Result<(), FlashFault> {
        let start = self.check(offset, bytes.len(), Self::WRITE_SIZE)?;
        let whole = self.begin_operation()?;
        let words = bytes.len() / Self::WRITE_SIZE;
        let landed = if whole { bytes.len() } else { words / 2 * Self::WRITE_SIZE };
        for (i, &byte) in bytes[..landed].iter().enumerate() {
            // NOR flash programming only clears bits.
            self.pages[(start + i) / PAGE][(start + i) % PAGE] &= byte;
        }
        if whole {
            Ok(())
        } else {
            Err(FlashFault::PowerCut)
        }
    }
}
