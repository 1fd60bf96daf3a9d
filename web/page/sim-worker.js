// The simulated board's worker (sim-serial.js talks to it): accelcal's firmware on the simulated
// MPU-6050 (web/src/browser/simulated.rs, SimulatedBoard), stepped as the page reads, and the hand
// that turns it. Messages are handled one after another, in the order they came.

import init, { SimulatedBoard } from "./pkg/accelcal_web.js";

let board = null;
let queue = init();

const handlers = {
  boot: ({ seed }) => {
    board = new SimulatedBoard(BigInt(seed));
  },
  write: ({ bytes }) => board.write(bytes),
  read: () => board.read(),
  "new-hand": () => board.newHand(),
  avoid: ({ ups }) => board.avoid(Float64Array.from(ups)),
  present: ({ name, up }) => board.present(name, Float64Array.from(up)),
  fresh: ({ index }) => board.fresh(index),
  quarter: () => board.turnQuarter(),
};

function handle({ id, kind, ...message }) {
  try {
    const bytes = handlers[kind](message);
    const boardSeconds = board?.boardSeconds();
    self.postMessage({ id, bytes, boardSeconds });
  } catch (error) {
    self.postMessage({ id, error: `${kind}: ${error?.message ?? error}` });
  }
}

self.onmessage = ({ data }) => {
  queue = queue.then(() => handle(data));
};
