// Browser tests of `plateball view`, run by ctest (view.browser) when node, Debian's
// chromium and web/node_modules/playwright-core are found:
//   node web/test/view_test.mjs --plateball BIN --chromium /usr/bin/chromium
//                               --problems DIR --work DIR [--screenshots DIR]
// For each example (simulate, plan, isoparallel, steer, steer with a rig, montecarlo) the tools write a result, `plateball view`
// writes the page, and headless chromium checks it: no console error, no request but the page
// itself; after seeking to time t the ball's orientation equals A(t) of the result JSON to 1e-9;
// two screenshots differ where the ball is and nowhere else; a 10,000-sample page stays
// responsive. Bad results are rejected with the field named. --screenshots writes docs/ PNGs.
import { execFileSync, spawnSync } from "node:child_process";
import { createRequire } from "node:module";
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, "..", "package.json"));
const { chromium } = require("playwright-core");
const fields = JSON.parse(fs.readFileSync(path.join(here, "..", "result_fields.json"), "utf8"));

const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, "")] = process.argv[i + 1];
for (const need of ["plateball", "chromium", "problems", "work"])
  if (!args[need]) throw new Error("missing --" + need);
fs.rmSync(args.work, { recursive: true, force: true });
fs.mkdirSync(args.work, { recursive: true });
const work = (name) => path.join(args.work, name);
const problem = (name) => path.join(args.problems, name);

let failures = 0;
const begun = Date.now();
function check(ok, name, detail = "") {
  const at = " [" + ((Date.now() - begun) / 1000).toFixed(1) + " s]";
  console.log((ok ? "ok - " : "not ok - ") + name + (detail ? ": " + detail : "") + at);
  if (!ok) ++failures;
}

// The value of a concept of result_fields.json (first path present) below `at`.
function field(at, concept) {
  for (const p of fields[concept]) {
    let node = at;
    for (const key of p.split(".")) node = node !== null && typeof node === "object" ? node[key] : undefined;
    if (node !== undefined) return node;
  }
  throw new Error("result lacks " + concept);
}
const run = (bin, argv) => execFileSync(bin, argv, { stdio: ["ignore", "pipe", "pipe"] }).toString();
const readJson = (f) => JSON.parse(fs.readFileSync(f, "utf8"));
const maxDiff = (a, b) => Math.max(...a.flatMap((row, i) => row.map((v, j) => Math.abs(v - b[i][j]))));

// ------------------------------------------------------------ the examples
const P = args.plateball;
run(P, ["simulate", problem("simulate_example.json"), "--out", work("simulate.json")]);
run(P, ["simulate", problem("simulate_example.json"), "--samples", "4001", "--out", work("simulate_dense.json")]);
run(P, ["plan", problem("circle.json"), "--out", work("plan.json")]);
run(P, ["isoparallel", problem("figure7.json"), "--out", work("isoparallel.json")]);
run(P, ["steer", problem("figure7_exact.json"), "--out", work("steer.json")]);
run(P, ["simulate", problem("simulate_example.json"), "--t-end", "100", "--samples", "10000", "--out", work("big.json")]);
// Strings that attack the page: a comment opener before "<script>" (which would make the data
// script swallow the document), the template's fill markers, U+2028/U+2029 and an ampersand.
const hostileName = 'a<!--<script> </script> /*@THREE@*/ "@DATA@" @TITLE@ /*@VIEW@*/ \u2028\u2029 & end';
{
  const doc = readJson(problem("simulate_example.json"));
  doc.name = hostileName;
  fs.writeFileSync(work("hostile_problem.json"), JSON.stringify(doc));
}
run(P, ["simulate", work("hostile_problem.json"), "--out", work("hostile.json")]);
// A motion reaching 1e5 ball radii: the plate's grid is scaled, not sized by the extent.
run(P, ["simulate", problem("simulate_example.json"), "--t-end", "1e5", "--samples", "2000", "--out", work("far.json")]);
run(P, ["simulate", problem("simulate_example.json"), "--t-end", "1e8", "--samples", "2000", "--out", work("too_far.json")]);
run(P, ["montecarlo", problem("circle.json"), "--trials", "40", "--noise", "impulse_magnitude=1e-3", "--noise", "timing=1e-3",
  "--threads", "1", "--quiet", "--out", work("montecarlo.json")]);
