// Two builds of the package compared on the corpus, interleaved: in Node and in headless
// Chromium, the two packages loaded side by side and plan() called on each in turn, so that
// the machine's drift (up to 40 % between minutes on a shared machine) falls on both alike.
// Also checks that both give the same plan for every field (GeoJSON and samples, clocks left
// out): a speed change that keeps the plans says so here.
//
//   node scripts/bench-compare.mjs OLD_PKG NEW_PKG [--rounds N] [--fields a,b,...] [--only node|chromium]
//
// OLD_PKG and NEW_PKG are directories built like pkg/ (scripts/build.sh; copy pkg/ aside before
// building the other version). Each round plans a field three times with each package; the
// table gives each package's median over all rounds and their ratio, new over old. Not part of
// the tests or of scripts/bench.sh.
import { cpSync, existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { basename, join, resolve } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";
import { FIELDS, corpusRows, readField } from "./corpus.mjs";

const ROOT = fileURLToPath(new URL("..", import.meta.url));
const USAGE =
  "usage: node scripts/bench-compare.mjs OLD_PKG NEW_PKG [--rounds N] [--fields a,b,...] [--only node|chromium]";

function fail(message) {
  process.stderr.write(`bench-compare: ${message}\n${USAGE}\n`);
  process.exit(2);
}

function parseArgs(argv) {
  const args = { packages: [], rounds: 7, fields: null, only: null };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (a === "--rounds") args.rounds = Number(argv[++i]);
    else if (a === "--fields") args.fields = (argv[++i] ?? "").split(",").filter(Boolean);
    else if (a === "--only") args.only = argv[++i];
    else if (a === "--help" || a === "-h") {
      process.stdout.write(`${USAGE}\n`);
      process.exit(0);
    } else if (a.startsWith("--")) fail(`unknown option ${a}`);
    else args.packages.push(resolve(a));
  }
  if (args.packages.length !== 2) fail("give two package directories");
  for (const p of args.packages) {
    if (!existsSync(join(p, "furrow.js")) || !existsSync(join(p, "furrow_wasm_bg.wasm"))) {
      fail(`${p} is not a built package (furrow.js and furrow_wasm_bg.wasm)`);
    }
  }
  if (!(Number.isInteger(args.rounds) && args.rounds > 0)) fail("--rounds takes a whole number above 0");
  if (args.only && !["node", "chromium"].includes(args.only)) fail("--only takes node or chromium");
  return args;
}

// ---- run in Node and in the page alike: nothing from this module's scope --------------------

/** Times the packages on one field, interleaved; returns each one's times and its plan's text. */
function compareOn(plans, field, options, rounds) {
  // What a plan is, for the comparison: every feature and figure and every sample, not the
  // clocks. "yes" where all of it is the same; else, where only positions differ (the
  // coordinates of the features and the samples' x and y) and by at most a micrometre's worth,
  // the largest difference, as a change in the projection's last digits gives; else "NO".
  const clockless = (key, value) => (key.endsWith("_ms") || key.endsWith("Ms") ? undefined : value);
  const fingerprint = (result) => {
    const { samples, ...geojson } = result;
    const text = JSON.stringify(geojson, clockless);
    const columns = Object.entries(samples).map(([name, column]) => `${name}:${Array.from(column).join(",")}`);
    return `${text}\n${columns.join("\n")}`;
  };
  const positionsApart = (a, b) => {
    let most = 0;
    const walk = (x, y, position) => {
      if (typeof x === "number" && typeof y === "number") {
        if (x === y) return true;
        if (!position) return false;
        most = Math.max(most, Math.abs(x - y));
        return true;
      }
      if (ArrayBuffer.isView(x) && ArrayBuffer.isView(y)) {
        return x.length === y.length && Array.from(x).every((v, i) => walk(v, y[i], position));
      }
      if (Array.isArray(x) && Array.isArray(y)) {
        return x.length === y.length && x.every((v, i) => walk(v, y[i], position));
      }
      if (x && y && typeof x === "object" && typeof y === "object") {
        const keys = Object.keys(x).filter((k) => clockless(k, 0) !== undefined);
        if (keys.length !== Object.keys(y).filter((k) => clockless(k, 0) !== undefined).length) return false;
        return keys.every((k) => walk(x[k], y[k], position || k === "coordinates" || k === "x" || k === "y"));
      }
      return x === y;
    };
    return walk(a, b, false) && most <= 1e-8 ? most : null;
  };
  const [first, second] = [plans[0](field, options), plans[1](field, options)];
  let same = "yes";
  if (fingerprint(first) !== fingerprint(second)) {
    const apart = positionsApart(first, second);
    same = apart === null ? "NO" : `positions within ${apart.toExponential(1)}`;
  }
  for (let i = 0; i < 4; i++) for (const plan of plans) plan(field, options);
  const times = plans.map(() => []);
  for (let round = 0; round < rounds; round++) {
    for (let k = 0; k < plans.length; k++) {
      for (let i = 0; i < 3; i++) {
        const t0 = performance.now();
        plans[k](field, options);
        times[k].push(performance.now() - t0);
      }
    }
  }
  return { times, same };
}

