// What a new user meets in the viewer's first hour, on a desktop and a phone, in headless
// Chromium: the page's Content-Security-Policy; drawing a new field (corners tapped clockwise,
// undo right after closing it); the edit hint beside, never over, a corner; the phone's first
// screen; files of many parcels (the list to pick from); large files (refused without freezing
// the page) and one file's error not left beside the next.
//
//   bash scripts/build.sh   (once), then   node --test pkg-tests/first-hour.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import {
  dataset,
  mapOrigin,
  planned,
  ready,
  TIMEOUT,
  vertexAt,
  withViewer,
} from "./viewer-support.mjs";

const DESKTOP = { viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 };

test("first hour: the page runs under a strict CSP: plans, edits, drives; inline scripts refused", { timeout: TIMEOUT }, async () => {
  await withViewer(DESKTOP, async (page, base) => {
    const response = await page.goto(`${base}#rectangle`);
    await planned(page);
    // The policy comes with the page (header and meta tag) and is enforced.
    const header = response.headers()["content-security-policy"] ?? "";
    assert.match(header, /script-src 'self' 'wasm-unsafe-eval'/);
    const meta = await page.getAttribute('meta[http-equiv="Content-Security-Policy"]', "content");
    assert.ok(meta && header.startsWith(meta), "the header is the meta tag's policy (and frame-ancestors)");
    // On a page of its own (whose console errors this test does not count): an inline script
    // is refused.
    const probe = await page.context().newPage();
    await probe.goto(base);
    const refused = await probe.evaluate(async () => {
      const seen = [];
      document.addEventListener("securitypolicyviolation", (e) => seen.push(e.effectiveDirective));
      const s = document.createElement("script");
      s.textContent = "window.__inline = true";
      document.head.append(s);
      await new Promise((r) => setTimeout(r, 50));
      return { inline: window.__inline === true, seen };
    });
    await probe.close();
    assert.equal(refused.inline, false, "an inline script does not run");
    assert.deepEqual([...new Set(refused.seen)], ["script-src-elem"]);
    await page.evaluate(() => {
      window.__cspSeen = 0;
      document.addEventListener("securitypolicyviolation", () => window.__cspSeen++);
    });
    assert.equal((await dataset(page)).planner, "worker", "the planner's worker compiled its WebAssembly");
    // Edit: drag a corner; draw a prohibited region (its bearing dial); drive.
    await page.click('#edit-bar [data-mode="edit"]');
    const v = await vertexAt(page, 0, 1);
    await page.mouse.move(v.x, v.y);
    await page.mouse.down();
    await page.mouse.move(v.x + 30, v.y + 10, { steps: 5 });
    await page.mouse.up();
    await planned(page);
    const o = await mapOrigin(page);
    await page.click('#edit-bar [data-mode="prohibited"]');
    const cx = o.x + o.width / 2;
    const cy = o.y + o.height / 2;
    for (const [dx, dy] of [[-30, -20], [30, -20], [0, 30]]) await page.mouse.click(cx + dx, cy + dy);
    await page.click("#finish");
    await planned(page);
    assert.ok(await page.isVisible("#region-dial svg"), "the region's dial is shown");
    await page.click("#display-options summary");
    await page.selectOption("#drive-speed", "1000");
    await page.click("#drive");
    await page.waitForFunction(() => Number(document.body.dataset.driveS) > 30, null, { timeout: 10_000 });
    await page.click("#drive");
    assert.equal(await page.evaluate(() => window.__cspSeen), 0, "no CSP violation while planning, editing and driving");
  });
});
