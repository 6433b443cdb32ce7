// The web explorer in headless Chromium, on SwiftShader's WebGPU (web/tests/README.md).
//
//   node browser.mjs            the test: the page without WebGPU, then with it the first
//                               frame, a noon and a sunset preset chosen through the menu,
//                               the exports (the PNG found on the page), the LUTs tab, a
//                               reload, the Reference tab tracing while frames keep coming,
//                               and no console error (web/tests/README.md)
//   node browser.mjs --bench    the Sky view's frame time (`bench gui --script sky-frames`)
//
// It serves web/dist (built by `bash web/run --build-only`) itself, on a free local port.
// Environment: CHROMIUM (default /usr/bin/chromium), ATMOSCOPE_WEB_DIST (default ../dist),
// ATMOSCOPE_WEB_OUT (screenshots and the report; default ./out), ATMOSCOPE_BENCH_MODEL.

import { chromium } from "playwright-core";
import { PNG } from "pngjs";
import http from "node:http";
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const dist = path.resolve(process.env.ATMOSCOPE_WEB_DIST ?? path.join(here, "..", "dist"));
const out = path.resolve(process.env.ATMOSCOPE_WEB_OUT ?? path.join(here, "out"));
const bench = process.argv.includes("--bench");
// The window the explorer's layout was laid out for (the desktop window's size too).
const VIEWPORT = { width: 1280, height: 800 };
// SwiftShader runs WebGPU on the CPU: the first frame builds every table there.
const FIRST_FRAME_TIMEOUT_MS = 240_000;
// Where the explorer's default layout puts things in a 1280×800 page on its first visit (the
// welcome window open): a layout change moves them, and the screenshots this test writes show
// where they went.
const AT = {
  startExploring: { x: 487, y: 574 },
  presetMenu: { x: 67, y: 61 },
  presets: { "clear-noon": { x: 45, y: 157 }, "urban-sunset": { x: 52, y: 364 } },
  lutsTab: { x: 500, y: 12 },
  referenceTab: { x: 555, y: 12 },
  // The Sky view's centre, and the LUTs tab's table image.
  sky: { x: 843, y: 402 },
  lutArea: { x0: 420, y0: 60, x1: 1270, y1: 770 },
  // The left strip of the Reference tab's path-traced picture (160×90, shown at 280×157 from
  // x 414): before the first pass the real-time picture is shown alone from x 488, so this
  // strip holds the path tracer's picture and nothing else.
  pathTraced: { x0: 416, y0: 117, x1: 480, y1: 270 },
};

function fail(message) {
  console.error(`web test: ${message}`);
  process.exit(1);
}

for (const file of ["index.html", "atmoscope.js", "atmoscope_bg.wasm"]) {
  if (!fs.existsSync(path.join(dist, file))) {
    fail(`${path.join(dist, file)} is missing: build the page with \`bash web/run --build-only\``);
  }
}
fs.mkdirSync(out, { recursive: true });

const TYPES = { ".html": "text/html", ".js": "text/javascript", ".wasm": "application/wasm" };
const server = http.createServer((req, res) => {
  const name = decodeURIComponent(new URL(req.url, "http://x").pathname).replace(/^\/+/, "") || "index.html";
  const file = path.join(dist, path.normalize(name));
  if (!file.startsWith(dist + path.sep) || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
    res.writeHead(404).end();
    return;
  }
  res.writeHead(200, { "Content-Type": TYPES[path.extname(file)] ?? "application/octet-stream" });
  fs.createReadStream(file).pipe(res);
});
await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));
const origin = `http://127.0.0.1:${server.address().port}`;

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  headless: true,
  args: [
    "--headless=new",
    "--enable-unsafe-webgpu",
    "--use-webgpu-adapter=swiftshader",
    // Without a GPU process of its own (GL and Vulkan, both SwiftShader's) the page is
    // composited in software, and a WebGPU canvas never reaches the screen or a screenshot.
    "--ignore-gpu-blocklist",
    "--use-angle=swiftshader",
    "--enable-features=Vulkan",
    "--use-vulkan=swiftshader",
    "--no-sandbox",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-quic",
  ],
});

let code = 0;
try {
  code = bench ? await benchmark() : await test();
} catch (e) {
  console.error(`web test: ${e.stack ?? e}`);
  code = 1;
} finally {
  await browser.close();
  server.close();
}
process.exit(code);

