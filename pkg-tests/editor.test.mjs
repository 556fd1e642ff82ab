// The viewer's editing in headless Chromium (playwright-core, Debian's chromium): a field drawn
// with the mouse and by touch, an obstacle and a prohibited region added, vertices dragged,
// inserted and deleted, undo and redo, the entrance; files imported and exported again equal; a
// vertex dragged on the large field with the frame times measured and stale plans never drawn;
// the machine driven along the path; touch targets; screenshots of corpus fields day and night.
//
//   bash scripts/build.sh   (once), then   node --test pkg-tests/editor.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { ISOXMLManager } from "isoxml";
import { kml as kmlToGeoJson } from "@tmcw/togeojson";
import { DOMParser } from "@xmldom/xmldom";
import { mkdirSync, readFileSync } from "node:fs";
import { join } from "node:path";
import {
  FIELDS,
  SHOTS,
  TIMEOUT,
  countColour,
  dataset,
  fieldPasses,
  mapOrigin,
  planKey,
  planned,
  ready,
  setInput,
  vertexAt,
  withViewer,
} from "./viewer-support.mjs";

const DESKTOP = { viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 };

/** The document's feature `feature`, first ring, without the closing point. */
const ringOf = (page, feature) =>
  page.evaluate((feature) => {
    const c = window.furrow.document.features[feature].geometry.coordinates[0];
    return c.slice(0, -1);
  }, feature);

const docOf = (page) => page.evaluate(() => window.furrow.document);

