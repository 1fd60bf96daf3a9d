// A simulated serial port with the Web Serial API's shape (open, readable, writable, close): behind
// it, in a Web Worker (sim-worker.js), accelcal's firmware on the simulated MPU-6050, and the
// tool's own hand on it, which follows the page's prompts (the "accelcal:*" events) as
// `accelcal calibrate --sim --seed SEED` turns its board. The page's "Try it with a simulated board"
// and the tests' fake `navigator.serial` use it.

class SimulatedPort {
  constructor(seed) {
    this.seed = BigInt(seed);
    this.boardSeconds = 0;
    this.calls = new Map();
    this.nextId = 0;
    this.listeners = [];
  }

  // One request to the worker; resolves with its answer. The worker answers in the order asked.
  call(message, transfer = []) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.calls.set(id, { resolve, reject });
      this.worker.postMessage({ id, ...message }, transfer);
    });
  }

  answered({ data }) {
    const call = this.calls.get(data.id);
    this.calls.delete(data.id);
    if (data.error) return call?.reject(new Error(data.error));
    if (data.boardSeconds !== undefined) this.boardSeconds = data.boardSeconds;
    call?.resolve(data.bytes);
  }

  async open() {
    this.worker = new Worker(new URL("./sim-worker.js", import.meta.url), { type: "module" });
    this.worker.onmessage = (event) => this.answered(event);
    await this.call({ kind: "boot", seed: this.seed });
    this.follow();
    // NOTE: highWaterMark 0: the worker's board steps only when the page reads (lockstep, as
    // `calibrate --sim` runs its board), never ahead of it.
    this.readable = new ReadableStream(
      { pull: async (controller) => controller.enqueue(await this.call({ kind: "read" })) },
      { highWaterMark: 0 },
    );
    this.writable = new WritableStream({ write: (chunk) => this.call({ kind: "write", bytes: chunk }) });
    this.readableController = null;
  }

  // The hand follows the page's prompts: each is posted before the run goes on, so it reaches the
  // board before the run's next read.
  follow() {
    const on = (name, message) => {
      const listener = (event) => this.post(message(event.detail));
      window.addEventListener(name, listener);
      this.listeners.push([name, listener]);
    };
    on("accelcal:new-hand", () => ({ kind: "new-hand" }));
    on("accelcal:avoid", ({ ups }) => ({ kind: "avoid", ups }));
    on("accelcal:prompt", ({ kind, name, up, index }) => ({ kind, name, up, index }));
  }

  post(message) {
    this.call(message).catch((error) => console.error(`the simulated hand: ${error.message}`));
  }

  /// The simulated board's own clock, in seconds (web/page/port.js reads it).
  accelcalBoardSeconds() {
    return this.boardSeconds;
  }

  /// Pulls the cable: reads and writes fail from now on, as a real port's do.
  pullCable() {
    this.pulled = true;
    const gone = new DOMException("The device has been lost.", "NetworkError");
    for (const { reject } of this.calls.values()) reject(gone);
    this.calls.clear();
    this.worker.terminate();
    this.worker = { postMessage: () => { throw gone; } };
  }

  async close() {
    for (const [name, listener] of this.listeners) window.removeEventListener(name, listener);
    if (!this.pulled) this.worker.terminate();
  }

  getInfo() {
    return { usbVendorId: undefined, usbProductId: undefined };
  }
}

/// A simulated port whose board and hand are those of `seed` (a BigInt or a whole number).
export function simulatedPort(seed) {
  return new SimulatedPort(seed);
}

/// A stand-in for `navigator.serial` whose one port is the simulated board of `seed`.
export function simulatedSerial(seed) {
  let port = null;
  return {
    async requestPort() {
      port = simulatedPort(seed);
      return port;
    },
    async getPorts() {
      return port ? [port] : [];
    },
    addEventListener() {},
    removeEventListener() {},
  };
}
