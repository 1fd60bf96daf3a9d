// Drives the built web page in headless Chromium (Debian's /usr/bin/chromium, or $CHROMIUM) for
// web/tests/page.rs, with a fake `navigator.serial` whose one port is the simulated board of a seed
// (web/page/sim-serial.js: the firmware in a Web Worker, the hand following the page's prompts).
//
// Usage: node drive.mjs calibrate PAGE_DIR OUT_DIR SEED DATE_MS CLI_JSON CLI_HTML
//          the whole run; writes OUT_DIR/page.json (the page's result), report.html, certificate.json,
//          compare.json (the page's report and report page against the CLI's), timing.json, step-*.png
//        node drive.mjs resume PAGE_DIR OUT_DIR SEED AFTER_CAPTURES
//          pulls the cable once AFTER_CAPTURES captures are kept, reloads, resumes; writes resume.json
//        node drive.mjs fit PAGE_DIR OUT_DIR LOG...
//          each log fitted in the page against LOG.cli.json (`accelcal fit LOG --json`); fit-compare.json
// Exits 1 with the reason on stderr.

import puppeteer from "puppeteer-core";
import { writeFile } from "node:fs/promises";
import { join } from "node:path";
import { readFileSync } from "node:fs";
import { serve } from "./serve.mjs";

const RUN_LIMIT_MS = 10 * 60 * 1000;

function fail(message) {
  process.stderr.write(`drive.mjs: ${message}\n`);
  process.exit(1);
}

// The fake navigator.serial, and the date frozen at `dateMs` (when set): run in the page before its scripts.
function fakeSerial(seed, dateMs) {
  if (dateMs) Date.now = () => dateMs;
  Object.defineProperty(navigator, "serial", {
    configurable: true,
    value: {
      requestPort: async () => (await import("/sim-serial.js")).simulatedSerial(BigInt(seed)).requestPort(),
      getPorts: async () => [],
      addEventListener() {},
      removeEventListener() {},
    },
  });
}

async function launch(pageDir, seed, dateMs) {
  const { server, base } = await serve(pageDir);
  const browser = await puppeteer.launch({
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
    headless: true,
    args: ["--no-sandbox", "--disable-gpu"],
  });
  const page = await browser.newPage();
  await page.setViewport({ width: 1000, height: 1100 });
  page.on("dialog", (dialog) => dialog.accept());
  page.on("pageerror", (error) => process.stderr.write(`page error: ${error.message}\n`));
  await page.evaluateOnNewDocument(fakeSerial, String(seed), dateMs);
  return { server, browser, page, base };
}

const state = (page) => page.evaluate(() => window.accelcal?.state);

async function untilState(page, wanted) {
  await page.waitForFunction((wanted) => wanted.includes(window.accelcal?.state), { timeout: RUN_LIMIT_MS, polling: 100 }, wanted);
  return state(page);
}

// Screenshots of each kind of step as the run reaches it.
async function watchSteps(page, outDir) {
  const shots = [];
  await page.exposeFunction("accelcalShot", async (name) => {
    shots.push(name);
    await page.screenshot({ path: join(outDir, `step-${String(shots.length).padStart(2, "0")}-${name}.png`), fullPage: true });
  });
  await page.evaluateOnNewDocument(() => {
    const seen = new Set();
    window.addEventListener("accelcal:prompt", ({ detail }) => {
      const name = detail.kind === "present" ? `present-${detail.name.includes("again") ? "again" : detail.name.length > 2 ? "corner" : "face"}` : detail.kind;
      if (!seen.has(name)) {
        seen.add(name);
        // NOTE: after the page has drawn the prompt.
        setTimeout(() => window.accelcalShot(name), 0);
      }
    });
  });
  return shots;
}

// Deep equality with exact numbers; the paths that differ, each with its relative difference (NaN
// where either side is not a number).
function differences(a, b, path = "") {
  if (typeof a !== typeof b || a === null || b === null || typeof a !== "object") {
    if (Object.is(a, b)) return [];
    const relative = typeof a === "number" && typeof b === "number" ? Math.abs(a - b) / Math.max(Math.abs(a), Math.abs(b)) : NaN;
    return [{ path, page: a, cli: b, relative }];
  }
  const keys = new Set([...Object.keys(a), ...Object.keys(b)]);
  return [...keys].flatMap((key) => differences(a[key], b[key], `${path}.${key}`));
}