test("editor: draw a field with the mouse, add an obstacle and a region, edit, undo, keep it", { timeout: TIMEOUT }, async () => {
  mkdirSync(SHOTS, { recursive: true });
  await withViewer(DESKTOP, async (page, base) => {
    await page.goto(base);
    await ready(page);
    const o = await mapOrigin(page);

    // A new field: tap four corners and the first again.
    await page.click("#new-field");
    assert.equal((await dataset(page)).editMode, "boundary");
    const cx = o.x + o.width / 2;
    const cy = o.y + o.height / 2;
    const corners = [
      [cx - 220, cy - 150],
      [cx + 220, cy - 150],
      [cx + 220, cy + 150],
      [cx - 220, cy + 150],
    ];
    for (const [x, y] of corners) await page.mouse.click(x, y);
    assert.equal(await page.isVisible("#finish"), true, "Finish shows while drawing");
    await page.mouse.click(corners[0][0], corners[0][1]); // closes it
    await planned(page);
    let doc = await docOf(page);
    assert.equal(doc.features.length, 1);
    assert.equal(doc.features[0].properties.role, "boundary");
    assert.equal(doc.features[0].geometry.coordinates[0].length, 5, "four corners, closed");
    const swaths = Number((await dataset(page)).swathCount);
    assert.ok(swaths > 5, `${swaths} swaths in the drawn field`);
    for (const kind of ["--swath", "--headland", "--turn", "--boundary"]) {
      const n = await countColour(page, kind);
      assert.ok(n > 100, `only ${n} pixels of ${kind} on the canvas`);
    }
    assert.equal((await dataset(page)).editMode, "edit", "drawing ends in edit mode");

    // An obstacle in the middle: three taps and Finish.
    await page.click('#edit-bar [data-mode="obstacle"]');
    for (const [dx, dy] of [
      [-40, -30],
      [40, -30],
      [0, 40],
    ]) {
      await page.mouse.click(cx + dx, cy + dy);
    }
    await page.click("#finish");
    await planned(page);
    doc = await docOf(page);
    assert.equal(doc.features[1].properties.role, "obstacle");
    const planObstacles = await page.evaluate(
      () => window.furrow.plan.features.filter((f) => f.properties.kind === "obstacle").length,
    );
    assert.equal(planObstacles, 1, "the plan has the obstacle");
    const aroundObstacle = await page.evaluate(
      () => window.furrow.plan.features.filter((f) => f.properties.kind === "headland" && f.properties.around !== "field").length,
    );
    assert.ok(aroundObstacle > 0, "the obstacle gets headland passes");
    await page.screenshot({ path: join(SHOTS, "editor-drawn.png") });

    // Headland passes change the plan of the drawn field.
    const before = await planKey(page);
    await setInput(page, "headlandPasses", 3);
    await planned(page);
    assert.equal(await fieldPasses(page), 3);
    assert.notEqual(await planKey(page), before);

    // Drag a corner outwards: the plan follows; undo puts it back, redo again.
    await page.click('#edit-bar [data-mode="edit"]');
    const ring0 = await ringOf(page, 0);
    const v = await vertexAt(page, 0, 2);
    await page.mouse.move(v.x, v.y);
    await page.mouse.down();
    await page.mouse.move(v.x + 30, v.y + 20, { steps: 5 });
    await page.mouse.move(v.x + 60, v.y + 40, { steps: 5 });
    await page.mouse.up();
    await planned(page);
    const ring1 = await ringOf(page, 0);
    assert.notDeepEqual(ring1[2], ring0[2], "the corner moved");
    assert.deepEqual(ring1[0], ring0[0], "the other corners stayed");
    const dragged = await page.evaluate(() => window.furrow.plan.summary.field_area_m2);
    await page.click("#undo");
    await planned(page);
    assert.deepEqual(await ringOf(page, 0), ring0, "undo puts the corner back");
    const undone = await page.evaluate(() => window.furrow.plan.summary.field_area_m2);
    assert.ok(dragged > undone * 1.02, `area ${dragged} after the drag, ${undone} after undo`);
    await page.click("#redo");
    await planned(page);
    assert.deepEqual(await ringOf(page, 0), ring1, "redo moves it again");

    // Tap the mark in the middle of edge 0: a vertex there; select it and delete it.
    const a = await vertexAt(page, 0, 0);
    const b = await vertexAt(page, 0, 1);
    await page.mouse.click((a.x + b.x) / 2, (a.y + b.y) / 2);
    await planned(page);
    assert.equal((await ringOf(page, 0)).length, 5, "a vertex inserted");
    const inserted = await vertexAt(page, 0, 1);
    await page.mouse.click(inserted.x, inserted.y);
    await page.click("#delete");
    await planned(page);
    assert.equal((await ringOf(page, 0)).length, 4, "the vertex deleted");

    // A prohibited region: drawn, then its forbidden bearings set by numbers.
    await page.click('#edit-bar [data-mode="prohibited"]');
    for (const [dx, dy] of [
      [60, -120],
      [200, -120],
      [200, 120],
      [60, 120],
    ]) {
      await page.mouse.click(cx + dx, cy + dy);
    }
    await page.click("#finish");
    await planned(page);
    assert.equal(await page.isVisible("#region-panel"), true, "the region's panel shows");
    assert.ok(await page.isVisible("#region-dial svg"), "with a dial");
    await page.fill("#region-from", "80");
    await page.fill("#region-to", "100");
    await planned(page);
    doc = await docOf(page);
    const region = doc.features.find((f) => f.properties.role === "prohibited");
    assert.deepEqual(region.properties.forbidden_bearings_deg, [[80, 100]]);
    // The dial's handle moves the range too (keyboard on its slider).
    await page.focus('#region-dial [aria-label="To bearing"]');
    await page.keyboard.press("Shift+ArrowRight");
    await planned(page);
    doc = await docOf(page);
    assert.deepEqual(doc.features.find((f) => f.properties.role === "prohibited").properties.forbidden_bearings_deg, [[80, 110]]);
    assert.equal(await page.inputValue("#region-to"), "110");

    // The entrance: tap a point on the field's edge; the plan starts there.
    await page.click('#edit-bar [data-mode="entrance"]');
    const e0 = await vertexAt(page, 0, 0);
    const e1 = await vertexAt(page, 0, 3);
    await page.mouse.click(e0.x, (e0.y + e1.y) / 2);
    await planned(page);
    const entrance = await page.evaluate(() => window.furrow.options.entrance);
    assert.ok(Array.isArray(entrance) && entrance.length === 2, "the entrance is an option");
    const fromEntrance = await page.evaluate(
      () => window.furrow.plan.features.filter((f) => f.properties.kind === "connection" && f.properties.sequence === 0).length,
    );
    assert.equal(fromEntrance, 1, "the route starts with a connection from the entrance");
    await page.screenshot({ path: join(SHOTS, "editor-edited.png") });

    // A reload brings the field back as drawn, with the settings.
    const kept = await docOf(page);
    await page.reload();
    await planned(page);
    assert.deepEqual(await docOf(page), kept, "the edited field is kept in this browser");
    assert.equal(await page.inputValue("#headlandPasses"), "3");
    assert.ok(Number((await dataset(page)).swathCount) > 0);
  });
});

