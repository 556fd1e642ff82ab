// Smoke test of the viewer (www/) in headless Chromium: it loads the package, plans the default
// field, draws it, re-plans on input, switches fields, survives planner errors, pans and zooms,
// and lays out on a phone; it opens field files (the corpus's invalid inputs among them) and shows
// the planner's errors and warnings in words beside the feature they concern; it labels obstacles
// with their classes and plans a headland only where needed. Screenshots go to
// target/screenshots/.
//
//   bash scripts/build.sh            (once: the wasm package and target/site)
//   node scripts/site.mjs            (after editing www/ only)
//   node --test pkg-tests/
//
// Uses playwright-core with Debian's chromium (never downloads a browser); set CHROMIUM to use
// another binary.
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync, readdirSync, readFileSync } from "node:fs";
import { join } from "node:path";
import { startServer } from "../scripts/serve.mjs";
import {
  FIELDS,
  INVALID,
  SHOTS,
  TIMEOUT,
  countColour,
  dataset,
  fieldPasses,
  planKey,
  planned,
  ready,
  reportCspViolations,
  setInput,
  withViewer,
} from "./viewer-support.mjs";
import { launchChromium, SITE } from "./support.mjs";

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
    // (headland_pass_count counts the passes around obstacles too: look at the field's.)
    const shown = await fieldPasses(page);
    assert.equal(shown, passes + 2);
    assert.notEqual(await planKey(page), before, "the plan did not change with the headland passes");

    // A fixed bearing re-plans along it; empty goes back to automatic.
    await setInput(page, "bearing", 17);
    await ready(page);
    assert.equal(await page.evaluate(() => Math.round(window.furrow.plan.summary.bearing_deg)), 17);
    await setInput(page, "bearing", "");
    await ready(page);
    assert.match(await page.textContent("#summary"), /auto/);

    // More headland passes than the field holds: planned with as many as leave it swaths, and
    // the warning says so.
    await setInput(page, "headlandPasses", 50);
    await ready(page);
    const reduced = await page.evaluate(() => window.furrow.plan.warnings.map((w) => w.code));
    assert.ok(reduced.includes("headland_passes_reduced"), `warnings: ${reduced}`);
    assert.ok(Number((await dataset(page)).swathCount) > 0);

    // Left empty, the passes are "auto": as deep as the loop a forward-only machine drives
    // between neighbouring swaths, by its three circles of the turning radius (6 m swaths,
    // 8 m radius: 8 + √(256 - 121) = 19.6 m, four passes), and the summary says so.
    const machine = {
      width: await page.inputValue("#width"),
      turnRadius: await page.inputValue("#turnRadius"),
      reverse: await page.inputValue("#reverse"),
    };
    const more = page.locator("#more-options");
    if ((await more.getAttribute("open")) === null) await more.locator("summary").click();
    await setInput(page, "width", 6);
    await setInput(page, "turnRadius", 8);
    await page.selectOption("#reverse", "false");
    await setInput(page, "headlandPasses", "");
    await planned(page);
    const loopDepth = 8 + Math.sqrt(4 * 8 * 8 - (8 + 6 / 2) ** 2);
    assert.equal(await page.evaluate(() => window.furrow.plan.summary.headland_passes), Math.ceil(loopDepth / 6));
    assert.equal(await fieldPasses(page), 4);
    assert.match(await page.textContent("#summary"), /Headland passes\s*4 \(auto\)/);
    // Every turn between the field's swaths stays in the field. A turn between two pieces of
    // the fill, in a corner the passes round off, may not (a loop between lines 4 m apart,
    // 1.3 m over the east side here): it is warned of.
    const outside = await page.evaluate(() => {
      const f = window.furrow.plan.features;
      const fill = (x) => x?.properties.fill === true;
      const turns = f.filter((x) => x.properties.kind === "turn" && x.properties.inside === false);
      return {
        field: turns.filter((x) => !fill(f[f.indexOf(x) - 1]) && !fill(f[f.indexOf(x) + 1])).length,
        all: turns.length,
        warned: window.furrow.plan.warnings.some((w) => w.code === "turn_leaves_field"),
      };
    });
    assert.equal(outside.field, 0);
    assert.ok(outside.all === 0 || outside.warned, JSON.stringify(outside));
    // Reversing, its cheapest turn stays within the radius: fewer passes.
    await page.selectOption("#reverse", "true");
    await planned(page);
    assert.ok((await page.evaluate(() => window.furrow.plan.summary.headland_passes)) < 4);
    await setInput(page, "width", machine.width);
    await setInput(page, "turnRadius", machine.turnRadius);
    await page.selectOption("#reverse", machine.reverse);
    await setInput(page, "headlandPasses", passes);
    await ready(page);

    // A planner error is shown in words, the page keeps working, and a good value recovers.
    await setInput(page, "turnRadius", 500);
    await page.waitForSelector("body[data-plan-state=error]", { timeout: 10_000 });
    const message = await page.textContent("#map-message");
    assert.match(message, /turnRadius|radius/i, `error message: ${message}`);
    assert.ok(await page.isVisible("#map-message"), "the error is visible on the page");
    assert.equal(await page.getAttribute("#turnRadius", "aria-invalid"), "true");
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
        .filter((el) => el.checkVisibility())
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
    assert.ok(layout.map.top >= 0 && layout.map.bottom <= 844, "the map first, whole on the first screen");
    assert.ok(layout.controls.top >= layout.map.bottom - 1, "controls below the map");
    assert.ok(layout.info.top >= layout.controls.bottom - 1, "figures below the controls");
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

    // An error's callout stays inside the map on a phone, its words wrapped, no sideways scrolling.
    const bowtie = readFileSync(join(INVALID, "self-intersecting-bowtie.geojson"), "utf8");
    await page.evaluate((t) => window.furrow.loadField(t, "bowtie"), bowtie);
    await page.waitForSelector("body[data-plan-state=error]");
    const map = await page.locator(".map").boundingBox();
    const callout = await page.locator("#map-message").boundingBox();
    assert.ok(inside(callout, map), `callout ${JSON.stringify(callout)} inside the map ${JSON.stringify(map)}`);
    assert.equal(await page.evaluate(() => document.documentElement.scrollWidth), 390, "no sideways scrolling");
    const toggle = page.locator("#map-message .callout-toggle");
    assert.ok((await toggle.boundingBox()).height >= 44, "the Hide button is a touch target");
    await toggle.tap();
    assert.ok(await page.isHidden("#map-message .callout-text"), "Hide folds the callout");
    await toggle.tap();
    assert.ok(await page.isVisible("#map-message .callout-text"), "Show unfolds it");
    await page.screenshot({ path: join(SHOTS, "viewer-phone-error.png"), fullPage: true });

    // A warning's words are a tap away, and a second tap puts them away.
    const defective = rectangleWith({ open: true, clockwise: true });
    await page.evaluate((t) => window.furrow.loadField(t, "rectangle, open and clockwise"), defective);
    await ready(page);
    const note = page.locator('.map-note[data-feature="0"]');
    assert.equal(await note.count(), 1);
    assert.ok(await note.locator(".callout").isHidden(), "closed until tapped");
    await note.locator(".note-badge").tap();
    assert.ok(await note.locator(".callout").isVisible(), "a tap opens the warning");
    assert.match(await note.locator(".callout").innerText(), /was open/);
    assert.ok(inside(await note.locator(".callout").boundingBox(), map), "the warning card inside the map");
    await page.screenshot({ path: join(SHOTS, "viewer-phone-warning.png"), fullPage: true });
    await note.locator(".note-badge").tap();
    assert.ok(await note.locator(".callout").isHidden(), "a second tap closes it");

    // The headland and obstacle options start folded on a phone, their values beside the title;
    // a tap unfolds them, touch-sized and without sideways scrolling.
    const more = page.locator("#more-options");
    assert.equal(await more.getAttribute("open"), null, "folded on a phone");
    assert.ok(await page.isHidden("#headlandMode"));
    assert.match(await page.textContent("#more-state"), /All around, last, 1 width/);
    await more.locator("summary").tap();
    assert.ok(await page.isVisible("#headlandMode"), "a tap unfolds the options");
    const targets = await page.evaluate(() =>
      ["objective", "decomposition", "search", "headlandMode", "headlandOrder", "obstacleThreshold"].map((id) => {
        const r = document.getElementById(id).getBoundingClientRect();
        return [id, r.width, r.height];
      }),
    );
    for (const [id, w, h] of targets) assert.ok(w >= 44 && h >= 44, `${id} is ${w}x${h}`);
    assert.ok((await more.locator("summary").boundingBox()).height >= 44, "the fold's title is a touch target");
    assert.equal(await page.evaluate(() => document.documentElement.scrollWidth), 390, "no sideways scrolling");
    const area = () => page.evaluate(() => window.furrow.plan.summary.headland_area_m2);
    const before = await area();
    await page.selectOption("#headlandMode", "needed");
    await ready(page);
    assert.ok((await area()) < before, "headland only where needed is smaller");
    await more.screenshot({ path: join(SHOTS, "viewer-phone-options.png") });
    await more.locator("summary").tap();
    assert.ok(await page.isHidden("#headlandMode"), "a second tap folds them");
    assert.match(await page.textContent("#more-state"), /Where needed/);
  });
});

