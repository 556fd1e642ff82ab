// The built package as a user gets it: packed by npm (so only what package.json's `files` lists)
// and unpacked into node_modules/furrow of a fresh directory under target/pkg-tests/.
import { execFileSync } from "node:child_process";
import { existsSync, mkdirSync, readFileSync, renameSync, rmSync, symlinkSync } from "node:fs";
import { join } from "node:path";
import { fileURLToPath } from "node:url";

export const ROOT = fileURLToPath(new URL("..", import.meta.url));
export const PKG = join(ROOT, "pkg");
export const PKG_URL = new URL("../pkg/", import.meta.url);

/** An entry of the package as built in pkg/ (`furrow.js`, ...), started with its wasm module. */
export async function builtEntry(entry, wasm) {
  if (!existsSync(new URL(entry, PKG_URL))) {
    throw new Error("pkg/ is missing: run scripts/build.sh first");
  }
  const module = await import(new URL(entry, PKG_URL));
  module.initSync({ module: readFileSync(new URL(wasm, PKG_URL)) });
  return module;
}

/** A fresh, empty directory `target/pkg-tests/NAME`. */
export function freshDir(name) {
  const dir = join(ROOT, "target", "pkg-tests", name);
  rmSync(dir, { recursive: true, force: true });
  mkdirSync(dir, { recursive: true });
  return dir;
}

/** A fresh directory with the package packed and unpacked in node_modules/furrow; its files. */
export function installPacked(name) {
  const dir = freshDir(name);
  const [packed] = JSON.parse(
    execFileSync("npm", ["pack", "--json", "--pack-destination", dir, PKG], {
      encoding: "utf8",
      stdio: ["ignore", "pipe", "ignore"],
    }),
  );
  execFileSync("tar", ["-xzf", join(dir, packed.filename), "-C", dir]);
  mkdirSync(join(dir, "node_modules"));
  renameSync(join(dir, "package"), join(dir, "node_modules", "furrow"));
  return { dir, files: packed.files.map((f) => f.path) };
}

/** A fresh directory whose node_modules/furrow is a link to pkg/ (for bundlers and tsc). */
export function installLinked(name) {
  const dir = freshDir(name);
  mkdirSync(join(dir, "node_modules"));
  symlinkSync(PKG, join(dir, "node_modules", "furrow"), "dir");
  return dir;
}

/** The code blocks of a Markdown text in the given language, in order. */
export function codeBlocks(markdown, language) {
  const blocks = [];
  const fence = new RegExp("^```" + language + "\\n([\\s\\S]*?)^```", "gm");
  for (const m of markdown.matchAll(fence)) blocks.push(m[1]);
  return blocks;
}
