// Runs the real Pico binary (the UF2 `cargo xtask dist` writes) under rp2040js, for accelcal's
// bridge (host/src/sim/emulated): `node harness.mjs accelcal-pico.uf2`.
//
// The bridge owns the world around the chip: the simulated MPU-6050 on its I2C0 bus, the pseudo-
// terminal its USB serial port appears on, and the clock on the wall. It talks to this process in
// lines: what the chip does goes out on stdout, and at every poll (each POLL_NS of emulated time) this
// process waits for the bridge's answer on stdin, so the two stay in step. Lines out:
//   s NS            an I2C transaction starts at emulated time NS (S: a repeated start)
//   c ADDR R        the chip addresses ADDR to read (R = 1) or write (0); answered "a 1" (ack) or "a 0"
//   w BYTE          the chip writes BYTE
//   r               the chip reads a byte; answered "b BYTE"
//   p               stop
//   u HEX           the device sent these bytes over USB
//   open            the USB serial port exists (the device is enumerated and configured)
//   t NS CYCLES     a poll: emulated time and the cycles the CPU has executed (not asleep) so far;
//                   answered by lines "h HEX" (bytes for the device), "power" (a power cycle: the chip
//                   restarts from its flash), "cable 0" / "cable 1" (the USB cable pulled: the chip
//                   loses its power / plugged in: it boots from its flash),
//                   "port 0" / "port 1" (the host's program closed / opened the port: DTR falls / rises),
//                   then "."
// Anything wrong (a fault, a ROM function the stand-in lacks) is said on stderr and ends the process.

import { readFileSync, readSync, writeSync } from 'node:fs';
import { BasePeripheral, ConsoleLogger, LogLevel, Simulator } from 'rp2040js';
import { CdcHost } from './cdc-host.mjs';
import { RomCalls, romImage, xipControlStandIn } from './rom.mjs';
import { loadUf2 } from './uf2.mjs';

/** Emulated time between polls of the bridge: short against the firmware's 10 ms sensor poll. */
const POLL_NS = 1_000_000;
/** IC_RAW_INTR_STAT's TX_EMPTY bit (RP2040 datasheet 4.3.17). */
const I2C_TX_EMPTY = 1 << 4;
/** The RP2040's system clock as the firmware sets it (embassy-rp's default, 125 MHz). */
const NS_PER_CYCLE = 8;

function fail(message) {
  process.stderr.write(`pico emulator: ${message}\n`);
  process.exit(3);
}

/** Line I/O with the bridge, synchronous so that the emulated chip waits for each answer. */
class Bridge {
  constructor() {
    this.buffer = '';
    this.chunk = Buffer.alloc(65536);
  }
  send(line) {
    try {
      writeSync(1, `${line}\n`);
    } catch (e) {
      if (e.code === 'EPIPE') process.exit(0); // the bridge is gone
      throw e;
    }
  }
  receive() {
    while (!this.buffer.includes('\n')) {
      let n;
      try {
        n = readSync(0, this.chunk, 0, this.chunk.length, null);
      } catch (e) {
        if (e.code === 'EAGAIN') continue;
        throw e;
      }
      if (n === 0) process.exit(0); // the bridge is gone
      this.buffer += this.chunk.toString('latin1', 0, n);
    }
    const end = this.buffer.indexOf('\n');
    const line = this.buffer.slice(0, end);
    this.buffer = this.buffer.slice(end + 1);
    return line;
  }
  ask(line, prefix) {
    this.send(line);
    const answer = this.receive();
    if (!answer.startsWith(prefix)) fail(`the bridge answered '${answer}' to '${line}'`);
    return Number(answer.slice(prefix.length));
  }
}

/** One powered-up chip: the ROM stand-in, the flash contents, the I2C0 bus and the USB host. */
class Chip {
  constructor(flash, bridge, timeBase) {
    this.bridge = bridge;
    this.timeBase = timeBase;
    // NOTE: the Simulator only for its chip and clock; this process runs the CPU itself (`run`).
    const { rp2040: mcu, clock } = new Simulator();
    this.clock = clock;
    mcu.logger = new ConsoleLogger(LogLevel.Error);
    mcu.loadBootrom(romImage());
    mcu.flash.set(flash);
    mcu.peripherals[0x14000] = xipControlStandIn(BasePeripheral, mcu);
    const rom = new RomCalls(mcu, fail);
    mcu.onBreak = (n) => rom.breakpoint(n);
    this.mcu = mcu;
    this.wireI2c(mcu.i2c[0]);
    this.usb = new CdcHost(mcu.usbCtrl, {
      onData: (bytes) => bridge.send(`u ${Buffer.from(bytes).toString('hex')}`),
      onReady: () => bridge.send('open'),
    });
    this.busyCycles = 0;
  }

