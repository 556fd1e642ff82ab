#!/usr/bin/env bash
# Builds the WebAssembly package into pkg/ (npm package "furrow", web target, also loadable in
# Node with initSync) and assembles the viewer site in target/site.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh rust

echo "[build] wasm (release)"
# The dependencies are optimised for size: 23 KB less gzipped (most of it the sorts that
# i_overlay instantiates), no slower in Node within 2 % (at "z" the planner's own code plans 2.3
# times slower). The planner's own code at opt-level 2: 14 KB less gzipped than at 3, and as
# fast in Node (geometric mean of the corpus 0.99, interleaved: scripts/bench-compare.mjs),
# which keeps the module clear of the 400 KB target. Native builds keep opt-level 3 throughout.
cargo build --release --target wasm32-unknown-unknown --lib --features small-alloc \
  --config 'profile.release.package."*".opt-level="z"' \
  --config 'profile.release.opt-level=2'
rm -rf pkg
# furrow_wasm.js is wasm-bindgen's module; furrow.js (js/) wraps it and recreates the instance
# after a trap, with the reset function wasm-bindgen generates on request.
# The name section (function names for stack traces, 125 KB) and the producers section are left
# out of the shipped module.
wasm-bindgen --target web --out-name furrow_wasm --experimental-reset-state-function \
  --remove-name-section --remove-producers-section \
  --out-dir pkg target/wasm32-unknown-unknown/release/furrow.wasm
cp js/furrow.js js/furrow.d.ts LICENSE-MIT LICENSE-APACHE pkg/
# Debian's wasm-opt (binaryen 108) produces a module that fails to load: never run it here.

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
    "./furrow_wasm_bg.wasm": "./furrow_wasm_bg.wasm",
    "./package.json": "./package.json"
  },
  "files": ["furrow.js", "furrow.d.ts", "furrow_wasm.js", "furrow_wasm.d.ts", "furrow_wasm_bg.wasm", "furrow_wasm_bg.wasm.d.ts", "README.md", "LICENSE-MIT", "LICENSE-APACHE"],
  "engines": { "node": ">=18" },
  "sideEffects": false,
  "keywords": ["agriculture", "coverage path planning", "geojson", "wasm", "tractor"]
}
JSON
cp js/README.md pkg/README.md
raw=$(wc -c < pkg/furrow_wasm_bg.wasm)
# Gzipped as the bench measures it against the 400 KB target (Node's zlib at level 9; GNU gzip
# comes out about 2.4 KB smaller).
gz=$(node -e 'process.stdout.write(String(require("zlib").gzipSync(require("fs").readFileSync(process.argv[1]), { level: 9 }).length))' pkg/furrow_wasm_bg.wasm)
echo "[build] pkg/furrow_wasm_bg.wasm: $raw bytes, $gz gzipped (Node's zlib, level 9)"
node scripts/site.mjs
