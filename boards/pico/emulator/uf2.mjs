// Reads a UF2 file into a flash image (the UF2 specification, github.com/microsoft/uf2: 512-byte
// blocks, each with its target address and up to 476 bytes of payload).

const BLOCK_BYTES = 512;
const MAGIC_START0 = 0x0a324655;
const MAGIC_START1 = 0x9e5d5157;
const MAGIC_END = 0x0ab16f30;
const FLAG_FAMILY_ID = 0x2000;
/** The RP2040's family id (as xtask/src/uf2.rs writes it). */
const RP2040_FAMILY = 0xe48bff56;
const FLASH_BASE = 0x10000000;

/** Writes every block of `file` into `flash` (offsets from the XIP base); `fail(message)` on a bad file. */
export function loadUf2(file, flash, fail) {
  if (file.length === 0 || file.length % BLOCK_BYTES) fail(`not a UF2 file: ${file.length} bytes is no whole number of blocks`);
  const view = new DataView(file.buffer, file.byteOffset, file.byteLength);
  for (let at = 0; at < file.length; at += BLOCK_BYTES) {
    const word = (offset) => view.getUint32(at + offset, true);
    if (word(0) !== MAGIC_START0 || word(4) !== MAGIC_START1 || word(508) !== MAGIC_END) fail(`not a UF2 block at byte ${at}`);
    if (word(8) & FLAG_FAMILY_ID && word(28) !== RP2040_FAMILY) fail(`a block for family 0x${word(28).toString(16)}, not the RP2040's`);
    const [address, size] = [word(12), word(16)];
    const offset = address - FLASH_BASE;
    if (offset < 0 || size > 476 || offset + size > flash.length) fail(`a block outside the flash: 0x${address.toString(16)}`);
    flash.set(file.subarray(at + 32, at + 32 + size), offset);
  }
}
