// The benchmark corpus as the scripts see it: the table of tests/fields/README.md (file, area,
// and the suggested width, headland passes and turning radius as plan() options).
import { existsSync, readFileSync } from "node:fs";
import { join } from "node:path";
import { fileURLToPath } from "node:url";

export const FIELDS = fileURLToPath(new URL("../tests/fields", import.meta.url));

/** The corpus table's rows; `fail(message)` is called (and must throw) on a broken table. */
export function corpusRows(fail) {
  const readme = join(FIELDS, "README.md");
  if (!existsSync(readme)) fail("tests/fields/README.md is missing: no corpus table to run");
  const rows = [];
  for (const line of readFileSync(readme, "utf8").split("\n")) {
    const c = line.split("|").map((s) => s.trim());
    if (c.length >= 10 && c[1].endsWith(".geojson")) {
      const row = {
        file: c[1],
        areaHa: +c[2],
        options: { width: +c[6], headlandPasses: +c[7], turnRadius: +c[8] },
      };
      if (!existsSync(join(FIELDS, row.file))) fail(`tests/fields/${row.file} (in the corpus table) is missing`);
      if (![row.areaHa, ...Object.values(row.options)].every(Number.isFinite)) {
        fail(`the corpus table's row for ${row.file} has a column that is not a number`);
      }
      rows.push(row);
    }
  }
  if (rows.length === 0) fail("tests/fields/README.md has no corpus table rows");
  return rows;
}

/** A corpus field's GeoJSON, parsed. */
export const readField = (file) => JSON.parse(readFileSync(join(FIELDS, file), "utf8"));