test("editor: import a corpus file and export it again equal; export the plan", { timeout: TIMEOUT }, async () => {
  await withViewer({ ...DESKTOP, acceptDownloads: true }, async (page, base) => {
    await page.goto(base);
    await ready(page);
    for (const name of ["obstacle-types", "underdrain", "real/dk_marker_2026_sample"]) {
      const path = join(FIELDS, `${name}.geojson`);
      const [chooser] = await Promise.all([page.waitForEvent("filechooser"), page.click("#open-file")]);
      await chooser.setFiles(path);
      // (A file of many parcels waits for one to be picked.)
      await page.waitForSelector("body[data-plan-state=ready], body[data-plan-state=error], body[data-plan-state=pick]");
      const [download] = await Promise.all([page.waitForEvent("download"), page.click("#export-field")]);
      const text = readFileSync(await download.path(), "utf8");
      assert.deepEqual(JSON.parse(text), JSON.parse(readFileSync(path, "utf8")), `${name}: exported equal to the file`);
      assert.match(download.suggestedFilename(), /\.geojson$/);
    }
    // The plan: its features and figures as GeoJSON.
    const [chooser] = await Promise.all([page.waitForEvent("filechooser"), page.click("#open-file")]);
    await chooser.setFiles(join(FIELDS, "h-shape.geojson"));
    await planned(page);
    const [download] = await Promise.all([page.waitForEvent("download"), page.click("#export-plan")]);
    const plan = JSON.parse(readFileSync(await download.path(), "utf8"));
    assert.equal(plan.type, "FeatureCollection");
    assert.equal(plan.summary.swath_count, Number((await dataset(page)).swathCount));
    assert.equal(
      plan.features.filter((f) => f.properties.kind === "swath").length,
      plan.summary.swath_count,
      "every swath is in the file",
    );
    assert.equal(plan.samples, undefined, "no typed arrays in the GeoJSON");
    // The plan for an ISOBUS terminal: ISOXML TaskData, zipped, read back by the npm isoxml
    // package: the boundary, and an AB line per block with swaths.
    const [taskdata] = await Promise.all([page.waitForEvent("download"), page.click("#export-isoxml")]);
    assert.match(taskdata.suggestedFilename(), /-TASKDATA\.zip$/);
    const manager = new ISOXMLManager();
    await manager.parseISOXMLFile(new Uint8Array(readFileSync(await taskdata.path())), "application/zip");
    assert.deepEqual(manager.getWarnings(), []);
    const pfd = manager.rootElement.attributes.Partfield[0].attributes;
    assert.equal(pfd.PolygonnonTreatmentZoneonly.filter((p) => p.attributes.PolygonType === "1").length, 1);
    const blocks = new Set(plan.features.filter((f) => f.properties.kind === "swath").map((f) => f.properties.block));
    assert.equal(pfd.GuidanceGroup.filter((g) => g.attributes.GuidanceGroupDesignator.startsWith("Block ")).length, blocks.size);
    // And for Google Earth: KML read back by @tmcw/togeojson, a placemark per swath.
    const [kmlFile] = await Promise.all([page.waitForEvent("download"), page.click("#export-kml")]);
    assert.match(kmlFile.suggestedFilename(), /-plan\.kml$/);
    const kml = kmlToGeoJson(new DOMParser().parseFromString(readFileSync(await kmlFile.path(), "utf8"), "text/xml"));
    assert.equal(kml.features.filter((f) => /^Swath \d+$/.test(f.properties.name)).length, plan.summary.swath_count);
  });
});

