// The page: connects a board over Web Serial (or the simulated one), runs the core's calibration on
// it (wasm: calibrate_board), shows its prompts, live tilt and progress, keeps the session in the
// browser after every capture, and offers the results as downloads.
//
// Automation hooks (DESIGN.md, "The web page"): #prompt holds the current instruction, its
// data-kind ("present", "fresh", "quarter") and data-wanted (the wanted orientation's name); window
// events "accelcal:prompt" (detail: kind, name, up, index), "accelcal:avoid" (detail: ups) and
// "accelcal:new-hand" fire as the run asks for them, before it goes on; window.accelcal holds
// `state` ("idle", "running", "done", "failed"), `result` (the report as `calibrate --json` prints
// it, parsed), `files` (each download's name and text), `error`, and `fitted` (a chosen log's fit as
// `accelcal fit LOG --json` prints it, text).

import init, { calibrate_board, fit_log } from "./pkg/accelcal_web.js";
import { PagePort } from "./port.js";
import { keepSession, keptSession, forgetSession } from "./store.js";

const $ = (id) => document.getElementById(id);
const accelcal = (window.accelcal = { state: "idle", result: null, files: {}, error: null, port: null });

function show(...ids) {
  for (const id of ["start", "run", "done", "failed", "kept", "fit-log"]) $(id).hidden = !ids.includes(id);
}

function fire(name, detail) {
  window.dispatchEvent(new CustomEvent(name, { detail }));
}

// What the run tells and asks (web/src/browser/page.rs, PageUi).
const pageUi = {
  say(line) {
    const item = document.createElement("li");
    item.textContent = line;
    $("said").append(item);
    item.scrollIntoView({ block: "nearest" });
  },
  live(line) {
    $("live").textContent = line;
  },
  progress(samples, total) {
    $("progress").max = Math.max(total, 1);
    $("progress").value = samples;
  },
  progressDone() {
    $("progress").value = $("progress").max;
  },
  confirm(question) {
    // NOTE: the run asks synchronously; the browser's own dialog is the one question that can wait.
    return window.confirm(question);
  },
  prompt(kind, name, up, index, line) {
    const prompt = $("prompt");
    prompt.textContent = line;
    prompt.dataset.kind = kind;
    prompt.dataset.wanted = name;
    fire("accelcal:prompt", { kind, name, up: Array.from(up), index });
  },
  avoid(ups) {
    fire("accelcal:avoid", { ups: Array.from(ups) });
  },
  newHand() {
    fire("accelcal:new-hand", {});
  },
  keep(json) {
    keepSession(json).catch((error) => pageUi.say(`the session could not be kept in this browser: ${error}`));
  },
};

/// What each download is, for the person.
const DOWNLOADS = {
  "accelcal-report.html": "the full report: every position, the fits, the verification, the figures",
  "accelcal-calibration.json": "the calibration and its checks, as \"accelcal calibrate --json\" prints them",
  "accelcal-certificate.html": "the calibration certificate, every parameter with its uncertainty",
  "accelcal-certificate.json": "the certificate, sealed (\"accelcal certificate verify\" checks it)",
  "accelcal-session.json": "the session: every capture (\"accelcal export\" turns it into code for your sketch)",
  "accelcal-session.csv": "the captures as a table",
};

function offer(name, text, type) {
  if (!text) return;
  accelcal.files[name] = text;
  const link = document.createElement("a");
  link.href = URL.createObjectURL(new Blob([text], { type }));
  link.download = name;
  link.textContent = name;
  const item = document.createElement("li");
  const what = document.createElement("span");
  what.textContent = `: ${DOWNLOADS[name]}`;
  item.append(link, what);
  $("downloads").append(item);
}