test("viewer: obstacle classes, lifted swaths, headland only where needed", { timeout: TIMEOUT }, async () => {
  mkdirSync(SHOTS, { recursive: true });
  await withViewer({ viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 }, async (page, base) => {
    await page.goto(`${base}#obstacle-types`);
    await ready(page);
    assert.equal(await page.inputValue("#field"), "obstacle-types");
    assert.equal(await page.inputValue("#headlandMode"), "constant", "headland all around by default");
    assert.equal(await page.inputValue("#headlandOrder"), "last", "headland worked last by default");
    assert.equal(await page.inputValue("#obstacleThreshold"), "", "obstacle threshold: one width by default");
    // On a screen this short the options start folded, their values beside the title.
    const more = page.locator("#more-options");
    assert.equal(await more.getAttribute("open"), null, "folded on a short screen");
    assert.equal(await page.textContent("#more-state"), "All around, last, 1 width, shortest time");
    await more.locator("summary").click();
    assert.ok(await page.isVisible("#obstacleThreshold"), "a click unfolds them");

    // One obstacle of each class; the map labels every obstacle with its class, on or beside it.
    const plan = await page.evaluate(() => {
      const fs = window.furrow.plan.features;
      const screenBox = (ring) => {
        const pts = ring.map((c) => window.furrow.view.toScreen(window.furrow.projection.forward(c)));
        const xs = pts.map((p) => p[0]);
        const ys = pts.map((p) => p[1]);
        return { x: Math.min(...xs), y: Math.min(...ys), width: Math.max(...xs) - Math.min(...xs), height: Math.max(...ys) - Math.min(...ys) };
      };
      return {
        obstacles: fs
          .filter((f) => f.properties.kind === "obstacle")
          .map((f) => ({ ...f.properties, box: screenBox(f.geometry.coordinates[0]) })),
        groups: fs.filter((f) => f.properties.kind === "obstacle_group").map((f) => f.properties),
        lifted: fs.flatMap((f) => f.properties.lifted ?? []).length,
        warnings: window.furrow.plan.warnings,
        summary: window.furrow.plan.summary,
      };
    });
    const classes = plan.obstacles.map((o) => o.class).sort();
    assert.deepEqual([...new Set(classes)], ["A", "B", "C", "D"], `obstacle classes ${classes}`);
    assert.deepEqual(plan.summary.obstacle_classes, { A: 1, B: 1, C: 2, D: 1 });
    const { labels, canvas } = await page.evaluate(() => ({
      labels: window.furrow.view.drawn.classLabels,
      canvas: window.furrow.view.state(),
    }));
    assert.deepEqual(labels.map((l) => l.text).sort(), classes, "a class label for every obstacle");
    for (const label of labels) {
      const o = plan.obstacles.find((x) => x.index === label.index);
      assert.equal(label.text, o.class, `obstacle ${o.index}: labelled with its class`);
      assert.ok(label.x > 0 && label.y > 0 && label.x < canvas.width && label.y < canvas.height, "label on the map");
      const d = distanceToBox([label.x, label.y], o.box);
      assert.ok(d <= 32, `the label of obstacle ${o.index} (${o.class}) is ${d.toFixed(0)} px from it`);
    }
    for (let i = 0; i < labels.length; i++) {
      for (let j = i + 1; j < labels.length; j++) {
        const [a, b] = [labels[i], labels[j]];
        assert.ok(Math.abs(a.x - b.x) >= 16 || Math.abs(a.y - b.y) >= 16, `labels ${a.index} and ${b.index} overlap`);
      }
    }

    // The two class-C obstacles form a group; the class-A obstacle is passed with the implement lifted.
    const cs = plan.obstacles.filter((o) => o.class === "C");
    assert.equal(plan.groups.length, 1);
    assert.deepEqual(plan.groups[0].members.sort(), cs.map((o) => o.index).sort());
    assert.ok(cs.every((o) => o.group === plan.groups[0].index), "class-C obstacles name their group");
    assert.ok(plan.lifted > 0, "some swath is lifted over the class-A obstacle");
    assert.equal(await page.evaluate(() => window.furrow.view.drawn.liftedStretches), plan.lifted);
    const a = plan.obstacles.find((o) => o.class === "A");
    assert.ok(plan.warnings.some((w) => w.code === "implement_lifted" && w.feature === a.feature));
    assert.equal(await page.locator("#warnings li[data-code=implement_lifted]").count(), 1, "listed in the panel");
    assert.match(await page.getAttribute(`.map-note[data-feature="${a.feature}"]`, "data-code"), /implement_lifted/);

    // The summary: classes as the map's tags, the new figures.
    const dd = (key) => page.locator(`#summary dd[data-key=${key}]`);
    const tags = await dd("obstacle_classes").locator(".class-tag").allInnerTexts();
    assert.deepEqual(tags, ["A", "B", "C", "D"]);
    assert.match(await dd("obstacle_classes").innerText(), /A\s*1\s*B\s*1\s*C\s*2\s*D\s*1/);
    const ratio = plan.summary.remaining_area_ratio;
    assert.equal(await dd("remaining_area_ratio").innerText(), `${(ratio * 100).toFixed(1)} %`);
    assert.match(await dd("uncovered_headland_area_m2").innerText(), /^\d[\d,.]* (m²|ha)$/);
    assert.match(await dd("headland_area_m2").innerText(), /^\d[\d,.]* ha$/);
    assert.match(await dd("lifted_distance_m").innerText(), /^\d+ m$/);
    // Coverage: the figure against the reachable limit, the parts left standing drawn in violet;
    // what is worked outside the field shown where there is any.
    const cov = plan.summary.coverage;
    const pct = (x) => (x * 100).toFixed(1);
    assert.equal(await dd("coverage").innerText(), `${pct(cov.coverage_ratio)} % of ${pct(cov.reachable_ratio)} % reachable`);
    assert.match(await dd("uncovered_area_m2").innerText(), /^\d[\d,.]* (m²|ha)$/);
    assert.equal(await dd("outside_area_m2").count(), cov.outside_area_m2 > 0 ? 1 : 0);
    if (cov.outside_area_m2 > 0) assert.match(await dd("outside_area_m2").innerText(), /^\d[\d,.]* (m²|ha)$/);
    const parts = await page.evaluate(() => window.furrow.plan.features.filter((f) => f.properties.kind === "uncovered").length);
    assert.ok(parts > 0, "the plan leaves some crop standing round the obstacles");
    assert.equal(await page.evaluate(() => window.furrow.view.drawn.uncovered), parts, "each part drawn");
    const legend = await page.textContent(".legend");
    for (const item of ["Obstacle class", "Obstacle group", "Implement lifted", "Crop left standing"]) {
      assert.ok(legend.includes(item), item);
    }
    assert.deepEqual(await page.locator("#obstacle-classes .class-tag").allInnerTexts(), ["A", "B", "C", "D"]);
    await page.screenshot({ path: join(SHOTS, "viewer-classes.png") });
    await page.locator(".info").screenshot({ path: join(SHOTS, "viewer-classes-summary.png") });

    // The obstacle threshold: at 0 nothing is small enough to be passed over.
    await setInput(page, "obstacleThreshold", 0);
    await ready(page);
    assert.equal(await page.evaluate(() => window.furrow.options.obstacleThreshold), 0);
    assert.equal(await page.evaluate(() => window.furrow.plan.summary.obstacle_classes.A), 0);
    // What is still lifted is where the implement would reach into an obstacle (a pass's chord a
    // centimetre close), drawn as the plan gives it; no warning of a class-A obstacle.
    const liftedNow = await page.evaluate(() => ({
      planned: window.furrow.plan.features.flatMap((f) => f.properties.lifted ?? []).length,
      drawn: window.furrow.view.drawn.liftedStretches,
    }));
    assert.equal(liftedNow.drawn, liftedNow.planned);
    assert.equal(await page.locator("#warnings li[data-code=implement_lifted]").count(), 0);
    await setInput(page, "obstacleThreshold", "");
    await ready(page);
    assert.equal(await page.evaluate(() => window.furrow.options.obstacleThreshold), null);
    assert.equal(await page.evaluate(() => window.furrow.plan.summary.obstacle_classes.A), 1);

    // Rectangle: a headland only where the swaths end is smaller than one all around, and its
    // passes are open lines.
    await page.selectOption("#field", "rectangle");
    await page.waitForFunction(() => window.furrow.field?.features?.[0]?.properties?.name === "rectangle");
    await ready(page);
    const headland = () =>
      page.evaluate(() => ({
        value: Number(document.querySelector("#summary dd[data-key=headland_area_m2]").dataset.value),
        text: document.querySelector("#summary dd[data-key=headland_area_m2]").textContent,
        closed: window.furrow.plan.features.filter((f) => f.properties.kind === "headland").map((f) => f.properties.closed),
        first: window.furrow.plan.features.find((f) => f.properties.sequence === 0).properties.kind,
      }));
    const around = await headland();
    assert.ok(around.closed.length > 0 && around.closed.every((c) => c === true), "closed passes all around");
    await page.selectOption("#headlandMode", "needed");
    await ready(page);
    assert.equal(await page.evaluate(() => window.furrow.options.headlandMode), "needed");
    const needed = await headland();
    assert.ok(needed.value < around.value, `headland area ${needed.value} m² where needed, ${around.value} m² all around`);
    const ha = (t) => Number(t.replace(/[^\d.]/g, ""));
    assert.ok(ha(needed.text) < ha(around.text), `the summary shows ${needed.text}, was ${around.text}`);
    assert.ok(needed.closed.length > 0 && needed.closed.every((c) => c === false), "open passes where needed");
    assert.ok((await countColour(page, "--headland")) > 100, "the open passes are drawn");
    // Headland first (harvest): the route starts on the headland.
    assert.equal(needed.first, "swath");
    await page.selectOption("#headlandOrder", "first");
    await ready(page);
    assert.equal((await headland()).first, "headland");
    // Another field keeps the headland settings.
    await page.selectOption("#field", "obstacle-types");
    await page.waitForFunction(() => window.furrow.field?.features?.[0]?.properties?.name === "obstacle-types");
    await ready(page);
    assert.equal(await page.inputValue("#headlandMode"), "needed");
    assert.equal(await page.inputValue("#headlandOrder"), "first");
    await page.screenshot({ path: join(SHOTS, "viewer-classes-needed.png") });
    // Corners worked into: the passes follow the field exactly, longer than rounded ones.
    assert.equal(await page.inputValue("#headlandCorners"), "auto", "corners auto by default");
    const passes = () => page.evaluate(() => window.furrow.plan.summary.headland_distance_m);
    const rounded = await passes();
    await page.selectOption("#headlandCorners", "manoeuvre");
    await ready(page);
    assert.equal(await page.evaluate(() => window.furrow.options.headlandCorners), "manoeuvre");
    const exact = await passes();
    assert.ok(exact > rounded, `headland passes ${exact} m with the corners worked into, ${rounded} m rounded`);
    // Worked by passes to the middle: headlandPasses "all", the count input idle, no swaths
    // across the field (only pieces filling what the passes leave), the count laid shown.
    await page.selectOption("#headlandMode", "constant");
    await ready(page);
    assert.equal(await page.inputValue("#workedAs"), "swaths", "swaths inside the headland by default");
    await page.selectOption("#workedAs", "passes");
    await ready(page);
    assert.equal(await page.evaluate(() => window.furrow.options.headlandPasses), "all");
    assert.ok(await page.isDisabled("#headlandPasses"), "the number of passes is the field's");
    const contour = await page.evaluate(() => window.furrow.plan.summary);
    assert.equal(contour.swath_count, contour.fill_swath_count, "no swaths across the field");
    assert.ok(contour.headland_passes > 2, `${contour.headland_passes} passes`);
    assert.match(await page.textContent("#summary"), new RegExp(`${contour.headland_passes} \\(all\\)`));
    await page.screenshot({ path: join(SHOTS, "viewer-passes-to-the-middle.png") });
    await page.selectOption("#workedAs", "swaths");
    await ready(page);
    assert.notEqual(await page.evaluate(() => window.furrow.options.headlandPasses), "all");
    assert.ok(!(await page.isDisabled("#headlandPasses")));
  });
});