test("editor: dragging a vertex of the large field keeps the page responsive; stale plans never drawn", { timeout: TIMEOUT }, async () => {
  await withViewer(DESKTOP, async (page, base) => {
    await page.goto(`${base}#large-250ha-10-obstacles`);
    await planned(page);
    await page.click('#edit-bar [data-mode="edit"]');
    // Record every plan drawn (its edit number) and the frame times while dragging.
    await page.evaluate(() => {
      window.drawnSeqs = [];
      window.previews = 0;
      new MutationObserver(() => {
        window.drawnSeqs.push(Number(document.body.dataset.planSeq));
        if (document.body.dataset.planPreview === "true") window.previews++;
      }).observe(document.body, {
        attributeFilter: ["data-plan-seq"],
      });
      window.frames = [];
      let last = performance.now();
      const tick = (now) => {
        window.frames.push(now - last);
        last = now;
        if (window.recording) requestAnimationFrame(tick);
      };
      window.recording = true;
      requestAnimationFrame(tick);
    });
    const v = await vertexAt(page, 0, 5);
    await page.mouse.move(v.x, v.y);
    await page.mouse.down();
    for (let k = 1; k <= 40; k++) {
      await page.mouse.move(v.x + k * 3, v.y + k * 1.5);
      await page.waitForTimeout(16);
    }
    await page.mouse.up();
    await planned(page);
    const result = await page.evaluate(() => {
      window.recording = false;
      return { seqs: window.drawnSeqs, previews: window.previews, frames: window.frames.slice(1), replans: window.furrow.replans };
    });
    const frames = [...result.frames].sort((a, b) => a - b);
    const median = frames[Math.floor(frames.length / 2)];
    console.log(
      `large field vertex drag: ${result.replans.made} re-plans asked, ${result.seqs.length} plans drawn ` +
        `(${result.previews} previews in one direction); ` +
        `${frames.length} frames, median ${median.toFixed(1)} ms, p95 ${frames[Math.floor(frames.length * 0.95)].toFixed(1)} ms, ` +
        `max ${frames[frames.length - 1].toFixed(1)} ms`,
    );
    assert.ok(result.replans.made >= 30, `every step of the drag asks for a plan (${result.replans.made})`);
    for (let i = 1; i < result.seqs.length; i++) {
      assert.ok(result.seqs[i] > result.seqs[i - 1], `plan ${result.seqs[i]} drawn after ${result.seqs[i - 1]}`);
    }
    assert.equal(result.seqs[result.seqs.length - 1], result.replans.made, "the last plan drawn is of the last edit");
    assert.ok(frames.length > 20, "the page kept drawing frames during the drag");
    assert.ok(result.seqs.length >= 3, `plans drawn while dragging (${result.seqs.length})`);
    assert.equal((await dataset(page)).planPreview, "false", "the release plans in full");
    // The plan shown is that of the final shape.
    const shown = await planKey(page);
    await page.evaluate(() => window.furrow.replan());
    await planned(page);
    assert.equal(await planKey(page), shown, "the plan drawn is that of the final shape");
  });
});

test("editor: by touch on a phone; touch targets at least 44 px", { timeout: TIMEOUT }, async () => {
  mkdirSync(SHOTS, { recursive: true });
  await withViewer({ viewport: { width: 390, height: 844 }, deviceScaleFactor: 2, hasTouch: true, isMobile: true }, async (page, base) => {
    await page.goto(base);
    await ready(page);
    // Every control the user touches is at least 44 px tall (buttons 44 px wide too).
    const small = await page.evaluate(() =>
      [...document.querySelectorAll("button, select, input:not([type=file]), summary")]
        .filter((el) => el.offsetParent !== null && !el.closest("[hidden]"))
        .map((el) => ({ id: el.id || el.dataset.mode || el.textContent.trim().slice(0, 20), r: el.getBoundingClientRect(), tag: el.tagName }))
        .filter(({ r, tag }) => r.height < 44 || (tag === "BUTTON" && r.width < 44))
        .map(({ id, r }) => `${id} ${r.width.toFixed(0)}x${r.height.toFixed(0)}`),
    );
    assert.deepEqual(small, [], "controls smaller than 44 px");
    await page.click("#new-field");
    await page.locator("#map").scrollIntoViewIfNeeded();
    const o = await mapOrigin(page);
    const cx = o.x + o.width / 2;
    const cy = o.y + o.height / 2 - 30;
    const corners = [
      [cx - 130, cy - 100],
      [cx + 130, cy - 110],
      [cx + 120, cy + 100],
      [cx - 120, cy + 90],
    ];
    for (const [x, y] of corners) await page.touchscreen.tap(x, y);
    await page.touchscreen.tap(corners[0][0], corners[0][1]);
    await planned(page);
    const doc = await docOf(page);
    assert.equal(doc.features[0].geometry.coordinates[0].length, 5, "a field drawn by four taps");
    assert.ok(Number((await dataset(page)).swathCount) > 0);
    await page.screenshot({ path: join(SHOTS, "editor-phone.png") });
  });
});

