// Speed, memory and size of the built npm package (pkg/), in Node and in headless Chromium.
//
//   node scripts/bench-wasm.mjs [--quick]
//
// For every field of the corpus table (tests/fields/README.md) with its suggested width, headland
// passes and turning radius, times plan(field, options) as called from JavaScript: the time
// includes building the JS result (the GeoJSON object and the typed arrays of `samples`);
// `summary.planning_ms` (the time inside the planner) is recorded beside it, so the cost of the
// conversion shows. Then the wasm memory (after init, after the largest field, after many plans
// in one instance: a leak check) and the size of the .wasm (raw and gzipped).
// Writes target/bench/wasm.json and prints a table. Needs pkg/ (scripts/build.sh) and, for the
// browser part, Debian's chromium (or CHROMIUM=/path) with playwright-core from node_modules.
import { existsSync, mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { cpus } from "node:os";
import { join } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";
import { gzipSync } from "node:zlib";
import { corpusRows, readField } from "./corpus.mjs";

const ROOT = fileURLToPath(new URL("..", import.meta.url));
const PKG = join(ROOT, "pkg");
const OUT_DIR = join(ROOT, "target/bench");
const OUT = join(OUT_DIR, "wasm.json");

const QUICK = process.argv.includes("--quick");
const WARMUP = 5;
const N = QUICK ? 8 : 30; // timed calls per field
const N_SLOW = QUICK ? 3 : 10; // ... for fields whose single call takes longer than SLOW_MS
const SLOW_MS = 200;
const LEAK_PLANS = QUICK ? 1000 : 10000;
const LEAK_CHECKPOINT = 1000;
const LEAK_FIELD = "square-1ha.geojson";

class BenchError extends Error {}
const fail = (message) => {
  throw new BenchError(message);
};
const log = (message) => process.stderr.write(`${message}\n`);

// ---- statistics -------------------------------------------------------------------------------

function median(values) {
  const s = [...values].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
}

/** The nearest-rank percentile: the smallest value with at least p% of the values at or below. */
function percentile(values, p) {
  const s = [...values].sort((a, b) => a - b);
  return s[Math.max(0, Math.ceil((p / 100) * s.length) - 1)];
}

const round = (x, digits = 3) => (x == null ? x : Math.round(x * 10 ** digits) / 10 ** digits);

function stats(row, { times, planner }) {
  return {
    field: row.file,
    areaHa: row.areaHa,
    n: times.length,
    medianMs: round(median(times)),
    p95Ms: round(percentile(times, 95)),
    plannerMedianMs: round(median(planner)),
  };
}

// ---- inputs -----------------------------------------------------------------------------------

function checkPackage() {
  for (const file of ["furrow.js", "furrow_wasm.js", "furrow_wasm_bg.wasm"]) {
    if (!existsSync(join(PKG, file))) {
      fail(`pkg/${file} is missing: build the package first with scripts/build.sh`);
    }
  }
}

/** The corpus README's table: file, area, width, headland passes, turning radius. */
const corpus = () => corpusRows(fail);

// ---- the timing loop (also run in the page: it must not use anything from this module) ---------

/** Warms up, then times plan() calls; fewer calls for slow fields. */
function timePlans(plan, field, options, cfg) {
  let last = 0;
  for (let i = 0; i < cfg.warmup; i++) {
    const t = performance.now();
    plan(field, options);
    last = performance.now() - t;
  }
  const n = last > cfg.slowMs ? cfg.nSlow : cfg.n;
  const times = [];
  const planner = [];
  for (let i = 0; i < n; i++) {
    const t = performance.now();
    const result = plan(field, options);
    times.push(performance.now() - t);
    planner.push(result.summary.planning_ms);
  }
  return { times, planner };
}

const TIMING = { warmup: WARMUP, n: N, nSlow: N_SLOW, slowMs: SLOW_MS };

/** Before any timing: every field once, then the first 50 times, so the wasm code is tiered up. */
function warmEngine(plan, cases) {
  for (const { field, options } of cases) plan(field, options);
  for (let i = 0; i < 50; i++) plan(cases[0].field, cases[0].options);
}

// ---- Node -------------------------------------------------------------------------------------

async function loadNode() {
  const furrow = await import(pathToFileURL(join(PKG, "furrow.js")).href);
  // initSync returns the wasm exports; called again it returns the current instance's exports
  // (the wrapper replaces the instance after a trap), so memory is always read from the live one.
  furrow.initSync({ module: readFileSync(join(PKG, "furrow_wasm_bg.wasm")) });
  const exports = () => furrow.initSync();
  if (!(exports()?.memory instanceof WebAssembly.Memory)) {
    fail("the package's initSync did not return the wasm exports with their memory");
  }
  return { furrow, exports };
}

function memoryBench({ furrow, exports }, rows) {
  const bytes = () => exports().memory.buffer.byteLength;
  const externrefs = () => exports().__wbindgen_externrefs?.length ?? null;
  const afterInitBytes = bytes();

  const largest = rows.reduce((a, b) => (b.areaHa > a.areaHa ? b : a));
  log(`memory: planning the largest field, ${largest.file}, once`);
  furrow.plan(readField(largest.file), largest.options);
  const afterLargestBytes = bytes();

  const small = rows.find((r) => r.file === LEAK_FIELD) ?? rows.reduce((a, b) => (b.areaHa < a.areaHa ? b : a));
  const field = readField(small.file);
  log(`memory: ${LEAK_PLANS} consecutive plans of ${small.file}`);
  const start = performance.now();
  let after1000Bytes = null;
  let after1000Refs = null;
  for (let i = 1; i <= LEAK_PLANS; i++) {
    furrow.plan(field, small.options);
    if (i === LEAK_CHECKPOINT) {
      after1000Bytes = bytes();
      after1000Refs = externrefs();
    }
    if (i % 1000 === 0 && i < LEAK_PLANS) log(`  ${i} plans, ${((performance.now() - start) / 1000).toFixed(0)} s`);
  }
  const afterAllBytes = bytes();
  const afterAllRefs = externrefs();
  const checked = LEAK_PLANS > LEAK_CHECKPOINT;
  return {
    afterInitBytes,
    afterLargestBytes,
    largestField: largest.file,
    after1000Bytes,
    // After LEAK_PLANS plans; with --quick that is plan 1,000 itself, so there is nothing to compare.
    after10000Bytes: checked ? afterAllBytes : null,
    plans: LEAK_PLANS,
    leakField: small.file,
    grew: checked ? afterAllBytes > after1000Bytes : null,
    externrefTable: { after1000: after1000Refs, [`after${LEAK_PLANS}`]: afterAllRefs },
    leakSeconds: round((performance.now() - start) / 1000, 1),
  };
}

function nodeBench({ furrow }, rows) {
  const fields = rows.map((row) => readField(row.file));
  warmEngine(furrow.plan, rows.map((row, i) => ({ field: fields[i], options: row.options })));
  const results = [];
  for (const [i, row] of rows.entries()) {
    const r = stats(row, timePlans(furrow.plan, fields[i], row.options, TIMING));
    log(`node     ${row.file.padEnd(34)} n=${String(r.n).padStart(2)}  median ${r.medianMs.toFixed(1)} ms`);
    results.push(r);
  }
  return results;
}

// ---- Chromium ---------------------------------------------------------------------------------

/** playwright-core and the browser, checked before the long Node part runs. */
async function loadBrowserSupport() {
  let support;
  try {
    support = await import(pathToFileURL(join(ROOT, "pkg-tests/support.mjs")).href);
  } catch (e) {
    fail(`cannot load playwright-core (run npm install in ${ROOT}): ${firstLine(e)}`);
  }
  let path;
  try {
    path = support.chromiumPath();
  } catch (e) {
    fail(firstLine(e));
  }
  if (!existsSync(path)) fail(`chromium not found at ${path} (apt-get install chromium, or set CHROMIUM=/path/to/chrome)`);
  return support;
}

async function chromiumBench(support, rows) {
  const { startServer } = await import(pathToFileURL(join(ROOT, "scripts/serve.mjs")).href);

  const server = await startServer(ROOT, 0);
  const base = `http://127.0.0.1:${server.address().port}/`;
  let browser;
  try {
    try {
      browser = await support.launchChromium();
    } catch (e) {
      fail(`cannot start headless Chromium: ${firstLine(e)}`);
    }
    const version = browser.version();
    const page = await browser.newPage();
    const pageErrors = [];
    page.on("pageerror", (e) => pageErrors.push(e.message));
    // Any page of the origin will do: the package and the fields are fetched from it.
    await page.goto(`${base}pkg/package.json`);
    try {
      await page.evaluate(async (url) => {
        const m = await import(url);
        await m.default();
        window.__furrow = m;
      }, `${base}pkg/furrow.js`);
    } catch (e) {
      fail(`the package does not load in Chromium: ${firstLine(e)}`);
    }

    // The fields, fetched once; then the same engine warm-up as in Node (V8 tiers wasm functions
    // up to optimized code only once they have run a while, so the first field would pay for it).
    await page.evaluate(
      async ({ urls, rows, source, warmSource }) => {
        window.__fields = await Promise.all(urls.map(async (u) => (await fetch(u)).json()));
        window.__timePlans = (0, eval)(`(${source})`);
        const warmEngine = (0, eval)(`(${warmSource})`);
        warmEngine(window.__furrow.plan, window.__fields.map((field, i) => ({ field, options: rows[i].options })));
      },
      { urls: rows.map((r) => `${base}tests/fields/${r.file}`), rows, source: timePlans.toString(), warmSource: warmEngine.toString() },
    );

    const results = [];
    for (const [i, row] of rows.entries()) {
      const measured = await page.evaluate(
        ({ i, options, cfg }) => window.__timePlans(window.__furrow.plan, window.__fields[i], options, cfg),
        { i, options: row.options, cfg: TIMING },
      );
      const r = stats(row, measured);
      log(`chromium ${row.file.padEnd(34)} n=${String(r.n).padStart(2)}  median ${r.medianMs.toFixed(1)} ms`);
      results.push(r);
    }
    if (pageErrors.length) log(`chromium page errors: ${pageErrors.join("; ")}`);
    return { version, results };
  } finally {
    await browser?.close();
    server.closeAllConnections?.();
    await new Promise((ok) => server.close(ok));
  }
}

const firstLine = (e) => String(e?.message ?? e).split("\n").find((l) => l.trim()) ?? String(e);

// ---- report -----------------------------------------------------------------------------------

function table(node, chromium) {
  const byField = new Map(chromium.map((r) => [r.field, r]));
  const ms = (r) => (r ? `${r.medianMs.toFixed(1)} / ${r.p95Ms.toFixed(1)}` : "-");
  const header = ["field", "area ha", "node ms median / p95", "(planner)", "chromium ms median / p95", "(planner)"];
  const lines = node.map((r) => {
    const c = byField.get(r.field);
    return [
      r.field.replace(/\.geojson$/, ""),
      r.areaHa.toFixed(2),
      ms(r),
      r.plannerMedianMs.toFixed(1),
      ms(c),
      c ? c.plannerMedianMs.toFixed(1) : "-",
    ];
  });
  const widths = header.map((h, i) => Math.max(h.length, ...lines.map((l) => l[i].length)));
  const fmt = (cells) => cells.map((c, i) => (i === 0 ? c.padEnd(widths[i]) : c.padStart(widths[i]))).join("  ");
  return [fmt(header), widths.map((w) => "-".repeat(w)).join("  "), ...lines.map(fmt)].join("\n");
}

const mib = (b) => (b == null ? "-" : `${(b / 2 ** 20).toFixed(2)} MiB`);

async function main() {
  const started = performance.now();
  checkPackage();
  const rows = corpus();
  log(`furrow wasm bench${QUICK ? " (--quick)" : ""}: ${rows.length} fields, ${N} calls each (${N_SLOW} if one takes > ${SLOW_MS} ms)`);

  const wasmBytes = readFileSync(join(PKG, "furrow_wasm_bg.wasm"));
  const wasm = { rawBytes: wasmBytes.length, gzipBytes: gzipSync(wasmBytes, { level: 9 }).length };

  const support = await loadBrowserSupport();
  const loaded = await loadNode();
  const memory = memoryBench(loaded, rows); // first, so "after init" is a fresh instance
  const node = nodeBench(loaded, rows);
  const browser = await chromiumBench(support, rows);

  const cpuList = cpus();
  const result = {
    machine: {
      node: process.version,
      chromium: browser.version,
      cpus: cpuList.length,
      cpu: cpuList[0]?.model ?? "unknown",
    },
    date: new Date().toISOString(),
    quick: QUICK,
    node,
    chromium: browser.results,
    memory,
    wasm,
  };
  mkdirSync(OUT_DIR, { recursive: true });
  writeFileSync(OUT, `${JSON.stringify(result, null, 2)}\n`);

  console.log(table(node, browser.results));
  console.log();
  console.log(`memory: after init ${mib(memory.afterInitBytes)}, after ${memory.largestField} ${mib(memory.afterLargestBytes)}`);
  console.log(
    `        after ${LEAK_CHECKPOINT} plans of ${memory.leakField} ${mib(memory.after1000Bytes)}` +
      (memory.after10000Bytes == null
        ? " (leak check between plan 1,000 and 10,000 skipped with --quick)"
        : `, after ${memory.plans} ${mib(memory.after10000Bytes)}: ${memory.grew ? "GREW (leak?)" : "no growth"}`),
  );
  console.log(`wasm:   ${wasm.rawBytes} bytes, ${wasm.gzipBytes} gzipped (level 9)`);
  console.log(`${process.version}, Chromium ${browser.version}, ${result.machine.cpus} × ${result.machine.cpu}`);
  console.log(`wrote ${OUT} in ${((performance.now() - started) / 1000).toFixed(0)} s`);
}

main().catch((e) => {
  console.error(`bench-wasm: ${e instanceof BenchError ? e.message : firstLine(e)}`);
  process.exit(1);
});
