// The harness's own stand-in for the RP2040 boot ROM: no byte of Raspberry Pi's ROM is used.
//
// The firmware needs three things of the ROM: the reset vector that starts the second-stage
// bootloader at the start of the flash, the magic and table pointers at 0x10-0x19 through which
// embassy-rp looks functions up (RP2040 datasheet 2.8.3, "Bootrom Contents"), and the flash functions
// (connect, exit XIP, erase, program, flush, enter XIP) and memcpy44 it calls to store the calibration.
// The image below holds a few hand-assembled Thumb instructions for the reset; each function is a
// `bkpt #n; bx lr` pair whose breakpoint the harness answers in JavaScript (`RomCalls`), working on the
// emulator's flash array as the NOR flash behaves (erase to 0xFF, programming only clears bits).

/** Where the stand-in's pieces sit in the ROM (byte addresses). */
const RESET_CODE = 0x100;
const FAULT_CODE = 0x120;
const LOOKUP_CODE = 0x140;
const FUNCTION_TABLE = 0x200;
const DATA_TABLE = 0x300;
const FUNCTION_STUBS = 0x400;
/** The breakpoint numbers: the lookup, a fault, and the first function's (the rest follow). */
const BKPT_LOOKUP = 0x01;
const BKPT_FAULT = 0xfe;
const BKPT_FIRST_FUNCTION = 0x10;
/** Top of the striped SRAM: the initial stack pointer. */
const STACK_TOP = 0x20042000;
/** The flash's XIP base: the second-stage bootloader is its first 256 bytes. */
const FLASH_BASE = 0x10000000;
/** NOR flash erases in 4 KiB sectors (the flash_range_erase contract). */
const SECTOR_BYTES = 4096;

/** A ROM table code: two ASCII characters, the first in the low byte (datasheet 2.8.3.1.1). */
const code = (name) => name.charCodeAt(0) | (name.charCodeAt(1) << 8);

/** The functions the stand-in provides, in stub order: the flash functions and memcpy44. */
const FUNCTIONS = ['IF', 'EX', 'RE', 'RP', 'FC', 'CX', 'C4'];

/** Thumb encodings used below (ARMv6-M Architecture Reference Manual, A6.7). */
const thumb = {
  movsR0Zero: 0x2000, // movs r0, #0
  movLrR0: 0x4686, // mov lr, r0
  ldrR1Pc1: 0x4901, // ldr r1, [pc, #4]
  bxR1: 0x4708, // bx r1
  bxLr: 0x4770, // bx lr
  nop: 0xbf00,
  branchSelf: 0xe7fe, // b .
  bkpt: (n) => 0xbe00 | n,
};

/** Builds the ROM image (16 KiB, as rp2040js's boot ROM array). */
export function romImage() {
  const bytes = new Uint8Array(16 * 1024);
  const view = new DataView(bytes.buffer);
  const half = (at, value) => view.setUint16(at, value, true);
  const word = (at, value) => view.setUint32(at, value >>> 0, true);
  word(0x00, STACK_TOP);
  word(0x04, RESET_CODE | 1);
  word(0x08, FAULT_CODE | 1); // NMI
  word(0x0c, FAULT_CODE | 1); // HardFault
  bytes.set([0x4d, 0x75, 0x01, 0x03], 0x10); // 'M', 'u', 1, version 3 (the B2 chip's)
  half(0x14, FUNCTION_TABLE);
  half(0x16, DATA_TABLE);
  half(0x18, LOOKUP_CODE | 1);
  // Reset: as the real ROM does after checking the flash, run the second stage with lr = 0, which
  // tells it to start the image's vector table afterwards (pico-sdk boot_stage2 "exit_from_boot2").
  [thumb.movsR0Zero, thumb.movLrR0, thumb.ldrR1Pc1, thumb.bxR1, thumb.nop, thumb.nop].forEach((h, i) =>
    half(RESET_CODE + 2 * i, h),
  );
  word(RESET_CODE + 12, FLASH_BASE | 1);
  half(FAULT_CODE, thumb.bkpt(BKPT_FAULT));
  half(FAULT_CODE + 2, thumb.branchSelf);
  half(LOOKUP_CODE, thumb.bkpt(BKPT_LOOKUP));
  half(LOOKUP_CODE + 2, thumb.bxLr);
  FUNCTIONS.forEach((name, i) => {
    const stub = FUNCTION_STUBS + 4 * i;
    half(stub, thumb.bkpt(BKPT_FIRST_FUNCTION + i));
    half(stub + 2, thumb.bxLr);
    half(FUNCTION_TABLE + 4 * i, code(name));
    half(FUNCTION_TABLE + 4 * i + 2, stub | 1);
  });
  half(FUNCTION_TABLE + 4 * FUNCTIONS.length, 0); // end of the table; the data table is empty
  half(DATA_TABLE, 0);
  return new Uint32Array(bytes.buffer);
}

