// What a new user meets in the viewer's first hour, on a desktop and a phone, in headless
// Chromium: the page's Content-Security-Policy; drawing a new field (corners tapped clockwise,
// undo right after closing it); the edit hint beside, never over, a corner; the phone's first
// screen; files of many parcels (the list to pick from); large files (refused without freezing
// the page) and one file's error not left beside the next.
//
//   bash scripts/build.sh   (once), then   node --test pkg-tests/first-hour.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdirSync, readFileSync, rmSync, statSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import {
  FIELDS,
  dataset,
  mapOrigin,
  planned,
  ready,
  SHOTS,
  TIMEOUT,
  vertexAt,
  withViewer,
} from "./viewer-support.mjs";

mkdirSync(SHOTS, { recursive: true });

const DESKTOP = { viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 };
const PHONE = { viewport: { width: 390, height: 844 }, deviceScaleFactor: 2, hasTouch: true, isMobile: true };

/** The marks on the map (corners, insert marks, corners being tapped) under the edit hint, with
 * a handle's radius around it; and where the hint is. */
const underHint = (page) =>
  page.evaluate(async () => {
    await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
    const hint = document.getElementById("edit-hint");
    const map = document.getElementById("map").getBoundingClientRect();
    const r = hint.getBoundingClientRect();
    const pad = 6;
    const covered = window.furrow.tool
      .handlePoints()
      .filter(([x, y]) => x + map.left > r.left - pad && x + map.left < r.right + pad && y + map.top > r.top - pad && y + map.top < r.bottom + pad);
    return { shown: !hint.hidden, place: hint.dataset.place, covered: covered.length, rect: r.toJSON() };
  });

/** Moves the view so that corner `i` of the boundary lies in the middle of the edit hint. */
const cornerToHint = (page, i) =>
  page.evaluate((i) => {
    const { view, tool } = window.furrow;
    const map = document.getElementById("map").getBoundingClientRect();
    const r = document.getElementById("edit-hint").getBoundingClientRect();
    const [sx, sy] = view.toScreen(tool.rings()[0].world[i]);
    view.moveTo(sx, sy, r.left + r.width / 2 - map.left, r.top + r.height / 2 - map.top);
    view.draw();
  }, i);

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
    // The edit hint covers no corner, also when the map moves one to where it was.
    let hint = await underHint(page);
    assert.ok(hint.shown);
    assert.equal(hint.covered, 0, `corners under the hint at ${hint.place}`);
    const firstPlace = hint.place;
    await cornerToHint(page, 2);
    hint = await underHint(page);
    assert.equal(hint.covered, 0, `corners under the hint at ${hint.place}`);
    assert.notEqual(hint.place, firstPlace, "the hint moved aside");
    await page.click("#fit");
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

/** The warnings shown: the plan's codes, the panel's list, and the badges on the map. */
const shownWarnings = (page) =>
  page.evaluate(() => ({
    plan: (window.furrow.plan?.warnings ?? []).map((w) => w.code),
    list: [...document.querySelectorAll("#warnings li")].map((li) => li.dataset.code),
    badges: document.querySelectorAll("#map-notes .map-note").length,
  }));

