#!/usr/bin/env bash
# The benchmarks and the plan-quality report (not part of the test run): writes
# target/bench/report.md with its SVG plots and pictures.
#   - the quality of every corpus plan, pictures of each, the time of each stage, and how the
#     time grows with the field's size (examples/report/);
#   - the whole plan natively (criterion, benches/plan.rs), the stages that run alone
#     (benches/stages.rs), and shortest paths along tracks (benches/tracks.rs);
#   - the wasm package's plan() from JavaScript in Node and headless Chromium, its memory and
#     size (scripts/bench-wasm.mjs).
# Installs what is missing first (scripts/setup.sh), builds the package, and takes about
# 10 minutes on 2 cores. QUICK=1 runs everything shorter.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh rust browser npm
started=$(date +%s)
quick=()
[[ "${QUICK:-}" == 1 ]] && quick=(--quick)
mkdir -p target/bench
echo "== quality, stages and scaling (examples/report/)"
cargo run --release --quiet --example report -- --out target/bench "${quick[@]}"
echo "== the whole plan natively (criterion)"
measure=(--warm-up-time 1 --measurement-time 2 --sample-size 10)
[[ "${QUICK:-}" == 1 ]] && measure=(--warm-up-time 0.5 --measurement-time 0.5 --sample-size 10)
cargo bench --quiet --bench plan -- "${measure[@]}" 'plan/' | grep -E '^plan/|time:' || true
cargo bench --quiet --bench tracks -- "${measure[@]}" | grep -E '^track|time:' || true
echo "== the stages that run alone natively (criterion)"
stage_measure=(--warm-up-time 0.3 --measurement-time 0.5 --sample-size 10)
[[ "${QUICK:-}" == 1 ]] && stage_measure=(--warm-up-time 0.2 --measurement-time 0.3 --sample-size 10)
cargo bench --quiet --bench stages -- "${stage_measure[@]}" | grep -E '^stage|time:' || true
echo "== the wasm package in Node and Chromium"
# Always built: a package left from an older checkout would be measured as this one (a
# second when nothing changed).
scripts/build.sh
node scripts/bench-wasm.mjs "${quick[@]}"
node scripts/bench-report.mjs
echo "== done in $(( $(date +%s) - started ))s: target/bench/report.md"