/** Answers the stand-in's breakpoints on one emulated chip. */
export class RomCalls {
  /** `fail(message)` is called for anything the stand-in does not provide. */
  constructor(mcu, fail) {
    this.mcu = mcu;
    this.fail = fail;
  }

  /** Handles breakpoint `n`; the `bx lr` after it returns to the caller. */
  breakpoint(n) {
    const r = this.mcu.core.registers;
    if (n === BKPT_LOOKUP) {
      r[0] = this.lookup(r[0], r[1]);
    } else if (n === BKPT_FAULT) {
      this.fail(`the firmware faulted (HardFault or NMI) near lr 0x${r[14].toString(16)}`);
    } else if (n >= BKPT_FIRST_FUNCTION && n < BKPT_FIRST_FUNCTION + FUNCTIONS.length) {
      this.call(FUNCTIONS[n - BKPT_FIRST_FUNCTION], r);
    } else {
      this.fail(`the firmware hit a breakpoint (bkpt #${n}) at 0x${this.mcu.core.PC.toString(16)}`);
    }
  }

  /** rom_table_lookup(table, code): the function's address, or 0 (as the real ROM) when unknown. */
  lookup(table, wanted) {
    if (table === FUNCTION_TABLE) {
      const index = FUNCTIONS.findIndex((name) => code(name) === wanted);
      if (index >= 0) return (FUNCTION_STUBS + 4 * index) | 1;
    }
    const name = String.fromCharCode(wanted & 0xff, wanted >> 8);
    this.fail(`the firmware looked up ROM ${table === DATA_TABLE ? 'data' : 'function'} '${name}', which the stand-in lacks`);
    return 0;
  }

  /** One ROM function, arguments in r0-r3 as the AAPCS passes them. */
  call(name, r) {
    const flash = this.mcu.flash;
    if (name === 'RE') {
      const [offset, count] = [r[0], r[1]];
      if (offset % SECTOR_BYTES || count % SECTOR_BYTES) this.fail(`flash erase not sector-aligned: 0x${offset.toString(16)}+${count}`);
      flash.fill(0xff, offset, offset + count);
    } else if (name === 'RP') {
      const [offset, data, count] = [r[0], r[1], r[2]];
      for (let i = 0; i < count; i++) flash[offset + i] &= this.mcu.readUint8(data + i);
    } else if (name === 'C4') {
      const [dest, src, count] = [r[0], r[1], r[2]];
      for (let i = 0; i < count; i += 4) this.mcu.writeUint32(dest + i, this.mcu.readUint32(src + i));
    }
    // IF, EX, FC, CX: the emulator reads the flash array directly, so connecting the flash, leaving
    // and entering XIP mode and flushing its cache have nothing to do.
  }
}

/**
 * XIP_CTRL (0x14000000), which rp2040js does not model: embassy-rp waits for its stream counter to
 * reach zero before a flash operation, and reads its status. The cache is not modelled: nothing
 * streams, the FIFO is empty and a flush is complete at once (datasheet 2.6.3.7, STAT and STREAM_CTR).
 */
export function xipControlStandIn(BasePeripheral, mcu) {
  const STAT = 0x08;
  const STREAM_CTR = 0x18;
  const FIFO_EMPTY_AND_FLUSH_READY = 0b11;
  class XipControl extends BasePeripheral {
    constructor() {
      super(mcu, 'XIP_CTRL');
      this.registers = new Map();
    }
    readUint32(offset) {
      if (offset === STAT) return FIFO_EMPTY_AND_FLUSH_READY;
      if (offset === STREAM_CTR) return 0;
      return this.registers.get(offset) ?? 0;
    }
    writeUint32(offset, value) {
      this.registers.set(offset, value);
    }
  }
  return new XipControl();
}