// A page with its console errors collected.
async function open(query = "") {
  const page = await browser.newPage({ viewport: VIEWPORT });
  const errors = [];
  page.on("console", (m) => {
    if (m.type() === "error") errors.push(m.text());
    else if (process.env.VERBOSE) console.log(`console.${m.type()}: ${m.text()}`);
  });
  page.on("pageerror", (e) => errors.push(String(e)));
  const started = Date.now();
  await page.goto(`${origin}/${query}`);
  const first = await Promise.race([
    page.waitForSelector("body[data-first-frame-ms]", { timeout: FIRST_FRAME_TIMEOUT_MS }).then(() => "frame"),
    page.waitForSelector("#problem:not([hidden])", { timeout: FIRST_FRAME_TIMEOUT_MS }).then(() => "problem"),
  ]);
  if (first === "problem") {
    throw new Error(`the page shows a problem: ${await page.textContent("#problem")}`);
  }
  const firstFrameMs = Number(await page.getAttribute("body", "data-first-frame-ms"));
  console.log(`web test: first frame after ${firstFrameMs} ms (page load to a complete sky; ${Date.now() - started} ms in all)`);
  return { page, errors, firstFrameMs };
}

// The pixels of a screenshot of the page.
async function pixels(page, name) {
  const png = await page.screenshot();
  fs.writeFileSync(path.join(out, `${name}.png`), png);
  return PNG.sync.read(png);
}

// The mean colour over a square of `r` pixels around (x, y).
function meanColour(img, x, y, r = 6) {
  const sum = [0, 0, 0];
  let n = 0;
  for (let j = y - r; j <= y + r; j++) {
    for (let i = x - r; i <= x + r; i++) {
      const k = 4 * (j * img.width + i);
      for (let c = 0; c < 3; c++) sum[c] += img.data[k + c];
      n++;
    }
  }
  return sum.map((v) => v / n);
}

// Waits until `check(img)` holds of a screenshot, taking one a second.
async function until(page, name, check, timeoutMs, what) {
  const end = Date.now() + timeoutMs;
  for (;;) {
    const img = await pixels(page, name);
    const verdict = check(img);
    if (verdict.ok) return verdict;
    if (Date.now() > end) throw new Error(`${what}: ${verdict.why}`);
    await page.waitForTimeout(1000);
  }
}


// A click as a hand makes it: the pointer comes to rest first, so that egui has seen it there
// in a frame of its own before the button goes down.
async function click(page, at, settleMs = 1000) {
  await page.mouse.move(at.x, at.y, { steps: 4 });
  await page.waitForTimeout(400);
  await page.mouse.down();
  await page.waitForTimeout(150);
  await page.mouse.up();
  await page.waitForTimeout(settleMs);
}

async function choosePreset(page, name) {
  await click(page, AT.presetMenu);
  await click(page, AT.presets[name]);
}

// Distinct colours (5 bits a channel) over `area`, every `step` pixels.
function distinctColours(img, area, step) {
  const seen = new Set();
  for (let y = area.y0; y < area.y1; y += step) {
    for (let x = area.x0; x < area.x1; x += step) {
      const k = 4 * (y * img.width + x);
      seen.add(((img.data[k] >> 3) << 10) | ((img.data[k + 1] >> 3) << 5) | (img.data[k + 2] >> 3));
    }
  }
  return seen.size;
}

// A table drawn on the LUTs tab has many colours, the tab's text alone few.
function lutColours(img) {
  return distinctColours(img, AT.lutArea, 4);
}

// The mean absolute difference of two screenshots over `area`, levels of 255.
function meanDifference(a, b, area) {
  let sum = 0;
  let n = 0;
  for (let y = area.y0; y < area.y1; y++) {
    for (let x = area.x0; x < area.x1; x++) {
      const k = 4 * (y * a.width + x);
      for (let c = 0; c < 3; c++) sum += Math.abs(a.data[k + c] - b.data[k + c]);
      n += 3;
    }
  }
  return sum / n;
}

