// Smoke test of the viewer (www/) in headless Chromium: it loads the package, plans the default
// field, draws it, re-plans on input, switches fields, survives planner errors, pans and zooms,
// and lays out on a phone. Screenshots go to target/screenshots/.
//
//   bash scripts/build.sh            (once: the wasm package and target/site)
//   node scripts/site.mjs            (after editing www/ only)
//   node --test pkg-tests/
//
// Uses playwright-core with Debian's chromium (never downloads a browser); set CHROMIUM to use
// another binary.
import { test } from "node:test";
import assert from "node:assert/strict";
import { existsSync, mkdirSync } from "node:fs";
import { join } from "node:path";
import { startServer } from "../scripts/serve.mjs";
import { launchChromium, ROOT, SITE } from "./support.mjs";

const SHOTS = join(ROOT, "target/screenshots");
const TIMEOUT = 60_000;

/** Starts the server and the browser, runs `body(page, base)`, and always closes both. */
async function withViewer(contextOptions, body) {
  if (!existsSync(join(SITE, "pkg", "furrow.js")) || !existsSync(join(SITE, "index.html"))) {
    throw new Error("target/site/pkg or target/site/index.html is missing: run scripts/build.sh first");
  }
  const server = await startServer(SITE, 0);
  let browser;
  try {
    browser = await launchChromium();
    const context = await browser.newContext(contextOptions);
    const page = await context.newPage();
    const problems = [];
    page.on("console", (msg) => {
      if (msg.type() === "error") problems.push(`console error: ${msg.text()}`);
    });
    page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
    page.on("requestfailed", (r) => problems.push(`request failed: ${r.url()} ${r.failure()?.errorText}`));
    page.on("response", (r) => {
      if (r.status() >= 400) problems.push(`HTTP ${r.status()}: ${r.url()}`);
    });
    // Only same-origin requests: no CDN, fonts or other hosts.
    const base = `http://127.0.0.1:${server.address().port}/`;
    page.on("request", (r) => {
      if (!r.url().startsWith(base) && !r.url().startsWith("data:")) problems.push(`foreign request: ${r.url()}`);
    });
    await body(page, base);
    assert.deepEqual(problems, [], "the page logged errors or made bad requests");
  } finally {
    await browser?.close();
    await new Promise((ok) => server.close(ok));
  }
}

const ready = (page) => page.waitForSelector("body[data-plan-state=ready]", { timeout: 20_000 });
const dataset = (page) => page.evaluate(() => ({ ...document.body.dataset }));

/** Number of canvas pixels within `tolerance` of the CSS colour of custom property `name`. */
function countColour(page, name, tolerance = 40) {
  return page.evaluate(
    ([name, tolerance]) => {
      const probe = document.createElement("span");
      probe.style.color = `var(${name})`;
      document.body.append(probe);
      const [r, g, b] = getComputedStyle(probe).color.match(/\d+(\.\d+)?/g).map(Number);
      probe.remove();
      const canvas = document.getElementById("map");
      const data = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
      let n = 0;
      for (let i = 0; i < data.length; i += 4) {
        if (Math.abs(data[i] - r) + Math.abs(data[i + 1] - g) + Math.abs(data[i + 2] - b) <= tolerance) n++;
      }
      return n;
    },
    [name, tolerance],
  );
}

/** Sets an input's value as typing would and fires `input`. */
async function setInput(page, id, value) {
  await page.fill(`#${id}`, String(value));
}

/** A fingerprint of the last plan, to tell plans apart. */
const planKey = (page) =>
  page.evaluate(() => {
    const p = window.furrow.plan;
    return p ? JSON.stringify([p.summary.swath_count, p.summary.total_distance_m, p.features.length]) : null;
  });