test("editor: drive the machine along the path", { timeout: TIMEOUT }, async () => {
  await withViewer(DESKTOP, async (page, base) => {
    await page.goto(`${base}#rectangle`);
    await planned(page);
    const before = await countColour(page, "--machine", 30);
    await page.click("#display-options summary");
    await page.selectOption("#drive-speed", "1000");
    await page.click("#drive");
    assert.equal((await dataset(page)).drive, "running");
    await page.waitForFunction(() => Number(document.body.dataset.driveS) > 60, null, { timeout: 10_000 });
    const during = await countColour(page, "--machine", 30);
    assert.ok(during > before + 50, `the machine is drawn (${before} -> ${during} px of its colour)`);
    await page.click("#drive");
    const stopped = await dataset(page);
    assert.equal(stopped.drive, "paused");
    const t = Number(stopped.driveS);
    await page.waitForTimeout(300);
    assert.equal(Number((await dataset(page)).driveS), t, "stopped means stopped");
    // The machine's pose follows the samples.
    const pose = await page.evaluate(() => window.furrow.driver.pose());
    assert.ok(Number.isFinite(pose.x) && Number.isFinite(pose.headingDeg));
    assert.ok(pose.i > 10, `${pose.i} samples driven`);
  });
});

test("editor: screenshots of corpus fields, day and night", { timeout: TIMEOUT * 2 }, async () => {
  const dir = join(SHOTS, "fields");
  mkdirSync(dir, { recursive: true });
  await withViewer(DESKTOP, async (page, base) => {
    await page.goto(base);
    await ready(page);
    for (const name of ["obstacle-types", "h-shape", "underdrain", "large-250ha-10-obstacles", "c-shape-escarpment"]) {
      await page.selectOption("#field", name);
      await planned(page);
      for (const theme of ["day", "night"]) {
        const night = await page.evaluate(() => document.documentElement.dataset.theme === "night");
        if (night !== (theme === "night")) await page.click("#theme");
        await page.screenshot({ path: join(dir, `${name}-${theme}.png`) });
      }
    }
  });
});

/** The bearings of the field's swaths in the plan shown (not those that fill what they leave, at
 * their own bearings), folded into [0, 180). */
const swathBearings = (page) =>
  page.evaluate(() =>
    window.furrow.plan.features.filter((f) => f.properties.kind === "swath" && !f.properties.fill).map((f) => ((f.properties.bearing_deg % 180) + 180) % 180),
  );

/** Compass bearing from lon/lat a to b, folded into [0, 180) (local flat approximation). */
function bearingOf(a, b) {
  const k = Math.cos(((a[1] + b[1]) / 2) * (Math.PI / 180));
  const deg = (Math.atan2((b[0] - a[0]) * k, b[1] - a[1]) * 180) / Math.PI;
  return ((deg % 180) + 180) % 180;
}

const foldedGap = (a, b) => {
  const d = Math.abs(a - b) % 180;
  return Math.min(d, 180 - d);
};

