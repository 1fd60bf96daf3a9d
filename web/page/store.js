// The run kept in the browser (IndexedDB) after every capture, so that a reload, a closed tab or a
// pulled cable resumes it, as `accelcal calibrate --resume` does.

const DB = "accelcal";
const STORE = "sessions";
const KEY = "current";

function database() {
  return new Promise((resolve, reject) => {
    const request = indexedDB.open(DB, 1);
    request.onupgradeneeded = () => request.result.createObjectStore(STORE);
    request.onsuccess = () => resolve(request.result);
    request.onerror = () => reject(request.error);
  });
}

async function transaction(mode, act) {
  const db = await database();
  return new Promise((resolve, reject) => {
    const tx = db.transaction(STORE, mode);
    const request = act(tx.objectStore(STORE));
    tx.oncomplete = () => resolve(request.result);
    tx.onerror = () => reject(tx.error);
  });
}

// NOTE: one write after another, in the order the run kept them: a later session never loses to an
// earlier one that finished last.
let writes = Promise.resolve();

/// Keeps the session's JSON text; resolves once it is written.
export function keepSession(json) {
  writes = writes.then(() => transaction("readwrite", (store) => store.put({ json, keptAt: Date.now() }, KEY)));
  return writes;
}

/// The kept session's JSON text, or null.
export async function keptSession() {
  await writes;
  const kept = await transaction("readonly", (store) => store.get(KEY));
  return kept?.json ?? null;
}

/// Forgets the kept session (it was finished or discarded).
export function forgetSession() {
  writes = writes.then(() => transaction("readwrite", (store) => store.delete(KEY)));
  return writes;
}
