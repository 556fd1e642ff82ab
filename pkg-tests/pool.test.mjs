// furrow/pool in Node (worker threads): a pool of workers gives the plan `plan()` gives, on
// every corpus field, with the same errors; plans asked together each get their own plan; an
// idle pool does not keep Node running.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { corpusRows, readField } from "../scripts/corpus.mjs";
import { builtEntry, PKG_URL as pkgUrl } from "./install.mjs";

const fieldsUrl = new URL("../tests/fields/", import.meta.url);
const furrow = await builtEntry("furrow.js", "furrow_wasm_bg.wasm");
const { PlannerPool, planInWorkers, MAX_WORKERS, FurrowError } = await import(new URL("pool.js", pkgUrl));
const corpus = () =>
  corpusRows((message) => {
    throw new Error(message);
  });

/** A plan without its planning times, which differ run to run; its samples as plain arrays. */
function comparable(plan) {
  const { planning_ms, stages_ms, ...summary } = plan.summary;
  const samples = Object.fromEntries(Object.entries(plan.samples).map(([k, v]) => [k, Array.from(v)]));
  return { ...plan, summary, samples };
}

test("a pool of 2 workers plans every corpus field as plan() does", async () => {
  const pool = new PlannerPool({ workers: 2 });
  assert.equal(pool.size, 2);
  try {
    const rows = corpus();
    assert.ok(rows.length >= 20);
    for (const { file, options } of rows) {
      const field = readField(file);
      const alone = furrow.plan(field, options);
      const pooled = await pool.plan(field, options);
      assert.deepEqual(comparable(pooled), comparable(alone), file);
    }
  } finally {
    pool.terminate();
  }
});

test("pools of 3 and 4 workers, and passes counted or to the middle, plan as plan() does", async () => {
  const cases = [
    ["obstacles-5.geojson", { width: 12, headlandPasses: 2, turnRadius: 8 }],
    ["h-shape.geojson", { width: 6, headlandPasses: "auto", turnRadius: 8 }],
    ["narrow-curved-strip.geojson", { width: 6, headlandPasses: 1, turnRadius: 6 }],
    ["l-shape.geojson", { width: 12, headlandPasses: "all", turnRadius: 6 }],
    ["many-bays.geojson", { width: 6, headlandPasses: 2, turnRadius: 6, decomposition: "split-merge" }],
    ["obstacles-2.geojson", { width: 12, headlandPasses: 2, turnRadius: 8, decomposition: "none" }],
    ["t-shape.geojson", { width: 6, headlandPasses: 2, turnRadius: 6, decomposition: "boustrophedon" }],
  ];
  for (const workers of [3, 4]) {
    const pool = new PlannerPool({ workers });
    try {
      for (const [file, options] of cases) {
        const field = readField(file);
        const pooled = await pool.plan(field, options);
        assert.deepEqual(comparable(pooled), comparable(furrow.plan(field, options)), `${file}, ${workers} workers`);
      }
    } finally {
      pool.terminate();
    }
  }
});

test("plans asked together each get their own plan", async () => {
  const pool = new PlannerPool({ workers: 2 });
  try {
    const asks = [
      ["l-shape.geojson", { width: 6, headlandPasses: 2, turnRadius: 6 }],
      ["t-shape.geojson", { width: 6, headlandPasses: 2, turnRadius: 6 }],
      ["l-shape.geojson", { width: 12, headlandPasses: 1, turnRadius: 9 }],
    ].map(([file, options]) => [readField(file), options]);
    const pooled = await Promise.all(asks.map(([field, options]) => pool.plan(field, options)));
    asks.forEach(([field, options], i) =>
      assert.deepEqual(comparable(pooled[i]), comparable(furrow.plan(field, options)), `ask ${i}`),
    );
  } finally {
    pool.terminate();
  }
});

test("a pool throws the errors plan() throws, as FurrowErrors, and keeps planning", async () => {
  const pool = new PlannerPool({ workers: 2 });
  try {
    const square = readField("square-1ha.geojson");
    const cases = [
      [readField("invalid/self-intersecting-bowtie.geojson"), {}],
      [square, { width: -1 }],
      [square, { widht: 6 }],
      ["{ not json", {}],
    ];
    for (const [field, options] of cases) {
      let expected;
      try {
        furrow.plan(field, options);
      } catch (e) {
        expected = e;
      }
      assert.ok(expected, "plan() refuses it");
      await assert.rejects(pool.plan(field, options), (e) => {
        assert.ok(e instanceof FurrowError);
        assert.equal(e.code, expected.code);
        assert.equal(e.message, expected.message);
        assert.deepEqual(e.coordinate, expected.coordinate);
        return true;
      });
    }
    // A field that is not plain values cannot be sent to a worker.
    await assert.rejects(pool.plan({ type: "Polygon", coordinates: [], extra: () => 1 }, {}), (e) => {
      assert.ok(e instanceof FurrowError);
      assert.equal(e.code, "invalid_geojson");
      return true;
    });
    const plan = await pool.plan(square, { width: 6 });
    assert.ok(plan.summary.swath_count > 0, "still plans");
  } finally {
    pool.terminate();
  }
  assert.throws(() => new PlannerPool({ workers: 0 }), (e) => e instanceof FurrowError && e.code === "invalid_option");
  assert.equal(new PlannerPool({ workers: 9 }).size, MAX_WORKERS);
  // Workers that cannot load the planner: every plan is refused, with the reason.
  const unloadable = new PlannerPool({ workers: 2, wasm: { module_or_path: new Uint8Array([0, 1, 2, 3]) } });
  for (let i = 0; i < 2; i++) {
    await assert.rejects(unloadable.plan(readField("square-1ha.geojson"), {}), (e) => {
      assert.ok(e instanceof FurrowError);
      assert.equal(e.code, "not_initialised");
      return true;
    });
  }
  unloadable.terminate();
  const closed = new PlannerPool({ workers: 1 });
  closed.terminate();
  await assert.rejects(closed.plan(readField("square-1ha.geojson"), {}), (e) => e.code === "not_initialised");
});

test("planInWorkers plans in a pool kept between calls, which does not keep Node running", () => {
  const script = `
    import { planInWorkers } from ${JSON.stringify(new URL("pool.js", pkgUrl).href)};
    import { readFileSync } from "node:fs";
    const field = JSON.parse(readFileSync(${JSON.stringify(new URL("l-shape.geojson", fieldsUrl).pathname)}, "utf8"));
    const a = await planInWorkers(field, { width: 6, headlandPasses: 2 }, { workers: 2 });
    const b = await planInWorkers(field, { width: 6, headlandPasses: 2 }, { workers: 2 });
    console.log(JSON.stringify([a.summary.swath_count, b.summary.estimated_time_s === a.summary.estimated_time_s]));
  `;
  // Node must exit by itself once the plans are made: a timeout here means the workers held it.
  const dir = mkdtempSync(join(tmpdir(), "furrow-pool-"));
  const file = join(dir, "plan.mjs");
  writeFileSync(file, script);
  const out = execFileSync(process.execPath, [file], {
    encoding: "utf8",
    timeout: 60_000,
  });
  rmSync(dir, { recursive: true });
  const [swaths, same] = JSON.parse(out.trim());
  const alone = furrow.plan(readField("l-shape.geojson"), { width: 6, headlandPasses: 2 });
  assert.equal(swaths, alone.summary.swath_count);
  assert.equal(same, true);
});