test("editor: direction along an AB line or a tapped edge; forbidden bearings; curvature rate", { timeout: TIMEOUT }, async () => {
  await withViewer(DESKTOP, async (page, base) => {
    await page.goto(`${base}#skew-quad`);
    await planned(page);
    await page.click("#more-options summary").catch(() => {});
    if (!(await page.isVisible("#direction"))) await page.click("#more-options summary");
    const o = await mapOrigin(page);
    const cx = o.x + o.width / 2;
    const cy = o.y + o.height / 2;

    // AB line: choosing it starts the tool; tap A and B.
    await page.selectOption("#direction", "line");
    assert.equal((await dataset(page)).editMode, "abline");
    await page.mouse.click(cx - 150, cy + 40);
    await page.mouse.click(cx + 150, cy - 60);
    await planned(page);
    const line = await page.evaluate(() => window.furrow.options.referenceLine);
    assert.ok(Array.isArray(line) && line.length === 2, "the AB line is an option");
    const want = bearingOf(line[0], line[1]);
    const along = await swathBearings(page);
    assert.ok(along.length > 0 && along.every((b) => foldedGap(b, want) < 0.5), `swaths along the AB line (${want.toFixed(1)}°): ${along.slice(0, 3)}`);
    assert.equal(await page.evaluate(() => window.furrow.plan.summary.direction.mode), "reference");

    // An edge: choose the mode, tap edge 1 of the boundary.
    await page.selectOption("#direction", "edge");
    assert.equal((await dataset(page)).editMode, "edge");
    const a = await vertexAt(page, 0, 1);
    const b = await vertexAt(page, 0, 2);
    await page.mouse.click((a.x * 2 + b.x) / 3, (a.y * 2 + b.y) / 3);
    await planned(page);
    assert.equal(await page.inputValue("#referenceEdge"), "1");
    const ring = await ringOf(page, 0);
    const edgeBearing = bearingOf(ring[1], ring[2]);
    const alongEdge = await swathBearings(page);
    assert.ok(alongEdge.every((x) => foldedGap(x, edgeBearing) < 0.5), `swaths along edge 1 (${edgeBearing.toFixed(1)}°)`);

    // Back to the search, with the best direction's neighbourhood forbidden.
    await page.selectOption("#direction", "search");
    await planned(page);
    const best = (await swathBearings(page))[0];
    const from = Math.round(best - 20);
    await setInput(page, "forbiddenBearings", `${from}-${from + 40}`);
    await planned(page);
    const allowed = (await swathBearings(page))[0];
    assert.ok(foldedGap(allowed, best) >= 19.5, `with ${from}-${from + 40} forbidden the swaths run at ${allowed}, not ${best}`);
    await setInput(page, "forbiddenBearings", "north");
    await page.waitForSelector("body[data-plan-state=error]");
    assert.equal(await page.getAttribute("#forbiddenBearings", "aria-invalid"), "true");
    await setInput(page, "forbiddenBearings", "");
    await planned(page);

    // A curvature rate: continuous-curvature turns.
    await setInput(page, "curvatureRate", "0.1");
    await planned(page);
    const forms = Object.keys(await page.evaluate(() => window.furrow.plan.summary.turn_forms));
    assert.ok(forms.length > 0 && forms.every((f) => f.startsWith("cc-")), `turn forms ${forms}`);

    // Settings persist: a reload of the same field keeps the curvature rate and the direction mode.
    await page.reload();
    await planned(page);
    assert.equal(await page.inputValue("#curvatureRate"), "0.1");
  });
});

test("editor: a file of many parcels: each shown, the one tapped planned", { timeout: TIMEOUT }, async () => {
  await withViewer(DESKTOP, async (page, base) => {
    await page.goto(base);
    await ready(page);
    const path = join(FIELDS, "real/dk_marker_2026_sample.geojson");
    const [chooser] = await Promise.all([page.waitForEvent("filechooser"), page.click("#open-file")]);
    await chooser.setFiles(path);
    await page.waitForSelector("body[data-plan-state=pick]");
    assert.equal((await dataset(page)).editMode, "parcel");
    assert.match(await page.textContent("#status"), /100 parcels/);
    // Tap the middle of the largest parcel.
    const target = await page.evaluate(() => {
      const { parcels, view } = window.furrow;
      const rings = parcels.parcels.map((p) => ({ feature: p.index, world: p.world[0] }));
      const area = (w) => Math.abs(w.reduce((s, p, i) => s + p[0] * w[(i + 1) % w.length][1] - w[(i + 1) % w.length][0] * p[1], 0)) / 2;
      const big = rings.reduce((a, b) => (area(b.world) > area(a.world) ? b : a));
      const xs = big.world.map((p) => p[0]);
      const ys = big.world.map((p) => p[1]);
      // A point inside: the middle of the widest horizontal chord through the box's middle.
      const y = (Math.min(...ys) + Math.max(...ys)) / 2;
      const cuts = [];
      big.world.forEach((p, i) => {
        const q = big.world[(i + 1) % big.world.length];
        if ((p[1] > y) !== (q[1] > y)) cuts.push(p[0] + ((y - p[1]) * (q[0] - p[0])) / (q[1] - p[1]));
      });
      cuts.sort((a, b) => a - b);
      let best = [cuts[0], cuts[1]];
      for (let i = 0; i + 1 < cuts.length; i += 2) if (cuts[i + 1] - cuts[i] > best[1] - best[0]) best = [cuts[i], cuts[i + 1]];
      void xs;
      return { feature: big.feature, screen: view.toScreen([(best[0] + best[1]) / 2, y]) };
    });
    const o = await mapOrigin(page);
    await page.mouse.click(o.x + target.screen[0], o.y + target.screen[1]);
    await planned(page);
    const doc = await docOf(page);
    const file = JSON.parse(readFileSync(path, "utf8"));
    assert.equal(doc.features[0].properties.role, "boundary");
    assert.deepEqual(doc.features[0].geometry.coordinates[0], file.features[target.feature].geometry.coordinates[0]);
    assert.ok(Number((await dataset(page)).swathCount) > 0, "the parcel is planned");
    assert.match(await page.inputValue("#field").then(() => page.textContent("#field option:checked")), /dk_marker_2026_sample_/);
  });
});