// Where `png` lies in the screenshot `img` if it is centred within a few pixels of `centre`:
// the share of a 5 × 5 grid of its patches whose mean colour is the screen's there within 6
// levels, at the best offset.
function findOnScreen(png, img, centre) {
  const patch = (im, x, y) => meanColour(im, x, y, 3);
  const grid = [];
  for (let j = 1; j <= 5; j++) {
    for (let i = 1; i <= 5; i++) {
      const x = Math.round((i / 6) * png.width);
      const y = Math.round((j / 6) * png.height);
      grid.push({ x, y, colour: patch(png, x, y) });
    }
  }
  let best = { matching: 0, dx: 0, dy: 0 };
  const x0 = centre.x - Math.floor(png.width / 2);
  const y0 = centre.y - Math.floor(png.height / 2);
  for (let dy = -12; dy <= 12; dy++) {
    for (let dx = -12; dx <= 12; dx++) {
      let matching = 0;
      for (const g of grid) {
        const x = x0 + dx + g.x;
        const y = y0 + dy + g.y;
        if (x < 3 || y < 3 || x >= img.width - 3 || y >= img.height - 3) continue;
        const c = patch(img, x, y);
        if (c.every((v, k) => Math.abs(v - g.colour[k]) <= 6)) matching++;
      }
      if (matching / grid.length > best.matching) best = { matching: matching / grid.length, dx, dy };
    }
  }
  return best;
}

function rgbText(c) {
  return `rgb(${c.map((v) => v.toFixed(0)).join(", ")})`;
}

async function test() {
  await withoutWebgpu();
  const { page, errors, firstFrameMs } = await open();
  await click(page, AT.startExploring);

  await choosePreset(page, "clear-noon");
  const noon = await until(page, "1-noon", (img) => {
    const c = meanColour(img, AT.sky.x, AT.sky.y);
    return { ok: c[2] > 1.35 * c[0] && c[2] > c[1] && c[2] > 80, why: `the sky's centre is ${rgbText(c)}, not blue`, c };
  }, 60_000, "a clear noon");
  console.log(`web test: clear noon, the sky's centre ${rgbText(noon.c)}`);

  await choosePreset(page, "urban-sunset");
  const sunset = await until(page, "2-sunset", (img) => {
    const c = meanColour(img, AT.sky.x, AT.sky.y);
    // Reddened: red over blue at least twice what it was at noon, and red above blue.
    const ratio = c[0] / Math.max(c[2], 1);
    return { ok: c[0] > c[2] && ratio > 2 * (noon.c[0] / noon.c[2]), why: `the sky's centre is ${rgbText(c)}, not reddened`, c };
  }, 60_000, "an urban sunset");
  console.log(`web test: urban sunset, the sky's centre ${rgbText(sunset.c)}`);

  // Exports are downloads: the view as displayed (PNG) and its radiance (EXR).
  const png = await exportAs(page, "Control+E", "atmoscope.png", (bytes) => PNG.sync.read(bytes));
  await exportAs(page, "Control+Shift+E", "atmoscope.exr", (bytes) => {
    // OpenEXR's magic number.
    if (bytes.readUInt32LE(0) !== 20000630) throw new Error("atmoscope.exr is not an OpenEXR file");
    return `${bytes.length} bytes`;
  });
  // The PNG is the view on the page: at render scale 1 and one pixel a point the view is
  // shown pixel for pixel, so the PNG, its size the view's, lies in a screenshot around the
  // view's centre.
  const placed = findOnScreen(png, await pixels(page, "2-exported"), AT.sky);
  if (placed.matching < 0.8) {
    throw new Error(`the exported PNG (${png.width}×${png.height}) is not the view on the page: at best ${(100 * placed.matching).toFixed(0)} % of its patches match the screen (offset ${placed.dx}, ${placed.dy})`);
  }
  console.log(`web test: exported the view as PNG (${png.width}×${png.height}, ${(100 * placed.matching).toFixed(0)} % of its patches as on the page) and EXR`);

  await click(page, AT.lutsTab);
  await until(page, "3-luts", (img) => {
    const colours = lutColours(img);
    return { ok: colours > 150, why: `the LUTs tab shows ${colours} colours, no table` };
  }, 60_000, "the LUTs tab");
  console.log("web test: the LUTs tab draws its table");

  // The layout and the scene are kept in the browser's storage: a reload opens on the LUTs
  // tab again, with the sunset's tables.
  await page.reload();
  await until(page, "4-reloaded", (img) => {
    const colours = lutColours(img);
    return { ok: colours > 150, why: `after a reload the LUTs tab shows ${colours} colours, no table` };
  }, 60_000, "the layout kept over a reload");
  console.log("web test: a reload keeps the layout");

  // The Reference tab's path tracer shares the page's thread a band of rows at a time and
  // shows its picture after each pass over the image: the first pass fills the picture in;
  // then, for at least half as long again as the first pass took, frames keep coming and the
  // picture changes (a later pass ended meanwhile: the tracer was running, not done).
  await click(page, AT.referenceTab);
  const clicked = Date.now();
  await until(page, "5-reference", (img) => {
    const colours = distinctColours(img, AT.pathTraced, 2);
    return { ok: colours > 60, why: `the path-traced picture shows ${colours} colours` };
  }, 120_000, "the Reference tab's path tracer");
  const firstPassMs = Date.now() - clicked;
  const windowMs = Math.max(5000, 1.5 * firstPassMs);
  const tracedBefore = await pixels(page, "5-tracing");
  const [frames, longestGapMs] = await page.evaluate((windowMs) => new Promise((done) => {
    let n = 0;
    let longest = 0;
    const start = performance.now();
    let last = start;
    const frame = () => {
      const now = performance.now();
      longest = Math.max(longest, now - last);
      last = now;
      n++;
      if (now - start < windowMs) requestAnimationFrame(frame);
      else done([n, longest]);
    };
    requestAnimationFrame(frame);
  }), windowMs);
  const seconds = windowMs / 1000;
  if (frames < seconds || longestGapMs > 2000) {
    throw new Error(`while the path tracer runs the page drew ${frames} frames in ${seconds.toFixed(0)} s, the longest gap ${longestGapMs.toFixed(0)} ms`);
  }
  const traced = meanDifference(tracedBefore, await pixels(page, "5-traced"), AT.pathTraced);
  if (!(traced > 1)) {
    throw new Error(`the path-traced picture did not change over ${seconds.toFixed(0)} s of frames (mean difference ${traced.toFixed(2)} levels; the first pass took ${(firstPassMs / 1000).toFixed(0)} s): the tracer was not running`);
  }
  console.log(`web test: the path tracer runs: its first pass in ${(firstPassMs / 1000).toFixed(0)} s; then the page drew ${frames} frames in ${seconds.toFixed(0)} s, the longest gap ${longestGapMs.toFixed(0)} ms, and the picture changed by ${traced.toFixed(1)} levels`);

  const problem = await page.isVisible("#problem");
  if (problem) throw new Error(`the page shows a problem: ${await page.textContent("#problem")}`);
  if (errors.length) {
    console.error(`web test: ${errors.length} console error(s):\n  ${errors.join("\n  ")}`);
    return 1;
  }
  fs.writeFileSync(path.join(out, "result.json"), JSON.stringify({ firstFrameMs, noon: noon.c, sunset: sunset.c }, null, 2));
  console.log(`web test: passed (screenshots in ${out})`);
  return 0;
}