// Steer results with a rig: Figure 7 on a disk plate with an obstacle, and every kind of shape with
// the stroke (tests/data/view_rig_shapes.json).
const testData = (name) => path.join(args.problems, "..", "tests", "data", name);
run(P, ["steer", problem("figure7_rig.json"), "--out", work("rig.json")]);
run(P, ["steer", testData("view_rig_shapes.json"), "--out", work("rig_shapes.json")]);
// A rig verdict whose margin name and violation attack the page.
{
  const doc = readJson(work("rig.json"));
  doc.rig.check.margins = { [hostileName]: -0.5 };
  doc.rig.check.violations = [hostileName];
  doc.rig.check.passed = false;
  fs.writeFileSync(work("rig_hostile.json"), JSON.stringify(doc));
}
const pages = {
  simulate: ["simulate.json"],
  plan: ["plan.json"],  // the problem file named in the result's header
  isoparallel: ["isoparallel.json"],
  steer: ["steer.json", "--problem", problem("figure7_exact.json")],
  big: ["big.json"],
  hostile: ["hostile.json"],
  far: ["far.json"],
  montecarlo: ["montecarlo.json"],
  rig: ["rig.json"],
  rig_shapes: ["rig_shapes.json"],
  rig_hostile: ["rig_hostile.json"],
};
for (const [name, [result, ...rest]] of Object.entries(pages))
  run(P, ["view", work(result), "--html", work(name + ".html"), ...rest]);
const sizes = Object.keys(pages).map((k) => k + " " + (fs.statSync(work(k + ".html")).size / 1e6).toFixed(2) + " MB");
console.log("# page sizes: " + sizes.join(", ") + " [" + ((Date.now() - begun) / 1000).toFixed(1) + " s]");