test("editor: no background map unless one is set; then its tiles are drawn under the field", { timeout: TIMEOUT }, async () => {
  await withViewer(DESKTOP, async (page, base) => {
    const png = readFileSync(join(FIELDS, "..", "..", "docs", "decomposition", "h-shape.png"));
    const tiles = [];
    // (On the context: the service worker's requests too.)
    await page.context().route(`${base}tiles/**`, (route) => {
      tiles.push(route.request().url());
      return route.fulfill({ status: 200, contentType: "image/png", body: png });
    });
    await page.goto(base);
    await ready(page);
    assert.equal(tiles.length, 0, "nothing fetched by default");
    assert.equal(await page.evaluate(() => window.furrow.view.drawn.tiles), 0);
    await page.click("#display-options summary");
    await page.fill("#tile-url", `${base}tiles/{z}/{x}/{y}.png`);
    await page.waitForFunction(() => window.furrow.view.drawn.tiles > 0, null, { timeout: 10_000 });
    assert.ok(tiles.length > 0 && tiles.every((u) => /tiles\/\d+\/\d+\/\d+\.png$/.test(u)), `tiles asked: ${tiles.slice(0, 2)}`);
    await page.fill("#tile-url", "");
    await page.waitForFunction(() => window.furrow.view.drawn.tiles === 0);
  });
});

test("editor: the way out along the tracks, from a tapped place and heading to a tapped exit", { timeout: TIMEOUT }, async () => {
  await withViewer(DESKTOP, async (page, base) => {
    await page.goto(`${base}#obstacles-2`);
    await planned(page);
    const before = await countColour(page, "--way", 30);
    await page.click('#edit-bar [data-mode="way"]');
    assert.match(await page.textContent("#edit-hint"), /where the machine is/);
    const o = await mapOrigin(page);
    // The middle of a swath, facing its end; the exit near the field's south-west corner.
    const [at, ahead, exit] = await page.evaluate(() => {
      const sw = window.furrow.plan.features.filter((f) => f.properties.kind === "swath")[10];
      const [a, b] = [sw.geometry.coordinates[0], sw.geometry.coordinates.at(-1)];
      const { projection: p, view: v } = window.furrow;
      const corner = window.furrow.document.features[0].geometry.coordinates[0][0];
      return [v.toScreen(p.forward([(a[0] + b[0]) / 2, (a[1] + b[1]) / 2])), v.toScreen(p.forward(b)), v.toScreen(p.forward(corner))];
    });
    await page.mouse.click(o.x + at[0], o.y + at[1]);
    assert.match(await page.textContent("#edit-hint"), /faces/);
    await page.mouse.click(o.x + ahead[0], o.y + ahead[1]);
    assert.equal((await dataset(page)).way, "exit");
    await page.mouse.click(o.x + exit[0], o.y + exit[1]);
    await page.waitForSelector("body[data-way=ready]");
    const length = Number((await dataset(page)).wayLength);
    assert.ok(length > 100, `way out ${length} m`);
    assert.match(await page.textContent("#edit-hint"), /Way out: [\d,.]+ m/);
    const drawn = await countColour(page, "--way", 30);
    assert.ok(drawn > before + 300, `the way is drawn (${before} -> ${drawn} px)`);
    // The same answer as the package gives for the plan shown.
    const path = await page.evaluate(() => window.furrow.way.path);
    assert.equal(path.properties.turning, "heading");
    assert.ok(path.geometry.coordinates.length >= 2);
    // Turning on the spot is never longer; the way follows a change of the option.
    await page.click("#display-options summary");
    await page.selectOption("#way-turning", "on-the-spot");
    await page.waitForFunction(() => window.furrow.way.path?.properties.turning === "on-the-spot");
    assert.ok(Number((await dataset(page)).wayLength) <= length + 1e-6);
    await page.screenshot({ path: join(SHOTS, "editor-way-out.png") });
  });
});