/** Every field planned twice by each package first: V8 tiers wasm code up only after a while. */
function warmUp(plans, cases) {
  for (let i = 0; i < 2; i++) for (const { field, options } of cases) for (const plan of plans) plan(field, options);
}

// ---- report -------------------------------------------------------------------------------------

function median(values) {
  const s = [...values].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
}

function report(engine, results) {
  console.log(`\n${engine}: median ms of each package, interleaved; ratio new / old`);
  console.log(`${"field".padEnd(30)} ${"old".padStart(8)} ${"new".padStart(8)}  ratio  same plan`);
  let logSum = 0;
  for (const { file, times, same } of results) {
    const [a, b] = times.map(median);
    logSum += Math.log(b / a);
    const name = basename(file, ".geojson");
    console.log(`${name.padEnd(30)} ${a.toFixed(1).padStart(8)} ${b.toFixed(1).padStart(8)}  ${(b / a).toFixed(3)}  ${same}`);
  }
  const differing = results.filter((r) => r.same === "NO").length;
  const moved = results.filter((r) => r.same.startsWith("positions")).length;
  const plansSaid = differing > 0 ? `${differing} plans differ` : moved > 0 ? `${moved} plans the same but for positions in the last digits` : "every plan the same";
  console.log(`geometric mean of the ratios ${Math.exp(logSum / results.length).toFixed(3)}; ${plansSaid}`);
}

async function inNode(packages, rows, rounds) {
  const plans = [];
  for (const p of packages) {
    const m = await import(pathToFileURL(join(p, "furrow.js")).href);
    m.initSync({ module: readFileSync(join(p, "furrow_wasm_bg.wasm")) });
    plans.push(m.plan);
  }
  const cases = rows.map((row) => ({ field: readField(row.file), options: row.options }));
  warmUp(plans, cases);
  return rows.map((row, i) => ({ file: row.file, ...compareOn(plans, cases[i].field, row.options, rounds) }));
}

async function inChromium(packages, rows, rounds) {
  const support = await import(pathToFileURL(join(ROOT, "pkg-tests/support.mjs")).href);
  const { startServer } = await import(pathToFileURL(join(ROOT, "scripts/serve.mjs")).href);
  // One origin for both packages and the fields: copies in a directory of their own.
  const site = mkdtempSync(join(tmpdir(), "furrow-compare-"));
  packages.forEach((p, k) => cpSync(p, join(site, `package-${k}`), { recursive: true }));
  mkdirSync(join(site, "fields"));
  for (const row of rows) cpSync(join(FIELDS, row.file), join(site, "fields", row.file));
  const server = await startServer(site, 0);
  const base = `http://127.0.0.1:${server.address().port}/`;
  const browser = await support.launchChromium();
  try {
    const page = await browser.newPage();
    await page.goto(`${base}fields/${rows[0].file}`);
    await page.evaluate(
      async ({ modules, source, warmSource, fieldUrls, options }) => {
        window.__plans = [];
        for (const m of modules) {
          const module = await import(m);
          await module.default();
          window.__plans.push(module.plan);
        }
        window.__compareOn = (0, eval)(`(${source})`);
        const fields = await Promise.all(fieldUrls.map(async (u) => (await fetch(u)).json()));
        window.__cases = fields.map((field, i) => ({ field, options: options[i] }));
        (0, eval)(`(${warmSource})`)(window.__plans, window.__cases);
      },
      {
        modules: packages.map((_, k) => `${base}package-${k}/furrow.js`),
        source: compareOn.toString(),
        warmSource: warmUp.toString(),
        fieldUrls: rows.map((row) => `${base}fields/${row.file}`),
        options: rows.map((row) => row.options),
      },
    );
    const results = [];
    for (const [i, row] of rows.entries()) {
      const r = await page.evaluate(
        ({ i, rounds }) => window.__compareOn(window.__plans, window.__cases[i].field, window.__cases[i].options, rounds),
        { i, rounds },
      );
      results.push({ file: row.file, ...r });
    }
    return results;
  } finally {
    await browser.close();
    server.close();
    rmSync(site, { recursive: true, force: true });
  }
}

const args = parseArgs(process.argv.slice(2));
let rows = corpusRows(fail);
if (args.fields) {
  rows = rows.filter((r) => args.fields.includes(basename(r.file, ".geojson")));
  if (rows.length === 0) fail("no corpus field of that name");
}
console.log(`old ${args.packages[0]}\nnew ${args.packages[1]}\n${args.rounds} rounds of 3 plans each`);
if (args.only !== "chromium") report("Node", await inNode(args.packages, rows, args.rounds));
if (args.only !== "node") report("Chromium", await inChromium(args.packages, rows, args.rounds));
