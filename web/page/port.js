// The page's port (web/src/browser/transport.rs, PagePort): a Web Serial port as the core's link
// wants it: bytes written whole, reads that wait a short while at most, the clocks, the person's Stop.

/// How long a read waits for bytes before it answers "nothing yet", in milliseconds: the link judges
/// silence by its own clock and reads again.
const READ_WAIT_MS = 50;
const NOTHING = new Uint8Array(0);

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

export class PagePort {
  /// Opens `serial` (a SerialPort, or the simulated one) at `baudRate` (a USB board ignores it).
  static async open(serial, baudRate = 115200) {
    await serial.open({ baudRate });
    return new PagePort(serial);
  }

  constructor(serial) {
    this.serial = serial;
    this.reader = serial.readable.getReader();
    this.writer = serial.writable.getWriter();
    this.openedMs = performance.now();
    this.pending = null;
    this.stopped = false;
  }

  write(bytes) {
    // NOTE: a copy: `bytes` is a view of the module's memory, which the next allocation may move.
    return this.writer.write(new Uint8Array(bytes));
  }

  read() {
    // NOTE: a read the wait gave up on stays pending and is the next call's: no chunk is lost.
    this.pending ??= this.reader.read().then((result) => ({ result }), (error) => ({ error }));
    const pending = this.pending;
    return Promise.race([pending, sleep(READ_WAIT_MS).then(() => null)]).then((won) => {
      if (won === null) return NOTHING;
      this.pending = null;
      if (won.error) throw new Error(`the board's port failed: ${won.error.message ?? won.error}`);
      if (won.result.done) throw new Error("the board's port closed (the cable was pulled or the board restarted)");
      return won.result.value;
    });
  }

  nowSeconds() {
    return (performance.now() - this.openedMs) / 1000;
  }

  unixTimeSeconds() {
    return Date.now() / 1000;
  }

  /// A simulated board's own clock when the port has one, else the host's since the port was opened.
  boardSeconds() {
    return this.serial.accelcalBoardSeconds?.() ?? this.nowSeconds();
  }

  interrupted() {
    return this.stopped;
  }

  async close() {
    try {
      this.reader.releaseLock();
      this.writer.releaseLock();
      await this.serial.close();
    } catch {
      // NOTE: a port whose cable was pulled is closed already.
    }
  }
}