test("first hour: a new field tapped clockwise plans without an orientation warning; undo right after closing it starts over", { timeout: TIMEOUT }, async () => {
  await withViewer(DESKTOP, async (page, base) => {
    await page.goto(base);
    await ready(page);
    // The map over the Pacific, so that a field drawn there carries a warning (at sea) with a
    // badge on its boundary.
    const square = [[-140, 30], [-139.998, 30], [-139.998, 30.002], [-140, 30.002], [-140, 30]];
    await page.evaluate((c) => window.furrow.loadField({ type: "Polygon", coordinates: [c] }, "at sea"), square);
    await ready(page);
    await page.click("#new-field");
    // A corner tapped where the hint is: the hint moves aside (Backspace takes the corner back).
    const at = (await underHint(page)).rect;
    await page.mouse.click(at.x + at.width / 2, at.y + at.height / 2);
    const moved = await underHint(page);
    assert.equal(moved.covered, 0, `the corner tapped is under the hint at ${moved.place}`);
    await page.keyboard.press("Backspace");
    assert.equal(await page.evaluate(() => window.furrow.tool.draft.length), 0);
    const o = await mapOrigin(page);
    const cx = o.x + o.width / 2;
    const cy = o.y + o.height / 2;
    // Clockwise on the map, the natural way.
    const corners = [
      [cx - 200, cy - 140],
      [cx + 200, cy - 140],
      [cx + 200, cy + 140],
      [cx - 200, cy + 140],
    ];
    for (const [x, y] of corners) await page.mouse.click(x, y);
    await page.mouse.click(corners[0][0], corners[0][1]);
    await planned(page);
    const first = await shownWarnings(page);
    assert.ok(!first.plan.includes("ring_reoriented"), `no orientation warning: ${first.plan}`);
    // The field's warning (the route's own, such as turns out of a square this small with two
    // passes, or over its crop, aside).
    const route = ["turn_crosses_crop", "turn_leaves_field", "connection_crosses_crop", "connection_leaves_field"];
    const fieldWarnings = first.plan.filter((c) => !route.includes(c));
    assert.deepEqual(fieldWarnings, ["field_at_sea"], "the one warning, to be cleared by undo");
    assert.ok(first.badges > 0 && first.list.length > 0);
    assert.equal((await dataset(page)).editMode, "edit");

    // Undo right after closing it: nothing of the plan is left, and taps draw the field again.
    await page.click("#undo");
    await page.waitForFunction(() => window.furrow.document.features.length === 0);
    const after = await page.evaluate(() => ({
      summary: document.querySelectorAll("#summary dd").length,
      status: document.getElementById("status").textContent,
      mode: document.body.dataset.editMode,
      swaths: document.body.dataset.swathCount,
      plan: window.furrow.plan,
      drawn: Boolean(window.furrow.view.plan),
    }));
    assert.deepEqual(await shownWarnings(page), { plan: [], list: [], badges: 0 });
    assert.deepEqual(after, { summary: 0, status: "Draw the field: tap its corners on the map", mode: "boundary", swaths: undefined, plan: null, drawn: false });
    // Redo brings the field back to edit; undo again, and three taps and Finish draw another.
    await page.click("#redo");
    await planned(page);
    assert.equal((await dataset(page)).editMode, "edit");
    assert.ok(Number((await dataset(page)).swathCount) > 0);
    await page.click("#undo");
    await page.waitForFunction(() => document.body.dataset.editMode === "boundary");
    for (const [x, y] of [[cx - 150, cy + 120], [cx + 150, cy + 120], [cx, cy - 130]]) await page.mouse.click(x, y);
    await page.click("#finish");
    await planned(page);
    const doc = await page.evaluate(() => window.furrow.document);
    assert.equal(doc.features.length, 1);
    assert.equal(doc.features[0].geometry.coordinates[0].length, 4, "the new triangle");
    // And it is planned: most of it worked (with the headland passes that leave it swaths).
    assert.ok((await page.evaluate(() => window.furrow.plan?.summary.coverage.coverage_ratio)) > 0.5, "and it is planned");
  });
});