  get nanos() {
    return this.timeBase + this.clock.nanos;
  }

  /** I2C0 to the bridge's simulated sensor, event by event. */
  wireI2c(i2c) {
    const { bridge } = this;
    i2c.onStart = (repeated) => {
      bridge.send(repeated ? 'S' : `s ${Math.round(this.nanos)}`);
      i2c.completeStart();
    };
    i2c.onConnect = (address, mode) => {
      const acknowledged = bridge.ask(`c ${address} ${mode}`, 'a ') === 1;
      i2c.completeConnect(acknowledged);
      // NOTE: the hardware raises TX_EMPTY from the FIFO's level, so also when an abort (here: no
      // device acknowledged) flushes it (RP2040 datasheet 4.3.17, IC_RAW_INTR_STAT); rp2040js 1.4.1
      // flushes without raising it, and embassy-rp's blocking write waits for it forever.
      if (!acknowledged) i2c.setInterrupts(I2C_TX_EMPTY);
    };
    i2c.onWriteByte = (value) => {
      bridge.send(`w ${value}`);
      i2c.completeWrite(true);
    };
    i2c.onReadByte = () => i2c.completeRead(bridge.ask('r', 'b '));
    i2c.onStop = () => {
      bridge.send('p');
      i2c.completeStop();
    };
  }

  /** Runs the CPU for `nanos` of emulated time; asleep (WFI), time jumps to the next event. */
  run(nanos) {
    const { mcu, clock } = this;
    const until = clock.nanos + nanos;
    while (clock.nanos < until) {
      if (mcu.core.waiting) {
        // NOTE: nanosToNextAlarm is 0 when no alarm is set.
        const next = clock.nanosToNextAlarm || Infinity;
        clock.tick(Math.max(1, Math.min(next, until - clock.nanos)));
      } else {
        const cycles = mcu.core.executeInstruction();
        this.busyCycles += cycles;
        clock.tick(cycles * NS_PER_CYCLE);
      }
    }
  }
}

function main() {
  const [uf2Path] = process.argv.slice(2);
  if (!uf2Path) fail('usage: node harness.mjs FIRMWARE.uf2');
  const flash = new Uint8Array(2 * 1024 * 1024).fill(0xff);
  loadUf2(readFileSync(uf2Path), flash, fail);
  const bridge = new Bridge();
  // NOTE: a Pico on USB runs from the cable's VBUS (Pico datasheet 4.5): pulling the cable powers it
  // off, plugging it in boots it from its flash. `chip` is null while the cable is out.
  let chip = new Chip(flash, bridge, 0);
  let kept = { flash, nanos: 0, cycles: 0 };
  const powerOff = () => {
    kept = { flash: chip.mcu.flash.slice(0, flash.length), nanos: chip.nanos, cycles: kept.cycles + chip.busyCycles };
    chip = null;
  };
  const powerOn = () => {
    chip = new Chip(kept.flash, bridge, kept.nanos);
  };
  let portOpen = false;
  for (;;) {
    if (chip) chip.run(POLL_NS);
    else kept.nanos += POLL_NS;
    const [nanos, cycles] = chip ? [chip.nanos, kept.cycles + chip.busyCycles] : [kept.nanos, kept.cycles];
    bridge.send(`t ${Math.round(nanos)} ${cycles}`);
    for (let line = bridge.receive(); line !== '.'; line = bridge.receive()) {
      if (line.startsWith('h ')) chip?.usb.send(Buffer.from(line.slice(2), 'hex'));
      else if (line === 'power') {
        // The flash keeps what was written; RAM, registers and the USB connection start afresh.
        if (chip) {
          powerOff();
          powerOn();
        }
      } else if (line === 'cable 0') {
        if (chip) powerOff();
      } else if (line === 'cable 1') {
        if (!chip) powerOn();
      } else if (line === 'port 0' || line === 'port 1') portOpen = line === 'port 1';
      else fail(`the bridge sent '${line}'`);
    }
    if (chip && chip.usb.portOpen !== portOpen) chip.usb.setPortOpen(portOpen);
  }
}

main();