// Presses `keys` and waits for the browser to download `name`; `check` reads its bytes.
async function exportAs(page, keys, name, check) {
  const [download] = await Promise.all([
    page.waitForEvent("download", { timeout: 60_000 }),
    page.keyboard.press(keys),
  ]);
  if (download.suggestedFilename() !== name) {
    throw new Error(`${keys} downloaded ${download.suggestedFilename()}, not ${name}`);
  }
  const file = path.join(out, name);
  await download.saveAs(file);
  return check(fs.readFileSync(file));
}

// A browser without WebGPU gets a page that says so, and no canvas.
async function withoutWebgpu() {
  const plain = await chromium.launch({
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
    headless: true,
    args: ["--no-sandbox", "--disable-background-networking", "--disable-component-update", "--disable-features=WebGPU"],
  });
  try {
    const page = await plain.newPage({ viewport: VIEWPORT });
    await page.goto(`${origin}/`);
    await page.waitForSelector("#problem:not([hidden])", { timeout: 60_000 });
    const text = await page.textContent("#problem");
    if (!/WebGPU/.test(text) || !(await page.isHidden("#atmoscope"))) {
      throw new Error(`without WebGPU the page says: ${text}`);
    }
    await page.screenshot({ path: path.join(out, "0-no-webgpu.png") });
    console.log(`web test: without WebGPU the page says: ${text.slice(0, 90)}…`);
  } finally {
    await plain.close();
  }
}

async function benchmark() {
  const model = process.env.ATMOSCOPE_BENCH_MODEL ?? "hillaire";
  const { page } = await open(`?bench=sky-frames&model=${model}`);
  await page.waitForSelector("body[data-bench-csv]", { timeout: 600_000 });
  const csv = await page.getAttribute("body", "data-bench-csv");
  fs.writeFileSync(path.join(out, "bench-sky-frames.csv"), csv);
  console.log(csv);
  return 0;
}