test("first hour: on a phone the map is whole on the first screen and usable at once; Undo and Redo in reach; the hint clear of corners", { timeout: TIMEOUT }, async () => {
  await withViewer(PHONE, async (page, base) => {
    await page.goto(`${base}#rectangle`);
    await planned(page);
    const first = await page.evaluate(() => {
      const rect = (el) => el.getBoundingClientRect().toJSON();
      // A button is in reach when it lies on the screen and a tap at its middle lands on it.
      const reach = (id) => {
        const el = document.getElementById(id);
        const r = rect(el);
        const onScreen = r.left >= 0 && r.top >= 0 && r.right <= innerWidth && r.bottom <= innerHeight;
        return onScreen && document.elementFromPoint(r.left + r.width / 2, r.top + r.height / 2)?.closest("button") === el;
      };
      return { map: rect(document.querySelector(".map")), undo: reach("undo"), redo: reach("redo"), finish: document.getElementById("finish").hidden };
    });
    assert.ok(first.map.top >= 0 && first.map.top < 1, `the map starts at the top (${first.map.top} px)`);
    assert.ok(first.map.bottom <= 844 && first.map.height >= 400, `the map whole on the screen: ${JSON.stringify(first.map)}`);
    assert.ok(first.undo && first.redo, "Undo and Redo in reach without scrolling");
    // Usable at once, all by touch and without scrolling: redraw the boundary (Field, three
    // taps, Finish), undo, redo.
    const o = await mapOrigin(page);
    const before = await page.evaluate(() => JSON.stringify(window.furrow.document.features[0].geometry));
    await page.locator('#edit-bar [data-mode="boundary"]').tap();
    const cx = o.x + o.width / 2;
    const cy = o.y + o.height / 2;
    for (const [x, y] of [[cx - 100, cy + 80], [cx + 100, cy + 80], [cx, cy - 100]]) await page.touchscreen.tap(x, y);
    await page.locator("#finish").tap();
    await planned(page);
    const triangle = await page.evaluate(() => JSON.stringify(window.furrow.document.features[0].geometry));
    assert.notEqual(triangle, before);
    await page.locator("#undo").tap();
    await planned(page);
    assert.equal(await page.evaluate(() => JSON.stringify(window.furrow.document.features[0].geometry)), before, "undo");
    await page.locator("#redo").tap();
    await planned(page);
    assert.equal(await page.evaluate(() => JSON.stringify(window.furrow.document.features[0].geometry)), triangle, "redo");
    assert.equal(await page.evaluate(() => scrollY), 0, "no scrolling needed");
    // The edit hint, nearly as wide as the map, keeps clear of the corners.
    assert.equal((await dataset(page)).editMode, "edit");
    let hint = await underHint(page);
    assert.equal(hint.covered, 0, `corners under the hint at ${hint.place}`);
    await cornerToHint(page, 0);
    hint = await underHint(page);
    assert.equal(hint.covered, 0, `corners under the hint at ${hint.place}`);
    await page.screenshot({ path: join(SHOTS, "first-hour-phone.png") });
  });
});

/** A Polygon of `n` vertices (n a multiple of 1,000: a ring of 1,000 round a circle, gone round
 * n / 1,000 times), written with `digits` decimals and `space` after each comma: about
 * (2 digits + 9 + space) bytes a vertex. */
function polygonText(n, digits, space) {
  const round = [];
  for (let i = 0; i < 1000; i++) {
    const a = (i / 1000) * 2 * Math.PI;
    round.push(`[${(24 + 0.01 * Math.cos(a)).toFixed(digits)},${space}${(60 + 0.005 * Math.sin(a)).toFixed(digits)}]`);
  }
  const rounds = new Array(n / 1000).fill(round.join(`,${space}`)).join(`,${space}`);
  return `{"type":"Polygon","coordinates":[[${rounds},${space}${round[0]}]]}`;
}

