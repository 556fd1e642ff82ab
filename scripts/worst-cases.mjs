// Time and memory of the worst cases of tests/termination.rs in the built npm package (pkg/), in
// Node: each case in its own Node process, so that each starts with a fresh wasm memory.
//
//   FURROW_WORST_CASES=DIR cargo test --release --test termination -- --ignored write_cases
//   node scripts/worst-cases.mjs DIR
//
// Prints, for each case, how it ended (planned, with its swaths, or the error's code), the time
// of plan() as called from JavaScript (building the JS result included), the wasm memory at the
// end (a wasm memory only grows, so this is its peak) and the process's peak resident memory.
import { spawnSync } from "node:child_process";
import { readdirSync, readFileSync } from "node:fs";
import { join } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const ROOT = fileURLToPath(new URL("..", import.meta.url));
const PKG = join(ROOT, "pkg");
const [dir, only] = process.argv.slice(2);
if (!dir) {
  console.error("usage: node scripts/worst-cases.mjs DIR (written by the termination test's write_cases)");
  process.exit(2);
}

if (only) {
  // A child: plans one case and prints one line of JSON.
  const furrow = await import(pathToFileURL(join(PKG, "furrow.js")).href);
  const exports = furrow.initSync({ module: readFileSync(join(PKG, "furrow_wasm_bg.wasm")) });
  const field = readFileSync(join(dir, `${only}.geojson`), "utf8");
  const options = JSON.parse(readFileSync(join(dir, `${only}.json`), "utf8"));
  const started = performance.now();
  let outcome;
  try {
    const plan = furrow.plan(field, options);
    outcome = `planned: ${plan.summary.swath_count} swaths`;
  } catch (e) {
    outcome = `refused: ${e.code ?? e.message}`;
  }
  const ms = performance.now() - started;
  const wasmMB = exports.memory.buffer.byteLength / 2 ** 20;
  const rssMB = process.resourceUsage().maxRSS / 1024;
  console.log(JSON.stringify({ outcome, ms, wasmMB, rssMB }));
} else {
  const cases = readdirSync(dir)
    .filter((f) => f.endsWith(".json"))
    .map((f) => f.slice(0, -5))
    .sort();
  console.log("| case | outcome | time in Node | wasm memory | peak resident |");
  console.log("|---|---|---:|---:|---:|");
  for (const name of cases) {
    const child = spawnSync(process.execPath, ["--max-old-space-size=4096", fileURLToPath(import.meta.url), dir, name], {
      encoding: "utf8",
      timeout: 120_000,
    });
    const line = child.stdout.trim().split("\n").at(-1);
    let row;
    try {
      const r = JSON.parse(line);
      row = [r.outcome, `${(r.ms / 1000).toFixed(2)} s`, `${r.wasmMB.toFixed(0)} MB`, `${r.rssMB.toFixed(0)} MB`];
    } catch {
      row = [`failed (${child.signal ?? child.status}): ${(child.stderr || "").trim().split("\n").at(-1)}`, "", "", ""];
    }
    console.log(`| ${name} | ${row.join(" | ")} |`);
  }
}
