// The built npm package in a real browser: Debian's Chromium, driven by playwright-core, loads
// pkg/furrow.js from a localhost server (streaming compile of application/wasm), plans every
// corpus field and reports errors as FurrowErrors; and an app bundled by esbuild as the
// package's README says.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { existsSync, mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { delimiter, join } from "node:path";
import { startServer } from "../scripts/serve.mjs";
import { codeBlocks, installLinked, ROOT } from "./install.mjs";
import { launchChromium, SITE } from "./support.mjs";

/**
 * Runs `body(page, problems)` on a page of the site (target/site, served on localhost) in
 * Chromium, opened at fields/index.json; `problems` collects the page's errors.
 */
async function onSitePage(body) {
  const server = await startServer(SITE, 0);
  const browser = await launchChromium();
  try {
    const page = await browser.newPage();
    const problems = [];
    page.on("console", (m) => m.type() === "error" && problems.push(m.text()));
    page.on("pageerror", (e) => problems.push(String(e)));
    await page.goto(`http://127.0.0.1:${server.address().port}/fields/index.json`);
    await body(page, problems);
  } finally {
    await browser.close();
    server.close();
  }
}

test("the package plans in Chromium", { timeout: 60_000 }, async () => {
  assert.ok(existsSync(join(SITE, "pkg/furrow.js")), "target/site is missing: run scripts/build.sh first");
  await onSitePage(async (page, problems) => {
    const result = await page.evaluate(async () => {
      const furrow = await import("/pkg/furrow.js");
      await furrow.default();
      const fields = await (await fetch("/fields/index.json")).json();
      const out = { planned: [], times: [] };
      for (const f of fields) {
        const geojson = await (await fetch(`/${f.file}`)).json();
        const options = { width: f.width, headlandPasses: f.headlandPasses, turnRadius: f.turnRadius };
        furrow.plan(geojson, options); // warm-up
        const t = performance.now();
        const plan = furrow.plan(geojson, options);
        out.times.push([f.name, performance.now() - t]);
        out.planned.push([f.name, plan.type, plan.summary.swath_count, plan.features.length]);
      }
      try {
        furrow.plan({ type: "Polygon", coordinates: [[[0, 0], [1, 1], [1, 0], [0, 1], [0, 0]]] });
        out.error = "no error";
      } catch (e) {
        out.error = {
          isError: e instanceof Error && e instanceof furrow.FurrowError,
          name: e.name,
          code: e.code,
          coordinate: e.coordinate,
        };
      }
      out.version = furrow.version();
      // A trap inside the planner: reported as an internal error, and the planner recovers. No
      // input makes it trap: the clock it reads throws a RuntimeError part-way through a plan.
      let calls = 0;
      const now = performance.now;
      Object.defineProperty(performance, "now", {
        configurable: true,
        value() {
          if (++calls === 2) throw new WebAssembly.RuntimeError("unreachable");
          return now.call(this);
        },
      });
      try {
        furrow.plan(await (await fetch(`/${fields[0].file}`)).json());
      } catch (e) {
        out.panic = { name: e.name, code: e.code, trap: e.cause instanceof WebAssembly.RuntimeError };
      } finally {
        delete performance.now;
      }
      const f0 = fields[0];
      const again = furrow.plan(await (await fetch(`/${f0.file}`)).json(), {
        width: f0.width,
        headlandPasses: f0.headlandPasses,
        turnRadius: f0.turnRadius,
      });
      out.afterPanic = again.summary.swath_count;
      return out;
    });
    assert.ok(result.planned.length >= 20);
    for (const [name, type, swaths, features] of result.planned) {
      assert.equal(type, "FeatureCollection", name);
      assert.ok(swaths > 0 && features > swaths, name);
    }
    assert.deepEqual(result.error.isError, true);
    assert.equal(result.error.name, "FurrowError");
    assert.equal(result.error.code, "self_intersection");
    assert.equal(result.error.coordinate.length, 2);
    assert.match(result.version, /^\d+\.\d+\.\d+/);
    assert.deepEqual(result.panic, { name: "FurrowError", code: "internal", trap: true });
    assert.equal(result.afterPanic, result.planned[0][2]);
    assert.deepEqual(problems, []);
    const slowest = result.times.sort((a, b) => b[1] - a[1]).slice(0, 3);
    console.log(`# slowest plans in Chromium (ms, one run after warm-up): ${JSON.stringify(slowest)}`);
  });
});

