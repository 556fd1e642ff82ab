#!/usr/bin/env bash
# Builds the WebAssembly package into pkg/ (npm package "furrow", web target, also loadable in
# Node with initSync) and assembles the viewer site in target/site.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh rust npm

# The package holds four WebAssembly modules built from the same crate, each with one feature
# (Cargo.toml): the planner (furrow_wasm, the package's main entry), the planner with planning
# in shares for the workers of "furrow/pool" (furrow_pool_wasm), the shortest paths along
# a plan's tracks (furrow_tracks_wasm, the "furrow/tracks" entry) and the field files' readers
# (furrow_formats_wasm, "furrow/formats"), so that a page that only plans never loads the
# others' code.
# The dependencies are optimised for size: 23 KB less gzipped (most of it the sorts that
# i_overlay instantiates), no slower in Node within 2 % (at "z" the planner's own code plans 2.3
# times slower, at "s" 1.4 times). The planner's own code at opt-level 2 with LLVM's inlining
# threshold at 45 (its default at opt-level 2 is 225): at 100, 17 KB less gzipped than the
# default and 4 to 8 % faster in Chromium and Node; at 50, 8 KB less again for 1 % more time in
# both (geometric means over the corpus, interleaved: scripts/bench-compare.mjs); at 45, with
# wasm-opt below, 1 KB less than 50 (2026-12-08; the size does not fall steadily with the
# threshold: at 40 the module is 6 KB larger).
# The threshold is passed by `cargo rustc` to this crate alone, so the dependencies keep their
# size-optimised inlining; the whole module's inlining is done there (fat LTO).
# Native builds keep opt-level 3 throughout.
rm -rf pkg
build_module() { # feature, wasm-bindgen output name
  echo "[build] wasm (release): $2"
  cargo rustc --release --target wasm32-unknown-unknown --lib --crate-type cdylib \
    --no-default-features --features "small-alloc,$1" \
    --config 'profile.release.package."*".opt-level="z"' \
    --config 'profile.release.opt-level=2' \
    -- -C llvm-args=-inline-threshold=45
  # furrow_wasm.js is wasm-bindgen's module; furrow.js (js/) wraps it and recreates the instance
  # after a trap, with the reset function wasm-bindgen generates on request.
  # The name section (function names for stack traces, 125 KB) and the producers section are left
  # out of the shipped module.
  wasm-bindgen --target web --out-name "$2" --experimental-reset-state-function \
    --remove-name-section --remove-producers-section \
    --out-dir pkg target/wasm32-unknown-unknown/release/furrow.wasm
  # binaryen's wasm-opt (npm's `binaryen`, package-lock.json) at -O2 on wasm-bindgen's output:
  # 5 KB less gzipped for the planner, 3 KB for the readers, 1.6 KB for the tracks; the corpus
  # plans as fast in Node and Chromium (0.998 and 1.010, interleaved) and every plan the same
  # (2026-12-07). -Os and -Oz leave it 1.6 KB larger gzipped than -O2. Its passes run until they
  # change nothing more (--converge), then code folding and block merging: 1.5 KB less for the
  # planner than -O2 once (2026-12-08). The features are those rustc emits for
  # wasm32-unknown-unknown; a module using any other fails to validate here.
  echo "[build] wasm-opt -O2 --converge: $2"
  node_modules/.bin/wasm-opt -O2 --converge --code-folding --merge-blocks --enable-bulk-memory --enable-nontrapping-float-to-int \
    --enable-sign-ext --enable-mutable-globals --enable-reference-types --enable-multivalue \
    "pkg/$2_bg.wasm" -o "pkg/$2_bg.wasm"
}
build_module planner-api furrow_wasm
build_module pool-api furrow_pool_wasm
build_module tracks-api furrow_tracks_wasm
build_module formats-api furrow_formats_wasm
# proj4rs compiles its own JavaScript API (Point, Projection, transform, add_nadgrid) into every
# wasm32 module that links it. formats.js does not export it; its declarations (whose
# [Symbol.dispose] needs TypeScript's esnext library) are taken out of the module's .d.ts.
node -e '
  const fs = require("fs");
  const file = "pkg/furrow_formats_wasm.d.ts";
  let dts = fs.readFileSync(file, "utf8");
  dts = dts.replace(/^export class (Point|Projection) \{[^}]*\}\n/gm, "");
  dts = dts.replace(/^export function (add_nadgrid|transform)\(.*\n/gm, "");
  if (/export class|Symbol\.dispose/.test(dts)) throw new Error(file + ": a class of proj4rs is left");
  fs.writeFileSync(file, dts);
'
cp js/furrow.js js/furrow.d.ts js/pool.js js/pool.d.ts js/pool-worker.js js/tracks.js js/tracks.d.ts js/formats.js js/formats.d.ts js/load.js LICENSE-MIT LICENSE-APACHE pkg/
# Debian's wasm-opt (binaryen 108) produces a module that fails to load: only npm's (above) is used.

version=$(awk -F'"' '/^version = / { print $2; exit }' Cargo.toml)
# The repository's address, from Cargo.toml's `repository` when it has one.
repository=$(awk -F'"' '/^repository = / { print $2; exit }' Cargo.toml)
repository_json=""
if [ -n "$repository" ]; then
  repository_json="\"repository\": { \"type\": \"git\", \"url\": \"git+$repository.git\" },"
fi
# engines: the oldest Node the package tests pass on (pkg-tests/node.test.mjs with Node 18.20).
cat > pkg/package.json <<JSON
{
  "name": "furrow",
  "version": "$version",
  "description": "Coverage path planning for farm machines, in WebAssembly: headland passes, swaths, blocks, routes and paths from a GeoJSON field",
  "license": "MIT OR Apache-2.0",
  $repository_json
  "type": "module",
  "main": "furrow.js",
  "module": "furrow.js",
  "types": "furrow.d.ts",
  "exports": {
    ".": { "types": "./furrow.d.ts", "default": "./furrow.js" },
    "./pool": { "types": "./pool.d.ts", "default": "./pool.js" },
    "./tracks": { "types": "./tracks.d.ts", "default": "./tracks.js" },
    "./formats": { "types": "./formats.d.ts", "default": "./formats.js" },
    "./furrow_wasm_bg.wasm": "./furrow_wasm_bg.wasm",
    "./furrow_pool_wasm_bg.wasm": "./furrow_pool_wasm_bg.wasm",
    "./furrow_tracks_wasm_bg.wasm": "./furrow_tracks_wasm_bg.wasm",
    "./furrow_formats_wasm_bg.wasm": "./furrow_formats_wasm_bg.wasm",
    "./package.json": "./package.json"
  },
  "files": ["furrow.js", "furrow.d.ts", "load.js", "furrow_wasm.js", "furrow_wasm.d.ts", "furrow_wasm_bg.wasm", "furrow_wasm_bg.wasm.d.ts", "pool.js", "pool.d.ts", "pool-worker.js", "furrow_pool_wasm.js", "furrow_pool_wasm.d.ts", "furrow_pool_wasm_bg.wasm", "furrow_pool_wasm_bg.wasm.d.ts", "tracks.js", "tracks.d.ts", "furrow_tracks_wasm.js", "furrow_tracks_wasm.d.ts", "furrow_tracks_wasm_bg.wasm", "furrow_tracks_wasm_bg.wasm.d.ts", "formats.js", "formats.d.ts", "furrow_formats_wasm.js", "furrow_formats_wasm.d.ts", "furrow_formats_wasm_bg.wasm", "furrow_formats_wasm_bg.wasm.d.ts", "README.md", "LICENSE-MIT", "LICENSE-APACHE"],
  "engines": { "node": ">=18" },
  "sideEffects": false,
  "keywords": ["agriculture", "coverage path planning", "geojson", "wasm", "tractor"]
}
JSON
cp js/README.md pkg/README.md
# Gzipped as the bench measures it against the 400 KB target (Node's zlib at level 9; GNU gzip
# comes out about 2.4 KB smaller).
for module in furrow_wasm furrow_pool_wasm furrow_tracks_wasm furrow_formats_wasm; do
  raw=$(wc -c < "pkg/${module}_bg.wasm")
  gz=$(node -e 'process.stdout.write(String(require("zlib").gzipSync(require("fs").readFileSync(process.argv[1]), { level: 9 }).length))' "pkg/${module}_bg.wasm")
  echo "[build] pkg/${module}_bg.wasm: $raw bytes, $gz gzipped (Node's zlib, level 9)"
done
node scripts/site.mjs
