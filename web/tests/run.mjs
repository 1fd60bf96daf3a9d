// Runs accelcal-web's WebAssembly under node and prints the JSON it computed, for
// wasm_matches_native.rs to compare with the same function compiled natively.
//
// Usage: node web/tests/run.mjs <accelcal_web.wasm> <seed>   (seed: 0 to 2^64 - 1)
// Exits 1 with a message on stderr on any failure.

import { readFile } from "node:fs/promises";

// NOTE: the core's plotters depends on wasm-bindgen on wasm32, and a cdylib exports every
// `#[no_mangle]` function of its dependencies, wasm-bindgen's included; those call into these two
// modules, which only the wasm-bindgen tool fills in. Nothing the core computes calls them: each is
// given a function that throws, so a call fails the run instead of changing its result. Any other
// import is refused.
const UNCALLED_MODULES = ["__wbindgen_placeholder__", "__wbindgen_externref_xform__"];

function fail(message) {
  process.stderr.write(`run.mjs: ${message}\n`);
  process.exit(1);
}

// The seed as a BigInt, refused unless it is a whole number that fits in 64 bits.
function parseSeed(text) {
  if (!/^[0-9]+$/.test(text ?? "")) fail(`the seed must be a whole number, not ${JSON.stringify(text)}`);
  const seed = BigInt(text);
  if (seed >= 1n << 64n) fail(`the seed ${text} does not fit in 64 bits`);
  return seed;
}

// The module's imports, each a function that throws: refused unless all are wasm-bindgen's.
function uncalledImports(module) {
  const imports = {};
  for (const { module: name, name: field, kind } of WebAssembly.Module.imports(module)) {
    if (!UNCALLED_MODULES.includes(name) || kind !== "function") {
      fail(`the module imports ${kind} ${name}.${field}; it must run with nothing from JavaScript`);
    }
    imports[name] ??= {};
    imports[name][field] = () => {
      throw new Error(`the module called ${name}.${field}, which only wasm-bindgen provides`);
    };
  }
  return imports;
}

// The result the module left in its memory: `length` bytes of UTF-8 at `result_ptr()`.
function readResult(exports, length) {
  // NOTE: `>>> 0`: wasm's i32 comes back signed; pointers and lengths are unsigned.
  const pointer = exports.result_ptr() >>> 0;
  const bytes = new Uint8Array(exports.memory.buffer, pointer, length >>> 0);
  return new TextDecoder("utf-8", { fatal: true }).decode(bytes);
}

async function main() {
  const [wasmPath, seedText] = process.argv.slice(2);
  if (!wasmPath) fail("usage: node run.mjs <accelcal_web.wasm> <seed>");
  const seed = parseSeed(seedText);
  const module = await WebAssembly.compile(await readFile(wasmPath));
  const { exports } = await WebAssembly.instantiate(module, uncalledImports(module));
  for (const name of ["memory", "simulated_session", "result_ptr"]) {
    if (!(name in exports)) fail(`${wasmPath} exports no ${name}`);
  }
  const length = exports.simulated_session(Number(seed & 0xffffffffn), Number(seed >> 32n));
  process.stdout.write(readResult(exports, length));
}

main().catch((error) => fail(error?.stack ?? String(error)));