// ------------------------------------------------------------ bad results: exit 3 naming the field
{
  fs.writeFileSync(work("bad_command.json"), JSON.stringify({ command: "converge" }));
  fs.writeFileSync(work("bad_sample.json"), fs.readFileSync(work("simulate.json"), "utf8").replace(/"orientation": \[\[1\.0/, '"orientation": [[7.0'));
  fs.writeFileSync(work("malformed.json"), "{\"command\": ");
  const cases = [
    ["bad_command.json", 3, "command: value \"converge\""],
    ["bad_sample.json", 3, "not a rotation matrix"],
    ["malformed.json", 3, "malformed JSON"],
    ["missing.json", 5, "cannot open"],
    ["too_far.json", 3, "contact path (re-simulated)["],
  ];
  for (const [file, code, text] of cases) {
    const r = spawnSync(P, ["view", work(file), "--html", work("bad.html")]);
    const err = r.stderr.toString();
    check(r.status === code && err.includes(text) && !fs.existsSync(work("bad.html")),
      "view rejects " + file + " (exit " + code + ")", "exit " + r.status + ", " + err.trim());
  }
}

// ------------------------------------------------------------ the browser
const browser = await chromium.launch({
  executablePath: args.chromium,
  args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
});
const viewport = { width: 1280, height: 760 };  // the docs/ screenshots' size

async function open(name) {
  const context = await browser.newContext({ viewport });
  const page = await context.newPage();
  const log = { errors: [], requests: [] };
  const url = "file://" + work(name + ".html");
  page.on("console", (m) => { if (m.type() === "error") log.errors.push(m.text()); });
  page.on("pageerror", (e) => log.errors.push(e.message));
  page.on("request", (r) => { if (r.url() !== url) log.requests.push(r.url()); });
  await page.goto(url);
  await page.waitForFunction(() => window.plateballView && window.plateballView.frames() > 0);
  return { page, log, context };
}
// Seeks through the time slider (as a user does) and waits until that time has been drawn.
async function seek(page, t) {
  const frames = await page.evaluate((t) => {
    const before = window.plateballView.frames();
    const s = document.getElementById("time");
    s.value = String(t);
    s.dispatchEvent(new Event("input"));
    return before;
  }, t);
  await page.waitForFunction((f) => window.plateballView.frames() > f, frames);
}
// The ball's orientation right after the slider's input event (the state the next frame draws).
async function orientationAt(page, t) {
  return page.evaluate((t) => {
    const s = document.getElementById("time");
    s.value = String(t);
    s.dispatchEvent(new Event("input"));
    return window.plateballView.orientation();
  }, t);
}

// Orientation checks: [time, A(t) from a result JSON] pairs per page.
function simulateChecks() {
  const pairs = [];
  const samples = field(readJson(work("simulate.json")), "samples");
  for (let i = 0; i < samples.length; i += 7) pairs.push([field(samples[i], "sample_t"), field(samples[i], "sample_orientation")]);
  // Times between the result's samples: A(t) of an independent, denser run of simulate.
  const dense = field(readJson(work("simulate_dense.json")), "samples");
  for (let i = 3; i < dense.length; i += 397) pairs.push([field(dense[i], "sample_t"), field(dense[i], "sample_orientation")]);
  return pairs;
}
function planChecks(file) {
  const doc = readJson(work(file));
  const steps = field(doc, "steps");
  const pairs = [];
  for (let k = 0; k + 1 < steps.length; k += 5) pairs.push([field(steps[k + 1], "t_impulse"), field(steps[k], "orientation_impulsive")]);
  pairs.push([field(doc, "total_time"), field(steps[steps.length - 1], "orientation_impulsive")]);
  return pairs;
}
function steerChecks() {
  const doc = readJson(work("steer.json"));
  return [[field(doc, "total_time"), field(doc, "arrival_orientation")]];
}
const checks = {
  simulate: simulateChecks(),
  plan: planChecks("plan.json"),
  isoparallel: planChecks("isoparallel.json"),
  steer: steerChecks(),
};

// ------------------------------------------------------------ between samples: the geodesic
// A quarter of the way between two samples the page's orientation is the rotation a quarter of the
// way along the geodesic between theirs (slerp on SO(3); interpolating angles or matrix entries is
// not, and leaves the geodesic).
async function geodesicCheck(page) {
  const times = await page.evaluate(() => [window.plateballView.range(), window.plateballView.sampleCount()]);
  const mul = (a, b) => a.map((r, i) => [0, 1, 2].map((j) => r[0] * b[0][j] + r[1] * b[1][j] + r[2] * b[2][j]));
  const tr = (a) => [0, 1, 2].map((i) => [0, 1, 2].map((j) => a[j][i]));
  const angle = (a, b) => { const m = mul(tr(a), b); return Math.acos(Math.min(1, Math.max(-1, (m[0][0] + m[1][1] + m[2][2] - 1) / 2))); };
  let worst = 0, orthogonality = 0;
  for (const u of [0.13, 0.41, 0.77]) {
    const t = await page.evaluate((u) => window.plateballView.sampleTimes(u), u);
    const a = await orientationAt(page, t[0]), b = await orientationAt(page, t[1]);
    const m = await orientationAt(page, 0.75 * t[0] + 0.25 * t[1]);
    const whole = angle(a, b);
    worst = Math.max(worst, Math.abs(angle(a, m) - whole / 4), Math.abs(angle(m, b) - 0.75 * whole));
    orthogonality = Math.max(orthogonality, maxDiff(mul(tr(m), m), [[1, 0, 0], [0, 1, 0], [0, 0, 1]]));
  }
  check(worst < 1e-9 && orthogonality < 1e-12, "plan: between samples the orientation is on the geodesic at the time's fraction (slerp)",
    `samples ${times[1]}, |angle to each end - fraction of the whole| <= ${worst.toExponential(2)}, |A^T A - I| <= ${orthogonality.toExponential(2)}`);
}

// ------------------------------------------------------------ screenshots at two times
async function screenshotCheck(page) {
  for (const id of ["show-upper", "show-trace", "show-ghost", "show-arrows"]) await page.uncheck("#" + id);
  const clip = await page.evaluate(() => {
    const r = document.querySelector("#scene canvas").getBoundingClientRect();
    return { x: r.left, y: r.top, width: r.width, height: r.height };
  });
  const shot = async (t) => {
    await seek(page, t);
    const box = await page.evaluate(() => window.plateballView.ballBox());
    return { png: (await page.screenshot({ clip })).toString("base64"), box };
  };
  const a = await shot(2.0), b = await shot(9.0);
  // Decode both PNGs in the page and count the pixels that differ inside and outside the ball's
  // boxes at the two times (3 px margin).
  const result = await page.evaluate(async ({ a, b, clip }) => {
    const pixels = async (png) => {
      const img = new Image();
      img.src = "data:image/png;base64," + png;
      await img.decode();
      const c = document.createElement("canvas");
      c.width = img.width;
      c.height = img.height;
      const g = c.getContext("2d");
      g.drawImage(img, 0, 0);
      return g.getImageData(0, 0, c.width, c.height);
    };
    const pa = await pixels(a.png), pb = await pixels(b.png);
    const inside = (box, x, y) => x >= box.x0 - clip.x - 3 && x <= box.x1 - clip.x + 3 && y >= box.y0 - clip.y - 3 && y <= box.y1 - clip.y + 3;
    let changedInside = 0, changedOutside = 0;
    for (let y = 0; y < pa.height; ++y)
      for (let x = 0; x < pa.width; ++x) {
        const k = 4 * (y * pa.width + x);
        const changed = pa.data[k] !== pb.data[k] || pa.data[k + 1] !== pb.data[k + 1] || pa.data[k + 2] !== pb.data[k + 2];
        if (!changed) continue;
        if (inside(a.box, x, y) || inside(b.box, x, y)) ++changedInside; else ++changedOutside;
      }
    return { changedInside, changedOutside };
  }, { a, b, clip });
  check(result.changedInside > 1000 && result.changedOutside === 0,
    "plan: screenshots at t = 2 and t = 9 differ where the ball is and nowhere else",
    result.changedInside + " pixels changed inside the ball's boxes, " + result.changedOutside + " outside");
}

for (const name of ["simulate", "plan", "isoparallel", "steer"]) {
  const { page, log, context } = await open(name);
  let worst = 0;
  for (const [t, A] of checks[name]) worst = Math.max(worst, maxDiff(await orientationAt(page, t), A));
  check(worst <= 1e-9, name + ": orientation after seeking equals A(t) of the JSON to 1e-9",
    checks[name].length + " times, max |entry difference| " + worst.toExponential(2));
  if (args.screenshots) {
    const [t0, t1] = await page.evaluate(() => window.plateballView.range());
    await seek(page, t0 + 0.45 * (t1 - t0));
    await page.screenshot({ path: path.join(args.screenshots, "view_" + name + ".png") });
  }
  if (name === "plan") {
    await geodesicCheck(page);
    await screenshotCheck(page);
  }
  check(log.errors.length === 0, name + ": no console errors", log.errors.join(" | "));
  check(log.requests.length === 0, name + ": no network requests", log.requests.join(" "));
  await context.close();
}

// ------------------------------------------------------------ hostile strings, huge extents
{
  const { page, log, context } = await open("hostile");
  const shown = await page.evaluate(() => ({ title: document.title, h1: document.getElementById("title").textContent,
    data: PLATEBALL_DATA.title, scripts: document.scripts.length }));
  const expected = readJson(work("hostile.json")).problem.name;
  check(expected === hostileName && shown.title.startsWith(hostileName) && shown.h1.startsWith(hostileName) &&
    shown.data.startsWith(hostileName) && shown.scripts === 3,
    "hostile: a name with \"<!--<script>\", fill markers and U+2028 is shown verbatim, the page intact",
    JSON.stringify(shown));
  check(log.errors.length === 0 && log.requests.length === 0, "hostile: no console errors, no network requests",
    log.errors.concat(log.requests).join(" | "));
  await context.close();
}
{
  const { page, log, context } = await open("far");
  const lines = await page.evaluate(() => window.plateballView.gridLines());
  check(log.errors.length === 0 && lines > 0 && lines <= 2 * 201,
    "far: a motion over 1e5 ball radii draws with a scaled grid", lines + " grid lines, " + log.errors.join(" | "));
  await context.close();
}

// ------------------------------------------------------------ rig limits
// The layers drawn are the problem file's shapes; the panel's margins are the result's replay
// check, as text; switching the rig layers off changes the picture.
for (const [name, file, problemFile] of [["rig", "rig.json", problem("figure7_rig.json")],
  ["rig_shapes", "rig_shapes.json", testData("view_rig_shapes.json")]]) {
  const { page, log, context } = await open(name);
  const doc = readJson(work(file));
  const rigFile = readJson(problemFile).rig;
  const [, t1] = await page.evaluate(() => window.plateballView.range());
  await seek(page, 0.6 * t1);
  const shown = await page.evaluate(() => ({
    layers: window.plateballView.rigLayers(),
    margins: [...document.querySelectorAll("#rig-margins tr")].slice(1).map((tr) => [...tr.cells].map((c) => c.textContent)),
    verdict: document.getElementById("rig-verdict").textContent,
    legend: document.getElementById("legend").textContent,
  }));
  const margins = Object.entries(doc.rig.check.margins);
  const marginsShown = margins.length === shown.margins.length &&
    margins.every(([k, v], i) => shown.margins[i][0] === k && Math.abs(Number(shown.margins[i][1]) - v) <= 1e-3 * Math.abs(v));
  const plate = rigFile.plate.type === "disk"
    ? shown.layers.plate.type === "disk" && shown.layers.plate.radius === rigFile.plate.radius
    : JSON.stringify(shown.layers.plate.vertices) === JSON.stringify(rigFile.plate.vertices);
  const stroke = !rigFile.stroke ? shown.layers.stroke === null && !shown.legend.includes("stroke")
    : shown.layers.stroke.half.join() === rigFile.stroke.join() && shown.legend.includes("upper plate's stroke");
  check(plate && stroke && shown.layers.obstacles.length === rigFile.obstacles.length && marginsShown &&
    shown.verdict.startsWith("Limits met in the replay check: " + doc.rig.check.samples + " contact points"),
    name + ": the rig's plate, obstacles and stroke drawn, the replay check's verdict and margins in the panel",
    JSON.stringify(shown.margins) + " " + shown.verdict);
  const clip = await page.evaluate(() => {
    const r = document.querySelector("#scene canvas").getBoundingClientRect();
    return { x: r.left, y: r.top, width: r.width, height: r.height };
  });
  const withRig = await page.screenshot({ clip });
  if (args.screenshots && name === "rig_shapes") await page.screenshot({ path: path.join(args.screenshots, "view_rig.png") });
  const frames = await page.evaluate(() => window.plateballView.frames());
  await page.uncheck("#show-rig");
  await page.waitForFunction((f) => window.plateballView.frames() > f, frames);
  const withoutRig = await page.screenshot({ clip });
  check(!withRig.equals(withoutRig), name + ": the rig layers draw (the picture changes when they are switched off)");
  check(log.errors.length === 0 && log.requests.length === 0, name + ": no console errors, no network requests",
    log.errors.concat(log.requests).join(" | "));
  await context.close();
}

{
  const { page, log, context } = await open("rig_hostile");
  const shown = await page.evaluate(() => ({
    margins: [...document.querySelectorAll("#rig-margins tr")].slice(1).map((tr) => [...tr.cells].map((c) => c.textContent)),
    facts: [...document.querySelectorAll("#rig-facts dd")].map((d) => d.textContent),
    verdict: document.getElementById("rig-verdict").textContent,
    failClass: document.querySelector("#rig-margins td.fail") !== null,
    scripts: document.scripts.length,
  }));
  check(shown.margins.length === 1 && shown.margins[0][0] === hostileName && shown.facts.includes(hostileName) &&
    shown.verdict.startsWith("Limits NOT met in the replay check") && shown.failClass && shown.scripts === 3,
    "rig_hostile: a margin name and a violation with \"<!--<script>\" are shown verbatim as text, the negative margin marked",
    JSON.stringify(shown));
  check(log.errors.length === 0 && log.requests.length === 0, "rig_hostile: no console errors, no network requests",
    log.errors.concat(log.requests).join(" | "));
  await context.close();
}

// ------------------------------------------------------------ Monte Carlo
// The page's final contact points are the trials re-run by the library: per cell, their median
// distance to the goal is the median final position error the result reports; the nominal plan's
// final orientation error is the chart's last value.
{
  const context = await browser.newContext({ viewport: { width: 1280, height: 1000 } });
  const page = await context.newPage();
  const errors = [], requests = [];
  const url = "file://" + work("montecarlo.html");
  page.on("console", (m) => { if (m.type() === "error") errors.push(m.text()); });
  page.on("pageerror", (e) => errors.push(e.message));
  page.on("request", (r) => { if (r.url() !== url) requests.push(r.url()); });
  await page.goto(url);
  await page.waitForFunction(() => window.plateballView && window.plateballView.frames() > 0);
  const doc = readJson(work("montecarlo.json"));
  const spread = await page.evaluate(() => window.plateballView.spread());
  const goal = await page.evaluate(() => window.plateballView.goal());
  const median = (v) => { const s = [...v].sort((a, b) => a - b), m = s.length - 1; return s[Math.floor(m / 2)] + (s[Math.ceil(m / 2)] - s[Math.floor(m / 2)]) / 2; };
  let worst = 0, cells = 0;
  for (const cell of field(doc, "mc_results")) {
    const label = field(cell, "cell_strategy") + ", " + field(cell, "cell_scenario");
    const shown = spread.find((c) => c.label === label);
    if (!shown) continue;
    ++cells;
    const d = [];
    for (let k = 0; k + 1 < shown.x.length; k += 2) d.push(Math.hypot(shown.x[k] - goal[0], shown.x[k + 1] - goal[1]));
    worst = Math.max(worst, Math.abs(median(d) - field(cell, "cell_position_median")));
  }
  check(cells === 4 && spread.every((c) => c.x.length === 80) && worst < 1e-9,
    "montecarlo: the spread's median distance to the goal is the result's median position error, per cell",
    `${cells} cells of ${spread.map((c) => c.x.length / 2).join(", ")} trials, max difference ${worst.toExponential(2)}`);
  const [, t1] = await page.evaluate(() => window.plateballView.range());
  await seek(page, t1);
  const chartEnd = await page.evaluate(() => window.plateballView.orientationError());
  const nominal = field(field(doc, "mc_nominal")[0], "nominal_orientation_error");
  check(Math.abs(chartEnd - nominal) < 1e-9, "montecarlo: the error chart ends at the nominal plan's orientation error",
    `${chartEnd} vs ${nominal}`);
  if (args.screenshots) {
    await seek(page, 0.45 * t1);
    await page.screenshot({ path: path.join(args.screenshots, "view_montecarlo.png") });
  }
  check(errors.length === 0 && requests.length === 0, "montecarlo: no console errors, no network requests",
    errors.concat(requests).join(" | "));
  await context.close();
}

// ------------------------------------------------------------ responsiveness, 10,000 samples
{
  const started = Date.now();
  const { page, log, context } = await open("big");
  const loadSeconds = (Date.now() - started) / 1000;
  const count = await page.evaluate(() => window.plateballView.sampleCount());
  // The page's own work per seek (the input handler: locate, slerp, geometry, chart cursor), then
  // the frame drawn (round trips included).
  let handlerMs = 0;
  const seekStart = Date.now();
  for (let i = 0; i < 10; ++i) {
    handlerMs = Math.max(handlerMs, await page.evaluate((t) => {
      const s = document.getElementById("time");
      const start = performance.now();
      s.value = String(t);
      s.dispatchEvent(new Event("input"));
      return performance.now() - start;
    }, (100 * ((i * 37) % 10)) / 10));
    await seek(page, (100 * ((i * 37 + 5) % 10)) / 10);
  }
  const perSeekMs = (Date.now() - seekStart) / 10;
  await page.evaluate(() => {
    window.__longest = 0;
    new PerformanceObserver((l) => { for (const e of l.getEntries()) window.__longest = Math.max(window.__longest, e.duration); })
      .observe({ type: "longtask", buffered: false });
  });
  await seek(page, 0);
  const framesBefore = await page.evaluate(() => window.plateballView.frames());
  await page.click("#play");
  await page.waitForTimeout(1000);
  await page.click("#play");
  const played = await page.evaluate(() => ({ frames: window.plateballView.frames(), t: window.plateballView.time(), longest: window.__longest, playing: window.plateballView.playing() }));
  const fps = played.frames - framesBefore;
  check(count === 10000 && loadSeconds < 15 && handlerMs < 50 && perSeekMs < 1000 && fps >= 5 && played.t > 0 &&
    !played.playing && played.longest < 1000,
    "big: a 10,000-sample page stays responsive",
    `${count} samples, load ${loadSeconds.toFixed(2)} s, seek handler at most ${handlerMs.toFixed(1)} ms, ` +
    `seek + draw ${perSeekMs.toFixed(1)} ms, ` +
    `${fps} frames in 1 s of play, longest task ${played.longest.toFixed(0)} ms, pause took effect: ${!played.playing}`);
  check(log.errors.length === 0 && log.requests.length === 0, "big: no console errors, no network requests",
    log.errors.concat(log.requests).join(" | "));
  await context.close();
}

await browser.close();
console.log(failures ? `# ${failures} failed` : "# all passed");
process.exit(failures ? 1 : 0);
