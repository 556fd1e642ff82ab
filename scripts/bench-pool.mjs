// The worker pool (furrow/pool) against plan() on one thread, in Node and in headless Chromium.
//
//   node scripts/bench-pool.mjs [--workers N] [--rounds N] [--only node|chromium]
//
// For every field of the corpus table with its suggested options, calls pool.plan() and plan()
// in turn, `rounds` times each (after two of each to warm up), so that the machine's drift falls
// on both alike; prints the median of each per field, their ratio, the geometric mean of the
// ratios and how many fields up to 60 ha plan under 16 ms. Also checks that the pool gave the
// same plan (all but the planning times). Needs pkg/ (scripts/build.sh) and, for the browser
// part, Debian's chromium with playwright-core from node_modules.
import { pathToFileURL, fileURLToPath } from "node:url";
import { join } from "node:path";
import { readFileSync } from "node:fs";
import { corpusRows, readField } from "./corpus.mjs";

const ROOT = fileURLToPath(new URL("..", import.meta.url));
const PKG = join(ROOT, "pkg");
const fail = (message) => {
  console.error(`bench-pool: ${message}`);
  process.exit(2);
};

function parseArgs(argv) {
  const args = { workers: 2, rounds: 11, only: null };
  for (let i = 0; i < argv.length; i++) {
    const key = argv[i].replace(/^--/, "");
    if (!(key in args)) fail(`unknown argument ${argv[i]}`);
    args[key] = key === "only" ? argv[++i] : Number(argv[++i]);
  }
  if (!(args.workers >= 1 && args.rounds >= 1)) fail("--workers and --rounds take whole numbers");
  return args;
}

/**
 * Times `plan()` and `pool.plan()` (globalThis.__plan and __pool) in turn on one field; runs in
 * Node and in the page (Playwright sends the function itself).
 */
async function timeBoth({ field, options, rounds }) {
  const plan = globalThis.__plan;
  const pool = globalThis.__pool;
  const comparable = (p) => {
    const { planning_ms, stages_ms, ...summary } = p.summary;
    const samples = Object.fromEntries(Object.entries(p.samples).map(([k, v]) => [k, Array.from(v)]));
    return JSON.stringify({ ...p, summary, samples });
  };
  const same = comparable(await pool.plan(field, options)) === comparable(plan(field, options));
  await pool.plan(field, options);
  plan(field, options);
  const alone = [];
  const pooled = [];
  for (let r = 0; r < rounds; r++) {
    let t = performance.now();
    plan(field, options);
    alone.push(performance.now() - t);
    t = performance.now();
    await pool.plan(field, options);
    pooled.push(performance.now() - t);
  }
  const median = (v) => {
    const s = [...v].sort((a, b) => a - b);
    const m = s.length >> 1;
    return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
  };
  return { alone: median(alone), pooled: median(pooled), same };
}

function report(where, rows, results, workers) {
  console.log(`\n${where}: plan() and a pool of ${workers} workers, medians (ms)`);
  let log = 0;
  const under = { alone: 0, pooled: 0, fields: 0 };
  let differ = 0;
  for (const [i, r] of results.entries()) {
    const ratio = r.pooled / r.alone;
    log += Math.log(ratio);
    if (rows[i].areaHa <= 60) {
      under.fields++;
      if (r.alone < 16) under.alone++;
      if (r.pooled < 16) under.pooled++;
    }
    if (!r.same) differ++;
    console.log(
      `${rows[i].file.padEnd(36)} ${r.alone.toFixed(1).padStart(7)} ${r.pooled.toFixed(1).padStart(7)}  x${ratio.toFixed(2)}${r.same ? "" : "  NOT THE SAME PLAN"}`,
    );
  }
  console.log(`geometric mean of pool / plan(): ${Math.exp(log / results.length).toFixed(3)}`);
  console.log(
    `fields up to 60 ha under 16 ms: plan() ${under.alone} of ${under.fields}, pool ${under.pooled} of ${under.fields}`,
  );
  console.log(differ ? `${differ} plans differ` : "every plan the same");
}

async function inNode(rows, { workers, rounds }) {
  const furrow = await import(pathToFileURL(join(PKG, "furrow.js")).href);
  furrow.initSync({ module: readFileSync(join(PKG, "furrow_wasm_bg.wasm")) });
  const { PlannerPool } = await import(pathToFileURL(join(PKG, "pool.js")).href);
  const pool = new PlannerPool({ workers });
  globalThis.__plan = furrow.plan;
  globalThis.__pool = pool;
  try {
    const results = [];
    for (const row of rows) results.push(await timeBoth({ field: readField(row.file), options: row.options, rounds }));
    return results;
  } finally {
    pool.terminate();
  }
}

async function inChromium(rows, { workers, rounds }) {
  const { launchChromium, SITE } = await import(pathToFileURL(join(ROOT, "pkg-tests/support.mjs")).href);
  const { startServer } = await import(pathToFileURL(join(ROOT, "scripts/serve.mjs")).href);
  const server = await startServer(SITE, 0);
  const browser = await launchChromium();
  try {
    const page = await browser.newPage();
    await page.goto(`http://127.0.0.1:${server.address().port}/fields/index.json`);
    await page.evaluate(
      async ({ workers }) => {
        const furrow = await import("/pkg/furrow.js");
        await furrow.default();
        const { PlannerPool } = await import("/pkg/pool.js");
        window.__plan = furrow.plan;
        window.__pool = new PlannerPool({ workers });
      },
      { workers },
    );
    const results = [];
    for (const row of rows) {
      results.push(await page.evaluate(timeBoth, { field: readField(row.file), options: row.options, rounds }));
    }
    return results;
  } finally {
    await browser.close();
    server.close();
  }
}

const args = parseArgs(process.argv.slice(2));
const rows = corpusRows(fail);
if (args.only !== "chromium") report("Node", rows, await inNode(rows, args), args.workers);
if (args.only !== "node") report("Chromium", rows, await inChromium(rows, args), args.workers);
