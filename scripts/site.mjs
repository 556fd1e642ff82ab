// Assembles the viewer site in target/site: the page (www/), the wasm package (pkg/) and the
// corpus fields (tests/fields/*.geojson) with an index of their suggested machine settings. The
// page keeps its Content-Security-Policy meta tag (checked here).
//
//   node scripts/site.mjs   (after the package is built into pkg/)
import { cp, mkdir, readdir, readFile, rm, writeFile } from "node:fs/promises";
import { join } from "node:path";
import { metaPolicy } from "./serve.mjs";

const out = "target/site";
await rm(out, { recursive: true, force: true });
await mkdir(join(out, "fields"), { recursive: true });
await cp("www", out, { recursive: true });
// The page must carry its Content-Security-Policy (serve.mjs sends the same as a header).
if (!metaPolicy(await readFile(join(out, "index.html"), "utf8"))) {
  throw new Error("site: www/index.html has no Content-Security-Policy meta tag");
}
await cp("pkg", join(out, "pkg"), { recursive: true });

// The README table: | file | area ha | vertices | obstacles | prohibited | width m | passes | radius m | note |
const readme = await readFile("tests/fields/README.md", "utf8");
const fields = [];
for (const line of readme.split("\n")) {
  const cells = line.split("|").map((c) => c.trim());
  if (cells.length < 10 || !cells[1].endsWith(".geojson")) continue;
  const file = cells[1];
  await cp(join("tests/fields", file), join(out, "fields", file));
  fields.push({
    name: file.replace(/\.geojson$/, ""),
    file: `fields/${file}`,
    areaHa: Number(cells[2]),
    width: Number(cells[6]),
    headlandPasses: Number(cells[7]),
    turnRadius: Number(cells[8]),
    note: cells[9],
  });
}
const names = new Set(fields.map((f) => f.name));
for (const f of await readdir("tests/fields")) {
  if (f.endsWith(".geojson") && !names.has(f.replace(/\.geojson$/, ""))) {
    console.warn(`site: ${f} is not in the fields README table; left out of the viewer`);
  }
}
await writeFile(join(out, "fields", "index.json"), JSON.stringify(fields, null, 1) + "\n");

// What the service worker (sw.js) caches for offline use: every file of the site.
const files = [];
async function walk(dir, prefix) {
  for (const entry of await readdir(dir, { withFileTypes: true })) {
    const path = prefix ? `${prefix}/${entry.name}` : entry.name;
    if (entry.isDirectory()) await walk(join(dir, entry.name), path);
    else if (path !== "sw.js" && path !== "precache.json" && !path.endsWith(".d.ts") && !path.endsWith(".md") && !path.includes("/LICENSE-")) files.push(path);
  }
}
await walk(out, "");
files.sort();
await writeFile(join(out, "precache.json"), JSON.stringify({ files }, null, 1) + "\n");
console.log(`site: ${out} with ${fields.length} fields, ${files.length} files for offline use`);