test("first hour: a 1.2 M-vertex file is refused within 3 s without holding up the page; one file's error is not left beside the next", { timeout: TIMEOUT }, async () => {
  const dir = join(SHOTS, "..", "first-hour-files");
  mkdirSync(dir, { recursive: true });
  // Over the planner's 32 MB (refused before it is read), and under it but with 1.2 M points
  // (refused once the worker has parsed it).
  const big = join(dir, "big.geojson");
  const dense = join(dir, "dense.geojson");
  writeFileSync(big, polygonText(1_200_000, 9, " "));
  writeFileSync(dense, polygonText(1_200_000, 5, ""));
  const MiB = 1024 * 1024;
  assert.ok(statSync(big).size > 32 * MiB && statSync(big).size < 64 * MiB, `big.geojson is ${statSync(big).size} bytes`);
  assert.ok(statSync(dense).size < 32 * MiB, `dense.geojson is ${statSync(dense).size} bytes`);
  try {
    await withViewer(DESKTOP, async (page, base) => {
      await page.goto(base);
      await ready(page);
      // The page's main thread, watched: long tasks, and the longest gap between frames.
      await page.evaluate(() => {
        window.__long = [];
        new PerformanceObserver((list) => window.__long.push(...list.getEntries().map((e) => e.duration))).observe({ type: "longtask" });
        window.__gap = 0;
        let last = performance.now();
        const tick = (t) => {
          window.__gap = Math.max(window.__gap, t - last);
          last = t;
          requestAnimationFrame(tick);
        };
        requestAnimationFrame(tick);
      });
      const open = async (path) => {
        const [chooser] = await Promise.all([page.waitForEvent("filechooser"), page.click("#open-file")]);
        await chooser.setFiles(path);
      };
      const errorList = () => page.$$eval("#warnings li", (items) => items.map((li) => [li.dataset.code, li.className]));

      // A broken file first: its error is shown, on the map and in the list.
      await open(join(FIELDS, "invalid/self-intersecting-bowtie.geojson"));
      await page.waitForSelector("body[data-plan-state=error]");
      assert.deepEqual(await errorList(), [["self_intersection", "error"]]);

      for (const [path, what] of [[big, "larger than the planner reads"], [dense, "more points than the planner accepts"]]) {
        await page.evaluate(() => {
          window.__long = [];
          window.__gap = 0;
        });
        const t0 = Date.now();
        await open(path);
        await page.waitForSelector("body[data-plan-state=error] #map-message[data-code=input_too_large]", { timeout: 3_000 });
        const ms = Date.now() - t0;
        await page.evaluate(() => new Promise((r) => setTimeout(r, 300))); // tasks still to come
        const { long, gap } = await page.evaluate(() => ({ long: Math.max(0, ...window.__long), gap: window.__gap }));
        console.log(`${path.replace(/.*\//, "")} (${what}): error shown after ${ms} ms; longest task ${long.toFixed(0)} ms, longest frame gap ${gap.toFixed(0)} ms`);
        assert.ok(ms < 3_000, `the error within 3 s (${ms} ms)`);
        assert.ok(long < 200, `the main thread held up for ${long.toFixed(0)} ms`);
        assert.ok(gap < 200, `no frame for ${gap.toFixed(0)} ms`);
        // The error of the file before is gone, from the list and from the map.
        assert.deepEqual(await errorList(), [["input_too_large", "error"]]);
        const left = await page.evaluate(() => ({ highlights: window.furrow.view.highlights.length, marker: window.furrow.view.marker, field: window.furrow.view.field?.boundary ?? null }));
        assert.deepEqual(left, { highlights: 0, marker: null, field: null }, "nothing of the file before on the map");
        assert.match(await page.textContent("#field option:checked"), new RegExp(path.replace(/.*\//, "").replace(".geojson", "")));
      }
      assert.match(await page.textContent("#map-message"), /more than 200000 points/);

      // A good file after them plans, with nothing of their errors left.
      await open(join(FIELDS, "rectangle.geojson"));
      await ready(page);
      assert.deepEqual((await errorList()).filter(([, kind]) => kind === "error"), []);
      assert.ok(await page.isHidden("#map-message"));
    });
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test("first hour: a zipped Shapefile in RD New opens as its parcels where the register has them; its parts chosen together open the same; KML, KMZ and TaskData too; a cut one is refused", { timeout: TIMEOUT }, async () => {
  const fixtures = join(FIELDS, "..", "format-fixtures");
  const register = JSON.parse(readFileSync(join(FIELDS, "real/nl_brp_2023_sample.geojson"), "utf8"));
  const dir = join(SHOTS, "..", "first-hour-shapefile");
  mkdirSync(dir, { recursive: true });
  try {
    // The zip's parts, unpacked by Python's zipfile, and the zip cut short.
    const zip = join(fixtures, "nl_brp_rd_new.zip");
    execFileSync("python3", ["-c", "import sys, zipfile; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])", zip, dir]);
    const bytes = readFileSync(zip);
    const cut = join(dir, "cut.zip");
    writeFileSync(cut, bytes.subarray(0, bytes.length >> 1));
    await withViewer(DESKTOP, async (page, base) => {
      await page.goto(base);
      await ready(page);
      const open = async (paths) => {
        const [chooser] = await Promise.all([page.waitForEvent("filechooser"), page.click("#open-file")]);
        await chooser.setFiles(paths);
      };
      // Opens a file of parcels and waits for its own list (not the one of the file before).
      const openParcels = async (paths) => {
        await page.evaluate(() => (window.__listBefore = window.furrow.parcels.features));
        await open(paths);
        await page.waitForFunction(
          () => document.body.dataset.planState === "pick" && window.furrow.parcels.features !== window.__listBefore,
        );
      };
      const names = () => page.$$eval("#parcels-list button .parcel-name", (n) => n.map((e) => e.textContent));
      const ids = register.features.map((f) => f.properties.id);
      for (const paths of [zip, ["shp", "shx", "dbf", "prj"].map((ext) => join(dir, `nl_brp_rd_new.${ext}`))]) {
        await openParcels(paths);
        assert.deepEqual(await names(), ids, "every parcel, by its id, in the file's order");
      }
      // The first parcel, picked, plans where the register has it (RD New read with its datum
      // shift: without it the parcel would lie about 114 m away).
      await page.click(`#parcels-list button:has-text("${ids[0]}")`);
      await planned(page);
      assert.ok(Number((await dataset(page)).swathCount) > 0, "the parcel is planned");
      const ring = await page.evaluate(() => window.furrow.document.features[0].geometry.coordinates[0]);
      const want = register.features[0].geometry.coordinates[0];
      assert.equal(ring.length, want.length);
      const off = Math.max(...ring.map((p) => Math.min(...want.map((q) => Math.hypot((p[0] - q[0]) * 68_500, (p[1] - q[1]) * 111_200)))));
      assert.ok(off < 0.01, `a corner read ${off} m from the register's`);
      // Google Earth's KML and KMZ (written by GDAL): the Danish register's parcels by their names.
      const danish = JSON.parse(readFileSync(join(FIELDS, "real/dk_marker_2026_sample.geojson"), "utf8"));
      for (const file of ["dk_marker.kml", "dk_marker.kmz"]) {
        await openParcels(join(fixtures, file));
        assert.deepEqual(await names(), danish.features.map((f) => f.properties.id), file);
      }
      // An ISOBUS terminal's TaskData (written by the npm isoxml package): its partfields.
      await openParcels(join(fixtures, "dk_marker_taskdata_v4.zip"));
      assert.deepEqual(await names(), danish.features.map((f) => f.properties.id));
      // A partfield picked plans along its AB line (written along its first edge).
      await page.click(`#parcels-list button:has-text("${danish.features[0].properties.id}")`);
      await planned(page);
      const picked = await page.evaluate(() => ({
        mode: window.furrow.plan.summary.direction.mode,
        line: window.furrow.document.features.find((f) => f.properties.role === "reference_line")?.geometry.coordinates,
      }));
      assert.equal(picked.mode, "reference");
      assert.deepEqual(picked.line, danish.features[0].geometry.coordinates[0].slice(0, 2));
      await page.click("#parcels-back");
      // A download cut short: a typed error, nothing planned.
      await open(cut);
      await page.waitForSelector("body[data-plan-state=error] #map-message[data-code=invalid_file]");
      assert.match(await page.textContent("#map-message"), /damaged or incomplete/);
    });
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test("first hour: a file of parcels: a searchable list of names and areas, tap to plan, back to the list; parcels a few pixels wide; a tap beside one picks it", { timeout: TIMEOUT }, async () => {
  const path = join(FIELDS, "real/dk_marker_2026_sample.geojson");
  const file = JSON.parse(readFileSync(path, "utf8"));
  await withViewer(DESKTOP, async (page, base) => {
    await page.goto(base);
    await ready(page);
    const [chooser] = await Promise.all([page.waitForEvent("filechooser"), page.click("#open-file")]);
    await chooser.setFiles(path);
    await page.waitForSelector("body[data-plan-state=pick]");
    assert.equal((await dataset(page)).editMode, "parcel");
    const items = () =>
      page.$$eval("#parcels-list button", (buttons) =>
        buttons.map((b) => ({ name: b.querySelector(".parcel-name").textContent, m2: Number(b.querySelector(".parcel-area").dataset.m2), area: b.querySelector(".parcel-area").textContent })),
      );

    // The list: every parcel by its id, in the file's order, with its area; the register's own
    // figure (area_ha, computed in its national grid) agrees.
    const list = await items();
    assert.deepEqual(list.map((i) => i.name), file.features.map((f) => f.properties.id));
    file.features.forEach((f, k) => {
      const ha = f.properties.area_ha;
      assert.ok(Math.abs(list[k].m2 / 1e4 - ha) <= 0.01 * ha + 0.002, `${f.properties.id}: ${list[k].m2} m² listed, ${ha} ha in the register`);
    });
    assert.match(list[4].area, /^9\.2\d ha$/);

    // Every parcel drawn at least a few pixels wide, far out as the map is.
    const drawn = await page.evaluate(() => {
      const { parcels, view } = window.furrow;
      const probe = document.createElement("span");
      probe.style.color = "var(--select)";
      document.body.append(probe);
      const [r, g, b] = getComputedStyle(probe).color.match(/\d+/g).map(Number);
      probe.remove();
      const canvas = document.getElementById("map");
      const k = canvas.width / canvas.clientWidth;
      const ctx = canvas.getContext("2d");
      return parcels.parcels.map((p) => {
        const pts = p.world[0].map((w) => view.toScreen(w));
        const x0 = Math.min(...pts.map((q) => q[0])) - 6;
        const y0 = Math.min(...pts.map((q) => q[1])) - 6;
        const x1 = Math.max(...pts.map((q) => q[0])) + 6;
        const y1 = Math.max(...pts.map((q) => q[1])) + 6;
        const data = ctx.getImageData(Math.round(x0 * k), Math.round(y0 * k), Math.round((x1 - x0) * k), Math.round((y1 - y0) * k)).data;
        let n = 0;
        for (let i = 0; i < data.length; i += 4) if (Math.abs(data[i] - r) + Math.abs(data[i + 1] - g) + Math.abs(data[i + 2] - b) < 60) n++;
        return { size: Math.max(x1 - x0, y1 - y0) - 12, px: n / (k * k) };
      });
    });
    assert.ok(drawn.some((d) => d.size < 4), "some parcels are under 4 px across at this zoom");
    const thin = drawn.map((d, k) => [k, d]).filter(([, d]) => d.px < 30);
    assert.deepEqual(thin, [], "parcels drawn with fewer than 30 px of colour");

    // A tap 10 px beside the small parcel with most room around it picks it.
    const target = await page.evaluate(() => {
      const { parcels, view } = window.furrow;
      const spots = parcels.parcels.map((p) => {
        const pts = p.world[0].map((w) => view.toScreen(w));
        return { index: p.index, right: Math.max(...pts.map((q) => q[0])), x: pts.reduce((s, q) => s + q[0], 0) / pts.length, y: pts.reduce((s, q) => s + q[1], 0) / pts.length };
      });
      const room = (s) => Math.min(...spots.filter((o) => o !== s).map((o) => Math.hypot(o.x - s.x, o.y - s.y)));
      return spots.reduce((a, b) => (room(b) > room(a) ? b : a));
    });
    const o = await mapOrigin(page);
    await page.mouse.click(o.x + target.right + 10, o.y + target.y);
    await page.waitForSelector("body[data-plan-state=ready], body[data-plan-state=error]");
    const id = file.features[target.index].properties.id;
    assert.match(await page.textContent("#field option:checked"), new RegExp(id));
    assert.deepEqual(
      await page.evaluate(() => window.furrow.document.features[0].geometry.coordinates[0]),
      file.features[target.index].geometry.coordinates[0],
    );
    assert.match(await page.textContent("#parcels-title"), new RegExp(`${id} \\(parcel ${target.index + 1} of 100\\)`));
    assert.ok(await page.isHidden("#parcels-list"));

    // Back to the list; search by id, and by the crop (any text of the parcel's properties).
    await page.click("#parcels-back");
    await page.waitForSelector("body[data-plan-state=pick]");
    assert.equal((await items()).length, 100);
    assert.equal(await page.textContent("#field option:checked"), "dk_marker_2026_sample (opened file)", "the file is the one shown again");
    await page.fill("#parcels-search", "063");
    assert.deepEqual((await items()).map((i) => i.name), ["dk_marker_2026_sample_063"]);
    const poplars = file.features.filter((f) => Object.values(f.properties).some((v) => typeof v === "string" && /poppel/i.test(v)));
    await page.fill("#parcels-search", "POPPEL");
    assert.deepEqual((await items()).map((i) => i.name), poplars.map((f) => f.properties.id));
    assert.ok(poplars.length >= 2 && poplars.length < 100);
    await page.fill("#parcels-search", "");
    // A tap in the list plans that parcel (the largest, 23 ha).
    const largest = file.features.reduce((a, f) => (f.properties.area_ha > a.properties.area_ha ? f : a));
    await page.click(`#parcels-list button:has-text("${largest.properties.id}")`);
    await planned(page);
    assert.ok(Number((await dataset(page)).swathCount) > 0, "the parcel is planned");
    assert.match(await page.textContent("#status"), new RegExp(largest.properties.id));
    await page.screenshot({ path: join(SHOTS, "first-hour-parcel.png") });
    await page.click("#parcels-back");
    await page.waitForSelector("body[data-plan-state=pick]");
    await page.screenshot({ path: join(SHOTS, "first-hour-parcels.png") });
    // Another field: the list goes.
    await page.selectOption("#field", "rectangle");
    await planned(page);
    assert.ok(await page.isHidden("#parcels"));
  });
});
