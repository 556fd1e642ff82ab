// The package's TypeScript declarations as a strict TypeScript user sees them: pkg-tests/types/
// usage.ts, and an import of every type the wasm modules declare, compiled with the workspace's
// pinned typescript (`tsc --strict --noEmit`, declarations checked too) against the built pkg/.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { copyFileSync, readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { installLinked, PKG, ROOT } from "./install.mjs";

test("the declarations compile with tsc --strict and export every type", () => {
  const dir = installLinked("types");
  copyFileSync(join(ROOT, "pkg-tests/types/usage.ts"), join(dir, "usage.ts"));
  // Every type each wasm module declares, imported from the package entry that wraps it.
  const typesOf = (file) =>
    [...readFileSync(join(PKG, file), "utf8").matchAll(/^export (?:interface|type) (\w+)/gm)].map((m) => m[1]);
  const types = typesOf("furrow_wasm.d.ts");
  const trackTypes = typesOf("furrow_tracks_wasm.d.ts");
  const formatTypes = typesOf("furrow_formats_wasm.d.ts");
  assert.ok(types.length > 30 && trackTypes.length >= 3);
  writeFileSync(
    join(dir, "every-type.ts"),
    `import type * as Furrow from "furrow";\n` +
      `import type * as Tracks from "furrow/tracks";\n` +
      `import type * as Formats from "furrow/formats";\n` +
      `export type Every = [${[
        ...types.map((t) => `Furrow.${t}`),
        ...trackTypes.map((t) => `Tracks.${t}`),
        ...formatTypes.map((t) => `Formats.${t}`),
      ].join(", ")}];\n`,
  );
  const tsc = join(ROOT, "node_modules/typescript/bin/tsc");
  const args = ["--strict", "--noEmit", "--skipLibCheck", "false", "--target", "es2022"];
  args.push("--module", "nodenext", "--moduleResolution", "nodenext", "usage.ts", "every-type.ts");
  try {
    execFileSync(process.execPath, [tsc, ...args], { cwd: dir, encoding: "utf8", stdio: "pipe" });
  } catch (e) {
    assert.fail(`tsc: ${e.stdout}${e.stderr}`);
  }
});