function finished(result) {
  accelcal.result = JSON.parse(result.report_json);
  const target = accelcal.result.target;
  $("outcome").textContent = target?.missed
    ? "Calibrated and uploaded, but the check at fresh orientations missed the target: see below."
    : "Done: the board is calibrated, and the calibration was checked at fresh orientations.";
  $("verdict").textContent = target?.line ?? "";
  $("verdict").classList.toggle("missed", Boolean(target?.missed));
  $("downloads").replaceChildren();
  offer("accelcal-report.html", result.report_html, "text/html");
  offer("accelcal-calibration.json", result.report_json, "application/json");
  offer("accelcal-certificate.html", result.certificate_html, "text/html");
  offer("accelcal-certificate.json", result.certificate_json, "application/json");
  offer("accelcal-session.json", result.session_json, "application/json");
  offer("accelcal-session.csv", result.session_csv, "text/csv");
  if (result.certificate_withheld) pageUi.say(`no certificate: ${result.certificate_withheld}`);
  $("prompt").textContent = "";
  show("done");
  accelcal.state = "done";
}

function failed(error) {
  accelcal.error = String(error?.message ?? error);
  $("why").textContent = accelcal.error;
  show("failed");
  accelcal.state = "failed";
}

async function run(serial, kept) {
  await init();
  let port = null;
  try {
    port = accelcal.port = await PagePort.open(serial);
    $("said").replaceChildren();
    show("run");
    accelcal.state = "running";
    const result = await calibrate_board(port, pageUi, kept ?? undefined);
    await forgetSession();
    finished(result);
  } catch (error) {
    failed(error);
  } finally {
    await port?.close();
  }
}

async function choosePort() {
  if (!("serial" in navigator)) throw new Error("this browser has no Web Serial: use Chrome, Edge or Opera");
  return navigator.serial.requestPort();
}

async function simulatedPort() {
  const { simulatedPort } = await import("./sim-serial.js");
  return simulatedPort(1n);
}

async function start(portChooser, kept) {
  let serial;
  try {
    serial = await portChooser();
  } catch (error) {
    // NOTE: the person closed the browser's list without picking a port: nothing to do.
    if (error?.name === "NotFoundError") return;
    return failed(error);
  }
  await run(serial, kept);
}

async function offerKept() {
  const kept = await keptSession().catch(() => null);
  if (!kept) return;
  const captures = JSON.parse(kept).captures?.length ?? 0;
  $("kept-what").textContent = `This browser kept a calibration of board ${JSON.parse(kept).board?.serial ?? "?"} ` +
    `with ${captures} positions captured. Connect the same board to go on from there.`;
  $("kept").hidden = false;
  $("resume").onclick = () => start(choosePort, kept);
  $("discard").onclick = async () => {
    await forgetSession();
    $("kept").hidden = true;
  };
}

// A log chosen in #log-file, fitted as `accelcal fit LOG` fits it; window.accelcal.fitted is its
// report as `fit LOG --json` prints it (text).
async function fitChosenLog() {
  const file = $("log-file").files[0];
  if (!file) return;
  await init();
  $("log-error").hidden = $("log-result").hidden = true;
  $("log-downloads").replaceChildren();
  try {
    const fitted = fit_log(new Uint8Array(await file.arrayBuffer()));
    accelcal.fitted = fitted.json;
    $("log-result").textContent = fitted.text;
    $("log-result").hidden = false;
    const link = document.createElement("a");
    link.href = URL.createObjectURL(new Blob([fitted.json], { type: "application/json" }));
    link.download = "accelcal-fit.json";
    link.textContent = "accelcal-fit.json";
    const item = document.createElement("li");
    item.append(link, ': the fit as "accelcal fit LOG --json" prints it ("accelcal export" reads it)');
    $("log-downloads").append(item);
  } catch (error) {
    accelcal.fitted = null;
    $("log-error").textContent = String(error?.message ?? error);
    $("log-error").hidden = false;
  }
}

function wire() {
  $("no-serial").hidden = "serial" in navigator;
  $("connect").disabled = !("serial" in navigator);
  $("connect").onclick = () => start(choosePort, null);
  $("simulate").onclick = () => start(simulatedPort, null);
  $("stop").onclick = () => accelcal.port && (accelcal.port.stopped = true);
  $("again").onclick = $("retry").onclick = () => location.reload();
  $("log-file").onchange = fitChosenLog;
  offerKept();
}

wire();
