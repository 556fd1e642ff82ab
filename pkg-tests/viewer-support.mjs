// Shared by the viewer's Playwright tests (viewer.test.mjs, editor.test.mjs): the server and
// browser around a test, and small probes of the page.
import assert from "node:assert/strict";
import { existsSync } from "node:fs";
import { join } from "node:path";
import { startServer } from "../scripts/serve.mjs";
import { launchChromium, ROOT, SITE } from "./support.mjs";

export const SHOTS = join(ROOT, "target/screenshots");
export const FIELDS = join(ROOT, "tests/fields");
export const INVALID = join(FIELDS, "invalid");
export const TIMEOUT = 60_000;

/** Makes every Content-Security-Policy violation in the context's pages a console error (which
 * the tests count as a problem), with the directive and what it refused. */
export function reportCspViolations(context) {
  return context.addInitScript(() => {
    document.addEventListener("securitypolicyviolation", (e) => {
      console.error(`CSP violation: ${e.effectiveDirective} refused ${e.blockedURI || "inline"} (${e.sourceFile}:${e.lineNumber})`);
    });
  });
}

/** Starts the server and the browser, runs `body(page, base)`, and always closes both. Console
 * errors (CSP violations among them), page errors, failed or foreign requests fail the test. */
export async function withViewer(contextOptions, body) {
  if (!existsSync(join(SITE, "pkg", "furrow.js")) || !existsSync(join(SITE, "index.html"))) {
    throw new Error("target/site/pkg or target/site/index.html is missing: run scripts/build.sh first");
  }
  const server = await startServer(SITE, 0);
  let browser;
  try {
    browser = await launchChromium();
    const context = await browser.newContext(contextOptions);
    await reportCspViolations(context);
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

export const ready = (page) => page.waitForSelector("body[data-plan-state=ready]", { timeout: 20_000 });
export const dataset = (page) => page.evaluate(() => ({ ...document.body.dataset }));

/** Waits until the plan drawn is that of the newest edit. */
export async function planned(page) {
  await page.waitForFunction(
    () => document.body.dataset.planState === "ready" && window.furrow.replans.made === window.furrow.replans.drawn,
    null,
    { timeout: 20_000 },
  );
}

/** The canvas's box in page px. */
export async function mapOrigin(page) {
  const box = await page.locator("#map").boundingBox();
  return { x: box.x, y: box.y, width: box.width, height: box.height };
}

/** Number of canvas pixels within `tolerance` of the CSS colour of custom property `name`. */
export function countColour(page, name, tolerance = 40) {
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
export async function setInput(page, id, value) {
  await page.fill(`#${id}`, String(value));
}

/** The outermost field headland pass of the plan shown (headland_pass_count also counts the
 * passes around obstacles). */
export const fieldPasses = (page) =>
  page.evaluate(() =>
    Math.max(
      ...window.furrow.plan.features
        .filter((f) => f.properties.kind === "headland" && f.properties.around === "field")
        .map((f) => f.properties.pass),
    ),
  );

/** A fingerprint of the last plan, to tell plans apart. */
export const planKey = (page) =>
  page.evaluate(() => {
    const p = window.furrow.plan;
    return p ? JSON.stringify([p.summary.swath_count, p.summary.total_distance_m, p.features.length]) : null;
  });

/** Screen position (page px) of vertex `i` of the first ring of feature `feature` of the document. */
export async function vertexAt(page, feature, i) {
  const o = await mapOrigin(page);
  const [x, y] = await page.evaluate(
    ([feature, i]) => {
      const { tool, view } = window.furrow;
      const ring = tool.rings().find((r) => r.feature === feature && r.ring === 0);
      return view.toScreen(ring.world[i]);
    },
    [feature, i],
  );
  return { x: o.x + x, y: o.y + y };
}