// The numbers computed through the transcendental functions of Rust's std (sin, cos, acos, exp, ln, ...):
// natively glibc's, in wasm32 the `libm` port's, which differ in the last place; the fits downstream
// (the gyro's standard errors, the certificate's budget) carry that on. The calibration itself, the
// fits' parameters and the verification use none of them on their way and must be equal bit for bit.
const LAST_PLACE = [/^\.calibration\.gyro\.(std_errors|residual_deg)/, /^\.gyro_check\./, /^\.certificate\./];
/// A fit's: the noise test's p-value (the chi-square distribution's, through exp and ln).
const FIT_LAST_PLACE = [/^\.noise_test\.p_value$/];
/// How far those may be apart: a relative 1e-6, far above the 2.2e-8 seen and far below any shown digit.
const LAST_PLACE_RELATIVE = 1e-6;

// The report's differences sorted: `exact` (must be none), `lastPlace` (within the bound), `beyond`.
function sorted(found, lastPlace = LAST_PLACE) {
  const inLastPlace = (d) => lastPlace.some((pattern) => pattern.test(d.path));
  const within = (d) => d.relative <= LAST_PLACE_RELATIVE || d.path === ".certificate.sha256";
  return {
    exact: found.filter((d) => !inLastPlace(d)),
    lastPlace: found.filter((d) => inLastPlace(d) && within(d)).length,
    beyond: found.filter((d) => inLastPlace(d) && !within(d)),
  };
}

// Two report pages compared: their text between numbers byte for byte, their numbers within the
// last-place bound; whether they are equal byte for byte, and what differs beyond that.
function comparePages(page, cli) {
  const number = /-?[0-9]+(?:\.[0-9]+)?(?:e-?[0-9]+)?/g;
  const [pageText, cliText] = [page.split(number), cli.split(number)];
  const [pageNumbers, cliNumbers] = [page.match(number) ?? [], cli.match(number) ?? []];
  const textEqual = pageText.length === cliText.length && pageText.every((piece, i) => piece === cliText[i]);
  const numbersApart = pageNumbers.filter((n, i) => n !== cliNumbers[i]).length;
  const beyond = pageNumbers
    .map((n, i) => [Number(n), Number(cliNumbers[i])])
    .filter(([a, b]) => Math.abs(a - b) > LAST_PLACE_RELATIVE * Math.max(Math.abs(a), Math.abs(b)));
  return { bytesEqual: page === cli, textEqual, numbers: pageNumbers.length, numbersApart, beyond: beyond.slice(0, 5) };
}

async function calibrate(pageDir, outDir, seed, dateMs, cliJsonPath, cliHtmlPath) {
  const { server, browser, page, base } = await launch(pageDir, seed, Number(dateMs));
  await watchSteps(page, outDir);
  const started = Date.now();
  await page.goto(base, { waitUntil: "load" });
  await page.screenshot({ path: join(outDir, "step-00-start.png"), fullPage: true });
  await page.click("#connect");
  await page.waitForFunction(() => document.getElementById("prompt").textContent !== "", { timeout: 60000, polling: 20 });
  const firstPromptMs = Date.now() - started;
  const ended = await untilState(page, ["done", "failed"]);
  const runMs = Date.now() - started;
  if (ended !== "done") fail(`seed ${seed}: the page's run failed: ${await page.evaluate(() => window.accelcal.error)}`);
  await page.screenshot({ path: join(outDir, "step-99-done.png"), fullPage: true });
  const { result, files } = await page.evaluate(() => ({ result: window.accelcal.result, files: window.accelcal.files }));
  const cli = JSON.parse(readFileSync(cliJsonPath, "utf8"));
  // NOTE: the simulated sensor's truth is known to the command line's simulation only.
  delete cli.truth;
  delete cli.true_error_mg;
  delete result.truth;
  delete result.true_error_mg;
  await writeFile(join(outDir, "page.json"), files["accelcal-calibration.json"]);
  await writeFile(join(outDir, "report.html"), files["accelcal-report.html"]);
  await writeFile(join(outDir, "certificate.json"), files["accelcal-certificate.json"] ?? "");
  const cliPage = readFileSync(cliHtmlPath, "utf8");
  const report = sorted(differences(result, cli));
  const pageReport = comparePages(files["accelcal-report.html"], cliPage);
  await writeFile(join(outDir, "compare.json"), JSON.stringify({ report, page: pageReport }, null, 1));
  await writeFile(join(outDir, "timing.json"), JSON.stringify({ first_prompt_ms: firstPromptMs, run_ms: runMs }));
  await browser.close();
  server.close();
}

