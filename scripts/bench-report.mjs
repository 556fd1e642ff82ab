// Assembles target/bench/report.md from what scripts/bench.sh measured:
//   target/bench/{quality,stages,scaling,wasm}.json (examples/report/, scripts/bench-wasm.mjs)
//   target/criterion/plan/<field>/new/estimates.json (cargo bench --bench plan)
//   target/criterion/stage-<stage>/<field>/new/estimates.json (cargo bench --bench stages)
//
//   node scripts/bench-report.mjs
import { existsSync, readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import os from "node:os";

const DIR = "target/bench";
const read = (name) => {
  const path = join(DIR, name);
  if (!existsSync(path)) throw new Error(`${path} is missing: run scripts/bench.sh`);
  return JSON.parse(readFileSync(path, "utf8"));
};
const readText = (name) => readFileSync(join(DIR, name), "utf8");
// A part written on its own (it keeps its title there) as a section of the report, under the
// report's own heading: its first line, if a title, is left out.
const section = (name) => readText(name).replace(/^# [^\n]*\n+/, "");

const quality = read("quality.json").fields;
const stages = read("stages.json").fields;
const scaling = read("scaling.json");
const wasm = read("wasm.json");

/** Criterion's median (ms) of a benchmark in `group`, by field name, where it was run. */
function criterion(name, group = "plan") {
  const path = join("target/criterion", group, name, "new/estimates.json");
  if (!existsSync(path)) return null;
  const e = JSON.parse(readFileSync(path, "utf8"));
  return e.median.point_estimate / 1e6;
}
const STAGE_BENCHES = ["validation", "route", "path", "output"];

const byName = (list) => new Map(list.map((r) => [String(r.field).replace(/\.geojson$/, ""), r]));
const node = byName(wasm.node);
const chromium = byName(wasm.chromium);
const stage = byName(stages);
const f = (v, d = 1) => (Number.isFinite(v) ? v.toFixed(d) : "–");
const kb = (b) => `${Math.round(b / 1000)} KB`;

const rows = quality.map((q) => {
  const name = q.field;
  return {
    name,
    ha: q.field_area_ha,
    native: criterion(name),
    stagesTotal: stage.get(name)?.totalMs,
    node: node.get(name),
    chromium: chromium.get(name),
    q,
  };
});

// The targets of issue 11, as measured.
const small = rows.filter((r) => r.ha <= 60 && r.chromium);
const slowSmall = small.filter((r) => r.chromium.medianMs > 16);
const large = rows.find((r) => r.name.startsWith("large"));
const auto = scaling.series.find((s) => s.decomposition === "auto") ?? scaling.series[0];
const targets = [
  [
    "whole plan under 16 ms median in headless Chromium, every corpus field up to 60 ha",
    slowSmall.length === 0,
    `${small.length - slowSmall.length} of ${small.length} fields; slowest ${f(Math.max(...small.map((r) => r.chromium.medianMs)))} ms`,
  ],
  ["the 210 ha field under 50 ms in headless Chromium", (large?.chromium?.medianMs ?? Infinity) < 50, `${f(large?.chromium?.medianMs)} ms`],
  [
    "time growing no faster than the number of swaths",
    auto.fit_swaths.slope <= 1,
    `time ~ swaths^${f(auto.fit_swaths.slope, 2)}, ~ area^${f(auto.fit_area.slope, 2)}`,
  ],
  ["wasm under 400 KB gzip", wasm.wasm.gzipBytes < 400 * 1000, `${kb(wasm.wasm.gzipBytes)} gzip, ${kb(wasm.wasm.rawBytes)} raw`],
];

const m = wasm.machine;
let md = `# furrow benchmark report

Measured ${new Date().toISOString().slice(0, 10)} on ${m.cpus} cores (${m.cpu}${os.totalmem() ? `, ${Math.round(os.totalmem() / 2 ** 30)} GB` : ""}), Node ${m.node}, Chromium ${m.chromium}.
Settings per field from \`tests/fields/README.md\` (width, headland passes, turning radius), every other option at its default (\`decomposition: auto\`).
Rerun: \`./scripts/bench.sh\`.

## Targets

| target | met | measured |
|---|---|---|
${targets.map(([t, ok, v]) => `| ${t} | ${ok ? "yes" : "**no**"} | ${v} |`).join("\n")}

## Summary

Whole \`plan()\`: natively (criterion median, release), and through the wasm package from JavaScript in Node and in headless Chromium's main thread (median and 95th percentile over repeated runs after warm-up, including building the result's GeoJSON object and typed-array samples). Estimated time and extra driving (Oksanen: total distance against area / width) from the plan.

| field | ha | native ms | Node median / p95 ms | Chromium median / p95 ms | swaths | est. time min | extra driving % |
|---|---:|---:|---:|---:|---:|---:|---:|
${rows
  .map(
    (r) =>
      `| ${r.name} | ${f(r.ha, 1)} | ${f(r.native ?? r.stagesTotal, 2)} | ${f(r.node?.medianMs)} / ${f(r.node?.p95Ms)} | ${f(r.chromium?.medianMs)} / ${f(r.chromium?.p95Ms)} | ${r.q.swath_count} | ${f(r.q.estimated_time_min)} | ${f(r.q.extra_driving_pct)} |`,
  )
  .join("\n")}

## Stages

${section("stages.md")}
The stages that run alone, natively (criterion median, \`benches/stages.rs\`), milliseconds: reading, checking and simplifying the field, and, from the finished plan, the route, the path and the GeoJSON text of the decomposition auto chose (once, where the stage clocks above count every candidate auto compares).

| field | ${STAGE_BENCHES.join(" | ")} |
|---|${STAGE_BENCHES.map(() => "---:").join("|")}|
${rows.map((r) => `| ${r.name} | ${STAGE_BENCHES.map((st) => f(criterion(r.name, `stage-${st}`), 3)).join(" | ")} |`).join("\n")}

## Scaling

${section("scaling.md")}

## Memory and size

- wasm memory after loading: ${kb(wasm.memory.afterInitBytes)}; after planning the largest field (${wasm.memory.largestField}): ${kb(wasm.memory.afterLargestBytes)} (wasm memory only grows: this is the peak).
- after ${wasm.memory.plans.toLocaleString("en")} consecutive plans of ${wasm.memory.leakField} in one instance: ${kb(wasm.memory.after10000Bytes)} (after 1,000: ${kb(wasm.memory.after1000Bytes)}; ${wasm.memory.grew ? "**it grew**" : "no growth"}).
- \`furrow_wasm_bg.wasm\`: ${wasm.wasm.rawBytes.toLocaleString("en")} bytes, ${wasm.wasm.gzipBytes.toLocaleString("en")} gzipped.

## Plan quality

${section("quality.md")}
Pictures of every plan: [plans.md](plans.md).
`;
writeFileSync(join(DIR, "report.md"), md);
console.log(`wrote ${join(DIR, "report.md")}`);
console.log(targets.map(([t, ok, v]) => `${ok ? "met    " : "NOT met"}  ${t}: ${v}`).join("\n"));
