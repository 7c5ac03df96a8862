#!/usr/bin/env node
// Drives a report page's interactive figures in a real browser (issue 34): Debian's chromium through npm
// playwright-core (no browser download).
//
//   node report_interactive.mjs PAGE.html --csv TABLE.csv --group UNIT --column COL [--window S]
//        [--screenshots DIR] [--max-fcp-ms MS] [--chromium PATH] [--wrap]
//
// Checks, in order, failing (exit 1) at the first that does not hold:
//   - no request leaves the page (every host resolves to nothing, the proxy is a dead port; any request other
//     than the file itself is a failure), no console error, no uncaught exception;
//   - the first contentful paint within --max-fcp-ms (default 1500);
//   - every chart and 3-D view is drawn (WebGL through SwiftShader in headless Chromium);
//   - a zoom box dragged with the mouse over COL's panel of UNIT to a --window-second window (default 1 s) in
//     the middle of the data: the panel shows that window (within 4 pixels), and every other panel of UNIT
//     follows it;
//   - the cursor at the window's middle: the read-out under the panel gives t_s, the value and its 1σ equal to
//     the row of TABLE.csv at that t_s (to float32 precision: 1e-6 relative);
//   - the 3-D view of UNIT (when the page has one) follows the cursor: its read-out's t_s is the chart's;
//   - a double click resets the zoom to the whole series on every panel of UNIT;
//   - each 3-D view recoloured by status and back by time;
//   - with --wrap (COL an angle that wraps, scripts/rk_html.py angle_wraps): the wraps of COL in TABLE.csv (rows
//     more than 180° from the previous finite row; at least one) are the panel's, and its line, ±1σ band included,
//     is clipped over each of them on the whole series and again after the reset (no line across the panel),
//     and the rows beside the wraps in view are drawn as points;
// and prints the figures (first paint, load, chart count, data span). Exit 77 when chromium or playwright-core
// is missing (the test is then reported skipped).
import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";

const SKIP = 77;
const args = process.argv.slice(2);
const opt = { window: 1, maxFcp: 1500, chromium: "/usr/bin/chromium" };
for (let i = 0; i < args.length; ++i) {
  const a = args[i];
  const next = () => { if (i + 1 >= args.length) fail("usage: " + a + " needs a value"); return args[++i]; };
  if (a === "--csv") opt.csv = next();
  else if (a === "--group") opt.group = next();
  else if (a === "--column") opt.column = next();
  else if (a === "--window") opt.window = Number(next());
  else if (a === "--screenshots") opt.shots = next();
  else if (a === "--max-fcp-ms") opt.maxFcp = Number(next());
  else if (a === "--chromium") opt.chromium = next();
  else if (a === "--wrap") opt.wrap = true;
  else if (!opt.page) opt.page = a;
  else fail("usage: unexpected argument " + a);
}
function fail(msg) {
  console.error("report_interactive: FAIL: " + msg);
  process.exit(1);
}
if (!opt.page || !opt.csv || !opt.group || !opt.column) fail("usage: PAGE --csv TABLE --group UNIT --column COL");

// playwright-core from the repository's node_modules (RK_NODE_MODULES, else the source tree's).
const modules = process.env.RK_NODE_MODULES || path.join(path.dirname(new URL(import.meta.url).pathname), "../../node_modules");
let chromium;
try {
  chromium = createRequire(path.join(modules, "x.js"))("playwright-core").chromium;
} catch (e) {
  console.log("SKIP: playwright-core is not installed in " + modules + " (scripts/setup.sh runs npm ci)");
  process.exit(SKIP);
}
if (!fs.existsSync(opt.chromium)) {
  console.log("SKIP: " + opt.chromium + " is not installed (scripts/setup.sh --browser)");
  process.exit(SKIP);
}

// The CSV row at t_s (the table's own text, not the page's numbers).
function csvRows(file) {
  const lines = fs.readFileSync(file, "utf8").split("\n").filter((l) => l && !l.startsWith("#"));
  const head = lines[0].split(",");
  return { head, rows: lines.slice(1).map((l) => l.split(",")) };
}