test("a pool of 2 Web Workers (furrow/pool) plans every corpus field as plan() does in Chromium", { timeout: 120_000 }, async () => {
  await onSitePage(async (page, problems) => {
    const result = await page.evaluate(async () => {
      const furrow = await import("/pkg/furrow.js");
      const { PlannerPool, FurrowError } = await import("/pkg/pool.js");
      await furrow.default();
      const pool = new PlannerPool({ workers: 2 });
      // A plan without its planning times; its samples as plain arrays.
      const comparable = (plan) => {
        const { planning_ms, stages_ms, ...summary } = plan.summary;
        const samples = Object.fromEntries(Object.entries(plan.samples).map(([k, v]) => [k, Array.from(v)]));
        return JSON.stringify({ ...plan, summary, samples });
      };
      const fields = await (await fetch("/fields/index.json")).json();
      const out = { differ: [], planned: 0 };
      for (const f of fields) {
        const geojson = await (await fetch(`/${f.file}`)).json();
        const options = { width: f.width, headlandPasses: f.headlandPasses, turnRadius: f.turnRadius };
        const pooled = await pool.plan(geojson, options);
        if (comparable(pooled) !== comparable(furrow.plan(geojson, options))) out.differ.push(f.name);
        out.planned++;
      }
      try {
        await pool.plan({ type: "Polygon", coordinates: [[[0, 0], [1, 1], [1, 0], [0, 1], [0, 0]]] });
      } catch (e) {
        out.error = { isFurrowError: e instanceof FurrowError, code: e.code };
      }
      pool.terminate();
      return out;
    });
    assert.ok(result.planned >= 20);
    assert.deepEqual(result.differ, []);
    assert.deepEqual(result.error, { isFurrowError: true, code: "self_intersection" });
    assert.deepEqual(problems, []);
  });
});

test("an app bundled by esbuild as the package's README says plans in Chromium", { timeout: 60_000 }, async () => {
  const dir = installLinked("esbuild");
  writeFileSync(
    join(dir, "app.js"),
    `import init, { plan, FurrowError } from "furrow";
    await init();
    const field = { type: "Polygon", coordinates: [[[24.05, 60.25], [24.055, 60.25], [24.055, 60.252], [24.05, 60.252], [24.05, 60.25]]] };
    let error;
    try {
      plan(field, { width: -1 });
    } catch (e) {
      error = e instanceof FurrowError && e.code;
    }
    window.result = { swaths: plan(field).summary.swath_count, error };`,
  );
  // The README's commands, as written, with the workspace's esbuild.
  const readme = readFileSync(join(ROOT, "js/README.md"), "utf8");
  const commands = codeBlocks(readme, "sh").find((block) => block.includes("esbuild "));
  assert.ok(commands, "js/README.md shows the esbuild commands");
  mkdirSync(join(dir, "dist"));
  const PATH = `${join(ROOT, "node_modules/.bin")}${delimiter}${process.env.PATH}`;
  execFileSync("bash", ["-euo", "pipefail", "-c", commands], { cwd: dir, env: { ...process.env, PATH }, stdio: "pipe" });
  writeFileSync(join(dir, "dist/index.html"), `<!doctype html><script type="module" src="app.js"></script>`);
  const server = await startServer(join(dir, "dist"), 0);
  const browser = await launchChromium();
  try {
    const page = await browser.newPage();
    const problems = [];
    page.on("pageerror", (e) => problems.push(String(e)));
    await page.goto(`http://127.0.0.1:${server.address().port}/`);
    await page.waitForFunction(() => window.result, null, { timeout: 30_000 });
    const result = await page.evaluate(() => window.result);
    assert.ok(result.swaths > 0, JSON.stringify(result));
    assert.equal(result.error, "option_out_of_range");
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    server.close();
  }
});