test("viewer: direction search, objective and the figures it reports", { timeout: TIMEOUT }, async () => {
  await withViewer({ viewport: { width: 1280, height: 900 } }, async (page, base) => {
    await page.goto(`${base}#h-shape`);
    await ready(page);
    assert.equal(await page.inputValue("#field"), "h-shape");
    assert.equal(await page.inputValue("#objective"), "time");
    assert.equal(await page.inputValue("#search"), "coarse-to-fine");
    const dd = (key) => page.locator(`#summary dd[data-key=${key}]`);
    const summary = () => page.evaluate(() => window.furrow.plan.summary);
    // Searched by default, coarse to fine, for the shortest time.
    let s = await summary();
    assert.equal(s.direction.mode, "search");
    assert.equal(s.direction.method, "coarse-to-fine");
    assert.equal(s.direction.objective, "time");
    assert.match(await dd("direction").innerText(), new RegExp(`searched, ${s.direction.evaluations} directions \\(coarse to fine\\)`));
    assert.match(await dd("estimated_time_s").innerText(), /^\d+ (h \d\d )?min$/);
    assert.equal(await dd("objectives").innerText(), `${(s.objectives.coverage * 100).toFixed(2)} %`);
    // Every degree: more directions evaluated, a plan no slower by the objective.
    await page.selectOption("#search", "brute-force");
    await ready(page);
    const brute = await summary();
    assert.equal(brute.direction.method, "brute-force");
    assert.ok(brute.direction.evaluations >= 180, `${brute.direction.evaluations} evaluations`);
    assert.ok(brute.direction.search_cost <= s.direction.search_cost * 1.01);
    // Fewest swaths: the objective reaches the planner and the summary.
    await page.selectOption("#objective", "swath-count");
    await ready(page);
    s = await summary();
    assert.equal(s.direction.objective, "swath-count");
    assert.ok(Number.isInteger(s.direction.search_cost), "a count of swaths");
    assert.equal(s.direction.cost, s.objectives.swath_count);
    // Blocks: by default the fastest decomposition; on the H its arms and cross block each get
    // their own direction. One direction for all is slower, and the summary says which is used.
    await page.selectOption("#objective", "time");
    await ready(page);
    assert.equal(await page.inputValue("#decomposition"), "auto");
    s = await summary();
    assert.equal(s.decomposition.requested, "auto");
    assert.equal(s.decomposition.method, "split-merge");
    assert.equal(s.decomposition.candidates.length, 3);
    // The arms north-south (drawn a degree or so apart, each worked along its own edges) and the
    // cross block east-west.
    assert.match(await dd("decomposition").innerText(), /^Direction per block, [23] directions \(fastest; /);
    const before = (m) => s.decomposition.candidates.find((c) => c.method === m).estimated_time_s;
    const [blocks, oneDirection] = [before("split-merge"), before("none")];
    const covered = s.coverage.coverage_ratio;
    await page.screenshot({ path: join(SHOTS, "viewer-h-shape-blocks.png") });
    await page.selectOption("#decomposition", "none");
    await ready(page);
    s = await summary();
    assert.equal(s.decomposition.method, "none");
    assert.equal(await dd("decomposition").innerText(), "One direction");
    // One direction for all is slower by what `auto` compares (the times before the fill), the
    // same plan as its candidate; filled, it leaves more crop standing.
    assert.ok(oneDirection > blocks, `one direction ${oneDirection} s, blocks ${blocks} s`);
    assert.equal(s.decomposition.candidates[0].estimated_time_s, oneDirection);
    assert.ok(s.coverage.coverage_ratio < covered, `one direction ${s.coverage.coverage_ratio}, blocks ${covered}`);
    await page.selectOption("#decomposition", "auto");
    await ready(page);
    // A bearing given: not searched.
    await setInput(page, "bearing", 30);
    await ready(page);
    s = await summary();
    assert.equal(s.direction.mode, "fixed");
    assert.equal(await dd("direction").innerText(), "as given");
    assert.ok(Math.abs(s.bearing_deg - 30) < 1e-9);
  });
});

/** The rectangle corpus field with its boundary ring left open and/or running clockwise. */
function rectangleWith({ open = false, clockwise = false }) {
  const field = JSON.parse(readFileSync(join(FIELDS, "rectangle.geojson"), "utf8"));
  const ring = field.features[0].geometry.coordinates[0];
  if (clockwise) ring.reverse();
  if (open) ring.pop();
  return JSON.stringify(field);
}

/** Whether box a lies inside box b (1 px of slack). */
const inside = (a, b) =>
  a &&
  b &&
  a.x >= b.x - 1 &&
  a.y >= b.y - 1 &&
  a.x + a.width <= b.x + b.width + 1 &&
  a.y + a.height <= b.y + b.height + 1;

/** Distance from point [x, y] to box (0 inside). */
const distanceToBox = ([x, y], b) =>
  Math.hypot(Math.max(b.x - x, 0, x - (b.x + b.width)), Math.max(b.y - y, 0, y - (b.y + b.height)));

/** Page position of a lon/lat position with the view's projection. */
const onScreen = (page, coordinate) =>
  page.evaluate((c) => {
    const [x, y] = window.furrow.view.toScreen(window.furrow.projection.forward(c));
    const r = document.getElementById("map").getBoundingClientRect();
    return [r.left + x, r.top + y];
  }, coordinate);

/** Distance on screen from a page point to the outline of input feature `index` (exterior ring). */
const distanceToFeature = (page, point, index) =>
  page.evaluate(
    ([[px, py], index]) => {
      const f = window.furrow.field;
      const geometry = f.type === "FeatureCollection" ? f.features[index].geometry : (f.geometry ?? f);
      const r = document.getElementById("map").getBoundingClientRect();
      const ring = geometry.coordinates[0].map((c) => {
        const [x, y] = window.furrow.view.toScreen(window.furrow.projection.forward(c));
        return [r.left + x, r.top + y];
      });
      let best = Infinity;
      for (let i = 0; i < ring.length; i++) {
        const [ax, ay] = ring[i];
        const [bx, by] = ring[(i + 1) % ring.length];
        const len2 = (bx - ax) ** 2 + (by - ay) ** 2 || 1;
        const t = Math.max(0, Math.min(1, ((px - ax) * (bx - ax) + (py - ay) * (by - ay)) / len2));
        best = Math.min(best, Math.hypot(px - (ax + t * (bx - ax)), py - (ay + t * (by - ay))));
      }
      return best;
    },
    [point, index],
  );

test("viewer: opens field files; errors and warnings in words beside the feature", { timeout: TIMEOUT }, async () => {
  mkdirSync(SHOTS, { recursive: true });
  await withViewer({ viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 }, async (page, base) => {
    await page.goto(base);
    await ready(page);
    const map = await page.locator(".map").boundingBox();
    const callout = page.locator("#map-message");

    // Every invalid input of the corpus, given to the page as the text of its file.
    const expected = {
      "hole-crossing-boundary.geojson": "hole_crossing_boundary",
      "lat-lon-swapped.geojson": "coordinates_swapped",
      "latitude-out-of-range.geojson": "coordinate_out_of_range",
      "nan-coordinates.geojson": "invalid_json",
      "not-geojson.geojson": "invalid_json",
      "obstacle-outside-field.geojson": "obstacle_outside_field",
      "self-intersecting-bowtie.geojson": "self_intersection",
      "too-few-points.geojson": "too_few_points",
      "zero-area.geojson": "zero_area",
    };
    const files = readdirSync(INVALID).filter((f) => f.endsWith(".geojson"));
    assert.deepEqual(files.sort(), Object.keys(expected).sort(), "tests/fields/invalid/ changed: update the test");
    for (const file of files) {
      const text = readFileSync(join(INVALID, file), "utf8");
      const name = file.replace(/\.geojson$/, "");
      const { error, warnings } = await page.evaluate(
        ([t, n]) => window.furrow.loadField(t, n).then((r) => ({ error: r.error, warnings: r.plan?.warnings })),
        [text, name],
      );
      assert.ok(error, `${file}: planned, with warnings ${JSON.stringify(warnings)}`);
      assert.equal(error.code, expected[file], `${file}: ${JSON.stringify(error)}`);
      await page.waitForSelector("body[data-plan-state=error]");
      assert.ok(await callout.isVisible(), `${file}: the callout is shown`);
      assert.equal(await callout.getAttribute("data-code"), error.code, `${file}: data-code`);
      const words = await callout.locator(".callout-text").innerText();
      assert.ok((words.match(/\b[a-z]{2,}\b/gi) ?? []).length >= 5, `${file}: a message in words: ${words}`);
      assert.ok(!words.includes(error.code), `${file}: words, not the code`);
      assert.equal(
        await callout.getAttribute("data-feature"),
        Number.isInteger(error.feature) ? String(error.feature) : null,
        `${file}: data-feature`,
      );
      const box = await callout.boundingBox();
      assert.ok(inside(box, map), `${file}: the callout ${JSON.stringify(box)} overflows the map`);
      assert.match(await page.textContent("#warnings li.error"), /Cannot plan/, `${file}: listed in the panel`);
      const located = Number.isInteger(error.feature) || error.coordinate;
      assert.equal(await callout.evaluate((e) => e.classList.contains("anchored")), !!located, `${file}: placement`);
      if (error.coordinate) {
        // Beside the point it names, which is marked on the map.
        const at = await onScreen(page, error.coordinate);
        const d = distanceToBox(at, box);
        assert.ok(d <= 80, `${file}: the callout is ${d.toFixed(0)} px from ${at}`);
        assert.ok(inside({ x: at[0], y: at[1], width: 0, height: 0 }, map), `${file}: the place is on the map`);
        assert.ok((await countColour(page, "--error-mark")) > 60, `${file}: the place marked in red`);
      } else if (Number.isInteger(error.feature)) {
        // Beside the feature, whose outline is red.
        assert.ok((await countColour(page, "--error-mark")) > 60, `${file}: the feature outlined in red`);
        const d = await distanceToFeature(page, [box.x + box.width / 2, box.y + box.height / 2], error.feature);
        assert.ok(d <= box.height / 2 + box.width / 2 + 40, `${file}: the callout ${d.toFixed(0)} px from the feature`);
      }

      if (file === "self-intersecting-bowtie.geojson") {
        await page.screenshot({ path: join(SHOTS, "viewer-error.png") });
        // The callout follows the map when it is panned.
        const cx = map.x + map.width / 2;
        const cy = map.y + map.height - 90; // above the edit bar
        await page.mouse.move(cx, cy);
        await page.mouse.down();
        await page.mouse.move(cx - 90, cy - 30, { steps: 4 });
        await page.mouse.up();
        await page.waitForFunction(() => !window.furrow.view.frame);
        const moved = await callout.boundingBox();
        const at = await onScreen(page, error.coordinate);
        assert.ok(distanceToBox(at, moved) <= 80, "the callout stays beside the crossing after a pan");
        assert.ok(Math.abs(moved.x - box.x) > 20 || Math.abs(moved.y - box.y) > 20, "the callout moved with the map");
        // Hide folds it to its title, Show unfolds it.
        await callout.locator(".callout-toggle").click();
        assert.ok(await callout.locator(".callout-text").isHidden());
        assert.equal(await callout.locator(".callout-toggle").getAttribute("aria-expanded"), "false");
        await callout.locator(".callout-toggle").click();
        assert.ok(await callout.locator(".callout-text").isVisible());
      }
      if (file === "obstacle-outside-field.geojson") assert.equal(await callout.getAttribute("data-feature"), "1");
      if (error.code === "invalid_json") {
        assert.ok(await callout.evaluate((e) => e.classList.contains("banner")), `${file}: a banner`);
      }
    }

    // The file picker: a rectangle whose boundary is left open and runs clockwise plans with two
    // warnings on feature 0, grouped under one small badge on its outline.
    const [chooser] = await Promise.all([page.waitForEvent("filechooser"), page.click("#open-file")]);
    // GeoJSON, and the field files of furrow/formats: zipped Shapefiles or their parts, KML, KMZ,
    // ISOXML TaskData.
    const accept = (await page.getAttribute("#file-input", "accept")).split(",");
    for (const type of [".geojson", ".json", "application/geo+json", ".zip", ".kml", ".kmz", ".xml", ".shp", ".shx", ".dbf", ".prj"]) {
      assert.ok(accept.includes(type), `the file picker offers ${type}`);
    }
    await chooser.setFiles({
      name: "rectangle-open-clockwise.geojson",
      mimeType: "application/geo+json",
      buffer: Buffer.from(rectangleWith({ open: true, clockwise: true })),
    });
    await ready(page);
    assert.ok(await callout.isHidden(), "no error callout");
    assert.match(await page.textContent("#status"), /rectangle-open-clockwise/);
    // The repairs of the feature (warnings of the plan as a whole, with no feature, aside).
    const codes = await page.evaluate(() =>
      window.furrow.plan.warnings.filter((w) => w.feature !== undefined).map((w) => `${w.code}@${w.feature}`),
    );
    assert.deepEqual(codes.sort(), ["ring_closed@0", "ring_reoriented@0"]);
    const note = page.locator(".map-note");
    assert.equal(await note.count(), 1, "one badge for the two warnings of one feature");
    assert.equal(await note.getAttribute("data-feature"), "0");
    assert.deepEqual((await note.getAttribute("data-code")).split(" ").sort(), ["ring_closed", "ring_reoriented"]);
    const pip = await note.locator(".pip").boundingBox();
    assert.ok(pip.width <= 40 && pip.height <= 30, `the badge is small: ${JSON.stringify(pip)}`);
    assert.match(await note.locator(".pip").innerText(), /2/, "the badge counts its warnings");
    const centre = [pip.x + pip.width / 2, pip.y + pip.height / 2];
    const off = await distanceToFeature(page, centre, 0);
    assert.ok(off <= 6, `the badge sits on the boundary's outline (${off.toFixed(1)} px off)`);
    assert.ok((await countColour(page, "--swath")) > 100, "the plan is drawn under the badge");
    const card = note.locator(".callout");
    assert.ok(await card.isHidden(), "the words wait for hover, focus or a tap");
    const label = await note.locator(".note-badge").getAttribute("aria-label");
    assert.match(label, /was open/, "the badge's accessible name has the words");
    // Hover shows the words and outlines the feature; leaving hides them.
    const warnBefore = await countColour(page, "--warn-mark");
    await note.locator(".note-badge").hover();
    assert.ok(await card.isVisible(), "hover opens the warning");
    assert.ok((await countColour(page, "--warn-mark")) > warnBefore + 200, "the feature is outlined while open");
    await page.mouse.move(map.x + 20, map.y + map.height - 80);
    await card.waitFor({ state: "hidden", timeout: 2000 }); // leaving closes it
    // A click (a tap) keeps it open, with both messages in words.
    await note.locator(".note-badge").click();
    assert.ok(await card.isVisible(), "a click opens the warning");
    assert.equal(await note.locator(".note-badge").getAttribute("aria-expanded"), "true");
    const items = await card.locator("li").evaluateAll((lis) => lis.map((li) => [li.dataset.code, li.textContent]));
    assert.equal(items.length, 2);
    for (const [code, words] of items) {
      assert.match(words, /^The field boundary .+ (closed|turned round)\.$/, `${code}: ${words}`);
    }
    assert.ok(inside(await card.boundingBox(), map), "the warning card inside the map");
    assert.equal(await page.locator("#warnings li[data-code=ring_closed]").count(), 1, "listed in the panel too");
    await page.mouse.move(map.x + 20, map.y + map.height - 80);
    assert.ok(await card.isVisible(), "stays open after the pointer leaves");
    await page.screenshot({ path: join(SHOTS, "viewer-warning.png") });
    await page.keyboard.press("Escape");
    assert.ok(await card.isHidden(), "Escape closes it");

    // Dropping a file on the map opens it too (here a file that is not JSON at all).
    await page.evaluate((text) => {
      const dt = new DataTransfer();
      dt.items.add(new File([text], "broken.geojson", { type: "application/geo+json" }));
      const target = document.querySelector(".map");
      for (const type of ["dragenter", "dragover", "drop"]) {
        target.dispatchEvent(new DragEvent(type, { dataTransfer: dt, bubbles: true, cancelable: true }));
      }
    }, readFileSync(join(INVALID, "not-geojson.geojson"), "utf8"));
    await page.waitForSelector("body[data-plan-state=error]");
    assert.equal(await callout.getAttribute("data-code"), "invalid_json");
    assert.equal(await note.count(), 0, "no warning badges without a plan");

    // A good field: the callouts go, the plan is drawn.
    const good = readFileSync(join(FIELDS, "rectangle.geojson"), "utf8");
    await page.evaluate((t) => window.furrow.loadField(t, "rectangle"), good);
    await ready(page);
    assert.ok(await callout.isHidden(), "the error callout is gone");
    // Nothing of the files before (the rectangle's own turns out of the field or over crop, at
    // two passes, aside).
    const own = ":not([data-code=turn_crosses_crop]):not([data-code=turn_leaves_field])";
    assert.equal(await page.locator(`[data-code]:visible${own}`).count(), 0, "no callouts or badges left");
    assert.equal(await page.locator(`#warnings li${own}`).count(), 0);
    assert.ok((await countColour(page, "--swath")) > 100, "swaths drawn");
    assert.ok((await countColour(page, "--headland")) > 100, "headland drawn");
    assert.ok((await countColour(page, "--error-mark")) < 10, "nothing drawn in the error colour");

    // And the bundled fields are still a pick away.
    await page.selectOption("#field", "square-1ha");
    await page.waitForFunction(() => window.furrow.field?.features?.[0]?.properties?.name === "square-1ha");
    await ready(page);
    assert.ok(await page.isEnabled("#suggested"));
  });
});

test("viewer: plans in a worker; rapid edits on the large field keep the page responsive, newest wins", { timeout: TIMEOUT }, async () => {
  await withViewer({ viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 }, async (page, base) => {
    await page.goto(`${base}#large-250ha-10-obstacles`);
    await page.waitForFunction(() => window.furrow.field?.features?.[0]?.properties?.name === "large-250ha-10-obstacles");
    await ready(page);
    // Every drawn plan is of a newer edit than the one drawn before it.
    await page.evaluate(() => {
      window.__drawn = [];
      new MutationObserver(() => window.__drawn.push(Number(document.body.dataset.planSeq))).observe(document.body, {
        attributes: true,
        attributeFilter: ["data-plan-seq"],
      });
    });
    // Twenty edits 25 ms apart (faster than the field plans), frames timed meanwhile.
    const frames = await page.evaluate(async () => {
      const gaps = [];
      let last = performance.now();
      let on = true;
      const tick = (t) => {
        gaps.push(t - last);
        last = t;
        if (on) requestAnimationFrame(tick);
      };
      requestAnimationFrame(tick);
      const width = document.getElementById("width");
      for (let i = 0; i < 20; i++) {
        width.value = String(20 + (i % 5));
        width.dispatchEvent(new Event("input", { bubbles: true }));
        await new Promise((r) => setTimeout(r, 25));
      }
      await new Promise((r) => {
        const check = () => (document.body.dataset.planState === "ready" ? r() : setTimeout(check, 10));
        check();
      });
      on = false;
      gaps.sort((a, b) => a - b);
      return { count: gaps.length, median: gaps[gaps.length >> 1], max: gaps[gaps.length - 1] };
    });
    const replans = await page.evaluate(() => window.furrow.replans);
    const drawn = await page.evaluate(() => window.__drawn);
    console.log(`large field, 20 edits 25 ms apart: ${drawn.length} plans drawn, frames median ${frames.median.toFixed(1)} ms, max ${frames.max.toFixed(1)} ms over ${frames.count}`);
    assert.equal(replans.drawn, replans.made, "the newest edit's plan is the one shown");
    for (let i = 1; i < drawn.length; i++) assert.ok(drawn[i] > drawn[i - 1], `plan ${drawn[i]} drawn after ${drawn[i - 1]}`);
    assert.ok(drawn.length < 20, "superseded edits were not all planned");
    // The last edit set the width to 24 m: the plan drawn is for that width.
    assert.equal(await page.evaluate(() => window.furrow.options.width), 24);
    const swaths = await page.evaluate(() => window.furrow.plan.summary.swath_count);
    const direct = await page.evaluate(async () => {
      const m = await import("./pkg/furrow.js");
      await m.default();
      return m.plan(window.furrow.field, window.furrow.options).summary.swath_count;
    });
    assert.equal(swaths, direct);
    // The planning ran off the page's thread, which kept drawing frames (their times are
    // printed above for the record, not asserted: speed is for the benchmarks).
    assert.equal((await dataset(page)).planner, "worker");
    assert.ok(frames.count > 5, "frames were drawn while the worker planned");
  });
});

test("viewer: slow full plans go to a pool of workers, the same plan, and the way out runs along it", { timeout: TIMEOUT }, async () => {
  await withViewer({ viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 }, async (page, base) => {
    // A tablet of four cores: the pool takes three, one is left to the page. (This machine may
    // have fewer; the plans are the same.)
    await page.addInitScript(() => Object.defineProperty(navigator, "hardwareConcurrency", { get: () => 4 }));
    await page.goto(`${base}#large-250ha-10-obstacles`);
    await planned(page);
    // The first plan is the worker's; it takes far over 40 ms, so the next goes to the pool.
    assert.equal((await dataset(page)).pooled, "false");
    const width = (await page.evaluate(() => window.furrow.options.width)) + 1;
    await setInput(page, "width", width);
    await page.waitForFunction((w) => window.furrow.options.width === w, width);
    await planned(page);
    assert.equal((await dataset(page)).pooled, "true");
    // The way out from the middle of a swath, facing its end, to the field's first corner:
    // the worker finds it along the pooled plan's tracks, as the package does on plan().
    const [shown, direct] = await page.evaluate(async () => {
      const { field, options, plan, way } = window.furrow;
      const sw = plan.features.filter((f) => f.properties.kind === "swath")[10];
      const [a, b] = [sw.geometry.coordinates[0], sw.geometry.coordinates.at(-1)];
      way.position = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
      const p = window.furrow.projection;
      const [fa, fb] = [p.forward(a), p.forward(b)];
      way.heading = ((Math.atan2(fb[0] - fa[0], fb[1] - fa[1]) * 180) / Math.PI + 360) % 360;
      way.exit = window.furrow.document.features[0].geometry.coordinates[0][0];
      await way.find();
      const furrow = await import("./pkg/furrow.js");
      await furrow.default();
      const again = furrow.plan(field, options);
      const tracks = await import("./pkg/tracks.js");
      await tracks.default();
      const graph = new tracks.TrackGraph(again, { turning: way.turning() });
      const expected = graph.shortestPath(way.position, way.heading, way.exit, { turning: way.turning() });
      graph.free();
      const summary = (s) => JSON.stringify({ ...s, planning_ms: 0, stages_ms: 0 });
      return [
        { summary: summary(plan.summary), length: way.path?.properties.length_m, error: way.error },
        { summary: summary(again.summary), length: expected.properties.length_m },
      ];
    });
    assert.equal(shown.summary, direct.summary, "the pool's plan is plan()'s");
    assert.equal(shown.error, null);
    assert.equal(shown.length, direct.length);
  });
});

test("viewer: swath order and reversing turns are settings", { timeout: TIMEOUT }, async () => {
  await withViewer({ viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 }, async (page, base) => {
    await page.goto(`${base}#rectangle`);
    await page.waitForFunction(() => window.furrow.field?.features?.[0]?.properties?.name === "rectangle");
    await ready(page);
    const forward = await page.evaluate(() => window.furrow.plan.summary);
    assert.equal(forward.cusp_count, 0);
    // On a short screen the machine's further settings start folded.
    const more = page.locator("#more-options");
    if ((await more.getAttribute("open")) === null) await more.locator("summary").click();
    await page.selectOption("#reverse", "true");
    await ready(page);
    const reversing = await page.evaluate(() => ({ options: window.furrow.options, s: window.furrow.plan.summary }));
    assert.equal(reversing.options.reverse, true);
    assert.ok(reversing.s.cusp_count > 0, "turns with cusps");
    // Its turns keep in the field, where the forward machine's leave it or are longer.
    assert.equal(reversing.s.turns_outside_field, 0);
    assert.ok(
      forward.turns_outside_field > 0 || reversing.s.turning_distance_m < forward.turning_distance_m,
      "reversing turns stay in and are no longer",
    );
    await page.selectOption("#pattern", "boustrophedon");
    await ready(page);
    const bous = await page.evaluate(() => window.furrow.plan.summary.route);
    assert.equal(bous.pattern, "boustrophedon");
    assert.ok(bous.block_patterns.every((p) => p === "boustrophedon"));
    assert.match(await page.textContent("#summary"), /Turn forms/);
  });
});

test("viewer: with the server stopped, a reload still opens and plans (service worker)", { timeout: TIMEOUT }, async () => {
  const server = await startServer(SITE, 0);
  let browser;
  let stopped = false;
  try {
    browser = await launchChromium();
    const context = await browser.newContext({ viewport: { width: 1280, height: 800 } });
    await reportCspViolations(context);
    const page = await context.newPage();
    const problems = [];
    page.on("console", (msg) => {
      if (msg.type() === "error") problems.push(`console error: ${msg.text()}`);
    });
    const base = `http://127.0.0.1:${server.address().port}/`;
    await page.goto(`${base}#rectangle`);
    await ready(page);
    await page.waitForSelector("body[data-offline=ready]", { timeout: 20_000 });
    const online = await page.evaluate(() => window.furrow.plan.summary.swath_count);
    // Stop the server: nothing answers on its port any more.
    server.closeAllConnections?.();
    await new Promise((ok) => server.close(ok));
    stopped = true;
    const down = await page.evaluate((u) => fetch(u, { cache: "no-store", mode: "no-cors" }).then(() => "up", () => "down"), `${base}nothing-${Date.now()}`);
    assert.equal(down, "down", "the server is stopped");
    await page.reload();
    await ready(page);
    assert.equal(await page.evaluate(() => window.furrow.plan.summary.swath_count), online);
    assert.equal((await dataset(page)).planner, "worker", "the planner's worker starts offline too");
    // And it plans again on an edit.
    const passes = Number(await page.inputValue("#headlandPasses"));
    await setInput(page, "headlandPasses", passes + 1);
    await ready(page);
    const shown = await fieldPasses(page);
    assert.equal(shown, passes + 1);
    // Another bundled field opens from the cache.
    await page.selectOption("#field", "h-shape");
    await page.waitForFunction(() => window.furrow.field?.features?.[0]?.properties?.name === "h-shape");
    await ready(page);
    // The page's Content-Security-Policy let all of it run, online and offline (the requests
    // refused while the server is down are expected errors).
    assert.deepEqual(problems.filter((p) => /CSP|Content.Security.Policy/i.test(p)), [], "CSP violations");
  } finally {
    await browser?.close();
    if (!stopped) await new Promise((ok) => server.close(ok));
  }
});

test("viewer: a night theme, kept across visits", { timeout: TIMEOUT }, async () => {
  mkdirSync(SHOTS, { recursive: true });
  await withViewer({ viewport: { width: 1280, height: 800 }, deviceScaleFactor: 1 }, async (page, base) => {
    await page.goto(`${base}#h-shape`);
    await page.waitForFunction(() => window.furrow.field?.features?.[0]?.properties?.name === "h-shape");
    await ready(page);
    const dayField = await countColour(page, "--map-field", 6);
    assert.ok(dayField > 1000, "the field drawn in the day colour");
    await page.screenshot({ path: join(SHOTS, "viewer-day.png") });
    await page.click("#theme");
    assert.equal(await page.evaluate(() => document.documentElement.dataset.theme), "night");
    assert.equal(await page.getAttribute("#theme", "aria-pressed"), "true");
    // The map is redrawn in the night colours: the field dark, the plan in its night colours.
    const nightField = await countColour(page, "--map-field", 6);
    assert.ok(nightField > 1000, `the field drawn in the night colour (${nightField} pixels)`);
    for (const kind of ["--swath", "--headland", "--turn"]) {
      assert.ok((await countColour(page, kind)) > 100, `${kind} in its night colour`);
    }
    const bg = await page.evaluate(() => getComputedStyle(document.body).backgroundColor);
    assert.notEqual(bg, "rgb(238, 240, 234)", "the page is dark");
    await page.screenshot({ path: join(SHOTS, "viewer-night.png") });
    await page.reload();
    await ready(page);
    assert.equal(await page.evaluate(() => document.documentElement.dataset.theme), "night", "kept after a reload");
    await page.click("#theme");
    assert.equal(await page.evaluate(() => document.documentElement.dataset.theme ?? "day"), "day");
  });
});