// COL's wraps in TABLE.csv: [t_s of the row before, t_s of the row after].
function csvWraps() {
  const { head, rows } = csvRows(opt.csv);
  const it = head.indexOf("t_s"), ic = head.indexOf(opt.column);
  const out = [];
  let last = null;
  for (const r of rows) {
    const v = r[ic] === "" ? NaN : Number(r[ic]);
    if (!Number.isFinite(v)) { last = null; continue; }
    if (last && Math.abs(v - last.v) > 180) out.push([last.t, Number(r[it])]);
    last = { v, t: Number(r[it]) };
  }
  return out;
}

// The panel's wraps and, for each drawn series, whether a clip gap of its path covers each wrap's pixel span.
async function checkWraps(page, k, expected, when) {
  const got = await page.evaluate((k) => {
    const u = window.rkCharts[k];
    const t = u.data[0];
    const breaks = (u.rkWrapBreaks || []).map(([a, b]) => [t[a], t[b]]);
    const covered = u.series.slice(1).filter((s) => s._paths).map((s) => (u.rkWrapBreaks || []).map(([a, b]) => {
      const p0 = Math.round(u.valToPos(t[a], "x", true)), p1 = Math.max(Math.round(u.valToPos(t[b], "x", true)), p0 + 1);
      const inView = t[b] >= u.scales.x.min && t[a] <= u.scales.x.max;
      return !inView || (s._paths.gaps || []).some((g) => g[0] <= p0 && g[1] >= p1);
    }));
    // The rows on either side of a wrap in view are drawn as points (the line between them is cut).
    const inView = (u.rkWrapBreaks || []).some(([a, b]) => t[b] >= u.scales.x.min && t[a] <= u.scales.x.max);
    const points = !inView || (u.series[1].points._paths !== null && u.series[1].points._paths !== undefined);
    return { breaks, covered, points };
  }, k);
  const same = got.breaks.length === expected.length &&
    got.breaks.every(([a, b], i) => Math.abs(a - expected[i][0]) <= 1e-9 * Math.max(1, Math.abs(a)) &&
                                    Math.abs(b - expected[i][1]) <= 1e-9 * Math.max(1, Math.abs(b)));
  if (!same) fail(when + ": the panel's wraps " + JSON.stringify(got.breaks) + " are not the CSV's " + JSON.stringify(expected));
  if (!got.covered.length || got.covered.some((c) => c.some((x) => !x))) {
    fail(when + ": a line drawn across a wrap of " + opt.column + " " + JSON.stringify(got.covered));
  }
  if (!got.points) fail(when + ": the rows beside the wraps of " + opt.column + " are not drawn as points");
  return got.breaks.length;
}