test("viewer: loads, draws, re-plans, switches fields, survives errors", { timeout: TIMEOUT }, async () => {
  mkdirSync(SHOTS, { recursive: true });
  await withViewer({ viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 }, async (page, base) => {
    await page.goto(base);
    await ready(page);

    // The default field is planned and drawn.
    let ds = await dataset(page);
    assert.ok(Number(ds.swathCount) > 0, `swath count ${ds.swathCount}`);
    assert.ok(Number(ds.planMs) >= 0, `plan ms ${ds.planMs}`);
    const fields = await page.$$eval("#field option", (os) => os.map((o) => o.value));
    assert.ok(fields.length > 1, "the field picker lists the bundled fields");
    const first = await page.inputValue("#field");
    for (const kind of ["--swath", "--headland", "--turn", "--boundary"]) {
      const n = await countColour(page, kind);
      assert.ok(n > 100, `only ${n} pixels of ${kind} on the canvas`);
    }
    const summary = await page.textContent("#summary");
    assert.match(summary, /Swaths/);
    assert.match(summary, /km/);
    assert.match(summary, /ha/);

    // Changing the headland passes re-plans.
    const before = await planKey(page);
    const passes = Number(await page.inputValue("#headlandPasses"));
    await setInput(page, "headlandPasses", passes + 2);
    await ready(page);
    assert.equal(await page.evaluate(() => window.furrow.plan.summary.headland_pass_count), passes + 2);
    assert.notEqual(await planKey(page), before, "the plan did not change with the headland passes");

    // A fixed bearing re-plans along it; empty goes back to automatic.
    await setInput(page, "bearing", 17);
    await ready(page);
    assert.equal(await page.evaluate(() => Math.round(window.furrow.plan.summary.bearing_deg)), 17);
    await setInput(page, "bearing", "");
    await ready(page);
    assert.match(await page.textContent("#summary"), /auto/);

    // A planner error is shown in words, the page keeps working, and a good value recovers.
    await setInput(page, "headlandPasses", 50);
    await page.waitForSelector("body[data-plan-state=error]", { timeout: 10_000 });
    const message = await page.textContent("#map-message");
    assert.match(message, /headland/i, `error message: ${message}`);
    assert.ok(await page.isVisible("#map-message"), "the error is visible on the page");
    assert.equal(await page.getAttribute("#headlandPasses", "aria-invalid"), "true");
    await setInput(page, "width", "");
    assert.match(await page.textContent("#map-message"), /number/i);
    await page.click("#suggested");
    await ready(page);
    assert.ok(await page.isHidden("#map-message"));

    // Pan, zoom and fit.
    const box = await page.locator("#map").boundingBox();
    const cx = box.x + box.width / 2;
    const cy = box.y + box.height / 2;
    const v0 = await page.evaluate(() => window.furrow.view.state());
    await page.mouse.move(cx, cy);
    await page.mouse.wheel(0, -400);
    await page.waitForFunction((s) => window.furrow.view.state().scale > s * 1.2, v0.scale);
    await page.mouse.down();
    await page.mouse.move(cx + 120, cy + 60, { steps: 5 });
    await page.mouse.up();
    const v1 = await page.evaluate(() => window.furrow.view.state());
    assert.ok(v1.cx < v0.cx && v1.cy > v0.cy, `drag pans the view: ${JSON.stringify([v0, v1])}`);
    await page.click("#fit");
    const v2 = await page.evaluate(() => window.furrow.view.state());
    assert.ok(Math.abs(v2.scale - v0.scale) < 1e-9 * v0.scale && v2.fitted, "fit restores the fitted view");

    // Another field from the picker loads, takes its suggested settings and re-plans.
    const other = fields.find((f) => f !== first && f === "underdrain") ?? fields.find((f) => f !== first);
    const beforeSwitch = await planKey(page);
    await page.selectOption("#field", other);
    await page.waitForFunction((name) => window.furrow.field?.features?.[0]?.properties?.name === name, other);
    await ready(page);
    ds = await dataset(page);
    assert.ok(Number(ds.swathCount) > 0);
    assert.notEqual(await planKey(page), beforeSwitch, "the plan did not change with the field");
    const index = await page.evaluate(() => fetch("fields/index.json").then((r) => r.json()));
    const entry = index.find((f) => f.name === other);
    assert.equal(Number(await page.inputValue("#width")), entry.width);
    assert.equal(Number(await page.inputValue("#headlandPasses")), entry.headlandPasses);
    assert.ok((await countColour(page, "--swath")) > 100, "swaths drawn on the other field");

    await page.screenshot({ path: join(SHOTS, "viewer.png") });
  });
});

test("viewer: phone layout with touch, pinch zoom", { timeout: TIMEOUT }, async () => {
  mkdirSync(SHOTS, { recursive: true });
  const phone = { viewport: { width: 390, height: 844 }, deviceScaleFactor: 2, hasTouch: true, isMobile: true };
  await withViewer(phone, async (page, base) => {
    await page.goto(`${base}#obstacles-2`);
    await ready(page);
    assert.equal(await page.inputValue("#field"), "obstacles-2");
    assert.ok(Number((await dataset(page)).swathCount) > 0);

    const layout = await page.evaluate(() => {
      const rect = (sel) => document.querySelector(sel).getBoundingClientRect().toJSON();
      const canvas = document.getElementById("map");
      const small = [...document.querySelectorAll("button, select, input")]
        .map((el) => [el.id || el.tagName, el.getBoundingClientRect()])
        .filter(([, r]) => r.height < 44 || r.width < 44)
        .map(([id, r]) => `${id} ${r.width}x${r.height}`);
      return {
        controls: rect(".controls"),
        map: rect(".map"),
        info: rect(".info"),
        canvas: [canvas.width, canvas.height, canvas.clientWidth, canvas.clientHeight],
        scrollWidth: document.documentElement.scrollWidth,
        small,
      };
    });
    assert.ok(layout.controls.bottom <= layout.map.top + 1, "controls above the map");
    assert.ok(layout.info.top >= layout.map.bottom - 1, "figures below the map");
    assert.ok(layout.map.height >= 300, `map height ${layout.map.height}`);
    assert.equal(layout.scrollWidth, 390, "no sideways scrolling");
    assert.deepEqual(layout.small, [], "touch targets of at least 44 px");
    const [w, h, cw, ch] = layout.canvas;
    assert.equal(w, cw * 2, "canvas at device resolution");
    assert.equal(h, ch * 2, "canvas at device resolution");
    assert.ok((await countColour(page, "--swath")) > 100, "swaths drawn");

    // Two-finger pinch outwards zooms in (touch events through the DevTools protocol).
    const box = await page.locator("#map").boundingBox();
    const x = box.x + box.width / 2;
    const y = box.y + box.height / 2;
    const s0 = (await page.evaluate(() => window.furrow.view.state())).scale;
    const cdp = await page.context().newCDPSession(page);
    const touch = (type, d) =>
      cdp.send("Input.dispatchTouchEvent", {
        type,
        touchPoints:
          type === "touchEnd"
            ? []
            : [
                { x: x - d, y, id: 1 },
                { x: x + d, y, id: 2 },
              ],
      });
    await touch("touchStart", 30);
    for (let d = 40; d <= 120; d += 20) await touch("touchMove", d);
    await touch("touchEnd", 0);
    await page.waitForFunction((s) => window.furrow.view.state().scale > s * 2, s0);

    await page.locator("#fit").tap();
    await page.screenshot({ path: join(SHOTS, "viewer-phone.png"), fullPage: true });
  });
});