const keptCaptures = (page) =>
  page.evaluate(async () => {
    const { keptSession } = await import("/store.js");
    const kept = await keptSession();
    return kept ? JSON.parse(kept).captures : [];
  });

async function resume(pageDir, outDir, seed, afterCaptures) {
  const { server, browser, page, base } = await launch(pageDir, seed, 0);
  await page.goto(base, { waitUntil: "load" });
  await page.click("#connect");
  await page.waitForFunction(async (n) => {
    const { keptSession } = await import("/store.js");
    const kept = await keptSession();
    return kept && JSON.parse(kept).captures.length >= n;
  }, { timeout: RUN_LIMIT_MS, polling: 50 }, Number(afterCaptures));
  // Mid-capture: once the next capture's progress has begun.
  await page.waitForFunction(() => Number(document.getElementById("progress").value) > 0 && document.getElementById("progress").value < document.getElementById("progress").max, { timeout: 60000, polling: 5 });
  await page.evaluate(() => window.accelcal.port.serial.pullCable());
  const pulled = await untilState(page, ["failed", "done"]);
  const error = await page.evaluate(() => window.accelcal.error);
  await page.screenshot({ path: join(outDir, "resume-1-pulled.png"), fullPage: true });
  const before = await keptCaptures(page);
  await page.reload({ waitUntil: "load" });
  await page.waitForSelector("#kept:not([hidden])", { timeout: 10000 });
  const offered = await page.evaluate(() => document.getElementById("kept-what").textContent);
  await page.screenshot({ path: join(outDir, "resume-2-offered.png"), fullPage: true });
  await page.click("#resume");
  const ended = await untilState(page, ["done", "failed"]);
  const finalError = await page.evaluate(() => window.accelcal.error);
  await page.screenshot({ path: join(outDir, "resume-3-done.png"), fullPage: true });
  const files = await page.evaluate(() => window.accelcal.files);
  const after = files["accelcal-session.json"] ? JSON.parse(files["accelcal-session.json"]).captures : [];
  await writeFile(join(outDir, "resume.json"), JSON.stringify({ pulled, error, offered, ended, finalError, before, after }));
  await browser.close();
  server.close();
}

// Each log chosen in the page's #log-file and fitted; its fit (`fit LOG --json`'s text) against the
// command line's (LOG.cli.json beside it), exact numbers: OUT_DIR/fit-compare.json.
async function fit(pageDir, outDir, ...logs) {
  const { server, browser, page, base } = await launch(pageDir, 1, 0);
  await page.goto(base, { waitUntil: "load" });
  const compared = {};
  for (const log of logs) {
    await page.evaluate(() => { window.accelcal.fitted = undefined; });
    const input = await page.$("#log-file");
    await input.uploadFile(log);
    await page.waitForFunction(() => window.accelcal.fitted !== undefined, { timeout: 60000, polling: 50 });
    const fitted = await page.evaluate(() => window.accelcal.fitted);
    if (fitted === null) fail(`${log}: ${await page.evaluate(() => document.getElementById("log-error").textContent)}`);
    const cli = readFileSync(log.replace(/\.log$/, ".cli.json"), "utf8");
    const found = sorted(differences(JSON.parse(fitted), JSON.parse(cli)), FIT_LAST_PLACE);
    compared[log] = { textEqual: fitted.trim() === cli.trim(), ...found };
  }
  await page.screenshot({ path: join(outDir, "fit-log.png"), fullPage: true });
  await writeFile(join(outDir, "fit-compare.json"), JSON.stringify(compared, null, 1));
  await browser.close();
  server.close();
}

const [mode, ...args] = process.argv.slice(2);
const modes = { calibrate, resume, fit };
if (!modes[mode]) fail("usage: node drive.mjs calibrate|resume ...");
modes[mode](...args).catch((error) => fail(error?.stack ?? String(error)));