const browser = await chromium.launch({
  executablePath: opt.chromium,
  headless: true,
  args: ["--no-sandbox", "--proxy-server=127.0.0.1:9", "--host-resolver-rules=MAP * ~NOTFOUND",
         "--enable-unsafe-swiftshader", "--use-angle=swiftshader", "--disable-background-networking"],
});
const problems = [];
let result = 0;
try {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  const url = "file://" + path.resolve(opt.page);
  page.on("console", (m) => { if (m.type() === "error") problems.push("console error: " + m.text()); });
  page.on("pageerror", (e) => problems.push("uncaught: " + e.message));
  page.on("request", (r) => { if (r.url() !== url && !r.url().startsWith("data:")) problems.push("request: " + r.url()); });
  await page.goto(url, { waitUntil: "load" });
  await page.waitForFunction(() => window.rkReady === true, null, { timeout: 30000 });
  await page.waitForFunction(() => performance.getEntriesByName("first-contentful-paint").length > 0, null,
                             { timeout: 10000 }).catch(() => {});
  const timing = await page.evaluate(() => {
    const fcp = performance.getEntriesByName("first-contentful-paint")[0];
    const nav = performance.getEntriesByType("navigation")[0];
    return { fcp: fcp ? fcp.startTime : null, load: nav ? nav.loadEventEnd : null };
  });
  if (timing.fcp === null || timing.fcp > opt.maxFcp) fail("first contentful paint " + timing.fcp + " ms > " + opt.maxFcp);

  // Every figure drawn.
  const made = await page.evaluate(() => {
    window.rkMakeAll();
    const views = [...document.querySelectorAll(".rk-3d")].map((e) => e.dataset.ready);
    return { charts: window.rkCharts.length, views };
  });
  if (!made.charts) fail("no chart on the page");
  if (made.views.some((v) => v !== "yes")) fail("3-D view not drawn: " + made.views.join(","));
  if (opt.shots) {
    fs.mkdirSync(opt.shots, { recursive: true });
  }

  // The panel of COL in UNIT, scrolled into view.
  const k = await page.evaluate(([g, c]) => window.rkCharts.findIndex((u) => u.rkGroup === g && u.rkColumn === c),
                                [opt.group, opt.column]);
  if (k < 0) fail("no panel of " + opt.column + " in " + opt.group);
  const over = page.locator(".u-over").nth(k);
  await over.scrollIntoViewIfNeeded();
  const span = await page.evaluate((k) => {
    const u = window.rkCharts[k];
    const t = u.data[0].filter((v) => v !== null);
    return { t0: t[0], t1: t[t.length - 1], min: u.scales.x.min, max: u.scales.x.max };
  }, k);
  const wraps = opt.wrap ? csvWraps() : [];
  if (opt.wrap && !wraps.length) fail("--wrap: " + opt.column + " never wraps in " + opt.csv + ": nothing checked");
  if (opt.wrap) await checkWraps(page, k, wraps, "whole series");
  // Drag boxes, each at most 40 times narrower than the window shown (a 1-s box on an hour is under a pixel),
  // until the window is --window seconds about the data's middle.
  const mid = (span.t0 + span.t1) / 2;
  let box, px, y, a, b, zoomed, tolerance;
  for (let step = 0; step < 8; ++step) {
    const now = await page.evaluate((k) => [window.rkCharts[k].scales.x.min, window.rkCharts[k].scales.x.max], k);
    const w = Math.max(opt.window, (now[1] - now[0]) / 40);
    a = mid - w / 2;
    b = mid + w / 2;
    box = await over.boundingBox();
    // Four pixels of the window the box is dragged on (the drag snaps to whole pixels at each end).
    tolerance = 4 * (now[1] - now[0]) / box.width;
    px = await page.evaluate(([k, a, b]) => {
      const u = window.rkCharts[k];
      return [u.valToPos(a, "x"), u.valToPos(b, "x")];
    }, [k, a, b]);
    y = box.y + box.height / 2;
    await page.mouse.move(box.x + px[0], y);
    await page.mouse.down();
    await page.mouse.move(box.x + (px[0] + px[1]) / 2, y, { steps: 4 });
    await page.mouse.move(box.x + px[1], y, { steps: 4 });
    await page.mouse.up();
    zoomed = await page.evaluate(([k, g]) => {
      const u = window.rkCharts[k];
      const others = window.rkCharts.filter((o) => o.rkGroup === g && o !== u).map((o) => [o.scales.x.min, o.scales.x.max]);
      return { min: u.scales.x.min, max: u.scales.x.max, others, pxPerS: u.bbox.width / devicePixelRatio / (u.scales.x.max - u.scales.x.min) };
    }, [k, opt.group]);
    if (Math.abs(zoomed.min - a) > tolerance || Math.abs(zoomed.max - b) > tolerance) {
      fail("zoom window [" + zoomed.min + ", " + zoomed.max + "] is not the dragged [" + a + ", " + b + "] (±" + tolerance + " s)");
    }
    for (const [lo, hi] of zoomed.others) {
      if (lo !== zoomed.min || hi !== zoomed.max) fail("another panel of " + opt.group + " shows [" + lo + ", " + hi + "]");
    }
    if (w === opt.window) break;
  }
  if (Math.abs(zoomed.max - zoomed.min - opt.window) > 2 * tolerance) fail("not zoomed to " + opt.window + " s");
  tolerance = 4 / zoomed.pxPerS;
  if (opt.shots) {
    await page.mouse.move(box.x + (px[0] + px[1]) / 2, y);
    await over.locator("xpath=ancestor::div[contains(@class,'rk-chart')]").screenshot({ path: path.join(opt.shots, "zoomed.png") });
  }

  // The cursor in the window's middle: the read-out against the CSV row.
  await page.mouse.move(box.x + (px[0] + px[1]) / 2, y);
  const read = await page.evaluate((k) => ({ ...window.rkCharts[k].rkReadout.dataset, text: window.rkCharts[k].rkReadout.textContent }), k);
  const { head, rows } = csvRows(opt.csv);
  const it = head.indexOf("t_s"), ic = head.indexOf(opt.column);
  const is = head.indexOf("sigma_" + opt.column);
  const t = Number(read.t);
  const row = rows.find((r) => Math.abs(Number(r[it]) - t) <= 1e-9 * Math.max(1, Math.abs(t)));
  if (!row) fail("no row of " + opt.csv + " at t_s " + read.t + " (read-out: " + read.text + ")");
  const close = (x, ref) => Math.abs(x - ref) <= 1e-6 * Math.max(1, Math.abs(ref));
  if (!close(Number(read.value), Number(row[ic]))) fail("read-out " + opt.column + " " + read.value + " != CSV " + row[ic]);
  if (is >= 0 && !close(Number(read.sigma), Number(row[is]))) fail("read-out 1σ " + read.sigma + " != CSV " + row[is]);
  // The 3-D view of the unit follows the cursor.
  const linked = await page.evaluate((g) => {
    const v = [...document.querySelectorAll(".rk-3d")].filter((e) => e.dataset.group === g);
    return v.map((e) => e.querySelector(".rk-readout").dataset.t);
  }, opt.group);
  for (const tv of linked) {
    if (tv === undefined || Math.abs(Number(tv) - t) > 0.5 / zoomed.pxPerS + 0.1) fail("3-D view at t_s " + tv + ", chart at " + t);
  }
  if (opt.shots && (await page.locator(".rk-3d").count())) {
    const mine = page.locator('.rk-3d[data-group="' + opt.group + '"]');
    const v = (await mine.count()) ? mine.first() : page.locator(".rk-3d").first();
    await v.scrollIntoViewIfNeeded();
    await v.screenshot({ path: path.join(opt.shots, "view3d.png") });
  }

  // Double click: the whole series again, on every panel of the group.
  await over.scrollIntoViewIfNeeded();
  const box2 = await over.boundingBox();
  await page.mouse.dblclick(box2.x + box2.width / 2, box2.y + box2.height / 2);
  const reset = await page.evaluate((g) => window.rkCharts.filter((o) => o.rkGroup === g).map((o) => [o.scales.x.min, o.scales.x.max]), opt.group);
  for (const [lo, hi] of reset) {
    if (lo > span.t0 + 1e-9 || hi < span.t1 - 1e-9) fail("after a double click a panel shows [" + lo + ", " + hi + "], not the whole [" + span.t0 + ", " + span.t1 + "]");
  }
  if (opt.wrap) await checkWraps(page, k, wraps, "after the reset");
  // The 3-D views coloured by status, then by time again.
  const pickers = page.locator("select.rk-colour");
  for (let i = 0; i < (await pickers.count()); ++i) {
    await pickers.nth(i).scrollIntoViewIfNeeded();
    await pickers.nth(i).selectOption("status");
    await pickers.nth(i).selectOption("time");
  }
  await page.waitForTimeout(100);
  if (problems.length) fail(problems.join("; "));
  console.log("report_interactive: " + opt.page + ": first paint " + timing.fcp.toFixed(0) + " ms, load " +
              timing.load.toFixed(0) + " ms, " + made.charts + " panels, " + made.views.length + " 3-D views; zoomed to [" +
              zoomed.min.toFixed(3) + ", " + zoomed.max.toFixed(3) + "] s and back; read-out " + read.text +
              (opt.wrap ? "; " + wraps.length + " wrap(s) of " + opt.column + ", no line across them" : ""));
} catch (e) {
  console.error("report_interactive: FAIL: " + (e && e.stack ? e.stack : e));
  result = 1;
} finally {
  await browser.close();
}
process.exit(result);
